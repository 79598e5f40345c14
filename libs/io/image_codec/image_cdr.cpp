#include "image_codec/image_cdr.hpp"

#include <cstring>
#include <limits>

namespace wysiwyf::io::image_codec {

namespace {

constexpr std::uint8_t kEncapsulation[4] = {0x00, 0x01, 0x00, 0x00};  // CDR, little endian

// Reads CDR after the encapsulation header; every read checks the bytes left, and the padding
// skipped to align must be zero (else writing back would not give the same bytes).
class In {
 public:
  In(const std::uint8_t* p, std::size_t n) : p_(p), n_(n) {}
  bool align(std::size_t a) {
    while (at_ % a) {
      if (at_ >= n_ || p_[at_] != 0) return fail("padding at byte " + std::to_string(at_ + 4) + " is not zero");
      ++at_;
    }
    return true;
  }
  template <typename T>
  bool number(T& v, const char* what) {
    if (!align(sizeof(T))) return false;
    if (n_ - at_ < sizeof(T)) return fail(std::string(what) + " past the end");
    std::memcpy(&v, p_ + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  bool string(std::string& s, std::uint32_t bound, const char* what) {
    std::uint32_t len = 0;
    if (!number(len, what)) return false;
    if (len == 0 || len - 1 > bound)
      return fail(std::string(what) + ": length " + std::to_string(len) + "; expected 1 to " +
                  std::to_string(bound + 1));
    if (n_ - at_ < len) return fail(std::string(what) + ": " + std::to_string(len) + " bytes past the end");
    if (p_[at_ + len - 1] != 0) return fail(std::string(what) + " is not NUL-terminated");
    s.assign(reinterpret_cast<const char*>(p_ + at_), len - 1);
    at_ += len;
    return true;
  }
  bool bytes(std::vector<std::uint8_t>& v, std::uint32_t bound, const char* what) {
    std::uint32_t len = 0;
    if (!number(len, what)) return false;
    if (len > bound)
      return fail(std::string(what) + ": " + std::to_string(len) + " bytes; at most " + std::to_string(bound));
    if (n_ - at_ < len) return fail(std::string(what) + ": " + std::to_string(len) + " bytes past the end");
    v.assign(p_ + at_, p_ + at_ + len);
    at_ += len;
    return true;
  }
  bool end() { return at_ == n_ ? true : fail(std::to_string(n_ - at_) + " bytes after the last field"); }
  const std::string& problem() const { return problem_; }

 private:
  bool fail(std::string why) {
    problem_ = std::move(why);
    return false;
  }
  const std::uint8_t* p_;
  std::size_t n_, at_ = 0;
  std::string problem_;
};

class Out {
 public:
  Out() { b_.assign(kEncapsulation, kEncapsulation + 4); }
  void align(std::size_t a) {
    while ((b_.size() - 4) % a) b_.push_back(0);
  }
  template <typename T>
  void number(T v) {
    align(sizeof(T));
    const auto at = b_.size();
    b_.resize(at + sizeof(T));
    std::memcpy(b_.data() + at, &v, sizeof(T));
  }
  void string(const std::string& s) {
    number(static_cast<std::uint32_t>(s.size() + 1));
    b_.insert(b_.end(), s.begin(), s.end());
    b_.push_back(0);
  }
  void bytes(const std::vector<std::uint8_t>& v) {
    number(static_cast<std::uint32_t>(v.size()));
    b_.insert(b_.end(), v.begin(), v.end());
  }
  std::vector<std::uint8_t> take() { return std::move(b_); }

 private:
  std::vector<std::uint8_t> b_;
};

std::string header_problem(const std::uint8_t* p, std::size_t n) {
  if (n < 4) return "a sample of " + std::to_string(n) + " bytes; expected at least the 4-byte CDR header";
  if (std::memcmp(p, kEncapsulation, 4) != 0) return "not little-endian CDR (encapsulation 00 01 00 00)";
  return "";
}

}  // namespace

std::string parse_image(const std::uint8_t* p, std::size_t n, ImageSample& out) {
  if (auto why = header_problem(p, n); !why.empty()) return "Image: " + why;
  In in(p + 4, n - 4);
  const bool ok = in.number(out.stamp_ns, "header.stamp_ns") && in.number(out.seq, "header.seq") &&
                  in.string(out.frame_id, 63, "header.frame_id") && in.number(out.height, "height") &&
                  in.number(out.width, "width") && in.string(out.encoding, 15, "encoding") &&
                  in.number(out.is_bigendian, "is_bigendian") && in.number(out.step, "step") &&
                  in.bytes(out.data, kMaxImageBytes, "data") && in.end();
  return ok ? "" : "Image: " + in.problem();
}

std::vector<std::uint8_t> image_cdr(const ImageSample& image) {
  Out o;
  o.number(image.stamp_ns);
  o.number(image.seq);
  o.string(image.frame_id);
  o.number(image.height);
  o.number(image.width);
  o.string(image.encoding);
  o.number(image.is_bigendian);
  o.number(image.step);
  o.bytes(image.data);
  return o.take();
}

std::string parse_compressed(const std::uint8_t* p, std::size_t n, CompressedFrame& out) {
  if (auto why = header_problem(p, n); !why.empty()) return "CompressedImage/Video: " + why;
  In in(p + 4, n - 4);
  std::uint32_t sec = 0, nsec = 0;
  const bool ok = in.number(sec, "timestamp.sec") && in.number(nsec, "timestamp.nsec") &&
                  in.string(out.frame_id, 63, "frame_id") &&
                  in.bytes(out.data, std::numeric_limits<std::uint32_t>::max(), "data") &&
                  in.string(out.format, 31, "format") && in.end();
  if (!ok) return "CompressedImage/Video: " + in.problem();
  if (nsec >= 1'000'000'000u)
    return "CompressedImage/Video: timestamp.nsec " + std::to_string(nsec) + "; expected < 10^9";
  out.stamp_ns = std::int64_t{sec} * 1'000'000'000 + nsec;
  return "";
}

std::vector<std::uint8_t> compressed_cdr(const CompressedFrame& frame) {
  Out o;
  o.number(static_cast<std::uint32_t>(frame.stamp_ns / 1'000'000'000));
  o.number(static_cast<std::uint32_t>(frame.stamp_ns % 1'000'000'000));
  o.string(frame.frame_id);
  o.bytes(frame.data);
  o.string(frame.format);
  return o.take();
}

namespace {
std::string foxglove_idl(const char* name, const char* what, const char* formats) {
  return std::string(
             "module foxglove {\n"
             "// A point in time: seconds and nanoseconds since the epoch (or since the sim clock's 0).\n"
             "struct Time {\n  uint32 sec;\n  uint32 nsec;\n};\n"
             "// ") +
         what + "\nstruct " + name + " {\n  Time timestamp;\n  string frame_id;\n  sequence<uint8> data;\n  // " +
         formats + "\n  string format;\n};\n};\n";
}
}  // namespace

std::string compressed_image_idl() { return foxglove_idl("CompressedImage", "A compressed image", "webp, png, jpeg"); }
std::string compressed_video_idl() {
  return foxglove_idl("CompressedVideo", "One access unit of a video stream (H.264 Annex B)", "h264");
}

}  // namespace wysiwyf::io::image_codec
