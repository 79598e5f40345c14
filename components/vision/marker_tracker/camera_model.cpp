#include "camera_model.hpp"

#include <opencv2/calib3d.hpp>

#include <cmath>
#include <stdexcept>

namespace wysiwyf::vision {

CameraModel::CameraModel(double fx, double fy, double cx, double cy, std::vector<double> distortion)
    : fx_(fx), fy_(fy), cx_(cx), cy_(cy) {
  if (!(fx > 0 && fy > 0 && std::isfinite(fx) && std::isfinite(fy) && std::isfinite(cx) && std::isfinite(cy)))
    throw std::invalid_argument("camera intrinsics: expected finite fx, fy > 0, cx, cy; got fx " + std::to_string(fx) +
                                ", fy " + std::to_string(fy) + ", cx " + std::to_string(cx) + ", cy " +
                                std::to_string(cy));
  const std::size_t n = distortion.size();
  if (n != 0 && n != 4 && n != 5 && n != 8 && n != 12 && n != 14)
    throw std::invalid_argument("camera distortion: expected 0, 4, 5, 8, 12 or 14 coefficients, got " +
                                std::to_string(n));
  for (double d : distortion) {
    if (!std::isfinite(d)) throw std::invalid_argument("camera distortion: a coefficient is not finite");
    if (d != 0) distorted_ = true;
  }
  if (distorted_) distortion_ = cv::Mat(distortion, true).reshape(1, 1);
}

Eigen::Vector2d CameraModel::distort(const Eigen::Vector2d& ideal) const {
  if (!distorted_) return ideal;
  const std::vector<cv::Point3d> ray{{(ideal.x() - cx_) / fx_, (ideal.y() - cy_) / fy_, 1.0}};
  std::vector<cv::Point2d> pixel;
  cv::projectPoints(ray, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), matrix(), distortion_, pixel);
  return {pixel[0].x, pixel[0].y};
}

Eigen::Vector2d CameraModel::undistort(const Eigen::Vector2d& measured) const {
  if (!distorted_) return measured;
  const std::vector<cv::Point2d> in{{measured.x(), measured.y()}};
  std::vector<cv::Point2d> out;
  cv::undistortPoints(in, out, matrix(), distortion_, cv::noArray(), matrix());
  return {out[0].x, out[0].y};
}

}  // namespace wysiwyf::vision
