#include "calibration/pose_refinement.hpp"

#include <cmath>

namespace wysiwyf::vision::calibration {

namespace {

using Vector12d = Eigen::Matrix<double, 12, 1>;

Eigen::Isometry3d perturbed(const Eigen::Isometry3d& T, const Eigen::Vector3d& rotation,
                            const Eigen::Vector3d& translation) {
  Eigen::Isometry3d d = Eigen::Isometry3d::Identity();
  const double angle = rotation.norm();
  if (angle > 0) d.linear() = Eigen::AngleAxisd(angle, rotation / angle).toRotationMatrix();
  d.translation() = translation;
  return T * d;
}

void apply(const Vector12d& x, Eigen::Isometry3d& base_T_eye, Eigen::Isometry3d& flange_T_board) {
  base_T_eye = perturbed(base_T_eye, x.segment<3>(0), x.segment<3>(3));
  flange_T_board = perturbed(flange_T_board, x.segment<3>(6), x.segment<3>(9));
}

// Stacked residuals (projected - seen, px) of every corner of every view.
Eigen::VectorXd residuals(const std::vector<PoseObservations>& views, const CameraIntrinsics& camera,
                          const Eigen::Isometry3d& base_T_eye, const Eigen::Isometry3d& flange_T_board) {
  std::size_t n = 0;
  for (const auto& v : views) n += v.seen.size();
  Eigen::VectorXd r(static_cast<Eigen::Index>(2 * n));
  Eigen::Index k = 0;
  const Eigen::Isometry3d eye_T_base = base_T_eye.inverse();
  for (const auto& v : views) {
    const std::vector<cv::Point2f> p = project(camera, eye_T_base * v.base_T_flange * flange_T_board, v.board_points);
    for (std::size_t i = 0; i < p.size(); ++i) {
      r[k++] = p[i].x - v.seen[i].x;
      r[k++] = p[i].y - v.seen[i].y;
    }
  }
  return r;
}

}  // namespace

std::vector<double> reprojection_errors(const std::vector<PoseObservations>& views, const CameraIntrinsics& camera,
                                        const Eigen::Isometry3d& base_T_eye, const Eigen::Isometry3d& flange_T_board) {
  const Eigen::VectorXd r = residuals(views, camera, base_T_eye, flange_T_board);
  std::vector<double> out;
  Eigen::Index k = 0;
  for (const auto& v : views) {
    const auto m = static_cast<Eigen::Index>(2 * v.seen.size());
    out.push_back(m > 0 ? std::sqrt(r.segment(k, m).squaredNorm() / static_cast<double>(v.seen.size())) : 0.0);
    k += m;
  }
  return out;
}

std::vector<double> refine_robot_world(const std::vector<PoseObservations>& views, const CameraIntrinsics& camera,
                                       Eigen::Isometry3d& base_T_eye, Eigen::Isometry3d& flange_T_board) {
  constexpr double kStep = 1e-6;  // rad and m: central differences
  double lambda = 1e-3;
  Eigen::VectorXd r = residuals(views, camera, base_T_eye, flange_T_board);
  for (int iteration = 0; iteration < 50; ++iteration) {
    Eigen::MatrixXd J(r.size(), 12);
    for (int j = 0; j < 12; ++j) {
      Vector12d dx = Vector12d::Zero();
      dx[j] = kStep;
      Eigen::Isometry3d a = base_T_eye, b = flange_T_board, c = base_T_eye, d = flange_T_board;
      apply(dx, a, b);
      apply(-dx, c, d);
      J.col(j) = (residuals(views, camera, a, b) - residuals(views, camera, c, d)) / (2 * kStep);
    }
    const Eigen::MatrixXd H = J.transpose() * J;
    const Vector12d g = J.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 10 && !improved; ++tries) {
      Eigen::MatrixXd A = H;
      A.diagonal() += lambda * H.diagonal().cwiseMax(1e-9);
      const Vector12d step = -A.ldlt().solve(g);
      Eigen::Isometry3d a = base_T_eye, b = flange_T_board;
      apply(step, a, b);
      const Eigen::VectorXd r2 = residuals(views, camera, a, b);
      if (r2.squaredNorm() < r.squaredNorm()) {
        const double gain = r.squaredNorm() - r2.squaredNorm();
        base_T_eye = a, flange_T_board = b, r = r2, improved = true;
        lambda = std::max(lambda / 10, 1e-9);
        if (step.norm() < 1e-10 || gain < 1e-12 * r.squaredNorm())
          return reprojection_errors(views, camera, base_T_eye, flange_T_board);
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;
  }
  return reprojection_errors(views, camera, base_T_eye, flange_T_board);
}

}  // namespace wysiwyf::vision::calibration
