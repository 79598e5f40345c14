#pragma once
// The contract between ur_driver, the URScript program it runs on the controller
// (config/robots/ur_follow.script) and the UR emulator, which executes that program's behaviour:
// which RTDE registers carry what, what the program reports, and the recipes both ends set up.
#include <string>
#include <string_view>
#include <vector>

#include "rtde/client_session.hpp"

namespace wysiwyf::robot::rtde::follow {

// The program's first line: the emulator runs a script only when it begins so.
constexpr std::string_view kHeader = "# wysiwyf_follow 1";

// Inputs the driver writes every period.
constexpr const char* kCounter = "input_int_register_24";  // one more every period: the watchdog's
constexpr const char* kMode = "input_int_register_25";     // kFollow or kHold
constexpr int kFollow = 1, kHold = 0;
// The reference q (registers 24..29), qd (30..35) and qdd (36..41).
constexpr int kFirstReferenceRegister = 24;
// What the program reports in output_int_register_24.
constexpr const char* kProgramState = "output_int_register_24";
enum class ProgramState : int { kNotRunning = 0, kFollowing = 1, kHolding = 2, kStoppedHostLost = 3 };
// Periods without a new counter after which the program stops the arm and ends.
constexpr int kWatchdogPeriods = 3;

// The input recipe: counter, mode, then q0..5, qd0..5, qdd0..5 as doubles.
inline std::vector<Variable> input_recipe() {
  std::vector<Variable> v = {{kCounter, FieldType::kInt32}, {kMode, FieldType::kInt32}};
  for (int r = 0; r < 18; ++r)
    v.push_back({"input_double_register_" + std::to_string(kFirstReferenceRegister + r), FieldType::kDouble});
  return v;
}

// The output recipe: the controller's state the driver publishes and checks.
inline std::vector<Variable> output_recipe() {
  return {{"timestamp", FieldType::kDouble},          {"actual_q", FieldType::kVector6d},
          {"actual_qd", FieldType::kVector6d},        {"actual_current", FieldType::kVector6d},
          {"target_moment", FieldType::kVector6d},    {"actual_TCP_force", FieldType::kVector6d},
          {"robot_mode", FieldType::kInt32},          {"safety_mode", FieldType::kInt32},
          {"runtime_state", FieldType::kUint32},      {"robot_status_bits", FieldType::kUint32},
          {"safety_status_bits", FieldType::kUint32}, {kProgramState, FieldType::kInt32}};
}

// Indices into input_recipe().
constexpr std::size_t kCounterIndex = 0, kModeIndex = 1, kQIndex = 2, kQdIndex = 8, kQddIndex = 14;

}  // namespace wysiwyf::robot::rtde::follow
