#include "rigid_body/friction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wysiwyf::haptics {
namespace {

// Pivots below these fractions of the largest end the factorisations (psd_pseudo_inverse.hpp):
// a touching contact whose row depends on the others' within the LCP's own test of a dependent
// row (1e-10 of A's scale), and round-off in the sticking rows' Schur complement.
constexpr double kTouchingRank = 1e-9;
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

void FrictionSolver::anticipate_sliders(const Eigen::VectorXd& mu, FrictionResult& r) {
  const auto nt = static_cast<Eigen::Index>(touching_.size());
  sliders_.clear();  // (contact, its place in the touching set)
  for (Eigen::Index t = 0; t < nt; ++t) {
    const int i = touching_[static_cast<std::size_t>(t)];
    const auto u = static_cast<std::size_t>(i);
    if (sliding_[u] && mu[i] > 0 && r.fn[i] > 0 && !direction_[u].isZero()) sliders_.push_back({i, t});
  }
  const auto ns = static_cast<Eigen::Index>(sliders_.size());
  if (ns == 0) return;
  const Eigen::MatrixXd& S_ = factor().S;
  const Eigen::MatrixXd& Z_ = factor().Z;
  const Eigen::MatrixXd& F_ = factor().F;
  const auto k = static_cast<Eigen::Index>(stick_rows_.size());
  // The touching forces f_T' = g - W ft: g = f_T + Ann_TT^+ Ant_T ft_seen (what they were, less
  // their answer to the friction the LCP saw), W = Ann_TT^+ Ant_T. The sliders' friction is
  // lambda D, the stickers' what the stick solve gives for it: ft_K = a - G lambda (G = K S_KS D,
  // K the stick solve's linear map, a its answer without the sliders). Over the sliders:
  // lambda = mu (g - W_K a + (W_K G - W_S D) lambda), a linear system of their number.
  // Through the half inverse F (F^T F = Ann_TT^+, F Ant_T = Z): W x = F^T Z x, and only the
  // sliders' rows of it are needed, F_S^T (Z x): no solve with Ann_TT^+ for each slider.
  F_sliders_.resize(F_.rows(), ns);
  slider_cols_.resize(Z_.rows(), ns);  // Z D, less Z_K G below
  for (Eigen::Index j = 0; j < ns; ++j) {
    const auto [i, t] = sliders_[static_cast<std::size_t>(j)];
    const Eigen::Vector2d& d = direction_[static_cast<std::size_t>(i)];
    F_sliders_.col(j) = F_.col(t);
    slider_cols_.col(j) = Z_.col(2 * i) * d.x() + Z_.col(2 * i + 1) * d.y();
  }
  answer_.noalias() = Z_ * ft_seen_;  // Z (ft_seen - scatter(a)) below
  if (k > 0) {
    // G, column j: K (S_K,j d_j), K = W B^+ W as the stick solve applies it.
    stick_cols_.resize(k, ns);
    for (Eigen::Index j = 0; j < ns; ++j) {
      const auto [i, t] = sliders_[static_cast<std::size_t>(j)];
      const Eigen::Vector2d& d = direction_[static_cast<std::size_t>(i)];
      for (Eigen::Index a = 0; a < k; ++a) {
        const Eigen::Index row = stick_rows_[static_cast<std::size_t>(a)];
        stick_cols_(a, j) = weight_[a] * (S_(2 * i, row) * d.x() + S_(2 * i + 1, row) * d.y());  // (S symmetric)
      }
    }
    stick_inverse_.solve(stick_cols_, stick_cols_);
    stick_cols_ = weight_.asDiagonal() * stick_cols_;
    stick_free_ = x_;  // a = the stickers' answer + G lambda_now
    for (Eigen::Index j = 0; j < ns; ++j) {
      const int i = sliders_[static_cast<std::size_t>(j)].first;
      stick_free_.noalias() += stick_cols_.col(j) * (mu[i] * r.fn[i]);
    }
    // Z over the stickers' columns: into answer_ (with g's term) and slider_cols_.
    Z_sticking_.resize(Z_.rows(), k);
    for (Eigen::Index a = 0; a < k; ++a) Z_sticking_.col(a) = Z_.col(stick_rows_[static_cast<std::size_t>(a)]);
    answer_.noalias() -= Z_sticking_ * stick_free_;
    slider_cols_.noalias() -= Z_sticking_ * stick_cols_;
  }
  slider_system_.noalias() = F_sliders_.transpose() * slider_cols_;
  slider_rhs_.noalias() = F_sliders_.transpose() * answer_;
  for (Eigen::Index j = 0; j < ns; ++j) {
    const int i = sliders_[static_cast<std::size_t>(j)].first;
    slider_system_.row(j) *= mu[i];
    slider_system_(j, j) += 1;
    slider_rhs_[j] = mu[i] * (r.fn[i] + slider_rhs_[j]);
  }
  slider_lu_.compute(slider_system_);
  const Eigen::VectorXd lambda = slider_lu_.solve(slider_rhs_);
  // A slider pressed off (a negative magnitude) or a singular answer: the round's own friction.
  if (!lambda.allFinite() || lambda.minCoeff() < 0) return;
  for (Eigen::Index j = 0; j < ns; ++j) {
    const int i = sliders_[static_cast<std::size_t>(j)].first;
    r.ft.segment<2>(2 * i) = lambda[j] * direction_[static_cast<std::size_t>(i)];
  }
  if (k > 0) {
    stick_free_.noalias() -= stick_cols_ * lambda;
    for (Eigen::Index a = 0; a < k; ++a) r.ft[stick_rows_[static_cast<std::size_t>(a)]] = stick_free_[a];
  }
}

bool FrictionSolver::anticipation_holds(const Eigen::VectorXd& bn, const Eigen::VectorXd& mu, double load,
                                        FrictionResult& r) {
  const auto m = static_cast<Eigen::Index>(bn.size());
  const auto fn = f_.head(m);  // the anticipated normal forces
  // The touching contacts stay at zero acceleration (Ant_T dft is in the range of Ann_TT: the
  // touching answer cancels it); they must stay in compression, the others must not close.
  const double force_scale = std::max(1e-300, r.fn.cwiseAbs().maxCoeff());
  touching_mask_.assign(static_cast<std::size_t>(m), false);
  for (int i : touching_) touching_mask_[static_cast<std::size_t>(i)] = true;
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto u = static_cast<std::size_t>(i);
    if (touching_mask_[u] ? fn[i] < -1e-9 * force_scale : effect_[i] + bn[i] < -tolerance * load) return false;
    if (mu[i] <= 0) continue;
    const double bound = mu[i] * std::max(0.0, fn[i]);
    if (sliding_[u]) {
      // A slider's friction must be mu f_n of these forces (anticipate_sliders' answer; a free
      // contact, without force, stays free only if it stays without).
      if (std::abs(r.ft.segment<2>(2 * i).norm() - bound) > 1e-9 * mu[i] * force_scale) return false;
    } else if (r.ft.segment<2>(2 * i).norm() > bound * (1 + 1e-12)) {
      return false;  // a sticker whose cone the anticipated force narrowed below its friction
    }
  }
  for (Eigen::Index i = 0; i < m; ++i) r.fn[i] = std::max(0.0, fn[i]);
  return true;
}

bool FrictionSolver::last_set_carries(Eigen::VectorXd& fn) {
  const auto nc = static_cast<Eigen::Index>(touching_last_.size());
  if (nc == 0 || touching_ == touching_last_ ||
      !std::includes(touching_.begin(), touching_.end(), touching_last_.begin(), touching_last_.end()))
    return false;
  // What the LCP's forces do on every touching contact, and the least forces over the last set
  // that do it on that set's (factor() is still that set's).
  const auto nt = static_cast<Eigen::Index>(touching_.size());
  motion_.setZero(nt);
  for (Eigen::Index j = 0; j < nt; ++j) {
    const int c = touching_[static_cast<std::size_t>(j)];
    if (fn[c] == 0.0) continue;
    for (Eigen::Index i = 0; i < nt; ++i) motion_[i] += Ann_(touching_[static_cast<std::size_t>(i)], c) * fn[c];
  }
  carried_.resize(nc);
  for (Eigen::Index i = 0, k = 0; i < nt && k < nc; ++i)
    if (touching_[static_cast<std::size_t>(i)] == touching_last_[static_cast<std::size_t>(k)])
      carried_[k++] = motion_[i];
  factor().inverse.solve(carried_, carried_);
  const double scale = std::max(1e-300, motion_.cwiseAbs().maxCoeff());
  const double force_scale = std::max(1e-300, carried_.cwiseAbs().maxCoeff());
  if (carried_.minCoeff() < -1e-12 * force_scale) return false;
  // They must do the same on every touching contact (the others' rows depend on the set's).
  for (Eigen::Index i = 0; i < nt; ++i) {
    double done = 0;
    for (Eigen::Index k = 0; k < nc; ++k)
      done += Ann_(touching_[static_cast<std::size_t>(i)], touching_last_[static_cast<std::size_t>(k)]) * carried_[k];
    if (std::abs(done - motion_[i]) > 1e-9 * scale) return false;
  }
  for (int c : touching_) fn[c] = 0.0;
  for (Eigen::Index k = 0; k < nc; ++k) fn[touching_last_[static_cast<std::size_t>(k)]] = std::max(0.0, carried_[k]);
  touching_ = touching_last_;
  return true;
}

void FrictionSolver::schur_columns(const Eigen::Ref<const Eigen::MatrixXd>& Att) {
  TouchingFactors& f = factor();
  if (f.s_whole) return;
  const Eigen::Index n = Att.rows();
  Eigen::Index missing = 0;
  for (const Eigen::Index c : stick_rows_) missing += !f.s_column[static_cast<std::size_t>(c)];
  if (missing == 0) return;
  const Eigen::Index nt = f.Z.rows();
  if (2 * missing > n) {
    // S whole: one triangle by a symmetric rank update, and its mirror (cheaper than the full
    // product, which makes both triangles).
    f.S = Att;
    f.S.selfadjointView<Eigen::Lower>().rankUpdate(f.Z.transpose(), -1.0);
    f.S.triangularView<Eigen::StrictlyUpper>() = f.S.transpose();
    f.s_whole = true;
    return;
  }
  // Column by column: S(:, c) = Att(:, c) - sum_l Z(l, :)^T Z(l, c), the terms taken in the same
  // order for every entry, so S(a, c) and S(c, a) are the same to the bit.
  if (f.Zt.rows() != n) {
    f.Zt = f.Z.transpose();
    f.S.resize(n, n);
  }
  for (const Eigen::Index c : stick_rows_) {
    if (f.s_column[static_cast<std::size_t>(c)]) continue;
    f.s_column[static_cast<std::size_t>(c)] = 1;
    double* out = f.S.col(c).data();
    for (Eigen::Index a = 0; a < n; ++a) out[a] = Att(a, c);
    for (Eigen::Index l = 0; l < nt; ++l) {
      const double z = f.Z(l, c);
      const double* zt = f.Zt.col(l).data();
      for (Eigen::Index a = 0; a < n; ++a) out[a] -= zt[a] * z;
    }
  }
}

void FrictionSolver::bind_factor() {
  std::size_t oldest = 0;
  for (std::size_t k = 0; k < factors_.size(); ++k) {
    TouchingFactors& f = factors_[k];
    if (f.used > 0 && f.set == touching_) {
      bound_ = k;
      f.used = ++uses_;
      return;
    }
    if (f.used < factors_[oldest].used) oldest = k;
  }
  // A set not seen in this solve: factored in place of the one least recently used.
  bound_ = oldest;
  TouchingFactors& f = factors_[oldest];
  f.set = touching_;
  f.used = ++uses_;
  f.schur = false;
  const auto nt = static_cast<Eigen::Index>(touching_.size());
  f.Ann.resize(nt, nt);
  for (Eigen::Index i = 0; i < nt; ++i)
    for (Eigen::Index j = 0; j < nt; ++j)
      f.Ann(i, j) = Ann_(touching_[static_cast<std::size_t>(i)], touching_[static_cast<std::size_t>(j)]);
  f.inverse.compute(f.Ann, kTouchingRank);
}

void FrictionSolver::spread_normal_forces(const LcpResult& normal, double load, Eigen::VectorXd& fn) {
  const auto m = static_cast<Eigen::Index>(fn.size());
  // Touching: clamped, or without force at (round-off from) zero acceleration, a contact the
  // pivoting kept out of C because its row depends on the clamped ones'.
  touching_next_.clear();
  const double at_zero = 1e-9 * std::max(load, normal.a.size() > 0 ? normal.a.cwiseAbs().maxCoeff() : 0.0);
  for (Eigen::Index i = 0; i < m; ++i)
    if (normal.f[i] > 0 || normal.a[i] <= at_zero) touching_next_.push_back(static_cast<int>(i));
  // The least forces that do what the LCP's do, Ann_TT^+ Ann_TT f, spread the load over every
  // touching contact and move continuously with the load. Redundant contacts: every f + v with
  // Ann_TT v = 0 does what f does (v moves no body: J_T^T v = 0), so the choice among them is
  // free; the pivoting picks a vertex (one of a face's four corners without force), and which
  // vertex flips with the friction load, taking the friction of the corner it drops: staggered
  // rounds cycled between two such sets without end. Where the least forces would pull on a
  // contact, the forces go from the LCP's towards them until that contact's reaches zero, and it
  // leaves the set (it carries nothing) for the rest to share the load: an active set, ending at
  // the least forces >= 0 over the contacts that carry them (a contact or two leave, in a pile).
  // Those move with the friction load as the touching set's answer to it, Ann_TT^+ Ant_T, which
  // is what the rounds anticipate (forces stopped at the first contact to reach zero would move
  // with the load in a way the anticipation does not see, and the rounds would converge only
  // geometrically instead of settling).
  touching_last_.swap(touching_);
  touching_.swap(touching_next_);
  // (Where the last round's carrying set still carries the load, it is kept with its factor: a
  // settled jam's round does not factor the touching set and then the same carrying set again.)
  if (last_set_carries(fn)) return;
  for (;;) {
    const auto nt = static_cast<Eigen::Index>(touching_.size());
    if (nt == 0) break;
    f_touching_.resize(nt);
    for (Eigen::Index i = 0; i < nt; ++i) f_touching_[i] = fn[touching_[static_cast<std::size_t>(i)]];
    bind_factor();
    if (factor().inverse.rank() == nt) break;  // (no redundant contact: the forces are unique)
    spread_.noalias() = factor().Ann * f_touching_;
    factor().inverse.solve(spread_, spread_);
    double toward = 1.0;
    Eigen::Index reaches_zero = -1;
    for (Eigen::Index i = 0; i < nt; ++i) {
      if (spread_[i] >= 0) continue;
      const double at = f_touching_[i] / (f_touching_[i] - spread_[i]);
      if (at < toward) toward = at, reaches_zero = i;
    }
    for (Eigen::Index i = 0; i < nt; ++i)
      fn[touching_[static_cast<std::size_t>(i)]] =
          std::max(0.0, f_touching_[i] + toward * (spread_[i] - f_touching_[i]));
    if (reaches_zero < 0) break;
    fn[touching_[static_cast<std::size_t>(reaches_zero)]] = 0.0;
    touching_.erase(touching_.begin() + reaches_zero);
  }
}

}  // namespace wysiwyf::haptics
