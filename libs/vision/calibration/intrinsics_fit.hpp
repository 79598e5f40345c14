#pragma once
// A camera's intrinsics from views of a ChArUco board (cv::aruco::calibrateCameraCharuco), with
// what makes a set of views good enough said and checked: each view's corners, sharpness and
// reprojection error; the image's coverage by every view's corners together (a 4 x 4 grid: a
// distortion is only measured where corners were); the whole fit's RMS. Views that are blurred or
// cover too little are named and left out; a set that is still too small, covers too little, or
// leaves a view's error over the limit is refused with the reason.
#include <string>
#include <vector>

#include "calibration/board_detection.hpp"
#include "calibration/camera_model.hpp"
#include "calibration/charuco_target.hpp"

namespace wysiwyf::vision::calibration {

struct IntrinsicsLimits {
  int min_views = 10;           // usable views, fewer is refused
  int min_corners = 12;         // a view with fewer is left out
  double min_view_area = 0.03;  // of the image, a view's corners' hull; smaller is left out
  double max_edge_width = 3.5;  // px; blurrier is left out (focused: ~1.5; sigma 1.4 px blur: 3.5)
  double min_coverage = 0.8;    // of the 4 x 4 image cells holding a corner
  double max_view_error = 0.5;  // px RMS per view
  double max_rms = 0.3;         // px RMS over every corner
};

struct ViewReport {
  std::string name;
  int corners = 0;
  double area = 0, edge_width = 0;
  double rms = -1;   // px; -1 when left out
  std::string note;  // why left out, or over a limit; empty when fine
};

struct IntrinsicsFit {
  bool accepted = false;
  std::string refusal;
  CameraIntrinsics camera;
  double rms = 0;                        // px over every used corner
  double coverage = 0;                   // share of the 4 x 4 cells with a corner
  std::vector<std::string> empty_cells;  // "top left", ... cells no corner reached
  std::vector<ViewReport> views;         // one per input view, in order
  cv::Vec4d sigma = cv::Vec4d::all(0);   // standard deviations of fx fy cx cy, px
};

// Calibrates from the detections (one per image, all of image_size). Fixes k3 (five coefficients,
// k3 = 0): a webcam's lens needs no more and it keeps the fit stable. Never throws.
IntrinsicsFit fit_intrinsics(const std::vector<BoardDetection>& views, const CharucoTarget& target,
                             const IntrinsicsLimits& limits = {});

// The report: the estimate, coverage, every view's corners, sharpness, error and note.
std::string describe(const IntrinsicsFit& fit, const IntrinsicsLimits& limits);

}  // namespace wysiwyf::vision::calibration
