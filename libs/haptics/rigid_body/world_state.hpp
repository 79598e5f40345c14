#pragma once
// What a World's motion changes, as MuJoCo's mjData less its scratch: the time, the bodies'
// states, the user's wrenches, the contacts being held and the ones being watched, and what
// the integrator must redo before it goes on.
#include <vector>

#include "scene/body.hpp"
#include "rigid_body/contact.hpp"
#include "rigid_body/lcp.hpp"
#include "rigid_body/world_model.hpp"

namespace wysiwyf::haptics {

struct ActiveContact {
  ContactFeature feature;
  ContactPoint point;
  double force = 0;              // N, normal, from the last LCP
  Vec3 friction = Vec3::Zero();  // N, tangential force on body a (world frame)
};

// The contacts of one island, a set of dynamic bodies that touch one another (a static body
// joins none: a table under two separate cubes leaves them apart), as a range of the resting
// contacts. Each island's contacts are solved alone: an LCP of n contacts costs up to n^3, and
// no force of one island reaches another.
struct ContactIsland {
  std::size_t begin = 0, end = 0;  // its contacts: resting[begin, end)
  std::size_t live = 0;            // of those, the first `live` still face each other (last evaluated)
  // The last right-hand side's clamped contacts (indices from begin): the next one's warm start.
  // It picks the LCP's solution path, so it belongs with the state that repeats a run.
  LcpIndices clamped;
  bool asleep = false;  // its bodies sleep (WorldParams::sleep_after): not integrated, forces held
};

struct WorldState {
  // At t = 0 in `initial` (orientations normalised), with no wrench and no contact yet.
  WorldState(const WorldModel& model, std::vector<BodyState> initial);
  // The user's wrench on body i's centre of mass (world frame), held until changed.
  void set_wrench(int body, const Vec3& force, const Vec3& torque);
  // Body i's state (orientation normalised), set from outside: the integrator starts over and
  // every body wakes (a static body set elsewhere may have left a sleeping one unsupported).
  void set_body(const WorldModel& model, int i, const BodyState& s);
  // The bodies' poses at `states`; the static ones stay where they were last set.
  void poses_of(const WorldModel& model, const std::vector<BodyState>& states, std::vector<Pose>& poses) const;
  // Kinetic plus gravitational potential energy of the dynamic bodies.
  double energy(const WorldModel& model) const;
  void wake_all();

  double t = 0;
  std::vector<BodyState> bodies;
  // Every body's pose at its last set state, and a dynamic body's where it fell asleep: the poses
  // of the bodies that do not move now (static ones, and sleeping ones).
  std::vector<Pose> static_poses;
  std::vector<Vec3> ext_force, ext_torque;  // the user's wrenches, held until changed
  std::vector<ActiveContact> resting;       // their last normal forces and the friction held for the step
  std::vector<ContactIsland> islands;       // the resting contacts, grouped (contiguous) by island
  std::vector<ContactFeature> watched;      // features that may hit: their gaps are watched for impacts
  // Each watched feature's gap at the current state (the margin where it does not face its
  // partner): what the next integrator step's gaps are compared with.
  std::vector<double> watched_gaps;
  // Per body: the time it last moved (faster than WorldParams::sleep_speed, or pushed) at a
  // step's start, and whether it sleeps (at rest, left out of the integration).
  std::vector<double> still_since;
  std::vector<char> asleep;
  bool restart = true;  // the integrator must be (re)started before integrating
};

}  // namespace wysiwyf::haptics
