#include "calibration/lamp_fit.hpp"

#include <cmath>
#include <cstdio>
#include <exception>
#include <opencv2/calib3d.hpp>

namespace wysiwyf::vision::calibration {

namespace {

struct Observation {
  std::size_t view, lamp;
  Eigen::Vector2d normalised;  // undistorted, on the z = 1 plane
};

// Parameters: base_T_eye's rotation vector and translation, then each lamp's xyz on the flange.
Eigen::Isometry3d eye_T_base_of(const Eigen::VectorXd& x) {
  Eigen::Isometry3d base_T_eye = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d r = x.segment<3>(0);
  if (r.norm() > 0) base_T_eye.linear() = Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
  base_T_eye.translation() = x.segment<3>(3);
  return base_T_eye.inverse();
}

// Residuals in px (normalised error times the focal length), two per observation.
Eigen::VectorXd residuals(const Eigen::VectorXd& x, const std::vector<Observation>& obs,
                          const std::vector<LampView>& views, double focal) {
  const Eigen::Isometry3d eye_T_base = eye_T_base_of(x);
  Eigen::VectorXd r(2 * static_cast<Eigen::Index>(obs.size()));
  for (std::size_t k = 0; k < obs.size(); ++k) {
    const Eigen::Vector3d p = x.segment<3>(6 + 3 * static_cast<Eigen::Index>(obs[k].lamp));
    const Eigen::Vector3d c = eye_T_base * views[obs[k].view].base_T_flange * p;
    const double z = std::max(c.z(), 1e-6);
    r.segment<2>(2 * static_cast<Eigen::Index>(k)) = focal * (c.head<2>() / z - obs[k].normalised);
  }
  return r;
}

}  // namespace

LampFit fit_lamps(const std::vector<LampView>& views, const CameraIntrinsics& camera,
                  const std::vector<Eigen::Vector3d>& nominal, const LampLimits& limits) {
  LampFit fit;
  const std::size_t lamps = nominal.size();
  if (lamps == 0 || static_cast<int>(views.size()) < limits.min_views) {
    fit.refusal = std::to_string(views.size()) + " views; expected at least " + std::to_string(limits.min_views) +
                  " of the arm at different poses, with the lamps' nominal positions";
    return fit;
  }
  // Every observation, undistorted once; each lamp's count.
  std::vector<Observation> obs;
  std::vector<int> seen(lamps, 0);
  std::vector<cv::Point3f> pnp_points;
  std::vector<cv::Point2f> pnp_pixels;
  for (std::size_t v = 0; v < views.size(); ++v) {
    if (views[v].lamp.size() != lamps) {
      fit.refusal =
          views[v].label + ": " + std::to_string(views[v].lamp.size()) + " lamps; expected " + std::to_string(lamps);
      return fit;
    }
    for (std::size_t i = 0; i < lamps; ++i) {
      const auto& px = views[v].lamp[i];
      if (!px || !std::isfinite(px->x) || !std::isfinite(px->y)) continue;
      std::vector<cv::Point2d> in{*px}, out;
      cv::undistortPoints(in, out, cv::Mat(camera.camera_matrix), cv::Mat(camera.distortion));
      obs.push_back({v, i, Eigen::Vector2d(out[0].x, out[0].y)});
      ++seen[i];
      const Eigen::Vector3d b = views[v].base_T_flange * nominal[i];
      pnp_points.emplace_back(static_cast<float>(b.x()), static_cast<float>(b.y()), static_cast<float>(b.z()));
      pnp_pixels.emplace_back(static_cast<float>(px->x), static_cast<float>(px->y));
    }
  }
  for (std::size_t i = 0; i < lamps; ++i)
    if (seen[i] < limits.min_views_per_lamp) {
      fit.refusal = "lamp " + std::to_string(i) + " seen in " + std::to_string(seen[i]) + " views; expected at least " +
                    std::to_string(limits.min_views_per_lamp);
      return fit;
    }
  // The start: the camera's pose from the nominal lamps (their base positions at every pose).
  Eigen::VectorXd x(6 + 3 * static_cast<Eigen::Index>(lamps));
  try {
    cv::Vec3d rvec, tvec;
    cv::solvePnP(pnp_points, pnp_pixels, cv::Mat(camera.camera_matrix), cv::Mat(camera.distortion), rvec, tvec);
    cv::Matx33d R;
    cv::Rodrigues(rvec, R);
    Eigen::Matrix3d eye_R_base;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) eye_R_base(r, c) = R(r, c);
    const Eigen::Matrix3d base_R_eye = eye_R_base.transpose();
    const Eigen::AngleAxisd aa(base_R_eye);
    x.segment<3>(0) = aa.angle() * aa.axis();
    x.segment<3>(3) = -base_R_eye * Eigen::Vector3d(tvec[0], tvec[1], tvec[2]);
  } catch (const std::exception& e) {
    fit.refusal = std::string("no camera pose from the nominal lamps: ") + e.what();
    return fit;
  }
  for (std::size_t i = 0; i < lamps; ++i) x.segment<3>(6 + 3 * static_cast<Eigen::Index>(i)) = nominal[i];
  // Levenberg-Marquardt with a forward-difference Jacobian (a few dozen parameters).
  const double focal = camera.camera_matrix(0, 0);
  Eigen::VectorXd r = residuals(x, obs, views, focal);
  double lambda = 1e-3;
  bool converged = false;
  for (int iteration = 0; iteration < 100 && !converged; ++iteration) {
    Eigen::MatrixXd J(r.size(), x.size());
    for (Eigen::Index j = 0; j < x.size(); ++j) {
      Eigen::VectorXd xp = x;
      xp[j] += 1e-7;
      J.col(j) = (residuals(xp, obs, views, focal) - r) / 1e-7;
    }
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 10 && !improved; ++tries) {
      Eigen::MatrixXd A = JtJ;
      A.diagonal() *= 1 + lambda;
      const Eigen::VectorXd step = A.ldlt().solve(-g);
      const Eigen::VectorXd r_try = residuals(x + step, obs, views, focal);
      if (r_try.squaredNorm() < r.squaredNorm()) {
        const double gain = r.squaredNorm() - r_try.squaredNorm();
        x += step, r = r_try, lambda = std::max(lambda / 3, 1e-9), improved = true;
        converged = gain < 1e-12 * std::max(1.0, r.squaredNorm());
      } else {
        lambda *= 4;
      }
    }
    if (!improved) break;
  }
  fit.base_T_eye = eye_T_base_of(x).inverse();
  for (std::size_t i = 0; i < lamps; ++i)
    fit.flange_p_lamp.push_back(x.segment<3>(6 + 3 * static_cast<Eigen::Index>(i)));
  fit.rms = std::sqrt(r.squaredNorm() / static_cast<double>(obs.size()));
  // Each view's error; the worst over the limit refuses the set.
  std::vector<double> sum(views.size(), 0);
  std::vector<int> n(views.size(), 0);
  for (std::size_t k = 0; k < obs.size(); ++k)
    sum[obs[k].view] += r.segment<2>(2 * static_cast<Eigen::Index>(k)).squaredNorm(), ++n[obs[k].view];
  std::size_t worst = 0;
  for (std::size_t v = 0; v < views.size(); ++v) {
    fit.view_rms.push_back(n[v] ? std::sqrt(sum[v] / n[v]) : -1);
    if (fit.view_rms[v] > fit.view_rms[worst]) worst = v;
  }
  if (fit.view_rms[worst] > limits.max_view_error) {
    char b[160];
    std::snprintf(b, sizeof b, "%s: %.2f px RMS after the fit (limit %.2f px): a lamp misread, or the camera moved",
                  views[worst].label.c_str(), fit.view_rms[worst], limits.max_view_error);
    fit.refusal = b;
    return fit;
  }
  fit.accepted = true;
  return fit;
}

}  // namespace wysiwyf::vision::calibration
