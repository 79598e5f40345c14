#include "pose_ekf.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "frames/pose_covariance.hpp"

namespace wysiwyf::vision {

namespace {

using frames::skew;

Eigen::Matrix3d exp_so3(const Eigen::Vector3d& r) {
  const double angle = r.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity() + skew(r);
  return Eigen::AngleAxisd(angle, r / angle).toRotationMatrix();
}

// Up to 8 markers per update without touching the heap.
constexpr int kMaxRows = 16;
using Rows = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxRows, 1>;
using RowsByStates = Eigen::Matrix<double, Eigen::Dynamic, PoseEkf::kStates, 0, kMaxRows, PoseEkf::kStates>;
using StatesByRows = Eigen::Matrix<double, PoseEkf::kStates, Eigen::Dynamic, 0, PoseEkf::kStates, kMaxRows>;
using RowsByRows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, kMaxRows>;

}  // namespace

void PoseEkf::reset(const Eigen::Isometry3d& eye_T_x, const Matrix6d& pose_cov, double velocity_sigma,
                    double angular_sigma) {
  eye_T_x_ = eye_T_x;
  v_.setZero(), w_.setZero();
  P_.setZero();
  P_.topLeftCorner<6, 6>() = pose_cov;
  P_.block<3, 3>(6, 6).diagonal().setConstant(velocity_sigma * velocity_sigma);
  P_.block<3, 3>(9, 9).diagonal().setConstant(angular_sigma * angular_sigma);
}

void PoseEkf::predict(double dt) {
  if (!(dt > 0)) return;
  // dv = -v / tau dt + white acceleration: over dt the velocity decays by a and moves the pose by
  // v * lever (tau = 0: a = 1, lever = dt, constant velocity).
  const double tau = noise_.velocity_time;
  const double a = tau > 0 ? std::exp(-dt / tau) : 1.0;
  const double lever = tau > 0 ? tau * (1 - a) : dt;
  const Eigen::Matrix3d dR = exp_so3(w_ * lever);
  eye_T_x_.translation() += v_ * lever;
  eye_T_x_.linear() = dR * eye_T_x_.linear();
  v_ *= a, w_ *= a;
  StateMatrix F = StateMatrix::Identity();
  F.block<3, 3>(0, 6).diagonal().setConstant(lever);
  F.block<3, 3>(3, 3) = dR;
  F.block<3, 3>(3, 9).diagonal().setConstant(lever);
  F.block<3, 3>(6, 6).diagonal().setConstant(a);
  F.block<3, 3>(9, 9).diagonal().setConstant(a);
  // The white acceleration integrated over dt, per axis: [pp pv; pv vv] times its spectral
  // density (constant velocity: [dt^3/3 dt^2/2; dt^2/2 dt]; decaying: the same integrals weighted
  // by the decay).
  double pp = dt * dt * dt / 3, pv = dt * dt / 2, vv = dt;
  if (tau > 0) {
    vv = tau / 2 * (1 - a * a);
    pv = tau * tau / 2 * (1 - a) * (1 - a);
    pp = tau * tau * (dt - 2 * tau * (1 - a) + tau / 2 * (1 - a * a));
  }
  StateMatrix Q = StateMatrix::Zero();
  const double qa = noise_.accel * noise_.accel, qw = noise_.angular_accel * noise_.angular_accel;
  for (int i = 0; i < 3; ++i) {
    Q(i, i) = pp * qa, Q(i, 6 + i) = Q(6 + i, i) = pv * qa, Q(6 + i, 6 + i) = vv * qa;
    Q(3 + i, 3 + i) = pp * qw, Q(3 + i, 9 + i) = Q(9 + i, 3 + i) = pv * qw, Q(9 + i, 9 + i) = vv * qw;
  }
  P_ = F * P_ * F.transpose() + Q;
}

bool PoseEkf::predict_pixel(const Eigen::Vector3d& x_p, const Eigen::Vector3d& eye_offset, const CameraModel& camera,
                            Prediction& out) const {
  const Eigen::Vector3d rotated = eye_T_x_.linear() * x_p;
  const Eigen::Vector3d p = rotated + eye_T_x_.translation() + eye_offset;
  if (p.z() < 1e-3) return false;
  out.depth = p.z();
  out.pixel = camera.project(p);
  const double iz = 1.0 / p.z();
  Eigen::Matrix<double, 2, 3> J;
  J << camera.fx() * iz, 0, -camera.fx() * p.x() * iz * iz, 0, camera.fy() * iz, -camera.fy() * p.y() * iz * iz;
  out.H.setZero();
  out.H.leftCols<3>() = J;
  out.H.block<2, 3>(0, 3) = -J * skew(rotated);
  out.S = out.H * P_ * out.H.transpose();
  out.S.diagonal().array() += noise_.pixel * noise_.pixel;
  return true;
}

double PoseEkf::joint_mahalanobis2(const Prediction* const predictions[], const Eigen::Vector2d pixels[],
                                   int count) const {
  const int m = std::min(count, kMaxRows / 2);
  if (m <= 0) return 0;
  RowsByStates H(2 * m, kStates);
  Rows y(2 * m);
  for (int i = 0; i < m; ++i) {
    H.middleRows<2>(2 * i) = predictions[i]->H;
    y.segment<2>(2 * i) = pixels[i] - predictions[i]->pixel;
  }
  RowsByRows S = H * P_ * H.transpose();
  S.diagonal().array() += noise_.pixel * noise_.pixel;
  return y.dot(S.ldlt().solve(y));
}

void PoseEkf::update(const std::vector<Prediction>& predictions, const std::vector<Eigen::Vector2d>& pixels) {
  assert(predictions.size() == pixels.size());
  const int m = static_cast<int>(std::min<std::size_t>(predictions.size(), kMaxRows / 2));
  if (m == 0) return;
  RowsByStates H(2 * m, kStates);
  Rows y(2 * m);
  for (int i = 0; i < m; ++i) {
    H.middleRows<2>(2 * i) = predictions[static_cast<std::size_t>(i)].H;
    y.segment<2>(2 * i) = pixels[static_cast<std::size_t>(i)] - predictions[static_cast<std::size_t>(i)].pixel;
  }
  const double r = noise_.pixel * noise_.pixel;
  const StatesByRows PHt = P_ * H.transpose();
  RowsByRows S = H * PHt;
  S.diagonal().array() += r;
  const StatesByRows K = S.ldlt().solve(PHt.transpose()).transpose();
  const Eigen::Matrix<double, kStates, 1> dx = K * y;
  // Joseph form: stays symmetric and positive.
  const StateMatrix IKH = StateMatrix::Identity() - K * H;
  P_ = IKH * P_ * IKH.transpose() + r * K * K.transpose();
  eye_T_x_.translation() += dx.segment<3>(0);
  eye_T_x_.linear() = exp_so3(dx.segment<3>(3)) * eye_T_x_.linear();
  v_ += dx.segment<3>(6);
  w_ += dx.segment<3>(9);
}

}  // namespace wysiwyf::vision
