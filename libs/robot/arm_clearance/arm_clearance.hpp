#pragma once
// The arm as a hand meets it: every box, cylinder and sphere of the arm's URDF <collision>
// elements (its links, the wrist sensor, the plate, its knob and lamps; meshes are not loaded), and
// for a point (the hand) how far each part's surface is and how fast its point nearest the hand
// approaches it (the part's body twist from the Jacobian at the body's frame). What speed and
// separation monitoring (ISO/TS 15066) needs, for the surface planner, the tests and the display's
// metrics alike, on any serial arm ArmModel loads.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "arm_model/arm_model.hpp"

namespace wysiwyf::robot {

struct PartClearance {
  const char* name = "";  // "<link> <shape>", e.g. "dev box"; owned by the ArmClearance
  double distance = 0;    // m from the part's surface to the point (0 inside)
  Eigen::Vector3d nearest =
      Eigen::Vector3d::Zero();  // the part's point nearest the point (the point itself inside), base
  double approach_speed = 0;    // m/s of that point toward the point (negative: moving away)
};

class ArmClearance {
 public:
  // Every supported collision shape of `model` (which outlives the clearance) is a part. Throws
  // std::invalid_argument naming the URDF when it has none.
  explicit ArmClearance(const ArmModel& model);
  // Copies share the model and get their own buffers.
  ArmClearance(const ArmClearance&);
  ArmClearance& operator=(const ArmClearance&) = delete;

  // The number of parts, and part i's name ("<link> <shape>", numbered when a link has several of one shape).
  std::size_t parts() const { return parts_.size(); }
  const std::string& part_name(std::size_t i) const { return names_.at(i); }

  // Every part's clearance to `point` with the arm at q moving at qd (model.dof() values each;
  // std::invalid_argument otherwise), in the order of the parts. The list is this object's buffer,
  // overwritten by the next call (no allocation); like ArmModel, one thread at a time.
  const std::vector<PartClearance>& evaluate(const JointRef& q, const JointRef& qd, const Eigen::Vector3d& point) const;
  // The part nearest `point` in a list evaluate() returned (not empty).
  static const PartClearance& nearest(const std::vector<PartClearance>& parts);

 private:
  struct Part {
    int body = 0;                                                    // the moving body it is fixed to
    Eigen::Isometry3d body_T_shape = Eigen::Isometry3d::Identity();  // its pose in that body's frame
    ShapeType type = ShapeType::kBox;
    Eigen::Vector3d half = Eigen::Vector3d::Zero();  // box: half extents
    double radius = 0, half_length = 0;              // cylinder (along z), sphere
  };

  // The point of `part` (posed at base_T_shape) nearest `point`, in base.
  static Eigen::Vector3d nearest_point(const Part& part, const Eigen::Isometry3d& base_T_shape,
                                       const Eigen::Vector3d& point);

  const ArmModel& model_;
  std::vector<Part> parts_;
  std::vector<std::string> names_;
  std::vector<int> bodies_;  // the bodies that carry a part, each once
  mutable std::vector<PartClearance> out_;
  mutable std::array<Eigen::Isometry3d, kMaxArmDof + 1> base_T_body_;
  mutable std::array<Eigen::Matrix<double, 6, 1>, kMaxArmDof + 1> body_twist_;  // [v; w] of the body frame, base
};

}  // namespace wysiwyf::robot
