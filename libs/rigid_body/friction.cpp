#include "rigid_body/friction.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::haptics {

FrictionResult FrictionSolver::solve(LcpSolver& lcp, const Eigen::MatrixXd& A, const Eigen::VectorXd& bn,
                                     const Eigen::VectorXd& bt, const Eigen::VectorXd& mu, const Eigen::VectorXd& vt,
                                     const Eigen::VectorXd& ft_start) {
  const Eigen::Index m = bn.size();
  FrictionResult r;
  r.fn = Eigen::VectorXd::Zero(m);
  r.ft = ft_start.size() == 2 * m ? ft_start : Eigen::VectorXd::Zero(2 * m);
  Ann_ = A.topLeftCorner(m, m);
  const auto Ant = A.topRightCorner(m, 2 * m);
  const auto Atn = A.bottomLeftCorner(2 * m, m);
  const auto Att = A.bottomRightCorner(2 * m, 2 * m);
  // Sliding contacts and the unit direction of their friction (in the tangent basis).
  std::vector<bool> moving(static_cast<std::size_t>(m), false), sliding;
  std::vector<Eigen::Vector2d> against(static_cast<std::size_t>(m), Eigen::Vector2d::Zero()), direction;
  // With stick_first every contact with friction is first asked to stick: to meet its target
  // (bt: stop sliding by the horizon) within its cone; one that cannot slides at the rim, against
  // its velocity if it slides (maximal dissipation), else along the force it needed. A sliding
  // contact is no exception: mu f_n against its velocity, held for a whole step, reversed a slow
  // one within the step (a spinning cube's corners swapped direction every step and it never
  // stopped); one that the cone can stop within the horizon stops.
  for (Eigen::Index i = 0; i < m; ++i) {
    const Eigen::Vector2d v = vt.segment<2>(2 * i);
    // (a frictionless contact: a slider with no force)
    if (mu[i] <= 0.0 || (!stick_first && v.norm() > sliding_speed)) moving[static_cast<std::size_t>(i)] = true;
    if (v.norm() > sliding_speed) against[static_cast<std::size_t>(i)] = -v.normalized();
  }
  // Convergence is judged on what the forces do, A [fn; ft] (contact-space accelerations or
  // velocity changes): with redundant contacts the forces themselves are not unique.
  Eigen::VectorXd f(3 * m), effect(3 * m), effect_prev = Eigen::VectorXd::Zero(3 * m);
  const double load = std::max({1e-12, bn.cwiseAbs().maxCoeff(), bt.cwiseAbs().maxCoeff()});
  std::vector<Eigen::Index> stick_rows;
  Eigen::MatrixXd Akk;
  Eigen::VectorXd rhs, weight;
  LcpIndices clamped;  // each round's normal LCP starts from the last one's clamped set
  for (r.iterations = 1; r.iterations <= max_rounds; ++r.iterations) {
    // Normal forces, friction as a known load.
    bn_eff_ = bn + Ant * r.ft;
    const LcpResult normal = lcp.solve(Ann_, bn_eff_, clamped);
    if (!normal.ok) return r;
    clamped = normal.clamped;
    r.ok = true;
    r.fn = normal.f;
    // The friction step sees the tangential rows as the clamped normal contacts will answer them:
    // a friction force tilts the body, and the clamped contacts' forces change to stop the tilt.
    // With the Schur complement S = Att - Atn_C Ann_CC^-1 Ant_C in place of Att (and the load
    // moved to match), the friction found is already the one that holds after the next normal
    // solve, as long as the clamped set stays: the rounds settle in two or three, not the
    // twenty-odd of plain alternation (which converges by about 0.6 a round).
    S_ = Att;
    c_ = bt + Atn * r.fn;  // the tangential rows' load at the current forces, less Att ft
    if (const Eigen::Index nc = clamped.size(); nc > 0) {
      AntC_.resize(nc, 2 * m);
      Acc_.resize(nc, nc);
      for (Eigen::Index i = 0; i < nc; ++i) {
        AntC_.row(i) = Ant.row(clamped[i]);
        for (Eigen::Index j = 0; j < nc; ++j) Acc_(i, j) = Ann_(clamped[i], clamped[j]);
      }
      const Eigen::LDLT<Eigen::MatrixXd> ldlt(Acc_);
      const auto d = ldlt.vectorD().cwiseAbs();
      if (ldlt.info() == Eigen::Success && d.minCoeff() > 1e-12 * d.maxCoeff()) {  // (C is kept regular)
        X_ = ldlt.solve(AntC_);  // Ann_CC^-1 Ant_C: how the clamped forces answer a friction force
        S_.noalias() -= AntC_.transpose() * X_;
        c_.noalias() += AntC_.transpose() * (X_ * r.ft);
      }
    }
    // Friction forces, normal forces fixed: sliders at the rim, stickers exact; a sticker beyond
    // its rim becomes a slider and the stickers are solved again.
    sliding = moving;
    direction = against;
    // A contact without normal force can hold no friction: it is free, not asked to stick (its
    // rows would otherwise ask the others' friction to stop its slip, in least squares where they
    // cannot: a corner lifting off).
    for (Eigen::Index i = 0; i < m; ++i)
      if (!(r.fn[i] > 0)) sliding[static_cast<std::size_t>(i)] = true;
    for (;;) {
      for (Eigen::Index i = 0; i < m; ++i)
        if (sliding[static_cast<std::size_t>(i)])
          r.ft.segment<2>(2 * i) = mu[i] * r.fn[i] * direction[static_cast<std::size_t>(i)];
      stick_rows.clear();
      for (Eigen::Index i = 0; i < m; ++i)
        if (!sliding[static_cast<std::size_t>(i)]) stick_rows.push_back(2 * i), stick_rows.push_back(2 * i + 1);
      if (stick_rows.empty()) break;
      const auto k = static_cast<Eigen::Index>(stick_rows.size());
      Akk.resize(k, k);
      rhs.resize(k);
      for (Eigen::Index a = 0; a < k; ++a) {
        const Eigen::Index row = stick_rows[static_cast<std::size_t>(a)];
        double load_a = c_[row];
        for (Eigen::Index i = 0; i < m; ++i)
          if (sliding[static_cast<std::size_t>(i)]) load_a += S_.row(row).segment<2>(2 * i).dot(r.ft.segment<2>(2 * i));
        rhs[a] = -load_a;
        for (Eigen::Index b = 0; b < k; ++b) Akk(a, b) = S_(row, stick_rows[static_cast<std::size_t>(b)]);
      }
      // The exact solution nearest zero in the metric sum |f_t,i|^2 / (mu f_n,i): each contact
      // carries friction in proportion to what it can hold (none without a normal force), so
      // they all reach their rims together, at the true breakaway.
      weight.resize(k);
      for (Eigen::Index a = 0; a < k; ++a) {
        const Eigen::Index i = stick_rows[static_cast<std::size_t>(a)] / 2;
        weight[a] = std::sqrt(std::max(0.0, mu[i] * r.fn[i]));
      }
      cod_.compute(Akk * weight.asDiagonal());
      const Eigen::VectorXd x = weight.cwiseProduct(cod_.solve(rhs));
      bool changed = false;
      for (Eigen::Index a = 0; a < k; a += 2) {
        const Eigen::Index i = stick_rows[static_cast<std::size_t>(a)] / 2;
        const Eigen::Vector2d need = x.segment<2>(a);
        r.ft.segment<2>(2 * i) = need;
        const double bound = mu[i] * r.fn[i];
        if (need.norm() > bound * (1 + 1e-12) + 1e-300) {  // it cannot stick: it starts to slide
          sliding[static_cast<std::size_t>(i)] = true;
          const Eigen::Vector2d& slip = against[static_cast<std::size_t>(i)];
          direction[static_cast<std::size_t>(i)] = !slip.isZero()      ? slip
                                                   : need.norm() > 0.0 ? Eigen::Vector2d(need.normalized())
                                                                       : Eigen::Vector2d::Zero();
          changed = true;
        }
      }
      if (!changed) break;
    }
    f << r.fn, r.ft;
    effect.noalias() = A * f;
    const double change = (effect - effect_prev).cwiseAbs().maxCoeff();
    effect_prev = effect;
    if (r.iterations > 1 && change <= tolerance * load) {
      r.converged = true;
      return r;
    }
  }
  r.iterations = max_rounds;
  // Not settled within the rounds: the last normal solve is still exact for the friction it saw,
  // so non-penetration holds; the caller reports it.
  return r;
}

}  // namespace wysiwyf::haptics
