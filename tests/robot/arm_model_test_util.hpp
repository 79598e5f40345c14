#pragma once
// Shared by the ArmModel tests: the robot files, random joint vectors within limits, pose errors
// and the textbook DH products the URDFs are checked against (typed in here, not read from them).
#include <cmath>
#include <random>
#include <string>

#include <Eigen/Geometry>

#include "arm_model/arm_model.hpp"

namespace wysiwyf::robot::test {

inline const std::string kPumaUrdf = std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf";
inline const std::string kUr5eUrdf = std::string(WYSIWYF_CONFIG_DIR) + "/robots/ur5e.urdf";
inline const std::string kFr3Urdf = std::string(WYSIWYF_CONFIG_DIR) + "/robots/fr3.urdf";
constexpr double kPi = 3.14159265358979323846;

// A_i = Rz(theta) Tz(d) Tx(a) Rx(alpha) (standard DH).
inline Eigen::Isometry3d standard_dh(double theta, double d, double a, double alpha) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()));
  T.translate(Eigen::Vector3d(0.0, 0.0, d));
  T.translate(Eigen::Vector3d(a, 0.0, 0.0));
  T.rotate(Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()));
  return T;
}

// T_i = Rx(alpha) Tx(a) Tz(d) Rz(theta) (modified DH, Craig).
inline Eigen::Isometry3d modified_dh(double theta, double d, double a, double alpha) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()));
  T.translate(Eigen::Vector3d(a, 0.0, 0.0));
  T.translate(Eigen::Vector3d(0.0, 0.0, d));
  T.rotate(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()));
  return T;
}

inline Eigen::Isometry3d translation(double x, double y, double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

inline double position_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}

inline double rotation_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(Eigen::Matrix3d(a.linear().transpose() * b.linear())).angle();
}

// Largest joint difference with revolute angles compared modulo 2 pi.
inline double angle_distance(const JointVector& a, const JointVector& b) {
  double worst = 0.0;
  for (Eigen::Index j = 0; j < a.size(); ++j) worst = std::max(worst, std::abs(std::remainder(a[j] - b[j], 2.0 * kPi)));
  return worst;
}

// Uniform within the position limits, kept `margin` away from them.
inline JointVector random_q(const ArmModel& model, std::mt19937_64& rng, double margin = 0.0) {
  JointVector q(model.dof());
  for (int j = 0; j < model.dof(); ++j)
    q[j] =
        std::uniform_real_distribution<double>(model.limits().lower[j] + margin, model.limits().upper[j] - margin)(rng);
  return q;
}

inline JointVector random_vector(int n, double scale, std::mt19937_64& rng) {
  JointVector v(n);
  for (int j = 0; j < n; ++j) v[j] = std::uniform_real_distribution<double>(-scale, scale)(rng);
  return v;
}

}  // namespace wysiwyf::robot::test
