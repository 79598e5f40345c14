#include "calibration/stereo_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace wysiwyf::vision::calibration {

namespace {

// The corners both detections hold, in one order: board points, left pixels, right pixels.
struct Common {
  std::vector<cv::Point3f> board;
  std::vector<cv::Point2f> left, right;
};

Common common_corners(const BoardDetection& l, const BoardDetection& r, const CharucoTarget& target) {
  std::map<int, cv::Point2f> in_right;
  for (std::size_t i = 0; i < r.ids.size() && i < r.corners.size(); ++i) in_right[r.ids[i]] = r.corners[i];
  Common c;
  const auto& corners = target.corners();
  for (std::size_t i = 0; i < l.ids.size() && i < l.corners.size(); ++i) {
    const int id = l.ids[i];
    const auto it = in_right.find(id);
    if (it == in_right.end() || id < 0 || static_cast<std::size_t>(id) >= corners.size()) continue;
    c.board.push_back(corners[static_cast<std::size_t>(id)]);
    c.left.push_back(l.corners[i]);
    c.right.push_back(it->second);
  }
  return c;
}

std::string px(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f px", v);
  return b;
}

}  // namespace

StereoFit fit_stereo(const std::vector<BoardDetection>& left, const std::vector<BoardDetection>& right,
                     const CharucoTarget& target, const CameraIntrinsics& left_camera,
                     const CameraIntrinsics& right_camera, const StereoLimits& limits) {
  StereoFit fit;
  if (left.size() != right.size()) {
    fit.refusal = std::to_string(left.size()) + " left views and " + std::to_string(right.size()) +
                  " right views; expected one pair per board position";
    return fit;
  }
  std::vector<std::vector<cv::Point3f>> board;
  std::vector<std::vector<cv::Point2f>> l_px, r_px;
  std::vector<std::size_t> used;
  fit.pair_epipolar.assign(left.size(), -1);
  for (std::size_t i = 0; i < left.size(); ++i) {
    Common c = common_corners(left[i], right[i], target);
    if (static_cast<int>(c.board.size()) < limits.min_common) continue;
    board.push_back(std::move(c.board));
    l_px.push_back(std::move(c.left));
    r_px.push_back(std::move(c.right));
    used.push_back(i);
  }
  fit.pairs_used = static_cast<int>(used.size());
  if (fit.pairs_used < limits.min_pairs) {
    fit.refusal = std::to_string(fit.pairs_used) + " usable pairs of " + std::to_string(left.size()) +
                  " (a pair needs " + std::to_string(limits.min_common) + " corners both cameras found); expected " +
                  "at least " + std::to_string(limits.min_pairs);
    return fit;
  }
  try {
    cv::Mat K1(left_camera.camera_matrix), D1(left_camera.distortion), K2(right_camera.camera_matrix),
        D2(right_camera.distortion), R, T, E, F;
    fit.rms =
        cv::stereoCalibrate(board, l_px, r_px, K1, D1, K2, D2, left_camera.size, R, T, E, F, cv::CALIB_FIX_INTRINSIC);
    Eigen::Matrix3d r;
    Eigen::Vector3d t;
    cv::cv2eigen(R, r);
    cv::cv2eigen(T, t);
    fit.right_T_left.linear() = r;
    fit.right_T_left.translation() = t;
    cv::Mat R1, R2, P1, P2, Q;
    cv::stereoRectify(K1, D1, K2, D2, left_camera.size, R, T, R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, 0);
    fit.R1 = cv::Matx33d(R1), fit.R2 = cv::Matx33d(R2), fit.P1 = cv::Matx34d(P1), fit.P2 = cv::Matx34d(P2);
    // Each corner in both rectified images: the same row, were the pair's geometry right.
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < used.size(); ++k) {
      std::vector<cv::Point2f> lr, rr;
      cv::undistortPoints(l_px[k], lr, K1, D1, R1, P1);
      cv::undistortPoints(r_px[k], rr, K2, D2, R2, P2);
      double pair_sum = 0;
      for (std::size_t j = 0; j < lr.size(); ++j) {
        const double dy = static_cast<double>(lr[j].y - rr[j].y);
        pair_sum += dy * dy;
        fit.epipolar_max = std::max(fit.epipolar_max, std::abs(dy));
      }
      fit.pair_epipolar[used[k]] = std::sqrt(pair_sum / static_cast<double>(lr.size()));
      sum += pair_sum;
      n += lr.size();
    }
    fit.epipolar_rms = std::sqrt(sum / static_cast<double>(n));
  } catch (const std::exception& e) {
    fit.refusal = std::string("OpenCV's stereo calibration failed: ") + e.what();
    return fit;
  }
  // The worst pairs, named.
  std::vector<std::size_t> order(used);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return fit.pair_epipolar[a] > fit.pair_epipolar[b]; });
  std::string worst;
  for (std::size_t k = 0; k < order.size() && k < 3; ++k)
    if (fit.pair_epipolar[order[k]] > limits.max_epipolar_pair)
      worst += (worst.empty() ? "" : ", ") + left[order[k]].name + " " + px(fit.pair_epipolar[order[k]]);
  if (fit.epipolar_rms > limits.max_epipolar_rms || !worst.empty()) {
    fit.refusal = "epipolar error " + px(fit.epipolar_rms) + " RMS over every corner (limit " +
                  px(limits.max_epipolar_rms) + ")" + (worst.empty() ? "" : "; worst pairs: " + worst) +
                  ": did a camera move between views, or are these the other cameras' intrinsics?";
    return fit;
  }
  fit.accepted = true;
  return fit;
}

}  // namespace wysiwyf::vision::calibration
