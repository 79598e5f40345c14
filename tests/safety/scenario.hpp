#pragma once
// Simulated users for the safety campaign: one seed, one scenario, in the display demo's scene
// terms (its features, the cube, the arm's side of it), written as a user_sim script and the hand
// tracker's faults. The same seed gives the same scenario on every run of the same build.
//
// Kinds (chosen by the seed):
//   reach      from a random start, toward any feature at 0.3-2 m/s, then a push, drag or nothing
//   change     heads for one feature, turns mid-reach to another
//   lunge      a fast move at the arm's side of the cube (its links), then back
//   rest       the hand parked inside the arm's workspace, then a reach
//   switch     touches and releases around the contact threshold and the mode switch's dwell
//   hard_push  presses far beyond the scene's expected force (up to 90 N)
// Any kind may come with a faulty hand source: noise, latency, dropouts, outages, a 10 cm glitch,
// stale stamps.
#include <cstdint>
#include <string>
#include <vector>

namespace wysiwyf::safety {

struct Scenario {
  std::uint64_t seed = 0;
  std::string kind;                 // one of the kinds above
  std::vector<std::string> script;  // user_sim's actions, one a line
  std::string tracker;              // hand_tracker_sim parameters (YAML flow-map entries)
  std::string faults;               // the hand source's faults, in words ("" when none)
};

// The scenario of `seed`.
Scenario make_scenario(std::uint64_t seed);

// The scenario's kinds, in the order the generator draws them from.
const std::vector<std::string>& scenario_kinds();

}  // namespace wysiwyf::safety
