#include "run_report.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace wysiwyf::display {

namespace {

std::ofstream open(const std::string& path, const char* header) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("run report: cannot write " + path);
  f << header << "\n";
  return f;
}

std::string cell(const std::optional<double>& v, const char* format = "%.4f") {
  if (!v) return "NaN";
  char s[32];
  std::snprintf(s, sizeof s, format, *v);
  return s;
}

}  // namespace

RunReport::RunReport(const std::string& dir) : dir_(dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("run report: cannot create " + dir + ": " + ec.message());
  series_ = open(dir + "/timeseries.csv",
                 "t_s,force_n,plate_x_m,plate_y_m,plate_z_m,cube_x_m,cube_y_m,cube_z_m,mode,attached,haptic_error_mm,"
                 "visual_error_mm");
  latency_ = open(dir + "/latency.csv", "t_s,camera_to_composite_ms");
}

void RunReport::row(const TimeSeriesRow& r) {
  auto xyz = [](const std::optional<Eigen::Vector3d>& p) {
    if (!p) return std::string("NaN,NaN,NaN");
    char s[96];
    std::snprintf(s, sizeof s, "%.6f,%.6f,%.6f", p->x(), p->y(), p->z());
    return std::string(s);
  };
  char t[32];
  std::snprintf(t, sizeof t, "%.3f", r.t_s);
  series_ << t << ',' << cell(r.force_n, "%.3f") << ',' << xyz(r.plate) << ',' << xyz(r.cube) << ','
          << (r.mode >= 0 ? std::to_string(r.mode) : "NaN") << ',' << (r.attached ? 1 : 0) << ',' << cell(r.haptic_mm)
          << ',' << cell(r.visual_mm) << '\n';
}

void RunReport::latency(double t_s, double ms) {
  char s[64];
  std::snprintf(s, sizeof s, "%.3f,%.3f\n", t_s, ms);
  latency_ << s;
}

}  // namespace wysiwyf::display
