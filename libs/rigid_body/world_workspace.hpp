#pragma once
// A World's scratch, as the arena of MuJoCo's mjData: vectors reused across steps and
// right-hand-side evaluations, so that neither allocates once their sizes have settled.
// Nothing here carries meaning from one use to the next.
#include <Eigen/Dense>

#include <cstdint>
#include <vector>

#include "scene/body.hpp"
#include "rigid_body/broad_phase.hpp"
#include "rigid_body/contact.hpp"
#include "rigid_body/contact_islands.hpp"
#include "rigid_body/world_state.hpp"

namespace wysiwyf::haptics {

struct WorldWorkspace {
  std::vector<BodyState> states;  // the state a right-hand side is evaluated at
  std::vector<Pose> poses;        // the bodies' poses at it (or at the current state)
  // classify_contacts: the features near enough to look at, and the next resting contacts and
  // watched features (swapped with the state's, so both keep their capacity).
  SweepAndPrune broad_phase;    // (its sort order only speeds the next sort)
  std::vector<BodyPair> pairs;  // the broad phase's
  std::vector<ContactFeature> candidates;
  std::vector<std::uint64_t> was_resting;  // the last step's resting contacts' feature keys, sorted
  std::vector<ActiveContact> touching;
  std::vector<ContactFeature> watched_next;
  Eigen::VectorXd ft_start;  // update_friction: the last step's friction, in the tangent bases
  IslandGrouping grouping;
  std::vector<Pose> impact_poses;        // collide: the bodies' poses at the impact
  std::vector<Pose> after_impact_poses;  // stop_approach: and after its impulses
  std::vector<BodyState> step_start;     // step: where the bodies were, to hold at if it fails
  std::vector<double> gaps_at_step_end;  // the watched gaps after an integrator step
  std::vector<Pose> gap_poses;           // watched_gap_at: the poses of the two bodies it evaluates
  std::vector<int> island_bodies;        // settle_islands: one island's dynamic bodies
  std::vector<char> in_island;           // and, per body, whether one holds it
};

}  // namespace wysiwyf::haptics
