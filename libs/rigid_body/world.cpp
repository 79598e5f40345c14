#include "rigid_body/world.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rigid_body/cvode_integrator.hpp"
#include "rigid_body/state_vector.hpp"

namespace wysiwyf::haptics {

namespace {

// (before the model's own checks, in the order they have always come)
std::vector<BodyModel> one_state_each(std::vector<BodyModel>& models, const std::vector<BodyState>& initial) {
  if (models.size() != initial.size()) throw std::invalid_argument("World: one initial state per body expected");
  return std::move(models);
}

}  // namespace

World::World(std::vector<BodyModel> models, std::vector<BodyState> initial, WorldParams params)
    : model_(one_state_each(models, initial), params), state_(model_, std::move(initial)) {
  const WorldParams& p = model_.params;
  const CvodeOptions options{p.rtol, p.atol, p.initial_step, p.restart_growth, p.nonlinear_convergence};
  const int size = std::max<int>(1, kStateSize * static_cast<int>(model_.dynamic.size()));
  integrator_ = std::make_unique<CvodeIntegrator>(size, options, *this);
}

World::~World() = default;

void World::set_external_wrench(int body, const Vec3& force, const Vec3& torque) {
  // A new sample is a discontinuity of the right-hand side: the multistep history is invalid.
  // (A change at the level of round-off, from a wrench rotated through a pose, is none.)
  const auto changed = [](const Vec3& a, const Vec3& b) { return (a - b).norm() > 1e-12 * std::max(1.0, b.norm()); };
  if (changed(force, state_.ext_force[body]) || changed(torque, state_.ext_torque[body])) state_.restart = true;
  state_.ext_force[body] = force;
  state_.ext_torque[body] = torque;
}

void World::set_state(int i, const BodyState& s) {
  state_.bodies[i] = s;
  state_.bodies[i].q.normalize();
  state_.static_poses[i] = model_.pose_of(i, state_.bodies[i]);
  state_.restart = true;
}

double World::energy() const {
  double e = 0;
  for (int i : model_.dynamic) {
    const BodyKinematics k(model_.bodies[i], state_.bodies[i]);
    e += 0.5 * model_.bodies[i].mass * k.v.squaredNorm() + 0.5 * k.omega.dot(state_.bodies[i].L) -
         model_.bodies[i].mass * model_.params.gravity.dot(state_.bodies[i].x);
  }
  return e;
}

void World::poses_of(const std::vector<BodyState>& states, std::vector<Pose>& poses) const {
  poses = state_.static_poses;  // (static bodies do not move)
  for (int i : model_.dynamic) poses[i] = model_.pose_of(i, states[i]);
}

// A = J M^-1 J^T, one entry at a time: a row of J touches at most two bodies, so the dense
// product over 6 columns per dynamic body would be mostly zeros.
void World::contact_matrix(const ActiveContact* contacts, std::size_t count, const std::vector<Pose>& poses,
                           bool with_tangents) {
  const std::size_t rows = with_tangents ? 3 * count : count;
  jacobian_.resize(rows);
  if (with_tangents) tangents_.resize(count);
  auto set_row = [&](std::size_t row, const ActiveContact& c, const Vec3& d) {
    JacobianRow& out = jacobian_[row];
    for (int side = 0; side < 2; ++side) {
      const int body = side == 0 ? c.feature.a : c.feature.b;
      out.slot[side] = model_.slot[body];
      if (model_.slot[body] < 0) continue;
      const Pose& p = poses[body];
      const Vec3 ds = side == 0 ? d : Vec3(-d);
      const Vec3 moment = (c.point.p - p.x).cross(ds);
      out.j[side].head<3>() = ds;
      out.j[side].tail<3>() = moment;
      out.minv_j[side].head<3>() = p.inv_mass * ds;
      out.minv_j[side].tail<3>() = p.inv_inertia * moment;
    }
  };
  for (std::size_t i = 0; i < count; ++i) {
    const auto& c = contacts[i];
    set_row(i, c, c.point.n);
    if (!with_tangents) continue;
    // Any orthonormal pair spanning the tangent plane (the friction disc is isotropic).
    const Vec3& nn = c.point.n;
    Eigen::Index least;
    nn.cwiseAbs().minCoeff(&least);
    const Vec3 t1 = nn.cross(Vec3::Unit(least)).normalized();
    const Vec3 t2 = nn.cross(t1);
    tangents_[i] = {t1, t2};
    set_row(count + 2 * i, c, t1);
    set_row(count + 2 * i + 1, c, t2);
  }
  const auto n = static_cast<Eigen::Index>(rows);
  A_.resize(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index k = 0; k <= i; ++k) {
      const JacobianRow &ri = jacobian_[static_cast<std::size_t>(i)], &rk = jacobian_[static_cast<std::size_t>(k)];
      double sum = 0;
      for (int s = 0; s < 2; ++s)
        for (int t = 0; t < 2; ++t)
          if (ri.slot[s] >= 0 && ri.slot[s] == rk.slot[t]) sum += ri.j[s].dot(rk.minv_j[t]);
      A_(i, k) = A_(k, i) = sum;
    }
}

bool World::friction_coefficients(const ActiveContact* contacts, std::size_t count) {
  mu_.resize(static_cast<Eigen::Index>(count));
  bool any = false;
  for (std::size_t i = 0; i < count; ++i) {
    const double mu = std::max(model_.bodies[contacts[i].feature.a].friction, model_.bodies[contacts[i].feature.b].friction);
    mu_[static_cast<Eigen::Index>(i)] = mu;
    any = any || mu > 0;
  }
  return any;
}

// gravity + the user's wrench (+ the friction held for this step) on every dynamic body.
void World::applied_loads(const std::vector<Pose>& poses, bool with_friction) {
  force_.resize(model_.bodies.size());
  torque_.resize(model_.bodies.size());
  for (int i : model_.dynamic) {
    force_[i] = model_.bodies[i].mass * model_.params.gravity + state_.ext_force[i];
    torque_[i] = state_.ext_torque[i];
  }
  if (!with_friction) return;
  for (const auto& c : state_.resting) {
    if (c.friction.isZero() || !c.point.valid) continue;
    for (int side = 0; side < 2; ++side) {
      const int body = side == 0 ? c.feature.a : c.feature.b;
      if (model_.slot[body] < 0) continue;
      const Vec3 f = side == 0 ? c.friction : Vec3(-c.friction);
      force_[body] += f;
      torque_[body] += (c.point.p - poses[body].x).cross(f);
    }
  }
}

void World::contact_terms(const ActiveContact* active, std::size_t live, const std::vector<BodyState>& states,
                          const std::vector<Pose>& poses, double tangent_horizon) {
  const auto m = static_cast<Eigen::Index>(live);
  b_.resize(m);
  b_free_.resize(m);
  if (tangent_horizon > 0) bt_.resize(2 * m), vt_.resize(2 * m);
  const double ws = 2 * M_PI * model_.params.stabilisation_hz;
  // Each dynamic body's accelerations under the applied loads alone.
  acc_.resize(model_.bodies.size());
  for (const int body : model_.dynamic) {
    auto& [linear, angular] = acc_[static_cast<std::size_t>(body)];
    const Pose& p = poses[body];
    linear = force_[body] * p.inv_mass;
    angular = p.inv_inertia * (torque_[body] - p.omega.cross(states[body].L));
  }
  for (std::size_t i = 0; i < live; ++i) {
    const auto& c = active[i].point;
    double acc = 0, gap_rate = 0;
    Vec3 a_rel = Vec3::Zero(), v_rel = Vec3::Zero();  // of a's point relative to b's
    for (int side = 0; side < 2; ++side) {
      const int body = side == 0 ? active[i].feature.a : active[i].feature.b;
      if (model_.slot[body] < 0) continue;  // a static body's points neither move nor accelerate
      const double sgn = side == 0 ? 1.0 : -1.0;
      const Pose& p = poses[body];
      const Vec3 r = c.p - p.x;
      const auto& [linear, angular] = acc_[static_cast<std::size_t>(body)];
      const Vec3 a = p.omega.cross(p.omega.cross(r)) + linear + angular.cross(r);  // centripetal + applied
      const Vec3 vp = p.v + p.omega.cross(r);
      acc += sgn * (c.n.dot(a) + 2 * c.ndot.dot(vp));
      gap_rate += sgn * c.n.dot(vp);
      a_rel += sgn * a;
      v_rel += sgn * vp;
    }
    const auto k = static_cast<Eigen::Index>(i);
    b_free_[k] = acc;
    b_[k] = acc + 2 * ws * gap_rate + ws * ws * c.gap;
    if (tangent_horizon > 0)
      for (int j = 0; j < 2; ++j) {
        const Vec3& t = tangents_[i][static_cast<std::size_t>(j)];
        vt_[2 * k + j] = t.dot(v_rel);
        bt_[2 * k + j] = t.dot(a_rel) + vt_[2 * k + j] / tangent_horizon;  // target: no sliding at the horizon
      }
  }
}

std::size_t World::evaluate_resting(const std::vector<Pose>& poses) {
  std::size_t live = 0;
  for (auto& c : state_.resting) {
    c.point = evaluate(c.feature, model_.bodies, poses);
    if (c.point.valid) std::swap(c, state_.resting[live++]);
  }
  return live;
}

void World::update_friction(double dt) {
  // (without friction coefficients no contact ever carries friction: nothing to do)
  if (!friction_coefficients(state_.resting.data(), state_.resting.size())) return;
  std::vector<Pose>& poses = work_.poses;
  poses_of(state_.bodies, poses);
  const std::size_t live = evaluate_resting(poses);
  const bool any = live > 0 && friction_coefficients(state_.resting.data(), live);
  if (any) {
    applied_loads(poses, false);
    contact_matrix(state_.resting.data(), live, poses, true);
    contact_terms(state_.resting.data(), live, state_.bodies, poses, dt);
    // The last step's friction (classify_contacts carries it over while the contacts stay the
    // same), in the tangent bases, starts the rounds.
    work_.ft_start.resize(static_cast<Eigen::Index>(2 * live));
    for (std::size_t i = 0; i < live; ++i)
      for (std::size_t j = 0; j < 2; ++j)
        work_.ft_start[static_cast<Eigen::Index>(2 * i + j)] = tangents_[i][j].dot(state_.resting[i].friction);
  }
  for (auto& c : state_.resting) c.friction.setZero();  // before solving: no failed solve leaves it applied
  if (!any) return;
  FrictionResult r = friction_.solve(lcp_, A_, b_, bt_, mu_, vt_, work_.ft_start);
  if (!r.ok) r = friction_.solve(lcp_, A_, b_free_, bt_, mu_, vt_);
  report_.friction_rounds += r.iterations;
  if (!r.ok) return;  // frictionless this step; the normal LCP of the right-hand side reports it
  if (!r.converged) ++report_.friction_unconverged;
  for (std::size_t i = 0; i < live; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    state_.resting[i].friction = r.ft[2 * k] * tangents_[i][0] + r.ft[2 * k + 1] * tangents_[i][1];
  }
  state_.restart = true;  // a new friction load: a discontinuity of the right-hand side, like a new wrench
}

void World::rhs(const double* y, double* ydot) {
  ++report_.rhs_evaluations;
  work_.states = state_.bodies;
  unpack_state(y, model_.dynamic, work_.states);
  poses_of(work_.states, work_.poses);
  // Resting contacts at this very state.
  const std::size_t live = evaluate_resting(work_.poses);
  for (std::size_t i = live; i < state_.resting.size(); ++i) state_.resting[i].force = 0;  // (the live ones get theirs below)
  // Gravity, the user's wrench and the friction held for this step, then the normal forces of
  // eqs. (9)-(10) that keep the contacts from closing under them.
  applied_loads(work_.poses, true);
  std::vector<Vec3>& force = force_;
  std::vector<Vec3>& torque = torque_;
  if (live > 0) {
    const ActiveContact* active = state_.resting.data();
    contact_matrix(active, live, work_.poses);
    contact_terms(active, live, work_.states, work_.poses, 0);
    // Warm-started from the last right-hand side's clamped set: the contacts rarely change
    // between evaluations, and then one small solve replaces the pivoting.
    LcpResult r = lcp_.solve(A_, b_, state_.rhs_clamped);
    // The gap feedback is not a physical acceleration: with redundant contacts whose gaps disagree
    // (a cube in the corner of a table and a wall) it can ask for the impossible. The physical
    // problem is always solvable (frictionless, b in the range of J): fall back to it.
    if (!r.ok) r = lcp_.solve(A_, b_free_);
    if (r.ok)
      state_.rhs_clamped = r.clamped;
    else
      ++report_.lcp_failures;
    for (std::size_t i = 0; i < live; ++i) {
      const double f = r.f[static_cast<Eigen::Index>(i)];
      state_.resting[i].force = f;
      const auto& c = active[i].point;
      for (int side = 0; side < 2; ++side) {
        const int body = side == 0 ? active[i].feature.a : active[i].feature.b;
        if (model_.slot[body] < 0) continue;
        const Vec3 fn = (side == 0 ? f : -f) * c.n;
        force[body] += fn;
        torque[body] += (c.p - work_.poses[body].x).cross(fn);
      }
    }
  }
  for (std::size_t k = 0; k < model_.dynamic.size(); ++k) {
    const int i = model_.dynamic[k];
    const Pose& p = work_.poses[i];
    write_derivative(p.v, p.omega, work_.states[i].q, force[i], torque[i], ydot + kStateSize * k);
  }
}

void World::roots(const double* y, double* g) {
  work_.states = state_.bodies;
  unpack_state(y, model_.dynamic, work_.states);
  poses_of(work_.states, work_.poses);
  for (std::size_t k = 0; k < state_.watched.size(); ++k) {
    const ContactPoint c = evaluate(state_.watched[k], model_.bodies, work_.poses);
    g[k] = c.valid ? c.gap : model_.params.margin;  // a feature that no longer faces the other cannot hit it
  }
}

bool World::collide(std::vector<ActiveContact>& contacts) {
  if (contacts.empty()) return true;
  std::vector<Pose> poses;
  poses_of(state_.bodies, poses);
  for (auto& c : contacts) c.point = evaluate(c.feature, model_.bodies, poses);
  const bool friction = friction_coefficients(contacts.data(), contacts.size());
  contact_matrix(contacts.data(), contacts.size(), poses, friction);
  const auto m = static_cast<Eigen::Index>(contacts.size());
  Eigen::VectorXd c(m), ct(friction ? 2 * m : 0);
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto& contact = contacts[static_cast<std::size_t>(i)];
    const Vec3& p = contact.point.p;
    const Pose &A = poses[contact.feature.a], &B = poses[contact.feature.b];
    const Vec3 v = A.v + A.omega.cross(p - A.x) - B.v - B.omega.cross(p - B.x);
    const double v_rel = contact.point.n.dot(v);
    double e = std::min(model_.bodies[contact.feature.a].restitution, model_.bodies[contact.feature.b].restitution);
    if (v_rel > -model_.params.resting_speed) e = 0;  // a slow approach ends the bounce sequence
    c[i] = (1 + e) * v_rel;                     // eq. (14): v+ + e v- >= 0
    if (friction)  // target: no tangential velocity after the impact (within mu times the normal impulse)
      for (int k = 0; k < 2; ++k) ct[2 * i + k] = tangents_[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)].dot(v);
  }
  Eigen::VectorXd jn, jt;
  if (friction) {
    const FrictionResult r = friction_.solve(lcp_, A_, c, ct, mu_, ct);
    if (!r.ok) return false;
    if (!r.converged) ++report_.friction_unconverged;
    jn = r.fn, jt = r.ft;
  } else {
    const LcpResult r = lcp_.solve(A_, c);
    if (!r.ok) return false;
    jn = r.f;
  }
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto& contact = contacts[static_cast<std::size_t>(i)];
    Vec3 j = jn[i] * contact.point.n;
    if (friction)
      j += jt[2 * i] * tangents_[static_cast<std::size_t>(i)][0] + jt[2 * i + 1] * tangents_[static_cast<std::size_t>(i)][1];
    for (int side = 0; side < 2; ++side) {
      const int body = side == 0 ? contact.feature.a : contact.feature.b;
      if (model_.slot[body] < 0) continue;
      const Vec3 on_body = side == 0 ? j : Vec3(-j);
      state_.bodies[body].P += on_body;
      state_.bodies[body].L += (contact.point.p - poses[body].x).cross(on_body);
    }
  }
  return true;
}

void World::classify_contacts() {
  std::vector<Pose>& poses = work_.poses;
  poses_of(state_.bodies, poses);
  work_.candidates.clear();
  for (int a : model_.dynamic)
    for (int b = 0; b < model_.body_count(); ++b)
      if (b != a && (!model_.bodies[b].dynamic || a < b)) find_candidates(a, b, model_.bodies, poses, model_.params.margin, work_.candidates);
  std::vector<ActiveContact>& touching = work_.touching;
  std::vector<ContactFeature>& watched = work_.watched_next;
  touching.clear();
  watched.clear();
  bool colliding = false;
  for (const auto& f : work_.candidates) {
    const ContactPoint c = evaluate(f, model_.bodies, poses);
    if (!c.valid) continue;
    if (c.gap > model_.params.contact_tolerance) {
      watched.push_back(f);
      continue;
    }
    touching.push_back(ActiveContact{f, c, 0});
    const Vec3 r_a = c.p - poses[f.a].x, r_b = c.p - poses[f.b].x;
    const double v_rel = c.n.dot(poses[f.a].v + poses[f.a].omega.cross(r_a) - poses[f.b].v - poses[f.b].omega.cross(r_b));
    if (v_rel < -model_.params.resting_speed) colliding = true;
  }
  if (colliding) {  // approaching faster than resting: an impact at the start of the step
    if (!collide(touching)) ++report_.lcp_failures;
    ++report_.collisions;
    state_.restart = true;
  }
  const bool same_resting =
      touching.size() == state_.resting.size() &&
      std::equal(touching.begin(), touching.end(), state_.resting.begin(),
                 [](const ActiveContact& x, const ActiveContact& y) { return x.feature == y.feature; });
  if (same_resting)  // the same contacts: the friction they held starts this step's solve
    for (std::size_t i = 0; i < touching.size(); ++i) touching[i].friction = state_.resting[i].friction;
  else
    state_.restart = true;
  if (watched != state_.watched) state_.restart = state_.roots_changed = true;
  state_.resting.swap(touching);  // (the scratch vectors keep their capacity)
  state_.watched.swap(watched);
}

StepReport World::step(double dt) {
  report_ = StepReport{};
  if (model_.dynamic.empty()) {
    state_.t += dt;
    return report_;
  }
  classify_contacts();
  update_friction(dt);
  CvodeIntegrator& cv = *integrator_;
  double* y = cv.state();
  auto watch_roots = [&] {
    state_.roots_changed = false;
    cv.watch_roots(static_cast<int>(state_.watched.size()));  // approaching only
  };
  if (state_.restart) {
    for (int i : model_.dynamic) state_.bodies[i].q.normalize();
    pack_state(state_.bodies, model_.dynamic, y);
    cv.restart(state_.t);
    if (state_.roots_changed) watch_roots();
    state_.restart = false;
  }
  const double t_end = state_.t + dt;
  cv.set_stop_time(t_end);
  while (true) {
    double t_reached = state_.t;
    const bool at_root = cv.advance(t_end, t_reached);
    cv.count_work(report_.integrator_steps, report_.error_test_failures);
    unpack_state(y, model_.dynamic, state_.bodies);
    state_.t = t_reached;
    if (!at_root) break;
    // An impact (STEP 4-6): impulses over every touching contact, then restart from here.
    std::vector<int> found(state_.watched.size(), 0);
    cv.root_info(found.data());
    // Every watched feature that touches now takes part, flagged or not: the four corners of a
    // cube landing flat hit together, whichever of them the root finder happened to report.
    std::vector<ActiveContact> contacts = state_.resting;
    std::vector<ContactFeature> still_watched;
    std::vector<Pose> poses;
    poses_of(state_.bodies, poses);
    for (std::size_t k = 0; k < state_.watched.size(); ++k) {
      const ContactPoint c = evaluate(state_.watched[k], model_.bodies, poses);
      if (found[k] != 0 || (c.valid && c.gap <= model_.params.contact_tolerance))
        contacts.push_back(ActiveContact{state_.watched[k], c, 0});
      else
        still_watched.push_back(state_.watched[k]);
    }
    if (!collide(contacts)) ++report_.lcp_failures;
    ++report_.collisions;
    state_.resting = std::move(contacts);
    state_.watched = std::move(still_watched);
    if (report_.collisions >= model_.params.max_collisions_per_step) state_.watched.clear();  // no more events this step
    pack_state(state_.bodies, model_.dynamic, y);
    cv.restart(state_.t);
    watch_roots();
    if (state_.t >= t_end) break;
  }
  return report_;
}

}  // namespace wysiwyf::haptics
