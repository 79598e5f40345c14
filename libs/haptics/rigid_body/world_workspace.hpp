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

// classify_contacts' (world_contacts.cpp): the features near enough to look at, and the next
// resting contacts and watched features (swapped with the state's, so both keep their capacity).
struct ContactSearchWork {
  SweepAndPrune broad_phase;    // (its sort order only speeds the next sort)
  std::vector<BodyPair> pairs;  // the broad phase's
  std::vector<ContactFeature> candidates;
  std::vector<std::uint64_t> was_resting;  // the last step's resting contacts' feature keys, sorted
  std::vector<ActiveContact> touching;
  std::vector<ContactFeature> watched_next;
};

// The impacts' (world_impacts.cpp).
struct ImpactWork {
  std::vector<Pose> impact_poses;        // collide: the bodies' poses at the impact
  std::vector<Pose> after_impact_poses;  // stop_approach: and after its impulses
  std::vector<double> gaps_at_step_end;  // the watched gaps after an integrator step
  std::vector<Pose> gap_poses;           // watched_gap_at: the poses of the two bodies it evaluates
};

// settle_islands' (world_sleep.cpp).
struct SleepWork {
  std::vector<int> island_bodies;  // one island's dynamic bodies
  std::vector<char> in_island;     // and, per body, whether one holds it
};

// integrate's, with more than one integration group (world_integration.cpp, world_groups.cpp): the
// world's contacts and watched features (and their gaps) while each group's are the state's; per
// watched feature, whether its group's impacts made it a contact; per island, whether a group's
// impacts replaced it; the islands of the groups that had impacts (their contacts in
// joined_resting); and the gathered islands' order (lowest body, island, where it is).
struct GroupShareWork {
  std::vector<ActiveContact> all_resting;
  std::vector<ContactIsland> all_islands;
  std::vector<ContactFeature> all_watched;
  std::vector<double> all_gaps;
  std::vector<char> watched_gone;
  std::vector<char> island_replaced;
  std::vector<ActiveContact> joined_resting;
  std::vector<ContactIsland> joined_islands;
  struct IslandPlace {
    int lowest_body;
    bool joined;  // in joined_islands (else all_islands)
    std::size_t index;
    bool operator<(const IslandPlace& o) const { return lowest_body < o.lowest_body; }
  };
  std::vector<IslandPlace> island_order;
  std::vector<ContactIsland> gathered_islands;
};

// One part per phase, and what more than one phase uses.
struct WorldWorkspace {
  std::vector<BodyState> states;      // the state a right-hand side is evaluated at
  std::vector<Pose> poses;            // the bodies' poses at it (or at the current state)
  IslandGrouping grouping;            // classify_contacts and impact: contacts into islands
  std::vector<BodyState> step_start;  // step: where the bodies were, to hold at if it fails
  Eigen::VectorXd ft_start;           // update_friction: the last step's friction, in the tangent bases
  ContactSearchWork search;
  ImpactWork impacts;
  SleepWork sleep;
  GroupShareWork share;
};

}  // namespace wysiwyf::haptics
