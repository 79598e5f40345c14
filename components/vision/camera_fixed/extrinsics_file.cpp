#include "extrinsics_file.hpp"

#include <cmath>
#include <stdexcept>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/persistence.hpp>

namespace wysiwyf::vision {

namespace {

Eigen::Isometry3d from_4x4(const cv::Mat& m, const std::string& what) {
  if (m.rows != 4 || m.cols != 4) throw std::invalid_argument(what + ": expected a 4x4 matrix");
  cv::Mat d;
  m.convertTo(d, CV_64F);
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) M(r, c) = d.at<double>(r, c);
  if (!M.allFinite() || (M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9)
    throw std::invalid_argument(what + ": expected a finite rigid transform with a last row 0 0 0 1");
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-6 || R.determinant() < 0)
    throw std::invalid_argument(what + ": its upper-left 3x3 is not a rotation (orthonormal, determinant +1)");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R, T.translation() = M.topRightCorner<3, 1>();
  return T;
}

}  // namespace

Eigen::Isometry3d load_eye_T_base(const std::string& path) {
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    throw std::invalid_argument("extrinsics '" + path + "': not an OpenCV YAML/XML/JSON file: " + e.msg);
  }
  if (!fs.isOpened()) throw std::invalid_argument("extrinsics: cannot read '" + path + "'");
  const std::string where = "extrinsics '" + path + "'";
  if (!fs["rvec"].empty() || !fs["tvec"].empty()) {
    cv::Mat rvec, tvec;
    fs["rvec"] >> rvec;
    fs["tvec"] >> tvec;
    if (rvec.total() != 3 || tvec.total() != 3)
      throw std::invalid_argument(where +
                                  ": expected rvec and tvec of 3 values each (solvePnP's X_eye = R X_base + t)");
    rvec.convertTo(rvec, CV_64F), tvec.convertTo(tvec, CV_64F);
    cv::Mat R;
    cv::Rodrigues(rvec.reshape(1, 3), R);
    cv::Mat M = cv::Mat::eye(4, 4, CV_64F);
    R.copyTo(M(cv::Rect(0, 0, 3, 3)));
    tvec.reshape(1, 3).copyTo(M(cv::Rect(3, 0, 1, 3)));
    return from_4x4(M, where + " rvec/tvec");
  }
  if (!fs["eye_T_base"].empty()) {
    cv::Mat M;
    fs["eye_T_base"] >> M;
    return from_4x4(M, where + " eye_T_base");
  }
  if (!fs["base_T_eye"].empty()) {
    cv::Mat M;
    fs["base_T_eye"] >> M;
    return from_4x4(M, where + " base_T_eye").inverse();
  }
  throw std::invalid_argument(where + ": found none of rvec/tvec, eye_T_base, base_T_eye; expected one of them");
}

}  // namespace wysiwyf::vision
