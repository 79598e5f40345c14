// The PUMA 560 model (libs/robot/puma_model) against config/robots/puma560.urdf:
// kinematics against an independent DH chain, IK round trips, Jacobian, dynamics identities,
// hand-computed gravity torques, unreachable poses, load errors, drive file, check_urdf.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>
#include <unistd.h>

#include "arm_joint_sim/drive_params.hpp"
#include "puma_model/puma_model.hpp"

namespace wysiwyf::robot {
namespace {

const std::string kUrdf = std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560.urdf";
const std::string kDrive = std::string(WYSIWYF_CONFIG_DIR) + "/robots/puma560_drive.yaml";
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// ---- the independent reference: the DH table of Corke & Armstrong-Helouvry 1994, typed in
// here, not read from the library or the URDF.
constexpr double kD[6] = {0.6718, 0.0, 0.15005, 0.4318, 0.0, 0.0};
constexpr double kA[6] = {0.0, 0.4318, 0.0203, 0.0, 0.0, 0.0};
constexpr double kAlpha[6] = {90 * kDeg, 0.0, -90 * kDeg, 90 * kDeg, -90 * kDeg, 0.0};
constexpr double kLower[6] = {-160 * kDeg, -45 * kDeg, -225 * kDeg, -110 * kDeg, -100 * kDeg, -266 * kDeg};
constexpr double kUpper[6] = {160 * kDeg, 225 * kDeg, 45 * kDeg, 170 * kDeg, 100 * kDeg, 266 * kDeg};
constexpr double kFlange = 0.05625;  // flange face beyond the wrist centre along z6

Eigen::Isometry3d dh_link(double theta, double d, double a, double alpha) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()));
  T.translate(Eigen::Vector3d(0.0, 0.0, d));
  T.translate(Eigen::Vector3d(a, 0.0, 0.0));
  T.rotate(Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()));
  return T;
}

// base_T_dh6 by the textbook product A1 ... A6.
Eigen::Isometry3d dh_fk(const Vector6d& q) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 6; ++i) T = T * dh_link(q[i], kD[i], kA[i], kAlpha[i]);
  return T;
}

Eigen::Isometry3d translation(double x, double y, double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

double position_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}

double rotation_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(Eigen::Matrix3d(a.linear().transpose() * b.linear())).angle();
}

double wrap(double a) { return std::remainder(a, 2 * kPi); }

class PumaTest : public ::testing::Test {
 protected:
  PumaModel model{kUrdf};
  std::mt19937_64 rng{20261122};

  Vector6d random_q() {
    Vector6d q;
    for (int j = 0; j < 6; ++j) q[j] = std::uniform_real_distribution<double>(kLower[j], kUpper[j])(rng);
    return q;
  }
  Vector6d random_vector(double scale) {
    Vector6d v;
    for (int j = 0; j < 6; ++j) v[j] = std::uniform_real_distribution<double>(-scale, scale)(rng);
    return v;
  }
};

TEST_F(PumaTest, LoadsTheChainFramesAndLimits) {
  EXPECT_EQ(model.joint_names()[0], "joint1");
  EXPECT_EQ(model.joint_names()[5], "joint6");
  EXPECT_EQ(model.frame_name(model.tip()), "flange");
  for (const char* name : {"base_link", "link1", "link6", "flange", "ft_sensor", "dev", "marker_0", "marker_1",
                           "marker_2", "marker_3", "knob"})
    EXPECT_NO_THROW(model.frame(name)) << name;
  EXPECT_THROW(model.frame("nope"), std::out_of_range);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(model.limits().lower[j], kLower[j], 1e-12) << j;
    EXPECT_NEAR(model.limits().upper[j], kUpper[j], 1e-12) << j;
    EXPECT_GT(model.limits().velocity[j], 0.0);
    EXPECT_GT(model.limits().effort[j], 0.0);
  }
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(model.dh().d[i], kD[i], 1e-12) << i;
    EXPECT_NEAR(model.dh().a[i], kA[i], 1e-12) << i;
    EXPECT_NEAR(model.dh().alpha[i], kAlpha[i], 1e-12) << i;
  }
  // Body 6 carries the wrist link, the sensor, the plate and the knob.
  EXPECT_NEAR(model.body(6).mass, 0.09 + 0.4 + 1.08 + 0.0763, 1e-12);
  EXPECT_NEAR(model.body(2).mass, 17.4, 1e-12);
}

TEST_F(PumaTest, ForwardKinematicsEqualsStandardDh) {
  const FrameId link6 = model.frame("link6"), flange = model.frame("flange"), knob = model.frame("knob"),
                marker0 = model.frame("marker_0"), dev = model.frame("dev");
  double worst_p = 0.0, worst_r = 0.0;
  for (int n = 0; n < 1000; ++n) {
    const Vector6d q = random_q();
    const Eigen::Isometry3d base_T_dh6 = dh_fk(q);
    const std::pair<FrameId, Eigen::Isometry3d> cases[] = {
        {link6, base_T_dh6},
        {flange, base_T_dh6 * translation(0, 0, kFlange)},
        {dev, base_T_dh6 * translation(0, 0, kFlange + 0.05)},
        {knob, base_T_dh6 * translation(0, 0, kFlange + 0.09)},
        {marker0, base_T_dh6 * translation(0.08, 0.08, kFlange + 0.05)},
    };
    for (const auto& [frame, expected] : cases) {
      const Eigen::Isometry3d got = model.fk(q, frame);
      worst_p = std::max(worst_p, position_error(got, expected));
      worst_r = std::max(worst_r, rotation_error(got, expected));
    }
  }
  EXPECT_LE(worst_p, 1e-9);
  EXPECT_LE(worst_r, 1e-9);
}

TEST_F(PumaTest, FramesOnThePlate) {
  const Vector6d q = random_q();
  const Eigen::Isometry3d base_T_dev = model.fk(q, model.frame("dev"));
  const double xy[4][2] = {{0.08, 0.08}, {-0.08, 0.08}, {-0.08, -0.08}, {0.08, -0.08}};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Isometry3d dev_T_marker =
        base_T_dev.inverse() * model.fk(q, model.frame("marker_" + std::to_string(i)));
    EXPECT_LE((dev_T_marker.translation() - Eigen::Vector3d(xy[i][0], xy[i][1], 0)).norm(), 1e-12) << i;
  }
  const Eigen::Isometry3d dev_T_knob = base_T_dev.inverse() * model.fk(q, model.frame("knob"));
  EXPECT_LE((dev_T_knob.translation() - Eigen::Vector3d(0, 0, 0.04)).norm(), 1e-12);
  const Eigen::Isometry3d flange_T_ft = model.fk(q).inverse() * model.fk(q, model.frame("ft_sensor"));
  EXPECT_LE((flange_T_ft.translation() - Eigen::Vector3d(0, 0, 0.03)).norm(), 1e-12);
}

TEST_F(PumaTest, InverseKinematicsRoundTrip) {
  double worst_p = 0.0, worst_r = 0.0, worst_q = 0.0;
  int checked_q = 0;
  const Vector6d q_ref = Vector6d::Zero();
  for (int n = 0; n < 10000; ++n) {
    const Vector6d q = random_q();
    const Eigen::Isometry3d base_T_flange = model.fk(q);
    const IkSolutions all = model.ik(base_T_flange, q_ref);
    ASSERT_EQ(all.status, IkStatus::kOk) << "q = " << q.transpose();
    ASSERT_GE(all.within_limits_count, 1);
    double nearest = 1e9;
    for (const IkSolution& sol : all.solution) {
      if (!sol.valid) continue;
      const Eigen::Isometry3d got = model.fk(sol.q);
      worst_p = std::max(worst_p, position_error(got, base_T_flange));
      worst_r = std::max(worst_r, rotation_error(got, base_T_flange));
      if (sol.within_limits) {
        EXPECT_TRUE(model.limits().within(sol.q, 1e-12));
      }
      double d = 0.0;
      for (int j = 0; j < 6; ++j) d = std::max(d, std::abs(wrap(sol.q[j] - q[j])));
      nearest = std::min(nearest, d);
    }
    // Away from the singularities q itself is among the solutions. Near one the joint angles
    // of a pose are ill-conditioned (a 1e-16 rounding of the pose moves them by 1e-16 / distance)
    // though every solution still matches the pose above: wrist (sin q5 = 0), elbow
    // (sin(q3 + atan2(d4, a3)) = 0), shoulder (wrist centre on the cylinder of radius d3, where
    // the arm-plane reach r = a2 c2 + a3 c23 - d4 s23 is 0).
    const double r = kA[1] * std::cos(q[1]) + kA[2] * std::cos(q[1] + q[2]) - kD[3] * std::sin(q[1] + q[2]);
    const double elbow = std::sin(q[2] + std::atan2(kD[3], kA[2]));
    if (std::abs(std::sin(q[4])) > 1e-3 && std::abs(elbow) > 1e-3 && std::abs(r) > 1e-3) {
      ++checked_q;
      worst_q = std::max(worst_q, nearest);
      // ... and the nearest solution to q itself is q.
      const IkResult nearest_to_q = model.ik_nearest(base_T_flange, q);
      ASSERT_TRUE(nearest_to_q.ok());
      EXPECT_LE((nearest_to_q.q - q).cwiseAbs().maxCoeff(), 1e-9);
    }
  }
  EXPECT_LE(worst_p, 1e-9);
  EXPECT_LE(worst_r, 1e-9);
  EXPECT_LE(worst_q, 1e-9);
  EXPECT_GT(checked_q, 9900);
}

TEST_F(PumaTest, InverseKinematicsOfAnotherToolFrame) {
  const FrameId knob = model.frame("knob");
  for (int n = 0; n < 200; ++n) {
    const Vector6d q = random_q();
    const Eigen::Isometry3d base_T_knob = model.fk(q, knob);
    const IkResult r = model.ik_nearest(base_T_knob, q, knob);
    ASSERT_TRUE(r.ok());
    EXPECT_LE(position_error(model.fk(r.q, knob), base_T_knob), 1e-9);
    EXPECT_LE(rotation_error(model.fk(r.q, knob), base_T_knob), 1e-9);
  }
  EXPECT_THROW(model.ik(Eigen::Isometry3d::Identity(), Vector6d::Zero(), model.frame("link3")), std::invalid_argument);
}

TEST_F(PumaTest, ConfigurationFlagsMeanWhatTheySay) {
  // left_arm: wrist centre behind the shoulder (arm-plane reach r < 0); elbow_up: the elbow
  // (origin of link3) above the shoulder-to-wrist line, in the arm plane; wrist_flip: q5 <= 0.
  const FrameId link2 = model.frame("link2"), link3 = model.frame("link3"), link6 = model.frame("link6");
  int checked = 0;
  for (int n = 0; n < 2000; ++n) {
    const Vector6d q = random_q();
    const IkSolutions all = model.ik(model.fk(q), q);
    for (const IkSolution& sol : all.solution) {
      if (!sol.valid || (sol.q - q).cwiseAbs().maxCoeff() > 1e-8) continue;
      ++checked;
      const Eigen::Isometry3d base_T_link2 = model.fk(q, link2);
      const Eigen::Vector3d shoulder = base_T_link2.translation(), elbow = model.fk(q, link3).translation(),
                            wrist = model.fk(q, link6).translation();
      Eigen::Vector3d up = base_T_link2.linear().col(2).cross(wrist - shoulder);
      if (up.z() < 0) up = -up;
      const double r = kA[1] * std::cos(q[1]) + kA[2] * std::cos(q[1] + q[2]) - kD[3] * std::sin(q[1] + q[2]);
      EXPECT_EQ(sol.left_arm, r < 0) << q.transpose();
      EXPECT_EQ(sol.elbow_up, (elbow - shoulder).dot(up) > 0) << q.transpose();
      EXPECT_EQ(sol.wrist_flip, q[4] < 0) << q.transpose();
    }
  }
  EXPECT_GT(checked, 1900);
}

TEST_F(PumaTest, WristSingularityKeepsTheCurrentQ4) {
  Vector6d q;
  q << 0.3, 0.5, -1.0, 0.7, 0.0, 0.2;
  const Eigen::Isometry3d target = model.fk(q);
  for (double q4_ref : {0.7, -0.4}) {
    Vector6d ref = q;
    ref[3] = q4_ref;
    const IkSolutions all = model.ik(target, ref);
    ASSERT_EQ(all.status, IkStatus::kOk);
    // The arm configuration of q (both wrist branches) puts q5 at 0; the other three
    // shoulder/elbow configurations reach the same pose with a bent wrist.
    int singular = 0;
    for (const IkSolution& sol : all.solution) {
      if (!sol.valid) continue;
      EXPECT_LE(position_error(model.fk(sol.q), target), 1e-9);
      EXPECT_LE(rotation_error(model.fk(sol.q), target), 1e-9);
      if (!sol.wrist_singular) continue;
      ++singular;
      EXPECT_NEAR(sol.q[3], q4_ref, 1e-12);
      EXPECT_NEAR(sol.q[4], 0.0, 1e-9);
      EXPECT_NEAR(wrap(sol.q[3] + sol.q[5] - (q[3] + q[5])), 0.0, 1e-9);
    }
    EXPECT_EQ(singular, 2);
    const IkResult r = model.ik_nearest(target, ref);
    ASSERT_TRUE(r.ok());
    EXPECT_TRUE(r.wrist_singular);
    EXPECT_NEAR(r.q[3], q4_ref, 1e-12);
    EXPECT_NEAR(wrap(r.q[3] + r.q[5] - (q[3] + q[5])), 0.0, 1e-9);  // q4 + q6 is what is fixed
  }
}

TEST_F(PumaTest, UnreachablePosesAreReported) {
  const FrameId link6 = model.frame("link6");
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() << 3.0, 0.0, 1.0;
  const IkResult r_far = model.ik_nearest(far, Vector6d::Zero());
  EXPECT_FALSE(r_far.ok());
  EXPECT_EQ(r_far.status, IkStatus::kOutOfReach) << to_string(r_far.status);

  Eigen::Isometry3d on_axis = Eigen::Isometry3d::Identity();
  on_axis.translation() << 0.0, 0.05, 1.0;  // nearer to the joint-1 axis than d3 = 0.15005
  EXPECT_EQ(model.ik_nearest(on_axis, Vector6d::Zero(), link6).status, IkStatus::kInsideShoulderCylinder);
  EXPECT_EQ(model.ik(on_axis, Vector6d::Zero(), link6).valid_count, 0);

  Eigen::Isometry3d nan_pose = Eigen::Isometry3d::Identity();
  nan_pose.translation().x() = std::nan("");
  EXPECT_EQ(model.ik_nearest(nan_pose, Vector6d::Zero()).status, IkStatus::kInvalidInput);

  // Reachable, but only with a joint beyond its limit: bend the wrist past 100 deg.
  int found = 0;
  for (int n = 0; n < 2000 && found < 20; ++n) {
    Vector6d q = random_q();
    q[4] = std::uniform_real_distribution<double>(110 * kDeg, 170 * kDeg)(rng);
    const Eigen::Isometry3d target = model.fk(q);
    const IkSolutions all = model.ik(target, q);
    if (all.status != IkStatus::kJointLimits) continue;
    ++found;
    EXPECT_GT(all.valid_count, 0);
    EXPECT_EQ(all.within_limits_count, 0);
    const IkResult r = model.ik_nearest(target, q);
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.status, IkStatus::kJointLimits);
  }
  EXPECT_EQ(found, 20);
}

TEST_F(PumaTest, JacobianMatchesFiniteDifferences) {
  const double h = 1e-6;
  for (const char* name : {"flange", "knob", "link4"}) {
    const FrameId f = model.frame(name);
    for (int n = 0; n < 100; ++n) {
      const Vector6d q = random_q();
      const Matrix6d J = model.jacobian(q, f);
      Matrix6d fd;
      for (int j = 0; j < 6; ++j) {
        Vector6d qp = q, qm = q;
        qp[j] += h;
        qm[j] -= h;
        const Eigen::Isometry3d Tp = model.fk(qp, f), Tm = model.fk(qm, f);
        fd.block<3, 1>(0, j) = (Tp.translation() - Tm.translation()) / (2 * h);
        const Eigen::AngleAxisd dR(Eigen::Matrix3d(Tp.linear() * Tm.linear().transpose()));
        fd.block<3, 1>(3, j) = dR.angle() * dR.axis() / (2 * h);
      }
      EXPECT_LE((J - fd).cwiseAbs().maxCoeff(), 1e-6) << name << " q = " << q.transpose();
    }
  }
}

TEST_F(PumaTest, DampedLeastSquaresConverges) {
  for (int n = 0; n < 20; ++n) {
    const Vector6d q_goal = random_q();
    const Eigen::Isometry3d target = model.fk(q_goal);
    Vector6d q = q_goal + random_vector(0.1);
    for (int k = 0; k < 200; ++k) q += model.dls_step(q, target, 0.01);
    EXPECT_LE(position_error(model.fk(q), target), 1e-9);
    EXPECT_LE(rotation_error(model.fk(q), target), 1e-9);
  }
  // At the wrist singularity the step stays bounded: |dq| <= |e| / (2 lambda).
  Vector6d q;
  q << 0.1, 0.4, -1.2, 0.0, 0.0, 0.0;
  Eigen::Isometry3d target = model.fk(q);
  target.translation() += Eigen::Vector3d(0.01, -0.01, 0.02);
  target.rotate(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()));
  const double lambda = 0.05;
  const Vector6d dq = model.dls_step(q, target, lambda);
  ASSERT_TRUE(dq.allFinite());
  const double e = std::hypot(Eigen::Vector3d(0.01, -0.01, 0.02).norm(), 0.05);
  EXPECT_LE(dq.norm(), e / (2 * lambda) + 1e-12);
}

TEST_F(PumaTest, MassMatrixIsSymmetricPositiveDefiniteAndMatchesRnea) {
  for (int n = 0; n < 200; ++n) {
    const Vector6d q = random_q();
    const Matrix6d M = model.mass_matrix(q);
    EXPECT_LE((M - M.transpose()).cwiseAbs().maxCoeff(), 1e-12);
    const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(M);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << "q = " << q.transpose();
    // Column j of M is the RNEA torque for qdd = e_j without velocity and gravity.
    for (int j = 0; j < 6; ++j) {
      const Vector6d col = model.rnea(q, Vector6d::Zero(), Vector6d::Unit(j), Eigen::Vector3d::Zero());
      EXPECT_LE((col - M.col(j)).cwiseAbs().maxCoeff(), 1e-12 * std::max(1.0, M.cwiseAbs().maxCoeff()));
    }
  }
}

// The paper's inertial parameters, typed in here in DH frames (not the URDF's link frames),
// and the tool side's bodies on DH frame 6.
struct DhBody {
  int frame;          // DH frame 1..6 the values are given in
  double m;           // kg
  Eigen::Vector3d r;  // centre of mass in that frame
  Eigen::Vector3d I;  // principal inertia about the COM, along that frame's axes
};
const DhBody kBodies[] = {
    {1, 13.0, {0, 0, 0}, {0.175, 0.35, 0.175}},  // y1 is the joint-1 axis: 0.35 (paper); m, x, z assumed
    {2, 17.4, {-0.3638, 0.006, 0.2275}, {0.13, 0.524, 0.539}},
    {3, 4.8, {-0.0203, -0.0141, 0.070}, {0.066, 0.086, 0.0125}},
    {4, 0.82, {0, 0.019, 0}, {1.8e-3, 1.3e-3, 1.8e-3}},
    {5, 0.34, {0, 0, 0}, {0.3e-3, 0.4e-3, 0.3e-3}},
    {6, 0.09, {0, 0, 0.032}, {0.15e-3, 0.15e-3, 0.04e-3}},
    {6, 0.4, {0, 0, kFlange + 0.02}, {2.1333e-4, 2.1333e-4, 3.2e-4}},       // F/T sensor
    {6, 1.08, {0, 0, kFlange + 0.045}, {3.609e-3, 3.609e-3, 7.2e-3}},       // plate
    {6, 0.0763, {0, 0, kFlange + 0.07}, {1.4466e-5, 1.4466e-5, 8.584e-6}},  // knob
};

TEST_F(PumaTest, MassMatrixAndGravityMatchAJacobianSumOverThePapersBodies) {
  // M = sum m Jv^T Jv + Jw^T I_base Jw; g = -sum m Jv^T gravity, with the test's DH chain.
  const Eigen::Vector3d gravity(0, 0, -9.81);
  for (int n = 0; n < 200; ++n) {
    const Vector6d q = random_q();
    Eigen::Isometry3d T[7];
    T[0] = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 6; ++i) T[i + 1] = T[i] * dh_link(q[i], kD[i], kA[i], kAlpha[i]);
    Matrix6d M = Matrix6d::Zero();
    Vector6d tau_g = Vector6d::Zero();
    for (const DhBody& b : kBodies) {
      const Eigen::Vector3d c = T[b.frame] * b.r;
      const Eigen::Matrix3d R = T[b.frame].linear();
      Eigen::Matrix<double, 3, 6> Jv = Eigen::Matrix<double, 3, 6>::Zero(), Jw = Jv;
      for (int j = 0; j < b.frame; ++j) {  // joint j+1 turns about z of DH frame j
        Jw.col(j) = T[j].linear().col(2);
        Jv.col(j) = Jw.col(j).cross(c - T[j].translation());
      }
      M += b.m * Jv.transpose() * Jv + Jw.transpose() * R * b.I.asDiagonal() * R.transpose() * Jw;
      tau_g -= b.m * Jv.transpose() * gravity;
    }
    EXPECT_LE((model.mass_matrix(q) - M).cwiseAbs().maxCoeff(), 1e-9 * M.cwiseAbs().maxCoeff())
        << "q = " << q.transpose();
    EXPECT_LE((model.gravity_torques(q, gravity) - tau_g).norm(), 1e-9 * tau_g.norm());
  }
}

TEST_F(PumaTest, CoriolisMatchesChristoffelSymbolsOfTheMassMatrix) {
  // c_i = (dM/dt qd)_i - 1/2 qd^T (dM/dq_i) qd, the derivatives by central differences of the
  // mass matrix (itself checked against the paper's bodies above).
  const double h = 1e-5;
  for (int n = 0; n < 100; ++n) {
    const Vector6d q = random_q(), qd = random_vector(2.0);
    Matrix6d dM[6];
    for (int k = 0; k < 6; ++k) {
      Vector6d qp = q, qm = q;
      qp[k] += h;
      qm[k] -= h;
      dM[k] = (model.mass_matrix(qp) - model.mass_matrix(qm)) / (2 * h);
    }
    Matrix6d Mdot = Matrix6d::Zero();
    for (int k = 0; k < 6; ++k) Mdot += dM[k] * qd[k];
    Vector6d c = Mdot * qd;
    for (int i = 0; i < 6; ++i) c[i] -= 0.5 * qd.dot(dM[i] * qd);
    EXPECT_LE((model.coriolis(q, qd) - c).norm(), 1e-6 * std::max(1.0, c.norm())) << "q = " << q.transpose();
  }
}

TEST_F(PumaTest, InverseAndForwardDynamicsAgree) {
  for (bool rotor : {false, true}) {
    if (rotor) model.set_rotor_inertia(load_drive_params(kDrive).reflected_inertia());
    for (int n = 0; n < 1000; ++n) {
      const Vector6d q = random_q(), qd = random_vector(2.0), tau = random_vector(50.0);
      const Vector6d qdd = model.forward_dynamics(q, qd, tau);
      const Vector6d back = model.rnea(q, qd, qdd);
      EXPECT_LE((back - tau).norm(), 1e-9 * tau.norm()) << "rotor " << rotor;
      // And the split M qdd + C + g = tau.
      const Vector6d split = model.mass_matrix(q) * qdd + model.coriolis(q, qd) + model.gravity_torques(q);
      EXPECT_LE((split - tau).norm(), 1e-9 * tau.norm());
    }
  }
}

TEST_F(PumaTest, GravityTorquesOfTheStretchedArmByHand) {
  // Arm stretched along +x: q = (0, 0, -90, 0, 0, 0) deg. Joints 2, 3 and 5 turn about -y
  // through x = 0, x = a2 and x = a2 + d4; every centre of mass lies in the plane y = -d3 (or
  // its own), and its x follows from the paper's COM vectors (DH frame i axes at this pose:
  // link 2: x2 = +x; link 3: z3 = +x; link 4: y4 = +x; link 6: z6 = +x):
  const double g = 9.81, a2 = 0.4318, d4 = 0.4318;
  struct Mass {
    double m, x;
  };
  const Mass arm[] = {
      {17.4, a2 - 0.3638},      // link 2, r2 = (-0.3638, 0.006, 0.2275)
      {4.8, a2 + 0.070},        // link 3, r3 = (-0.0203, -0.0141, 0.070)
      {0.82, a2 + d4 + 0.019},  // link 4, r4 = (0, 0.019, 0)
      {0.34, a2 + d4},          // link 5, r5 = 0
      {0.09, a2 + d4 + 0.032},  // link 6, r6 = (0, 0, 0.032)
  };
  const double wc = a2 + d4 + kFlange;  // the flange face
  const Mass tool[] = {
      {0.4, wc + 0.02},     // F/T sensor body, centred 0.02 beyond the flange
      {1.08, wc + 0.045},   // plate, 0.04 .. 0.05 beyond the flange
      {0.0763, wc + 0.07},  // knob, 0.05 .. 0.09 beyond the flange
  };
  double arm2 = 0, arm3 = 0;
  for (int i = 0; i < 5; ++i) {
    arm2 += arm[i].m * g * arm[i].x;                     // joint 2 carries links 2..6
    if (i >= 1) arm3 += arm[i].m * g * (arm[i].x - a2);  // joint 3 carries links 3..6
  }
  double tau2 = arm2, tau3 = arm3;
  double tau5 = 0.09 * g * 0.032;  // joint 5 carries link 5 (COM on its axis) and link 6
  for (const Mass& b : tool) {
    tau2 += b.m * g * b.x;
    tau3 += b.m * g * (b.x - a2);
    tau5 += b.m * g * (b.x - a2 - d4);
  }
  // The arm alone gives the Robotics Toolbox's gravload(qs) = (0, 46.0069, 8.7722, 0, ...).
  EXPECT_NEAR(arm2, 46.0069, 1e-3);
  EXPECT_NEAR(arm3, 8.7722, 1e-3);

  Vector6d qs;
  qs << 0, 0, -90 * kDeg, 0, 0, 0;
  const Vector6d tau = model.gravity_torques(qs);
  EXPECT_NEAR(tau[0], 0.0, 1e-9);
  EXPECT_NEAR(tau[1], tau2, 1e-9);
  EXPECT_NEAR(tau[2], tau3, 1e-9);
  EXPECT_NEAR(tau[3], 0.0, 1e-9);
  EXPECT_NEAR(tau[4], tau5, 1e-9);
  EXPECT_NEAR(tau[5], 0.0, 1e-9);
  // Gravity along another direction is just another vector: turned upside down, all flip.
  EXPECT_LE((model.gravity_torques(qs, Eigen::Vector3d(0, 0, 9.81)) + tau).norm(), 1e-12);
}

TEST_F(PumaTest, DriveFile) {
  const DriveParams drive = load_drive_params(kDrive);
  const double G[6] = {-62.6111, 107.815, -53.7063, 76.0364, 71.923, 76.686};
  const double Jm[6] = {200e-6, 200e-6, 200e-6, 33e-6, 33e-6, 33e-6};
  const Vector6d reflected = drive.reflected_inertia();
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(reflected[j], Jm[j] * G[j] * G[j], 1e-12) << j;
  const Vector6d q = random_q();
  const Matrix6d M0 = model.mass_matrix(q);
  model.set_rotor_inertia(reflected);
  const Matrix6d M1 = model.mass_matrix(q);
  EXPECT_LE((M1 - M0 - Matrix6d(reflected.asDiagonal())).cwiseAbs().maxCoeff(), 1e-12);
  // Friction opposes motion at the joint whatever the gear's sign.
  const Vector6d qd = random_vector(1.0);
  const Vector6d tf = drive.friction_torque(qd);
  for (int j = 0; j < 6; ++j) EXPECT_GT(tf[j] * qd[j], 0.0) << j;
  EXPECT_THROW(load_drive_params(kDrive + ".missing"), std::runtime_error);
}

// ---- load errors name the file and what is wrong

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A file in the temporary directory for the lifetime of the object.
struct TempFile {
  std::string path;
  TempFile(const std::string& name, const std::string& text)
      : path(
            (std::filesystem::temp_directory_path() / ("wysiwyf_test_robot_" + std::to_string(::getpid()) + "_" + name))
                .string()) {
    std::ofstream(path) << text;
  }
  ~TempFile() { std::filesystem::remove(path); }
};

// Replaces the first `from` after `anchor` in the URDF text.
std::string edit(const std::string& anchor, const std::string& from, const std::string& to) {
  std::string text = read_file(kUrdf);
  const auto at = text.find(from, text.find(anchor));
  EXPECT_NE(at, std::string::npos) << anchor << " / " << from;
  return text.replace(at, from.size(), to);
}

void expect_load_error(const std::string& path, const std::string& tip, const std::string& fragment) {
  try {
    PumaModel m(path, tip);
    ADD_FAILURE() << "loaded " << path << " without error, expected: " << fragment;
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(PumaModelLoad, ErrorsNameTheFileAndTheProblem) {
  expect_load_error(kUrdf + ".missing", "flange", "cannot open");
  expect_load_error(kUrdf, "nope", "no link 'nope'");
  expect_load_error(kUrdf, "link4", "found 4 revolute joints");
  const TempFile axis("axis.urdf", edit("<joint name=\"joint3\"", "<axis xyz=\"0 0 1\"/>", "<axis xyz=\"0 1 0\"/>"));
  expect_load_error(axis.path, "flange", "joint 'joint3' has axis");
  const TempFile twist("twist.urdf", edit("<joint name=\"joint5\"", "rpy=\"1.5707963267948966 0 0\"", "rpy=\"0 0 0\""));
  expect_load_error(twist.path, "flange", "alpha4");
  const TempFile prismatic("prismatic.urdf", edit("<joint name=\"joint2\"", "type=\"revolute\"", "type=\"prismatic\""));
  expect_load_error(prismatic.path, "flange", "joint 'joint2' is prismatic");
  const TempFile broken("broken.urdf", "<robot name=\"x\"><link name=\"a\"></robot>");
  expect_load_error(broken.path, "flange", "not a valid URDF");
}

// The IK takes its geometry from the URDF: another pedestal (d1) and a base mounted shifted and
// turned still invert the FK.
TEST(PumaModelLoad, AnotherMountAndPedestal) {
  std::string text = edit("<joint name=\"joint2\"", "<origin xyz=\"0 0 0.6718\"", "<origin xyz=\"0 0 0.8\"");
  const auto at = text.find("<origin xyz=\"0 0 0\" rpy=\"0 0 0\"/>", text.find("<joint name=\"joint1\""));
  ASSERT_NE(at, std::string::npos);
  text.replace(at, std::string("<origin xyz=\"0 0 0\" rpy=\"0 0 0\"/>").size(),
               "<origin xyz=\"0.1 -0.2 0.05\" rpy=\"0.02 -0.01 0.3\"/>");
  const TempFile file("mount.urdf", text);
  const PumaModel model(file.path);
  EXPECT_NEAR(model.dh().d[0], 0.8, 1e-12);
  Eigen::Isometry3d base_T_dh0 = translation(0.1, -0.2, 0.05);
  base_T_dh0.rotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                    Eigen::AngleAxisd(-0.01, Eigen::Vector3d::UnitY()) *
                    Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitX()));
  std::mt19937_64 rng(5);
  for (int n = 0; n < 500; ++n) {
    Vector6d q;
    for (int j = 0; j < 6; ++j) q[j] = std::uniform_real_distribution<double>(kLower[j], kUpper[j])(rng);
    Eigen::Isometry3d expected = base_T_dh0;
    for (int i = 0; i < 6; ++i) expected = expected * dh_link(q[i], i == 0 ? 0.8 : kD[i], kA[i], kAlpha[i]);
    expected = expected * translation(0, 0, kFlange);
    const Eigen::Isometry3d got = model.fk(q);
    ASSERT_LE(position_error(got, expected), 1e-9);
    ASSERT_LE(rotation_error(got, expected), 1e-9);
    const IkResult r = model.ik_nearest(got, q);
    ASSERT_TRUE(r.ok()) << to_string(r.status);
    EXPECT_LE(position_error(model.fk(r.q), got), 1e-9);
    EXPECT_LE(rotation_error(model.fk(r.q), got), 1e-9);
  }
}

TEST(PumaUrdf, CheckUrdfAcceptsIt) {
  const std::string cmd = "check_urdf '" + kUrdf + "' > /dev/null 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd << " (check_urdf is in package liburdfdom-tools)";
}

}  // namespace
}  // namespace wysiwyf::robot
