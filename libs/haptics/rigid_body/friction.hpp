#pragma once
// Coulomb friction on top of the exact frictionless contact LCP, by staggered projections
// (Kaufman, Sueda, James & Pai, "Staggered projections for frictional contact in multibody
// systems", SIGGRAPH Asia 2008): alternately
//  - the normal forces from Baraff's pivoting LCP (exact non-penetration) with the current
//    friction forces as known loads, and
//  - the friction forces with the normal forces' answer to them anticipated (the tangential rows
//    through the Schur complement S = Att - Atn_T Ann_TT^+ Ant_T over the touching set T, the
//    normal LCP's clamped contacts and those at zero acceleration that it left without force
//    because they are redundant, less those the spread below leaves without force: a friction
//    force tilts the body, the touching contacts stop the tilt), by an active set over the
//    contacts:
//    every contact is first asked to stick: the minimum-norm forces that meet the targets exactly
//    (no sliding by the horizon, or after the impact; the least-norm solution, psd_pseudo_inverse.hpp, so
//    the four coplanar corners of a face, a singular system, share the load evenly); a contact
//    that needs more than mu f_n slides at mu f_n, against its velocity if it slides faster than
//    sliding_speed (maximal dissipation), else along the force it needed, and the rest are
//    solved again (isotropic Coulomb: a disc, no pyramid),
// until what the forces do, A [f_n; f_t], stops changing. The friction is bounded by normal forces
// spread over redundant contacts (a face's four corners) as the least forces >= 0 that do what
// the LCP's do, the split four equal springs would carry: the LCP's own answer leaves one corner
// without force, and which one flips with the friction load, so the rounds cycled.
//
// The rows: a_n = Ann f_n + Ant f_t + bn (>= 0, complementary to f_n >= 0) and
// a_t = Atn f_n + Att f_t + bt (-> 0 for sticking contacts), contact i's tangent rows 2i, 2i+1.
#include <Eigen/Dense>

#include <array>
#include <utility>
#include <vector>

#include "rigid_body/lcp.hpp"
#include "rigid_body/psd_pseudo_inverse.hpp"

namespace wysiwyf::haptics {

struct FrictionResult {
  // Normal (m; spread over redundant contacts, see above, where there is friction) and tangential
  // (2m) forces or impulses.
  Eigen::VectorXd fn, ft;
  int iterations = 0;      // staggered rounds
  bool ok = false;         // every normal LCP solved (non-penetration holds for the friction applied)
  bool converged = false;  // and the rounds settled (not: max_rounds, or stall_rounds without progress)
};

class FrictionSolver {
 public:
  // A is the full contact-space matrix J M^-1 J^T over [normal rows (m); tangent rows (2m)];
  // vt: the contacts' tangential sliding velocities (2m), the direction a sliding contact's
  // friction opposes.
  // ft_start (2m, optional): friction forces to start the rounds from, such as the last step's
  // answer: where the contacts stay, the rounds then settle in one or two. clamped_start
  // (optional): the first normal LCP's warm start, such as the clamped set of the last
  // right-hand side over the same contacts, so that the LCP does not pivot through every
  // contact from nothing at every step.
  FrictionResult solve(LcpSolver& lcp, const Eigen::MatrixXd& A, const Eigen::VectorXd& bn, const Eigen::VectorXd& bt,
                       const Eigen::VectorXd& mu, const Eigen::VectorXd& vt,
                       const Eigen::VectorXd& ft_start = Eigen::VectorXd(),
                       const LcpIndices& clamped_start = LcpIndices());

  // m/s: a contact that cannot stick slides against its velocity if faster than this; a slower
  // one along the force it needed, which does not chase the direction of a velocity that is
  // mostly round-off.
  double sliding_speed = 1e-3;
  // true: every contact is first asked to stick (friction held through a step: a fast slider
  // that the cone can stop within the step stops). false: a contact sliding faster than
  // sliding_speed slides from the start, at mu f_n against its velocity. World's impacts use
  // false: with every contact asked to stick first, a falling pile's impacts can drive a corner
  // into the table (docs/design/friction-staggered-rounds.md).
  bool stick_first = true;

  // Staggered rounds. With the touching set's answer anticipated, a round changes what the
  // forces do only where an active set changed (a contact starts to slide, a normal force
  // reaches zero): what the forces do is judged with the normal forces the touching set will
  // answer the round's friction with, and a round whose friction is within every cone of those
  // (which then solve the normal LCP for it) is the answer: a sticking cube, or a pushed stack,
  // settles in one round started from the last step's friction and in two from none. The
  // friction is held through a step, so 1e-8 of the loads (1e-7 N on a 1 kg cube) is far below
  // anything a hand could feel.
  int max_rounds = 40;
  double tolerance = 1e-8;  // change of A [fn; ft] between rounds, relative to the loads, that ends them
  // Rounds without the change halving that end them unsettled: a cycle (the normal forces under
  // fast sliders, whose friction mu f_n moves with them, switching between sets in turn, as in a
  // pile with a box pulled out of it) goes on as long as it is let, and its last round is as good
  // as any; a contraction halves the change within two rounds, so three rounds without it tell a
  // cycle, and every round more would be another LCP and stick solve for nothing.
  int stall_rounds = 3;
  // A two-round cycle (the forces and what they do repeat every other round: a jam's touching set
  // alternating between two) ended as soon as it shows, on the answer the stall would end on
  // (false: at the stall). A jam in a pulled pile can cycle so at every step for many steps.
  bool end_two_round_cycles = true;

 private:
  // What depends on a touching set T alone, within one solve (Ann is the solve's): Ann_TT and its
  // factor, and, once the friction step has needed them, Z and the half inverse F (F^T F =
  // Ann_TT^+, Z = F Ant_T) with Ant_T (AntC), and the Schur complement S's columns the stick
  // solves have asked for (schur_columns).
  struct TouchingFactors {
    std::vector<int> set;
    Eigen::MatrixXd Ann;
    PsdPseudoInverse inverse;
    bool schur = false;  // Z, F and AntC made for this set
    Eigen::MatrixXd S, Z, F, AntC;
    Eigen::MatrixXd Zt;          // Z^T, for S's columns one by one (made with the first)
    std::vector<char> s_column;  // per column of S: made (all of them where s_whole)
    bool s_whole = false;
    long used = 0;  // when last bound (0: holds no set of this solve)
  };
  // Binds factor() to touching_'s: the one kept, or made in place of the least recently used. A
  // jam's rounds can alternate between two touching sets, one contact more or less, nothing
  // sliding, for many steps on end; the set of two rounds before comes back with its factor and S.
  void bind_factor();
  TouchingFactors& factor() { return factors_[bound_]; }
  // Makes the columns of factor()'s S = Att - Z^T Z that the sticking rows (stick_rows_) read: S
  // is read along the sticking rows only (their system, their load, the sliders' effect on
  // them), and S is symmetric, so their columns are all it needs. Where the stickers are few
  // (an impact, most contacts sliding from the start), only those columns are made, each exactly
  // the mirror of its row; where more than half the rows stick (most resting solves), S whole by
  // one symmetric rank update, cheaper per entry than column by column.
  void schur_columns(const Eigen::Ref<const Eigen::MatrixXd>& Att);

  // The normal forces the friction is bounded by: the LCP's, spread over redundant touching
  // contacts (the same motion, the least forces >= 0); sets touching_, the contacts that carry
  // them, and binds factor() to them.
  void spread_normal_forces(const LcpResult& normal, double load, Eigen::VectorXd& fn);
  // Whether the last call's carrying set, within this touching set, carries what the LCP's forces
  // do; if so, sets fn to its least forces and touching_ back to it (its factor kept).
  bool last_set_carries(Eigen::VectorXd& fn);

  // Whether this round's forces r and what they do (effect_) are, within the rounds' tolerance,
  // those of two rounds before (the solver's state then repeats: a two-round cycle).
  bool repeats_two_rounds_back(const FrictionResult& r, double load) const;

  // The first round's shortcut: where no contact slides with friction and the frictionless normal
  // forces (the LCP's, seen with no friction load) leave the tangential rows within the rounds'
  // tolerance, no friction is the answer: what the stick solve would find does less than a
  // settled round may leave undone. (A resting box of a pile, not pushed: most island solves of
  // a pushed pile, each spared a Schur complement and a stick solve.) Sets r.ft to zero.
  bool without_friction_settles(const Eigen::MatrixXd& A, const LcpResult& normal, const Eigen::VectorXd& bt,
                                const Eigen::VectorXd& mu, double load, FrictionResult& r);

  // The sliders' magnitudes lambda = mu f_n' with f_n' the touching set's answer to the friction
  // lambda d itself and to the stickers' answer to it (a linear system over the sliders, solved
  // at once: left to the rounds, a pushed pile's sliders converge only geometrically); into r.ft,
  // the stickers' friction with them, unless a slider would be pressed off. Needs the round's
  // touching set (factor()), ft_seen_ and the last stick solve (stick_rows_,
  // weight_, stick_inverse_, x_).
  void anticipate_sliders(const Eigen::VectorXd& mu, FrictionResult& r);

  // Whether the round's friction r.ft with the normal forces the touching set answers it with
  // (f_'s head; effect_ = A f_) is already the answer: those forces solve the normal LCP for this
  // friction (the touching contacts in compression at zero acceleration, the others not closing;
  // what the next round's LCP would find, its A f being unique) and every contact is within its
  // cone of them, no slider's friction moving with them. If so, sets r.fn to them: the next
  // round, an LCP and a stick solve, would only repeat this one (a pushed stack ends in one round).
  bool anticipation_holds(const Eigen::VectorXd& bn, const Eigen::VectorXd& mu, double load, FrictionResult& r);

  // Workspace, kept between solves (no allocation once the sizes have been seen). The rounds':
  Eigen::MatrixXd Ann_, Bkk_;
  Eigen::VectorXd c_, y_, x_, rhs_, weight_, f_, effect_, effect_prev_, ft_seen_, answer_;
  Eigen::VectorXd effect_before_, fn_before_, ft_before_;  // two rounds before
  Eigen::VectorXd fn_last_, ft_last_;                      // the last round's answer
  Eigen::VectorXd bn_eff_, load_;
  std::vector<bool> moving_, sliding_;                // per contact: sliding from the start, this round
  std::vector<Eigen::Vector2d> against_, direction_;  // per contact: against its velocity, its friction's
  std::vector<Eigen::Index> stick_rows_;
  std::vector<int> sliding_now_;  // this pass's sliders (their friction loads the sticking rows)
  std::vector<int> touching_;     // the round's touching set
  PsdPseudoInverse stick_inverse_;
  Eigen::MatrixXd identity_;
  // spread_normal_forces' and last_set_carries' (friction_touching.cpp).
  struct CarryWorkspace {
    Eigen::VectorXd f_touching, spread, motion, carried;
    std::vector<int> next, last;  // the touching set being built; the last call's carrying set
  } carry_;
  // anticipate_sliders' and anticipation_holds' (friction_sliders.cpp).
  struct SlideWorkspace {
    std::vector<std::pair<int, Eigen::Index>> sliders;                // contact, place in touching_
    Eigen::MatrixXd cols, system, stick_cols, Z_sticking, F_sliders;  // (F's sliders' columns)
    Eigen::VectorXd rhs, stick_free;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
    std::vector<bool> touching_mask;  // per contact: in touching_
  } slide_;
  std::array<TouchingFactors, 4> factors_;  // (4: a two-set cycle and the spread's sets on the way)
  std::size_t bound_ = 0;                   // factors_[bound_]: touching_'s (bind_factor)
  long uses_ = 0;
};

}  // namespace wysiwyf::haptics
