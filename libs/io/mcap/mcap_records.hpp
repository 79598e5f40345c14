#pragma once
// The MCAP format's constants and little-endian primitives (https://mcap.dev/spec), shared by
// the writer and the reader.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace wysiwyf::io::mcap {

inline constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

enum Op : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

// Appends primitives to a byte buffer.
struct Bytes {
  std::vector<std::uint8_t> b;
  void u8(std::uint8_t v) { b.push_back(v); }
  void u16(std::uint16_t v) { put(&v, 2); }
  void u32(std::uint32_t v) { put(&v, 4); }
  void u64(std::uint64_t v) { put(&v, 8); }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    put(s.data(), s.size());
  }
  void bytes32(const std::uint8_t* p, std::size_t n) {
    u32(static_cast<std::uint32_t>(n));
    put(p, n);
  }
  void put(const void* p, std::size_t n) {
    const auto* c = static_cast<const std::uint8_t*>(p);
    b.insert(b.end(), c, c + n);
  }
  // Opcode and a length to fill in later: returns where the length goes.
  std::size_t open(Op op) {
    u8(op);
    const std::size_t at = b.size();
    u64(0);
    return at;
  }
  void close(std::size_t at) {
    const std::uint64_t n = b.size() - at - 8;
    std::memcpy(b.data() + at, &n, 8);
  }
  void clear() { b.clear(); }
};

// Reads primitives from a record's content; `ok` turns false on the first read past its end.
struct Cursor {
  const std::uint8_t* p;
  std::size_t n;
  std::size_t at = 0;
  bool ok = true;
  template <class T>
  T get() {
    T v{};
    if (!take(sizeof(T))) return v;
    std::memcpy(&v, p + at - sizeof(T), sizeof(T));
    return v;
  }
  std::string str() {
    const auto len = get<std::uint32_t>();
    if (!take(len)) return {};
    return std::string(reinterpret_cast<const char*>(p + at - len), len);
  }
  bool take(std::size_t k) {
    if (!ok || n - at < k) return ok = false;
    at += k;
    return true;
  }
};

}  // namespace wysiwyf::io::mcap
