#pragma once
// The physically based simulation of the paper's section 4: rigid boxes under gravity, external
// (user) wrenches and non-penetration constraints, integrated with SUNDIALS (ARKODE or CVODE).
//
// One step(dt) is the paper's section 4.3 cycle. The contacts found at its start (STEP 4 of the
// previous cycle) that touch are resting contacts: their forces come from the LCP of eqs. (9)-(10)
// at every right-hand-side evaluation, so the constraint holds in acceleration throughout the
// step (STEP 2-3). Contacts that are near but apart are watched: after each of the integrator's
// steps their gaps are evaluated, and where one has closed (approaching direction only) the time of
// impact is found in the step's dense output to WorldParams::impact_tolerance (gap_closing.hpp),
// the impulses come from the LCP of eqs. (15)-(16) with the restitution of each contact, the
// momenta are reset and the integrator is restarted from there (STEP 4-6).
//
// Coulomb friction (a contact's coefficient is the larger of its two bodies', MuJoCo's rule)
// comes from FrictionSolver (friction.hpp) together with the normal forces. For resting contacts
// it is found at the start of each step, asking each contact to stop sliding by the step's end,
// and held through the step like the user's wrench (an iterative solve inside the right-hand
// side would put its round-off into the integrator's error test); a contact that needs more than mu f_n
// slides with the full mu f_n against its motion. The normal forces stay exact at every
// right-hand side with the held friction as a load. At impacts, the impulses make each contact's
// tangential velocity zero within mu times its normal impulse. Without friction coefficients the
// frictionless LCP runs alone.
#include <memory>
#include <string>
#include <vector>

#include "scene/body.hpp"
#include "rigid_body/contact.hpp"
#include "rigid_body/contact_system.hpp"
#include "rigid_body/friction.hpp"
#include "rigid_body/integration_groups.hpp"
#include "rigid_body/lcp.hpp"
#include "rigid_body/world_model.hpp"
#include "rigid_body/world_state.hpp"
#include "rigid_body/world_workspace.hpp"

namespace wysiwyf::haptics {

// The haptic display's integration accuracy: the integrator's relative tolerance in admittance_sim (the
// absolute one is 1e-2 of it). A cube pushed by a new noisy sample every 1 ms stays within 5 um
// of its exact motion over 10 s (test_world), far below the robot's 0.1 mm repeatability and
// the sensor noise's own effect: a tighter tolerance would buy accuracy no hand can feel at a
// higher cost a step (docs/design/rigid-body-integration.md).
constexpr double kHapticRtol = 1e-7;

struct StepReport {
  int collisions = 0;  // impacts inside the step (watched gaps that closed)
  int rhs_evaluations = 0;
  int integrator_steps = 0;     // the integrator's internal steps
  int error_test_failures = 0;  // the integrator's rejected steps
  int lcp_failures = 0;
  int friction_unconverged = 0;  // friction rounds that did not settle (forces still bounded)
  int friction_rounds = 0;       // staggered rounds of the step's friction solve
  // The step could not be integrated (the integrator gave up, or an island outgrew the LCP): the bodies
  // were put back where the step began, at rest (World::last_failure says why).
  int integration_failures = 0;
  int frictionless_retries = 0;  // the step failed with friction and was taken again without
  int bodies_asleep = 0;         // dynamic bodies at rest, left out of the integration, at the step's end
};

class OdeIntegrator;

class World {
 public:
  World(std::vector<BodyModel> models, std::vector<BodyState> initial, WorldParams params = {});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // A wrench on body i's centre of mass (world frame), held until changed (zero-order hold).
  void set_external_wrench(int body, const Vec3& force, const Vec3& torque);
  // Never throws: a step that cannot be integrated holds (StepReport::integration_failures).
  StepReport step(double dt);
  const std::string& last_failure() const { return last_failure_; }

  double time() const { return state_.t; }
  int body_count() const { return model_.body_count(); }
  const BodyModel& model(int i) const { return model_.bodies[i]; }
  const BodyState& state(int i) const { return state_.bodies[i]; }
  void set_state(int i, const BodyState& s);
  // Takes `other`'s state: its time, bodies, wrenches and contacts; the integrator starts over
  // from it. `other` must have the same bodies (throws otherwise). For looking ahead of a world
  // in a second one without disturbing it.
  void copy_state_from(const World& other);
  // Whether a gap of body i is watched (a feature of it near another body's but apart): an impact
  // of it may come within the next steps. Bodies further apart than WorldParams::margin are not.
  bool watching(int i) const;
  double margin() const { return model_.params.margin; }
  BodyKinematics kinematics(int i) const { return BodyKinematics(model_.bodies[i], state_.bodies[i]); }
  const std::vector<ActiveContact>& resting_contacts() const { return state_.resting; }
  // Body i sleeps: at rest, left out of the integration (WorldParams::sleep_after).
  bool asleep(int i) const { return state_.asleep[i] != 0; }
  // Kinetic plus gravitational potential energy of the dynamic bodies.
  double energy() const;

 private:
  friend class OdeIntegrator;  // calls rhs()

  // Contact search and classification at a step's start (world_contacts.cpp).
  void classify_contacts(double dt);  // (dt: the step ahead, over which an edge pair may turn to face)
  // Feature f at `poses`, a point within the rim of its face or edge still on it (every
  // evaluation of the world's contacts: search, right-hand sides, watched gaps and impacts).
  ContactPoint point_of(const ContactFeature& f, const std::vector<Pose>& poses) const;
  // Whether a touching contact already listed is the same constraint as f at c.
  bool twin_of_touching(const ContactFeature& f, const ContactPoint& c) const;

  // The resting contacts' forces (world_forces.cpp).
  // Evaluates the resting contacts at `poses` and moves those still facing to the front of their
  // island; returns how many they are. within_step (a right-hand side): one that has left its
  // face or edge since the step began, by less than the margin, still faces (see the .cpp).
  std::size_t evaluate_resting(const std::vector<Pose>& poses, bool within_step);
  // The resting contacts' friction for the next step of dt (held through it).
  void update_friction(double dt);
  // The state's derivative at y (the integrator's right-hand side).
  void rhs(const double* y, double* ydot);

  // Integration of a step, group by group (world_integration.cpp, world_groups.cpp).
  // An integrator for a group of `bodies` dynamic bodies (WorldParams::integrator).
  std::unique_ptr<OdeIntegrator> make_integrator(int bodies);
  // The step's work (the resting contacts' friction held through it or none); throws where it
  // cannot go on.
  void integrate(double dt, bool friction);
  // One integration group's bodies (integrated_, integrator_) from state_.t to t_end, the state
  // holding its contacts and watched features only; restart: its integrator starts over.
  void integrate_group(double t_end, bool restart);
  // The state's contacts and watched features shared out among the groups and gathered back
  // (world_groups.cpp): the world's are kept in the workspace while each group's are the
  // state's; a group that had no impact gives its contacts back where they were, one that had
  // gives its new islands, and the gathered islands take the order IslandGrouping gives them.
  void take_share(const IntegrationGroup& g, bool restart);
  void give_back(const IntegrationGroup& g, bool impacted);
  void gather_groups(bool any_impacted);

  // Impacts (world_impacts.cpp).
  // The watched features' gaps at the state y (the margin for one that does not face its partner:
  // it cannot hit it).
  void watched_gaps_at(const double* y, std::vector<double>& gaps);
  // One watched feature's, evaluating its two bodies only.
  double watched_gap_at(const ContactFeature& f, const double* y);
  double watched_gap(const ContactPoint& c) const { return c.valid ? c.gap : model_.params.margin; }
  // After the integrator's step from t_start: the watched gap that closed first within it, at its
  // time of impact (false: none closed).
  bool first_closing(double t_start, double t_reached, std::size_t& feature, double& t_impact);
  // A watched feature that faced its partner at an integrator step's start and not at its end
  // is looked at in this many equal parts of the step for a gap that closed in between.
  static constexpr int kLeftFaceSamples = 16;
  // The impact at the current state (STEP 4-6), feature `hit` of the watched having closed.
  void impact(std::size_t hit);
  // Applies the LCP impulses of eqs. (15)-(16) over `contacts` (grouped into `islands`) to the
  // bodies, island by island; returns false if one failed.
  bool collide(std::vector<ActiveContact>& contacts, const std::vector<ContactIsland>& islands);
  bool collide_island(const ActiveContact* contacts, std::size_t count, const std::vector<Pose>& poses);
  // After a frictional impact: a frictionless, inelastic one on the contacts still approaching.
  bool stop_approach(const ActiveContact* contacts, std::size_t count);
  static constexpr double kStillApproaching = 1e-9;  // m/s
  // Impulse j (world frame, on body a) at the contact's point, added to both bodies' momenta.
  void apply_impulse(const ActiveContact& contact, const Vec3& j, const std::vector<Pose>& poses);

  // Sleeping islands (world_sleep.cpp).
  // Wakes every sleeping body of an island with one that moves, is pushed or is awake (an impact
  // or a new contact joined them), and, may_sleep (at a step's end), puts to sleep the islands
  // whose bodies have all been still for sleep_after; returns whether any body changed.
  bool settle_islands(bool may_sleep);
  bool all_asleep() const;

  // A step that fails (world.cpp).
  // The bodies set to `bodies` at t, the contacts to be found again and the integrator started over.
  void restart_from(double t, const std::vector<BodyState>& bodies);
  void hold(double t, const std::string& why);

  const WorldModel model_;
  WorldState state_;
  WorldWorkspace work_;
  IntegrationGroups groups_;
  OdeIntegrator* integrator_ = nullptr;  // the group being integrated's
  // The dynamic bodies being integrated (a group's; every one's outside the integration), and how
  // many impacts that group has had in this step (WorldParams::max_collisions_per_step).
  const std::vector<int>* integrated_ = nullptr;
  int group_collisions_ = 0;
  LcpSolver lcp_;
  FrictionSolver friction_;         // the resting contacts' friction for a step
  FrictionSolver impact_friction_;  // at impacts
  ContactSystem contact_system_;    // rebuilt at each right-hand side and impact
  StepReport report_;
  std::string last_failure_;
};

}  // namespace wysiwyf::haptics
