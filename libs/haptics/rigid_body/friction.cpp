// FrictionSolver's staggered rounds (friction.hpp): each an LCP for the normal forces, then a stick
// solve for the friction, until what the forces do settles.
#include "rigid_body/friction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wysiwyf::haptics {
namespace {

// Pivots below this fraction of the largest end the sticking rows' factorisation
// (psd_pseudo_inverse.hpp): round-off in their Schur complement.
constexpr double kStickRank = 1e-12;

// Whether a sticking contact's needed friction lies beyond its cone (mu f_n; beyond round-off).
bool beyond_cone(const Eigen::Vector2d& need, double bound) { return need.norm() > bound * (1 + 1e-12) + 1e-300; }

}  // namespace

FrictionResult FrictionSolver::solve(LcpSolver& lcp, const Eigen::MatrixXd& A, const Eigen::VectorXd& bn,
                                     const Eigen::VectorXd& bt, const Eigen::VectorXd& mu, const Eigen::VectorXd& vt,
                                     const Eigen::VectorXd& ft_start, const LcpIndices& clamped_start) {
  const Eigen::Index m = bn.size();
  FrictionResult r;
  r.fn = Eigen::VectorXd::Zero(m);
  r.ft = ft_start.size() == 2 * m ? ft_start : Eigen::VectorXd::Zero(2 * m);
  Ann_ = A.topLeftCorner(m, m);
  const auto Ant = A.topRightCorner(m, 2 * m);
  const auto Atn = A.bottomLeftCorner(2 * m, m);
  const auto Att = A.bottomRightCorner(2 * m, 2 * m);
  // Sliding contacts and the unit direction of their friction (in the tangent basis).
  moving_.assign(static_cast<std::size_t>(m), false);
  against_.assign(static_cast<std::size_t>(m), Eigen::Vector2d::Zero());
  // With stick_first every contact with friction is first asked to stick: to meet its target
  // (bt: stop sliding by the horizon) within its cone; one that cannot slides at the rim, against
  // its velocity if it slides (maximal dissipation), else along the force it needed. A sliding
  // contact is no exception: mu f_n against its velocity, held for a whole step, would reverse a
  // slow one within the step (a spinning cube's corners would swap direction every step and it
  // would never stop); one that the cone can stop within the horizon stops.
  for (Eigen::Index i = 0; i < m; ++i) {
    const Eigen::Vector2d v = vt.segment<2>(2 * i);
    // (a frictionless contact: a slider with no force)
    if (mu[i] <= 0.0 || (!stick_first && v.norm() > sliding_speed)) moving_[static_cast<std::size_t>(i)] = true;
    if (v.norm() > sliding_speed) against_[static_cast<std::size_t>(i)] = -v.normalized();
  }
  // Convergence is judged on what the forces do, A [fn; ft] (contact-space accelerations or
  // velocity changes).
  f_.resize(3 * m);
  effect_prev_.resize(3 * m);
  const double load = std::max({1e-12, bn.cwiseAbs().maxCoeff(), bt.cwiseAbs().maxCoeff()});
  LcpIndices clamped = clamped_start;  // each round's normal LCP starts from the last one's clamped set
  double best_change = std::numeric_limits<double>::infinity();
  int best_round = 1;
  touching_.clear();  // (a new Ann: no factor kept from another solve)
  for (TouchingFactors& f : factors_) f.set.clear(), f.schur = false, f.used = 0;
  bound_ = 0;
  uses_ = 0;
  for (r.iterations = 1; r.iterations <= max_rounds; ++r.iterations) {
    // Normal forces, friction as a known load.
    ft_seen_ = r.ft;
    bn_eff_ = bn + Ant * r.ft;
    const LcpResult normal = lcp.solve(Ann_, bn_eff_, clamped);
    if (!normal.ok) return r;
    clamped = normal.clamped;
    r.ok = true;
    r.fn = normal.f;
    if (r.iterations == 1 && without_friction_settles(A, normal, bt, mu, load, r)) return r;
    spread_normal_forces(normal, load, r.fn);
    // The friction step sees the tangential rows as the touching normal contacts will answer them:
    // a friction force tilts the body, and the touching contacts' forces change to stop the tilt.
    // With the Schur complement S = Att - Atn_T Ann_TT^+ Ant_T in place of Att (and the load
    // moved to match), the friction found is already the one that holds after the next normal
    // solve, as long as the touching set stays: the rounds settle in one or two, where plain
    // alternation (Att in place of S) converges only geometrically. (Ann_TT^+: the
    // least forces that answer it; redundant contacts share the answer.) S and Z depend on the
    // touching set only: kept with its factor (bind_factor), for as long as the solve lasts.
    const auto nt = static_cast<Eigen::Index>(touching_.size());
    if (nt == 0) bind_factor();  // (the spread binds a factor only to a set that has contacts)
    if (TouchingFactors& set = factor(); !set.schur) {
      set.schur = true;
      Eigen::MatrixXd& Z_ = set.Z;
      Eigen::MatrixXd& F_ = set.F;
      Eigen::MatrixXd& AntC_ = set.AntC;
      set.s_column.assign(static_cast<std::size_t>(2 * m), 0);
      set.s_whole = false;
      set.Zt.resize(0, 0);
      if (nt > 0) {
        AntC_.resize(nt, 2 * m);
        for (Eigen::Index i = 0; i < nt; ++i) AntC_.row(i) = Ant.row(touching_[static_cast<std::size_t>(i)]);
        // Z^T Z = Atn_T Ann_TT^+ Ant_T; Z ft: how the touching forces answer a friction force.
        // Z = F Ant_T through the half inverse F (F^T F = Ann_TT^+; anticipate_sliders needs it
        // too): a product in place of a solve for each of the 2m columns.
        identity_.setIdentity(nt, nt);
        set.inverse.half_solve(identity_, F_);
        Z_.noalias() = F_ * AntC_;
      } else {
        set.S = Att;  // (nothing touches: nothing answers the friction)
        set.s_whole = true;
      }
    }
    const Eigen::MatrixXd& S_ = factor().S;
    const Eigen::MatrixXd& Z_ = factor().Z;
    if (r.iterations == 1) {
      // What the forces this LCP answered do: the friction it saw (the last step's, mostly) and its
      // normal forces. A first round that keeps that friction has settled: a step of a resting
      // stack ends in its first round.
      f_ << r.fn, ft_seen_;
      effect_prev_.noalias() = A * f_;
    }
    c_ = bt + Atn * r.fn;  // the tangential rows' load at the current forces, less S ft
    if (nt > 0) c_.noalias() += Z_.transpose() * (Z_ * r.ft);
    // Friction forces, normal forces fixed: sliders at the rim, stickers exact; a sticker beyond
    // its rim becomes a slider and the stickers are solved again.
    sliding_ = moving_;
    direction_ = against_;
    // A contact without normal force can hold no friction: it is free, not asked to stick (its
    // rows would otherwise ask the others' friction to stop its slip, in least squares where they
    // cannot: a corner lifting off).
    for (Eigen::Index i = 0; i < m; ++i)
      if (!(r.fn[i] > 0)) sliding_[static_cast<std::size_t>(i)] = true;
    for (;;) {
      for (Eigen::Index i = 0; i < m; ++i)
        if (sliding_[static_cast<std::size_t>(i)])
          r.ft.segment<2>(2 * i) = mu[i] * r.fn[i] * direction_[static_cast<std::size_t>(i)];
      stick_rows_.clear();
      for (Eigen::Index i = 0; i < m; ++i)
        if (!sliding_[static_cast<std::size_t>(i)]) stick_rows_.push_back(2 * i), stick_rows_.push_back(2 * i + 1);
      if (stick_rows_.empty()) break;
      const auto k = static_cast<Eigen::Index>(stick_rows_.size());
      schur_columns(Att);
      // The sticking rows' load: c plus what the sliders' friction does there, read down each
      // sticking row's column of S (S is symmetric), each slider's two terms summed first.
      sliding_now_.clear();
      for (Eigen::Index i = 0; i < m; ++i)
        if (sliding_[static_cast<std::size_t>(i)]) sliding_now_.push_back(static_cast<int>(i));
      load_.resize(2 * m);
      for (Eigen::Index a = 0; a < k; ++a) {
        const Eigen::Index row = stick_rows_[static_cast<std::size_t>(a)];
        const double* s = S_.col(row).data();
        double sum = c_[row];
        for (const int i : sliding_now_) sum += s[2 * i] * r.ft[2 * i] + s[2 * i + 1] * r.ft[2 * i + 1];
        load_[row] = sum;
      }
      // The exact solution nearest zero in the metric sum |f_t,i|^2 / (mu f_n,i): each contact
      // carries friction in proportion to what it can hold (none without a normal force), so
      // they all reach their rims together, at the true breakaway.
      weight_.resize(k);
      for (Eigen::Index a = 0; a < k; ++a) {
        const Eigen::Index i = stick_rows_[static_cast<std::size_t>(a)] / 2;
        weight_[a] = std::sqrt(std::max(0.0, mu[i] * r.fn[i]));
      }
      // (Akk W y = rhs and W Akk W y = W rhs have the same solutions; the second is symmetric.)
      // W Akk W, gathered from S column by column (contiguous).
      Bkk_.resize(k, k);
      rhs_.resize(k);
      for (Eigen::Index b = 0; b < k; ++b) {
        const Eigen::Index col = stick_rows_[static_cast<std::size_t>(b)];
        const double* s = S_.col(col).data();
        double* out = Bkk_.col(b).data();
        for (Eigen::Index a = 0; a < k; ++a)
          out[a] = weight_[a] * s[stick_rows_[static_cast<std::size_t>(a)]] * weight_[b];
        rhs_[b] = -load_[col];
      }
      stick_inverse_.compute(Bkk_, kStickRank);
      stick_inverse_.solve(weight_.cwiseProduct(rhs_), y_);
      x_ = weight_.cwiseProduct(y_);
      // Contacts that slide fast and cannot stick start to slide first: the forces that would
      // stop them within the step load the contacts around them beyond their cones too (a box
      // sliding over a resting one would take the lower box's table friction to its rim, twice
      // what holds it, and drag it backwards); those are asked again once the fast ones slide.
      bool fast_beyond = false;
      for (Eigen::Index a = 0; a < k && !fast_beyond; a += 2) {
        const Eigen::Index i = stick_rows_[static_cast<std::size_t>(a)] / 2;
        fast_beyond = !against_[static_cast<std::size_t>(i)].isZero() && beyond_cone(x_.segment<2>(a), mu[i] * r.fn[i]);
      }
      bool changed = false;
      for (Eigen::Index a = 0; a < k; a += 2) {
        const Eigen::Index i = stick_rows_[static_cast<std::size_t>(a)] / 2;
        const Eigen::Vector2d need = x_.segment<2>(a);
        r.ft.segment<2>(2 * i) = need;
        const double bound = mu[i] * r.fn[i];
        if (fast_beyond && against_[static_cast<std::size_t>(i)].isZero()) continue;
        if (beyond_cone(need, bound)) {  // it cannot stick: it starts to slide
          sliding_[static_cast<std::size_t>(i)] = true;
          const Eigen::Vector2d& slip = against_[static_cast<std::size_t>(i)];
          direction_[static_cast<std::size_t>(i)] = !slip.isZero()      ? slip
                                                    : need.norm() > 0.0 ? Eigen::Vector2d(need.normalized())
                                                                        : Eigen::Vector2d::Zero();
          changed = true;
        }
      }
      if (!changed) break;
    }
    // The sliders' friction is mu f_n with f_n what the touching set answers that very friction
    // (and the stickers' answer to it) with: solved for at once.
    if (nt > 0) anticipate_sliders(mu, r);
    // What the forces do, with the normal forces this round's friction will get from the touching
    // set (f_n less Ann_TT^+ Ant_T times the friction's change; exact while the set stays): the
    // rounds are done once that stops changing, a round before the normal forces have caught up.
    f_ << r.fn, r.ft;
    if (const auto nt = static_cast<Eigen::Index>(touching_.size()); nt > 0) {
      ft_seen_ = r.ft - ft_seen_;
      answer_.noalias() = factor().AntC * ft_seen_;
      factor().inverse.solve(answer_, answer_);
      for (Eigen::Index i = 0; i < nt; ++i) f_[touching_[static_cast<std::size_t>(i)]] -= answer_[i];
    }
    effect_.noalias() = A * f_;
    const double change = (effect_ - effect_prev_).cwiseAbs().maxCoeff();
    if (change <= tolerance * load) {
      r.converged = true;
      return r;
    }
    if (anticipation_holds(bn, mu, load, r)) {
      r.converged = true;
      return r;
    }
    if (r.iterations > 1 && change < 0.5 * best_change) best_change = change, best_round = r.iterations;
    // A two-round cycle: the forces and what they do are what they were two rounds before (a
    // jam's touching set alternating between two, a contact more or less), so the rounds to come
    // repeat these two, every change the same and none halving, to the stall. Ended now, on the
    // answer the stall would end on: this round's, or the last one's where the rounds left are odd.
    if (end_two_round_cycles && r.iterations >= 3 && repeats_two_rounds_back(r, load)) {
      const int stall_at = std::min(max_rounds, std::max(r.iterations, best_round + stall_rounds));
      if ((stall_at - r.iterations) % 2 == 1) r.fn.swap(fn_last_), r.ft.swap(ft_last_);
      break;
    }
    if (r.iterations - best_round >= stall_rounds) break;
    effect_before_.swap(effect_prev_);
    effect_prev_.swap(effect_);
    fn_before_.swap(fn_last_);
    ft_before_.swap(ft_last_);
    fn_last_ = r.fn;
    ft_last_ = r.ft;
  }
  r.iterations = std::min(r.iterations, max_rounds);
  // Not settled within the rounds: the last normal solve is still exact for the friction it saw,
  // so non-penetration holds; the caller reports it.
  return r;
}

bool FrictionSolver::repeats_two_rounds_back(const FrictionResult& r, double load) const {
  const double force_scale = std::max(1e-300, r.fn.cwiseAbs().maxCoeff());
  return (effect_ - effect_before_).cwiseAbs().maxCoeff() <= tolerance * load &&
         (r.fn - fn_before_).cwiseAbs().maxCoeff() <= tolerance * force_scale &&
         (r.ft - ft_before_).cwiseAbs().maxCoeff() <= tolerance * force_scale;
}

bool FrictionSolver::without_friction_settles(const Eigen::MatrixXd& A, const LcpResult& normal,
                                              const Eigen::VectorXd& bt, const Eigen::VectorXd& mu, double load,
                                              FrictionResult& r) {
  if (!ft_seen_.isZero(0.0)) return false;  // (the LCP saw a friction load: not the frictionless one)
  const auto m = static_cast<Eigen::Index>(mu.size());
  for (Eigen::Index i = 0; i < m; ++i)
    if (moving_[static_cast<std::size_t>(i)] && mu[i] > 0) return false;  // a slider has friction
  // The tangential rows without friction: what the stick solve would cancel. (A f_n is the same for
  // every normal force that does what the LCP's do, so the spread would not change it.)
  c_.noalias() = A.bottomLeftCorner(2 * m, m) * normal.f;
  c_ += bt;
  if (c_.cwiseAbs().maxCoeff() > tolerance * load) return false;
  r.ft.setZero();
  r.converged = true;
  return true;
}

}  // namespace wysiwyf::haptics
