// The shipped display pipelines: demo-sim.yaml (the paper's experiment, scripts/demo) and
// demo-real.yaml (the same display on puma_driver, ft_netft and two cameras), which differ by one
// line. Both validate; nothing that only a simulator has (sim/ topics, simulator components)
// reaches the real one's graph (the simulated experiment's contacts and figures:
// test_demo_figures.cpp); the two-object demo hits both objects; the real one runs
// against the emulated controller and the emulated Net F/T, tracking the hand on recorded stereo
// video, with no fault.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "demo_runs.hpp"
#include "display_support.hpp"
#include "netft_rdt/rdt_emulator.hpp"
#include "puma_controller_emulator/controller_emulator.hpp"
#include "scene/scene.hpp"
#include "real_pipeline.hpp"
#include "puma_model/puma_model.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {

namespace {

// The lines of a file that are not comments or blank.
std::vector<std::string> content_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) {
    const auto hash = line.find('#');
    std::string code = hash == std::string::npos ? line : line.substr(0, hash);
    code.erase(code.find_last_not_of(" \t") + 1);
    if (!code.empty()) out.push_back(code);
  }
  return out;
}

}  // namespace

TEST(DemoPipelines, SimAndRealDifferByOneLineAndNothingSimulatedLeaksIntoTheReal) {
  const auto sim = content_lines(kPipelines + "demo-sim.yaml"), real = content_lines(kPipelines + "demo-real.yaml");
  ASSERT_EQ(sim.size(), real.size());
  int differing = 0;
  for (std::size_t i = 0; i < sim.size(); ++i) differing += sim[i] != real[i];
  EXPECT_EQ(differing, 1);

  Loader loader({WYSIWYF_COMPONENT_DIR});
  const std::set<std::string> simulators = {"arm_sim", "camera_sim", "user_sim", "hand_tracker_sim", "display_metrics"};
  for (const char* name : {"demo-sim.yaml", "demo-real.yaml"}) {
    SCOPED_TRACE(name);
    const PipelineSpec spec = load_pipeline(kPipelines + name);
    const ValidationResult v = validate_pipeline(spec, loader);
    for (const auto& e : v.errors) ADD_FAILURE() << e.str();
    if (std::string(name) != "demo-real.yaml") continue;
    for (const auto& c : spec.components) {
      EXPECT_EQ(simulators.count(c.type.value), 0u) << c.name << " is a simulator (" << c.type.value << ")";
      for (const auto& [port, topic] : c.topics)
        EXPECT_NE(topic.value.rfind("sim/", 0), 0u) << c.name << "." << port << " reads or writes " << topic.value;
    }
    // Every topic the real display reads, something in it writes.
    for (const auto& w : v.warnings)
      EXPECT_EQ(w.message.find("no component of this pipeline publishes topic '"), std::string::npos)
          << "an input the real hardware leaves dangling: " << w.str();
  }
}

// demo-two-objects.yaml (issue 16): the plate goes from one object to the other, and the user
// pushes the box into the cube. The hand never touches the cube during the first contact, so the
// cube moves only if the box struck it and drove it; the wrist force rises at the impact (the
// plate under the finger slows as the cube's mass joins).
TEST(DemoPipelines, TheTwoObjectDemoPushesTheBoxIntoTheCubeAndReachesBoth) {
  const auto dir = display_scratch();
  const std::string text =
      run_demo_hitting_every_contact("demo-two-objects.yaml",
                                     {"domain=77", "record.params.path=" + (dir / "demo.mp4").string(),
                                      "metrics.params.summary=null", "metrics.params.report=" + dir.string()},
                                     2);
  EXPECT_NE(text.find("[physics] attached to box (box -y knob)"), std::string::npos) << text;
  EXPECT_NE(text.find("[physics] attached to cube (cube +x knob)"), std::string::npos) << text;
  // timeseries.csv: t_s, force_n, plate xyz, cube xyz, mode, attached, ...; the first contact is
  // the only one attached before the cube first moves.
  std::ifstream series(dir / "timeseries.csv");
  std::string row;
  ASSERT_TRUE(std::getline(series, row)) << "no timeseries.csv";
  // The force before: pushing the box alone, 50 ms before the cube moves (the setpoint brakes for
  // the impact from half its preview window ahead, and the hand feels that from then on).
  double cube_y = 0, t_impact = -1, force_before = 0, force_after = 0;
  std::vector<std::pair<double, double>> pushing;  // (t, force) while attached, before the impact
  while (std::getline(series, row)) {
    const auto f = split(row);
    ASSERT_GE(f.size(), 10u) << row;
    const double t = std::stod(f[0]), force = std::stod(f[1]), y = std::stod(f[6]);
    const bool attached = f[9] == "1";
    if (t_impact < 0 && y > 1e-4) {
      EXPECT_TRUE(attached) << "the cube moved at " << t << " s with the device on nothing";
      t_impact = t;
      for (const auto& [when, push] : pushing)
        if (when <= t_impact - 0.05) force_before = push;
    }
    if (attached && t_impact < 0) pushing.emplace_back(t, force);
    if (t_impact >= 0 && t <= t_impact + 0.05) force_after = std::max(force_after, force);
    if (t_impact >= 0 && cube_y < 0.02) cube_y = std::max(cube_y, y);
    if (cube_y >= 0.02) break;
  }
  std::printf(
      "[measured] two objects: impact at %.3f s, wrist force %.2f N before, %.2f N peak after; "
      "the cube driven %.1f mm\n",
      t_impact, force_before, force_after, cube_y * 1e3);
  EXPECT_GE(t_impact, 0) << "the box never struck the cube";
  EXPECT_GE(cube_y, 0.02) << "m the box drove the cube";
  EXPECT_GT(force_after, force_before + 2.0) << "N: the impact felt through the plate";
}

// demo-real.yaml against the emulated PUMA controller (lockstep, on the simulated clock) and the
// emulated Net F/T (the tool's weight, as the sensor feels it at the parked pose), its two
// cameras reading a stereo recording of a hand with the fingertip LED reaching for the cube.
TEST(DemoPipelines, TheRealOneRunsAgainstTheEmulators) {
  const auto dir = display_scratch();
  const std::string urdf = std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf";
  robot::Vector6d parked;
  parked << 0.344932, 0.380005, -3.43618, 0.346061, 1.49034, 3.11254;
  // The recording: 2 s at 25 Hz of the parked arm and a hand coming in from 1.1 m to 0.85 m.
  write_stereo_recording(dir, urdf, parked);
  if (::testing::Test::HasFatalFailure()) return;
  // The emulated controller, parked; the emulated sensor, feeling the tool's weight there.
  robot::link::ControllerEmulator::Options arm;
  arm.lockstep = true;
  arm.urdf = urdf;
  arm.drive = std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560_drive.yaml";
  arm.initial_q = parked;
  robot::link::ControllerEmulator controller(arm);
  const haptics::Scene scene = haptics::load_scene(std::string(WYSIWYF_CONFIG_DIR) + "/scenes/display_demo.yaml");
  const robot::PumaModel model(urdf, "dev");
  const Eigen::Matrix3d base_R_sensor = model.fk(parked).linear() * scene.device.dev_T_sensor.linear();
  const Eigen::Vector3d weight = base_R_sensor.transpose() * (scene.device.tool_mass * scene.gravity);
  const Eigen::Vector3d torque = scene.device.tool_com.cross(weight);
  robot::rdt::Emulator::Options ft;
  ft.port = 0;
  robot::rdt::Emulator sensor(ft);
  sensor.set_wrench({weight.x(), weight.y(), weight.z(), torque.x(), torque.y(), torque.z()});
  // The real pipeline, pointed at them, with the loop recorder beside it.
  const RealRun run = run_real_pipeline(
      "demo-real.yaml", dir, 79,
      {"arm.params.host=127.0.0.1", "arm.params.port=" + std::to_string(controller.port()), "arm.params.lockstep=true",
       "arm.params.reply_timeout=5", "wrench.params.host=127.0.0.1",
       "wrench.params.port=" + std::to_string(sensor.port()),
       // The emulated sensor streams on the wall clock, the pipeline ticks on its paced sim clock:
       // on a loaded machine a 30 ms gap between readings in sim time is the machine's, not the wiring's.
       "supervisor.params.wrench_timeout=0.5"});
  ASSERT_TRUE(run.ok) << run.log;
  EXPECT_NE(run.log.find("[supervisor] idle -> surface"), std::string::npos) << run.log;
  EXPECT_EQ(run.log.find("-> fault"), std::string::npos) << run.log;
  // Every tick reached the controller, none refused.
  const auto counters = controller.counters();
  EXPECT_GE(counters.commands_applied, 1900u);
  EXPECT_EQ(counters.rejected, 0u);
  // The hand was tracked from the video, and the planner went for the knob.
  std::printf(
      "[measured] real pipeline, 2 s: %llu commands applied by the emulated controller, %d ms with a tracked "
      "hand, %d ms with the +x knob as the target\n",
      static_cast<unsigned long long>(counters.commands_applied), run.tracked, run.planned);
  EXPECT_GT(run.tracked, 1000);
  EXPECT_GT(run.planned, 500);
}

}  // namespace wysiwyf::test
