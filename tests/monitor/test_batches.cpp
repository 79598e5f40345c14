// The monitoring tools declare a DDS latency budget, so a pipeline on the real clock sends them
// its samples in batches instead of waking its publisher thread after every tick (that wake slowed
// a 1 kHz loop's next tick by about a tenth); `--prompt` asks for each sample as it is written.
// Real clock: what is checked is behaviour (every sample goes out, how many wakes carried them),
// never how precise the timing is.
#include <gtest/gtest.h>

#include "../kernel/cli_process.hpp"
#include "../kernel/test_support.hpp"

namespace wysiwyf::test {

namespace {

namespace fs = std::filesystem;

struct Watched {
  RunResult run;
  std::string monitor_log;
};

// A 1 kHz writer on topic 'x' for two seconds of the real clock, watched by `topic hz` with
// `extra` options; the run starts once the monitor has had time to match (start_after_s).
Watched watched_run(int domain, const std::vector<std::string>& extra) {
  const fs::path dir = scratch_dir();
  std::vector<std::string> hz{"topic",       "hz",    "x",          "--domain", std::to_string(domain),
                              "--transport", "local", "--duration", "8"};
  hz.insert(hz.end(), extra.begin(), extra.end());
  const pid_t monitor = spawn_cli(hz, dir / "hz.log");
  Loader loader(test_search_dirs());
  const PipelineSpec spec =
      load_pipeline_from_string("wysiwyf: 1\ndomain: " + std::to_string(domain) +
                                    "\ndds: {transport: local}\nclock: {mode: real, duration: 2s}\ncomponents:\n"
                                    "  src: {type: test_probe, rate: 1000, topics: {out: x}}\n",
                                "test.yaml");
  std::ostringstream log;
  RunOptions options{"", false, &log};
  options.start_after_s = 2;
  Watched w;
  w.run = Runtime(spec, loader, options).run();
  EXPECT_EQ(wait_exit(monitor, std::chrono::seconds(60)), 0) << read_file(dir / "hz.log");
  w.monitor_log = read_file(dir / "hz.log");
  EXPECT_TRUE(w.run.ok) << w.run.error << "\n" << log.str();
  return w;
}

}  // namespace

TEST(MonitorBatches, AMonitorTakesTheSamplesInBatchesAndWithPromptEachAsItIsWritten) {
  const Watched batched = watched_run(81, {});
  ASSERT_GT(batched.run.dds_samples_sent, 1000u) << batched.monitor_log;  // 2 s at 1 kHz, the monitor matched
  // One wake per dds::kBatchingPeriod (5 ms: about five samples each), not one per tick.
  EXPECT_LT(2 * batched.run.dds_publisher_wakes, batched.run.dds_samples_sent)
      << batched.run.dds_publisher_wakes << " wakes";
  EXPECT_NE(batched.monitor_log.find("rate "), std::string::npos) << batched.monitor_log;
  EXPECT_NE(batched.monitor_log.find("samples arrive in batches"), std::string::npos) << batched.monitor_log;

  const Watched prompt = watched_run(82, {"--prompt"});
  ASSERT_GT(prompt.run.dds_samples_sent, 1000u) << prompt.monitor_log;
  // A wake after every tick (two ticks' samples in one only when the publisher thread is late).
  EXPECT_GT(2 * prompt.run.dds_publisher_wakes, prompt.run.dds_samples_sent)
      << prompt.run.dds_publisher_wakes << " wakes";
  EXPECT_NE(prompt.monitor_log.find("rate "), std::string::npos) << prompt.monitor_log;
  EXPECT_EQ(prompt.monitor_log.find("samples arrive in batches"), std::string::npos) << prompt.monitor_log;
}

}  // namespace wysiwyf::test
