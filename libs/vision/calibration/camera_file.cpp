#include "calibration/camera_file.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <opencv2/core/persistence.hpp>

namespace wysiwyf::vision::calibration {

namespace {

cv::Mat matrix(const cv::FileStorage& fs, const char* key, const std::string& where, bool required) {
  const cv::FileNode n = fs[key];
  if (n.empty()) {
    if (required) throw std::runtime_error(where + ": " + key + ": missing; expected an !!opencv-matrix");
    return {};
  }
  cv::Mat m;
  try {
    n >> m;
  } catch (const cv::Exception&) {
    throw std::runtime_error(where + ": " + key + ": expected an !!opencv-matrix");
  }
  if (m.empty() || m.channels() != 1) throw std::runtime_error(where + ": " + key + ": expected an !!opencv-matrix");
  m.convertTo(m, CV_64F);
  if (!cv::checkRange(m)) throw std::runtime_error(where + ": " + key + ": expected finite numbers");
  return m;
}

int size_of(const cv::FileStorage& fs, const char* key, const std::string& where) {
  const cv::FileNode n = fs[key];
  if (!n.isInt() || static_cast<int>(n) < 1 || static_cast<int>(n) > 16384)
    throw std::runtime_error(where + ": " + key + ": expected a whole number of pixels, 1 to 16384");
  return static_cast<int>(n);
}

}  // namespace

CameraFile load_camera_file(const std::string& path) {
  cv::FileStorage fs;
  const std::string where = "camera calibration '" + path + "'";
  try {
    if (!fs.open(path, cv::FileStorage::READ)) throw std::runtime_error(where + ": cannot read it");
  } catch (const cv::Exception& e) {
    throw std::runtime_error(where + ": not an OpenCV YAML/XML/JSON file: " + e.msg);
  }
  CameraFile f;
  f.intrinsics.size.width = size_of(fs, "image_width", where);
  f.intrinsics.size.height = size_of(fs, "image_height", where);
  const cv::Mat K = matrix(fs, "camera_matrix", where, true);
  if (K.rows != 3 || K.cols != 3) throw std::runtime_error(where + ": camera_matrix: expected 3x3");
  const cv::Matx33d k(K);
  if (!(k(0, 0) > 0 && k(1, 1) > 0) || k(2, 0) != 0 || k(2, 1) != 0 || k(2, 2) != 1 || k(1, 0) != 0)
    throw std::runtime_error(where + ": camera_matrix: expected [fx s cx; 0 fy cy; 0 0 1] with fx, fy > 0");
  if (k(0, 2) < 0 || k(0, 2) > f.intrinsics.size.width || k(1, 2) < 0 || k(1, 2) > f.intrinsics.size.height)
    throw std::runtime_error(where + ": camera_matrix: expected the principal point inside the image");
  f.intrinsics.camera_matrix = k;
  const cv::Mat D = matrix(fs, "distortion_coefficients", where, false);
  const std::size_t n = D.total();
  if (n != 0 && n != 4 && n != 5 && n != 8 && n != 12 && n != 14)
    throw std::runtime_error(where + ": distortion_coefficients: expected 4, 5, 8, 12 or 14 values");
  for (std::size_t i = 5; i < n; ++i)
    if (D.at<double>(static_cast<int>(i)) != 0)
      throw std::runtime_error(where + ": distortion_coefficients: only k1 k2 p1 p2 k3 are used; expected the rest 0");
  for (int i = 0; i < 5 && i < static_cast<int>(n); ++i) f.intrinsics.distortion[i] = D.at<double>(i);
  const cv::Mat T = matrix(fs, "base_T_eye", where, false);
  if (!T.empty()) {
    if (T.rows != 4 || T.cols != 4) throw std::runtime_error(where + ": base_T_eye: expected 4x4");
    Eigen::Matrix4d m;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) m(r, c) = T.at<double>(r, c);
    const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
    if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-6 || R.determinant() < 0 ||
        (m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9)
      throw std::runtime_error(where + ": base_T_eye: expected a rigid transform (a rotation, last row 0 0 0 1)");
    Eigen::Isometry3d iso = Eigen::Isometry3d::Identity();
    iso.linear() = R, iso.translation() = m.topRightCorner<3, 1>();
    f.base_T_eye = iso;
  }
  const cv::Mat R = matrix(fs, "rectification_matrix", where, false), P = matrix(fs, "projection_matrix", where, false);
  if (R.empty() != P.empty())
    throw std::runtime_error(where + ": expected rectification_matrix and projection_matrix together, or neither");
  if (!R.empty()) {
    const cv::Matx33d r = R.rows == 3 && R.cols == 3 ? cv::Matx33d(R) : cv::Matx33d::zeros();
    if (cv::norm(cv::Mat(r.t() * r - cv::Matx33d::eye())) > 1e-6 || cv::determinant(r) < 0)
      throw std::runtime_error(where + ": rectification_matrix: expected a 3x3 rotation");
    if (P.rows != 3 || P.cols != 4 || !(P.at<double>(0, 0) > 0) || !(P.at<double>(1, 1) > 0))
      throw std::runtime_error(where + ": projection_matrix: expected 3x4 [f 0 cx Tx; 0 f cy 0; 0 0 1 0], f > 0");
    f.rectification = r;
    f.projection = cv::Matx34d(P);
  }
  return f;
}

void save_camera_file(const std::string& path, const CameraFile& f, const std::string& comment) {
  cv::FileStorage fs;
  try {
    if (!fs.open(path, cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML))
      throw std::runtime_error("cannot write '" + path + "'");
  } catch (const cv::Exception& e) {
    throw std::runtime_error("cannot write '" + path + "': " + e.msg);
  }
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) fs.writeComment(line);
  fs << "image_width" << f.intrinsics.size.width << "image_height" << f.intrinsics.size.height;
  fs << "camera_matrix" << cv::Mat(f.intrinsics.camera_matrix);
  fs << "distortion_coefficients" << cv::Mat(f.intrinsics.distortion).reshape(1, 1);
  if (f.base_T_eye) {
    cv::Mat T(4, 4, CV_64F);
    const Eigen::Matrix4d m = f.base_T_eye->matrix();
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) T.at<double>(r, c) = m(r, c);
    fs << "base_T_eye" << T;
  }
  if (f.rectification && f.projection)
    fs << "rectification_matrix" << cv::Mat(*f.rectification) << "projection_matrix" << cv::Mat(*f.projection);
  fs.release();
}

}  // namespace wysiwyf::vision::calibration
