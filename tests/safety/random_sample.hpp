#pragma once
// Random samples of any message type, as the CDR bytes a DDS reader would receive (little-endian
// XCDR1), seeded and reproducible. Two kinds:
//  - plausible: values near what a pipeline sends (positions within metres, unit quaternions,
//    stamps within 20 ms before now, frame ids the pipelines use, images whose data fits their
//    size), so a component's code past its input checks runs;
//  - hostile: NaN, infinities, 1e308, denormals and -0 among the numbers; stamps of 0,
//    INT64_MIN/MAX, seconds ahead or behind, before the last one; strings of random bytes up to
//    their bound; enum values out of range; sequences from empty to their bound (and one past it,
//    which deserialisation must refuse, as DDS does).
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "cdr_walk.hpp"

namespace wysiwyf::safety {

class RandomSample {
 public:
  explicit RandomSample(std::uint64_t seed) : rng_(seed) {}

  // A sample of `type` (a structure), stamped about `now_ns`.
  std::vector<std::uint8_t> make(const types::DynamicType_ptr& type, std::int64_t now_ns, bool hostile);

  std::mt19937_64& rng() { return rng_; }

  // The walk's visitor (cdr_walk.hpp).
  void basic(const types::DynamicType_ptr& type, const std::string& path);
  std::uint32_t length(std::uint32_t bound, const types::DynamicType_ptr& element, const std::string& path);
  void bytes(std::uint32_t n, const std::string& path);

 private:
  template <class T>
  void put(T v) {
    out_.resize(cdr_aligned(out_.size(), sizeof(T)));
    const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
    out_.insert(out_.end(), b, b + sizeof(T));
  }
  void put_string(const std::string& s);
  double real(const std::string& path);
  std::int64_t stamp();
  std::string text(std::uint32_t bound, const std::string& path);
  bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
  std::uint64_t below(std::uint64_t n) { return n ? std::uniform_int_distribution<std::uint64_t>(0, n - 1)(rng_) : 0; }

  std::mt19937_64 rng_;
  std::vector<std::uint8_t> out_;
  bool hostile_ = false;
  std::int64_t now_ns_ = 0, last_stamp_ns_ = 0;
  double quaternion_[4] = {0, 0, 0, 1};               // the unit quaternion being written (plausible)
  std::map<std::string, std::uint64_t> last_number_;  // by member name: an image's height, width
  std::string last_encoding_;
};

}  // namespace wysiwyf::safety
