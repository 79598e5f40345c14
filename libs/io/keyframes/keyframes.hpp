#pragma once
// A table of timed rows given as one flat parameter list: [t0, v0..., t1, v1..., ...], times in
// seconds, strictly increasing from 0. Shared by the scripted sources of the io area.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace wysiwyf::io {

class Keyframes {
 public:
  // Throws std::invalid_argument saying what is wrong (for Context::reject).
  Keyframes(const std::vector<double>& flat, int values_per_row);

  struct Segment {
    int from, to;     // row indices (equal after the last row)
    double tau;       // 0..1 within the segment
    double duration;  // seconds
  };
  // The segment containing time t (seconds since start); after the end: the last row, tau 1.
  Segment at(double t) const;

  int rows() const { return static_cast<int>(times_.size()); }
  double time(int row) const { return times_[row]; }
  double end_time() const { return times_.back(); }
  const double* values(int row) const { return &values_[static_cast<std::size_t>(row) * width_]; }

 private:
  int width_;
  std::vector<double> times_;
  std::vector<double> values_;
};

// A script's own time: seconds since its first tick (so a script starts when the pipeline does,
// on the sim clock and on the wall clock alike), wrapped to the script's length when looping.
class ScriptTime {
 public:
  double at(std::int64_t now_ns, double length_s, bool loop) {
    if (start_ns_ < 0) start_ns_ = now_ns;
    const double t = static_cast<double>(now_ns - start_ns_) * 1e-9;
    return loop && length_s > 0 ? std::fmod(t, length_s) : t;
  }

 private:
  std::int64_t start_ns_ = -1;
};

}  // namespace wysiwyf::io
