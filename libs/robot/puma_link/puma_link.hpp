#pragma once
// The puma-link protocol, version 1 (docs/puma-link.md): commands from the host, states from the
// joint controller, little-endian, CRC-32 (zlib) checked. Decoding never trusts its input.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace wysiwyf::robot::link {

constexpr std::uint32_t kMagic = 0x4B4C5550;  // "PULK"
constexpr std::uint16_t kVersion = 1;
constexpr std::size_t kCommandSize = 168;
constexpr std::size_t kStateSize = 176;
constexpr std::uint16_t kDefaultPort = 47000;

using Joints = std::array<double, 6>;

// The joint reference for the next servo period: position and velocity now, and the acceleration
// that takes it to the next period (the servo's feedforward).
struct Command {
  std::uint32_t sequence = 0;
  bool hold = false;         // keep the current position; q, qd, qdd are ignored
  bool reset_fault = false;  // clear a latched controller fault
  bool query = false;        // only ask for the state: the reference stays; a lockstep controller does not advance
  Joints q{}, qd{}, qdd{};
};

enum class Status : std::uint32_t { kOk = 0, kHolding = 1, kFault = 2 };
enum class Fault : std::uint32_t { kNone = 0, kCommandTimeout = 1, kJointLimit = 2, kBadCommand = 3 };

struct State {
  std::uint32_t sequence = 0;
  std::uint32_t ack = 0;
  Status status = Status::kOk;
  Fault fault = Fault::kNone;
  Joints q{}, qd{}, tau{};
};

enum class DecodeError { kNone, kSize, kMagic, kVersion, kKind, kChecksum, kNotFinite, kFlags };
std::string to_string(DecodeError e);

std::array<std::uint8_t, kCommandSize> encode(const Command& c);
std::array<std::uint8_t, kStateSize> encode(const State& s);
DecodeError decode(const std::uint8_t* data, std::size_t size, Command& out);
DecodeError decode(const std::uint8_t* data, std::size_t size, State& out);

// True when `sequence` is newer than `last` (modulo 2^32, within half the range).
inline bool newer(std::uint32_t sequence, std::uint32_t last) { return static_cast<std::int32_t>(sequence - last) > 0; }

}  // namespace wysiwyf::robot::link
