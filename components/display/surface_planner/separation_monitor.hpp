#pragma once
// Speed and separation monitoring of the plate's planned motion (ISO/TS 15066, robot::SsmParams):
// for each part of the arm (ArmClearance: the collision shapes of its URDF) the
// separation S to the hand and how fast the planned motion carries the part toward it; the path's
// clock may run at the largest rate kappa at which no part approaches faster than the protective
// distance allows at its S. Within it an approaching motion stops; moving away is always allowed.
// Without a tracked hand the plate moves at speed_without_hand at most.
#include <limits>

#include "arm_clearance/arm_clearance.hpp"
#include "arm_clearance/speed_separation.hpp"
#include "arm_model/arm_model.hpp"
#include "plate_path.hpp"

namespace wysiwyf::display {

class SeparationMonitor {
 public:
  // model (its tip the plate's frame) and clearance outlive the monitor; finger_radius: m taken
  // off every separation.
  SeparationMonitor(const robot::ArmModel& model, const robot::ArmClearance& clearance, const robot::SsmParams& ssm,
                    double finger_radius, double speed_without_hand)
      : model_(model),
        clearance_(clearance),
        still_(robot::JointVector::Zero(model.dof())),
        ssm_(ssm),
        finger_radius_(finger_radius),
        without_hand_(speed_without_hand) {}

  // The largest kappa for `path` at joints q with the hand at `hand` (base frame). Judged at the
  // path's current velocity, but never below a tenth of its segment's peak (a straight line at a
  // fixed turn: only the speed varies along it), so a move does not start toward a hand inside
  // the protective distance, and its last millimetres are not held up.
  double kappa(const PlatePath& path, const robot::JointRef& q, const Eigen::Vector3d& hand);
  // The separation from the hand to the arm's nearest part, the arm still.
  void measure(const robot::JointRef& q, const Eigen::Vector3d& hand);
  // The kappa without a tracked hand: the plate at speed_without_hand at most.
  double kappa_without_hand(const PlatePath& path) const;
  // The lowest kappa for the next tick (dt s) at which the plate's speed falls by no more than the
  // arm brakes (a_s dt): the path's own acceleration over the tick counted, or the plate would
  // speed up while kappa falls.
  double braking_kappa(const PlatePath& path, double kappa, double dt) const;

  // From the last kappa() or measure(): m from the hand to the nearest part, its name, and the
  // speed SSM allows toward the hand there.
  double separation() const { return separation_; }
  const char* nearest_part() const { return nearest_part_; }
  double allowed_speed() const { return allowed_; }
  double speed_without_hand() const { return without_hand_; }

 private:
  const robot::ArmModel& model_;
  const robot::ArmClearance& clearance_;
  robot::JointVector still_;  // zero joint rates (the arm still)
  robot::SsmParams ssm_;
  double finger_radius_, without_hand_;
  double separation_ = std::numeric_limits<double>::infinity(), allowed_ = 0;
  const char* nearest_part_ = "";
};

}  // namespace wysiwyf::display
