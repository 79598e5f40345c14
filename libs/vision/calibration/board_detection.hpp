#pragma once
// The ChArUco corners in one image, and how sharp the board is there: the markers found
// (cv::aruco::detectMarkers), the chessboard corners between them interpolated and refined to
// sub-pixel (interpolateCornersCharuco), and the board's edge width: the board's contrast over its
// steepest grey gradient, about 2.5 times the blur's sigma for a blurred edge, 1.5 px for a
// focused one. A blurred board still gives corners, biased and noisy; the width tells.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calibration/charuco_target.hpp"

namespace wysiwyf::vision::calibration {

struct BoardDetection {
  std::string name;  // the view's name in reports (its file)
  cv::Size image_size;
  std::vector<cv::Point2f> corners;  // px
  std::vector<int> ids;              // charuco ids (CharucoTarget::corners())
  int markers = 0;                   // markers found
  double edge_width = 0;             // px, over the markers' bounding box (0: no marker found)
  double area = 0;                   // the corners' convex hull over the image's area
};

// Finds the board in an 8-bit grey or BGR image; never throws for an image without a board (no
// corners come back). Throws std::invalid_argument for an empty image or another pixel type.
BoardDetection detect_board(const cv::Mat& image, const CharucoTarget& target, const std::string& name);

}  // namespace wysiwyf::vision::calibration
