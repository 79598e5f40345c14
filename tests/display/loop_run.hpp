#pragma once
// The display loop as a pipeline (the simulated arm, user and hand tracker, the planner,
// admittance_sim, the supervisor, metrics, and a recorder), run in this process on the sim clock,
// and what the recorder wrote. Free of GoogleTest: the display tests and the safety campaign use it.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "puma_model/types.hpp"
#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/runtime.hpp"
#include "wysiwyf/validator.hpp"

namespace wysiwyf::test {

// One tick of the recorder (tests/components/test_display_recorder.cpp).
struct Tick {
  double t = 0;  // s
  int mode = 0, planner = 0;
  robot::Vector6d q = robot::Vector6d::Zero(), qd = robot::Vector6d::Zero();
  Eigen::Vector3d hand = Eigen::Vector3d::Zero(), plate = Eigen::Vector3d::Zero(), setpoint = Eigen::Vector3d::Zero();
  Eigen::Quaterniond plate_q = Eigen::Quaterniond::Identity();
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // the wrist reading, sensor frame
  std::string feature;
};

struct Event {
  double t = 0;
  std::string what;  // "mode", "planner" or "user"
  int kind = 0;
  int contact = 0;
  std::string text;  // mode and planner: the reason; user: the feature
};

struct LoopRun {
  RunResult result;
  std::string log;
  std::vector<Tick> ticks;
  std::vector<Event> events;
  std::vector<Event> user(int kind) const {
    std::vector<Event> out;
    for (const auto& e : events)
      if (e.what == "user" && e.kind == kind) out.push_back(e);
    return out;
  }
};

// The loop's pipeline: the user's script (one action a string), the arm's start, and extra
// parameters for the planner, the supervisor and the tracker (YAML flow-map entries).
struct LoopSetup {
  std::vector<std::string> script;
  std::string initial_q = "[0.344932, 0.380005, -3.43618, 0.346061, 1.49034, 3.11254]";  // parked above the cube
  std::string planner = "";
  std::string supervisor = "";
  std::string tracker = "";
  std::string user = "";  // extra user_sim parameters
  double duration_s = 0;  // 0: until the script is done
  int domain = 70;
};

inline std::string loop_yaml(const LoopSetup& s, const std::filesystem::path& dir) {
  std::string script;
  for (const auto& line : s.script) script += (script.empty() ? "\"" : ", \"") + line + "\"";
  std::ostringstream y;
  y << "wysiwyf: 1\nname: display-test\ndomain: " << s.domain << "\ndds: {transport: local}\n"
    << "clock: {mode: sim, step: 1ms" << (s.duration_s > 0 ? ", duration: " + std::to_string(s.duration_s) + "s" : "")
    << "}\ncomponents:\n"
    << "  user: {type: user_sim, rate: 1000, params: {scene: scenes/display_demo.yaml, "
       "stop_when_done: true, script: ["
    << script << "]" << s.user
    << "},\n    topics: {objects: haptics/objects, hand_pose: sim/hand_pose, hand_target: sim/hand_target, "
       "events: user/events}}\n"
    << "  arm: {type: arm_sim, rate: 1000, params: {initial_q: " << s.initial_q << ", setpoint_source: supervisor},\n"
    << "    topics: {setpoint: robot/setpoint, hand_target: sim/hand_target, joint_state: robot/joint_state,\n"
    << "             device_pose: robot/device_pose, wrench: robot/wrench, hand_pose: sim/hand_pose, status: "
       "robot/status,\n             request: robot/request}}\n"
    << "  hand: {type: hand_tracker_sim, rate: 100, params: {" << s.tracker
    << "}, topics: {hand_pose: sim/hand_pose, hand: hand/position}}\n"
    << "  planner: {type: surface_planner, rate: 1000, params: {scene: scenes/display_demo.yaml" << s.planner << "},\n"
    << "    topics: {hand: hand/position, objects: haptics/objects, joint_state: robot/joint_state,\n"
    << "             device_pose: robot/device_pose, mode: display/mode, commanded: robot/setpoint,\n"
    << "             setpoint: display/surface, status: display/planner}}\n"
    << "  physics: {type: admittance_sim, rate: 1000, params: {scene: scenes/display_demo.yaml, attached_at_start: "
       "false},\n"
    << "    topics: {wrench: robot/wrench, device_pose: robot/device_pose, attach: display/attach,\n"
    << "             setpoint: display/admittance, objects: haptics/objects}}\n"
    << "  supervisor: {type: supervisor, rate: 1000, params: {scene: scenes/display_demo.yaml" << s.supervisor << "},\n"
    << "    topics: {surface: display/surface, admittance: display/admittance, wrench: robot/wrench,\n"
    << "             device_pose: robot/device_pose, hand: hand/position, robot_status: robot/status,\n"
    << "             planner_status: display/planner, objects: haptics/objects, setpoint: robot/setpoint,\n"
    << "             mode: display/mode, attach: display/attach, arm_request: robot/request}}\n"
    << "  metrics: {type: display_metrics, rate: 100, params: {scene: scenes/display_demo.yaml},\n"
    << "    topics: {events: user/events, device_pose: robot/device_pose, objects: haptics/objects, contacts: "
       "display/contacts}}\n"
    << "  rec: {type: test_display_recorder, rate: 1000, params: {samples: " << (dir / "samples.csv").string()
    << ", events: " << (dir / "events.csv").string() << "},\n"
    << "    topics: {joint_state: robot/joint_state, hand_pose: sim/hand_pose, device_pose: robot/device_pose,\n"
    << "             setpoint: robot/setpoint, mode: display/mode, planner: display/planner, events: user/events,\n"
    << "             wrench: robot/wrench}}\n";
  return y.str();
}

inline std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string f; std::getline(s, f, ',');) out.push_back(f);
  return out;
}

// The user's force at a tick: the wrist reading less the weight of the tool (tool_mass kg; the
// sensor's axes are the plate's).
inline double user_force(const Tick& k, double tool_mass) {
  const Eigen::Vector3d weight = k.plate_q.toRotationMatrix().transpose() * (tool_mass * Eigen::Vector3d(0, 0, -9.81));
  return (k.force - weight).norm();
}

// Runs the loop with its files in `dir` (made if missing). The pipeline's validation errors go to
// `errors` (the run goes ahead; the Runtime refuses what cannot run).
inline LoopRun run_loop_in(const LoopSetup& setup, const std::filesystem::path& dir,
                           std::vector<std::string>* errors = nullptr) {
  std::filesystem::create_directories(dir);
  Loader loader({WYSIWYF_TEST_COMPONENT_DIR, WYSIWYF_COMPONENT_DIR});
  const PipelineSpec spec = load_pipeline_from_string(loop_yaml(setup, dir), "display-test.yaml");
  const ValidationResult v = validate_pipeline(spec, loader);
  if (errors)
    for (const auto& e : v.errors) errors->push_back(e.str());
  std::ostringstream log;
  LoopRun run;
  {
    Runtime runtime(spec, loader, RunOptions{"", false, &log});
    run.result = runtime.run();
  }
  run.log = log.str();
  std::ifstream samples(dir / "samples.csv");
  for (std::string line; std::getline(samples, line);) {
    const auto f = split(line);
    if (f.size() < 41) continue;
    Tick k;
    k.t = std::stod(f[0]) * 1e-9;
    k.mode = std::stoi(f[1]), k.planner = std::stoi(f[2]);
    for (int j = 0; j < 6; ++j) k.q[j] = std::stod(f[3 + j]), k.qd[j] = std::stod(f[9 + j]);
    k.hand = {std::stod(f[15]), std::stod(f[16]), std::stod(f[17])};
    k.plate = {std::stod(f[18]), std::stod(f[19]), std::stod(f[20])};
    k.plate_q = Eigen::Quaterniond(std::stod(f[24]), std::stod(f[21]), std::stod(f[22]), std::stod(f[23]));
    k.setpoint = {std::stod(f[25]), std::stod(f[26]), std::stod(f[27])};
    k.force = {std::stod(f[37]), std::stod(f[38]), std::stod(f[39])};
    k.feature = f[40];
    run.ticks.push_back(k);
  }
  std::ifstream events(dir / "events.csv");
  for (std::string line; std::getline(events, line);) {
    const auto f = split(line);
    if (f.size() < 3) continue;
    Event e;
    e.t = std::stod(f[0]) * 1e-9;
    e.what = f[1];
    e.kind = std::stoi(f[2]);
    if (e.what == "user" && f.size() > 4) e.contact = std::stoi(f[3]), e.text = f[4];
    if ((e.what == "mode" || e.what == "planner") && f.size() > 3) e.text = f[3];
    run.events.push_back(e);
  }
  return run;
}

}  // namespace wysiwyf::test
