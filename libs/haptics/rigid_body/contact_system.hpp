#pragma once
// The contact system over a list of contacts, as the LCP and friction solvers take it (the
// paper's eqs. (9)-(10) for forces, (15)-(16) for impulses): the rows of J, a unit force along
// each contact direction (the normal, then with friction two tangents per contact); A = J M^-1
// J^T; the free terms b, the rows' accelerations under the applied loads alone; the friction
// coefficients; and the applied loads themselves (gravity, the user's wrench, held friction).
// Everything here is rebuilt for each right-hand side or impact: scratch, kept for its capacity.
#include <Eigen/Dense>

#include <array>
#include <utility>
#include <vector>

#include "scene/body.hpp"
#include "rigid_body/contact.hpp"
#include "rigid_body/world_model.hpp"
#include "rigid_body/world_state.hpp"

namespace wysiwyf::haptics {

// Each body of a contact that moves, as each(side, body): body a (side 0) and body b (side 1;
// the normal points from b to a, so b takes what a takes with the opposite sign). A static body
// neither moves nor takes a load: it is skipped.
template <class Each>
void for_each_moving_body(const ContactFeature& f, const std::vector<int>& slot, Each&& each) {
  for (int side = 0; side < 2; ++side) {
    const int body = side == 0 ? f.a : f.b;
    if (slot[body] < 0) continue;
    each(side, body);
  }
}

// A vector v (a force, an impulse, a unit direction) applied at contact point p: v on body a and
// -v on body b, each with its moment about that body's centre of mass, handed over as
// apply(side, body, on_body, moment). Static bodies are skipped. (Through for_each_moving_body
// rather than its own loop: GCC 12 compiles it to fewer instructions so.)
template <class Apply>
void apply_at_contact(const ContactFeature& f, const Vec3& p, const Vec3& v, const std::vector<int>& slot,
                      const std::vector<Pose>& poses, Apply&& apply) {
  for_each_moving_body(f, slot, [&](int side, int body) {
    const Vec3 on_body = side == 0 ? v : Vec3(-v);
    apply(side, body, on_body, Vec3((p - poses[body].x).cross(on_body)));
  });
}

// The velocity at point p of body a relative to body b (poses a and b).
inline Vec3 relative_velocity(const Pose& a, const Pose& b, const Vec3& p) {
  return a.v + a.omega.cross(p - a.x) - b.v - b.omega.cross(p - b.x);
}

struct ContactSystem {
  // The model must outlive the system.
  explicit ContactSystem(const WorldModel& model) : model(model) {}

  // A = J M^-1 J^T over the first `count` of `contacts`: their normal rows, then (with_tangents)
  // two tangent rows per contact along `tangents`. The rows of J are kept in `rows`.
  void build(const ActiveContact* contacts, std::size_t count, const std::vector<Pose>& poses,
             bool with_tangents = false);
  // The contacts' friction coefficients into mu; true if any is > 0.
  bool friction_coefficients(const ActiveContact* contacts, std::size_t count);
  // force, torque of the dynamic `bodies`: gravity and the user's wrench, plus (with_friction)
  // the friction that the state's resting contacts hold (which reach no other dynamic body).
  void applied_loads(const WorldState& state, const std::vector<int>& bodies, const std::vector<Pose>& poses,
                     bool with_friction);
  // Their accelerations under force/torque alone (body_acc), for free_terms.
  void accelerations(const std::vector<int>& bodies, const std::vector<BodyState>& states,
                     const std::vector<Pose>& poses);
  // The first `live` rows' free terms under force/torque (after accelerations()): b (with gap feedback), b_free, and for
  // tangent_horizon > 0 bt (tangential acceleration that stops sliding within the horizon) and vt.
  void free_terms(const ActiveContact* active, std::size_t live, const std::vector<Pose>& poses,
                  double tangent_horizon);

  const WorldModel& model;
  // A row of J: a unit force along a contact direction as it acts on each side's body (force and
  // moment about the centre of mass), and M^-1 times that; slot -1 for a static body.
  struct JacobianRow {
    int slot[2];
    Eigen::Matrix<double, 6, 1> j[2], minv_j[2];
  };
  std::vector<JacobianRow> rows;              // the first `count` (3 `count` with tangents) of the last build
  std::vector<std::array<Vec3, 2>> tangents;  // per contact: the orthonormal pair of its tangent rows
  Eigen::MatrixXd A;
  Eigen::VectorXd b, b_free;        // with and without the gap feedback
  Eigen::VectorXd bt, vt, mu;       // tangent rows' free terms and sliding velocities, friction coefficients
  std::vector<Vec3> force, torque;  // per body: the applied loads
  std::vector<std::pair<Vec3, Vec3>> body_acc;  // per body: linear and angular acceleration under them

 private:
  // build's scratch: the dynamic bodies the rows touch (slots, in order met; local_of: slot -> place
  // there, -1 between builds), per such body k the rows that touch it, (row, side), from
  // body_rows[body_row_start[k]]; its J_k, M_k^-1 J_k^T and their product (grown, never shrunk).
  std::vector<int> local_of, touched;
  std::vector<std::size_t> body_row_start, fill;
  std::vector<std::pair<std::size_t, int>> body_rows;
  Eigen::Matrix<double, 6, Eigen::Dynamic> body_j, body_minv_j;
  Eigen::MatrixXd body_block;
};

}  // namespace wysiwyf::haptics
