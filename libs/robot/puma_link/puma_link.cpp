#include "puma_link/puma_link.hpp"

#include <zlib.h>

#include <cmath>
#include <cstring>

namespace wysiwyf::robot::link {

namespace {

// Little-endian field access, independent of the host's byte order.
template <class T>
void put(std::uint8_t* p, T v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof v);
  for (std::size_t i = 0; i < sizeof v; ++i) p[i] = static_cast<std::uint8_t>(bits >> (8 * i));
}
template <class T>
T get(const std::uint8_t* p) {
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) bits |= std::uint64_t{p[i]} << (8 * i);
  T v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

std::uint32_t crc(const std::uint8_t* data, std::size_t size) {
  return static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), data, static_cast<uInt>(size)));
}

void put_header(std::uint8_t* p, std::uint16_t kind, std::uint32_t sequence) {
  put<std::uint32_t>(p, kMagic);
  put<std::uint16_t>(p + 4, kVersion);
  put<std::uint16_t>(p + 6, kind);
  put<std::uint32_t>(p + 8, sequence);
}

DecodeError check(const std::uint8_t* data, std::size_t size, std::size_t expected, std::uint16_t kind) {
  if (size != expected) return DecodeError::kSize;
  if (get<std::uint32_t>(data) != kMagic) return DecodeError::kMagic;
  if (get<std::uint16_t>(data + 4) != kVersion) return DecodeError::kVersion;
  if (get<std::uint16_t>(data + 6) != kind) return DecodeError::kKind;
  if (get<std::uint32_t>(data + size - 4) != crc(data, size - 4)) return DecodeError::kChecksum;
  return DecodeError::kNone;
}

}  // namespace

std::string to_string(DecodeError e) {
  switch (e) {
    case DecodeError::kNone: return "ok";
    case DecodeError::kSize: return "wrong datagram size";
    case DecodeError::kMagic: return "not a puma-link datagram (magic)";
    case DecodeError::kVersion: return "another protocol version";
    case DecodeError::kKind: return "wrong datagram kind";
    case DecodeError::kChecksum: return "checksum mismatch";
    case DecodeError::kNotFinite: return "a joint value is not finite";
    case DecodeError::kFlags: return "unknown flag bits set";
  }
  return "?";
}

std::array<std::uint8_t, kCommandSize> encode(const Command& c) {
  std::array<std::uint8_t, kCommandSize> out{};
  put_header(out.data(), 1, c.sequence);
  put<std::uint32_t>(&out[12], (c.hold ? 1u : 0u) | (c.reset_fault ? 2u : 0u) | (c.query ? 4u : 0u));
  for (int i = 0; i < 6; ++i) {
    put<double>(&out[16 + 8 * i], c.q[i]);
    put<double>(&out[64 + 8 * i], c.qd[i]);
    put<double>(&out[112 + 8 * i], c.qdd[i]);
  }
  put<std::uint32_t>(&out[164], crc(out.data(), 164));
  return out;
}

std::array<std::uint8_t, kStateSize> encode(const State& s) {
  std::array<std::uint8_t, kStateSize> out{};
  put_header(out.data(), 2, s.sequence);
  put<std::uint32_t>(&out[12], s.ack);
  put<std::uint32_t>(&out[16], static_cast<std::uint32_t>(s.status));
  put<std::uint32_t>(&out[20], static_cast<std::uint32_t>(s.fault));
  for (int i = 0; i < 6; ++i) {
    put<double>(&out[24 + 8 * i], s.q[i]);
    put<double>(&out[72 + 8 * i], s.qd[i]);
    put<double>(&out[120 + 8 * i], s.tau[i]);
  }
  put<std::uint32_t>(&out[172], crc(out.data(), 172));
  return out;
}

DecodeError decode(const std::uint8_t* data, std::size_t size, Command& out) {
  if (const DecodeError e = check(data, size, kCommandSize, 1); e != DecodeError::kNone) return e;
  Command c;
  c.sequence = get<std::uint32_t>(data + 8);
  const std::uint32_t flags = get<std::uint32_t>(data + 12);
  c.hold = flags & 1u;
  c.reset_fault = flags & 2u;
  c.query = flags & 4u;
  if (flags & ~7u) return DecodeError::kFlags;
  for (int i = 0; i < 6; ++i) {
    c.q[i] = get<double>(data + 16 + 8 * i);
    c.qd[i] = get<double>(data + 64 + 8 * i);
    c.qdd[i] = get<double>(data + 112 + 8 * i);
    if (!std::isfinite(c.q[i]) || !std::isfinite(c.qd[i]) || !std::isfinite(c.qdd[i])) return DecodeError::kNotFinite;
  }
  out = c;
  return DecodeError::kNone;
}

DecodeError decode(const std::uint8_t* data, std::size_t size, State& out) {
  if (const DecodeError e = check(data, size, kStateSize, 2); e != DecodeError::kNone) return e;
  State s;
  s.sequence = get<std::uint32_t>(data + 8);
  s.ack = get<std::uint32_t>(data + 12);
  s.status = static_cast<Status>(get<std::uint32_t>(data + 16));
  s.fault = static_cast<Fault>(get<std::uint32_t>(data + 20));
  for (int i = 0; i < 6; ++i) {
    s.q[i] = get<double>(data + 24 + 8 * i);
    s.qd[i] = get<double>(data + 72 + 8 * i);
    s.tau[i] = get<double>(data + 120 + 8 * i);
    if (!std::isfinite(s.q[i]) || !std::isfinite(s.qd[i]) || !std::isfinite(s.tau[i])) return DecodeError::kNotFinite;
  }
  out = s;
  return DecodeError::kNone;
}

}  // namespace wysiwyf::robot::link
