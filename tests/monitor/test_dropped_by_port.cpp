// Samples pushed out of a full input queue unread are counted per input port in the kernel's
// diagnostics (dropped_by_port), so a monitor says which port of which component lost what.
#include <gtest/gtest.h>

#include <fstream>

#include "../kernel/cli_process.hpp"
#include "../kernel/test_support.hpp"

namespace wysiwyf::test {

namespace fs = std::filesystem;

TEST(Diagnostics, SamplesDroppedFromAFullQueueAreCountedPerPort) {
  const fs::path dir = scratch_dir();
  const fs::path pipeline = dir / "slow_reader.yaml";
  // A 1 kHz writer and a 10 Hz reader keeping one sample: 99 of every 100 are pushed out unread.
  std::ofstream(pipeline) << "wysiwyf: 1\nname: slow_reader\ndomain: 68\ndds: {transport: local}\n"
                             "clock: {mode: sim, step: 1ms, duration: 4s, pace: 1}\n"
                             "components:\n"
                             "  fast: {type: test_probe, rate: 1000, topics: {out: stream}}\n"
                             "  slow: {type: test_probe, rate: 10, topics: {in: stream}, qos: {in: {depth: 1}}}\n";
  const pid_t run = spawn_cli({"run", pipeline.string(), "--no-progress"}, dir / "run.log");
  // The diagnostics as any monitor reads them (after the first second, once there are drops).
  const pid_t echo = spawn_cli({"topic", "echo", "wysiwyf/diagnostics", "--domain", "68", "--transport", "local",
                                "--count", "8", "--timeout", "30"},
                               dir / "echo.log");
  EXPECT_EQ(wait_exit(echo, std::chrono::seconds(60)), 0) << read_file(dir / "echo.log");
  EXPECT_EQ(wait_exit(run, std::chrono::seconds(60)), 0) << read_file(dir / "run.log");
  const std::string echoed = read_file(dir / "echo.log");
  // The slow reader's report names its port with a count; the fast writer has no input that dropped.
  const auto slow = echoed.rfind("instance: \"slow\"");
  ASSERT_NE(slow, std::string::npos) << echoed;
  const std::string report = echoed.substr(slow, echoed.find("---", slow) - slow);
  const auto at = report.find("dropped_by_port:\n-\n  port: \"in\"\n  count: ");
  ASSERT_NE(at, std::string::npos) << report;
  EXPECT_GT(std::stoull(report.substr(at + 41)), 50u) << report;
  const auto fast = echoed.rfind("instance: \"fast\"");
  ASSERT_NE(fast, std::string::npos) << echoed;
  EXPECT_NE(echoed.find("dropped_by_port: []", fast), std::string::npos) << echoed.substr(fast);
}

}  // namespace wysiwyf::test
