#pragma once
// A serial arm loaded from any URDF: the chain of n revolute, continuous or prismatic joints
// (n <= kMaxArmDof) from a base link to a tip link, with every other link fixed to it as an
// extra named frame (flange, ft_sensor, dev, marker_0..3, knob, ...), the joint limits, the
// merged body inertias and the collision shapes. Kinematics and dynamics run on the Orocos
// Kinematics and Dynamics Library (KDL) behind an Eigen interface; IK is closed form where the
// chain has one (PUMA 560 by PumaModel, UR-type 6R) and numerical otherwise.
//
// Poses are base_T_<frame> (the frame expressed in the base link); Jacobians are geometric,
// [v; w] of the frame's origin in base coordinates, as in PumaModel.
//
// The hot calls (fk, jacobian, ik, ik_nearest, dls_step, rnea, mass_matrix, gravity_torques,
// coriolis, forward_dynamics) allocate nothing: they use the workspace the constructor sized
// (KDL's solvers and buffers) and return inline-storage Eigen types. Because they share that
// workspace, one ArmModel serves one thread at a time; give each thread its own copy (a copy
// builds its own workspace and reads no file).
#include <memory>
#include <string>
#include <vector>

#include "arm_model/arm_ik.hpp"
#include "arm_model/arm_types.hpp"
#include "arm_model/collision_shape.hpp"
#include "arm_model/dh_geometry.hpp"

namespace wysiwyf::robot {

class PumaModel;
namespace detail {
struct KdlParts;
}

class ArmModel {
 public:
  // Loads the URDF at `urdf_path`. Throws std::runtime_error naming the file and what is wrong:
  // unreadable or malformed file, no link `base` or `tip`, `tip` not below `base`, no moving
  // joint or more than kMaxArmDof, a floating or planar joint on the chain, a moving joint off
  // the chain, missing or inconsistent limits (a continuous joint still needs velocity and
  // effort limits), a zero axis, a negative mass or non-finite inertia.
  explicit ArmModel(const std::string& urdf_path, const std::string& tip = "flange",
                    const std::string& base = "base_link");
  // Copies build their own workspace (KDL solvers), so a copy may run on another thread.
  ArmModel(const ArmModel& other);
  ArmModel& operator=(const ArmModel& other);
  ArmModel(ArmModel&& other) noexcept;
  ArmModel& operator=(ArmModel&& other) noexcept;
  ~ArmModel();

  // ---- description
  // The file the model was loaded from.
  const std::string& urdf_path() const { return urdf_path_; }
  // The number of moving joints n.
  int dof() const { return static_cast<int>(joints_.size()); }
  // Joint names from base to tip.
  const std::vector<std::string>& joint_names() const { return joint_names_; }
  // Whether joint j is revolute, continuous or prismatic.
  JointKind joint_kind(int j) const { return joints_.at(static_cast<std::size_t>(j)).kind; }
  // Position, velocity and effort limits per joint.
  const ArmLimits& limits() const { return limits_; }
  // Mass properties of body k = 0..n (0 = the base; k = the link after joint k with every link
  // fixed to it), in that body's frame.
  const BodyInertia& body(int k) const { return bodies_.at(static_cast<std::size_t>(k)); }

  // ---- frames: every link below the base. Throws std::out_of_range for an unknown name.
  // The id of the frame (URDF link) called `name`.
  FrameId frame(const std::string& name) const;
  // The tip frame (the default frame of fk, jacobian, ik).
  FrameId tip() const { return tip_; }
  // The name of a frame.
  const std::string& frame_name(FrameId f) const { return frames_[check(f)].name; }
  // All frame names, base first.
  std::vector<std::string> frame_names() const;
  // The body (0..n) a frame is fixed to.
  int frame_body(FrameId f) const { return frames_[check(f)].body; }
  // The frame of body k's own link (k = 0: the base link; else the child link of joint k),
  // whose origin lies on joint k's axis.
  FrameId body_frame(int k) const { return body_frames_.at(static_cast<std::size_t>(k)); }
  // The frame's pose in its body's frame.
  const Eigen::Isometry3d& body_T_frame(FrameId f) const { return frames_[check(f)].body_T_frame; }

  // ---- collision shapes from the URDF's <collision> elements
  // Every collision element of every link below the base, meshes included (supported() false).
  const std::vector<CollisionShape>& collision_shapes() const { return collision_; }
  // One line per collision element the model cannot use yet (meshes), empty when none.
  const std::vector<std::string>& collision_notes() const { return collision_notes_; }
  // Links that have no <collision> element at all.
  const std::vector<std::string>& links_without_collision() const { return links_without_collision_; }

  // ---- kinematics (q: n joint values)
  // Pose of the tip frame.
  Eigen::Isometry3d fk(const JointRef& q) const { return fk(q, tip_); }
  // Pose of frame f.
  Eigen::Isometry3d fk(const JointRef& q, FrameId f) const;
  // Geometric Jacobian of the tip frame: [v; w] of its origin, in base coordinates.
  ArmJacobian jacobian(const JointRef& q) const { return jacobian(q, tip_); }
  // Geometric Jacobian of frame f (columns of joints after f's body are zero).
  ArmJacobian jacobian(const JointRef& q, FrameId f) const;

  // How ik() solves: the closed form found for this chain, or numerical.
  ArmIkMethod ik_method() const { return ik_method_; }
  // Use the numerical IK even where a closed form exists (to compare them).
  void use_numerical_ik() { ik_method_ = ArmIkMethod::kNumerical; }
  // The numerical IK's settings.
  const ArmIkOptions& ik_options() const { return ik_options_; }
  // Changes the numerical IK's settings (and its seeds: this call allocates).
  void set_ik_options(const ArmIkOptions& options);

  // Every solution found for base_T_frame of the tip frame; q_ref picks each angle's 2 pi
  // representative, the closed forms' angle at a wrist singularity, and the numerical IK's first
  // seed and null-space goal.
  ArmIkSolutions ik(const Eigen::Isometry3d& base_T_frame, const JointRef& q_ref) const {
    return ik(base_T_frame, q_ref, tip_);
  }
  // The same for frame f, which must be fixed to the last body (std::invalid_argument otherwise).
  ArmIkSolutions ik(const Eigen::Isometry3d& base_T_frame, const JointRef& q_ref, FrameId f) const;
  // The solution within limits nearest (Euclidean in joint space) to q_current, or why none.
  // Numerical IK: the q_current seed's solution when it lies within ik_options().local_radius of
  // q_current, else the nearest of every seed's.
  ArmIkResult ik_nearest(const Eigen::Isometry3d& base_T_frame, const JointRef& q_current) const {
    return ik_nearest(base_T_frame, q_current, tip_);
  }
  // The same for frame f (fixed to the last body).
  ArmIkResult ik_nearest(const Eigen::Isometry3d& base_T_frame, const JointRef& q_current, FrameId f) const;

  // One damped least squares step towards base_T_target: dq = J^T (J J^T + lambda^2 I)^-1 e,
  // e = [position error; rotation vector of R_target R^T] in base coordinates (apply as q + dq).
  JointVector dls_step(const JointRef& q, const Eigen::Isometry3d& base_T_target, double lambda) const {
    return dls_step(q, base_T_target, lambda, tip_);
  }
  // The same for frame f.
  JointVector dls_step(const JointRef& q, const Eigen::Isometry3d& base_T_target, double lambda, FrameId f) const;

  // ---- dynamics (gravity: acceleration of gravity in base coordinates)
  // Recursive Newton-Euler: joint torques for q, qd, qdd (plus rotor_inertia .* qdd).
  JointVector rnea(const JointRef& q, const JointRef& qd, const JointRef& qdd,
                   const Eigen::Vector3d& gravity = standard_gravity()) const;
  // Joint-space mass matrix (plus rotor inertia on the diagonal).
  JointMatrix mass_matrix(const JointRef& q) const;
  // Torques that hold the arm still against gravity.
  JointVector gravity_torques(const JointRef& q, const Eigen::Vector3d& gravity = standard_gravity()) const;
  // Coriolis and centrifugal torques C(q, qd) qd.
  JointVector coriolis(const JointRef& q, const JointRef& qd) const;
  // qdd = M(q)^-1 (tau - C(q, qd) qd - g(q)).
  JointVector forward_dynamics(const JointRef& q, const JointRef& qd, const JointRef& tau,
                               const Eigen::Vector3d& gravity = standard_gravity()) const;

  // Sets the reflected motor inertia G^2 Jm per joint, added to the mass matrix diagonal and to
  // rnea (zero after construction).
  void set_rotor_inertia(const JointRef& reflected);
  // The reflected motor inertia per joint.
  const JointVector& rotor_inertia() const { return rotor_inertia_; }

 private:
  struct Frame {
    std::string name;
    int body = 0;
    Eigen::Isometry3d body_T_frame = Eigen::Isometry3d::Identity();
  };
  struct Joint {
    JointKind kind = JointKind::kRevolute;
    Eigen::Isometry3d body_T_origin = Eigen::Isometry3d::Identity();  // in the parent body's frame
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();                  // unit, in the joint frame
  };

  // The index of a valid frame id (std::out_of_range otherwise).
  std::size_t check(FrameId f) const;
  // Throws std::invalid_argument unless v has n values.
  void check_size(const JointRef& v, const char* what) const;
  // Throws std::runtime_error naming the file and `what`.
  [[noreturn]] void fail(const std::string& what) const;
  // Reads the URDF: chain, joints, limits, frames, merged bodies, collision shapes.
  void load(const std::string& tip, const std::string& base);
  // Builds the KDL chain and workspace from the loaded joints and bodies.
  void build_kdl();
  // Picks the IK method from the chain's geometry (PUMA, UR-type or numerical).
  void choose_ik(const std::string& tip, const std::string& base);
  // Spreads the numerical IK's seeds over the joint limits (Halton sequence).
  void make_seeds();
  // Pose of body k's frame (KDL up to segment k).
  Eigen::Isometry3d body_pose(const JointRef& q, int body) const;
  // The UR-type closed form for the last body's pose.
  ArmIkSolutions ik_closed_form(const Eigen::Isometry3d& base_T_body, const JointRef& q_ref) const;
  // PumaModel's closed form, its solutions carried over.
  ArmIkSolutions ik_puma(const Eigen::Isometry3d& base_T_frame, const JointRef& q_ref, FrameId f) const;
  // The numerical IK from q_ref and every seed.
  ArmIkSolutions ik_numerical(const Eigen::Isometry3d& base_T_frame, const JointRef& q_ref, FrameId f) const;
  // One numerical solve from `seed`, pulled towards q_goal in the null space; false when it fails.
  bool solve_numerical(const Eigen::Isometry3d& base_T_frame, FrameId f, const JointVector& seed,
                       const JointRef& q_goal, JointVector& q) const;
  // Levenberg-Marquardt on the pose error from q (clamped to limits), within `budget` iterations.
  bool converge(const Eigen::Isometry3d& base_T_frame, FrameId f, JointVector& q, int& budget) const;
  // Appends q, wrapped towards q_ref, unless a duplicate or the list is full.
  void add_solution(ArmIkSolutions& out, const JointVector& q, const JointRef& q_ref, int branch, bool singular) const;

  std::string urdf_path_;
  std::vector<std::string> joint_names_;
  std::vector<Joint> joints_;
  ArmLimits limits_;
  std::vector<BodyInertia> bodies_;
  std::vector<Frame> frames_;
  std::vector<FrameId> body_frames_;
  FrameId tip_;
  std::vector<CollisionShape> collision_;
  std::vector<std::string> collision_notes_;
  std::vector<std::string> links_without_collision_;
  JointVector rotor_inertia_;

  ArmIkMethod ik_method_ = ArmIkMethod::kNumerical;
  ArmIkOptions ik_options_;
  std::vector<JointVector> seeds_;
  detail::DhChain dh_;                     // UR closed form
  std::shared_ptr<const PumaModel> puma_;  // PUMA closed form (immutable, so shared by copies)
  std::vector<FrameId> puma_frames_;       // this model's frame index -> PumaModel's frame
  std::unique_ptr<detail::KdlParts> kdl_;  // the chain, its solvers and buffers
};

}  // namespace wysiwyf::robot
