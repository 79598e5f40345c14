#include "rtde/protocol.hpp"

#include <array>
#include <utility>

namespace wysiwyf::robot::rtde {

std::optional<PackageType> package_type(std::uint8_t byte) {
  switch (static_cast<PackageType>(byte)) {
    case PackageType::kRequestProtocolVersion:
    case PackageType::kGetUrcontrolVersion:
    case PackageType::kTextMessage:
    case PackageType::kDataPackage:
    case PackageType::kSetupOutputs:
    case PackageType::kSetupInputs:
    case PackageType::kStart:
    case PackageType::kPause: return static_cast<PackageType>(byte);
  }
  return std::nullopt;
}

const char* to_string(PackageType type) {
  switch (type) {
    case PackageType::kRequestProtocolVersion: return "RTDE_REQUEST_PROTOCOL_VERSION";
    case PackageType::kGetUrcontrolVersion: return "RTDE_GET_URCONTROL_VERSION";
    case PackageType::kTextMessage: return "RTDE_TEXT_MESSAGE";
    case PackageType::kDataPackage: return "RTDE_DATA_PACKAGE";
    case PackageType::kSetupOutputs: return "RTDE_CONTROL_PACKAGE_SETUP_OUTPUTS";
    case PackageType::kSetupInputs: return "RTDE_CONTROL_PACKAGE_SETUP_INPUTS";
    case PackageType::kStart: return "RTDE_CONTROL_PACKAGE_START";
    case PackageType::kPause: return "RTDE_CONTROL_PACKAGE_PAUSE";
  }
  return "unknown";
}

namespace {

constexpr std::array<std::pair<FieldType, const char*>, 10> kFieldNames = {{
    {FieldType::kBool, "BOOL"},
    {FieldType::kUint8, "UINT8"},
    {FieldType::kUint32, "UINT32"},
    {FieldType::kUint64, "UINT64"},
    {FieldType::kInt32, "INT32"},
    {FieldType::kDouble, "DOUBLE"},
    {FieldType::kVector3d, "VECTOR3D"},
    {FieldType::kVector6d, "VECTOR6D"},
    {FieldType::kVector6Int32, "VECTOR6INT32"},
    {FieldType::kVector6Uint32, "VECTOR6UINT32"},
}};

}  // namespace

std::size_t field_size(FieldType type) {
  switch (type) {
    case FieldType::kBool:
    case FieldType::kUint8: return 1;
    case FieldType::kUint32:
    case FieldType::kInt32: return 4;
    case FieldType::kUint64:
    case FieldType::kDouble: return 8;
    case FieldType::kVector3d: return 24;
    case FieldType::kVector6d: return 48;
    case FieldType::kVector6Int32:
    case FieldType::kVector6Uint32: return 24;
  }
  return 0;
}

const char* to_string(FieldType type) {
  for (const auto& [t, name] : kFieldNames)
    if (t == type) return name;
  return "unknown";
}

std::optional<FieldType> field_type(std::string_view name) {
  for (const auto& [t, n] : kFieldNames)
    if (name == n) return t;
  return std::nullopt;
}

std::string_view to_string(RobotMode mode) {
  switch (mode) {
    case RobotMode::kNoController: return "NO_CONTROLLER";
    case RobotMode::kDisconnected: return "DISCONNECTED";
    case RobotMode::kConfirmSafety: return "CONFIRM_SAFETY";
    case RobotMode::kBooting: return "BOOTING";
    case RobotMode::kPowerOff: return "POWER_OFF";
    case RobotMode::kPowerOn: return "POWER_ON";
    case RobotMode::kIdle: return "IDLE";
    case RobotMode::kBackdrive: return "BACKDRIVE";
    case RobotMode::kRunning: return "RUNNING";
    case RobotMode::kUpdatingFirmware: return "UPDATING_FIRMWARE";
  }
  return "UNKNOWN";
}

std::string_view to_string(SafetyMode mode) {
  switch (mode) {
    case SafetyMode::kNormal: return "NORMAL";
    case SafetyMode::kReduced: return "REDUCED";
    case SafetyMode::kProtectiveStop: return "PROTECTIVE_STOP";
    case SafetyMode::kRecovery: return "RECOVERY";
    case SafetyMode::kSafeguardStop: return "SAFEGUARD_STOP";
    case SafetyMode::kSystemEmergencyStop: return "SYSTEM_EMERGENCY_STOP";
    case SafetyMode::kRobotEmergencyStop: return "ROBOT_EMERGENCY_STOP";
    case SafetyMode::kViolation: return "VIOLATION";
    case SafetyMode::kFault: return "FAULT";
    case SafetyMode::kValidateJointId: return "VALIDATE_JOINT_ID";
    case SafetyMode::kUndefined: return "UNDEFINED_SAFETY_MODE";
    case SafetyMode::kAutomaticModeSafeguardStop: return "AUTOMATIC_MODE_SAFEGUARD_STOP";
    case SafetyMode::kSystemThreePositionEnablingStop: return "SYSTEM_THREE_POSITION_ENABLING_STOP";
  }
  return "UNKNOWN";
}

std::string_view to_string(RuntimeState state) {
  switch (state) {
    case RuntimeState::kStopping: return "STOPPING";
    case RuntimeState::kStopped: return "STOPPED";
    case RuntimeState::kPlaying: return "PLAYING";
    case RuntimeState::kPausing: return "PAUSING";
    case RuntimeState::kPaused: return "PAUSED";
    case RuntimeState::kResuming: return "RESUMING";
  }
  return "UNKNOWN";
}

}  // namespace wysiwyf::robot::rtde
