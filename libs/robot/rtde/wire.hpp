#pragma once
// Big-endian reading and writing of RTDE's scalar types. The reader never reads past its end: a
// read that would sets failed() and returns zero, so a parser reads a whole structure and checks
// once. The writer appends to a byte vector.
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

namespace wysiwyf::robot::rtde {

class WireReader {
 public:
  WireReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t u8() { return static_cast<std::uint8_t>(take(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(take(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(take(4)); }
  std::uint64_t u64() { return take(8); }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  double f64() {
    const std::uint64_t bits = take(8);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  // The next n bytes as text (empty, and failed, when fewer are left).
  std::string_view text(std::size_t n) {
    if (failed_ || n > size_ - pos_) return fail_view();
    const std::string_view v(reinterpret_cast<const char*>(data_ + pos_), n);
    pos_ += n;
    return v;
  }
  // The rest as text.
  std::string_view rest() { return text(size_ - pos_); }

  bool failed() const { return failed_; }
  std::size_t remaining() const { return size_ - pos_; }
  // Whether every byte was read and none was missing.
  bool done() const { return !failed_ && pos_ == size_; }

 private:
  std::uint64_t take(std::size_t n) {
    if (failed_ || n > size_ - pos_) {
      failed_ = true;
      return 0;
    }
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i) v = (v << 8) | data_[pos_ + i];
    pos_ += n;
    return v;
  }
  std::string_view fail_view() {
    failed_ = true;
    return {};
  }

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  bool failed_ = false;
};

class WireWriter {
 public:
  explicit WireWriter(std::vector<std::uint8_t>& out) : out_(out) {}

  void u8(std::uint8_t v) { put(v, 1); }
  void u16(std::uint16_t v) { put(v, 2); }
  void u32(std::uint32_t v) { put(v, 4); }
  void u64(std::uint64_t v) { put(v, 8); }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f64(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    put(bits, 8);
  }
  void text(std::string_view s) { out_.insert(out_.end(), s.begin(), s.end()); }

 private:
  void put(std::uint64_t v, std::size_t n) {
    for (std::size_t i = n; i-- > 0;) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  std::vector<std::uint8_t>& out_;
};

}  // namespace wysiwyf::robot::rtde
