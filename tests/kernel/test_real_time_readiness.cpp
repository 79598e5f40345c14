// What `wysiwyf run` says at start of a real-clock pipeline against the machine: its fast loops
// and the CPUs, SCHED_FIFO and its permission, timer slack (machines described here, not read).
#include <gtest/gtest.h>

#include "wysiwyf/real_time_readiness.hpp"

namespace wysiwyf::test {

const char* const kLoop =
    "wysiwyf: 1\nclock: {mode: real}\ncomponents:\n"
    "  physics: {type: test_probe, rate: 1000, priority: 80, spin: 100us, process: display}\n"
    "  planner: {type: test_probe, rate: 1000, process: display}\n"
    "  camera: {type: test_probe, rate: 30, process: vision}\n"
    "  arm: {type: test_probe, rate: 1000, process: robot}\n";

std::string all_text(const std::vector<ReadinessLine>& lines, bool* warned = nullptr) {
  std::string out;
  for (const auto& l : lines) {
    out += l.text + "\n";
    if (warned && l.warning) *warned = true;
  }
  return out;
}

TEST(RealTimeReadiness, FastLoopsAgainstTheCpusOfTheProcess) {
  const PipelineSpec spec = load_pipeline_from_string(kLoop, "loop.yaml");
  MachineFacts two;
  two.cpus_online = two.cpus_allowed = 2;
  two.cap_sys_nice = true;
  bool warned = false;
  std::string text = all_text(real_time_readiness(spec, "display", two), &warned);
  EXPECT_NE(text.find("2 CPU(s) for this process (2 online) for 2 fast loop(s) (physics, planner): they share CPUs"),
            std::string::npos)
      << text;
  EXPECT_TRUE(warned);
  MachineFacts sixteen = two;
  sixteen.cpus_online = sixteen.cpus_allowed = 16;
  warned = false;
  text = all_text(real_time_readiness(spec, "", sixteen), &warned);
  EXPECT_NE(text.find("for 3 fast loop(s) (physics, planner, arm): each can have a CPU of its own"), std::string::npos)
      << text;
  EXPECT_FALSE(warned) << text;
  text = all_text(real_time_readiness(spec, "vision", two));
  EXPECT_NE(text.find("no loop at 500 Hz or more, none spinning"), std::string::npos) << text;
}

TEST(RealTimeReadiness, SchedFifoAllowedOrRefusedAndWhy) {
  const PipelineSpec spec = load_pipeline_from_string(kLoop, "loop.yaml");
  MachineFacts user;
  user.cpus_online = user.cpus_allowed = 8;
  bool warned = false;
  std::string text = all_text(real_time_readiness(spec, "display", user), &warned);
  EXPECT_NE(text.find("SCHED_FIFO for physics (up to priority 80): refused here (no CAP_SYS_NICE, ulimit -r 0)"),
            std::string::npos)
      << text;
  EXPECT_TRUE(warned);
  user.rtprio_limit = 95;
  warned = false;
  text = all_text(real_time_readiness(spec, "display", user), &warned);
  EXPECT_NE(text.find("SCHED_FIFO for physics (up to priority 80): allowed (ulimit -r 95)"), std::string::npos) << text;
  EXPECT_FALSE(warned) << text;
  EXPECT_NE(text.find("timer slack 50 us for this process, 1 ns for each component's thread"), std::string::npos)
      << text;
  text = all_text(real_time_readiness(spec, "robot", user));
  EXPECT_NE(text.find("no component asks for SCHED_FIFO"), std::string::npos) << text;
}

TEST(RealTimeReadiness, ThisMachineIsRead) {
  const MachineFacts m = read_machine_facts();
  EXPECT_GE(m.cpus_online, 1);
  EXPECT_GE(m.cpus_allowed, 1);
  EXPECT_LE(m.cpus_allowed, m.cpus_online);
  EXPECT_GE(m.timer_slack_ns, 0);
}

}  // namespace wysiwyf::test
