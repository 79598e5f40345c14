// The encountered-type loop end to end on the sim clock (arm_sim, user_sim, hand_tracker_sim,
// surface_planner, admittance_sim, supervisor), each run checked against stated truths:
// - speed and separation monitoring (ISO/TS 15066) at every 1 ms sample of surface mode, with the
//   separation from the true fingertip to every part of the arm (upper arm, forearm, wrist,
//   sensor, plate, knob), not only the plate: no part approaches faster than the protective
//   distance allows at its separation (inside it: still or moving away);
// - the plate in place and still before the finger arrives in every reach the arm can make, and
//   the ones it cannot (out of reach, or a hand too near for the arm to come in time) reported;
// - the mode switches on the stated force thresholds and dwell times, with no setpoint step
//   larger than 0.1 mm at a switch.
#include <cmath>

#include "arm_clearance/arm_clearance.hpp"
#include "arm_clearance/speed_separation.hpp"
#include "display_support.hpp"
#include "arm_model/arm_model.hpp"

namespace wysiwyf::test {

namespace {

constexpr int kSurface = 1, kAdmittance = 2;
constexpr int kTouch = 1, kMiss = 2;
constexpr double kFingerRadius = 0.01, kToolMass = 1.1563;

robot::ArmModel& model() {
  static robot::ArmModel m(std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf", "dev");
  return m;
}

struct SsmCheck {
  int samples = 0;
  double worst_excess = -1e9;  // m/s by which a part approached faster than allowed (<= 0: never)
  double worst_t = 0, worst_speed = 0, worst_separation = 0;
  std::string worst_part;
  Tick worst_tick;
  double min_separation = 1e9;
};

// SSM at every sample of surface mode, against the true fingertip and the measured arm.
SsmCheck check_ssm(const LoopRun& run) {
  const robot::ArmClearance clearance(model());
  const robot::SsmParams ssm;  // the planner's defaults
  SsmCheck c;
  for (const Tick& k : run.ticks) {
    if (k.mode != kSurface) continue;
    ++c.samples;
    for (const auto& p : clearance.evaluate(k.q, k.qd, k.hand)) {
      const double s = std::max(0.0, p.distance - kFingerRadius);
      c.min_separation = std::min(c.min_separation, s);
      const double excess = p.approach_speed - ssm.allowed_speed(s);
      if (getenv("SSM_DIAG") && k.t > 2.19 && k.t < 2.24 && std::string(p.name) == "dev box")
        std::printf("DIAG %.3f plate d %.4f v %.4f nearest %s qd %s\n", k.t, p.distance, p.approach_speed,
                    ::testing::PrintToString(std::vector<double>(p.nearest.data(), p.nearest.data() + 3)).c_str(),
                    ::testing::PrintToString(std::vector<double>(k.qd.data(), k.qd.data() + 6)).c_str());
      if (excess > c.worst_excess)
        c.worst_excess = excess, c.worst_t = k.t, c.worst_part = p.name, c.worst_tick = k,
        c.worst_speed = p.approach_speed, c.worst_separation = s;
    }
  }
  return c;
}

// The plate's largest speed over 100 ms windows within [from, to].
double plate_speed(const LoopRun& run, double from, double to) {
  double fastest = 0;
  for (std::size_t i = 100; i < run.ticks.size(); ++i) {
    const Tick &k = run.ticks[i], &before = run.ticks[i - 100];
    if (k.t < from || k.t > to) continue;
    fastest = std::max(fastest, (k.plate - before.plate).norm() / (k.t - before.t));
  }
  return fastest;
}

void expect_ssm(const LoopRun& run, const char* what) {
  const SsmCheck c = check_ssm(run);
  ASSERT_GT(c.samples, 1000) << what;
  // 5 mm/s of slack for the simulated arm's joint-velocity noise.
  EXPECT_LE(c.worst_excess, 0.005) << what << ": the " << c.worst_part << " approached the hand " << c.worst_excess
                                   << " m/s faster than SSM allows (" << c.worst_speed << " m/s at "
                                   << c.worst_separation * 1e3 << " mm) at t = " << c.worst_t << " s (hand "
                                   << c.worst_tick.hand.transpose() << ", plate " << c.worst_tick.plate.transpose()
                                   << ", planner state " << c.worst_tick.planner << ")";
  std::printf("[ SSM      ] %s: %d samples in surface mode, worst margin %.4f m/s (%s at %.3f s), nearest %.1f mm\n",
              what, c.samples, -c.worst_excess, c.worst_part.c_str(), c.worst_t, c.min_separation * 1e3);
}

// The finger's arrival and the plate: still at least `still_s` before, within 1 mm of its target.
void expect_in_place_before(const LoopRun& run, const Event& touch, double still_s) {
  const double fastest = plate_speed(run, touch.t - still_s, touch.t - 0.005);
  EXPECT_LT(fastest, 0.002) << "contact " << touch.contact << " (" << touch.text << "): the plate moved at " << fastest
                            << " m/s in the " << still_s << " s before the finger arrived at " << touch.t << " s";
}

}  // namespace

TEST(DisplayLoop, FrontalReachMeetsThePlateAndSwitchesOnTheThresholds) {
  LoopSetup s;
  s.domain = 71;
  s.script = {"wait 2.0", "reach cube +x knob speed 1.0", "push 6 1.5", "release 0.3", "withdraw 0.15 0.6", "wait 0.3"};
  const LoopRun run = run_loop(s);
  ASSERT_TRUE(run.result.ok) << run.result.error << run.log;
  ASSERT_EQ(run.user(kTouch).size(), 1u) << run.log;
  EXPECT_TRUE(run.user(kMiss).empty()) << run.log;
  expect_ssm(run, "frontal reach");
  expect_in_place_before(run, run.user(kTouch)[0], 0.1);

  // The mode switches: to admittance once the user's force has stayed above 2 N for 20 ms, back
  // to surface once it has stayed below 1 N for 100 ms with the hand 2 cm off the plate.
  // Surface once the arm follows the supervisor's first hold (a few ticks).
  std::size_t start = 0;
  while (start < run.ticks.size() && run.ticks[start].mode != kSurface) ++start;
  ASSERT_LT(start, run.ticks.size());
  EXPECT_LE(run.ticks[start].t - run.ticks.front().t, 0.01) << "surface mode came late";
  std::vector<std::pair<std::size_t, int>> switches;  // tick index, new mode
  for (std::size_t i = start + 1; i < run.ticks.size(); ++i)
    if (run.ticks[i].mode != run.ticks[i - 1].mode) switches.push_back({i, run.ticks[i].mode});
  ASSERT_EQ(switches.size(), 2u);  // surface -> admittance -> surface
  EXPECT_EQ(switches[0].second, kAdmittance);
  EXPECT_EQ(switches[1].second, kSurface);
  {
    const std::size_t at = switches[0].first;
    std::size_t first_above = at;
    while (first_above > 0 && user_force(run.ticks[first_above - 1], kToolMass) > 2.0) --first_above;
    const double held = run.ticks[at].t - run.ticks[first_above].t;
    EXPECT_GE(held, 0.020 - 1e-9) << "switched to admittance after " << held << " s above 2 N";
    EXPECT_LE(held, 0.025) << "switched to admittance " << held << " s after the force passed 2 N";
  }
  {
    const std::size_t at = switches[1].first;
    std::size_t first_below = at;
    while (first_below > 0 && user_force(run.ticks[first_below - 1], kToolMass) < 1.0) --first_below;
    const double held = run.ticks[at].t - run.ticks[first_below].t;
    EXPECT_GE(held, 0.100 - 1e-9) << "released after " << held << " s below 1 N";
  }
  // No setpoint step at a switch: the steps around each one no larger than 0.1 mm.
  for (const auto& [at, mode] : switches) {
    double step = 0;
    for (std::size_t i = at - 2; i <= at + 5 && i < run.ticks.size(); ++i)
      step = std::max(step, (run.ticks[i].setpoint - run.ticks[i - 1].setpoint).norm());
    EXPECT_LE(step, 1e-4) << "a " << step * 1e3 << " mm setpoint step at the switch to mode " << mode << " at "
                          << run.ticks[at].t << " s";
  }
  // The push moved the cube into the wall: 10 cm, and the plate with it.
  EXPECT_NEAR(run.ticks.back().plate.x(), 0.60, 0.005);
}

TEST(DisplayLoop, ObliqueAndFastReachesKeepSpeedAndSeparation) {
  {
    LoopSetup s;
    s.domain = 72;
    s.script = {"move 0.95 0.30 0.25 1.0", "wait 1.5", "reach cube +x face at 0.05 -0.05 speed 1.0", "release 0.2",
                "withdraw 0.15 0.5"};
    const LoopRun run = run_loop(s);
    ASSERT_TRUE(run.result.ok) << run.result.error << run.log;
    ASSERT_EQ(run.user(kTouch).size(), 1u) << run.log;
    expect_ssm(run, "oblique reach");
    expect_in_place_before(run, run.user(kTouch)[0], 0.1);
  }
  {
    LoopSetup s;
    s.domain = 73;
    s.script = {"wait 2.0", "reach cube +x knob speed 1.6", "release 0.2", "withdraw 0.15 0.4"};
    const LoopRun run = run_loop(s);
    ASSERT_TRUE(run.result.ok) << run.result.error << run.log;
    ASSERT_EQ(run.user(kTouch).size(), 1u) << run.log;
    expect_ssm(run, "fast reach (1.6 m/s)");
    expect_in_place_before(run, run.user(kTouch)[0], 0.1);
  }
}

// The hand starts for the +x face, then turns to the +y face mid-reach: the planner relocates the
// plate (through the cube's inside) as far as SSM lets it; if it cannot be there in time it says so
// (the hand too near), and the user misses rather than the arm rushing at the hand.
TEST(DisplayLoop, ASwitchToAnotherFaceMidReachKeepsSpeedAndSeparation) {
  LoopSetup s;
  s.domain = 74;
  s.script = {"wait 2.0", "move 0.90 0.05 0.15 0.35", "reach cube +y face at 0.05 0.05 speed 1.2", "release 0.2",
              "withdraw 0.15 0.5"};
  const LoopRun run = run_loop(s);
  ASSERT_TRUE(run.result.ok) << run.result.error << run.log;
  expect_ssm(run, "switch mid-reach");
  const auto touches = run.user(kTouch), misses = run.user(kMiss);
  ASSERT_EQ(touches.size() + misses.size(), 1u) << run.log;
  if (!touches.empty()) {
    expect_in_place_before(run, touches[0], 0.1);
  } else {
    // Missed: the planner said before the finger got there that it would be late or had to wait.
    bool reported = false;
    for (const auto& e : run.events)
      if (e.what == "planner" && e.t < misses[0].t && (e.kind == 3 || e.text.find("late") != std::string::npos))
        reported = true;
    EXPECT_TRUE(reported) << "a miss the planner did not report";
  }
  // The plate relocated toward the +y face.
  bool targeted = false;
  for (const auto& k : run.ticks) targeted = targeted || k.feature == "cube +y face";
  EXPECT_TRUE(targeted);
}

// The top face is beyond the PUMA's joint limits: the planner says so and keeps the plate away;
// the finger goes through the virtual face (a miss, counted).
TEST(DisplayLoop, AnUnreachableFeatureIsReportedNotSilentlyMissed) {
  LoopSetup s;
  s.domain = 75;
  s.script = {"wait 2.0", "move 0.65 0.0 0.45 0.8", "wait 1.0", "reach cube +z face at 0.05 0.05 speed 0.6",
              "withdraw 0.1 0.5"};
  const LoopRun run = run_loop(s);
  ASSERT_TRUE(run.result.ok) << run.result.error << run.log;
  expect_ssm(run, "unreachable top face");
  EXPECT_EQ(run.user(kMiss).size(), 1u) << run.log;
  EXPECT_TRUE(run.user(kTouch).empty());
  bool reported = false;
  for (const auto& e : run.events)
    if (e.what == "planner" && e.kind == 4 && e.text.find("joint limits") != std::string::npos) reported = true;
  EXPECT_TRUE(reported) << "no UNREACHABLE status naming the joint limits";
  EXPECT_NE(run.log.find("'cube +z face' is out of the arm's reach"), std::string::npos) << run.log;
}

}  // namespace wysiwyf::test
