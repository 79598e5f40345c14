// ArmModel's constructor: reads the URDF, finds the serial chain from the base to the tip,
// fixes every other link to a body of it, merges the bodies' inertias, reads the limits and the
// collision elements; then builds the KDL workspace and picks the IK method.
#include <cmath>
#include <fstream>
#include <functional>
#include <stdexcept>

#include <urdf_parser/urdf_parser.h>

#include "arm_model/arm_model.hpp"
#include "arm_model/kdl_parts.hpp"
#include "arm_model/urdf_collision.hpp"
#include "puma_model/puma_model.hpp"
#include "puma_model/urdf_parts.hpp"

namespace wysiwyf::robot {
const char* to_string(ArmIkMethod method) {
  switch (method) {
    case ArmIkMethod::kPumaClosedForm: return "PUMA closed form";
    case ArmIkMethod::kUrClosedForm: return "UR closed form";
    case ArmIkMethod::kNumerical: return "numerical";
  }
  return "unknown";
}

ArmModel::ArmModel(const std::string& urdf_path, const std::string& tip, const std::string& base)
    : urdf_path_(urdf_path) {
  load(tip, base);
  build_kdl();
  choose_ik(tip, base);
  make_seeds();
}

ArmModel::ArmModel(const ArmModel& other)
    : urdf_path_(other.urdf_path_),
      joint_names_(other.joint_names_),
      joints_(other.joints_),
      limits_(other.limits_),
      bodies_(other.bodies_),
      frames_(other.frames_),
      body_frames_(other.body_frames_),
      tip_(other.tip_),
      collision_(other.collision_),
      collision_notes_(other.collision_notes_),
      links_without_collision_(other.links_without_collision_),
      rotor_inertia_(other.rotor_inertia_),
      ik_method_(other.ik_method_),
      ik_options_(other.ik_options_),
      seeds_(other.seeds_),
      dh_(other.dh_),
      puma_(other.puma_),
      puma_frames_(other.puma_frames_),
      kdl_(std::make_unique<detail::KdlParts>(*other.kdl_)) {}

ArmModel& ArmModel::operator=(const ArmModel& other) {
  if (this != &other) *this = ArmModel(other);
  return *this;
}

ArmModel::ArmModel(ArmModel&& other) noexcept = default;
ArmModel& ArmModel::operator=(ArmModel&& other) noexcept = default;
ArmModel::~ArmModel() = default;

void ArmModel::fail(const std::string& what) const {
  throw std::runtime_error("ArmModel: " + urdf_path_ + ": " + what);
}

std::size_t ArmModel::check(FrameId f) const {
  if (f.index < 0 || static_cast<std::size_t>(f.index) >= frames_.size())
    throw std::out_of_range("ArmModel: invalid FrameId " + std::to_string(f.index));
  return static_cast<std::size_t>(f.index);
}

void ArmModel::check_size(const JointRef& v, const char* what) const {
  if (v.size() != dof())
    throw std::invalid_argument(std::string("ArmModel: ") + what + " has " + std::to_string(v.size()) +
                                " values, the arm has " + std::to_string(dof()) + " joints");
}

FrameId ArmModel::frame(const std::string& name) const { return frame_named(frames_, name, "ArmModel", urdf_path_); }

std::vector<std::string> ArmModel::frame_names() const { return frame_names_of(frames_); }

void ArmModel::set_rotor_inertia(const JointRef& reflected) {
  check_size(reflected, "rotor inertia");
  rotor_inertia_ = reflected;
}

void ArmModel::load(const std::string& tip, const std::string& base) {
  if (!std::ifstream(urdf_path_)) fail("cannot open the file");
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDFFile(urdf_path_);
  if (!model) fail("not a valid URDF (urdfdom's messages above say why)");
  const urdf::LinkConstSharedPtr base_link = model->getLink(base);
  if (!base_link) fail("no link '" + base + "' (the base of the chain)");
  const urdf::LinkConstSharedPtr tip_link = model->getLink(tip);
  if (!tip_link) fail("no link '" + tip + "' (the tip of the chain)");

  // The chain: the moving joints on the way from the tip up to the base.
  std::vector<urdf::JointConstSharedPtr> path;
  for (urdf::LinkConstSharedPtr link = tip_link; link->name != base;) {
    const urdf::JointConstSharedPtr joint = link->parent_joint;
    if (!joint) fail("link '" + tip + "' is not below link '" + base + "'");
    if (joint->type != urdf::Joint::FIXED) path.insert(path.begin(), joint);
    link = model->getLink(joint->parent_link_name);
    if (!link) fail("joint '" + joint->name + "' has no parent link '" + joint->parent_link_name + "'");
  }
  if (path.empty()) fail("no moving joint from '" + base + "' to '" + tip + "'");
  if (path.size() > static_cast<std::size_t>(kMaxArmDof))
    fail(std::to_string(path.size()) + " moving joints from '" + base + "' to '" + tip + "'; the model holds at most " +
         std::to_string(kMaxArmDof));
  const int n = static_cast<int>(path.size());
  limits_.lower.resize(n);
  limits_.upper.resize(n);
  limits_.velocity.resize(n);
  limits_.effort.resize(n);
  joints_.assign(path.size(), Joint{});
  for (int j = 0; j < n; ++j) {
    const urdf::Joint& joint = *path[static_cast<std::size_t>(j)];
    Joint& out = joints_[static_cast<std::size_t>(j)];
    joint_names_.push_back(joint.name);
    switch (joint.type) {
      case urdf::Joint::REVOLUTE: out.kind = JointKind::kRevolute; break;
      case urdf::Joint::CONTINUOUS: out.kind = JointKind::kContinuous; break;
      case urdf::Joint::PRISMATIC: out.kind = JointKind::kPrismatic; break;
      default:
        fail("joint '" + joint.name + "' is " + joint_type_name(joint.type) +
             "; the chain takes revolute, continuous and prismatic joints");
    }
    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    if (!(axis.norm() > 1e-9) || !axis.allFinite()) fail("joint '" + joint.name + "' has a zero or non-finite axis");
    out.axis = axis.normalized();
    if (!joint.limits)
      fail("joint '" + joint.name + "' (" + joint_type_name(joint.type) +
           ") has no <limit>: velocity and effort limits are needed (and position limits unless continuous)");
    const urdf::JointLimits& lim = *joint.limits;
    if (out.kind == JointKind::kContinuous) {
      limits_.lower[j] = -std::numeric_limits<double>::infinity();
      limits_.upper[j] = std::numeric_limits<double>::infinity();
    } else {
      if (!(lim.lower < lim.upper))
        fail("joint '" + joint.name + "' has lower limit " + std::to_string(lim.lower) + " >= upper limit " +
             std::to_string(lim.upper));
      limits_.lower[j] = lim.lower;
      limits_.upper[j] = lim.upper;
    }
    if (!(lim.velocity > 0.0) || !(lim.effort > 0.0))
      fail("joint '" + joint.name + "' needs velocity and effort limits > 0 (has " + std::to_string(lim.velocity) +
           ", " + std::to_string(lim.effort) + ")");
    limits_.velocity[j] = lim.velocity;
    limits_.effort[j] = lim.effort;
  }
  rotor_inertia_ = JointVector::Zero(n);

  // Every link from the base down: which body it is fixed to, where, its inertia and collision.
  std::vector<InertiaSum> sums(static_cast<std::size_t>(n + 1));
  frames_.clear();
  std::function<void(const urdf::LinkConstSharedPtr&, int, const Eigen::Isometry3d&)> visit =
      [&](const urdf::LinkConstSharedPtr& link, int body, const Eigen::Isometry3d& body_T_link) {
        const FrameId id{static_cast<int>(frames_.size())};
        frames_.push_back(Frame{link->name, body, body_T_link});
        if (body_frames_.size() == static_cast<std::size_t>(body)) body_frames_.push_back(id);
        if (const auto& in = link->inertial) {
          if (!(in->mass >= 0.0) || !std::isfinite(in->mass)) fail("link '" + link->name + "' has a mass < 0");
          Eigen::Matrix3d I;
          I << in->ixx, in->ixy, in->ixz, in->ixy, in->iyy, in->iyz, in->ixz, in->iyz, in->izz;
          if (!I.allFinite()) fail("link '" + link->name + "' has a non-finite inertia");
          const Eigen::Isometry3d body_T_com = body_T_link * isometry_of(in->origin);
          sums[static_cast<std::size_t>(body)].add(in->mass, body_T_com.translation(),
                                                   body_T_com.linear() * I * body_T_com.linear().transpose());
        }
        if (link->collision_array.empty() && !link->collision) links_without_collision_.push_back(link->name);
        detail::collect_collision(*link, id, body, body_T_link, collision_, collision_notes_);
        for (const auto& joint : link->child_joints) {
          const urdf::LinkConstSharedPtr child = model->getLink(joint->child_link_name);
          const Eigen::Isometry3d body_T_joint = body_T_link * isometry_of(joint->parent_to_joint_origin_transform);
          if (joint->type == urdf::Joint::FIXED) {
            visit(child, body, body_T_joint);
            continue;
          }
          int j = -1;
          for (int k = 0; k < n; ++k)
            if (path[static_cast<std::size_t>(k)]->name == joint->name) j = k;
          if (j < 0)
            fail("joint '" + joint->name + "' (" + joint_type_name(joint->type) + ") at link '" + link->name +
                 "' is off the chain from '" + base + "' to '" + tip +
                 "'; the model holds one serial chain with links fixed to it");
          if (j != body) fail("joint '" + joint->name + "' is out of order in the chain");
          joints_[static_cast<std::size_t>(j)].body_T_origin = body_T_joint;
          visit(child, j + 1, Eigen::Isometry3d::Identity());
        }
      };
  visit(base_link, 0, Eigen::Isometry3d::Identity());
  bodies_.clear();
  for (const InertiaSum& s : sums) bodies_.push_back(s.body());
  tip_ = frame(tip);
}

void ArmModel::choose_ik(const std::string& tip, const std::string& base) {
  const int n = dof();
  bool revolute = true;
  for (const Joint& j : joints_) revolute = revolute && j.kind != JointKind::kPrismatic;
  if (n != 6 || !revolute) return;  // numerical
  // The PUMA 560 geometry: PumaModel's loader checks it (DH layout, twists, wrist) and refuses
  // anything else, so a PumaModel that loads is the closed form of this very chain.
  try {
    puma_ = std::make_shared<const PumaModel>(urdf_path_, tip, base);
  } catch (const std::exception&) {
    puma_.reset();
  }
  if (puma_) {
    for (const Frame& fr : frames_) {
      FrameId id;
      try {
        id = puma_->frame(fr.name);
      } catch (const std::out_of_range&) {
      }
      puma_frames_.push_back(id);
    }
    ik_method_ = ArmIkMethod::kPumaClosedForm;
    return;
  }
  // UR-type geometry, from the axes at q = 0 wherever the URDF puts its frames.
  std::array<detail::AxisLine, kMaxArmDof> axes;
  const JointVector zero = JointVector::Zero(n);
  for (int j = 0; j < n; ++j) {
    const Joint& jt = joints_[static_cast<std::size_t>(j)];
    const Eigen::Isometry3d base_T_origin = body_pose(zero, j) * jt.body_T_origin;
    axes[static_cast<std::size_t>(j)].point = base_T_origin.translation();
    axes[static_cast<std::size_t>(j)].direction = base_T_origin.linear() * jt.axis;
  }
  const detail::DhChain dh = detail::dh_from_axes(axes.data(), n, body_pose(zero, n));
  if (!detail::ur_geometry_mismatch(dh).empty()) return;
  // The DH product must reproduce the chain (it does by construction; this guards the derivation).
  for (int k = 0; k < 8; ++k) {
    JointVector q(n);
    for (int j = 0; j < n; ++j) q[j] = std::sin(1.3 * (k + 1) + 0.7 * j) * 3.0;
    const Eigen::Isometry3d a = detail::dh_forward(dh, q), b = body_pose(q, n);
    if ((a.matrix() - b.matrix()).norm() > 1e-9) return;
  }
  dh_ = dh;
  ik_method_ = ArmIkMethod::kUrClosedForm;
}

}  // namespace wysiwyf::robot
