#include "calibration/charuco_target.hpp"

#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace wysiwyf::vision::calibration {

std::string problem(const CharucoSpec& s) {
  if (s.squares_x < 3 || s.squares_x > 30 || s.squares_y < 3 || s.squares_y > 30)
    return "board: " + std::to_string(s.squares_x) + " x " + std::to_string(s.squares_y) +
           " squares; expected 3 to 30 each way";
  if (!(s.square >= 0.005 && s.square <= 1.0)) return "board: square side; expected 0.005 to 1 m";
  if (!(s.marker >= 0.3 * s.square && s.marker <= 0.9 * s.square))
    return "board: marker side; expected 30 to 90 % of the square's side";
  if (s.dictionary < cv::aruco::DICT_4X4_50 || s.dictionary > cv::aruco::DICT_APRILTAG_36h11)
    return "board: dictionary " + std::to_string(s.dictionary) + "; expected one of cv::aruco's predefined";
  const int markers = s.squares_x * s.squares_y / 2;
  const int available = cv::aruco::getPredefinedDictionary(s.dictionary)->bytesList.rows;
  if (markers > available)
    return "board: " + std::to_string(markers) + " markers; the dictionary has " + std::to_string(available);
  return "";
}

CharucoTarget::CharucoTarget(const CharucoSpec& spec) : spec_(spec) {
  if (const std::string p = problem(spec); !p.empty()) throw std::invalid_argument(p);
  board_ = cv::aruco::CharucoBoard::create(spec.squares_x, spec.squares_y, static_cast<float>(spec.square),
                                           static_cast<float>(spec.marker),
                                           cv::aruco::getPredefinedDictionary(spec.dictionary));
  // A marker's corners run clockwise in the image the dictionary draws (y down); if they turn the
  // other way in the board frame, its y runs up.
  const std::vector<cv::Point3f>& m = board_->objPoints.front();
  const cv::Point3f a = m[1] - m[0], b = m[3] - m[0];
  flipped_ = a.x * b.y - a.y * b.x < 0;
}

cv::Mat CharucoTarget::texture(int pps) const {
  const double k = pps / spec_.square;  // texture pixels per metre
  const int cols = spec_.squares_x * pps, rows = spec_.squares_y * pps;
  cv::Mat tex(rows, cols, CV_8UC1, cv::Scalar(0));
  const auto to_tex = [&](const cv::Point3f& p) {
    return cv::Point2f(static_cast<float>(p.x * k), static_cast<float>(flipped_ ? rows - p.y * k : p.y * k));
  };
  // Every marker sits in a white square; the others are black.
  const int side = static_cast<int>(std::lround(spec_.marker * k));
  for (std::size_t i = 0; i < board_->objPoints.size(); ++i) {
    const std::vector<cv::Point3f>& c = board_->objPoints[i];
    const cv::Point2f centre = (to_tex(c[0]) + to_tex(c[2])) * 0.5f;
    const int sx = static_cast<int>(centre.x / pps), sy = static_cast<int>(centre.y / pps);
    tex(cv::Rect(sx * pps, sy * pps, pps, pps)).setTo(255);
    cv::Mat marker;
    board_->dictionary->drawMarker(board_->ids[i], side, marker, 1);
    const cv::Point2f from[3] = {{0, 0}, {static_cast<float>(side), 0}, {0, static_cast<float>(side)}};
    const cv::Point2f to[3] = {to_tex(c[0]), to_tex(c[1]), to_tex(c[3])};
    cv::Mat warped;
    cv::warpAffine(marker, warped, cv::getAffineTransform(from, to), tex.size(), cv::INTER_NEAREST, cv::BORDER_CONSTANT,
                   cv::Scalar(0));
    cv::Mat mask(side, side, CV_8UC1, cv::Scalar(255)), where;
    cv::warpAffine(mask, where, cv::getAffineTransform(from, to), tex.size(), cv::INTER_NEAREST, cv::BORDER_CONSTANT,
                   cv::Scalar(0));
    warped.copyTo(tex, where);
  }
  return tex;
}

}  // namespace wysiwyf::vision::calibration
