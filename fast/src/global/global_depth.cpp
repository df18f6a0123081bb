// global_depth.cpp — see global_depth.h for the method and its argument.
#include "global/global_depth.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "exact/exact_candidate.h"
#include "exact/exact_geometry.h"
#include "global/piece_screen.h"
#include "qp/deformable_depth.h"
#include "qp/direction_qp.h"
#include "qp/direction_qp_impl.h"

namespace pdd::fast {
namespace {

using detail::ColumnsB;
using detail::kPopcount;
using detail::kSignOf;
using detail::kSign;
using detail::RowLanes;
using detail::ScreenLanes;
using detail::screen;
using detail::surviving_pieces;

using V3 = std::array<double, 3>;

constexpr double kU = 0x1p-53;         // unit roundoff
constexpr double kGlobalRel = 1e-10;   // value error budget (definitions §8's 1e-9, with room)
constexpr double kPrune = 1e-10;       // an eigenvalue must beat the best by this, relative
constexpr double kEigen = 1e-12;       // eigenvalue error of the 3x3 solver, times |H|_F
constexpr double kDegenerate = 1e-6;   // eigenvalues this close (times |H|_F) span a plane
constexpr double kNearDouble = 1e-2;   // a gap below this (times |H|_F): the iterative solver

double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 add(const V3& a, const V3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
V3 mul(const V3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double norm(const V3& a) { return std::sqrt(dot(a, a)); }
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

struct Problem {
  V3 relA[4], relB[4];  // x - A[0] (rounded once): heights for the evaluations
  V3 pA[4], pB[4];      // about the centroid: the enumeration's geometry
  double scale = 0;     // max |relA|, |relB| component
};

// relaxed(v) = cost / (20 v.v) by direction_qp.h's closed form on heights relative to A[0].
// (hA, hB: the heights, when wanted.)
double relaxed_at(const Problem& P, const V3& v, DirectionSolution* sol = nullptr,
                  double* hmax = nullptr, double* hA_out = nullptr, double* hB_out = nullptr) {
  double local[8];
  double *hA = hA_out ? hA_out : local, *hB = hB_out ? hB_out : local + 4, hm = 0;
  for (int i = 0; i < 4; ++i) {
    hA[i] = dot(v, P.relA[i]), hB[i] = dot(v, P.relB[i]);
    hm = std::max({hm, std::fabs(hA[i]), std::fabs(hB[i])});
  }
  const DirectionSolution s = solve_relaxed(hA, hB);
  if (sol) *sol = s;
  if (hmax) *hmax = hm;
  return s.cost / (20.0 * dot(v, v));
}

// relaxed(v) in rationals (the exact closed form along the exact normal v), with its solution.
detail::Q relaxed_exact(const TetVertices& A, const TetVertices& B, const V3& v, detail::Q hA[4],
                        detail::Q hB[4], Solution<detail::Q>& s) {
  using detail::Q;
  const Q v0(v[0]), v1(v[1]), v2(v[2]);
  for (int i = 0; i < 4; ++i) {
    hA[i] = v0 * (Q(A[i][0]) - Q(A[0][0])) + v1 * (Q(A[i][1]) - Q(A[0][1])) + v2 * (Q(A[i][2]) - Q(A[0][2]));
    hB[i] = v0 * (Q(B[i][0]) - Q(A[0][0])) + v1 * (Q(B[i][1]) - Q(A[0][1])) + v2 * (Q(B[i][2]) - Q(A[0][2]));
  }
  s = detail::solve_relaxed_heights(hA, hB);
  return s.cost / (20 * (v0 * v0 + v1 * v1 + v2 * v2));
}

// The certified relative error of relaxed_at's value along v (value_bounds.h's QP bound):
// heights rel = x - A0 rounded (u |rel|) then a dot product (3 u sum |v_k rel_k|), so
// e_h <= 5 u |v|_1 scale; the closed form's T within dT = 2^12 u Hm; |Phi~ - Phi| <= 2 e_h +
// sqrt(2) dT + 4 u Phi~ with Phi = sqrt(cost / 20); the value Phi^2 / v.v (v.v to 3u) has
// relative error <= 2 r + 8u, r = |Phi~ - Phi| / Phi~. +inf when Phi~ = 0.
double value_error(const Problem& P, const V3& v, double cost, double hm) {
  const double vn1 = std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2]);
  const double phi = std::sqrt(cost / 20.0);
  if (!(phi > 0)) return INFINITY;
  const double r = (2 * 5 * kU * vn1 * P.scale + std::sqrt(2.0) * 0x1p12 * kU * hm) / phi + 4 * kU;
  return 2 * r + 8 * kU;
}

bool nonzero(const V3& v) { return v[0] != 0 || v[1] != 0 || v[2] != 0; }

// The normals offered so far and the best. Compared by the double closed form with its error
// bound, or (slow path, where doubles cannot resolve the pair's depths) by the exact one.
struct Best {
  double value = INFINITY;
  V3 n{};
  const TetVertices* A = nullptr;  // set: compare exactly
  const TetVertices* B = nullptr;
  // Exact comparison (A set): the best exact value `qvalue` (the pair's units); `value` is it
  // times 2^-2unit (the coordinates' scale of the exact pieces), for the record only: pieces
  // compare eigenvalues in their own units through value_in().
  long unit = 0;
  detail::Q qvalue;
  bool have_q = false;
  struct Offer {
    double value, error;
    V3 n;
  };
  // Double path: every normal evaluated. One buffer per thread, cleared per call (its
  // allocations, three per pair as it grew, were ~2% of pdd2_global); global_depth() does not
  // recurse, and one Best lives at a time per thread.
  std::vector<Offer>& offers = offer_buffer();
  static std::vector<Offer>& offer_buffer() {
    static thread_local std::vector<Offer> buffer;
    buffer.clear();
    return buffer;
  }
  // Double path: an in-window eigenvalue so close to another that the doubles' eigenvector
  // may miss its value by more than the budget (consider_piece): the caller redoes it exactly.
  bool needs_exact = false;
  // Exact path: the exact H (the scaled pair's units) and the eigenvalue's index of every
  // eigenvector that held its piece's sign conditions when offered (unrepresented() below).
  // With the piece's exact sign conditions (its cone R_S: sign[c] l[c].n >= 0 for every c, in
  // the same units), for represent_suspect().
  struct Suspect {
    std::array<std::array<detail::Q, 3>, 3> h;
    int k;  // the index (ascending) of the eigenvalue whose vector held its signs
    std::array<std::array<detail::Q, 3>, 8> l;
    std::array<int, 8> sign;
  };
  std::vector<Suspect> suspects;
  // The best value in units scaled by 2^-extra (a piece's own scale, exact path), or as is.
  double value_in(long extra) const {
    if (!A) return value;
    if (!have_q) return INFINITY;
    detail::Q x = qvalue;
    detail::scale_pow2(x, -2 * unit - extra);
    return x.get_d();
  }
  void offer(const Problem& P, const V3& v) {
    if (!nonzero(v)) return;
    if (A) {
      detail::Q hA[4], hB[4];
      Solution<detail::Q> s;
      const detail::Q q = relaxed_exact(*A, *B, v, hA, hB, s);
      if (have_q && !(q < qvalue)) return;
      qvalue = q, have_q = true, n = v;
      value = value_in(0);
      return;
    }
    DirectionSolution& s = last;
    double hm = 0, hA[4], hB[4];
    const double x = relaxed_at(P, v, &s, &hm, hA, hB);
    const double error = value_error(P, v, s.cost, hm);
    offers.push_back({x, error, v});
    if (x < value) {
      value = x, n = v;
      win.n = v, win.sol = s, win.error = error;
      std::copy(hA, hA + 4, win.hA), std::copy(hB, hB + 4, win.hB);
    }
  }
  DirectionSolution last;  // double path: the last offer's solution (descent_step)
  // Double path: the lowest offer's solution, value_error and heights (relative to A[0]).
  struct Winner {
    V3 n{};
    DirectionSolution sol;
    double error = INFINITY;
    double hA[4], hB[4];
  } win;
};

V3 refine(const double (&h)[3][3], const V3& v0, double mu, long);  // (below)

// One step from v towards a local minimum (double path, before the enumeration): v's active
// set S (its solution s, direction_qp.h: A's vertices at or above C + S_A, B's at or below
// C + S_B) has G = n^T H_S n on S's piece (enumerate_pieces' H_S, here from the centred
// vertices directly), and H_S's smallest eigenvector, oriented as v (two steps of inverse
// iteration from v), is where G would be least if the piece reached that far. It is only
// offered: an offer only ever lowers the best value,
// and a lower best prunes more pieces (the screen's and consider_piece's windows). Measured on
// the paper's pairs: 41 -> 30 pieces screened, 2.3 -> 1.4 to the eigensolver, ~0.3 us saved
// per pair (Eigen's solver in place of the inverse iteration: 0.1 us more); a second step
// costs more than it saves. Zero when S has an empty side.
V3 descent_step(const Problem& P, const V3& v, const DirectionSolution& s) {
  unsigned ma = 0, mb = 0;
  for (int i = 0; i < 4; ++i) {
    if (dot(v, P.relA[i]) >= s.c + s.sumA) ma |= 1u << i;
    if (dot(v, P.relB[i]) <= s.c + s.sumB) mb |= 1u << i;
  }
  if (!ma || !mb) return {0, 0, 0};
  const int mA = kPopcount[ma], mB = kPopcount[mb];
  const double wA = 1.0 / (5 - mA), wB = 1.0 / (5 - mB);
  V3 SA{0, 0, 0}, SB{0, 0, 0};
  for (int i = 0; i < 4; ++i) {
    if (ma >> i & 1u) SA = add(SA, P.pA[i]);
    if (mb >> i & 1u) SB = add(SB, P.pB[i]);
  }
  const V3 C = mul(add(mul(SA, wA), mul(SB, wB)), 1 / (mA * wA + mB * wB));
  const V3 TA = mul(sub(mul(C, mA), SA), wA);
  double H[3][3] = {};  // 20 H_S: the same eigenvectors
  auto add_outer = [&H](const V3& d, double w) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) H[r][c] += w * d[r] * d[c];
  };
  for (int i = 0; i < 4; ++i) {
    if (ma >> i & 1u) add_outer(sub(C, P.pA[i]), 1);
    if (mb >> i & 1u) add_outer(sub(C, P.pB[i]), 1);
  }
  add_outer(TA, 10 - mA - mB);
  // Its smallest eigenvector by inverse iteration from v (refine with shift 0: x <- adj(H) x,
  // H^-1 up to the determinant's factor, the projector onto the kernel when H is singular),
  // oriented as v: cheaper than an eigensolver, and v, the start, is usually near it.
  return refine(H, v, 0.0, 0);
}

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
bool arc_middle(const Conditions& c, const V3& p, const V3& q, V3& out) {
  double lo = 0, hi = 0;
  bool started = false;
  for (int k = 0; k < 8; ++k) {
    const double a = c.sign[k] * dot(c.l[k], p), b = c.sign[k] * dot(c.l[k], q);
    const double R = std::hypot(a, b), tol = c.tol(k);
    if (R <= tol) continue;  // holds on the whole circle within tolerance
    const double phi = std::atan2(b, a), w = M_PI / 2 + std::asin(std::min(1.0, tol / R));
    double x0 = phi - w, x1 = phi + w;
    if (!started) {
      lo = x0, hi = x1, started = true;
      continue;
    }
    const double shift = 2 * M_PI * std::round(((lo + hi) / 2 - phi) / (2 * M_PI));
    x0 += shift, x1 += shift;
    lo = std::max(lo, x0), hi = std::min(hi, x1);
    if (lo > hi) return false;
  }
  const double t = started ? (lo + hi) / 2 : 0.0;
  out = add(mul(p, std::cos(t)), mul(q, std::sin(t)));
  return true;
}

// One active set's piece as consider_piece takes it: H, its entries within h_error (absolute;
// on the exact path H is the exact one times 2^-pe, rounded once), and which path builds it.
struct PieceMatrix {
  const Eigen::Matrix3d& H;
  double h_error;
  bool exact;
  long pe;
};

// What the enumeration offers to and prunes with: the evaluations' problem, the best so far,
// and the lower bound on every G(u) (global_depth.h), in the pair's units.
struct Search {
  const Problem& P;
  Best& best;
  double lower;
};

// The piece's own operations: make_conditions() its sign conditions (built only when an
// eigenpair survives), refine(v, mu) and ritz(e, f, out) on its H (refine and ritz below),
// suspect(k) (exact path: eigenvector k held its signs, for unrepresented()).
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
      : H(piece.H), h_error(piece.h_error), exact(piece.exact), pe(piece.pe), calls(calls), P(search.P),
        best(search.best), lower(search.lower) {}

  void run() {
    hnorm = H.norm();
    margin = kEigen * hnorm + 3 * h_error;
    best_here = best.value_in(pe);  // the best value in this piece's units
    lower_here = std::ldexp(lower, int(std::clamp(-pe, -4000L, 4000L)));
    threshold = best_here * (1 - kPrune) + margin;
    floor = lower_here - margin;
    if (outside_window_cheaply() || !solve()) return;
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
  bool outside_window_cheaply() const {
    const double tr = H.trace();
    const double det_low = H.determinant() - 64 * kU * hnorm * hnorm * hnorm - 18 * hnorm * hnorm * h_error;
    if (tr > 0 && 4 * det_low / (tr * tr) > threshold) return true;
    if (tr + 3 * margin < floor) return true;
    return false;
  }

  // The eigenpairs and each eigenvalue's margin (above); false when none can matter.
  // Double path: the closed-form solver (fast; eigenvectors off by ~u |H| / gap, so the value
  // along one exceeds the stationary value by ~|H| (u |H| / gap)^2, below 1e-13 of any depth
  // this path takes, >= 1e-10 scale^2). Exact path: the iterative solver (Householder + QR),
  // whose vectors keep structure such as a zero row, then inverse iteration (refine).
  bool solve() {
    if (exact) eig.compute(H);
    else eig.computeDirect(H);
    if (eig.info() != Eigen::Success) return false;
    mu = eig.eigenvalues();
    for (int k = 0; k < 3; ++k) {
      double gap = INFINITY;
      if (k > 0) gap = std::min(gap, mu(k) - mu(k - 1));
      if (k < 2) gap = std::min(gap, mu(k + 1) - mu(k));
      m[k] = margin + 8 * kU * hnorm * hnorm / std::max(gap, std::sqrt(kU) * hnorm);
    }
    bool any = exact;  // exact: the smallest eigenvector is tried below (if not under the floor)
    for (int k = 0; k < 3; ++k) any = any || in_window(k);
    return any;
  }

  bool in_window(int k) const {
    return mu(k) >= lower_here - m[k] && mu(k) < best_here * (1 - kPrune) + m[k];
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
    for (int k = 0; k < 3; ++k) near_double = near_double || (in_window(k) && !(gap_of(k) >= kNearDouble * hnorm));
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
    const double E = 3 * h_error + 8 * kU * hnorm;
    for (int k = 0; k < 3; ++k)
      if (in_window(k) && !(2 * E * E / gap_of(k) <= 1e-11 * std::max(mu(k), lower_here))) best.needs_exact = true;
    return true;
  }

  V3 vector(int k) const {
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
    for (int k = 0; k < 3; ++k) {
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
  const long pe;
  Calls& calls;
  const Problem& P;
  Best& best;
  const double lower;
  double hnorm = 0, margin = 0, best_here = 0, lower_here = 0, threshold = 0, floor = 0;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  Eigen::Vector3d mu;
  double m[3] = {0, 0, 0};  // each eigenvalue's margin (above)
  Conditions cond;
  bool held[3] = {false, false, false};  // exact path: eigenvector k held the signs
};

template <class Calls>
void consider_piece(const PieceMatrix& piece, Calls& calls, const Search& search) {
  PieceVisit<Calls>(piece, calls, search).run();
}

// The number of eigenvalues of the symmetric M below t, exactly. N = M - tI has the
// characteristic polynomial x^3 - tr(N) x^2 + c1 x - det(N) (c1: the sum of N's principal 2x2
// minors); its roots are N's eigenvalues, all real, so by Descartes' rule (exact for real-rooted
// polynomials, zero coefficients skipped) N's negative eigenvalues, the positive roots of
// -(x^3 + tr(N) x^2 + c1 x + det(N)), number the sign changes of (1, tr N, c1, det N).
// An eigenvalue equal to t is not counted (it is not below t) unless `or_equal`: then each
// eigenvalue equal to t (a zero root of the polynomial: its trailing zero coefficients) is.
int eigenvalues_below(const std::array<std::array<detail::Q, 3>, 3>& M, const detail::Q& t,
                      bool or_equal = false) {
  using detail::Q;
  Q a[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[r][c] = M[r][c] - (r == c ? t : Q(0));
  const Q tr = a[0][0] + a[1][1] + a[2][2];
  const Q c1 = a[0][0] * a[1][1] - a[0][1] * a[1][0] + a[0][0] * a[2][2] - a[0][2] * a[2][0] +
               a[1][1] * a[2][2] - a[1][2] * a[2][1];
  const Q det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  int changes = 0, last = 1;
  for (const Q* c : {&tr, &c1, &det}) {
    const int sg = sgn(*c);
    if (sg == 0) continue;
    if (sg != last) ++changes;
    last = sg;
  }
  if (or_equal)
    for (const Q* c : {&det, &c1, &tr}) {
      if (sgn(*c) != 0) break;
      ++changes;
    }
  return changes;
}

// Exact path: whether the best offer may miss the minimum by more than definitions §8 allows
// because no double normal represents a better stationary point. An offered normal is an
// eigenvector rounded to doubles; along it the value exceeds the eigenvalue mu by up to
// ~|H| (u |v|)^2 / |v|^2, which is not small beside mu when the depth is far below the pair's
// size (a vertex 1e-18 inside a face: mu ~1e-37 beside |H| ~ 25). So every eigenvector that held its piece's
// signs when offered (the minimum may be there) is a suspect, and one whose exact eigenvalue
// lies in (floor, top), top = best (1 + 2^-53) / (1 + 1e-9), may be a stationary value (if the
// exact vector lies in the piece's cone, which the tolerant signs cannot tell) that beats every
// offer. Eigenvalues at or below the floor (PD^2 / 32 (1 - 1e-8), strictly below G everywhere;
// 0 when the rigid value is not known in doubles: G > 0 on the sphere of an intersecting pair)
// are not stationary values in the cone. Counted exactly (eigenvalues_below: the eigenvalue of
// index k lies in (floor, top) iff #at_or_below(floor) <= k < #below(top)).
// Each suspect in that window is then settled (represent_suspect): either its exact eigenvector
// is proved outside its piece's cone in both orientations (not a stationary value of G), or it
// yields a proved lower bound lo <= mu, and its eigenvector rounded, the neighbouring doubles
// and integer normals along it are offered (evaluated exactly: they only lower the best; the
// normal that attains pdd2_global on a generic near-coplanar contact is found by trying such
// triples, not excluded by a ratio of depth to size). The pair is kept when the
// best exact value q after those offers satisfies q (1 + 2^-53) <= lo (1 + 1e-9) for every
// suspect kept. Why that certifies definitions §8: the true minimum m* is G(u*) with u* an
// eigenvector of the H_S of a piece S whose cone holds u* (global_depth.h); q >= m* (q is G along a
// normal). If m* is a suspect's eigenvalue: at or below the floor it cannot be; at or above top,
// q (1 + 2^-53) <= q0 (1 + 2^-53) = top (1 + 1e-9) <= m* (1 + 1e-9) with q0 the best before the
// new offers (they only lower it); in the window, settled: not discarded (its eigenvector is in
// the cone), so m* >= lo and q (1 + 2^-53) <= lo (1 + 1e-9) <= m* (1 + 1e-9). Otherwise the
// enumeration itself offered m*'s own vector, and the bound holds without this check. The
// reported value is q rounded
// once (here by get_d, or again on the pair as given: within [q (1 - 2^-52), q (1 + 2^-53)]),
// so it lies within [m* (1 - 2^-52), m* (1 + 1e-9)].
// An unsettled suspect makes the caller reject the pair (kGlobalNotRepresentable), never
// report a value. Walls' stationary points are not checked (the class below has no case of them).
V3 refine(const detail::Q (&h)[3][3], const V3& v0, double mu, long pe);  // (below)

// Integer normals near the direction of y (exact), for represent_suspect: a double triple
// rounded from a unit vector misses its direction by ~u, and along a generic direction (a contact
// not along a coordinate plane) the neighbouring doubles do no better; but the normal need not
// be a unit vector. With y_m its largest component and alpha_i = y_i / y_m (|alpha_i| <= 1),
// the triple c (alpha_0, alpha_1, alpha_2) with c an integer below 2^53 and the other two
// components rounded to integers is a double triple (every integer up to 2^53 is) whose
// direction misses y's by (frac distance of c alpha_i) / c: for the c among `tries` consecutive
// integers below 2^53 where both fractional parts are small (they are equidistributed: the best
// of M tries has both within ~1/sqrt(M)), that angle is ~1/sqrt(M) of a rounded unit vector's.
// The fractional parts are tracked in 64-bit fixed point (wrapping arithmetic is arithmetic mod
// 1): the first exactly, then minus alpha_i 2^64 rounded down per step, so after j steps they
// are off by < j 2^-64, beside the ~2^-9 that selects; the chosen triples' integers are then
// computed exactly. Only a search: each triple is evaluated exactly by the caller.
void integer_normals(const detail::Q (&y)[3], int tries, int keep, std::vector<V3>& out) {
  using detail::Q;
  int m = 0;
  for (int i = 1; i < 3; ++i)
    if (abs(y[i]) > abs(y[m])) m = i;
  if (sgn(y[m]) == 0) return;
  const int idx[2] = {(m + 1) % 3, (m + 2) % 3};
  const std::uint64_t c0 = (std::uint64_t(1) << 53) - 1;
  Q alpha[2];
  std::uint64_t A[2], F[2];
  for (int t = 0; t < 2; ++t) {
    alpha[t] = y[idx[t]] / y[m];
    auto frac64 = [&](unsigned long c) {  // floor(c alpha 2^64) mod 2^64
      mpz_class num = alpha[t].get_num() * c, q, r;
      mpz_mul_2exp(num.get_mpz_t(), num.get_mpz_t(), 64);
      mpz_fdiv_q(q.get_mpz_t(), num.get_mpz_t(), alpha[t].get_den_mpz_t());
      mpz_fdiv_r_2exp(r.get_mpz_t(), q.get_mpz_t(), 64);  // in [0, 2^64)
      return std::uint64_t(mpz_get_ui(r.get_mpz_t()));
    };
    A[t] = frac64(1), F[t] = frac64(static_cast<unsigned long>(c0));
  }
  std::vector<std::pair<double, std::uint64_t>> top;  // (metric, c), the `keep` best
  auto dist = [](std::uint64_t f) {  // distance to the nearest integer, times 2^64
    return double(f < (std::uint64_t(1) << 63) ? f : std::uint64_t(0) - f);
  };
  for (int j = 0; j < tries; ++j) {
    const double d0 = dist(F[0]), d1 = dist(F[1]), metric = d0 * d0 + d1 * d1;
    if (int(top.size()) < keep || metric < top.back().first) {
      if (int(top.size()) == keep) top.pop_back();
      top.insert(std::upper_bound(top.begin(), top.end(), std::make_pair(metric, std::uint64_t(0))),
                 {metric, c0 - std::uint64_t(j)});
    }
    F[0] -= A[0], F[1] -= A[1];  // c -> c - 1 (mod 2^64: mod 1)
  }
  const double s = sgn(y[m]) > 0 ? 1.0 : -1.0;
  for (const auto& [metric, c] : top) {
    V3 v;
    v[m] = s * double(c);
    for (int t = 0; t < 2; ++t) {  // round(c alpha) = floor((2 c num + den) / (2 den)), exactly
      mpz_class num = alpha[t].get_num(), den = alpha[t].get_den(), q;
      num *= static_cast<unsigned long>(c);
      num = 2 * num + den;
      den *= 2;
      mpz_fdiv_q(q.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
      v[idx[t]] = s * q.get_d();  // |q| <= c < 2^53: exact
    }
    out.push_back(v);
  }
}

// One suspect in the window (above): true when its eigenvalue is proved not to be a stationary
// value of G (both unit eigenvectors outside the cone); else lo (a proved lower bound of the
// eigenvalue, at least `bottom`) and the offers, as above.
// The eigenvector x: Eigen's on h rounded (scaled by a power of two), polished by inverse
// iteration on the exact h (refine: each step rounded componentwise to doubles) shifted by the
// exact Rayleigh quotient of Eigen's; then y = one exact step more (below). The proof holds
// for any non-zero vector y (x, tried first as it is cheap, or y): with rho = y^T h y / y^T y
// and R2 = |h y - rho y|^2 / y^T y (exact rationals), and g > 0 such that h has exactly one
// eigenvalue, the k-th, in (rho - g, rho + g) (counted exactly by eigenvalues_below, with multiplicity: so that
// eigenvalue mu is simple and every other lambda_j has |lambda_j - rho| >= g). Write y / |y| =
// sum c_j e_j in h's orthonormal eigenvectors, sum c_j^2 = 1. Then R2 = sum c_j^2 (lambda_j -
// rho)^2 >= g^2 sum_{j != k} c_j^2 = g^2 sin^2 t (t the angle between y and e = +-e_k chosen
// with e.y >= 0, t <= pi/2), so sin^2 t <= s2 = R2 / g^2 (the sin theta theorem).
// (a) Cone: |y/|y| - e|^2 = 2 - 2 cos t <= 2 sin^2 t for t <= pi/2, so |l.y/|y| - l.e| <=
// |l| sqrt(2 s2) for each condition l: when sign l.y < 0 and (l.y)^2 > 2 |l|^2 |y|^2 s2,
// sign l.e < 0 and e is outside the cone; when sign l.y > 0 and the same, -e is. Both outside
// (the only unit eigenvectors of the simple mu): not a stationary value of its piece, dropped.
// (b) Bound: sum c_j^2 (lambda_j - rho) = 0 (rho's definition), so c_k^2 |mu - rho| =
// |sum_{j != k} c_j^2 (lambda_j - rho)| <= sum_{j != k} c_j^2 (lambda_j - rho)^2 / g <= R2 / g,
// and c_k^2 = cos^2 t >= 1 - s2: mu >= rho - R2 / (g (1 - s2)) when s2 < 1. lo is that,
// checked once more by counting (#at_or_below(lo) <= k, i.e. mu > lo), when above `bottom`.
// Where a step fails (no gap, s2 >= 1, a count disagrees), lo = bottom: still a lower bound
// (the eigenvalue lies in the window), which no offer meets unless its value is as low as the
// floor (0, or ~PD^2 / 32 <= G): in practice the pair is then rejected. The offers are tried
// in order of cost (x itself; the 26 triples one ulp away; integer normals along y) until q
// meets lo to kGlobalRel (below).
// represent_suspect's exact arithmetic on one suspect (its argument above): the eigenvector x
// (Eigen's, polished), y (one exact step more), the Rayleigh quotient rho of the last vector
// given to rayleigh() with R2 = |h q - rho q|^2 / q.q and q.q, and what settle() proved.
class SuspectProof {
  using Q = detail::Q;

 public:
  explicit SuspectProof(const Best::Suspect& s) : s(s) {}

  // h (exact), its double image H = h 2^-pe and Eigen's eigenpairs of H; false when h = 0 or
  // the solver fails.
  bool setup() {
    pe = LONG_MIN;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) h[r][c] = s.h[r][c], pe = std::max(pe, detail::log2_estimate(h[r][c]));
    if (pe == LONG_MIN) return false;  // h = 0 (no eigenvalue in the window: not reached)
    Eigen::Matrix3d H;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        Q x = h[r][c];
        detail::scale_pow2(x, -pe);
        H(r, c) = x.get_d();
      }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(H);
    if (eig.info() != Eigen::Success) return false;
    mu_d = eig.eigenvalues();  // in units of 2^pe
    e0 = eig.eigenvectors().col(s.k);
    return true;
  }

  // x: Eigen's vector polished by refine, shifted by its exact Rayleigh quotient; then rho and
  // R2 of x. false when a vector vanishes.
  bool polish() {
    qx[0] = Q(e0(0)), qx[1] = Q(e0(1)), qx[2] = Q(e0(2));
    if (sgn(qx[0]) == 0 && sgn(qx[1]) == 0 && sgn(qx[2]) == 0) return false;
    rayleigh(qx);
    x = refine(h, V3{e0(0), e0(1), e0(2)}, in_units(rho), pe);
    if (!nonzero(x)) return false;
    for (int c = 0; c < 3; ++c) qx[c] = Q(x[c]);
    rayleigh(qx);
    return true;
  }

  // The Rayleigh quotient rho of q, R2 = |h q - rho q|^2 / q.q and q.q, exactly.
  void rayleigh(const Q (&q)[3]) {
    Q hq[3];
    for (int r = 0; r < 3; ++r) hq[r] = h[r][0] * q[0] + h[r][1] * q[1] + h[r][2] * q[2];
    qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
    rho = (q[0] * hq[0] + q[1] * hq[1] + q[2] * hq[2]) / qq;
    R2 = 0;
    for (int r = 0; r < 3; ++r) {
      const Q res = hq[r] - rho * q[r];
      R2 += res * res;
    }
    R2 /= qq;
  }

  // (a) and (b) above for the vector q of the last rayleigh(): which orientations are proved
  // outside the cone (excluded_pos, excluded_neg), and the bound rho - R2 / (g (1 - s2));
  // false where g or s2 fails. g: half the distance from rho to the solver's nearest other
  // eigenvalue (a guess; the counts decide).
  bool settle(const Q (&q)[3]) {
    excluded_pos = excluded_neg = false;
    const double rho_d = in_units(rho);
    double gap_d = INFINITY;
    for (int j = 0; j < 3; ++j)
      if (j != s.k) gap_d = std::min(gap_d, std::fabs(mu_d(j) - rho_d));
    if (!(gap_d > 0) || !std::isfinite(gap_d)) return false;
    Q g(gap_d / 2);
    if (sgn(g) == 0) return false;  // (underflow)
    detail::scale_pow2(g, pe);
    if (eigenvalues_below(s.h, rho - g, true) != s.k || eigenvalues_below(s.h, rho + g) != s.k + 1) return false;
    const Q s2 = R2 / (g * g);
    if (!(s2 < 1)) return false;
    for (int c = 0; c < 8; ++c) {
      const auto& l = s.l[c];
      const Q p = s.sign[c] * (l[0] * q[0] + l[1] * q[1] + l[2] * q[2]);
      const Q ll = l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
      if (p * p > 2 * ll * qq * s2) (sgn(p) < 0 ? excluded_pos : excluded_neg) = true;
    }
    bound = rho - R2 / (g * (1 - s2));
    return true;
  }
  bool excluded() const { return excluded_pos && excluded_neg; }

  // y = adj(h - rho I) x: one more step of inverse iteration, exact, shifted by x's Rayleigh
  // quotient. It damps x's components along the other eigenvectors by |mu - rho| /
  // |lambda_j - rho| (rho is within ~|H| u^2 of mu), so y's direction is far more accurate than
  // x's (x is rounded to doubles: its Rayleigh quotient, and the bound from it, would miss mu
  // by ~|H| u^2, not small beside a depth of 1e-26 |H|). Oriented as x. Then rho and R2 of y.
  void exact_step() {
    Q m[3][3], adj[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m[r][c] = h[r][c] - (r == c ? rho : Q(0));
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
        adj[r][c] = m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1];  // cofactor (c, r)
      }
    for (int r = 0; r < 3; ++r) y[r] = adj[r][0] * qx[0] + adj[r][1] * qx[1] + adj[r][2] * qx[2];
    const Q yx = y[0] * qx[0] + y[1] * qx[1] + y[2] * qx[2];
    if (sgn(yx) == 0)
      for (int c = 0; c < 3; ++c) y[c] = qx[c];  // (x orthogonal to adj's range: keep x)
    else if (sgn(yx) < 0)
      for (Q& c : y) c = -c;
    rayleigh(y);
  }

  // Offers, each stage only while the bound lo is not met (met() below): x in each orientation
  // not excluded; integer normals along y (a generic direction); the 26 triples one ulp away
  // from x in some components (nextafter each way: a direction near an axis, where x's small
  // components carry their own exponents and integer normals would round them coarsely).
  // bounded: lo is a proved bound (else lo = bottom, which no offer meets).
  void offer_near(Best& best, const Q& lo, bool bounded) const {
    Problem none;  // (the exact offers do not read it)
    Q scale_top(1);
    detail::scale_pow2(scale_top, -2 * best.unit);
    // The offers go on until q (1 + 2^-53) <= lo (1 + kGlobalRel), q in the suspects' units: the
    // double path's budget, a tenth of what unrepresented() accepts (definitions §8's 1e-9), so
    // that a value accepted there is not needlessly near the contract's edge where a better normal
    // is cheap to find.
    auto met = [&] {
      return bounded && best.qvalue * scale_top * (Q(1) + Q(1, 1ul << 53)) <= lo * (Q(1) + Q(kGlobalRel));
    };
    auto offer = [&](const V3& v) {
      for (double sg : {1.0, -1.0})
        if (!(sg > 0 ? excluded_pos : excluded_neg)) best.offer(none, mul(v, sg));
    };
    offer(x);
    if (!bounded || met()) return;  // (unbounded: lo = bottom, which no offer meets)
    std::vector<V3> normals;
    integer_normals(y, 1 << 18, 4, normals);
    for (const V3& v : normals) offer(v);
    for (int m = 0; m < 27 && !met(); ++m) {
      if (m == 13) continue;  // all three components as they are: x
      V3 v = x;
      for (int c = 0, mm = m; c < 3; ++c, mm /= 3)
        if (mm % 3 != 1) v[c] = std::nextafter(v[c], mm % 3 == 0 ? -INFINITY : INFINITY);
      offer(v);
    }
  }

  Q qx[3], y[3];
  Q bound;  // settle()'s bound, when it succeeded

 private:
  double in_units(const Q& v) const {  // v 2^-pe as a double
    Q t = v;
    detail::scale_pow2(t, -pe);
    return t.get_d();
  }

  const Best::Suspect& s;
  Q h[3][3];
  long pe = LONG_MIN;
  Eigen::Vector3d mu_d, e0;
  Q rho, R2, qq;
  V3 x{};
  bool excluded_pos = false, excluded_neg = false;
};

bool represent_suspect(Best& best, const Best::Suspect& s, const detail::Q& bottom, detail::Q& lo) {
  lo = bottom;
  SuspectProof p(s);
  if (!p.setup() || !p.polish()) return false;
  // x alone usually proves a spurious suspect outside its cone (its conditions are violated
  // far beyond x's error, ~u): no exact step needed.
  if (p.settle(p.qx) && p.excluded()) return true;
  p.exact_step();
  bool bounded = false;
  if (p.settle(p.y)) {
    if (p.excluded()) return true;
    if (eigenvalues_below(s.h, p.bound, true) <= s.k && p.bound > bottom) lo = p.bound, bounded = true;
  }
  p.offer_near(best, lo, bounded);
  return false;
}

bool unrepresented(Best& best, double floor_scaled) {
  using detail::Q;
  if (!best.have_q || best.suspects.empty()) return false;
  // top: the reported value, qvalue rounded to a double (<= qvalue (1 + 2^-53)), is within
  // 1e-9 of every stationary value mu >= top (qvalue (1 + 2^-53) <= mu (1 + 1e-9)). (Was
  // qvalue (1 - 1e-9): it let the rounded value exceed such a mu by up to 1e-9 + 1.2e-16.)
  Q top = best.qvalue * (Q(1) + Q(1, 1ul << 53)) / (Q(1) + Q(1, 1000000000));
  detail::scale_pow2(top, -2 * best.unit);
  const Q bottom(floor_scaled);
  std::vector<std::size_t> window;
  for (std::size_t i = 0; i < best.suspects.size(); ++i) {  // eigenvalue k (ascending) in (bottom, top)?
    const auto& [h, k, l, sign] = best.suspects[i];
    const int below_top = eigenvalues_below(h, top), below_floor = eigenvalues_below(h, bottom, true);
    if (below_floor <= k && k < below_top) window.push_back(i);
  }
  if (window.empty()) return false;
  std::vector<Q> lows;  // the settled suspects' lower bounds
  for (std::size_t i : window) {
    Q lo;
    if (!represent_suspect(best, best.suspects[i], bottom, lo)) lows.push_back(lo);
  }
  // The suspects just above the window, in [top, q0 (1 + 2^-53) / (1 + kGlobalRel)), q0 the
  // best now: within 1e-9 of the value already (the argument above needs nothing of them), but
  // more than kGlobalRel below it, and their offers may come closer (a generic direction's
  // rounded eigenvector misses by up to that 1e-9). Offers only: they lower the best and leave
  // every bound above as it is. (Only where the window was not empty: a pair accepted without
  // it keeps its value.)
  Q q0 = best.qvalue * (Q(1) + Q(1, 1ul << 53)) / (Q(1) + Q(kGlobalRel));
  detail::scale_pow2(q0, -2 * best.unit);
  for (std::size_t i = 0; i < best.suspects.size(); ++i) {
    const auto& [h, k, l, sign] = best.suspects[i];
    if (eigenvalues_below(h, top) <= k && k < eigenvalues_below(h, q0)) {
      Q lo;
      represent_suspect(best, best.suspects[i], top, lo);
    }
  }
  Q q = best.qvalue * (Q(1) + Q(1, 1ul << 53));  // (the final best, after every offer)
  detail::scale_pow2(q, -2 * best.unit);
  for (const Q& lo : lows)
    if (q > lo * (Q(1) + Q(1, 1000000000))) return true;
  return false;
}

// unrepresented()'s class: a rounded normal v~ (componentwise, |v~ - v| <= u |v|) changes the
// value of a stationary point mu of a piece by (v~ - v)^T (H - mu I) (v~ - v) / |v~|^2 <=
// |H|_2 u^2 (1 + 2u). When every vertex is within L of the centroid, H's entries
// (enumerate_pieces: (QA + QB - C S - S C + m C C + k T T) / 20 with |Q| <= 4 L^2, |C| <= L,
// |S| <= 8 L, |T| <= 2 L, m <= 8, k <= 8) are <= 76 L^2 / 20 < 4 L^2, so |H|_2 <= 12 L^2, and
// where mu >= 1e-20 L^2 the rounding costs <= 12 * 4.9e-32 / 1e-20 < 6e-11 relative, within
// kGlobalRel: the offers (eigenvectors polished exactly, rounded componentwise) represent it.
// Below that, unrepresented() decides. L is taken as the SMALLER tetrahedron's extent: a
// contact much shallower than both tetrahedra (a vertex 1e-18 inside a face: adversarial-1-3,
// -13, -23, whose fast values would be 13%, 7% and 22% above the exact minimum without this rule)
// is rejected. Not proved: a pair whose one tetrahedron is far larger than the other (a vertex
// 1e18 away: the pieces with it active have |H| ~ 1e36) is not covered by the bound above;
// there the minimiser lies on the walls of the far vertex, offered from the near side, and
// the fast values agree with the exact engine's closed intervals (coordinates-1-to-1e18,
// adversarial-1-9, -19, the wide pair of tests/compare; -29 within its 1.7e-8 gap).
constexpr double kUnrepresentedDepth = 1e-20;
constexpr double kCompactTiny = 1e-14;  // global_depth(): the compact pairs' exact-pieces depth
double near_extent_sq(const TetVertices& A, const TetVertices& B) {
  double L = INFINITY;  // the smaller tetrahedron's extent (largest coordinate range)
  for (const TetVertices* T : {&A, &B}) {
    double e = 0;
    for (int k = 0; k < 3; ++k) {
      double lo = (*T)[0][k], hi = lo;
      for (int i = 1; i < 4; ++i) lo = std::min(lo, (*T)[i][k]), hi = std::max(hi, (*T)[i][k]);
      e = std::max(e, hi - lo);
    }
    L = std::min(L, e);
  }
  return L * L;
}

// Inverse iteration on the exact H (slow path): x = (H - sigma I)^-1 v by the adjugate, twice,
// each time rounded componentwise to doubles. Eigen's vectors carry an absolute error of
// u |v| in every component; a tiny component of the true eigenvector (a normal tilted by
// 2^-60 from an axis) then has no correct digit, and the relaxed value along it, of order
// |H| u^2, swamps a depth of 1e-38. Rounded componentwise, every component keeps its relative
// accuracy. sigma = mu (1 - 1e-6): the iteration contracts by about 1e-6 towards mu's vector.
V3 refine(const detail::Q (&h)[3][3], const V3& v0, double mu, long pe) {
  using detail::Q;
  Q sigma = Q(mu) * (1 - Q(1, 1000000));
  detail::scale_pow2(sigma, pe);  // mu is in the piece's units, 2^-pe of h's
  Q m[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[r][c] = h[r][c] - (r == c ? sigma : Q(0));
  Q adj[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      adj[r][c] = m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1];  // cofactor (c, r)
    }
  const Q det = m[0][0] * adj[0][0] + m[0][1] * adj[1][0] + m[0][2] * adj[2][0];
  V3 v = v0;
  for (int it = 0; it < 3; ++it) {
    Q x[3];
    for (int r = 0; r < 3; ++r) x[r] = adj[r][0] * Q(v[0]) + adj[r][1] * Q(v[1]) + adj[r][2] * Q(v[2]);
    Q big = 0;
    for (const Q& c : x) big = std::max(big, Q(abs(c)));
    if (sgn(big) == 0) return v;
    if (sgn(det) < 0) big = -big;
    v = {Q(x[0] / big).get_d(), Q(x[1] / big).get_d(), Q(x[2] / big).get_d()};
  }
  return v;
}
// Rayleigh-Ritz on the plane of e and f (consider_piece's exact path): K = [e f]^T h [e f] in
// rationals; its eigenvectors make the angles t and t + pi/2 with e, tan 2t = 2 K01 / (K00 -
// K11), taken from K01 and (K00 - K11) / 2 rounded once. false when K is a multiple of I (every
// vector of the plane is an eigenvector: e and f are offered already).
bool ritz(const detail::Q (&h)[3][3], const V3& e, const V3& f, V3 (&out)[2]) {
  using detail::Q;
  const Q qe[3] = {Q(e[0]), Q(e[1]), Q(e[2])}, qf[3] = {Q(f[0]), Q(f[1]), Q(f[2])};
  Q he[3], hf[3];
  for (int r = 0; r < 3; ++r) {
    he[r] = h[r][0] * qe[0] + h[r][1] * qe[1] + h[r][2] * qe[2];
    hf[r] = h[r][0] * qf[0] + h[r][1] * qf[1] + h[r][2] * qf[2];
  }
  const Q k00 = qe[0] * he[0] + qe[1] * he[1] + qe[2] * he[2];
  const Q k11 = qf[0] * hf[0] + qf[1] * hf[1] + qf[2] * hf[2];
  const Q k01 = qe[0] * hf[0] + qe[1] * hf[1] + qe[2] * hf[2];
  const Q half_diff = (k00 - k11) / 2;
  if (sgn(k01) == 0 && sgn(half_diff) == 0) return false;
  // (the ratio, not the parts: h's entries may lie far outside the double range)
  const double t = sgn(half_diff) == 0 ? (sgn(k01) > 0 ? M_PI / 4 : -M_PI / 4)
                                       : 0.5 * std::atan2(Q(k01 / abs(half_diff)).get_d(), sgn(half_diff) > 0 ? 1.0 : -1.0);
  const double c = std::cos(t), s = std::sin(t);
  out[0] = add(mul(e, c), mul(f, s));
  out[1] = add(mul(e, -s), mul(f, c));
  return true;
}

// Double path: two steps of inverse iteration in doubles, x = adj(H - sigma I) v with sigma =
// mu (1 - 1e-6), normalised. The closed-form solver's vectors are the cross products of rows
// of H - mu I: beside a vertex 10^4 away (|H| ~ 1e9, a depth ~ 1) their error along the large
// eigenvector, ~ u |H| / mu, costs |H| (u |H| / mu)^2 ~ 1e-5 of the value. Each step damps that
// component by (mu - sigma) / (lambda_big - sigma); the vector's rounding then leaves u.
V3 refine(const double (&h)[3][3], const V3& v0, double mu, long) {
  const double sigma = mu * (1 - 1e-6);
  double m[3][3], adj[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[r][c] = h[r][c] - (r == c ? sigma : 0.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      adj[r][c] = m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1];  // cofactor (c, r)
    }
  V3 v = v0;
  for (int it = 0; it < 2; ++it) {
    V3 x;
    for (int r = 0; r < 3; ++r) x[r] = adj[r][0] * v[0] + adj[r][1] * v[1] + adj[r][2] * v[2];
    const double nx = norm(x);
    if (!(nx > 0) || !std::isfinite(nx)) return v;
    x = mul(x, 1 / nx);
    if (dot(x, v) < 0) x = mul(x, -1.0);  // keep the orientation
    v = x;
  }
  return v;
}

// H_S by moments (enumerate_pieces): with S_A's sum SA and second moment QA = sum a a^T (and B's), the closed form's
//   20 H = sum_{S_A} (C - a)(C - a)^T + sum_{S_B} (C - b)(C - b)^T + k TA TA^T
//        = QA + QB - C (SA + SB)^T - (SA + SB) C^T + (mA + mB) C C^T + k TA TA^T,
// k = 2 + (4 - mA) + (4 - mB) (the free vertices' T_A^2 and T_B^2, and 2 T_A^2 for the centre),
// with the 16 subsets' sums and moments computed once. In doubles each entry of 20 H errs by
// at most 2^-39 mag, mag the sum of the terms' bounds (|QA| + |QB| + 2 |C| |SA + SB| +
// (mA + mB) |C|^2 + k |TA|^2, max norms): the derivation is piece_screen.h's (the inputs' own
// errors, C's and T_A's above all, included; 16u mag would count only the last expression's
// roundings). The /20 adds u relative, inside that bound's margin.
// The 16 subsets' sums and second moments (xx xy xz yy yz zz) of A's and B's positions, each
// from the subset without its highest vertex i: the terms added in increasing i, from 0 (the
// same roundings as summing each subset on its own).
template <class T>
void subset_sums(const std::array<std::array<T, 3>, 4>& pA, const std::array<std::array<T, 3>, 4>& pB,
                 std::array<T, 3> (&SA)[16], std::array<T, 3> (&SB)[16], std::array<T, 6> (&QA)[16],
                 std::array<T, 6> (&QB)[16]) {
  constexpr int kR[6] = {0, 0, 0, 1, 1, 2}, kC[6] = {0, 1, 2, 1, 2, 2};
  SA[0] = SB[0] = {T(0), T(0), T(0)};
  QA[0].fill(T(0)), QB[0].fill(T(0));
  for (unsigned m = 1; m < 16; ++m) {
    const int i = m >= 8 ? 3 : m >= 4 ? 2 : m >= 2 ? 1 : 0;
    const unsigned rest = m & ~(1u << i);
    for (int k = 0; k < 3; ++k) SA[m][k] = SA[rest][k] + pA[i][k], SB[m][k] = SB[rest][k] + pB[i][k];
    for (int q = 0; q < 6; ++q)
      QA[m][q] = QA[rest][q] + pA[i][kR[q]] * pA[i][kC[q]], QB[m][q] = QB[rest][q] + pB[i][kR[q]] * pB[i][kC[q]];
  }
}

template <class T>
using Corners = std::array<std::array<T, 3>, 4>;

// One piece's geometry (relaxed_pieces.h's closed form: c = C.n, T_A = TA.n = -T_B), its
// 20 H's moments' combination H (exact or in doubles), and (exact path) the power of two pe
// its double matrix is scaled by.
template <class T>
struct PieceGeometry {
  unsigned ma = 0, mb = 0;
  int mA = 0, mB = 0;
  std::array<T, 3> C, TA, S;
  T h[3][3];
  long pe = 0;
};

// The enumeration of enumerate_pieces (below) over one pair: the subset sums, the pieces that
// survive the pruning, and each survivor's H and conditions for consider_piece.
template <class T, class ToDouble>
class PieceEnumeration {
  static constexpr bool kExact = !std::is_same_v<T, double>;
  using TV = std::array<T, 3>;
  using M6 = std::array<T, 6>;  // xx xy xz yy yz zz
  static constexpr int kR[6] = {0, 0, 0, 1, 1, 2}, kC[6] = {0, 1, 2, 1, 2, 2};
  static TV vadd(const TV& a, const TV& b) { return TV{a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
  static TV vsub(const TV& a, const TV& b) { return TV{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
  static TV vmul(const TV& a, const T& s) { return TV{a[0] * s, a[1] * s, a[2] * s}; }

 public:
  PieceEnumeration(const Corners<T>& pA, const Corners<T>& pB, const Search& search, ToDouble to_d)
      : pA(pA), pB(pB), search(search), P(search.P), best(search.best), to_d(to_d) {}

  void run() {
    sums();
    if constexpr (kExact) survivors_exact();
    else survivors_double();
    for (unsigned ma = 1; ma < 16; ++ma)
      for (unsigned bits = survivors[ma]; bits; bits &= bits - 1) visit(ma, unsigned(__builtin_ctz(bits)));
  }

 private:
  double amax(const TV& x) const {
    double m = 0;
    for (const T& c : x) m = std::max(m, std::fabs(to_d(c)));
    return m;
  }

  // The pieces' double matrices N = 20 H by rows (surviving_pieces), with their eigenvalue
  // counts at the window's edges. Double path: on its own sums. Exact path: on the exact
  // positions rounded once (|x| < 4 here), each coordinate within u |x| of the exact one;
  // that moves the exact 20 H by at most 704 u L^2 per entry (C moves by <= u L and each C - a
  // by <= 2u L, |C - a| <= 2L: 8u L^2 per outer product, <= 8 of them; T_A = wA sum (C - a)
  // moves by <= 2u L mA wA, |T_A| <= 2L mA wA, so k T_A T_A^T by <= 8 k wA^2 mA^2 u L^2 <=
  // 640u L^2 (mA = 4: k <= 5, wA = 1)), inside the 2^14 u mag of n_error (piece_screen.h's
  // count, 10720u L^2 + 9u mag, leaves 5655u L^2 with mag >= L^2): the counts hold for the
  // exact H too.
  void sums() {
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) dA[i][k] = to_d(pA[i][k]), dB[i][k] = to_d(pB[i][k]);
    subset_sums(dA, dB, dSA, dSB, dQA, dQB);
    if constexpr (kExact) {
      subset_sums(pA, pB, xSA, xSB, xQA, xQB);
      SA = xSA, SB = xSB, QA = xQA, QB = xQB;
    } else {
      SA = dSA, SB = dSB, QA = dQA, QB = dQB;  // (the double path's own: dA = pA)
    }
    for (unsigned m = 0; m < 16; ++m) {
      qa[m] = qb[m] = 0;
      for (int q = 0; q < 6; ++q) qa[m] = std::max(qa[m], std::fabs(dQA[m][q])), qb[m] = std::max(qb[m], std::fabs(dQB[m][q]));
    }
    for (unsigned mb = 0; mb < 16; ++mb) {
      for (int k = 0; k < 3; ++k) cols.S[k][mb] = dSB[mb][k];
      for (int q = 0; q < 6; ++q) cols.Q[q][mb] = dQB[mb][q];
      cols.q[mb] = qb[mb];
      cols.m[mb] = kPopcount[mb];
      cols.w[mb] = 1.0 / (5 - kPopcount[mb]);
    }
    top = best.value_in(0) * (1 - kPrune);
  }

  // Double path: every row's pieces outside the window are dropped (surviving_pieces), the
  // rest gathered and screened side by side (screen); survivors[ma] keeps the bits of the
  // pieces left for consider_piece. Both use the best value offered so far (the start's): a
  // higher threshold than later ones, so nothing is dropped that a later one would keep.
  void survivors_double() {
    static thread_local ScreenLanes lanes;  // (~42 KB: off the stack)
    lanes.n = 0;
    for (unsigned ma = 1; ma < 16; ++ma) {
      RowLanes row;
      survivors[ma] = surviving_pieces(dSA[ma].data(), dQA[ma].data(), qa[ma], kPopcount[ma], cols, top,
                                       search.lower, row);
      for (unsigned bits = survivors[ma]; bits; bits &= bits - 1) {  // (set bits: no branch per piece)
        const unsigned mb = unsigned(__builtin_ctz(bits));
        const int p = lanes.n++;
        for (int q = 0; q < 6; ++q) lanes.N[q][p] = row.N[q][mb];
        for (int k = 0; k < 3; ++k) lanes.C[k][p] = row.C[k][mb], lanes.TA[k][p] = row.TA[k][mb];
        lanes.n_error[p] = row.n_error[mb], lanes.below_low[p] = row.below_low[mb], lanes.one[p] = row.one[mb];
        for (int i = 0; i < 4; ++i) lanes.sign[i][p] = kSignOf[ma][i], lanes.sign[4 + i][p] = kSignOf[mb][i];
        lanes.ma[p] = static_cast<unsigned char>(ma), lanes.mb[p] = static_cast<unsigned char>(mb);
      }
    }
    double qA[4][3], qB[4][3];
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) qA[i][k] = dA[i][k], qB[i][k] = dB[i][k];
    screen(lanes, qA, qB, 1e-12 * P.scale, top, search.lower);
    for (int p = 0; p < lanes.n; ++p) survivors[lanes.ma[p]] &= ~(unsigned(!lanes.keep[p]) << lanes.mb[p]);
  }

  // Exact path: only the pieces whose eigenvalues all lie certainly above the window's top
  // edge or below its bottom one are dropped: such a piece holds no stationary value in the
  // window, and no wall offer either (a wall's value lies between H's two smallest
  // eigenvalues, Cauchy interlacing: above the top, or below the bottom edge); the pieces
  // with eigenvalues on both sides of the window keep their wall offers (a far vertex's
  // minimiser, consider_piece).
  void survivors_exact() {
    for (unsigned ma = 1; ma < 16; ++ma) {
      RowLanes row;
      surviving_pieces(dSA[ma].data(), dQA[ma].data(), qa[ma], kPopcount[ma], cols, top, search.lower, row);
      survivors[ma] = 0;
      for (unsigned mb = 1; mb < 16; ++mb)
        if (!(row.below_top[mb] == 0 || row.below_low[mb] == 3)) survivors[ma] |= 1u << mb;
    }
  }

  // relaxed_pieces.h's closed form: c = C.n, T_A = TA.n = -T_B; 20 H by moments (above).
  void build(PieceGeometry<T>& g) const {
    const unsigned ma = g.ma, mb = g.mb;
    const int mA = g.mA = kPopcount[ma], mB = g.mB = kPopcount[mb];
    const T wA = T(1) / T(5 - mA), wB = T(1) / T(5 - mB);
    g.C = vmul(vadd(vmul(SA[ma], wA), vmul(SB[mb], wB)), T(1) / (T(mA) * wA + T(mB) * wB));
    g.TA = vmul(vsub(vmul(g.C, T(mA)), SA[ma]), wA);
    g.S = vadd(SA[ma], SB[mb]);
    const TV &C = g.C, &TA = g.TA, &S = g.S;
    const T m = T(mA + mB), k = T(10 - mA - mB);
    for (int q = 0; q < 6; ++q) {
      const int r = kR[q], c = kC[q];
      g.h[r][c] = (QA[ma][q] + QB[mb][q] - C[r] * S[c] - S[r] * C[c] + m * C[r] * C[c] +
                   k * TA[r] * TA[c]) / T(20);
      g.h[c][r] = g.h[r][c];
    }
  }

  // Exact path: H rounded after scaling by 2^-pe, its largest entry near 1 (a piece of the
  // near vertices of a pair with a vertex 1e200 away has entries ~1e-400 in the pair's
  // scaled units: they would underflow). Eigenvectors do not change; eigenvalues and the
  // values they are compared with are taken in the piece's units (consider_piece).
  void rounded_matrix(PieceGeometry<T>& g, Eigen::Matrix3d& H) const {
    if constexpr (kExact) {
      g.pe = LONG_MIN;
      for (int q = 0; q < 6; ++q) g.pe = std::max(g.pe, detail::log2_estimate(g.h[kR[q]][kC[q]]));
      if (g.pe == LONG_MIN) g.pe = 0;
    }
    for (int q = 0; q < 6; ++q) {
      const int r = kR[q], c = kC[q];
      if constexpr (kExact) {
        T x = g.h[r][c];
        detail::scale_pow2(x, -g.pe);
        H(r, c) = H(c, r) = to_d(x);
      } else {
        H(r, c) = H(c, r) = to_d(g.h[r][c]);
      }
    }
  }

  double h_error(const PieceGeometry<T>& g) const {
    if constexpr (kExact) return 0;
    const double c = amax(g.C), t = amax(g.TA);
    return 0x1p-39 * (qa[g.ma] + qb[g.mb] + 2 * c * amax(g.S) + (g.mA + g.mB) * c * c + (10 - g.mA - g.mB) * t * t) /
           20;
  }

  // The conditions' vectors: in doubles, with an absolute floor for their rounding (a few
  // roundings of coordinates <= scale: far above); exact path, each scaled by its own power
  // of two before rounding once (relative error u, no floor: a condition of the near
  // vertices beside a far one would underflow or drown in an absolute floor).
  V3 rounded(TV x) const {
    if constexpr (kExact) {
      long top = LONG_MIN;
      for (const T& y : x) top = std::max(top, detail::log2_estimate(y));
      if (top != LONG_MIN)
        for (T& y : x) detail::scale_pow2(y, -top);
    }
    return V3{to_d(x[0]), to_d(x[1]), to_d(x[2])};
  }
  Conditions conditions(const PieceGeometry<T>& g) const {
    Conditions cond;
    cond.floor = kExact ? 0.0 : 1e-12 * P.scale;
    for (int i = 0; i < 4; ++i) {
      const TV d = vsub(vsub(pA[i], g.C), g.TA), e = vsub(vsub(g.C, pB[i]), g.TA);
      cond.l[i] = rounded(d);        // d_i = a_i - c - T_A
      cond.sign[i] = g.ma >> i & 1u ? 1 : -1;
      cond.l[4 + i] = rounded(e);    // e_j = c - b_j + T_B
      cond.sign[4 + i] = g.mb >> i & 1u ? 1 : -1;
    }
    cond.finish();
    return cond;
  }

  // Exact path: eigenvector k of the piece held its signs (unrepresented()): its exact H and
  // conditions (conditions()' vectors, exact: d_i = a_i - c - T_A, e_j = c - b_j + T_B).
  void suspect(const PieceGeometry<T>& g, int k) {
    if constexpr (kExact) {
      const auto& h = g.h;
      Best::Suspect x{{{{h[0][0], h[0][1], h[0][2]}, {h[1][0], h[1][1], h[1][2]}, {h[2][0], h[2][1], h[2][2]}}},
                      k, {}, {}};
      for (int i = 0; i < 4; ++i) {
        const TV d = vsub(vsub(pA[i], g.C), g.TA), e = vsub(vsub(g.C, pB[i]), g.TA);
        for (int q = 0; q < 3; ++q) x.l[i][q] = d[q], x.l[4 + i][q] = e[q];
        x.sign[i] = g.ma >> i & 1u ? 1 : -1;
        x.sign[4 + i] = g.mb >> i & 1u ? 1 : -1;
      }
      best.suspects.push_back(std::move(x));
    }
  }

  void visit(unsigned ma, unsigned mb) {
    PieceGeometry<T> g;
    g.ma = ma, g.mb = mb;
    build(g);
    Eigen::Matrix3d H;
    rounded_matrix(g, H);
    auto calls = piece_calls([&] { return conditions(g); },
                             [&](const V3& v, double mu) { return refine(g.h, v, mu, g.pe); },
                             [&](const V3& e, const V3& f, V3 (&r)[2]) {
                               if constexpr (kExact) return ritz(g.h, e, f, r);
                               else return false;
                             },
                             [&](int k) { suspect(g, k); });
    consider_piece(PieceMatrix{H, h_error(g), kExact, g.pe}, calls, search);
  }

  const Corners<T>& pA;
  const Corners<T>& pB;
  const Search& search;
  const Problem& P;
  Best& best;
  ToDouble to_d;
  std::array<std::array<double, 3>, 4> dA, dB;
  std::array<double, 3> dSA[16], dSB[16];
  std::array<double, 6> dQA[16], dQB[16];
  TV xSA[16], xSB[16];  // exact path: the exact sums
  M6 xQA[16], xQB[16];
  const TV *SA = nullptr, *SB = nullptr;
  const M6 *QA = nullptr, *QB = nullptr;
  double qa[16], qb[16];  // max |QA|, |QB| (doubles)
  ColumnsB cols{};        // B's sums as lanes (surviving_pieces)
  unsigned survivors[16];
  double top = 0;         // the window's top edge: the best value so far, less kPrune
};

// Visits every active set (both sides non-empty): H_S, its eigenpairs, the eigenvectors worth
// evaluating (global_depth.h). T: double (positions about the centroid) or Q (exact positions
// relative to A[0], scaled); H and the conditions are rounded to doubles once built.
template <class T, class ToDouble>
void enumerate_pieces(const Corners<T>& pA, const Corners<T>& pB, const Search& search, ToDouble to_d) {
  PieceEnumeration<T, ToDouble>(pA, pB, search, to_d).run();
}

// The relaxed value along v (a double normal, A -> B) with a certified relative error bound,
// on heights relative to A's highest vertex along v (near the plane), so that value_bounds.h's
// tight case applies: when every vertex's KKT margin at the computed solution exceeds 2 dT,
// dT = 2^9 u Ha with Ha = max(|C|, |heights of the vertices at the plane|) ~ |v| depth, instead
// of value_error's 2^12 u max|H| ~ |v| size. Heights: x - o rounded (u |x - o| <= 2u scale per
// coordinate) then a dot product: e_h <= 10 u |v|_1 scale; then value_error's chain: r =
// (2 e_h + sqrt(2) dT) / Phi~ + 4u, error 2 r + 8u. error = +inf when a margin fails.
struct Evaluation {
  double value = INFINITY, error = INFINITY;
  DirectionSolution sol;
  double hA[4], hB[4];
};
Evaluation evaluate_tight(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v) {
  Evaluation ev;
  int top = 0;
  for (int i = 1; i < 4; ++i)
    if (dot(v, P.relA[i]) > dot(v, P.relA[top])) top = i;
  for (int i = 0; i < 4; ++i) {
    V3 a, b;
    for (int k = 0; k < 3; ++k) a[k] = A[i][k] - A[top][k], b[k] = B[i][k] - A[top][k];
    ev.hA[i] = dot(v, a), ev.hB[i] = dot(v, b);
  }
  const DirectionSolution& sol = ev.sol = solve_relaxed(ev.hA, ev.hB);
  double Ha = std::fabs(sol.c);
  bool margins = true;
  double margin[8];
  for (int i = 0; i < 4; ++i) {
    margin[i] = sol.c - ev.hA[i] + sol.sumA;      // < 0: at the plane (active)
    margin[4 + i] = sol.c - ev.hB[i] + sol.sumB;  // > 0: at the plane (active)
    if (margin[i] < 0) Ha = std::max(Ha, std::fabs(ev.hA[i]));
    if (margin[4 + i] > 0) Ha = std::max(Ha, std::fabs(ev.hB[i]));
  }
  const double dT = 0x1p9 * kU * Ha;
  for (double m : margin) margins = margins && std::fabs(m) > 2 * dT;
  const double phi = std::sqrt(sol.cost / 20.0);
  const double vn1 = std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2]);
  const double r = phi > 0 ? (2 * 10 * kU * vn1 * P.scale + std::sqrt(2.0) * dT) / phi + 4 * kU : INFINITY;
  ev.value = sol.cost / (20.0 * dot(v, v));
  if (margins) ev.error = 2 * r + 8 * kU;
  return ev;
}


// One global_depth() call: the pair, the evaluations' problem, the offers and the bounds.
struct GlobalRun {
  GlobalRun(const TetVertices& A, const TetVertices& B) : A(A), B(B) {}
  const TetVertices& A;
  const TetVertices& B;
  Problem P;
  Best best;
  double lower = 0;          // every G(u) >= lower (the pair's units)
  double lower_scaled = 0;   // the exact path's floor in its units
  bool exact_pieces = false;  // the pieces were built exactly
};

// The problem (coordinates relative to A[0] and about the centroid), the lower bound, and the
// start's offer.
void set_up(GlobalRun& g, const double start_normal[3], double rigid_pd2) {
  // G >= PD^2 / 32 (global_depth.h), with the given PD^2's 1e-8: a lower bound on every G(u).
  g.lower = std::isfinite(rigid_pd2) && rigid_pd2 > 0 ? rigid_pd2 * (1 - 1e-8) * kDeformableBoundCoeff : 0.0;
  const TetVertices &A = g.A, &B = g.B;
  Problem& P = g.P;
  V3 centroid{0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      P.relA[i][k] = A[i][k] - A[0][k], P.relB[i][k] = B[i][k] - A[0][k];
      P.scale = std::max({P.scale, std::fabs(P.relA[i][k]), std::fabs(P.relB[i][k])});
      centroid[k] += (P.relA[i][k] + P.relB[i][k]) / 8;
    }
  for (int i = 0; i < 4; ++i) P.pA[i] = sub(P.relA[i], centroid), P.pB[i] = sub(P.relB[i], centroid);
  g.best.value = INFINITY;
  g.best.n = {start_normal[0], start_normal[1], start_normal[2]};
  g.best.offer(P, g.best.n);
}

// Doubles or rationals for the pieces (the enumeration is the same). H's entries carry
// absolute errors ~64 u scale^2 in doubles, so a computed eigenvector is off by an angle
// ~1e-14 scale^2 / gap, and the value along it exceeds the minimum by about gap * angle^2 ~
// 1e-28 scale^4 / gap: negligible while the depth is far above 1e-16 scale^2. A far vertex
// (depth ~1e-11 scale^2 with a vertex 3e4 away) can also put the minimiser on the wall of a
// steep piece, which only the exact path's wall offers reach (the fuzzer found a miss of
// 1.6e-8 there). Below 1e-10 scale^2 (far vertices, contacts of 1e-5 of the pair's size) the
// pieces are built exactly, with the wall offers, and their eigenvectors polished. A compact
// pair (the smaller tetrahedron's extent >= scale / 16: no vertex far from the others, so
// every piece's |H| <= 12 L^2 with centred |coordinates| L <= 2 scale, <= 12288 near^2: no
// steep piece) keeps the doubles down to kCompactTiny = 1e-14 scale^2: the paper's shallow
// contacts (1 pair in 10^4 below 1e-10 scale^2, each ~3 ms exactly). The argument above
// takes gap ~ |H| ~ scale^2; a piece whose active vertices form a small cluster far from the
// centroid has |H| << scale^2 while H's error stays ~2^-39 of the moments: consider_piece's
// estimate 2 E^2 / gap <= 1e-11 mu, checked for every in-window eigenvalue, sends such a pair
// to the exact pieces (of shallow "tip" contacts 10-25% stay in doubles, all between 1e-12
// and 1e-10 scale^2, all within the exact intervals).
// The double pieces also need the pair's own scale within [2^-100, 2^100] (solve_pair and
// pdd2_global pass pairs rescaled to it; an unscaled pair, spanning more of the double range
// than any rescaling can bring into it, arrives through the exact path): H ~ scale^2 and its
// determinant ~ scale^6 then neither overflow nor underflow. When the double enumeration
// finds a depth below that (1e-10 or, compact, 1e-14 scale^2), it is done again exactly.
// Returns whether the pieces must be built exactly (then the double offers are dropped).
bool needs_exact_pieces(GlobalRun& g, double start_value) {
  const Problem& P = g.P;
  Best& best = g.best;
  const double tiny_rel = near_extent_sq(g.A, g.B) >= P.scale * P.scale / 256 ? kCompactTiny : 1e-10;
  auto tiny = [&](double value) { return !(value >= tiny_rel * P.scale * P.scale); };
  if (!(P.scale >= 0x1p-100 && P.scale <= 0x1p100) || tiny(best.value)) return true;
  if (nonzero(best.n) && std::isfinite(best.value)) best.offer(P, descent_step(P, best.n, best.last));
  std::array<std::array<double, 3>, 4> dA, dB;
  for (int i = 0; i < 4; ++i) dA[i] = P.pA[i], dB[i] = P.pB[i];
  enumerate_pieces(dA, dB, Search{P, best, g.lower}, [](double x) { return x; });
  // A result above the start's certified value means the doubles could not evaluate even the
  // start's normal (its components are not accurate enough beside a far vertex): exactly.
  if (tiny(best.value) || best.value > start_value * (1 + 1e-9) || best.needs_exact) {
    best.offers.clear();
    return true;
  }
  return false;
}

// The exact pieces are built on the coordinates relative to A[0] times 2^-unit (exact), with
// 2^unit the largest of them (a pair spanning 1e-302..1e308 reaches this branch unscaled,
// through solve_pair's exact path; its H would overflow in doubles). A uniform scale leaves
// the normals unchanged and multiplies every value by 2^-2unit (Best::unit). The near
// vertices' pieces beside a far vertex are still ~(size / R)^2: each piece's H and each
// condition is scaled again by its own power of two before rounding (enumerate_pieces).
void enumerate_exact(GlobalRun& g, const ExactStart& exact_start) {
  using detail::Q;
  const TetVertices &A = g.A, &B = g.B;
  Best& best = g.best;
  std::array<std::array<Q, 3>, 4> qA, qB;
  long unit = LONG_MIN;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      qA[i][k] = Q(A[i][k]) - Q(A[0][k]), qB[i][k] = Q(B[i][k]) - Q(A[0][k]);
      unit = std::max({unit, detail::log2_estimate(qA[i][k]), detail::log2_estimate(qB[i][k])});
    }
  if (unit == LONG_MIN) unit = 0;  // not reached: a valid pair has a non-zero edge
  for (auto* side : {&qA, &qB})
    for (auto& x : *side)
      for (Q& c : x) detail::scale_pow2(c, -unit);
  Problem Ps = g.P;  // the conditions' floor in the scaled units
  Ps.scale = 4.0;    // |x| 2^-unit < 4 (bit lengths give log2 |x| within 1)
  best.A = &A, best.B = &B, best.unit = unit;
  best.value = INFINITY;
  best.offer(Ps, best.n);
  if (exact_start) best.offer(Ps, exact_start());
  g.lower_scaled = std::ldexp(g.lower, int(std::clamp(-2 * unit, -4000L, 4000L)));
  enumerate_pieces(qA, qB, Search{Ps, best, g.lower_scaled}, [](const Q& x) { return x.get_d(); });
  // (lower is in the pair's units; each piece takes it, and the best value, in its own)
}

// Which offer wins (double path). Each double value carries value_error's loose bound; offers
// whose intervals meet the winner's are contenders (every other offer is certainly above the
// winner). When every contender's bounds together stay below kCompare, the double winner is
// within kCompare of the true best offer; otherwise the same test on the contenders with
// evaluate_tight's values and bounds (its winner, likewise, is within kCompare of the best
// contender), and where that fails too the contenders are compared exactly.
constexpr double kCompare = 4e-10;

// evaluate_tight's bounds (doubles): value_error's are wider than kCompare where the depth is
// far below the pair's size, and two offers of one stationary point (the descent's and the
// enumeration's) tie within them. True (best.n set) when they separate the winner.
bool tight_winner(GlobalRun& g, double win_err) {
  Best& best = g.best;
  std::vector<std::pair<Evaluation, V3>> contenders;
  for (const auto& o : best.offers)
    if (!(o.value > best.value * (1 + 2 * (win_err + o.error))))  // inf band (or NaN): every offer
      contenders.push_back({evaluate_tight(g.A, g.B, g.P, o.n), o.n});
  std::size_t w = 0;
  for (std::size_t i = 1; i < contenders.size(); ++i)
    if (contenders[i].first.value < contenders[w].first.value) w = i;
  bool separated = !contenders.empty();
  for (std::size_t i = 0; i < contenders.size(); ++i) {
    const Evaluation &x = contenders[w].first, &y = contenders[i].first;
    if (i != w && !(y.value > x.value * (1 + 2 * (x.error + y.error))) && !(x.error + y.error <= kCompare))
      separated = false;
  }
  if (separated) best.n = contenders[w].second;
  return separated;
}

// The contenders compared exactly.
void exact_winner(GlobalRun& g, double win_err) {
  Best& best = g.best;
  detail::Q bestq;
  bool have = false;
  for (const auto& o : best.offers) {
    const double band = 2 * (win_err + o.error);
    if (o.value > best.value * (1 + band)) continue;  // inf band (or NaN): every offer
    detail::Q hA[4], hB[4];
    Solution<detail::Q> sq;
    const detail::Q x = relaxed_exact(g.A, g.B, o.n, hA, hB, sq);
    if (!have || x < bestq) bestq = x, best.n = o.n, have = true;
  }
}

void choose_offer(GlobalRun& g) {
  Best& best = g.best;
  double win_err = INFINITY;
  for (const auto& o : best.offers)
    if (o.n == best.n) win_err = std::min(win_err, o.error);
  bool separated = true;
  for (const auto& o : best.offers)
    if (o.n != best.n && !(o.value > best.value * (1 + 2 * (win_err + o.error))) &&
        !(win_err + o.error <= kCompare))
      separated = false;
  if (!separated) separated = tight_winner(g, win_err);
  if (!separated) exact_winner(g, win_err);
}

// The deformed positions along the normal v (A -> B; a reference: it follows the best normal)
// from a solution s of the relaxed QP with heights hA, hB: q1 = x + t / v.v v.
struct Placement {
  const TetVertices& A;
  const TetVertices& B;
  const V3& v;
  double vv;
  GlobalOptimum& out;
  template <class S, class Heights, class ToDouble>
  void operator()(const S& s, const Heights& heights_A, const Heights& heights_B, ToDouble to_d) const {
    for (int i = 0; i < 4; ++i) {
      const double tA = to_d(displacement_below(heights_A[i], false, s));
      const double tB = to_d(displacement_above(heights_B[i], false, s));
      for (int k = 0; k < 3; ++k) {
        out.q1_A[i][k] = A[i][k] + tA / vv * v[k];
        out.q1_B[i][k] = B[i][k] + tB / vv * v[k];
      }
    }
  }
};

// The reported value (double path): the offer's own when value_error's bound meets the budget
// (the common case: ~3e-11 on the paper's pairs), else evaluate_tight's when its bound does.
// False when neither does.
bool report_double(const GlobalRun& g, const Placement& place) {
  const Best& best = g.best;
  GlobalOptimum& out = place.out;
  const V3& v = best.n;
  if (best.win.n == v && best.win.error <= kGlobalRel) {
    out.value = best.value;
    place(best.win.sol, best.win.hA, best.win.hB, [](double x) { return x; });
    out.certified = true;
    return true;
  }
  const Evaluation ev = evaluate_tight(g.A, g.B, g.P, v);
  if (ev.error <= kGlobalRel) {
    out.value = ev.value;
    place(ev.sol, ev.hA, ev.hB, [](double x) { return x; });
    out.certified = true;
    return true;
  }
  return false;
}

// Slow path: the same closed form in rationals along the same (exact) normal.
void report_exact(GlobalRun& g, Placement& place, double start_value) {
  using detail::Q;
  Best& best = g.best;
  GlobalOptimum& out = place.out;
  const V3& v = best.n;
  Q hA[4], hB[4];
  Solution<Q> qs;
  Q value = relaxed_exact(g.A, g.B, v, hA, hB, qs);
  // A depth below unrepresented()'s class on the exact pieces: its suspects are settled, and the
  // offers that settle them may lower the best (a new normal: value and positions along it).
  bool missed = false;
  if (g.exact_pieces && value.get_d() < kUnrepresentedDepth * near_extent_sq(g.A, g.B)) {
    const V3 before = best.n;
    missed = unrepresented(best, g.lower_scaled);
    if (best.n != before) {
      out.normal = best.n;
      place.vv = dot(v, v);
      value = relaxed_exact(g.A, g.B, v, hA, hB, qs);
    }
  }
  out.value = value.get_d();
  place(qs, hA, hB, [](const Q& x) { return x.get_d(); });
  out.exact_value = true;
  // Not even the start's certified value reached (rare: a pair whose depth is below about 1e-7
  // of its extent, where no double normal near the start's exact one reproduces it, and the
  // walls did not help): the normal is not given (kGlobalNotRepresentable).
  out.certified = std::isfinite(out.value) &&
                  !(std::isfinite(start_value) && value > detail::Q(start_value) * detail::Q(1 + 1e-9)) &&
                  !missed;
}

GlobalOptimum report(GlobalRun& g, double start_value) {
  GlobalOptimum out;
  out.normal = g.best.n;
  const V3& v = g.best.n;
  Placement place{g.A, g.B, v, dot(v, v), out};
  // No normal at all (no start and no stationary point passed: coordinates spanning the whole
  // double range, the caller's exact-path branch): not certified; the caller reports it
  // (found by the fast_engine fuzzer: the exact evaluation along a zero normal divided by 0).
  if (!nonzero(v) || !std::isfinite(place.vv)) return out;
  if (!g.exact_pieces && report_double(g, place)) return out;
  report_exact(g, place, start_value);
  return out;
}

}  // namespace

double exact_relaxed_value(const TetVertices& A, const TetVertices& B, const std::array<double, 3>& n,
                           bool& ok) {
  detail::Q hA[4], hB[4];
  Solution<detail::Q> s;
  return detail::rounded_value(relaxed_exact(A, B, n, hA, hB, s), ok);
}

GlobalOptimum global_depth(const TetVertices& A, const TetVertices& B, const double start_normal[3],
                           double start_value, const ExactStart& exact_start, double rigid_pd2) {
  GlobalRun g(A, B);
  set_up(g, start_normal, rigid_pd2);
  g.exact_pieces = needs_exact_pieces(g, start_value);
  if (g.exact_pieces) enumerate_exact(g, exact_start);
  else choose_offer(g);
  return report(g, start_value);
}

}  // namespace pdd::fast
