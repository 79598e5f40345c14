#pragma once
// ATI Net F/T "Raw Data Transfer" (RDT) over UDP, port 49152 (ATI Net F/T manual, section 9.1):
//   request  8 bytes, big-endian: uint16 header 0x1234, uint16 command, uint32 sample count
//            (command 0 stop, 2 start real-time streaming, 0x42 set software bias; count 0 = endless)
//   record  36 bytes, big-endian: uint32 rdt_sequence, uint32 ft_sequence, uint32 status,
//            int32 Fx Fy Fz Tx Ty Tz in counts (divide by counts-per-force / counts-per-torque)
// Parsing never trusts the input: every malformed datagram is an error value, never a crash.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace wysiwyf::robot::rdt {

constexpr std::uint16_t kHeader = 0x1234;
constexpr std::size_t kRequestSize = 8;
constexpr std::size_t kRecordSize = 36;
constexpr std::uint16_t kDefaultPort = 49152;

enum class Command : std::uint16_t { kStop = 0x0000, kStartStreaming = 0x0002, kSetBias = 0x0042 };

struct Request {
  Command command = Command::kStartStreaming;
  std::uint32_t sample_count = 0;  // 0: endless
};

struct Record {
  std::uint32_t rdt_sequence = 0;
  std::uint32_t ft_sequence = 0;
  std::uint32_t status = 0;              // 0: healthy; otherwise the sensor's error bits
  std::array<std::int32_t, 6> counts{};  // Fx Fy Fz Tx Ty Tz
};

enum class ParseError { kNone, kShort, kLong, kWrongHeader, kUnknownCommand, kStatusError, kOutOfRange };
std::string to_string(ParseError e);

std::array<std::uint8_t, kRequestSize> encode(const Request& r);
std::array<std::uint8_t, kRecordSize> encode(const Record& r);

struct RequestResult {
  ParseError error = ParseError::kNone;
  Request request;
};
RequestResult parse_request(const std::uint8_t* data, std::size_t size);

struct RecordResult {
  ParseError error = ParseError::kNone;
  Record record;
};
// max_counts: readings beyond it (the sensor's calibrated range) are kOutOfRange.
RecordResult parse_record(const std::uint8_t* data, std::size_t size, std::int64_t max_counts);

// Samples lost between two rdt_sequence numbers (wrapping at 2^32).
inline std::uint32_t dropped_between(std::uint32_t previous, std::uint32_t current) { return current - previous - 1u; }

}  // namespace wysiwyf::robot::rdt
