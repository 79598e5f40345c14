#include "rigid_body/contact_system.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::haptics {

// A = J M^-1 J^T: a row of J touches at most two bodies, so the dense product over 6 columns per
// dynamic body would be mostly zeros; it is summed body by body instead.
void ContactSystem::build(const ActiveContact* contacts, std::size_t count, const std::vector<Pose>& poses,
                          bool with_tangents) {
  const std::size_t row_count = with_tangents ? 3 * count : count;
  if (rows.size() < row_count) rows.resize(row_count);  // (never shrunk: right-hand sides and friction alternate)
  if (with_tangents) {
    tangents.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      // Any orthonormal pair spanning the tangent plane (the friction disc is isotropic).
      const Vec3& nn = contacts[i].point.n;
      Eigen::Index least;
      nn.cwiseAbs().minCoeff(&least);
      const Vec3 t1 = nn.cross(Vec3::Unit(least)).normalized();
      const Vec3 t2 = nn.cross(t1);
      tangents[i] = {t1, t2};
    }
  }
  // Row r: contact r's normal for r < count, then contact i's two tangents at count + 2i, + 1.
  for (std::size_t r = 0; r < row_count; ++r) {
    const std::size_t i = r < count ? r : (r - count) / 2;
    const ActiveContact& c = contacts[i];
    const Vec3& d = r < count ? c.point.n : tangents[i][(r - count) % 2];
    JacobianRow& out = rows[r];
    out.slot[0] = model.slot[c.feature.a], out.slot[1] = model.slot[c.feature.b];
    apply_at_contact(c.feature, c.point.p, d, model.slot, poses,
                     [&](int side, int body, const Vec3& ds, const Vec3& moment) {
                       const Pose& p = poses[body];
                       out.j[side].head<3>() = ds;
                       out.j[side].tail<3>() = moment;
                       out.minv_j[side].head<3>() = p.inv_mass * ds;
                       out.minv_j[side].tail<3>() = p.inv_inertia * moment;
                     });
  }
  // Body by body: the rows that touch it, as columns of J_k (6 x r_k) and M_k^-1 J_k^T, give its
  // share J_k M_k^-1 J_k^T of A in one small dense product (vectorised), added at those rows.
  // (Only the bodies these rows touch are visited: an island's build costs nothing per body
  // elsewhere in the world.)
  const auto n = static_cast<Eigen::Index>(row_count);
  A.setZero(n, n);
  local_of.resize(model.dynamic.size(), -1);
  touched.clear();
  body_row_start.assign(1, 0);
  for (std::size_t r = 0; r < row_count; ++r)
    for (const int s : rows[r].slot) {
      if (s < 0) continue;
      int& local = local_of[static_cast<std::size_t>(s)];
      if (local < 0) local = static_cast<int>(touched.size()), touched.push_back(s), body_row_start.push_back(0);
      ++body_row_start[static_cast<std::size_t>(local) + 1];
    }
  const std::size_t bodies = touched.size();
  for (std::size_t k = 0; k < bodies; ++k) body_row_start[k + 1] += body_row_start[k];
  body_rows.resize(body_row_start[bodies]);
  fill.assign(body_row_start.begin(), body_row_start.end() - 1);
  for (std::size_t r = 0; r < row_count; ++r)
    for (int side = 0; side < 2; ++side)
      if (const int s = rows[r].slot[side]; s >= 0)
        body_rows[fill[static_cast<std::size_t>(local_of[static_cast<std::size_t>(s)])]++] = {r, side};
  for (const int s : touched) local_of[static_cast<std::size_t>(s)] = -1;
  for (std::size_t k = 0; k < bodies; ++k) {
    const std::size_t first = body_row_start[k];
    const auto r_k = static_cast<Eigen::Index>(body_row_start[k + 1] - first);
    if (body_j.cols() < r_k) body_j.resize(6, r_k), body_minv_j.resize(6, r_k), body_block.resize(r_k, r_k);
    for (Eigen::Index c = 0; c < r_k; ++c) {
      const auto [r, side] = body_rows[first + static_cast<std::size_t>(c)];
      body_j.col(c) = rows[r].j[side];
      body_minv_j.col(c) = rows[r].minv_j[side];
    }
    auto block = body_block.topLeftCorner(r_k, r_k);
    block.noalias() = body_j.leftCols(r_k).transpose().lazyProduct(body_minv_j.leftCols(r_k));
    // (a body's rows come in order: its block's lower triangle goes to A's, column by column)
    for (Eigen::Index d = 0; d < r_k; ++d) {
      const auto column = static_cast<Eigen::Index>(body_rows[first + static_cast<std::size_t>(d)].first);
      for (Eigen::Index c = d; c < r_k; ++c)
        A(static_cast<Eigen::Index>(body_rows[first + static_cast<std::size_t>(c)].first), column) += block(c, d);
    }
  }
  A.triangularView<Eigen::StrictlyUpper>() = A.transpose();  // (exactly symmetric, as the solvers take it)
}

bool ContactSystem::friction_coefficients(const ActiveContact* contacts, std::size_t count) {
  mu.resize(static_cast<Eigen::Index>(count));
  bool any = false;
  for (std::size_t i = 0; i < count; ++i) {
    const double m =
        std::max(model.bodies[contacts[i].feature.a].friction, model.bodies[contacts[i].feature.b].friction);
    mu[static_cast<Eigen::Index>(i)] = m;
    any = any || m > 0;
  }
  return any;
}

// gravity + the user's wrench (+ the friction held for this step) on the bodies listed.
void ContactSystem::applied_loads(const WorldState& state, const std::vector<int>& bodies,
                                  const std::vector<Pose>& poses, bool with_friction) {
  force.resize(model.bodies.size());
  torque.resize(model.bodies.size());
  for (int i : bodies) {
    force[i] = model.bodies[i].mass * model.params.gravity + state.ext_force[i];
    torque[i] = state.ext_torque[i];
  }
  if (!with_friction) return;
  for (const auto& c : state.resting) {
    if (c.friction.isZero() || !c.point.valid) continue;
    apply_at_contact(c.feature, c.point.p, c.friction, model.slot, poses,
                     [&](int, int body, const Vec3& f, const Vec3& moment) {
                       force[body] += f;
                       torque[body] += moment;
                     });
  }
}

void ContactSystem::accelerations(const std::vector<int>& bodies, const std::vector<BodyState>& states,
                                  const std::vector<Pose>& poses) {
  body_acc.resize(model.bodies.size());
  for (const int body : bodies) {
    auto& [linear, angular] = body_acc[static_cast<std::size_t>(body)];
    const Pose& p = poses[body];
    linear = force[body] * p.inv_mass;
    angular = p.inv_inertia * (torque[body] - p.omega.cross(states[body].L));
  }
}

void ContactSystem::free_terms(const ActiveContact* active, std::size_t live, const std::vector<Pose>& poses,
                               double tangent_horizon) {
  const auto m = static_cast<Eigen::Index>(live);
  b.resize(m);
  b_free.resize(m);
  if (tangent_horizon > 0) bt.resize(2 * m), vt.resize(2 * m);
  const double ws = 2 * M_PI * model.params.stabilisation_hz;
  for (std::size_t i = 0; i < live; ++i) {
    const auto& c = active[i].point;
    double acc = 0, gap_rate = 0;
    Vec3 a_rel = Vec3::Zero(), v_rel = Vec3::Zero();  // of a's point relative to b's
    // The contact point's motion on each moving body, b's with the opposite sign: the transpose
    // of apply_at_contact. (Its own loop: through for_each_moving_body GCC 12 vectorises the
    // cross products worse.)
    for (int side = 0; side < 2; ++side) {
      const int body = side == 0 ? active[i].feature.a : active[i].feature.b;
      if (model.slot[body] < 0) continue;  // a static body's points neither move nor accelerate
      const double sgn = side == 0 ? 1.0 : -1.0;
      const Pose& p = poses[body];
      const Vec3 r = c.p - p.x;
      const auto& [linear, angular] = body_acc[static_cast<std::size_t>(body)];
      const Vec3 a = p.omega.cross(p.omega.cross(r)) + linear + angular.cross(r);  // centripetal + applied
      const Vec3 vp = p.v + p.omega.cross(r);
      acc += sgn * (c.n.dot(a) + 2 * c.ndot.dot(vp));
      gap_rate += sgn * c.n.dot(vp);
      a_rel += sgn * a;
      v_rel += sgn * vp;
    }
    const auto k = static_cast<Eigen::Index>(i);
    b_free[k] = acc;
    b[k] = acc + 2 * ws * gap_rate + ws * ws * c.gap;
    if (tangent_horizon > 0)
      for (int j = 0; j < 2; ++j) {
        const Vec3& t = tangents[i][static_cast<std::size_t>(j)];
        vt[2 * k + j] = t.dot(v_rel);
        bt[2 * k + j] = t.dot(a_rel) + vt[2 * k + j] / tangent_horizon;  // target: no sliding at the horizon
      }
  }
}

}  // namespace wysiwyf::haptics
