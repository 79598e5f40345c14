// A one-writer input (the arm's setpoint, its requests) that no component of the pipeline writes
// takes its writer from outside it: without DDS-Security that is refused at validation
// (tests/kernel/broken/one_writer_from_outside_unsecured.yaml), with `insecure: true` accepted and
// said at every start; an optional one left unmapped is not connected at all, not even to DDS.
#include <signal.h>

#include <chrono>

#include "cli_process.hpp"
#include "test_support.hpp"
#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/validator.hpp"

namespace wysiwyf::test {
namespace {

namespace fs = std::filesystem;

ValidationResult validate(const std::string& yaml) {
  Loader loader({WYSIWYF_TEST_COMPONENT_DIR});
  return validate_pipeline(load_pipeline_from_string(yaml, "outside.yaml"), loader);
}

TEST(OneWriterOutside, WithInsecureItIsAcceptedAndSaidAtEveryStart) {
  const ValidationResult v = validate(
      "wysiwyf: 1\nname: outside\ndomain: 81\ninsecure: true\nclock: {mode: real}\ncomponents:\n"
      "  sink: {type: test_probe, rate: 100, params: {one_writer: true}, topics: {in: requests}}\n");
  ASSERT_TRUE(v.ok()) << (v.errors.empty() ? "" : v.errors.front().message);
  int said = 0;
  for (const auto& w : v.warnings)
    said += w.message.find(
                "INSECURE (insecure: true): topic 'requests': sink.in takes its one writer from a "
                "program outside this pipeline, unauthenticated: any participant on domain 81") == 0;
  EXPECT_EQ(said, 1);
}

TEST(OneWriterOutside, AnOptionalOneLeftUnmappedIsNotConnectedNotEvenToDds) {
  const fs::path dir = scratch_dir();
  const std::string yaml =
      "wysiwyf: 1\nname: unmapped\ndomain: 82\ndds: {transport: local}\n"
      "clock: {mode: sim, step: 1ms, duration: 60s, pace: 1}\ncomponents:\n"
      "  sink: {type: test_probe, rate: 50, params: {one_writer: true, optional_in: true}}\n";
  const ValidationResult v = validate(yaml);
  ASSERT_TRUE(v.ok()) << (v.errors.empty() ? "" : v.errors.front().message);
  EXPECT_TRUE(v.warnings.empty()) << v.warnings.front().message;
  EXPECT_EQ(v.unconnected_topics, std::set<std::string>{"sink/in"});
  // Running, the process has no DDS endpoint on it: nothing outside can write into it.
  std::ofstream(dir / "unmapped.yaml") << yaml;
  const pid_t run = spawn_cli({"run", (dir / "unmapped.yaml").string(), "--no-progress"}, dir / "run.log");
  const std::string list = list_topics_until(
      82, dir / "list.log", [](const std::string& l) { return l.find("wysiwyf/diagnostics") != std::string::npos; });
  EXPECT_NE(list.find("wysiwyf/diagnostics"), std::string::npos) << list;
  EXPECT_EQ(list.find("sink/in"), std::string::npos) << list;
  kill(run, SIGTERM);
  EXPECT_EQ(wait_exit(run, std::chrono::seconds(30)), 0) << read_file(dir / "run.log");
}

}  // namespace
}  // namespace wysiwyf::test
