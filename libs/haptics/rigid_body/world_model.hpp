#pragma once
// The constant part of a World, as MuJoCo's mjModel: the bodies' models and the parameters, and
// what follows from them once: which bodies move, where each sits in the state vector, their
// body-frame inverse inertias. Nothing here changes while the world runs.
#include <vector>

#include "scene/body.hpp"
#include "rigid_body/contact.hpp"

namespace wysiwyf::haptics {

enum class Integrator { kRungeKutta, kAdams };

struct WorldParams {
  Vec3 gravity{0, 0, -9.81};
  double rtol = 1e-9;
  double atol = 1e-11;
  double contact_tolerance = 1e-5;  // gap below this: touching (above the scale of integration error)
  // Hysteresis: a contact resting at a step's end stays touching at the next step's start until
  // its gap passes this, unless it approaches faster than the gap feedback closes (then it is
  // watched, to hit where it touches). The corners of a pushed pile's rocking boxes lift a few um
  // past contact_tolerance and come back a step or two later: released at contact_tolerance, each
  // would come back by an impact; within the release the gap feedback sets it down
  // (test_contact_hysteresis). Within it, as within the tolerance, an opening contact's force
  // still follows the gap feedback.
  double contact_release = 3e-5;
  double margin = 0.01;  // features closer than this are watched (resting, or their gaps for impacts)
  // A corner within this of a face's rim counts as over the face, and a resting contact keeps its
  // force until its point leaves its face or edge by more. Equal boxes side by side put corners on
  // the rims of each other's faces, where integration error would switch a contact on and off at
  // every trial step (a discontinuity each time, until CVODE's step collapses), or put it on the
  // face beside (a corner at the side of a box taken as under it: a normal across the true one).
  // As the contact tolerance: a corner that near a face touches it.
  double rim_slack = 1e-5;
  double resting_speed = 0.01;  // approach slower than this: inelastic (ends bounce sequences)
  // A touching contact approaching faster than this, plus ws times its gap (what the gap feedback
  // closes it at without overshoot), takes an (inelastic) impulse at the step's start. Left to
  // the gap feedback, an approach at v beyond that overshoots by v / (e ws) (ws the
  // stabilisation's 2 pi 20 Hz): tens of um at 10 mm/s, enough to carry a box's corners past the
  // rim onto the faces beside; 0.1 mm/s overshoots by 0.3 um.
  double settle_speed = 1e-4;
  double stabilisation_hz = 20.0;  // Baumgarte feedback on resting gaps (0: off)
  // How the bodies' motion is integrated between events (ode_integrator.hpp):
  //  - kRungeKutta: ARKODE's explicit Bogacki-Shampine 3(2). A restart (every sensor sample, every
  //    impact) costs it nothing, and a box under a push held for the step moves along a quadratic,
  //    which it integrates exactly: the noisy-pushed cube's step is one step of 4 right-hand
  //    sides, its motion exact to round-off (test_world).
  //  - kAdams: CVODE's variable-order Adams-Moulton, orders up to 12: long smooth motion at tight
  //    tolerances (test_world's torque-free tumbling box at rtol 1e-9), where its high orders take
  //    far fewer steps (docs/design/rigid-body-integration.md).
  Integrator integrator = Integrator::kRungeKutta;
  // The Adams integrator's options (CVODE):
  double initial_step = 1e-6;  // s, CVODE's first step after a restart (0: CVODE estimates it)
  // After a restart (every new sensor sample) CVODE lets each of its first steps grow tenfold;
  // the first order-2 step then fails its error test, and a noisy haptic step spends right-hand
  // sides on the failures. Growing fourfold, it passes.
  double restart_growth = 4.0;
  // CVODE's corrector stops when its estimated error is below this fraction of the local error
  // test (CVODE's default 0.1): with 0.2 one fixed-point iteration does more often, and the
  // noisy push's global error stays the same to three digits.
  double nonlinear_convergence = 0.2;
  // An impact's time is found to where the closing gap is within this of zero: far below the
  // contact tolerance and the integration error of a position (rtol 1e-7 of a metre), so the
  // bodies meet where they touch, not early or through.
  double impact_tolerance = 1e-10;
  int max_collisions_per_step = 32;
  // Sleeping, as islands sleep in Box2D and Bullet: an island of touching bodies none of which has
  // moved faster than sleep_speed (at any of its points) at a step's start for sleep_after, and
  // none under a user's wrench, is at rest. Its momenta are set to zero and it leaves the
  // integration (no right-hand side, friction or contact solve of it) until an awake body touches
  // it, a wrench is set on one of its bodies or a state is set. A pile at rest moves at 1e-14 to
  // 5e-11 m/s; still at every step's start for sleep_after, a body accelerates at less than
  // 2 sleep_speed / sleep_after (4e-8 m/s^2). sleep_after 0: nothing sleeps.
  double sleep_speed = 1e-9;  // m/s
  double sleep_after = 0.05;  // s
  // The integrator's internal steps towards one stop (the step's end or an impact): a 1 ms haptic
  // step takes 1 to 50. Beyond this the step fails and the world holds (World::step).
  long max_integrator_steps = 5000;
};

struct WorldModel {
  // Throws std::invalid_argument for tolerances or bodies that cannot be simulated.
  WorldModel(std::vector<BodyModel> bodies, const WorldParams& params);
  int body_count() const { return static_cast<int>(bodies.size()); }
  // Body i's world pose at state s.
  Pose pose_of(int body, const BodyState& s) const;

  std::vector<BodyModel> bodies;
  WorldParams params;
  std::vector<int> dynamic;            // indices of dynamic bodies, in state-vector order
  std::vector<int> slot;               // body -> position in dynamic, or -1
  std::vector<Mat3> inv_inertia_body;  // per body, body frame (zero for static bodies)
};

}  // namespace wysiwyf::haptics
