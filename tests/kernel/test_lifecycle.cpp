// Lifecycle order, and what happens when a component throws in each phase.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>

#include "test_support.hpp"

namespace wysiwyf::test {

std::string three_probes(const std::filesystem::path& log, const std::string& b_params, int domain) {
  return "wysiwyf: 1\nname: lifecycle\ndomain: " + std::to_string(domain) +
         "\ndds: {transport: local}\nclock: {mode: sim, step: 1ms, duration: 50ms}\n"
         "components:\n"
         "  a: {type: test_probe, rate: 100, params: {lifecycle_log: " +
         log.string() +
         "}}\n"
         "  b: {type: test_probe, rate: 100, params: {lifecycle_log: " +
         log.string() + ", " + b_params +
         "}}\n"
         "  c: {type: test_probe, rate: 100, params: {lifecycle_log: " +
         log.string() + "}}\n";
}

TEST(Lifecycle, ConfiguresAndActivatesInOrderAndDeactivatesInReverse) {
  const auto log = scratch_dir() / "events.txt";
  const RunResult r = run_pipeline(three_probes(log, "gain: 1", 41));
  EXPECT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.stop_reason, "duration reached");
  EXPECT_EQ(read_file(log),
            "a configure\nb configure\nc configure\n"
            "a activate\nb activate\nc activate\n"
            "c deactivate\nb deactivate\na deactivate\n");
  ASSERT_EQ(r.components.size(), 3u);
  EXPECT_EQ(r.components[0].ticks, 5u);  // t = 0, 10, 20, 30, 40 ms
  EXPECT_EQ(r.sim_time_ns, 50'000'000);
}

TEST(Lifecycle, ATickExceptionIsReportedByNameAndEveryoneHoldsBeforeDeactivating) {
  const auto log = scratch_dir() / "events.txt";
  const RunResult r = run_pipeline(three_probes(log, "fail_phase: tick, fail_tick: 2", 42));
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.stop_reason, "fault");
  EXPECT_NE(r.error.find("component 'b' (test_probe) failed in tick at t=20000000 ns: tick failed on purpose"),
            std::string::npos)
      << r.error;
  EXPECT_EQ(read_file(log),
            "a configure\nb configure\nc configure\n"
            "a activate\nb activate\nc activate\n"
            "a hold\nb hold\nc hold\n"
            "c deactivate\nb deactivate\na deactivate\n");
}

TEST(Lifecycle, AConfigureExceptionStopsBeforeAnythingIsActivated) {
  const auto log = scratch_dir() / "events.txt";
  Loader loader(test_search_dirs());
  const PipelineSpec spec = load_pipeline_from_string(three_probes(log, "fail_phase: configure", 43), "t.yaml");
  // The validator runs configure() too and reports the failure before anything starts.
  const auto v = validate_pipeline(spec, loader);
  ASSERT_EQ(v.errors.size(), 1u);
  EXPECT_NE(
      v.errors[0].message.find("component 'b' (test_probe) rejected its configuration: configure failed on purpose"),
      std::string::npos)
      << v.errors[0].message;
  std::filesystem::remove(log);
  std::ostringstream out;
  Runtime runtime(spec, loader, RunOptions{"", false, &out});
  const RunResult r = runtime.run();
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("component 'b' (test_probe) failed in configure"), std::string::npos) << r.error;
  EXPECT_EQ(read_file(log), "a configure\nb configure\n");
}

TEST(Lifecycle, AnActivateExceptionDeactivatesOnlyTheActivatedInReverse) {
  const auto log = scratch_dir() / "events.txt";
  const RunResult r = run_pipeline(three_probes(log, "fail_phase: activate", 44));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("component 'b' (test_probe) failed in activate: activate failed on purpose"),
            std::string::npos)
      << r.error;
  EXPECT_EQ(read_file(log),
            "a configure\nb configure\nc configure\n"
            "a activate\nb activate\n"
            "a hold\n"
            "a deactivate\n");
}

TEST(Lifecycle, ADeactivateExceptionIsReportedAndTheOthersStillDeactivate) {
  const auto log = scratch_dir() / "events.txt";
  const RunResult r = run_pipeline(three_probes(log, "fail_phase: deactivate", 45));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("component 'b' (test_probe) failed in deactivate"), std::string::npos) << r.error;
  EXPECT_NE(read_file(log).find("c deactivate\nb deactivate\na deactivate\n"), std::string::npos) << read_file(log);
}

TEST(Lifecycle, AComponentCanEndTheRun) {
  const auto dir = scratch_dir();
  const RunResult r = run_pipeline(
      "wysiwyf: 1\ndomain: 46\ndds: {transport: local}\nclock: {mode: sim, step: 1ms, duration: 10s}\n"
      "components:\n"
      "  src: {type: test_probe, rate: 1000, topics: {out: x}}\n"
      "  sink: {type: test_probe, rate: 1000, topics: {in: x}, params: {stop_after_received: 25}}\n");
  EXPECT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.stop_reason, "stopped by sink: received 25");
  EXPECT_EQ(r.sim_time_ns, 25'000'000);  // src ticks first in each step, so sink sees one sample per step
}

}  // namespace wysiwyf::test

namespace wysiwyf::test {

// A component rejects an unusable sample through the kernel: counted, logged once, in the
// run's report and diagnostics; the run goes on.
TEST(BadInput, RejectedSamplesAreCountedAndWarnedOnce) {
  std::string log;
  const RunResult r = run_pipeline(
      "wysiwyf: 1\ndomain: 56\ndds: {transport: local}\nclock: {mode: sim, step: 1ms, duration: 50ms}\ncomponents:\n"
      "  source: {type: test_probe, rate: 1000, params: {emit_nan: true}, topics: {out: x}}\n"
      "  sink: {type: test_probe, rate: 1000, topics: {in: x}}\n",
      {}, &log);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.components.size(), 2u);
  EXPECT_EQ(r.components[1].rejected_samples, 50u);  // the source ticks first: its sample of each step
  EXPECT_EQ(r.components[1].warnings, 50u);
  EXPECT_EQ(r.components[0].rejected_samples, 0u);
  std::size_t lines = 0;
  for (std::size_t at = log.find("rejected a sample"); at != std::string::npos;
       at = log.find("rejected a sample", at + 1))
    ++lines;
  EXPECT_EQ(lines, 1u) << log;
  EXPECT_NE(log.find("[sink] warning: input 'in': rejected a sample: position[0] is not finite"), std::string::npos)
      << log;
}

// What a component reports of its health reaches the run's summary: the worst state of the run
// with its reason, even when it recovered (a hold that ended is still a run that held), and
// `wysiwyf run` exits 1 with it.
TEST(Health, TheWorstStateOfTheRunIsReportedAndFailsTheCommand) {
  const std::string yaml =
      "wysiwyf: 1\ndomain: 62\ndds: {transport: local}\nclock: {mode: sim, step: 1ms, duration: 20ms}\n"
      "components:\n"
      "  steady: {type: test_probe, rate: 1000}\n"
      "  wobbly: {type: test_probe, rate: 1000, params: {hold_ticks: [5, 8]}}\n";
  const RunResult r = run_pipeline(yaml);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.components.size(), 2u);
  EXPECT_EQ(r.components[0].state, "ok");
  EXPECT_EQ(r.components[1].state, "holding");
  EXPECT_EQ(r.components[1].state_reason, "told to hold at tick 5");
  ASSERT_NE(r.first_unhealthy(), nullptr);
  EXPECT_EQ(r.first_unhealthy()->name, "wobbly");
  // A fault outranks a hold; a clean run has no unhealthy component.
  EXPECT_EQ(run_pipeline(yaml, {"wobbly.params.fault_tick=10"}).components[1].state, "fault");
  EXPECT_EQ(run_pipeline(yaml, {"wobbly.params.hold_ticks=~"}).first_unhealthy(), nullptr);

  // The command line: exit 1, the state column names it, 0 for the clean run.
  const auto dir = scratch_dir();
  const auto file = dir / "health.yaml";
  std::ofstream(file) << yaml;
  const std::string cli = "WYSIWYF_COMPONENT_PATH=" WYSIWYF_TEST_COMPONENT_DIR " " + std::string(WYSIWYF_CLI) +
                          " run " + file.string() + " --no-progress";
  EXPECT_EQ(WEXITSTATUS(std::system((cli + " > " + (dir / "held.txt").string() + " 2>&1").c_str())), 1);
  const std::string held = read_file(dir / "held.txt");
  EXPECT_NE(held.find("holding: told to hold at tick 5"), std::string::npos) << held;
  EXPECT_NE(held.find("error: component 'wobbly' (test_probe) held during the run"), std::string::npos) << held;
  EXPECT_EQ(WEXITSTATUS(std::system((cli + " --set wobbly.params.hold_ticks=null > /dev/null 2>&1").c_str())), 0);
}

}  // namespace wysiwyf::test
