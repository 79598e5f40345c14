#pragma once
// Reads a sample's CDR bytes (as its type support wrote them) by its type's description and finds
// the first number that is not finite: what a component must never send.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "cdr_walk.hpp"

namespace wysiwyf::safety {

class FiniteCheck {
 public:
  // The path of the first non-finite float or double in `cdr` ("pose.position.x"), empty if none.
  // Throws std::runtime_error where the bytes end early.
  static std::string first_non_finite(const std::vector<std::uint8_t>& cdr, const types::DynamicType_ptr& type) {
    FiniteCheck check(cdr);
    CdrWalk<FiniteCheck> walk(check);
    walk.structure(resolve_alias(type), "");
    return check.found_;
  }

  void basic(const types::DynamicType_ptr& type, const std::string& path) {
    switch (type->get_kind()) {
      case types::TK_BOOLEAN:
      case types::TK_BYTE:
      case types::TK_CHAR8: skip(1, path); break;
      case types::TK_INT16:
      case types::TK_UINT16: skip(2, path); break;
      case types::TK_INT32:
      case types::TK_UINT32:
      case types::TK_ENUM: skip(4, path); break;
      case types::TK_INT64:
      case types::TK_UINT64: skip(8, path); break;
      case types::TK_FLOAT32: check(static_cast<double>(read<float>(path)), path); break;
      case types::TK_FLOAT64: check(read<double>(path), path); break;
      case types::TK_STRING8: {
        const auto n = read<std::uint32_t>(path);
        need(n, path);
        pos_ += n;
        break;
      }
      default: throw std::runtime_error("'" + path + "': a kind not read");
    }
  }
  std::uint32_t length(std::uint32_t, const types::DynamicType_ptr&, const std::string& path) {
    return read<std::uint32_t>(path);
  }
  void bytes(std::uint32_t n, const std::string& path) {
    need(n, path);
    pos_ += n;
  }

 private:
  explicit FiniteCheck(const std::vector<std::uint8_t>& cdr) : cdr_(cdr) {}
  template <class T>
  T read(const std::string& path) {
    pos_ = cdr_aligned(pos_, sizeof(T));
    need(sizeof(T), path);
    T v;
    std::memcpy(&v, cdr_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  void skip(std::size_t size, const std::string& path) {
    pos_ = cdr_aligned(pos_, size);
    need(size, path);
    pos_ += size;
  }
  void need(std::size_t n, const std::string& path) const {
    if (pos_ + n > cdr_.size()) throw std::runtime_error("the sample ends inside '" + path + "'");
  }
  void check(double v, const std::string& path) {
    if (!std::isfinite(v) && found_.empty()) found_ = path + " = " + std::to_string(v);
  }

  const std::vector<std::uint8_t>& cdr_;
  std::size_t pos_ = 4;  // after the encapsulation header
  std::string found_;
};

}  // namespace wysiwyf::safety
