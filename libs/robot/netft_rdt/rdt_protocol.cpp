#include "netft_rdt/rdt_protocol.hpp"

namespace wysiwyf::robot::rdt {

namespace {

void put16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v >> 8);
  p[1] = static_cast<std::uint8_t>(v);
}
void put32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (24 - 8 * i));
}
std::uint16_t get16(const std::uint8_t* p) { return static_cast<std::uint16_t>((p[0] << 8) | p[1]); }
std::uint32_t get32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]};
}

}  // namespace

std::string to_string(ParseError e) {
  switch (e) {
    case ParseError::kNone: return "ok";
    case ParseError::kShort: return "datagram too short";
    case ParseError::kLong: return "datagram too long";
    case ParseError::kWrongHeader: return "wrong header (expected 0x1234)";
    case ParseError::kUnknownCommand: return "unknown command";
    case ParseError::kStatusError: return "the sensor reports an error in its status word";
    case ParseError::kOutOfRange: return "a reading beyond the sensor's calibrated range";
  }
  return "?";
}

std::array<std::uint8_t, kRequestSize> encode(const Request& r) {
  std::array<std::uint8_t, kRequestSize> out{};
  put16(&out[0], kHeader);
  put16(&out[2], static_cast<std::uint16_t>(r.command));
  put32(&out[4], r.sample_count);
  return out;
}

std::array<std::uint8_t, kRecordSize> encode(const Record& r) {
  std::array<std::uint8_t, kRecordSize> out{};
  put32(&out[0], r.rdt_sequence);
  put32(&out[4], r.ft_sequence);
  put32(&out[8], r.status);
  for (int i = 0; i < 6; ++i) put32(&out[12 + 4 * i], static_cast<std::uint32_t>(r.counts[i]));
  return out;
}

RequestResult parse_request(const std::uint8_t* data, std::size_t size) {
  RequestResult r;
  if (size < kRequestSize) return r.error = ParseError::kShort, r;
  if (size > kRequestSize) return r.error = ParseError::kLong, r;
  if (get16(data) != kHeader) return r.error = ParseError::kWrongHeader, r;
  const std::uint16_t command = get16(data + 2);
  if (command != 0x0000 && command != 0x0002 && command != 0x0042) return r.error = ParseError::kUnknownCommand, r;
  r.request.command = static_cast<Command>(command);
  r.request.sample_count = get32(data + 4);
  return r;
}

RecordResult parse_record(const std::uint8_t* data, std::size_t size, std::int64_t max_counts) {
  RecordResult r;
  if (size < kRecordSize) return r.error = ParseError::kShort, r;
  if (size > kRecordSize) return r.error = ParseError::kLong, r;
  r.record.rdt_sequence = get32(data);
  r.record.ft_sequence = get32(data + 4);
  r.record.status = get32(data + 8);
  for (int i = 0; i < 6; ++i) r.record.counts[i] = static_cast<std::int32_t>(get32(data + 12 + 4 * i));
  if (r.record.status != 0) return r.error = ParseError::kStatusError, r;
  for (const std::int32_t c : r.record.counts)
    if (c > max_counts || -static_cast<std::int64_t>(c) > max_counts) return r.error = ParseError::kOutOfRange, r;
  return r;
}

}  // namespace wysiwyf::robot::rdt
