#pragma once
// The run report's time series, written as the run goes (bounded memory): timeseries.csv, one
// row per metrics tick with the latest of each signal (NaN: none yet, or not attached; so a
// plotted line breaks there), and latency.csv, one row per composite. The plots and index.html come from
// scripts/run-report, which reads these and summary.json.
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>

#include <Eigen/Core>

namespace wysiwyf::display {

struct TimeSeriesRow {
  double t_s = 0;
  std::optional<double> force_n;               // the user's force (wrist reading less the tool)
  std::optional<Eigen::Vector3d> plate, cube;  // base frame, m
  int mode = -1;                               // DisplayModeKind; -1 none heard
  bool attached = false;
  std::optional<double> haptic_mm, visual_mm;  // the latest registration errors
};

class RunReport {
 public:
  // Creates `dir` and the CSV files with their headers; throws naming the file it cannot write.
  explicit RunReport(const std::string& dir);
  const std::string& dir() const { return dir_; }
  void row(const TimeSeriesRow& r);
  void latency(double t_s, double ms);

 private:
  std::string dir_;
  std::ofstream series_, latency_;
};

}  // namespace wysiwyf::display
