#include "wrist_calibration/tool_load_fit.hpp"

#include <cmath>
#include <cstdio>

#include <Eigen/SVD>

namespace wysiwyf::robot {

namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Largest over smallest singular value (infinite when the design is rank deficient).
double condition_number(const Eigen::MatrixXd& a) {
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(a).singularValues();
  const double smallest = s(s.size() - 1);
  return smallest > 1e-12 * s(0) ? s(0) / smallest : INFINITY;
}

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace

ToolLoadFit fit_tool_load(const std::vector<WristReading>& readings, const ToolLoadLimits& limits) {
  ToolLoadFit fit;
  const int n = static_cast<int>(readings.size());
  if (n < limits.min_poses || n < 3) {
    fit.refusal = std::to_string(n) + " poses; expected at least " + std::to_string(std::max(3, limits.min_poses)) +
                  " static poses with the sensor turned so that gravity points along different sensor axes";
    return fit;
  }
  bool all_zero = true;  // a readings template never filled in
  for (const WristReading& r : readings) all_zero = all_zero && r.force.isZero(0) && r.torque.isZero(0);
  if (all_zero) {
    fit.refusal = "every reading is exactly zero; expected the sensor's mean reading at each pose";
    return fit;
  }
  for (const WristReading& r : readings) {
    if (!r.gravity_sensor.allFinite() || !r.force.allFinite() || !r.torque.allFinite()) {
      fit.refusal = r.label + ": a non-finite gravity, force or torque; expected finite numbers";
      return fit;
    }
    if (r.gravity_sensor.norm() < 1e-6) {
      fit.refusal = r.label + ": zero gravity; expected the gravity vector in the sensor frame (about 9.81 m/s^2)";
      return fit;
    }
  }
  // Designs on unit gravity directions for the condition number; on gravity itself for the fit.
  Eigen::MatrixXd a(3 * n, 4), a_unit(3 * n, 4), b(3 * n, 6), b_unit(3 * n, 6);
  Eigen::VectorXd f(3 * n), t(3 * n);
  for (int i = 0; i < n; ++i) {
    const WristReading& r = readings[static_cast<std::size_t>(i)];
    const Eigen::Vector3d u = r.gravity_sensor.normalized();
    a.block<3, 3>(3 * i, 0).setIdentity(), a.block<3, 1>(3 * i, 3) = r.gravity_sensor;
    a_unit.block<3, 3>(3 * i, 0).setIdentity(), a_unit.block<3, 1>(3 * i, 3) = u;
    b.block<3, 3>(3 * i, 0).setIdentity(), b.block<3, 3>(3 * i, 3) = -skew(r.gravity_sensor);
    b_unit.block<3, 3>(3 * i, 0).setIdentity(), b_unit.block<3, 3>(3 * i, 3) = -skew(u);
    f.segment<3>(3 * i) = r.force;
    t.segment<3>(3 * i) = r.torque;
  }
  fit.condition = std::max(condition_number(a_unit), condition_number(b_unit));
  if (!(fit.condition <= limits.max_condition)) {
    fit.refusal = "the poses' gravity directions span too little: condition number " + fixed(fit.condition, 1) +
                  " over " + fixed(limits.max_condition, 1) +
                  "; expected poses that turn the sensor so that gravity points along each of its axes, both ways";
    return fit;
  }
  const Eigen::Vector4d x = a.colPivHouseholderQr().solve(f);
  const Eigen::Matrix<double, 6, 1> y = b.colPivHouseholderQr().solve(t);
  fit.force_bias = x.head<3>();
  fit.tool_mass = x(3);
  fit.torque_bias = y.head<3>();
  // m c is what the torques give; c needs a mass to divide by.
  fit.tool_com = fit.tool_mass > 1e-3 ? Eigen::Vector3d(y.tail<3>() / fit.tool_mass) : Eigen::Vector3d::Zero();
  const Eigen::VectorXd rf = a * x - f, rt = b * y - t;
  double worst_force = 0, worst_torque = 0;
  std::string worst_force_pose, worst_torque_pose;
  for (int i = 0; i < n; ++i) {
    PoseResidual p{readings[static_cast<std::size_t>(i)].label, rf.segment<3>(3 * i).norm(),
                   rt.segment<3>(3 * i).norm()};
    if (p.force > worst_force) worst_force = p.force, worst_force_pose = p.label;
    if (p.torque > worst_torque) worst_torque = p.torque, worst_torque_pose = p.label;
    fit.residuals.push_back(p);
  }
  fit.force_rms = std::sqrt(rf.squaredNorm() / n);
  fit.torque_rms = std::sqrt(rt.squaredNorm() / n);
  if (fit.tool_mass < -1e-3) {
    fit.refusal = "a negative tool mass (" + fixed(fit.tool_mass, 4) +
                  " kg); expected gravity in the sensor's own frame: check the sensor frame and the gravity's sign";
  } else if (worst_force > limits.max_force_residual) {
    fit.refusal = worst_force_pose + ": force residual " + fixed(worst_force, 3) + " N over " +
                  fixed(limits.max_force_residual, 3) +
                  " N; expected the arm at rest with nothing touching the tool (retake that pose)";
  } else if (worst_torque > limits.max_torque_residual) {
    fit.refusal = worst_torque_pose + ": torque residual " + fixed(worst_torque, 4) + " N m over " +
                  fixed(limits.max_torque_residual, 4) +
                  " N m; expected the arm at rest with nothing touching the tool (retake that pose)";
  }
  fit.accepted = fit.refusal.empty();
  return fit;
}

std::string describe(const ToolLoadFit& fit, const ToolLoadLimits& limits) {
  if (fit.residuals.empty()) return "refused: " + fit.refusal + "\n";  // refused before fitting
  std::string s;
  s += "force bias   [" + fixed(fit.force_bias.x(), 4) + ", " + fixed(fit.force_bias.y(), 4) + ", " +
       fixed(fit.force_bias.z(), 4) + "] N\n";
  s += "torque bias  [" + fixed(fit.torque_bias.x(), 5) + ", " + fixed(fit.torque_bias.y(), 5) + ", " +
       fixed(fit.torque_bias.z(), 5) + "] N m\n";
  s += "tool mass    " + fixed(fit.tool_mass, 4) + " kg\n";
  s += "tool com     [" + fixed(fit.tool_com.x(), 5) + ", " + fixed(fit.tool_com.y(), 5) + ", " +
       fixed(fit.tool_com.z(), 5) + "] m, sensor frame\n";
  s += "condition    " + fixed(fit.condition, 2) + " (limit " + fixed(limits.max_condition, 1) + ")\n";
  s += "pose                      force N   torque N m\n";
  for (const PoseResidual& p : fit.residuals) {
    char line[160];
    std::snprintf(
        line, sizeof line, "%-24s %8.4f %11.5f%s\n", p.label.c_str(), p.force, p.torque,
        p.force > limits.max_force_residual || p.torque > limits.max_torque_residual ? "  over the limit" : "");
    s += line;
  }
  s += "rms                      " + fixed(fit.force_rms, 4) + "     " + fixed(fit.torque_rms, 5) + "  (limits " +
       fixed(limits.max_force_residual, 3) + " N, " + fixed(limits.max_torque_residual, 4) + " N m per pose)\n";
  s += fit.accepted ? "accepted\n" : "refused: " + fit.refusal + "\n";
  return s;
}

}  // namespace wysiwyf::robot
