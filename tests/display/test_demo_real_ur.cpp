// demo-real-ur5e.yaml against the UR emulator (libs/robot/ur_controller_emulator: RTDE, the
// script port and the dashboard; lockstep, on the simulated clock): the whole display on a UR5e
// through ur_driver, the wrist wrench from the emulated TCP force sensor, its two cameras reading
// a stereo recording (made by camera_sim) of a hand with the fingertip LED reaching for the cube.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "real_pipeline.hpp"
#include "ur_controller_emulator/ur_emulator.hpp"

namespace wysiwyf::test {
namespace {

TEST(DemoPipelines, TheRealOneRunsOnTheUr5eAgainstItsEmulator) {
  const auto dir = display_scratch();
  const std::string urdf = std::string(WYSIWYF_CONFIG_DIR) + "/robots/ur5e.urdf";
  Eigen::Matrix<double, 6, 1> parked;  // robots/ur5e-sim.yaml's: the plate at (0.55, 0, 0.4)
  parked << 2.802180, -1.581828, 1.807510, -0.225596, 1.231347, 1.570657;
  write_stereo_recording(dir, urdf, parked);
  if (::testing::Test::HasFatalFailure()) return;
  robot::ur::UrEmulator::Options options;
  options.lockstep = true;
  options.controller.urdf = urdf;
  robot::ur::UrEmulator controller(options);  // parked there by default
  const RealRun run =
      run_real_pipeline("demo-real-ur5e.yaml", dir, 85,
                        {"arm.params.host=127.0.0.1", "arm.params.lockstep=true", "arm.params.reply_timeout=5",
                         "arm.params.rtde_port=" + std::to_string(controller.rtde_port()),
                         "arm.params.script_port=" + std::to_string(controller.script_port()),
                         "arm.params.dashboard_port=" + std::to_string(controller.dashboard_port())});
  ASSERT_TRUE(run.ok) << run.log;
  EXPECT_NE(run.log.find("[supervisor] idle -> surface"), std::string::npos) << run.log;
  EXPECT_EQ(run.log.find("-> fault"), std::string::npos) << run.log;
  EXPECT_EQ(run.log.find("holding"), std::string::npos) << run.log;
  // One controller period per tick of the arm's 500 Hz, none refused.
  const auto counters = controller.counters();
  EXPECT_GE(counters.periods, 950u);
  EXPECT_EQ(counters.packages_refused, 0u);
  EXPECT_EQ(counters.scripts_run, 1u);
  // The hand was tracked from the video, and the planner went for the knob.
  std::printf(
      "[measured] real pipeline on the UR5e, 2 s: %llu controller periods, %d ms with a tracked hand, %d ms with the "
      "+x knob as the target\n",
      static_cast<unsigned long long>(counters.periods), run.tracked, run.planned);
  EXPECT_GT(run.tracked, 1000);
  EXPECT_GT(run.planned, 500);
}

}  // namespace
}  // namespace wysiwyf::test
