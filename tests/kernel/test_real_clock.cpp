// The real-time executor, the DDS set-up options and the tick-time report (wall time on either
// clock). These run on the wall clock, so they check behaviour (it ticks, it stops, it counts
// overruns, a tick that slept is counted as long), never how precise the timing is.
#include <limits>

#include "test_support.hpp"
#include "wysiwyf/real_time_throttling.hpp"

namespace wysiwyf::test {

// Differences of stamps from outside saturate instead of wrapping (and stay std::abs-safe).
TEST(Time, ElapsedSaturatesInsteadOfWrapping) {
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max(),
                         kMin = std::numeric_limits<std::int64_t>::min();
  EXPECT_EQ(elapsed_ns(5, 3), 2);
  EXPECT_EQ(elapsed_ns(3, 5), -2);
  EXPECT_EQ(elapsed_ns(kMax, -1), kMax);
  EXPECT_EQ(elapsed_ns(1000, kMin), kMax) << "an ancient stamp is long ago, not in the future";
  EXPECT_EQ(elapsed_ns(-1, kMax), -kMax);
  EXPECT_EQ(elapsed_ns(kMin, 1), -kMax);
  EXPECT_EQ(elapsed_ns(kMin, kMin), 0);
}

TEST(RealClock, TicksEveryComponentOnItsOwnThreadUntilTheDuration) {
  const auto dir = scratch_dir();
  const RunResult r = run_pipeline(
      "wysiwyf: 1\ndomain: 51\ndds: {transport: local}\nclock: {mode: real, duration: 300ms}\ncomponents:\n"
      "  src: {type: test_probe, rate: 200, topics: {out: x}}\n"
      "  sink: {type: test_probe, rate: 100, topics: {in: x}, params: {record: " +
      (dir / "r.txt").string() + "}}\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.stop_reason, "duration reached");
  ASSERT_EQ(r.components.size(), 2u);
  EXPECT_GT(r.components[0].ticks, 0u);
  EXPECT_GT(r.components[1].ticks, 0u);
  // Stamps are wall-clock time since the epoch (after 2020).
  const std::string rec = read_file(dir / "r.txt");
  ASSERT_FALSE(rec.empty());
  EXPECT_GT(std::stoll(rec.substr(0, rec.find(' '))), 1'577'836'800'000'000'000LL);
}

TEST(RealClock, ATickLongerThanItsPeriodIsCountedAsAnOverrun) {
  // 1 ms period, 5 ms ticks: at least four periods are missed on every tick.
  const RunResult r = run_pipeline(
      "wysiwyf: 1\ndomain: 52\ndds: {transport: local}\nclock: {mode: real, duration: 100ms}\ncomponents:\n"
      "  slow: {type: test_probe, rate: 1000, params: {tick_sleep_us: 5000}}\n");
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_GT(r.components[0].ticks, 0u);
  EXPECT_GE(r.components[0].overruns, 4 * (r.components[0].ticks - 1));
}

TEST(TickReport, GivesTheP99OverTheWholeRunBesideTheLast1024Ticks) {
  // 2000 ticks on the sim clock, the first 30 sleeping 20 ms (1.5 %): over the whole run the p99
  // is one of those; the last 1024 ticks (the Diagnostics window) hold none of them.
  const RunResult r = run_pipeline(
      "wysiwyf: 1\ndomain: 61\ndds: {transport: local}\nclock: {mode: sim, step: 1ms, duration: 2s}\ncomponents:\n"
      "  probe: {type: test_probe, rate: 1000, params: {tick_sleep_us: 20000, sleep_ticks: 30}}\n");
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.components.size(), 1u);
  const ComponentReport& c = r.components[0];
  EXPECT_GE(c.ticks, 2000u);
  EXPECT_GE(c.run_tick_max_us, 20000.0);
  EXPECT_GE(c.run_tick_p99_us, 20000.0);
  EXPECT_LE(c.run_tick_p99_us, c.run_tick_max_us);
  EXPECT_LT(c.tick_p99_us, 20000.0);  // (the window: 1024 ticks that did not sleep)
  EXPECT_LE(c.tick_max_us, c.run_tick_max_us);
}

TEST(TickReport, MeasuresEachTicksCostToItsThreadApartFromItsWallTimeWhenAsked) {
  // Ticks that sleep 2 ms: 2 ms of wall time each, almost none of the thread's CPU time. The cost
  // is what a monitor in another process cannot change, where a wall time can.
  const std::string yaml =
      "wysiwyf: 1\ndomain: 87\ndds: {transport: local}\nclock: {mode: sim, step: 1ms, duration: 50ms}\n"
      "components:\n  probe: {type: test_probe, rate: 1000, params: {tick_sleep_us: 2000}}\n";
  Loader loader(test_search_dirs());
  const PipelineSpec spec = load_pipeline_from_string(yaml, "test.yaml");
  std::ostringstream log;
  RunOptions options{"", false, &log};
  options.measure_tick_cost = true;
  const RunResult r = Runtime(spec, loader, options).run();
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.components.size(), 1u);
  const ComponentReport& c = r.components[0];
  EXPECT_GE(c.tick_p50_us, 2000.0);
  EXPECT_GE(c.cpu_p50_us, 0.0);
  EXPECT_LT(c.cpu_p99_us, 500.0) << "us of CPU for a tick that slept";
  EXPECT_LE(c.cpu_p50_us, c.cpu_p99_us);
  // Instructions where this machine's kernel counts them for a process (not in most VMs).
  if (c.instructions_p50 >= 0) {
    EXPECT_GT(c.instructions_p99, 0.0);
  }
  // Not asked for: not measured.
  const RunResult plain = run_pipeline(yaml);
  ASSERT_TRUE(plain.ok) << plain.error;
  EXPECT_EQ(plain.components[0].cpu_p50_us, -1.0);
  EXPECT_EQ(plain.components[0].instructions_p50, -1.0);
}

TEST(RealClock, SpinAndPriorityRunAndTheLatenessOfEveryTickIsReported) {
  // spin: wake 200 us early and busy-wait; priority: SCHED_FIFO if this process may (a warning
  // otherwise; the run goes on either way). What is checked is behaviour, not precision.
  std::string said;
  const RunResult r = run_pipeline(
      "wysiwyf: 1\ndomain: 55\ndds: {transport: local}\nclock: {mode: real, duration: 100ms}\ncomponents:\n"
      "  fast: {type: test_probe, rate: 1000, spin: 200us, priority: 10}\n"
      "  slow: {type: test_probe, rate: 100}\n",
      {}, &said);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.components.size(), 2u);
  for (const auto& c : r.components) {
    EXPECT_GT(c.ticks, 0u) << c.name;
    EXPECT_GE(c.late_p50_us, 0.0) << c.name;
    EXPECT_GE(c.late_p99_us, c.late_p50_us) << c.name;
    EXPECT_GE(c.late_max_us, c.late_p99_us) << c.name;
  }
  if (said.find("SCHED_FIFO") != std::string::npos) {  // refused here: said so, and for the right one
    EXPECT_NE(said.find("[fast] priority 10 (SCHED_FIFO) refused"), std::string::npos) << said;
  }
}

TEST(RealClock, ASpinOfTheWholePeriodKeepsTheThreadBusyAndStillStops) {
  // spin equal to the period: the thread never sleeps between ticks (a haptic loop on a core of
  // its own); it ticks, and stops when the run does.
  const RunResult r = run_pipeline(
      "wysiwyf: 1\ndomain: 58\ndds: {transport: local}\nclock: {mode: real, duration: 50ms}\ncomponents:\n"
      "  busy: {type: test_probe, rate: 1000, spin: 1ms}\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.stop_reason, "duration reached");
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_GT(r.components[0].ticks, 0u);
}

TEST(RealClock, PriorityWithASpinOfTheWholePeriodWarnsOfTheKernelsRealTimeLimit) {
  // SCHED_FIFO threads may run 950000 of every 1000000 us by default: one that never sleeps is
  // stopped for 50 ms every second. (Decided from the numbers: a test thread at SCHED_FIFO that
  // never sleeps would take a core of the test machine.)
  const RealTimeBandwidth linux_default{950000, 1000000};
  const std::string said = real_time_throttling_warning(1'000'000, 1'000'000, linux_default);
  EXPECT_NE(said.find("never sleeps"), std::string::npos) << said;
  EXPECT_NE(said.find("950000 of every 1000000 us"), std::string::npos) << said;
  EXPECT_NE(said.find("stopped for about 50 ms every 1000 ms"), std::string::npos) << said;
  EXPECT_NE(said.find("expected a spin below the period"), std::string::npos) << said;
  EXPECT_NE(real_time_throttling_warning(2'000'000, 1'000'000, linux_default), "");  // (more than the period)
  // Nothing to say: the thread sleeps in each period, or the kernel sets no limit.
  EXPECT_EQ(real_time_throttling_warning(100'000, 1'000'000, linux_default), "");
  EXPECT_EQ(real_time_throttling_warning(0, 1'000'000, linux_default), "");
  EXPECT_EQ(real_time_throttling_warning(1'000'000, 1'000'000, RealTimeBandwidth{-1, 1000000}), "");
  EXPECT_EQ(real_time_throttling_warning(1'000'000, 1'000'000, RealTimeBandwidth{1000000, 1000000}), "");
  // This machine's limit reads as a limit within its period, or as none.
  const RealTimeBandwidth here = read_real_time_bandwidth();
  EXPECT_TRUE(here.runtime_us == -1 || (here.period_us > 0 && here.runtime_us <= here.period_us))
      << here.runtime_us << " of " << here.period_us;
}

TEST(RealClock, CpusPinAComponentsThreadAndACpuTheMachineLacksIsSaid) {
  // cpus: [0] exists everywhere (pinned, nothing said); a CPU beyond the machine's is said, and
  // the component runs unpinned.
  std::string said;
  const RunResult r = run_pipeline(
      "wysiwyf: 1\ndomain: 56\ndds: {transport: local}\nclock: {mode: real, duration: 50ms}\ncomponents:\n"
      "  pinned: {type: test_probe, rate: 1000, cpus: [0]}\n"
      "  nowhere: {type: test_probe, rate: 1000, cpus: 1023}\n",
      {}, &said);
  ASSERT_TRUE(r.ok) << r.error;
  for (const auto& c : r.components) EXPECT_GT(c.ticks, 0u) << c.name;
  EXPECT_EQ(said.find("[pinned] cpus"), std::string::npos) << said;
  EXPECT_NE(said.find("[nowhere] cpus: CPU 1023 does not exist (this machine has "), std::string::npos) << said;
}

TEST(DdsSetup, AFastDdsXmlParticipantProfileCanBeNamed) {
  const auto dir = scratch_dir();
  std::ofstream(dir / "profiles.xml") << R"(<?xml version="1.0" encoding="UTF-8" ?>
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles>
    <transport_descriptors>
      <transport_descriptor><transport_id>shm_only</transport_id><type>SHM</type></transport_descriptor>
    </transport_descriptors>
    <participant profile_name="wysiwyf_test_shm">
      <rtps>
        <userTransports><transport_id>shm_only</transport_id></userTransports>
        <useBuiltinTransports>false</useBuiltinTransports>
      </rtps>
    </participant>
  </profiles>
</dds>
)";
  std::ofstream(dir / "p.yaml")
      << "wysiwyf: 1\ndomain: 53\ndds: {profiles: profiles.xml, participant_profile: wysiwyf_test_shm}\n"
         "clock: {mode: sim, step: 1ms, duration: 20ms}\ncomponents:\n"
         "  a: {type: test_probe, rate: 1000}\n";
  Loader loader(test_search_dirs());
  const PipelineSpec spec = load_pipeline((dir / "p.yaml").string());
  EXPECT_TRUE(validate_pipeline(spec, loader).ok());
  std::ostringstream log;
  Runtime runtime(spec, loader, RunOptions{"", false, &log});
  const RunResult r = runtime.run();
  EXPECT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.components.at(0).ticks, 20u);
}

TEST(DdsSetup, AnUnknownProfileNameFailsTheRunWithAClearError) {
  const auto dir = scratch_dir();
  std::ofstream(dir / "profiles.xml") << R"(<?xml version="1.0" encoding="UTF-8" ?>
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles><participant profile_name="another"><rtps/></participant></profiles>
</dds>
)";
  std::ofstream(dir / "p.yaml") << "wysiwyf: 1\ndomain: 54\ndds: {profiles: profiles.xml, participant_profile: nope}\n"
                                   "clock: {mode: sim, step: 1ms, duration: 20ms}\ncomponents:\n"
                                   "  a: {type: test_probe, rate: 1000, params: {lifecycle_log: " +
                                       (dir / "log").string() + "}}\n";
  Loader loader(test_search_dirs());
  std::ostringstream log;
  Runtime runtime(load_pipeline((dir / "p.yaml").string()), loader, RunOptions{"", false, &log});
  const RunResult r = runtime.run();
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("no participant profile 'nope' in '"), std::string::npos) << r.error;
  EXPECT_FALSE(std::filesystem::exists(dir / "log"));  // nothing was configured
}

}  // namespace wysiwyf::test
