#include "calibration/intrinsics_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>

namespace wysiwyf::vision::calibration {

namespace {

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

constexpr int kGrid = 4;

std::string cell_name(int cx, int cy) {
  static const char* rows[kGrid] = {"top", "upper middle", "lower middle", "bottom"};
  static const char* cols[kGrid] = {"left", "centre left", "centre right", "right"};
  return std::string(rows[cy]) + " " + cols[cx];
}

}  // namespace

IntrinsicsFit fit_intrinsics(const std::vector<BoardDetection>& views, const CharucoTarget& target,
                             const IntrinsicsLimits& limits) {
  IntrinsicsFit fit;
  if (views.empty()) {
    fit.refusal = "no views; expected at least " + std::to_string(limits.min_views) + " images of the board";
    return fit;
  }
  const cv::Size size = views.front().image_size;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<std::vector<int>> ids;
  std::vector<std::size_t> used;
  int blurred = 0;
  bool cells[kGrid][kGrid] = {};
  for (std::size_t i = 0; i < views.size(); ++i) {
    const BoardDetection& v = views[i];
    ViewReport r{v.name, static_cast<int>(v.corners.size()), v.area, v.edge_width, -1, ""};
    if (v.image_size != size)
      r.note = "image size " + std::to_string(v.image_size.width) + "x" + std::to_string(v.image_size.height) +
               " differs from the first view's";
    else if (v.markers == 0)
      r.note = "no board found";
    else if (v.edge_width > limits.max_edge_width)
      r.note = "blurred: edges " + fixed(v.edge_width, 1) + " px wide", ++blurred;
    else if (r.corners < limits.min_corners)
      r.note = "too little coverage: " + std::to_string(r.corners) + " corners";
    else if (v.area < limits.min_view_area)
      r.note = "too little coverage: the board spans " + fixed(100 * v.area, 1) + " % of the image";
    if (r.note.empty()) {
      corners.push_back(v.corners);
      ids.push_back(v.ids);
      used.push_back(i);
      for (const cv::Point2f& p : v.corners) {
        const int cx = std::clamp(static_cast<int>(p.x * kGrid / size.width), 0, kGrid - 1);
        const int cy = std::clamp(static_cast<int>(p.y * kGrid / size.height), 0, kGrid - 1);
        cells[cy][cx] = true;
      }
    }
    fit.views.push_back(r);
  }
  int covered = 0;
  for (int cy = 0; cy < kGrid; ++cy)
    for (int cx = 0; cx < kGrid; ++cx) {
      covered += cells[cy][cx];
      if (!cells[cy][cx]) fit.empty_cells.push_back(cell_name(cx, cy));
    }
  fit.coverage = static_cast<double>(covered) / (kGrid * kGrid);
  if (static_cast<int>(used.size()) < limits.min_views) {
    fit.refusal =
        std::to_string(used.size()) + " usable views of " + std::to_string(views.size()) + "; expected at least " +
        std::to_string(limits.min_views) +
        (blurred > 0 ? " (" + std::to_string(blurred) + " blurred: focus the camera, light the board, hold it still)"
                     : " (the views left out are named below)");
    return fit;
  }
  fit.camera.size = size;
  cv::Mat K, D, std_intrinsics, std_extrinsics, errors;
  std::vector<cv::Mat> rvecs, tvecs;
  try {
    fit.rms = cv::aruco::calibrateCameraCharuco(corners, ids, target.board(), size, K, D, rvecs, tvecs, std_intrinsics,
                                                std_extrinsics, errors, cv::CALIB_FIX_K3);
  } catch (const cv::Exception& e) {
    fit.refusal = std::string("OpenCV could not calibrate: ") + e.what();
    return fit;
  }
  K.convertTo(K, CV_64F), D.convertTo(D, CV_64F), errors.convertTo(errors, CV_64F);
  fit.camera.camera_matrix = cv::Matx33d(K);
  for (int i = 0; i < 5 && i < static_cast<int>(D.total()); ++i) fit.camera.distortion[i] = D.at<double>(i);
  for (int i = 0; i < 4; ++i) fit.sigma[i] = std_intrinsics.at<double>(i);
  std::string worst;
  double worst_error = 0;
  for (std::size_t k = 0; k < used.size(); ++k) {
    ViewReport& r = fit.views[used[k]];
    r.rms = errors.at<double>(static_cast<int>(k));
    if (r.rms > limits.max_view_error) r.note = "reprojection error over the limit";
    if (r.rms > worst_error) worst_error = r.rms, worst = r.name;
  }
  if (!cv::checkRange(K) || !cv::checkRange(D))
    fit.refusal = "the fit gave non-finite intrinsics; expected views of the board at many angles";
  else if (fit.coverage < limits.min_coverage) {
    std::string empty;
    for (const std::string& c : fit.empty_cells) empty += (empty.empty() ? "" : ", ") + c;
    fit.refusal = "the corners cover " + fixed(100 * fit.coverage, 0) + " % of the image (limit " +
                  fixed(100 * limits.min_coverage, 0) + " %); no corner in: " + empty +
                  "; expected views that bring the board into every part of the image";
  } else if (worst_error > limits.max_view_error)
    fit.refusal = worst + ": reprojection error " + fixed(worst_error, 3) + " px over " +
                  fixed(limits.max_view_error, 2) + " px; expected a sharp, still, flat board (retake or drop it)";
  else if (fit.rms > limits.max_rms)
    fit.refusal = "reprojection error " + fixed(fit.rms, 3) + " px RMS over " + fixed(limits.max_rms, 2) + " px";
  fit.accepted = fit.refusal.empty();
  return fit;
}

std::string describe(const IntrinsicsFit& fit, const IntrinsicsLimits& limits) {
  const cv::Matx33d& K = fit.camera.camera_matrix;
  const cv::Vec<double, 5>& D = fit.camera.distortion;
  const bool fitted = fit.rms > 0;  // refused before the fit: no estimate to show
  std::string s;
  if (fitted)
    s += "fx fy        " + fixed(K(0, 0), 2) + " " + fixed(K(1, 1), 2) + " px (sigma " + fixed(fit.sigma[0], 2) + " " +
         fixed(fit.sigma[1], 2) + ")\n";
  if (fitted)
    s += "cx cy        " + fixed(K(0, 2), 2) + " " + fixed(K(1, 2), 2) + " px (sigma " + fixed(fit.sigma[2], 2) + " " +
         fixed(fit.sigma[3], 2) + ")\n";
  if (fitted)
    s += "distortion   " + fixed(D[0], 5) + " " + fixed(D[1], 5) + " " + fixed(D[2], 6) + " " + fixed(D[3], 6) + " " +
         fixed(D[4], 5) + " (k1 k2 p1 p2 k3)\n";
  s += "coverage     " + fixed(100 * fit.coverage, 0) + " % of the image's 4 x 4 cells (limit " +
       fixed(100 * limits.min_coverage, 0) + " %)\n";
  s += "view                              corners  area %  edge px  error px\n";
  for (const ViewReport& v : fit.views) {
    char line[256];
    std::snprintf(line, sizeof line, "%-32s %7d %7.1f %8.2f %9s  %s\n", v.name.c_str(), v.corners, 100 * v.area,
                  v.edge_width, v.rms < 0 ? "-" : fixed(v.rms, 3).c_str(), v.note.c_str());
    s += line;
  }
  if (fitted)
    s += "rms          " + fixed(fit.rms, 3) + " px (limits " + fixed(limits.max_rms, 2) + " px overall, " +
         fixed(limits.max_view_error, 2) + " px per view)\n";
  s += fit.accepted ? "accepted\n" : "refused: " + fit.refusal + "\n";
  return s;
}

}  // namespace wysiwyf::vision::calibration
