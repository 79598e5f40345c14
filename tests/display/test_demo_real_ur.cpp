// demo-real-ur5e.yaml against the UR emulator (libs/robot/ur_controller_emulator: RTDE, the
// script port and the dashboard; lockstep, on the simulated clock): the whole display on a UR5e
// through ur_driver, the wrist wrench from the emulated TCP force sensor, its two cameras reading
// a stereo recording (made by camera_sim) of a hand with the fingertip LED reaching for the cube.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "demo_runs.hpp"
#include "display_support.hpp"
#include "stereo_recording.hpp"
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
  const std::string yaml = "wysiwyf: 1\ninclude: [" + kPipelines +
                           "demo-real-ur5e.yaml]\ncomponents:\n"
                           "  rec: {type: test_display_recorder, rate: 1000, params: {samples: " +
                           (dir / "samples.csv").string() + ", events: " + (dir / "events.csv").string() +
                           "},\n    topics: {joint_state: robot/joint_state, device_pose: robot/device_pose, "
                           "setpoint: robot/setpoint, mode: display/mode, planner: display/planner, "
                           "wrench: robot/wrench, tracked_hand: hand/position}}\n";
  const PipelineSpec spec = load_pipeline_from_string(
      yaml, (dir / "real-ur5e-with-recorder.yaml").string(),
      {"domain=85", "dds.transport=local", "clock.mode=sim", "clock.step=1ms", "clock.pace=1", "clock.duration=2s",
       "arm.params.host=127.0.0.1", "arm.params.lockstep=true", "arm.params.reply_timeout=5",
       "arm.params.rtde_port=" + std::to_string(controller.rtde_port()),
       "arm.params.script_port=" + std::to_string(controller.script_port()),
       "arm.params.dashboard_port=" + std::to_string(controller.dashboard_port()),
       "camera.params.source=" + (dir / "left_%d.png").string(), "camera.params.backend=any",
       "camera_right.params.source=" + (dir / "right_%d.png").string(), "camera_right.params.backend=any",
       "record.params.path=" + (dir / "real-ur5e.mp4").string()});
  Loader loader({WYSIWYF_TEST_COMPONENT_DIR, WYSIWYF_COMPONENT_DIR});
  std::ostringstream log;
  RunResult result;
  {
    Runtime runtime(spec, loader, RunOptions{"", false, &log});
    result = runtime.run();
  }
  ASSERT_TRUE(result.ok) << result.error << log.str();
  const std::string text = log.str();
  EXPECT_NE(text.find("[supervisor] idle -> surface"), std::string::npos) << text;
  EXPECT_EQ(text.find("-> fault"), std::string::npos) << text;
  EXPECT_EQ(text.find("holding"), std::string::npos) << text;
  // One controller period per tick of the arm's 500 Hz, none refused.
  const auto counters = controller.counters();
  EXPECT_GE(counters.periods, 950u);
  EXPECT_EQ(counters.packages_refused, 0u);
  EXPECT_EQ(counters.scripts_run, 1u);
  // The hand was tracked from the video, the planner went for the knob, the plate stayed put
  // within a millimetre while the hand was on its way (the knob is where the plate parks).
  std::ifstream samples(dir / "samples.csv");
  int tracked = 0, planned = 0;
  for (std::string row; std::getline(samples, row);) {
    const auto f = split(row);
    if (f.size() < 45) continue;
    tracked += std::stoi(f[44]) == msg::TRACKING_OK;
    planned += f[40] == "cube +x knob";
  }
  std::printf(
      "[measured] real pipeline on the UR5e, 2 s: %llu controller periods, %d ms with a tracked hand, %d ms with the "
      "+x knob as the target\n",
      static_cast<unsigned long long>(counters.periods), tracked, planned);
  EXPECT_GT(tracked, 1000);
  EXPECT_GT(planned, 500);
}

}  // namespace
}  // namespace wysiwyf::test
