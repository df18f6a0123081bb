// piece_visit.h — internal to fast/src/global: one piece of the global depth's enumeration,
// its eigenpairs pruned and the ones that may hold the minimiser offered.
//
// Input : an active set S's matrix H_S (rounded, with its entries' absolute error h_error; on
//         the exact path H = h_S 2^-pe rounded once), its sign conditions (built on demand),
//         the best value so far and the lower bound on every G(u) (Search).
// Output: offers to Best (best_offer.h) of every eigenvector v of H_S, or point of an
//         eigen-plane's arc, that lies in S's cone R_S up to the tolerance kSign and whose
//         eigenvalue may lie in the window [lower, best):
//             H_S v = mu v, v in R_S, lower <= mu < best   (global_depth.h: pdd2_global is the
//             least such mu over the 15 x 15 active sets);
//         exact path, also each wall's stationary point (the 2x2 eigenproblem of H on l.v = 0),
//         the Rayleigh-Ritz vectors of near-double eigenvalues, and the suspects of
//         suspect_proof.h (eigenvectors that held their signs).
#pragma once

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

#include "exact/expansion.h"
#include "global/accurate_piece_matrix.h"
#include "global/best_offer.h"
#include "global/piece_screen.h"
#include "global/vec3.h"

namespace pdd::fast::global {

using detail::kSign;

inline constexpr double kPrune = 1e-10;       // an eigenvalue must beat the best by this, relative
inline constexpr double kEigen = 1e-12;       // eigenvalue error of the 3x3 solver, times |H|_F
inline constexpr double kDegenerate = 1e-6;   // eigenvalues this close (times |H|_F) span a plane
inline constexpr double kDirectBackward = 32 * 0x1p-53;  // closed form kept on an accurate H (solve)
inline constexpr double kNearDouble = 1e-2;   // a gap below this (times |H|_F): the iterative solver

// The sign conditions of active set (ma, mb) at v, with tolerance: l.v >= -tol (active) or
// l.v <= tol (free), per condition.
struct Conditions {
  V3 l[8];
  double sign[8];  // +1: needs l.v >= 0, -1: l.v <= 0
  double floor = 0;  // absolute error of the computed l (rounding of centred positions)
  double tol_[8];    // kSign |l|_1 + floor (|l|_1 >= |l|_2: a wider tolerance, no square root)
  void finish() {
    for (int k = 0; k < 8; ++k)
      tol_[k] = kSign * (std::fabs(l[k][0]) + std::fabs(l[k][1]) + std::fabs(l[k][2])) + floor;
  }
  double tol(int k) const { return tol_[k]; }
  bool hold(const V3& v) const {
    const double nv = norm(v);
    for (int k = 0; k < 8; ++k)
      if (sign[k] * dot(l[k], v) < -tol(k) * nv) return false;
    return true;
  }
};

// The plane spanned by unit p, q: the arc of unit vectors cos t p + sin t q where every
// condition holds (each one a half circle widened by its tolerance); its middle, if any.
bool arc_middle(const Conditions& c, const V3& p, const V3& q, V3& out);

// One active set's piece as consider_piece takes it: H, its entries within h_error (absolute;
// on the exact path H is the exact one times 2^-pe, rounded once), and which path builds it.
// `accurate` (double path): H from accurate_piece_matrix.h, its error near its own rounding;
// then the solver's error bounded a posteriori (backward_error: the closed form where that bound
// is within a few u |H|, else the iterative solver), and its vectors offered as computed (the
// caller's refine is the identity: the double polish of eigen_polish.h would not add accuracy
// to a vector exact for H + F with |F| a few u |H|).
// `zeros` (double path): a count of eigenvalues of the exact H_S that are exactly 0: G_S(n), the
// least norm of a deformation putting S's vertices on one plane of normal n (20 G_S(n) = sum
// over S of (p_i.n - c)^2 + k (T_A.n)^2), vanishes for every n orthogonal to their affine span,
// so H_S has at least 4 - |S| zero eigenvalues when |S| <= 3 (2 for |S| = 2, 1 for |S| = 3).
// Sorted, the exact eigenvalues' first `zeros` are 0 and (Weyl) the computed first `zeros` are
// their images: none is a stationary value of G (G > 0 on the sphere of an intersecting pair;
// a touching one, depth 0, goes to the exact pieces before: global_depth.cpp's tiny start), so
// they are never in the window, whatever the margin (a shallow contact's margin exceeds its
// floor: they would send the pair to the exact pieces). An in-window eigenvalue beside them
// keeps them in its gap (gap_of), so its accuracy estimate sees them.
// `moments`, `ma`, `mb` (accurate visits): where H's double words come from (the Ritz step of
// PieceVisit::ritz_pair); null: none.
struct PieceMatrix {
  const Eigen::Matrix3d& H;
  double h_error;
  bool exact;
  long pe;
  bool accurate = false;
  int zeros = 0;
  const AccurateMoments* moments = nullptr;
  unsigned ma = 0, mb = 0;
};

// What the enumeration offers to and prunes with: the evaluations' problem, the best so far,
// and the lower bound on every G(u) (global_depth.h), in the pair's units. `walls` (exact
// path): the pair has a vertex far from the others, whose minimiser may sit on the wall of a
// steep piece (PieceVisit::offer_wall); false for a compact pair (global_depth.cpp), whose
// pieces are then pruned by eigenvalues in the window alone, as on the double path.
struct Search {
  const Problem& P;
  Best& best;
  double lower;
  bool walls = true;
  // The vertices that may be at the plane at a stationary value below the best (bit i: A's
  // vertex i, bit 4 + j: B's vertex j): a piece with another one at the plane is not visited
  // (global_depth.cpp's enumerate_exact says why).
  unsigned contact = 0xFFu;
};

// With `zeros` of H's exact eigenvalues exactly 0 (PieceMatrix), whether the others certainly
// exceed `threshold`, H's entries within h_error of the exact ones and hnorm = |H|_F as computed:
// for zeros == 2 the third is tr(H*); for zeros == 1 the two others have sum tr(H*) and product
// c2(H*), the sum of the principal 2x2 minors (lambda_0 = 0), so the smaller is >= c2(H*) /
// tr(H*). With each entry within e = h_error: tr within 3e, and 4 u |H|_F for its two
// additions; each of c2's six products within (2 |H|_F + e) e, and its eleven roundings within
// 32 u |H|_F^2 (the products' magnitudes sum to <= 2 |H|_F^2); the quotient's rounding in the
// factor 1 - 4u. False for zeros == 0 (the determinant, not 0, is PieceVisit's own test).
inline bool nonzero_eigenvalues_above(const Eigen::Matrix3d& H, double hnorm, double h_error, int zeros,
                                      double threshold) {
  const double tr = H.trace();
  if (zeros == 2) return tr - 3 * h_error - 4 * kU * hnorm > threshold;
  if (zeros != 1) return false;
  const double c2 = H(0, 0) * H(1, 1) - H(0, 1) * H(0, 1) + H(0, 0) * H(2, 2) - H(0, 2) * H(0, 2) +
                    H(1, 1) * H(2, 2) - H(1, 2) * H(1, 2);
  const double c2_low = c2 - 6 * (2 * hnorm + h_error) * h_error - 32 * kU * hnorm * hnorm;
  const double tr_up = tr + 3 * h_error + 4 * kU * hnorm;
  return c2_low > 0 && tr_up > 0 && c2_low / tr_up * (1 - 4 * kU) > threshold;
}

// The piece's own operations: make_conditions() its sign conditions (built only when an
// eigenpair survives), refine(v, mu) and ritz(e, f, out) on its H (eigen_polish.h),
// suspect(k) (exact path: eigenvector k held its signs, for represented()).
template <class MakeConditions, class Refine, class Ritz, class Suspect>
struct PieceCalls {
  MakeConditions make_conditions;
  Refine refine;
  Ritz ritz;
  Suspect suspect;
};
template <class MakeConditions, class Refine, class Ritz, class Suspect>
PieceCalls<MakeConditions, Refine, Ritz, Suspect> piece_calls(MakeConditions make_conditions, Refine refine,
                                                              Ritz ritz, Suspect suspect) {
  return {make_conditions, refine, ritz, suspect};
}

// One active set's H and sign conditions: prune by eigenvalue, evaluate the eigenvectors (or
// the eigen-plane's arc) that satisfy the conditions (global_depth.h).
// Pruning window: an eigenpair can hold the minimiser only if its exact eigenvalue mu (= G
// there) lies in [lower, best): every G(u) >= lower (global_depth.h's bound), and a value at or
// above the best cannot improve it. The computed eigenvalues of the rounded H are within
// h_error (Weyl: |E|_2 <= |E|_F <= 3 max |E_rc|) of the exact ones, plus the solver's own error:
// kEigen |H|_F where the eigenvalues are apart, growing near a double eigenvalue (the closed
// form's cubic roots: measured 2e-11 |H| at a gap of 4e-6 |H|, 4.5e-9 |H| below 1e-6 |H|), so
// each eigenvalue's margin adds 8 u |H|^2 / max(gap to its neighbours, sqrt(u) |H|) (>= 1e-9
// |H| at any gap). The window is widened by that margin on both sides (and kPrune above).
template <class Calls>
class PieceVisit {
 public:
  PieceVisit(const PieceMatrix& piece, Calls& calls, const Search& search)
      : H(piece.H), h_error(piece.h_error), exact(piece.exact), accurate(piece.accurate), zeros(piece.zeros),
        moments(piece.moments), ma(piece.ma), mb(piece.mb), pe(piece.pe), calls(calls), P(search.P),
        best(search.best), lower(search.lower) {}

  // The window and the cheap tests alone: true when the piece certainly holds no eigenvalue of
  // the exact H_S in the window (run() returns there).
  bool outside() {
    hnorm = H.norm();
    // (accurate: no solver yet; the trace's and determinant's own roundings, a few u |H|; the
    // solver's error is bounded after it ran, backward_error())
    margin = (accurate ? 8 * kU : kEigen) * hnorm + 3 * h_error;
    best_here = best.value_in(pe);  // the best value in this piece's units
    lower_here = std::ldexp(lower, int(std::clamp(-pe, -4000L, 4000L)));
    threshold = best_here * (1 - kPrune) + margin;
    floor = lower_here - margin;
    return outside_window_cheaply();
  }

  void run() {
    if (outside() || !solve()) return;
    if (!exact && !double_path_accuracy()) return;
    cond = calls.make_conditions();
    if (exact) {
      offer_smallest();
      for (int k = 0; k < 8; ++k) offer_wall(k);
      offer_ritz();
    }
    offer_eigenvectors();
    if (exact)
      for (int k = 0; k < 3; ++k)
        if (held[k]) calls.suspect(k);
  }

 private:
  // Cheap tests first. mu_min >= 4 det / trace^2 (mu2 mu3 <= (trace / 2)^2), with the
  // determinant lowered by a bound on its rounding (6 products of 3 entries <= |H|_F, and the
  // entries' own errors): 64 u |H|_F^3 + 6 |H|_F^2 (3 h_error). mu_max <= trace (H is PSD).
  // With `zeros` (double path: the exact H_S's first `zeros` eigenvalues are 0, PieceMatrix),
  // the others follow from the invariants, where the determinant (0) says nothing
  // (nonzero_eigenvalues_above). A piece whose nonzero eigenvalues all lie above the window is
  // left: the drop that shallow contacts need, their windows ~1e-13 |H| far below what the
  // screen resolves.
  bool outside_window_cheaply() const {
    const double tr = H.trace();
    const double det_low = H.determinant() - 64 * kU * hnorm * hnorm * hnorm - 18 * hnorm * hnorm * h_error;
    if (tr > 0 && 4 * det_low / (tr * tr) > threshold) return true;
    if (tr + 3 * margin < floor) return true;
    return nonzero_eigenvalues_above(H, hnorm, h_error, zeros, threshold);
  }

  // The eigenpairs and each eigenvalue's margin (above); false when none can matter.
  // Double path: the closed-form solver (fast; eigenvectors off by ~u |H| / gap, so the value
  // along one exceeds the stationary value by ~|H| (u |H| / gap)^2, below 1e-13 of any depth
  // this path takes, >= 1e-10 scale^2). Exact path: the iterative solver (Householder + QR),
  // whose vectors keep structure such as a zero row, then inverse iteration (refine).
  // Accurate H: the closed form first, kept where its a-posteriori bound (backward_error) is
  // within kDirectBackward |H| (on shallow contacts' pieces typically 12-13 u |H|, the
  // iterative solver's 14-19 u |H|); else (near-double eigenvalues: the closed form's
  // vectors anywhere in their plane) the iterative solver. Either way the margins are the bound
  // of the pairs actually used.
  bool solve() {
    bool direct = !exact;
    if (direct) {
      eig.computeDirect(H);
      direct = !accurate || direct_is_tight();
    }
    if (!direct) eig.compute(H);
    if (eig.info() != Eigen::Success) {
      if (accurate) best.needs_exact = true;  // (as double_path_accuracy's own failure)
      return false;
    }
    mu = eig.eigenvalues();
    if (accurate && !direct && !backward_error()) {
      best.needs_exact = true;
      return false;
    }
    for (int k = 0; k < 3 && accurate; ++k) m[k] = 3 * h_error + solver_error;
    for (int k = 0; k < 3 && !accurate; ++k) {
      double gap = INFINITY;
      if (k > 0) gap = std::min(gap, mu(k) - mu(k - 1));
      if (k < 2) gap = std::min(gap, mu(k + 1) - mu(k));
      m[k] = margin + 8 * kU * hnorm * hnorm / std::max(gap, std::sqrt(kU) * hnorm);
    }
    bool any = exact;  // exact: the smallest eigenvector is tried below (if not under the floor)
    for (int k = 0; k < 3; ++k) any = any || in_window(k);
    return any;
  }

  // The closed form's pairs on an accurate H, bounded by backward_error within kDirectBackward |H|.
  bool direct_is_tight() {
    if (eig.info() != Eigen::Success) return false;
    mu = eig.eigenvalues();
    return backward_error() && solver_error <= kDirectBackward * hnorm;
  }

  // The computed pairs' backward error, a posteriori (accurate H): with R = H V - V Lambda (V the
  // computed eigenvectors, Lambda their eigenvalues), H + F with F = -R V^-1 has exactly these
  // eigenpairs, |F|_2 <= |R|_F |V^-1|_2, and |V^-1|_2 = 1 / sigma_min(V) <= 1 / sqrt(1 - 3 o) <=
  // 1 + 3 o for o = max |V^T V - I| <= 0.1 (|V^T V - I|_2 <= 3 o). So by Weyl each exact
  // eigenvalue of H lies within |F|_2 of its computed one (sorted), and each computed vector
  // is an exact one of H + F: solver_error = that bound, the solver's part of the margins and
  // of double_path_accuracy's E. R's entries computed in doubles: a row of three products and
  // two sums, then the subtraction of mu v_i, within 5u of (sum |H_ij v_j| + |mu v_i|); o's dot
  // products within 4u; the relative 2^-40 for the rest of these roundings. False when V is
  // too far from orthonormal (o > 0.1) or a value is not finite.
  bool backward_error() {
    const Eigen::Matrix3d& V = eig.eigenvectors();
    double r2 = 0, o = 0;
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) {
        double hv = 0, mag = 0;
        for (int j = 0; j < 3; ++j) hv += H(i, j) * V(j, k), mag += std::fabs(H(i, j) * V(j, k));
        const double rik = std::fabs(hv - mu(k) * V(i, k)) + 5 * kU * (mag + std::fabs(mu(k) * V(i, k)));
        r2 += rik * rik;
        o = std::max(o, std::fabs(V.col(k).dot(V.col(i)) - (k == i ? 1.0 : 0.0)) + 4 * kU);
      }
    solver_error = std::sqrt(r2) * (1 + 3 * o) * (1 + 0x1p-40);
    return o <= 0.1 && std::isfinite(solver_error);
  }

  bool in_window(int k) const {
    return k >= zeros && mu(k) >= lower_here - m[k] && mu(k) < best_here * (1 - kPrune) + m[k];
  }
  double gap_of(int k) const {
    double g = INFINITY;
    for (int j = 0; j < 3; ++j)
      if (j != k) g = std::min(g, std::fabs(mu(j) - mu(k)));
    return g;
  }

  // Near-double eigenvalues (double path). An eigenvector v~ off the exact one v* by small
  // components d_j along the other eigenvectors has a value off by sum_j (lambda_j - mu) d_j^2
  // (the quadratic form on the unit sphere), and d_j ~ E / |lambda_j - mu| for a matrix error
  // E: so about E^2 / gap, which is not small beside a shallow mu when the gap is small. The
  // closed-form solver is worse there (its eigenvalues err by up to ~4.5e-9 |H| near a double
  // root, so its vectors can be anywhere in the plane: on pairs of nearly collinear edges in
  // shallow contact, two eigenvalues 1e-9 apart, its values come out 4% above the minimum).
  // So an in-window eigenvalue within kNearDouble |H| of another is taken from the iterative
  // solver (vectors off by ~u |H| / gap; eigenvalues backward stable, within a few u |H| of
  // H's whatever the gap, so the margin drops the closed form's loss term and keeps kEigen
  // |H| + 3 h_error), and where its estimate 2 E^2 / gap, E = 3 h_error +
  // 8 u |H| (H's error and the solver's), exceeds 1e-11 of the eigenvalue (a tenth of the
  // budget kGlobalRel), the pair is redone on exact pieces (needs_exact), whose Ritz offers
  // below do not depend on the gap. false: the iterative solver failed (needs_exact set).
  bool double_path_accuracy() {
    bool near_double = false;
    for (int k = 0; k < 3 && !accurate; ++k)
      near_double = near_double || (in_window(k) && !(gap_of(k) >= kNearDouble * hnorm));
    if (near_double) {
      eig.compute(H);
      if (eig.info() != Eigen::Success) {
        best.needs_exact = true;
        return false;
      }
      mu = eig.eigenvalues();
      for (double& mk : m) mk = margin;
    }
    // The same estimate for every in-window eigenvalue, near-double or not (the closed-form
    // solver's vectors are off by ~u |H| / gap too): H's error E is absolute, ~2^-39 of the
    // moments' magnitude, so a piece whose active vertices form a small cluster far from the
    // centroid (|H| << mag) in a shallow contact can have E^2 / gap near the eigenvalue
    // itself (estimated: ~1e-8 of it for |H| ~ 1e-8 R^2, gap ~ 1e-2 |H|). Such a
    // piece sends the pair to the exact pieces. On the paper's pairs it never triggers.
    const double E = 3 * h_error + (accurate ? solver_error : 8 * kU * hnorm);
    int pair_of[3];
    planes(pair_of);
    for (int k = 0; k < 3; ++k)
      if (in_window(k) && !(2 * E * E / gap_of(k) <= 1e-11 * std::max(mu(k), lower_here)) &&
          !(pair_of[k] >= 0 && plane_accurate(pair_of[k], E)) && !(pair_of[k] < 0 && ritz_pair(k, E)) &&
          !partner_of_zero(k, E))
        best.needs_exact = true;
    return true;
  }

  // An in-window mu_k whose small gap is to one neighbour (its partner p = k - 1 or k + 1), the
  // third eigenvalue apart: a contact far shallower than the pair beside a near-zero eigenvalue
  // (three or four nearly coplanar active vertices of a nearly aligned resting contact: mu_1
  // ~1e-13 |H| beside mu_0 ~0, faces 1e-6 rad apart). The estimate above sees a gap of about
  // mu_k itself and fails. The vector is taken instead as a Rayleigh-Ritz vector of the computed
  // plane Q = [v_lo v_hi] (lo < hi the two indices) on H's double words (AccurateMoments, each
  // entry within its certified bound). With H's exact unit eigenvectors e_i (lambda_0 <=
  // lambda_1 <= lambda_2) and a unit v = sum c_i e_i, v^T H v - lambda_k = sum_i (lambda_i -
  // lambda_k) c_i^2, whose terms below k are <= 0:
  // (1) Q spans the exact invariant plane of lambda_lo, lambda_hi up to sin <= s = E / delta +
  // 2 o (Davis-Kahan: Q's vectors are exact for H + F, |F| <= E, so H Q - Q Lambda = -F Q;
  // delta = the distance from Q's eigenvalues to the third one's interval [mu_j - E, mu_j + E];
  // o: Q's departure from orthonormality).
  // (2) K = Q^T H Q in double words (Bounded: certified), rounded (entries within `bound`, so
  // |.|_2 <= 2 bound); it differs from H's restriction to the exact plane (in the bases
  // matched by projection, Q = Q* + W, |W| <= s: cross terms vanish, H Q* lying in the plane) by
  // |H| s^2, and the Gram matrix of Q* from I by 2 (o + s^2), which moves the 2x2 problem by
  // 4 (o + s^2) |K|; with the closed form's 8 u |K|: eps in all. Davis-Kahan on the 2x2 puts each
  // Ritz vector within phi <= eps / (gap of K - 2 eps) + 2 o of its eigenvector's image, inside
  // the plane (the 2 o: coordinates mapped back through Q).
  // (3) So the Ritz vector r of k (K's upper one for k = hi, lower for k = lo) is within s + phi
  // + 8 u of e_k; its component along the third e_j is at most s + 8 u, along the partner's at
  // most phi + 8 u, and v^T H v - lambda_k <= (lambda_p - lambda_k)^+ (phi + 8u)^2 +
  // (lambda_j - lambda_k)^+ (s + 8u)^2, each lambda_i - lambda_k <= mu_i - mu_k + 2 E. Required:
  // that excess within half of the 1e-11 above, and r within 1e-9 of e_k (far inside the
  // conditions' kSign). True with r kept as vector k; false (the pair goes to the exact pieces)
  // otherwise.
  bool ritz_pair(int k, double E) {
    using detail::dw::Bounded;
    if (!accurate || !moments) return false;
    const int p = k == 0 ? 1 : k == 2 ? 1 : (mu(1) - mu(0) <= mu(2) - mu(1) ? 0 : 2);
    const int lo = std::min(k, p), hi = std::max(k, p), j = 3 - lo - hi;  // j: the third index
    const double delta = std::min(std::fabs(mu(j) - mu(lo)), std::fabs(mu(j) - mu(hi))) - E;
    if (!(delta > 0) || !(mu(hi) - mu(lo) < std::fabs(mu(j) - mu(k)))) return false;
    const V3 q0 = raw_vector(lo), q1 = raw_vector(hi);
    const double o = std::max({std::fabs(dot(q0, q1)), std::fabs(dot(q0, q0) - 1), std::fabs(dot(q1, q1) - 1)}) +
                     4 * kU;
    const double s = E / delta + 2 * o;
    Bounded Hb[3][3];
    if (!moments->matrix(ma, mb, Hb)) return false;
    auto form = [&](const V3& x, const V3& y) {
      Bounded f;
      for (int c = 0; c < 3; ++c) {
        Bounded t;
        for (int r = 0; r < 3; ++r) t = detail::dw::plus(t, detail::dw::times(Hb[r][c], detail::dw::exactly(x[r])));
        f = detail::dw::plus(f, detail::dw::times(t, detail::dw::exactly(y[c])));
      }
      return f;
    };
    const Bounded K00 = form(q0, q0), K01 = form(q0, q1), K11 = form(q1, q1);
    const double k00 = K00.v.hi + K00.v.lo, k01 = K01.v.hi + K01.v.lo, k11 = K11.v.hi + K11.v.lo;
    const double kmax = std::max({std::fabs(k00), std::fabs(k01), std::fabs(k11)});
    const double bound = std::max({K00.e, K01.e, K11.e}) + 2 * kU * kmax;
    const double eps = (2 * bound + 4 * (o + s * s) * kmax + hnorm * s * s + 8 * kU * kmax) * (1 + 0x1p-40);
    const double rad = std::hypot((k00 - k11) / 2, k01);
    if (!(2 * rad > 2 * eps)) return false;
    const double phi = eps / (2 * rad - 2 * eps) + 2 * o;
    auto above = [&](int i, double c) { return i > k ? (mu(i) - mu(k) + 2 * E) * c * c : 0.0; };
    const double excess = above(p, phi + 8 * kU) + above(j, s + 8 * kU);
    if (!(excess <= 0.5e-11 * std::max(mu(k), lower_here)) || !(s + phi + 8 * kU <= 1e-9)) return false;
    // K's eigenvector for its eigenvalue of k: a normal of a row of K - ev I, the longer one
    const double ev = (k00 + k11) / 2 + (k == hi ? rad : -rad);
    const double a0 = k01, b0 = ev - k00, a1 = ev - k11, b1 = k01;
    const bool first = std::hypot(a0, b0) >= std::hypot(a1, b1);
    const double ua = first ? a0 : a1, ub = first ? b0 : b1;
    const double big = std::max(std::fabs(ua), std::fabs(ub));
    if (!(big > 0)) return false;
    const V3 w = add(mul(q0, ua / big), mul(q1, ub / big));
    ritz[k] = mul(w, 1 / norm(w));
    has_ritz[k] = true;
    return true;
  }

  // Three active vertices nearly on one line, or four on one plane nearly on one line (zeros ==
  // 1: H's exact eigenvalues 0 <= lambda_1 <= lambda_2, the 0 structural or affine_zeros'):
  // lambda_1, a resting contact's window value, lies within E of the 0, so no estimate on the
  // computed pairs resolves its vector (blocks on each other's columns: a vertex of A 1e-8 above
  // the line of an edge of B, or an edge of A 1e-9 above the same edge of B). Its exact
  // eigenvector is known from the other two: the 0's is the vertices' plane's normal n0 = (x1 -
  // x0) x (x2 - x0) (H_S n0 = 0: they lie on a plane of normal n0), so e_1 = n0 x e_2 / |n0 x
  // e_2|.
  // n0 is taken by expansions (expansion.h: exact, then each component rounded within err of it,
  // |n0~ - n0| <= sqrt(3) err: an angle an <= sqrt(3) err / (|n0~| - sqrt(3) err)); e_2, the
  // computed vector of mu_2, is an exact eigenvector of H + F, |F| <= E, so within s2 = E /
  // delta + 2 o of e_2's direction (Davis-Kahan: delta = mu_2 - mu_1 - 2 E, the distance to the
  // other two eigenvalues' intervals; o its departure from unit length). n0 is orthogonal to
  // e_2 exactly, so the cross product of the two is within an + s2 (to first order, the factor
  // 1 + 1e-3 for the second) of e_1's direction, and the rounding of the cross product and its
  // normalisation add 16 u. Along that w, v^T H v - lambda_1 <= (lambda_2 - lambda_1) sin^2 phi
  // <= (mu_2 + E) phi^2 (the component along n0 only lowers it): required within half of the
  // 1e-11 of double_path_accuracy, relative to the window's floor (every stationary value
  // that matters is above it), and phi <= 1e-9 (the conditions' kSign). True with w kept as
  // vector 1; false otherwise (the pair goes to the exact pieces).
  bool partner_of_zero(int k, double E) {
    if (!accurate || !moments || zeros != 1 || k != 1 || !(lower_here > 0)) return false;
    const int m = __builtin_popcount(ma) + __builtin_popcount(mb);
    if (m != 3 && m != 4) return false;
    Vec3d x[4];
    int n = 0;
    for (int i = 0; i < 4; ++i)
      if (ma >> i & 1u) x[n++] = moments->vertices(true)[i];
    for (int i = 0; i < 4; ++i)
      if (mb >> i & 1u) x[n++] = moments->vertices(false)[i];
    if (!detail::in_exact_range(moments->vertices(true), moments->vertices(false))) return false;
    // (four vertices: zeros == 1 only from affine_zeros, so they lie on one plane exactly and
    // any three of them off one line give its normal; the longest cross product is taken)
    static constexpr int kTriple[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    detail::ExpVec c;
    double longest = -1;
    for (int t = 0; t < (m == 3 ? 1 : 4); ++t) {
      const Vec3d &p = x[kTriple[t][0]], &q = x[kTriple[t][1]], &r = x[kTriple[t][2]];
      const detail::ExpVec ct = detail::cross(detail::difference(q, p), detail::difference(r, p));
      if (!ct.ok()) return false;
      double len = 0;
      for (int a = 0; a < 3; ++a) len += detail::approx_of(ct.x[a]).v * detail::approx_of(ct.x[a]).v;
      if (len > longest) longest = len, c = ct;
    }
    V3 n0;
    double err = 0;
    for (int q = 0; q < 3; ++q) {
      const detail::Approx a = detail::approx_of(c.x[q]);
      n0[q] = a.v, err = std::max(err, a.err);
    }
    const double n0_norm = norm(n0) * (1 - 4 * kU), slack = std::sqrt(3.0) * err * (1 + 4 * kU);
    if (!(n0_norm > 2 * slack)) return false;
    const double an = slack / (n0_norm - slack) * (1 + 4 * kU);
    const V3 e2 = raw_vector(2);
    const double o = std::fabs(dot(e2, e2) - 1) + 4 * kU;
    const double delta = mu(2) - mu(1) - 2 * E;
    if (!(delta > 0)) return false;
    const double phi = ((an + E / delta + 2 * o) * (1 + 1e-3) + 16 * kU) * (1 + 4 * kU);
    if (!((mu(2) + E) * phi * phi <= 0.5e-11 * lower_here) || !(phi <= 1e-9)) return false;
    const V3 w = cross(n0, e2);
    const double wn = norm(w);
    if (!(wn > 0) || !std::isfinite(wn)) return false;
    ritz[1] = mul(w, 1 / wn);
    has_ritz[1] = true;
    return true;
  }

  // The planes offer_eigenvectors takes (eigenvalues j, j + 1 within kDegenerate, paired in
  // ascending order): pair_of[k] = j for both members, -1 for an eigenvalue taken alone.
  void planes(int (&pair_of)[3]) const {
    pair_of[0] = pair_of[1] = pair_of[2] = -1;
    for (int k = 0; k < 2; ++k)
      if (mu(k + 1) - mu(k) <= kDegenerate * std::fabs(mu(k + 1)) + 2 * m[k]) {
        pair_of[k] = pair_of[k + 1] = k;
        ++k;
      }
  }

  // A plane (eigenvalues j, j + 1) whose vectors are accurate enough as a plane, whatever the
  // gap inside it (an exactly double eigenvalue: symmetric aligned pairs), where the estimate
  // 2 E^2 / gap above is no bound. The computed pairs are exact for H' = H + F, |F|_2 <= E
  // (H's error and the solver's backward error, as above), so the computed plane P' is
  // invariant under H' with eigenvalues mu_j <= mu_j+1, and for a unit w of P' (up to the
  // vectors' own orthogonality error, a few u, covered by 16 u |H|) w^T H w lies in
  // [mu_j - E, mu_j+1 + E]; every exact eigenvalue of H in the cluster is >= mu_j - E (Weyl).
  // So whichever vector of P' offer_plane evaluates (the arc's middle, or each computed
  // vector) is within (mu_j+1 - mu_j) + 2 E + 16 u |H| of the cluster's stationary value: within
  // 1e-10 of the eigenvalue, beside the evaluation's kGlobalRel and the pruning's kPrune
  // (1e-10 each: 3e-10 inside definitions §8's 1e-9). The arc must also meet the exact plane's
  // cone: P' is tilted from the exact invariant plane by at most E / delta (Davis-Kahan, delta
  // the distance to the third eigenvalue), required <= 1e-9, far inside the conditions'
  // tolerance kSign = 1e-6.
  bool plane_accurate(int j, double E) const {
    const int third = j == 0 ? 2 : 0;
    const double delta = std::min(std::fabs(mu(third) - mu(j)), std::fabs(mu(third) - mu(j + 1)));
    const double spread = mu(j + 1) - mu(j) + 2 * E + 16 * kU * hnorm;
    return spread <= 1e-10 * std::max(mu(j), lower_here) && E <= 1e-9 * delta;
  }

  V3 vector(int k) const { return has_ritz[k] ? ritz[k] : raw_vector(k); }
  V3 raw_vector(int k) const {  // the solver's
    const Eigen::Vector3d e = eig.eigenvectors().col(k);
    return V3{e(0), e(1), e(2)};
  }
  void offer_if_held(const V3& v, int k) {  // k: the eigenvector's index, -1 for none
    if (!cond.hold(v)) return;
    if (k >= 0) held[k] = true;
    best.offer(P, v);
  }

  // Generic minimisers are interior to their piece, hence the smallest eigenvalue's vector
  // (the Rayleigh quotient has no other local minimum). Its eigenvalue can be far below the
  // solver's resolution u |H| (a vertex 1e18 away makes |H| ~ 1e36 while the depth is ~1):
  // inverse iteration with shift 0 on the exact H (slow path) finds it regardless.
  void offer_smallest() {
    if (mu(0) < lower_here - m[0]) return;
    const V3 v = calls.refine(vector(0), 0.0);
    for (double s : {1.0, -1.0}) offer_if_held(mul(v, s), 0);
  }

  // A far vertex (exact path): a vertex 1e18 away from the others makes the H of every piece
  // where it is active the sum of a moderate part and a huge rank-one part ~ d d^T (d its
  // lever); the minimiser then sits on the wall l.v = 0 between a moderate piece (vertex free)
  // and that steep one (within ~1e-36 rad of it), an eigenvector of the steep H with an
  // eigenvalue far below its resolution, and no double normal reaches the steep side without
  // its value exploding. So on each wall of each piece the moderate H's smallest stationary
  // point on the wall (the 2x2 eigenproblem of H on the plane l^T v = 0) is offered, nudged
  // by 2^-49 rad into the piece: far above the normal's rounding (3 u of each component), so
  // the vertex stays free, and a change of the value of ~2^-49 |H| / G relative. Each offer is
  // evaluated exactly; offers only ever lower the result.
  void offer_wall(int k) {
    const V3& l = cond.l[k];
    const double ln = norm(l);
    if (!(ln > 0)) return;
    const int axis = std::fabs(l[0]) <= std::fabs(l[1]) && std::fabs(l[0]) <= std::fabs(l[2]) ? 0
                     : std::fabs(l[1]) <= std::fabs(l[2])                                     ? 1
                                                                                              : 2;
    V3 p = cross(l, V3{axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0});
    p = mul(p, 1 / norm(p));
    const V3 q = mul(cross(l, p), 1 / ln);
    auto form = [&](const V3& x, const V3& y) {
      double f = 0;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) f += x[r] * H(r, c) * y[c];
      return f;
    };
    const double m00 = form(p, p), m01 = form(p, q), m11 = form(q, q);
    const double mw = (m00 + m11) / 2 - std::hypot((m00 - m11) / 2, m01);
    if (!(mw < threshold) || mw < floor) return;
    const double a0 = m01, b0 = mw - m00, a1 = mw - m11, b1 = m01;
    const bool first = std::hypot(a0, b0) >= std::hypot(a1, b1);
    double ua = first ? a0 : a1, ub = first ? b0 : b1;
    const double big = std::max(std::fabs(ua), std::fabs(ub));  // H-sized: may be ~1e-300
    if (!(big > 0)) return;
    const V3 u = add(mul(p, ua / big), mul(q, ub / big));
    const V3 nudge = mul(l, cond.sign[k] * 0x1p-49 / ln);
    for (double s : {1.0, -1.0}) {
      offer_if_held(add(mul(u, s / norm(u)), nudge), -1);  // (a wall: not an eigenvector)
    }
  }

  // Exact path: near-double eigenvalues. On the plane of two computed eigenvectors e, f whose
  // eigenvalues are within 1e-2 of each other, the Rayleigh-Ritz vectors of the exact H (ritz:
  // the 2x2 matrix K = [e f]^T H [e f] in rationals, its eigenvectors by one atan2 of its
  // exactly computed entries) are offered. Why they are accurate whatever the gap: e, f span
  // the exact invariant plane up to components w orthogonal to it, |w| ~ u |H| / (distance to
  // the third eigenvalue), and H maps that plane into itself, so K differs from H's own
  // restriction by w^T H w only (second order); [e f]^T [e f] = I + O(u) moves K's eigenvalues
  // by O(u mu) and its vectors by O(u mu / gap), a value change of O(min(gap, (u mu)^2 / gap))
  // <= u mu; the atan2 of entries rounded once is good to a few u. The inverse iteration
  // (refine) alone cannot do this: its shift, 1e-6 of mu below, lies between two eigenvalues
  // that are closer than that.
  void offer_ritz() {
    for (int k = 0; k < 2; ++k) {
      if (!(in_window(k) || in_window(k + 1))) continue;
      if (!(mu(k + 1) - mu(k) <= 1e-2 * std::max(std::fabs(mu(k + 1)), std::fabs(mu(k))) + 2 * m[k])) continue;
      V3 r[2];
      if (!calls.ritz(vector(k), vector(k + 1), r)) continue;
      for (const V3& v : r)
        for (double s : {1.0, -1.0}) offer_if_held(mul(v, s), -1);
    }
  }

  // The eigenvectors in the window, ascending. A plane of eigenvectors: two eigenvalues within
  // the solver's resolution of each other (relative to them, not to |H|: a far vertex's huge
  // eigenvalue beside two moderate ones must not merge the moderate two). Its arc's middle is
  // offered, and each computed vector.
  void offer_eigenvectors() {
    for (int k = zeros; k < 3; ++k) {
      if (!(mu(k) < best_here * (1 - kPrune) + m[k])) break;  // ascending
      const bool plane = k < 2 && mu(k + 1) - mu(k) <= kDegenerate * std::fabs(mu(k + 1)) + 2 * m[k];
      if (mu(k) < lower_here - m[k] && !(plane && mu(k + 1) >= lower_here - m[k + 1])) continue;
      if (plane) {
        offer_plane(k);
        ++k;
        continue;
      }
      // The polish (refine) only for an orientation that holds its conditions as computed: the
      // conditions' tolerance (kSign) is far above the polish's change of direction.
      const V3 raw = vector(k);
      for (double s : {1.0, -1.0}) {
        if (!exact && !cond.hold(mul(raw, s))) continue;
        offer_if_held(mul(calls.refine(raw, mu(k)), s), k);
      }
    }
  }
  void offer_plane(int k) {  // eigenvectors k and k + 1 span a plane
    const V3 e = vector(k), f = vector(k + 1);
    V3 w;
    if (arc_middle(cond, e, f, w)) {
      held[k] = held[k + 1] = true;
      best.offer(P, w);
    }
    for (int j = 0; j < 2; ++j) {
      const V3 u = calls.refine(j ? f : e, mu(k));
      for (double s : {1.0, -1.0}) offer_if_held(mul(u, s), k + j);
    }
  }

  const Eigen::Matrix3d& H;
  const double h_error;
  const bool exact;
  const bool accurate;  // PieceMatrix::accurate
  const int zeros;      // PieceMatrix::zeros
  const AccurateMoments* moments;  // PieceMatrix::moments, ma, mb
  const unsigned ma, mb;
  const long pe;
  Calls& calls;
  const Problem& P;
  Best& best;
  const double lower;
  double hnorm = 0, margin = 0, best_here = 0, lower_here = 0, threshold = 0, floor = 0;
  double solver_error = 0;  // accurate H: the computed pairs' backward error (backward_error)
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  Eigen::Vector3d mu;
  double m[3] = {0, 0, 0};  // each eigenvalue's margin (above)
  Conditions cond;
  bool held[3] = {false, false, false};  // exact path: eigenvector k held the signs
  V3 ritz[3] = {};  // ritz_pair's vectors, kept as vector k where has_ritz[k]
  bool has_ritz[3] = {false, false, false};
};

template <class Calls>
void consider_piece(const PieceMatrix& piece, Calls& calls, const Search& search) {
  PieceVisit<Calls>(piece, calls, search).run();
}

// consider_piece's first step alone: the piece certainly holds no eigenvalue of the exact H_S in
// the window (nothing to offer), shown by the cheap tests on this H and its error.
template <class Calls>
bool outside_window(const PieceMatrix& piece, Calls& calls, const Search& search) {
  return PieceVisit<Calls>(piece, calls, search).outside();
}

}  // namespace pdd::fast::global
