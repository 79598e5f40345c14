// PumaModel's constructor: reads the URDF, checks it is the PUMA's serial chain and
// precomputes everything the hot calls use (joint origins, frames, merged body inertias).
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

#include <urdf_parser/urdf_parser.h>

#include "puma_model/puma_model.hpp"
#include "puma_model/urdf_parts.hpp"

namespace wysiwyf::robot {

PumaModel::PumaModel(const std::string& urdf_path, const std::string& tip, const std::string& base)
    : urdf_path_(urdf_path) {
  load(tip, base);
  derive_ik_constants();
}

void PumaModel::fail(const std::string& what) const {
  throw std::runtime_error("PumaModel: " + urdf_path_ + ": " + what);
}

std::size_t PumaModel::check(FrameId f) const {
  if (f.index < 0 || static_cast<std::size_t>(f.index) >= frames_.size())
    throw std::out_of_range("PumaModel: invalid FrameId " + std::to_string(f.index));
  return static_cast<std::size_t>(f.index);
}

FrameId PumaModel::frame(const std::string& name) const { return frame_named(frames_, name, "PumaModel", urdf_path_); }

std::vector<std::string> PumaModel::frame_names() const { return frame_names_of(frames_); }

void PumaModel::load(const std::string& tip, const std::string& base) {
  {
    std::ifstream in(urdf_path_);
    if (!in) fail("cannot open the file");
  }
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDFFile(urdf_path_);
  if (!model) fail("not a valid URDF (urdfdom's messages above say why)");
  const urdf::LinkConstSharedPtr base_link = model->getLink(base);
  if (!base_link) fail("no link '" + base + "' (the base of the chain)");
  const urdf::LinkConstSharedPtr tip_link = model->getLink(tip);
  if (!tip_link) fail("no link '" + tip + "' (the tip of the chain)");

  // The chain: joints from the tip up to the base.
  std::vector<urdf::JointConstSharedPtr> path;
  for (urdf::LinkConstSharedPtr link = tip_link; link->name != base;) {
    const urdf::JointConstSharedPtr joint = link->parent_joint;
    if (!joint) fail("link '" + tip + "' is not below link '" + base + "'");
    path.push_back(joint);
    link = model->getLink(joint->parent_link_name);
    if (!link) fail("joint '" + joint->name + "' has no parent link '" + joint->parent_link_name + "'");
  }
  int moving = 0;
  for (auto it = path.rbegin(); it != path.rend(); ++it) {
    const auto& joint = **it;
    if (joint.type == urdf::Joint::FIXED) continue;
    if (joint.type != urdf::Joint::REVOLUTE)
      fail("joint '" + joint.name + "' is " + joint_type_name(joint.type) +
           "; the chain needs revolute joints with position limits");
    if (moving == kDof) fail("more than 6 revolute joints from '" + base + "' to '" + tip + "'");
    const std::size_t j = static_cast<std::size_t>(moving++);
    joint_names_[j] = joint.name;
    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    if ((axis - Eigen::Vector3d::UnitZ()).norm() > 1e-12)
      fail("joint '" + joint.name + "' has axis (" + std::to_string(axis.x()) + " " + std::to_string(axis.y()) + " " +
           std::to_string(axis.z()) + "); every joint axis must be local z (0 0 1), DH style");
    if (!joint.limits) fail("joint '" + joint.name + "' has no <limit>");
    const auto& lim = *joint.limits;
    if (!(lim.lower < lim.upper)) fail("joint '" + joint.name + "' has lower limit >= upper limit");
    if (!(lim.velocity > 0.0) || !(lim.effort > 0.0))
      fail("joint '" + joint.name + "' needs velocity and effort limits > 0");
    limits_.lower[j] = lim.lower;
    limits_.upper[j] = lim.upper;
    limits_.velocity[j] = lim.velocity;
    limits_.effort[j] = lim.effort;
  }
  if (moving != kDof)
    fail("found " + std::to_string(moving) + " revolute joints from '" + base + "' to '" + tip + "', need 6");

  // Every link from the base down: which moving body it is fixed to, and where.
  std::array<InertiaSum, kDof + 1> sums;
  frames_.clear();
  std::function<void(const urdf::LinkConstSharedPtr&, int, const Eigen::Matrix3d&, const Eigen::Vector3d&)> visit =
      [&](const urdf::LinkConstSharedPtr& link, int body, const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
        frames_.push_back(Frame{link->name, body, R, p});
        if (const auto& in = link->inertial) {
          if (!(in->mass >= 0.0) || !std::isfinite(in->mass)) fail("link '" + link->name + "' has a mass < 0");
          Eigen::Matrix3d I;
          I << in->ixx, in->ixy, in->ixz, in->ixy, in->iyy, in->iyz, in->ixz, in->iyz, in->izz;
          if (!I.allFinite()) fail("link '" + link->name + "' has a non-finite inertia");
          const Eigen::Matrix3d Rc = R * isometry_of(in->origin).linear();
          sums[static_cast<std::size_t>(body)].add(in->mass, p + R * isometry_of(in->origin).translation(),
                                                   Rc * I * Rc.transpose());
        }
        for (const auto& joint : link->child_joints) {
          const urdf::LinkConstSharedPtr child = model->getLink(joint->child_link_name);
          const Eigen::Matrix3d Ro = isometry_of(joint->parent_to_joint_origin_transform).linear();
          const Eigen::Vector3d po = isometry_of(joint->parent_to_joint_origin_transform).translation();
          int j = -1;
          for (int k = 0; k < kDof; ++k)
            if (joint_names_[static_cast<std::size_t>(k)] == joint->name) j = k;
          if (j >= 0) {
            if (j != body) fail("joint '" + joint->name + "' is out of order in the chain");
            joints_[static_cast<std::size_t>(j)] = JointOrigin{R * Ro, p + R * po};
            visit(child, j + 1, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
          } else if (joint->type == urdf::Joint::FIXED) {
            visit(child, body, R * Ro, p + R * po);
          } else {
            fail("joint '" + joint->name + "' (" + joint_type_name(joint->type) + ") branches off the chain at link '" +
                 link->name + "'; the model handles one serial chain with links fixed to it");
          }
        }
      };
  visit(base_link, 0, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k <= kDof; ++k) bodies_[k] = sums[k].body();
  tip_ = frame(tip);
}

void PumaModel::derive_ik_constants() {
  // Joint j+1's origin holds link j's DH bracket Tz(d) Tx(a) Rx(alpha) (see puma560.urdf).
  constexpr double kTol = 1e-9;
  for (int i = 0; i < 5; ++i) {
    const JointOrigin& o = joints_[static_cast<std::size_t>(i + 1)];
    const std::string& name = joint_names_[static_cast<std::size_t>(i + 1)];
    const Eigen::Matrix3d& R = o.R;
    if (std::abs(R(0, 0) - 1.0) > kTol || std::abs(R(0, 1)) > kTol || std::abs(R(0, 2)) > kTol ||
        std::abs(R(1, 0)) > kTol || std::abs(R(2, 0)) > kTol || std::abs(o.p.y()) > kTol)
      fail("the origin of joint '" + name +
           "' is not a DH bracket: need xyz=\"a 0 d\" rpy=\"alpha 0 0\" (the closed-form IK needs it)");
    dh_.a[i] = o.p.x();
    dh_.d[i] = o.p.z();
    dh_.alpha[i] = std::atan2(R(2, 1), R(1, 1));
  }
  constexpr double kHalfPi = 1.5707963267948966;
  const double alpha[5] = {kHalfPi, 0.0, -kHalfPi, kHalfPi, -kHalfPi};
  std::ostringstream bad;
  for (int i = 0; i < 5; ++i)
    if (std::abs(dh_.alpha[i] - alpha[i]) > kTol)
      bad << " alpha" << i + 1 << " = " << dh_.alpha[i] << " (need " << alpha[i] << ")";
  if (std::abs(dh_.a[3]) > kTol) bad << " a4 = " << dh_.a[3] << " (need 0)";
  if (std::abs(dh_.a[4]) > kTol) bad << " a5 = " << dh_.a[4] << " (need 0)";
  if (std::abs(dh_.d[4]) > kTol) bad << " d5 = " << dh_.d[4] << " (need 0)";
  if (!(dh_.a[1] > kTol)) bad << " a2 = " << dh_.a[1] << " (need > 0)";
  if (std::hypot(dh_.a[2], dh_.d[3]) < kTol) bad << " a3 = d4 = 0 (need a forearm)";
  if (!bad.str().empty()) fail("not a PUMA 560 geometry (spherical wrist, DH twists 90 0 -90 90 -90):" + bad.str());

  ikc_.d1 = dh_.d[0];
  ikc_.a1 = dh_.a[0];
  ikc_.shoulder_offset = dh_.d[1] + dh_.d[2];
  ikc_.a2 = dh_.a[1];
  ikc_.l3 = std::hypot(dh_.a[2], dh_.d[3]);
  ikc_.beta = std::atan2(dh_.d[3], dh_.a[2]);
  ikc_.cos_beta = std::cos(ikc_.beta);
  ikc_.sin_beta = std::sin(ikc_.beta);
  ikc_.mount_R = joints_[0].R;
  ikc_.mount_p = joints_[0].p;
}

}  // namespace wysiwyf::robot
