#pragma once
// Universal Robots' Real-Time Data Exchange (RTDE), protocol version 2, as the UR "RTDE Guide"
// documents it: TCP port 30004, every package a big-endian header (uint16 size of the whole
// package, header included; uint8 type) and a payload; the client negotiates the protocol
// version, sets up an output recipe (the controller's variables it wants, at a frequency) and an
// input recipe (registers it will write), starts the stream and then exchanges data packages of
// those recipes. This header holds the protocol's constants and its field types.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace wysiwyf::robot::rtde {

constexpr std::uint16_t kPort = 30004;
constexpr std::uint16_t kProtocolVersion = 2;
constexpr std::size_t kHeaderSize = 3;
// The largest package this implementation reads or writes: a data package of every output
// variable is under 2 kB; the header's uint16 allows 65535, which a peer that misbehaves could
// use to make a reader wait.
constexpr std::size_t kMaxPackageSize = 4096;

enum class PackageType : std::uint8_t {
  kRequestProtocolVersion = 86,  // 'V'
  kGetUrcontrolVersion = 118,    // 'v'
  kTextMessage = 77,             // 'M'
  kDataPackage = 85,             // 'U'
  kSetupOutputs = 79,            // 'O'
  kSetupInputs = 73,             // 'I'
  kStart = 83,                   // 'S'
  kPause = 80,                   // 'P'
};

// The package type of a header byte, or none for a byte no package has.
std::optional<PackageType> package_type(std::uint8_t byte);
// The guide's name of a package type (RTDE_DATA_PACKAGE, ...).
const char* to_string(PackageType type);

// The types a recipe's fields have, with their names in setup replies.
enum class FieldType : std::uint8_t {
  kBool,  // uint8, 0 or 1
  kUint8,
  kUint32,
  kUint64,
  kInt32,
  kDouble,         // IEEE 754 binary64
  kVector3d,       // 3 doubles
  kVector6d,       // 6 doubles
  kVector6Int32,   // 6 int32
  kVector6Uint32,  // 6 uint32
};

// The field's size on the wire in bytes.
std::size_t field_size(FieldType type);
// The guide's name (BOOL, UINT8, ..., VECTOR6UINT32).
const char* to_string(FieldType type);
// The type of a name in a setup reply, or none (NOT_FOUND, IN_USE or anything else).
std::optional<FieldType> field_type(std::string_view name);

// What a setup reply says for a variable the controller does not have, or that another client's
// input recipe holds.
constexpr std::string_view kNotFound = "NOT_FOUND";
constexpr std::string_view kInUse = "IN_USE";

// robot_mode (INT32).
enum class RobotMode : std::int32_t {
  kNoController = -1,
  kDisconnected = 0,
  kConfirmSafety = 1,
  kBooting = 2,
  kPowerOff = 3,
  kPowerOn = 4,
  kIdle = 5,
  kBackdrive = 6,
  kRunning = 7,
  kUpdatingFirmware = 8,
};

// safety_mode (INT32).
enum class SafetyMode : std::int32_t {
  kNormal = 1,
  kReduced = 2,
  kProtectiveStop = 3,
  kRecovery = 4,
  kSafeguardStop = 5,
  kSystemEmergencyStop = 6,
  kRobotEmergencyStop = 7,
  kViolation = 8,
  kFault = 9,
  kValidateJointId = 10,
  kUndefined = 11,
  kAutomaticModeSafeguardStop = 12,
  kSystemThreePositionEnablingStop = 13,
};

// runtime_state (UINT32): the state of the program on the controller.
enum class RuntimeState : std::uint32_t {
  kStopping = 0,
  kStopped = 1,
  kPlaying = 2,
  kPausing = 3,
  kPaused = 4,
  kResuming = 5,
};

// The guide's names ("RUNNING", "PROTECTIVE_STOP", "PLAYING"; "UNKNOWN" for other values).
std::string_view to_string(RobotMode mode);
std::string_view to_string(SafetyMode mode);
std::string_view to_string(RuntimeState state);

// A text message's level (RTDE_TEXT_MESSAGE, protocol 2).
enum class MessageLevel : std::uint8_t { kException = 0, kError = 1, kWarning = 2, kInfo = 3 };

}  // namespace wysiwyf::robot::rtde
