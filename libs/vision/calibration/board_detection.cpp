#include "calibration/board_detection.hpp"

#include <algorithm>
#include <stdexcept>

#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>

namespace wysiwyf::vision::calibration {

namespace {

// The value below which `share` of the values lie.
float quantile(std::vector<float> v, double share) {
  if (v.empty()) return 0;
  const auto k = static_cast<std::ptrdiff_t>(share * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[static_cast<std::size_t>(k)];
}

double edge_width(const cv::Mat& grey, const std::vector<cv::Point2f>& corners) {
  const cv::Rect box = cv::boundingRect(corners) & cv::Rect(0, 0, grey.cols, grey.rows);
  if (box.width < 8 || box.height < 8) return 0;
  cv::Mat roi, gx, gy, mag;
  grey(box).convertTo(roi, CV_32F);
  cv::Sobel(roi, gx, CV_32F, 1, 0, 3, 1.0 / 8);
  cv::Sobel(roi, gy, CV_32F, 0, 1, 3, 1.0 / 8);
  cv::magnitude(gx, gy, mag);
  std::vector<float> g(mag.begin<float>(), mag.end<float>()), v(roi.begin<float>(), roi.end<float>());
  const double contrast = quantile(v, 0.98) - quantile(v, 0.02);
  const double steepest = quantile(g, 0.995);
  return steepest > 0 ? contrast / steepest : 0;
}

}  // namespace

BoardDetection detect_board(const cv::Mat& image, const CharucoTarget& target, const std::string& name) {
  if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
    throw std::invalid_argument(name + ": expected an 8-bit grey or colour image");
  cv::Mat grey;
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else
    grey = image;
  BoardDetection d;
  d.name = name;
  d.image_size = grey.size();
  std::vector<std::vector<cv::Point2f>> marker_corners;
  std::vector<int> marker_ids;
  cv::aruco::detectMarkers(grey, target.board()->dictionary, marker_corners, marker_ids);
  d.markers = static_cast<int>(marker_ids.size());
  if (marker_ids.empty()) return d;
  std::vector<cv::Point2f> found;  // every marker's corners: where the board is, even without chessboard corners
  for (const auto& m : marker_corners) found.insert(found.end(), m.begin(), m.end());
  d.edge_width = edge_width(grey, found);
  cv::aruco::interpolateCornersCharuco(marker_corners, marker_ids, grey, target.board(), d.corners, d.ids);
  // OpenCV 4.6's interpolation hands back its sub-pixel corners shifted by +0.5 px in x and y
  // (opencv/opencv#25539, fixed upstream in 2026): refine them again from there, which converges to
  // the corner itself whichever version ran. Each corner's window stops short of the nearest
  // marker corner (1/8 of a square away on a usual board), whose edges would pull it.
  for (cv::Point2f& c : d.corners) {
    double clear = 1e9;  // Chebyshev distance to the nearest marker corner, px
    for (const cv::Point2f& m : found)
      clear = std::min(clear, std::max<double>(std::abs(m.x - c.x), std::abs(m.y - c.y)));
    const int half = std::clamp(static_cast<int>(clear) - 2, 2, 10);
    std::vector<cv::Point2f> one{c};
    cv::cornerSubPix(grey, one, cv::Size(half, half), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-3));
    c = one[0];
  }
  if (d.corners.size() >= 3) {
    std::vector<cv::Point2f> hull;
    cv::convexHull(d.corners, hull);
    d.area = cv::contourArea(hull) / (static_cast<double>(grey.cols) * grey.rows);
  }
  return d;
}

}  // namespace wysiwyf::vision::calibration
