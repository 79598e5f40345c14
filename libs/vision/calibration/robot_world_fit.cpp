#include "calibration/robot_world_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include <Eigen/SVD>
#include <opencv2/calib3d.hpp>

#include "calibration/pose_refinement.hpp"

namespace wysiwyf::vision::calibration {

namespace {

constexpr double kDeg = 180.0 / M_PI;

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

Eigen::Isometry3d from_cv(const cv::Mat& R, const cv::Mat& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = R.at<double>(r, c);
    T.translation()[r] = t.at<double>(r);
  }
  return T;
}

// The rotation and the translation of T as new matrices (never sharing data with earlier ones).
std::pair<cv::Mat, cv::Mat> to_cv(const Eigen::Isometry3d& T) {
  cv::Mat R(3, 3, CV_64F), t(3, 1, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R.at<double>(r, c) = T.linear()(r, c);
    t.at<double>(r) = T.translation()[r];
  }
  return {R, t};
}

// The flange's rotation about its least-turned axis: RMS over the poses, degrees.
double rotation_spread(const std::vector<PoseObservations>& views) {
  const Eigen::Matrix3d R0 = views.front().base_T_flange.linear();
  Eigen::MatrixXd r(static_cast<Eigen::Index>(views.size()), 3);
  for (std::size_t i = 0; i < views.size(); ++i) {
    const Eigen::AngleAxisd aa(R0.transpose() * views[i].base_T_flange.linear());
    r.row(static_cast<Eigen::Index>(i)) = (aa.angle() * aa.axis()).transpose();
  }
  r.rowwise() -= r.colwise().mean();
  const Eigen::Vector3d s = Eigen::JacobiSVD<Eigen::MatrixXd>(r).singularValues();
  return s[2] / std::sqrt(static_cast<double>(views.size())) * kDeg;
}

struct Solution {
  Eigen::Isometry3d base_T_eye, flange_T_board;
  std::vector<double> errors;
  double worst = 0;
};

// The closed form from the boards' PnP poses, then the reprojection fit.
Solution solve(const std::vector<PoseObservations>& views, const std::vector<Eigen::Isometry3d>& eye_T_board,
               const CameraIntrinsics& camera) {
  std::vector<cv::Mat> R_board_eye, t_board_eye, R_flange_base, t_flange_base;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const auto [R_be, t_be] = to_cv(eye_T_board[i].inverse());
    R_board_eye.push_back(R_be), t_board_eye.push_back(t_be);
    const auto [R_fb, t_fb] = to_cv(views[i].base_T_flange.inverse());
    R_flange_base.push_back(R_fb), t_flange_base.push_back(t_fb);
  }
  cv::Mat R_eb, t_eb, R_bf, t_bf;
  cv::calibrateRobotWorldHandEye(R_board_eye, t_board_eye, R_flange_base, t_flange_base, R_eb, t_eb, R_bf, t_bf);
  // OpenCV solves A X = Z B with A = cTw, B = gTb for X = wTb, Z = cTg; its camera is our board, its
  // world our camera, its gripper our flange: X = eye_T_base, Z = board_T_flange.
  Solution s{from_cv(R_eb, t_eb).inverse(), from_cv(R_bf, t_bf).inverse(), {}, 0};
  s.errors = refine_robot_world(views, camera, s.base_T_eye, s.flange_T_board);
  for (double e : s.errors) s.worst = std::max(s.worst, e);
  return s;
}

}  // namespace

RobotWorldFit fit_robot_world(const std::vector<FlangeView>& views, const CharucoTarget& target,
                              const CameraIntrinsics& camera, const RobotWorldLimits& limits) {
  RobotWorldFit fit;
  std::vector<PoseObservations> used;
  std::vector<Eigen::Isometry3d> eye_T_board;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const FlangeView& v = views[i];
    FlangePoseReport r{v.label, static_cast<int>(v.corners.size()), -1, ""};
    bool ids_ok = v.ids.size() == v.corners.size();
    for (int id : v.ids) ids_ok = ids_ok && id >= 0 && id < static_cast<int>(target.corners().size());
    if (!v.base_T_flange.matrix().allFinite())
      r.note = "a non-finite flange pose";
    else if (!ids_ok)
      r.note = "corner ids that are not the board's";
    else if (r.corners < limits.min_corners)
      r.note = r.corners == 0 ? "no board found" : "too few corners: " + std::to_string(r.corners);
    if (r.note.empty()) {
      PoseObservations o{v.base_T_flange, {}, v.corners};
      for (int id : v.ids) o.board_points.push_back(target.corners()[static_cast<std::size_t>(id)]);
      cv::Vec3d rvec, tvec;
      if (!cv::solvePnP(o.board_points, o.seen, cv::Mat(camera.camera_matrix), cv::Mat(camera.distortion), rvec,
                        tvec)) {
        r.note = "the board's pose could not be found from its corners";
      } else {
        cv::Mat R;
        cv::Rodrigues(rvec, R);
        eye_T_board.push_back(from_cv(R, cv::Mat(tvec)));
        used.push_back(o);
        index.push_back(i);
      }
    }
    fit.poses.push_back(r);
  }
  if (static_cast<int>(used.size()) < limits.min_poses) {
    fit.refusal = std::to_string(used.size()) + " usable poses of " + std::to_string(views.size()) +
                  "; expected at least " + std::to_string(limits.min_poses) +
                  " poses with the whole board in view (`wysiwyf calibrate camera-base-poses` makes a set)";
    return fit;
  }
  fit.rotation_spread = rotation_spread(used);
  if (fit.rotation_spread < limits.min_rotation_spread) {
    fit.refusal = "the flange turns " + fixed(fit.rotation_spread, 1) + " deg RMS about its least-turned axis (limit " +
                  fixed(limits.min_rotation_spread, 1) +
                  " deg); expected poses that tilt the board about different axes";
    return fit;
  }
  Solution s;
  try {
    s = solve(used, eye_T_board, camera);
  } catch (const cv::Exception& e) {
    fit.refusal = std::string("OpenCV could not solve the robot-world calibration: ") + e.what();
    return fit;
  }
  fit.base_T_eye = s.base_T_eye, fit.flange_T_board = s.flange_T_board;
  double sum = 0;
  std::size_t corners = 0;
  std::string worst;
  for (std::size_t k = 0; k < used.size(); ++k) {
    FlangePoseReport& r = fit.poses[index[k]];
    r.rms = s.errors[k];
    if (r.rms > limits.max_pose_error) r.note = "reprojection error over the limit";
    if (r.rms == s.worst) worst = r.label;
    sum += r.rms * r.rms * static_cast<double>(used[k].seen.size());
    corners += used[k].seen.size();
  }
  fit.rms = std::sqrt(sum / static_cast<double>(corners));
  if (!fit.base_T_eye.matrix().allFinite()) {
    fit.refusal = "the fit gave a non-finite pose; expected poses that tilt the board about different axes";
  } else if (s.worst > limits.max_pose_error) {
    fit.refusal =
        worst + ": reprojection error " + fixed(s.worst, 2) + " px over " + fixed(limits.max_pose_error, 2) + " px";
    // Two halves that each fit where the whole does not: something moved between them.
    const int half = std::max(4, limits.min_poses / 2), n = static_cast<int>(used.size());
    int best_split = -1;
    double best = INFINITY;
    Solution before, after;
    for (int k = half; k + half <= n; ++k) {
      const std::vector<PoseObservations> a(used.begin(), used.begin() + k), b(used.begin() + k, used.end());
      const std::vector<Eigen::Isometry3d> ea(eye_T_board.begin(), eye_T_board.begin() + k),
          eb(eye_T_board.begin() + k, eye_T_board.end());
      Solution sa = solve(a, ea, camera), sb = solve(b, eb, camera);
      if (std::max(sa.worst, sb.worst) < best)
        best = std::max(sa.worst, sb.worst), best_split = k, before = sa, after = sb;
    }
    if (best_split > 0 && best <= limits.max_pose_error) {
      const Eigen::Isometry3d d = before.base_T_eye.inverse() * after.base_T_eye;
      fit.refusal = "the camera (or the board on the flange) moved between " +
                    fit.poses[index[static_cast<std::size_t>(best_split - 1)]].label + " and " +
                    fit.poses[index[static_cast<std::size_t>(best_split)]].label + ": the poses before and after fit " +
                    "apart, with cameras " + fixed(1e3 * d.translation().norm(), 1) + " mm and " +
                    fixed(Eigen::AngleAxisd(d.linear()).angle() * kDeg, 2) +
                    " deg apart; expected both fixed (tighten them and take the poses again)";
    } else {
      fit.refusal += "; expected the arm at rest at each pose, and the camera and the board fixed";
    }
  }
  fit.accepted = fit.refusal.empty();
  return fit;
}

std::string describe(const RobotWorldFit& fit, const RobotWorldLimits& limits) {
  const Eigen::Vector3d p = fit.base_T_eye.translation();
  const Eigen::Vector3d rpy = fit.base_T_eye.linear().eulerAngles(2, 1, 0).reverse() * kDeg;
  const Eigen::Vector3d b = fit.flange_T_board.translation();
  std::string s;
  if (fit.rms > 0)
    s += "base_T_eye      position [" + fixed(p.x(), 4) + ", " + fixed(p.y(), 4) + ", " + fixed(p.z(), 4) +
         "] m, roll pitch yaw (about x, y, z of base) [" + fixed(rpy.x(), 3) + ", " + fixed(rpy.y(), 3) + ", " +
         fixed(rpy.z(), 3) + "] deg\n";
  if (fit.rms > 0)
    s += "flange_T_board  position [" + fixed(b.x(), 4) + ", " + fixed(b.y(), 4) + ", " + fixed(b.z(), 4) + "] m\n";
  s += "rotation spread " + fixed(fit.rotation_spread, 1) + " deg (limit " + fixed(limits.min_rotation_spread, 1) +
       ")\n";
  s += "pose                              corners  error px\n";
  for (const FlangePoseReport& r : fit.poses) {
    char line[256];
    std::snprintf(line, sizeof line, "%-32s %7d %9s  %s\n", r.label.c_str(), r.corners,
                  r.rms < 0 ? "-" : fixed(r.rms, 3).c_str(), r.note.c_str());
    s += line;
  }
  if (fit.rms > 0)
    s += "rms             " + fixed(fit.rms, 3) + " px (limit " + fixed(limits.max_pose_error, 2) + " px per pose)\n";
  s += fit.accepted ? "accepted\n" : "refused: " + fit.refusal + "\n";
  return s;
}

}  // namespace wysiwyf::vision::calibration
