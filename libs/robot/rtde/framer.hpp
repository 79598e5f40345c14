#pragma once
// RTDE over TCP: bytes arrive in any chunks; the framer cuts them into whole packages by their
// headers. A size below the header's or above kMaxPackageSize cannot be resynchronised (the next
// header is unknown): the framer stops and says why, and the connection must be closed. A package
// of an unknown type is whole and is handed on (the caller refuses and counts it).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rtde/protocol.hpp"

namespace wysiwyf::robot::rtde {

struct RawPackage {
  std::uint8_t type = 0;  // the header's type byte (package_type() names it, or not)
  const std::uint8_t* payload = nullptr;
  std::size_t size = 0;  // payload bytes (the package's size less the header)
};

class PackageFramer {
 public:
  PackageFramer() { buffer_.reserve(2 * kMaxPackageSize); }

  // Appends received bytes (nothing, once failed()).
  void feed(const std::uint8_t* data, std::size_t n);
  // The next whole package, valid until the next feed() or next(); none when more bytes are
  // needed or the stream failed.
  std::optional<RawPackage> next();

  // Whether the stream is broken (a header with an impossible size), and why.
  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }
  // Bytes received and not yet cut into a package.
  std::size_t pending() const { return buffer_.size() - start_; }
  // Forgets everything, for a new connection.
  void reset();

 private:
  std::vector<std::uint8_t> buffer_;
  std::size_t start_ = 0;  // the first byte not yet handed out
  std::string error_;
};

}  // namespace wysiwyf::robot::rtde
