#include "rtde/framer.hpp"

namespace wysiwyf::robot::rtde {

void PackageFramer::feed(const std::uint8_t* data, std::size_t n) {
  if (failed() || n == 0) return;
  // What was handed out is dropped before the buffer grows (a package handed out by next() stays
  // valid until here, as documented).
  if (start_ > 0) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    start_ = 0;
  }
  buffer_.insert(buffer_.end(), data, data + n);
}

std::optional<RawPackage> PackageFramer::next() {
  if (failed() || pending() < kHeaderSize) return std::nullopt;
  const std::uint8_t* p = buffer_.data() + start_;
  const std::size_t size = (static_cast<std::size_t>(p[0]) << 8) | p[1];
  if (size < kHeaderSize || size > kMaxPackageSize) {
    error_ = "an RTDE header says the package is " + std::to_string(size) + " bytes, expected " +
             std::to_string(kHeaderSize) + " to " + std::to_string(kMaxPackageSize) + " (type byte " +
             std::to_string(p[2]) + ")";
    return std::nullopt;
  }
  if (pending() < size) return std::nullopt;
  start_ += size;
  return RawPackage{p[2], p + kHeaderSize, size - kHeaderSize};
}

void PackageFramer::reset() {
  buffer_.clear();
  start_ = 0;
  error_.clear();
}

}  // namespace wysiwyf::robot::rtde
