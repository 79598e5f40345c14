// FrictionSolver's slider phase: the sliders' friction solved with the touching set's answer to it
// anticipated, and the test whether that answer already ends the rounds.
#include "rigid_body/friction.hpp"

#include <algorithm>
#include <cmath>

namespace wysiwyf::haptics {

void FrictionSolver::anticipate_sliders(const Eigen::VectorXd& mu, FrictionResult& r) {
  const auto nt = static_cast<Eigen::Index>(touching_.size());
  slide_.sliders.clear();  // (contact, its place in the touching set)
  for (Eigen::Index t = 0; t < nt; ++t) {
    const int i = touching_[static_cast<std::size_t>(t)];
    const auto u = static_cast<std::size_t>(i);
    if (sliding_[u] && mu[i] > 0 && r.fn[i] > 0 && !direction_[u].isZero()) slide_.sliders.push_back({i, t});
  }
  const auto ns = static_cast<Eigen::Index>(slide_.sliders.size());
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
  slide_.F_sliders.resize(F_.rows(), ns);
  slide_.cols.resize(Z_.rows(), ns);  // Z D, less Z_K G below
  for (Eigen::Index j = 0; j < ns; ++j) {
    const auto [i, t] = slide_.sliders[static_cast<std::size_t>(j)];
    const Eigen::Vector2d& d = direction_[static_cast<std::size_t>(i)];
    slide_.F_sliders.col(j) = F_.col(t);
    slide_.cols.col(j) = Z_.col(2 * i) * d.x() + Z_.col(2 * i + 1) * d.y();
  }
  answer_.noalias() = Z_ * ft_seen_;  // Z (ft_seen - scatter(a)) below
  if (k > 0) {
    // G, column j: K (S_K,j d_j), K = W B^+ W as the stick solve applies it.
    slide_.stick_cols.resize(k, ns);
    for (Eigen::Index j = 0; j < ns; ++j) {
      const auto [i, t] = slide_.sliders[static_cast<std::size_t>(j)];
      const Eigen::Vector2d& d = direction_[static_cast<std::size_t>(i)];
      for (Eigen::Index a = 0; a < k; ++a) {
        const Eigen::Index row = stick_rows_[static_cast<std::size_t>(a)];
        slide_.stick_cols(a, j) = weight_[a] * (S_(2 * i, row) * d.x() + S_(2 * i + 1, row) * d.y());  // (S symmetric)
      }
    }
    stick_inverse_.solve(slide_.stick_cols, slide_.stick_cols);
    slide_.stick_cols = weight_.asDiagonal() * slide_.stick_cols;
    slide_.stick_free = x_;  // a = the stickers' answer + G lambda_now
    for (Eigen::Index j = 0; j < ns; ++j) {
      const int i = slide_.sliders[static_cast<std::size_t>(j)].first;
      slide_.stick_free.noalias() += slide_.stick_cols.col(j) * (mu[i] * r.fn[i]);
    }
    // Z over the stickers' columns: into answer_ (with g's term) and slide_.cols.
    slide_.Z_sticking.resize(Z_.rows(), k);
    for (Eigen::Index a = 0; a < k; ++a) slide_.Z_sticking.col(a) = Z_.col(stick_rows_[static_cast<std::size_t>(a)]);
    answer_.noalias() -= slide_.Z_sticking * slide_.stick_free;
    slide_.cols.noalias() -= slide_.Z_sticking * slide_.stick_cols;
  }
  slide_.system.noalias() = slide_.F_sliders.transpose() * slide_.cols;
  slide_.rhs.noalias() = slide_.F_sliders.transpose() * answer_;
  for (Eigen::Index j = 0; j < ns; ++j) {
    const int i = slide_.sliders[static_cast<std::size_t>(j)].first;
    slide_.system.row(j) *= mu[i];
    slide_.system(j, j) += 1;
    slide_.rhs[j] = mu[i] * (r.fn[i] + slide_.rhs[j]);
  }
  slide_.lu.compute(slide_.system);
  const Eigen::VectorXd lambda = slide_.lu.solve(slide_.rhs);
  // A slider pressed off (a negative magnitude) or a singular answer: the round's own friction.
  if (!lambda.allFinite() || lambda.minCoeff() < 0) return;
  for (Eigen::Index j = 0; j < ns; ++j) {
    const int i = slide_.sliders[static_cast<std::size_t>(j)].first;
    r.ft.segment<2>(2 * i) = lambda[j] * direction_[static_cast<std::size_t>(i)];
  }
  if (k > 0) {
    slide_.stick_free.noalias() -= slide_.stick_cols * lambda;
    for (Eigen::Index a = 0; a < k; ++a) r.ft[stick_rows_[static_cast<std::size_t>(a)]] = slide_.stick_free[a];
  }
}

bool FrictionSolver::anticipation_holds(const Eigen::VectorXd& bn, const Eigen::VectorXd& mu, double load,
                                        FrictionResult& r) {
  const auto m = static_cast<Eigen::Index>(bn.size());
  const auto fn = f_.head(m);  // the anticipated normal forces
  // The touching contacts stay at zero acceleration (Ant_T dft is in the range of Ann_TT: the
  // touching answer cancels it); they must stay in compression, the others must not close.
  const double force_scale = std::max(1e-300, r.fn.cwiseAbs().maxCoeff());
  slide_.touching_mask.assign(static_cast<std::size_t>(m), false);
  for (int i : touching_) slide_.touching_mask[static_cast<std::size_t>(i)] = true;
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto u = static_cast<std::size_t>(i);
    if (slide_.touching_mask[u] ? fn[i] < -1e-9 * force_scale : effect_[i] + bn[i] < -tolerance * load) return false;
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

}  // namespace wysiwyf::haptics
