// FrictionSolver's touching-set phase: the normal forces spread over redundant contacts, the
// factors of the touching set kept between rounds, and the Schur complement's columns.
#include "rigid_body/friction.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::haptics {
namespace {

// Pivots below this fraction of the largest end the touching set's factorisation
// (psd_pseudo_inverse.hpp): a touching contact whose row depends on the others' within the LCP's
// own test of a dependent row (1e-10 of A's scale).
constexpr double kTouchingRank = 1e-9;

}  // namespace

bool FrictionSolver::last_set_carries(Eigen::VectorXd& fn) {
  const auto nc = static_cast<Eigen::Index>(carry_.last.size());
  if (nc == 0 || touching_ == carry_.last ||
      !std::includes(touching_.begin(), touching_.end(), carry_.last.begin(), carry_.last.end()))
    return false;
  // What the LCP's forces do on every touching contact, and the least forces over the last set
  // that do it on that set's (factor() is still that set's).
  const auto nt = static_cast<Eigen::Index>(touching_.size());
  carry_.motion.setZero(nt);
  for (Eigen::Index j = 0; j < nt; ++j) {
    const int c = touching_[static_cast<std::size_t>(j)];
    if (fn[c] == 0.0) continue;
    for (Eigen::Index i = 0; i < nt; ++i) carry_.motion[i] += Ann_(touching_[static_cast<std::size_t>(i)], c) * fn[c];
  }
  carry_.carried.resize(nc);
  for (Eigen::Index i = 0, k = 0; i < nt && k < nc; ++i)
    if (touching_[static_cast<std::size_t>(i)] == carry_.last[static_cast<std::size_t>(k)])
      carry_.carried[k++] = carry_.motion[i];
  factor().inverse.solve(carry_.carried, carry_.carried);
  const double scale = std::max(1e-300, carry_.motion.cwiseAbs().maxCoeff());
  const double force_scale = std::max(1e-300, carry_.carried.cwiseAbs().maxCoeff());
  if (carry_.carried.minCoeff() < -1e-12 * force_scale) return false;
  // They must do the same on every touching contact (the others' rows depend on the set's).
  for (Eigen::Index i = 0; i < nt; ++i) {
    double done = 0;
    for (Eigen::Index k = 0; k < nc; ++k)
      done +=
          Ann_(touching_[static_cast<std::size_t>(i)], carry_.last[static_cast<std::size_t>(k)]) * carry_.carried[k];
    if (std::abs(done - carry_.motion[i]) > 1e-9 * scale) return false;
  }
  for (int c : touching_) fn[c] = 0.0;
  for (Eigen::Index k = 0; k < nc; ++k) fn[carry_.last[static_cast<std::size_t>(k)]] = std::max(0.0, carry_.carried[k]);
  touching_ = carry_.last;
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
  carry_.next.clear();
  const double at_zero = 1e-9 * std::max(load, normal.a.size() > 0 ? normal.a.cwiseAbs().maxCoeff() : 0.0);
  for (Eigen::Index i = 0; i < m; ++i)
    if (normal.f[i] > 0 || normal.a[i] <= at_zero) carry_.next.push_back(static_cast<int>(i));
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
  carry_.last.swap(touching_);
  touching_.swap(carry_.next);
  // (Where the last round's carrying set still carries the load, it is kept with its factor: a
  // settled jam's round does not factor the touching set and then the same carrying set again.)
  if (last_set_carries(fn)) return;
  for (;;) {
    const auto nt = static_cast<Eigen::Index>(touching_.size());
    if (nt == 0) break;
    carry_.f_touching.resize(nt);
    for (Eigen::Index i = 0; i < nt; ++i) carry_.f_touching[i] = fn[touching_[static_cast<std::size_t>(i)]];
    bind_factor();
    if (factor().inverse.rank() == nt) break;  // (no redundant contact: the forces are unique)
    carry_.spread.noalias() = factor().Ann * carry_.f_touching;
    factor().inverse.solve(carry_.spread, carry_.spread);
    double toward = 1.0;
    Eigen::Index reaches_zero = -1;
    for (Eigen::Index i = 0; i < nt; ++i) {
      if (carry_.spread[i] >= 0) continue;
      const double at = carry_.f_touching[i] / (carry_.f_touching[i] - carry_.spread[i]);
      if (at < toward) toward = at, reaches_zero = i;
    }
    for (Eigen::Index i = 0; i < nt; ++i)
      fn[touching_[static_cast<std::size_t>(i)]] =
          std::max(0.0, carry_.f_touching[i] + toward * (carry_.spread[i] - carry_.f_touching[i]));
    if (reaches_zero < 0) break;
    fn[touching_[static_cast<std::size_t>(reaches_zero)]] = 0.0;
    touching_.erase(touching_.begin() + reaches_zero);
  }
}

}  // namespace wysiwyf::haptics
