#include "random_sample.hpp"

#include <cmath>
#include <limits>

namespace wysiwyf::safety {

namespace {

// The member's own name: "header.stamp_ns" -> "stamp_ns".
std::string leaf(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? path : path.substr(dot + 1);
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

int channels_of(const std::string& encoding) {
  if (encoding == "mono8") return 1;
  if (encoding == "rgba8" || encoding == "bgra8" || encoding == "32FC1") return 4;
  return 3;
}

const char* const kFrames[] = {"base", "eye", "dev", "world", "left", "right", "camera", "", "base_link", "tool0"};
const char* const kWords[] = {"surface", "admittance", "script", "plumb_bob", "rgb8", "bgr8", "mono8", "rgba8"};
const char* const kSources[] = {"surface", "admittance", "script", ""};
const char* const kEncodings[] = {"rgb8", "bgr8", "mono8", "rgba8", "bgra8", "32FC1"};

}  // namespace

std::vector<std::uint8_t> RandomSample::make(const types::DynamicType_ptr& type, std::int64_t now_ns, bool hostile) {
  out_ = {0x00, 0x01, 0x00, 0x00};  // CDR, little-endian
  hostile_ = hostile;
  now_ns_ = now_ns;
  last_number_.clear();
  last_encoding_.clear();
  CdrWalk<RandomSample> walk(*this);
  walk.structure(resolve_alias(type), "");
  // Bytes that are not the type: cut short, or one byte changed (a length, a boolean).
  if (hostile_ && chance(0.03)) out_.resize(4 + below(out_.size() - 3));
  if (hostile_ && out_.size() > 4 && chance(0.03)) out_[4 + below(out_.size() - 4)] = static_cast<std::uint8_t>(rng_());
  return out_;
}

double RandomSample::real(const std::string& path) {
  if (hostile_ && chance(0.3)) {
    const double special[] = {std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::infinity(),
                              -std::numeric_limits<double>::infinity(),
                              1e308,
                              -1e308,
                              1e-310,
                              -0.0,
                              1e9,
                              -1e9};
    return special[below(std::size(special))];
  }
  if (hostile_) return std::uniform_real_distribution<double>(-1e3, 1e3)(rng_);
  // A unit quaternion, its four components written in turn (x, y, z, w as the IDL orders them).
  const std::string name = leaf(path);
  if (path.find("orientation") != std::string::npos || path.find("rotation") != std::string::npos) {
    if (name == "x") {
      std::normal_distribution<double> n(0, 1);
      double norm = 0;
      for (double& c : quaternion_) norm += (c = n(rng_)) * c;
      for (double& c : quaternion_) c /= std::sqrt(norm);
    }
    if (name == "x") return quaternion_[0];
    if (name == "y") return quaternion_[1];
    if (name == "z") return quaternion_[2];
    if (name == "w") return quaternion_[3];
  }
  return std::uniform_real_distribution<double>(-2, 2)(rng_);
}

std::int64_t RandomSample::stamp() {
  std::int64_t s = now_ns_ - static_cast<std::int64_t>(below(20'000'000));
  if (hostile_ && chance(0.5)) {
    const std::int64_t choices[] = {0,
                                    std::numeric_limits<std::int64_t>::min(),
                                    std::numeric_limits<std::int64_t>::max(),
                                    now_ns_ + 1'000'000'000,
                                    now_ns_ - 1'000'000'000,
                                    now_ns_ + static_cast<std::int64_t>(below(10'000'000)),
                                    last_stamp_ns_ - 1'000'000,
                                    -1};
    s = choices[below(std::size(choices))];
  }
  return last_stamp_ns_ = s;
}

std::string RandomSample::text(std::uint32_t bound, const std::string& path) {
  const std::string name = leaf(path);
  if (!hostile_ || chance(0.3)) {
    if (name == "encoding") return last_encoding_ = kEncodings[below(std::size(kEncodings))];
    if (name == "source") return kSources[below(std::size(kSources))];
    if (name == "frame_id" && chance(0.6)) return "base";  // most inputs are in the base frame
    if (name.find("frame") != std::string::npos) return kFrames[below(std::size(kFrames))];
    return chance(0.5) ? kFrames[below(std::size(kFrames))] : kWords[below(std::size(kWords))];
  }
  const std::uint32_t cap = bound ? bound : 300;
  std::uint32_t n = static_cast<std::uint32_t>(below(std::uint64_t{cap} + 1));
  if (chance(0.05)) n = cap + 1;  // one past the bound: deserialisation refuses it
  std::string s(n, '\0');
  for (char& c : s) c = static_cast<char>(below(256));
  return s;
}

void RandomSample::put_string(const std::string& s) {
  put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + 1));
  out_.insert(out_.end(), s.begin(), s.end());
  out_.push_back(0);
}

void RandomSample::basic(const types::DynamicType_ptr& type, const std::string& path) {
  const std::string name = leaf(path);
  // Small numbers where a pipeline sends them; an image's row length fits its width.
  auto whole = [&](std::uint64_t wide) -> std::uint64_t {
    std::uint64_t v = below(11);
    if (hostile_) v = chance(0.5) ? rng_() & wide : v;
    if (!hostile_ && (name == "width" || name == "height")) v = 1 + below(48);
    if (!hostile_ && name == "step") v = last_number_["width"] * channels_of(last_encoding_);
    last_number_[name] = v;
    return v;
  };
  switch (type->get_kind()) {
    case types::TK_BOOLEAN:
      put<std::uint8_t>(hostile_ && chance(0.02) ? 2 : static_cast<std::uint8_t>(below(2)));
      break;
    case types::TK_BYTE:
    case types::TK_CHAR8: put<std::uint8_t>(static_cast<std::uint8_t>(below(256))); break;
    case types::TK_INT16: put<std::int16_t>(static_cast<std::int16_t>(whole(0xffff))); break;
    case types::TK_UINT16: put<std::uint16_t>(static_cast<std::uint16_t>(whole(0xffff))); break;
    case types::TK_INT32: put<std::int32_t>(static_cast<std::int32_t>(whole(0xffffffff))); break;
    case types::TK_UINT32: put<std::uint32_t>(static_cast<std::uint32_t>(whole(0xffffffff))); break;
    case types::TK_INT64:
      put<std::int64_t>(ends_with(name, "stamp_ns") ? stamp() : static_cast<std::int64_t>(whole(~0ull)));
      break;
    case types::TK_UINT64: put<std::uint64_t>(whole(~0ull)); break;
    case types::TK_FLOAT32: put<float>(static_cast<float>(real(path))); break;
    case types::TK_FLOAT64: put<double>(real(path)); break;
    case types::TK_STRING8: put_string(text(type->get_descriptor()->get_bounds(0), path)); break;
    case types::TK_ENUM: {
      const std::uint32_t literals = type->get_members_count();
      put<std::uint32_t>(hostile_ && chance(0.2) ? static_cast<std::uint32_t>(rng_())
                                                 : static_cast<std::uint32_t>(below(literals ? literals : 1)));
      break;
    }
    default: throw std::runtime_error("'" + path + "': a kind (" + std::to_string(type->get_kind()) + ") not written");
  }
}

std::uint32_t RandomSample::length(std::uint32_t bound, const types::DynamicType_ptr& element,
                                   const std::string& path) {
  const bool octets = element->get_kind() == types::TK_BYTE || element->get_kind() == types::TK_CHAR8;
  const bool structs = element->get_kind() == types::TK_STRUCTURE;
  std::uint32_t n;
  if (!hostile_ && octets && leaf(path) == "data") {
    n = static_cast<std::uint32_t>(last_number_["height"] * last_number_["step"]);  // an image that fits
  } else {
    const std::uint32_t cap = structs ? 4 : octets ? 4096 : 12;
    const std::uint32_t top = bound ? std::min(bound, cap) : cap;
    n = static_cast<std::uint32_t>(below(std::uint64_t{top} + 1));
    if (!hostile_ && !octets && !structs && chance(0.6)) n = std::min<std::uint32_t>(top, chance(0.5) ? 6 : 7);
    if (hostile_ && bound && bound <= 4096 && chance(0.05)) n = bound + (chance(0.5) ? 1 : 0);
  }
  put<std::uint32_t>(n);
  return n;
}

void RandomSample::bytes(std::uint32_t n, const std::string&) {
  const std::size_t at = out_.size();
  out_.resize(at + n);
  for (std::size_t i = at; i < out_.size(); ++i) out_[i] = static_cast<std::uint8_t>(rng_());
}

}  // namespace wysiwyf::safety
