#pragma once
// A camera's intrinsics as OpenCV calibrates them: image size, the pinhole matrix K and the
// plumb-bob distortion k1 k2 p1 p2 k3 (what config/calibration/*.yaml hold).
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

namespace wysiwyf::vision::calibration {

struct CameraIntrinsics {
  cv::Size size{640, 480};
  cv::Matx33d camera_matrix = cv::Matx33d::eye();              // fx 0 cx; 0 fy cy; 0 0 1, px
  cv::Vec<double, 5> distortion = cv::Vec<double, 5>::all(0);  // k1 k2 p1 p2 k3
};

// Where points of a frame posed at eye_T_frame land in the image (px, OpenCV's projection).
inline std::vector<cv::Point2f> project(const CameraIntrinsics& cam, const Eigen::Isometry3d& eye_T_frame,
                                        const std::vector<cv::Point3f>& points) {
  const Eigen::AngleAxisd aa(eye_T_frame.linear());
  const Eigen::Vector3d r = aa.angle() * aa.axis(), t = eye_T_frame.translation();
  std::vector<cv::Point2f> out;
  if (points.empty()) return out;
  cv::projectPoints(points, cv::Vec3d(r.x(), r.y(), r.z()), cv::Vec3d(t.x(), t.y(), t.z()), cv::Mat(cam.camera_matrix),
                    cv::Mat(cam.distortion), out);
  return out;
}

}  // namespace wysiwyf::vision::calibration
