#pragma once
// The physically based simulation of the paper's section 4: rigid boxes under gravity, external
// (user) wrenches and non-penetration constraints, integrated with SUNDIALS CVODE.
//
// One step(dt) is the paper's section 4.3 cycle. The contacts found at its start (STEP 4 of the
// previous cycle) that touch are resting contacts: their forces come from the LCP of eqs. (9)-(10)
// at every right-hand-side evaluation, so the constraint holds in acceleration throughout the
// step (STEP 2-3). Contacts that are near but apart are CVODE root functions on their gaps,
// approaching direction only: at a root the integration stops at the exact time of impact, the
// impulses come from the LCP of eqs. (15)-(16) with the restitution of each contact, the momenta
// are reset and CVODE is restarted (CVodeReInit) from there (STEP 4-6).
//
// Coulomb friction (a contact's coefficient is the larger of its two bodies', MuJoCo's rule)
// comes from FrictionSolver (friction.hpp) together with the normal forces. For resting contacts
// it is found at the start of each step, asking each contact to stop sliding by the step's end,
// and held through the step like the user's wrench (an iterative solve inside the right-hand
// side would put its round-off into CVODE's error test); a contact that needs more than mu f_n
// slides with the full mu f_n against its motion. The normal forces stay exact at every
// right-hand side with the held friction as a load. At impacts, the impulses make each contact's
// tangential velocity zero within mu times its normal impulse. Without friction the frictionless
// LCP runs alone, as before.
#include <array>
#include <memory>
#include <vector>

#include "scene/body.hpp"
#include "rigid_body/contact.hpp"
#include "rigid_body/friction.hpp"
#include "rigid_body/lcp.hpp"

namespace wysiwyf::haptics {

// The haptic display's integration accuracy: CVODE's relative tolerance in admittance_sim (the
// absolute one is 1e-2 of it). A cube pushed by a new noisy sample every 1 ms stays within 5 um
// of its exact motion over 10 s (test_world), far below the robot's 0.1 mm repeatability and
// the sensor noise's own effect; 1e-8 gives 0.5 um at about 1.4x the cost of a step.
constexpr double kHapticRtol = 1e-7;

struct WorldParams {
  Vec3 gravity{0, 0, -9.81};
  double rtol = 1e-9;
  double atol = 1e-11;
  double contact_tolerance = 1e-5;  // gap below this: touching (above the scale of integration error)
  double margin = 0.01;             // features closer than this are watched (resting or root)
  double resting_speed = 0.01;      // approach slower than this: inelastic (ends bounce sequences)
  double stabilisation_hz = 20.0;   // Baumgarte feedback on resting gaps (0: off)
  double initial_step = 1e-6;       // s, CVODE's first step after a restart (0: CVODE estimates it)
  // After a restart (every new sensor sample) CVODE lets each of its first steps grow 10x; the
  // first order-2 step then fails its error test (measured: 4 of 10 right-hand sides a noisy
  // haptic step were spent so). 4x passes.
  double restart_growth = 4.0;
  // CVODE's corrector stops when its estimated error is below this fraction of the local error
  // test (CVODE's default 0.1): with 0.2 one fixed-point iteration does more often; the global
  // error of the noisy push was unchanged to three digits.
  double nonlinear_convergence = 0.2;
  int max_collisions_per_step = 32;
};

struct ActiveContact {
  ContactFeature feature;
  ContactPoint point;
  double force = 0;                 // N, normal, from the last LCP
  Vec3 friction = Vec3::Zero();     // N, tangential force on body a (world frame)
};

struct StepReport {
  int collisions = 0;       // impact events (roots) inside the step
  int rhs_evaluations = 0;
  int integrator_steps = 0;      // CVODE's internal steps
  int error_test_failures = 0;   // CVODE's rejected steps
  int lcp_failures = 0;
  int friction_unconverged = 0;  // friction rounds that did not settle (forces still bounded)
  int friction_rounds = 0;       // staggered rounds of the step's friction solve
};

class CvodeIntegrator;

class World {
 public:
  World(std::vector<BodyModel> models, std::vector<BodyState> initial, WorldParams params = {});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // A wrench on body i's centre of mass (world frame), held until changed (zero-order hold).
  void set_external_wrench(int body, const Vec3& force, const Vec3& torque);
  StepReport step(double dt);

  double time() const { return t_; }
  int body_count() const { return static_cast<int>(models_.size()); }
  const BodyModel& model(int i) const { return models_[i]; }
  const BodyState& state(int i) const { return states_[i]; }
  void set_state(int i, const BodyState& s);
  BodyKinematics kinematics(int i) const { return BodyKinematics(models_[i], states_[i]); }
  const std::vector<ActiveContact>& resting_contacts() const { return resting_; }
  // Kinetic plus gravitational potential energy of the dynamic bodies.
  double energy() const;

 private:
  friend class CvodeIntegrator;  // calls rhs() and roots()
  Pose pose_of(int body, const BodyState& s) const;
  void poses_of(const std::vector<BodyState>& states, std::vector<Pose>& poses) const;
  void rhs(const double* y, double* ydot);
  void roots(const double* y, double* g);
  void classify_contacts();
  // Applies the LCP impulses of eqs. (15)-(16) over `contacts` to states_; returns false if it failed.
  bool collide(std::vector<ActiveContact>& contacts);
  // A = J M^-1 J^T over the first `count` of `contacts`: their normal rows, then (with_tangents)
  // two tangent rows per contact along tangents_. The rows of J are kept in jacobian_.
  void contact_matrix(const ActiveContact* contacts, std::size_t count, const std::vector<Pose>& poses,
                      bool with_tangents = false);
  // The contacts' friction coefficients into mu_; true if any is > 0.
  bool friction_coefficients(const ActiveContact* contacts, std::size_t count);
  // force_, torque_: gravity and the user's wrench, plus (with_friction) the held friction.
  void applied_loads(const std::vector<Pose>& poses, bool with_friction);
  // The contact rows' free terms under force_/torque_: b_ (with gap feedback), b_free_, and for
  // tangent_horizon > 0 bt_ (tangential acceleration that stops sliding within the horizon).
  void contact_terms(const ActiveContact* active, std::size_t live, const std::vector<BodyState>& states,
                     const std::vector<Pose>& poses, double tangent_horizon);
  // Evaluates the resting contacts at `poses` and moves those still facing to the front; returns
  // how many they are.
  std::size_t evaluate_resting(const std::vector<Pose>& poses);
  // The resting contacts' friction for the next step of dt (held through it).
  void update_friction(double dt);

  std::vector<BodyModel> models_;
  std::vector<BodyState> states_;
  WorldParams params_;
  double t_ = 0;
  std::vector<int> dynamic_;                 // indices of dynamic bodies, in state-vector order
  std::vector<int> slot_;                    // body -> position in dynamic_, or -1
  std::vector<Mat3> inv_inertia_body_;       // per body, body frame (zero for static bodies)
  std::vector<Pose> static_poses_;           // every body's pose at its last set state; static ones stay so
  std::vector<Vec3> ext_force_, ext_torque_;
  std::vector<ActiveContact> resting_;
  std::vector<ContactFeature> watched_;      // root functions
  bool restart_ = true;                      // CVODE must be (re)initialised before integrating
  bool roots_changed_ = true;                // CVodeRootInit must be called again
  std::unique_ptr<CvodeIntegrator> integrator_;
  LcpSolver lcp_;
  LcpIndices rhs_clamped_;  // the last right-hand side's clamped contacts (indices into resting_)
  FrictionSolver friction_;
  // Scratch, reused across steps and right-hand-side evaluations.
  std::vector<ContactFeature> candidates_, watched_next_;
  std::vector<ActiveContact> touching_;
  Eigen::VectorXd ft_start_;    // the resting contacts' friction of the last step, in the tangent bases
  std::vector<BodyState> scratch_states_;
  std::vector<Pose> scratch_poses_;
  std::vector<Vec3> force_, torque_;
  // A row of J: a unit force along a contact direction as it acts on each side's body (force and
  // moment about the centre of mass), and M^-1 times that; slot -1 for a static body.
  struct JacobianRow {
    int slot[2];
    Eigen::Matrix<double, 6, 1> j[2], minv_j[2];
  };
  std::vector<JacobianRow> jacobian_;
  std::vector<std::pair<Vec3, Vec3>> acc_;  // per body: linear and angular acceleration under the applied loads
  Eigen::MatrixXd A_;
  Eigen::VectorXd b_, b_free_;  // with and without the gap feedback
  Eigen::VectorXd bt_, vt_, mu_;  // tangent rows' free terms and sliding velocities, friction coefficients
  std::vector<std::array<Vec3, 2>> tangents_;
  StepReport report_;
};

}  // namespace wysiwyf::haptics
