#include "pdd/reference/global_pdd.h"

#include <CGAL/Interval_nt.h>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <stdexcept>
#include <vector>

#include "pdd/reference/candidate_directions.h"
#include "pdd/reference/direction_qp.h"
#include "pdd/reference/relaxed_pieces.h"

namespace pdd::reference {
namespace {

using Vec3 = std::array<double, 3>;

// ---------------------------------------------------------------- the double-precision guess
// Only a heuristic: which active set to try at a normal. Every bound and value it leads to is
// decided exactly (a wrong guess costs tightness, never validity).
struct DoublePair {
  std::array<Vec3, 4> A, B;
};

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The threshold structure of relaxed_pieces.h: the active vertices of A are the highest m_A,
// those of B the lowest m_B. Of the 16 (m_A, m_B), the one whose KKT conditions are violated
// least (in doubles, relative to the spread of the heights).
ActiveSet guess_active_set(const DoublePair& p, const Vec3& n) {
  std::array<double, 4> a, b;
  std::array<int, 4> ia{0, 1, 2, 3}, ib{0, 1, 2, 3};
  for (int i = 0; i < 4; ++i) a[i] = dot(n, p.A[i]), b[i] = dot(n, p.B[i]);
  std::sort(ia.begin(), ia.end(), [&](int x, int y) { return a[x] > a[y]; });
  std::sort(ib.begin(), ib.end(), [&](int x, int y) { return b[x] < b[y]; });
  ActiveSet best{};
  double best_violation = INFINITY;
  for (int mA = 1; mA <= 4; ++mA)
    for (int mB = 1; mB <= 4; ++mB) {
      double sa = 0, sb = 0;
      for (int k = 0; k < mA; ++k) sa += a[ia[k]];
      for (int k = 0; k < mB; ++k) sb += b[ib[k]];
      const double wA = 1.0 / (5 - mA), wB = 1.0 / (5 - mB);
      const double c = (wA * sa + wB * sb) / (mA * wA + mB * wB);
      const double TA = (mA * c - sa) * wA, TB = -TA;
      double violation = 0;
      for (int k = 0; k < 4; ++k) {
        const double d = a[ia[k]] - c - TA, e = c - b[ib[k]] + TB;
        violation = std::max(violation, k < mA ? -d : d);
        violation = std::max(violation, k < mB ? -e : e);
      }
      if (violation < best_violation) {
        best_violation = violation;
        best = {0, 0};
        for (int k = 0; k < mA; ++k) best.a |= 1u << ia[k];
        for (int k = 0; k < mB; ++k) best.b |= 1u << ib[k];
      }
    }
  return best;
}

// ---------------------------------------------------------------- exact helpers
bool positive_semidefinite(const std::array<std::array<Rational, 3>, 3>& S) {
  for (int i = 0; i < 3; ++i)
    if (S[i][i] < 0) return false;
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (S[i][i] * S[j][j] - S[i][j] * S[j][i] < 0) return false;
  const Rational det = S[0][0] * (S[1][1] * S[2][2] - S[1][2] * S[2][1]) -
                       S[0][1] * (S[1][0] * S[2][2] - S[1][2] * S[2][0]) +
                       S[0][2] * (S[1][0] * S[2][1] - S[1][1] * S[2][0]);
  return det >= 0;  // all principal minors >= 0: positive semi-definite
}

// A double mu <= the smallest eigenvalue lambda_1 of H (proved), as close to it as a double can
// be. H is symmetric (real eigenvalues lambda_1 <= lambda_2 <= lambda_3) and a sum of outer
// products (lambda_1 >= 0), so mu = 0 always holds.
// Start: the doubles' estimate (a Rayleigh quotient), lowered until H - mu I is positive
// semi-definite (checked exactly: all principal minors >= 0, i.e. mu <= lambda_1), else 0.
// Then Newton's method on p(t) = det(t I - H) = t^3 - tr t^2 + m2 t - det (exact rational
// coefficients; m2 the sum of the principal 2 x 2 minors), from the left. Proof that every
// iterate stays <= lambda_1: for t <= lambda_1, p(t) = (t - lambda_1)(t - lambda_2)(t - lambda_3)
// <= 0, p'(t) > 0 unless t = lambda_1 = lambda_2, and p''(t) = 6 (t - tr/3) <= 0 since
// lambda_1 <= tr/3 (the smallest eigenvalue is at most their mean). p is concave on
// [t, lambda_1], so its tangent at t lies above it there and meets 0 at t' = t - p(t)/p'(t) <=
// lambda_1 (t' >= t as p(t) <= 0 < p'(t)). Each iterate is rounded DOWN to a double (to_interval's
// lower end), which keeps it <= lambda_1 and the rationals small. Convergence is quadratic for a
// simple root: the estimate's ~u |H|^2 / gap error (a depth of 1e-27 beside |H| ~ 1 leaves it
// no correct digit; the exact check then accepts only mu = lambda (1 - 1e-4)) is gone after a
// few steps, and a double root converges linearly. The result is re-checked exactly.
double certified_min_eigenvalue(const std::array<std::array<Rational, 3>, 3>& H, double lambda_min) {
  double mu = 0;
  if (lambda_min > 0 && std::isfinite(lambda_min))
    for (double shrink : {1e-15, 1e-13, 1e-10, 1e-7, 1e-4}) {
      const double m = lambda_min * (1 - shrink);
      auto S = H;
      for (int i = 0; i < 3; ++i) S[i][i] -= Rational(m);
      if (positive_semidefinite(S)) {
        mu = m;
        break;
      }
    }
  const double start = mu;
  const Rational tr = H[0][0] + H[1][1] + H[2][2];
  const Rational m2 = H[0][0] * H[1][1] - H[0][1] * H[1][0] + H[0][0] * H[2][2] - H[0][2] * H[2][0] +
                      H[1][1] * H[2][2] - H[1][2] * H[2][1];
  const Rational det = H[0][0] * (H[1][1] * H[2][2] - H[1][2] * H[2][1]) -
                       H[0][1] * (H[1][0] * H[2][2] - H[1][2] * H[2][0]) +
                       H[0][2] * (H[1][0] * H[2][1] - H[1][1] * H[2][0]);
  for (int it = 0; it < 60; ++it) {
    const Rational t(mu);
    const Rational p = ((t - tr) * t + m2) * t - det;
    if (p >= 0) break;  // p(t) = 0: t = lambda_1 (p > 0 cannot happen for t <= lambda_1)
    const Rational dp = (3 * t - 2 * tr) * t + m2;
    if (dp <= 0) break;  // t = lambda_1 = lambda_2 (then p(t) = 0 too): nothing to gain
    const double next = CGAL::to_interval(t - p / dp).first;  // rounded down
    if (!(next > mu)) break;  // no progress in doubles
    mu = next;
  }
  auto S = H;  // the proof above, checked
  for (int i = 0; i < 3; ++i) S[i][i] -= Rational(mu);
  return positive_semidefinite(S) ? mu : start;
}

// Interval arithmetic (CGAL::Interval_nt, rounding set outward by the caller's protector):
// every bound below is the lower end of an interval that contains an exact quantity, hence a
// proved bound; signs an interval cannot decide are decided in exact rationals.
using Interval = CGAL::Interval_nt<false>;
using IVec = std::array<Interval, 3>;

IVec to_ivec(const Vector& v) {
  return {CGAL::to_interval(v.x()), CGAL::to_interval(v.y()), CGAL::to_interval(v.z())};
}
Interval idot(const IVec& a, const Vec3& n) { return a[0] * n[0] + a[1] * n[1] + a[2] * n[2]; }

// The witness normal of a piece: its smallest eigenvector, polished by inverse iteration on
// the exact H (x = adj(H - sigma I) v, sigma just below the eigenvalue, three times) and
// rounded componentwise. The solver's vector has an absolute error ~u in every component, so
// a component that should be 1e-20 has no correct digit, and the value along it exceeds the
// minimum by ~|H| u^2, which is not small beside a depth of 1e-38; componentwise rounding keeps
// every component's relative accuracy. Only the witness depends on it (any normal is a valid
// witness; its value is computed exactly).
Vec3 inverse_iteration(const std::array<std::array<Rational, 3>, 3>& H, Vec3 v, double lambda) {
  const Rational sigma = lambda > 0 && std::isfinite(lambda) ? Rational(lambda) * Rational(999999, 1000000)
                                                              : Rational(0);
  Rational m[3][3], adj[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[r][c] = H[r][c] - (r == c ? sigma : Rational(0));
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      adj[r][c] = m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1];
    }
  const Rational det = m[0][0] * adj[0][0] + m[0][1] * adj[1][0] + m[0][2] * adj[2][0];
  for (int it = 0; it < 3; ++it) {
    Rational x[3], big = 0;
    for (int r = 0; r < 3; ++r) {
      x[r] = adj[r][0] * Rational(v[0]) + adj[r][1] * Rational(v[1]) + adj[r][2] * Rational(v[2]);
      big = std::max(big, CGAL::abs(x[r]));
    }
    if (big == 0) break;
    if (det < 0) big = -big;
    for (int r = 0; r < 3; ++r) v[r] = CGAL::to_double(x[r] / big);
  }
  return v;
}

struct CachedPiece {
  RelaxedPiece piece;
  std::array<IVec, 4> D, E;  // the sign conditions, as intervals
  std::array<Vec3, 4> Dd, Ed;  // and as doubles (multiplier guesses)
  std::array<IVec, 3> H;
  double mu = 0;  // proved: u^T H u >= mu on the unit sphere
};

Vector to_vector(const Vec3& n) { return Vector(Rational(n[0]), Rational(n[1]), Rational(n[2])); }

// The smallest stationary point of u^T H u on the plane l.u = 0 (the 2x2 eigenproblem there),
// both orientations, each nudged by 2^-49 rad to the side `side` of the plane (+1: l.u > 0);
// none when l or the plane's form vanishes. A heuristic for witnesses only (each is decided
// exactly): the minimiser of a pair with a vertex 1e18 away lies on such a wall of a moderate
// piece (the far vertex free), next to a piece whose H has a huge rank-one part, which no
// double normal can enter without its value exploding (global_pdd.h).
std::vector<Vec3> wall_points(const Eigen::Matrix3d& H, const Vec3& l, double side) {
  const double ln = std::sqrt(dot(l, l));
  if (!(ln > 0) || !std::isfinite(ln)) return {};
  const int axis = std::fabs(l[0]) <= std::fabs(l[1]) && std::fabs(l[0]) <= std::fabs(l[2]) ? 0
                   : std::fabs(l[1]) <= std::fabs(l[2])                                     ? 1
                                                                                            : 2;
  const Eigen::Vector3d L(l[0], l[1], l[2]);
  Eigen::Vector3d p = L.cross(Eigen::Vector3d::Unit(axis));
  p.normalize();
  const Eigen::Vector3d q = L.cross(p) / ln;
  const double m00 = p.dot(H * p), m01 = p.dot(H * q), m11 = q.dot(H * q);
  const double mw = (m00 + m11) / 2 - std::hypot((m00 - m11) / 2, m01);
  const double a0 = m01, b0 = mw - m00, a1 = mw - m11, b1 = m01;
  const bool first = std::hypot(a0, b0) >= std::hypot(a1, b1);
  const double ua = first ? a0 : a1, ub = first ? b0 : b1;
  const double big = std::max(std::fabs(ua), std::fabs(ub));  // H-sized: may be ~1e-300
  if (!(big > 0) || !std::isfinite(big)) return {};
  const Eigen::Vector3d u = p * (ua / big) + q * (ub / big);
  if (!(u.norm() > 0) || !u.allFinite()) return {};
  std::vector<Vec3> out;
  for (double s : {1.0, -1.0}) {
    const Eigen::Vector3d w = u * (s / u.norm()) + L * (side * 0x1p-49 / ln);
    out.push_back({w(0), w(1), w(2)});
  }
  return out;
}

Vec3 face_normal(int face, double a, double b) {
  const int k = face / 2;
  Vec3 n;
  n[k] = (face % 2) ? -1.0 : 1.0, n[(k + 1) % 3] = a, n[(k + 2) % 3] = b;
  return n;
}
Vector face_normal(int face, const Rational& a, const Rational& b) {
  const int k = face / 2;
  Rational n[3];
  n[k] = (face % 2) ? -1 : 1, n[(k + 1) % 3] = a, n[(k + 2) % 3] = b;
  return Vector(n[0], n[1], n[2]);
}

struct Patch {
  int face;
  double a0, a1, b0, b1;  // dyadic: exact in doubles down to widths of 2^-52
  double lower;           // proved lower bound of relaxed(u) on the patch (a rational)
  int exact = -1;         // >= 0: the corners are ExactRect number `exact` (a0..b1 unused)
};
// A patch narrower than the doubles' grid: its dyadic corners as exact rationals.
struct ExactRect {
  Rational a0, a1, b0, b1;
};
struct ByLower {
  bool operator()(const Patch& x, const Patch& y) const { return y.lower < x.lower; }
};

class Search {
 public:
  Search(const ExactPair& pair) : pair_(pair) {
    // Positions relative to s0 (exact), for the dual bound's g and the doubles' guess.
    for (int i = 0; i < 4; ++i) {
      const Vector a = pair.A[i] - pair.A[0], b = pair.B[i] - pair.A[0];
      relA_[i] = to_ivec(a), relB_[i] = to_ivec(b);
      for (int k = 0; k < 3; ++k)
        dpair_.A[i][k] = CGAL::to_double(a[k]), dpair_.B[i][k] = CGAL::to_double(b[k]);
    }
  }

  // Current witness.
  Rational best_value;
  Vector best_normal;
  std::optional<ActiveSet> best_set;  // nullopt: the start witness
  std::size_t evaluations = 0;

  double evaluate(const Patch& patch) {
    ++evaluations;
    const double ac = (patch.a0 + patch.a1) / 2, bc = (patch.b0 + patch.b1) / 2;
    const Vec3 nc = face_normal(patch.face, ac, bc);
    ActiveSet s = guess_active_set(dpair_, nc);
    if (s.a == 0 || s.b == 0) return 0;
    if (!optimal_at(piece(s), nc)) {  // doubles guessed wrong (near ties): decide exactly
      if (auto exact = exact_active_set(nc)) s = *exact;
    }
    const CachedPiece& cp = piece(s);
    if (optimal_at(cp, nc)) offer(cp, nc);

    const std::array<Vec3, 4> corners = {
        face_normal(patch.face, patch.a0, patch.b0), face_normal(patch.face, patch.a1, patch.b0),
        face_normal(patch.face, patch.a0, patch.b1), face_normal(patch.face, patch.a1, patch.b1)};
    double lower = 0;
    bool everywhere = true;  // the piece is optimal on the whole cone
    for (const Vec3& n : corners) everywhere = everywhere && optimal_at(cp, n);
    if (everywhere) lower = cp.mu;
    lower = std::max(lower, dual_bound(cp, nc, corners));
    // Bound (D) holds for ANY admissible multipliers (relaxed_pieces.h), so where the centre's
    // do not reach the target, two more choices are tried:
    //  - those of the piece optimal at each corner (decided exactly where the doubles' guess
    //    fails). This closes patches that straddle a wall: beside a far vertex
    //    (coordinates-1-to-1e18) a centre just on the steep side gives multipliers dominated by
    //    that vertex, whose g is nearly orthogonal to the corners on the moderate side (bound
    //    0), while a corner on the moderate side gives the moderate multipliers, continuous
    //    across the wall (G is C^1);
    //  - those of the witness's piece at the witness: tight there (at a stationary point g is
    //    parallel to the normal), so the patches around the witness close at a coarser width.
    for (std::size_t k = 0; k < corners.size() && lower < want; ++k) {
      ActiveSet sk = guess_active_set(dpair_, corners[k]);
      if (sk.a == 0 || sk.b == 0 || !optimal_at(piece(sk), corners[k]))
        if (auto exact = exact_active_set(corners[k])) sk = *exact;
      if (sk.a == 0 || sk.b == 0) continue;
      lower = std::max(lower, dual_bound(piece(sk), corners[k], corners));
    }
    if (lower < want) {
      if (const CachedPiece* wp = witness_piece()) {
        const Vec3 nb{CGAL::to_double(best_normal[0]), CGAL::to_double(best_normal[1]),
                      CGAL::to_double(best_normal[2])};
        lower = std::max(lower, dual_bound(*wp, nb, corners));
        // The same multipliers taken exactly, at the exact witness: where heights cancel (six
        // vertices of nearly coplanar faces within 1e-13 of one plane, a far vertex's walls
        // stacked in one band) the doubles' multipliers have no correct digit, while the
        // exact ones at a minimiser make g parallel to it, so (D) loses only ~theta^2 of the
        // value at an angle theta from it: the patches there close.
        if (lower < want)
          lower = std::max(lower, exact_multiplier_bound(*wp, best_normal,
                                                         {to_vector(corners[0]), to_vector(corners[1]),
                                                          to_vector(corners[2]), to_vector(corners[3])}));
      }
    }
    if (lower < want)  // bound (Q) below: every active set of the patch at once
      lower = std::max(lower, hull_bound({to_vector(corners[0]), to_vector(corners[1]),
                                          to_vector(corners[2]), to_vector(corners[3])}));
    return lower;
  }

  // A patch below the doubles' grid (a vertex 1e-18 inside a face puts the minimiser in a
  // band ~1e-19 rad wide, where G changes by orders of magnitude across 2^-52): the same
  // bounds with every normal, active set and multiplier exact. Multipliers in doubles carry an
  // error ~u |D_i| |n|, which swamps g when the depth is below ~u times the pair's size.
  double evaluate_exact(int face, const ExactRect& r) {
    ++evaluations;
    const Vector nc = face_normal(face, (r.a0 + r.a1) / 2, (r.b0 + r.b1) / 2);
    const std::array<Vector, 4> corners = {face_normal(face, r.a0, r.b0), face_normal(face, r.a1, r.b0),
                                           face_normal(face, r.a0, r.b1), face_normal(face, r.a1, r.b1)};
    double lower = 0;
    if (const auto s = exact_active_set(nc)) {
      const CachedPiece& cp = piece(*s);
      offer_exact(cp, nc);
      bool everywhere = true;
      for (const Vector& n : corners) everywhere = everywhere && piece_is_optimal_at(cp.piece, n);
      if (everywhere) lower = cp.mu;
      lower = std::max(lower, exact_multiplier_bound(cp, nc, corners));
    }
    for (std::size_t k = 0; k < corners.size() && lower < want; ++k)
      if (const auto sk = exact_active_set(corners[k]))
        lower = std::max(lower, exact_multiplier_bound(piece(*sk), corners[k], corners));
    if (lower < want)
      if (const CachedPiece* wp = witness_piece())
        lower = std::max(lower, exact_multiplier_bound(*wp, best_normal, corners));
    if (lower < want) lower = std::max(lower, hull_bound(corners));
    return lower;
  }

  // Bound (Q), for patches that no single multiplier vector closes: around a vertex 1e15 to
  // 1e18 away from the others, its walls (where its status changes) stack within ~1e-14 rad,
  // the corners of one patch fall in up to four active sets, and bound (D) with any one
  // piece's multipliers gives nothing there (adversarial kind 9: gaps of 1e-9 to 53% without bound (Q)).
  // The patch is the cone spanned by its four corners c_k; scaled by dyadic s_k with
  // |s_k c_k| <= 1 (checked exactly), every unit u of the patch is p/|p| with p in
  // conv{s_k c_k}, |p| <= 1, so relaxed(u) = G(p)/|p|² >= G(p) >= the minimum of G over the hull,
  // which relaxed_hull_minimum (direction_qp.h) computes exactly as one QP, over every active
  // set at once. Valid at any width; it loses only the factor |p*|² at the hull's minimiser,
  // 1 − O(width²) (the chord's sagitta) − ~2^-49 (the scaling). Returned rounded down to a
  // double. One exact QP (~2 ms): used only where the other bounds fall short of the target,
  // at most max_hull_bounds times per search (GlobalOptions; the far-vertex pairs need 40 to 120).
  std::size_t max_hull_bounds = 0;
  std::size_t hull_bounds = 0;
  double hull_bound(const std::array<Vector, 4>& corners) {
    if (hull_bounds >= max_hull_bounds) return 0;
    ++hull_bounds;
    std::vector<Vector> scaled;
    for (const Vector& c : corners) {
      const Rational cc = c.squared_length();
      double s = (1 / std::sqrt(CGAL::to_double(cc))) * (1 - 0x1p-50);
      while (!(Rational(s) * Rational(s) * cc <= 1)) s *= 1 - 0x1p-50;
      scaled.push_back(c * Rational(s));
    }
    const double v = CGAL::to_interval(relaxed_hull_minimum(pair_, scaled)).first;
    return v > 0 ? v : 0;
  }

  // The bound a patch must reach to be closed (the search's target; 0: no extra work).
  double want = 0;

 private:
  const CachedPiece& piece(ActiveSet s) {
    auto it = cache_.find(s);
    if (it != cache_.end()) return it->second;
    CachedPiece c;
    c.piece = relaxed_piece(pair_, s);
    for (int i = 0; i < 4; ++i) {
      c.D[i] = to_ivec(c.piece.D[i]), c.E[i] = to_ivec(c.piece.E[i]);
      for (int k = 0; k < 3; ++k)
        c.Dd[i][k] = CGAL::to_double(c.piece.D[i][k]), c.Ed[i][k] = CGAL::to_double(c.piece.E[i][k]);
    }
    Eigen::Matrix3d H;
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) {
        c.H[r][k] = CGAL::to_interval(c.piece.H[r][k]);
        H(r, k) = CGAL::to_double(c.piece.H[r][k]);
      }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(H);
    if (eig.info() == Eigen::Success) {
      const Eigen::Vector3d e = eig.eigenvectors().col(0);
      double estimate = eig.eigenvalues()(0);
      if (e.allFinite() && e.norm() > 0) {
        const Vec3 v = inverse_iteration(c.piece.H, {e(0), e(1), e(2)}, estimate);
        const Vector vv = to_vector(v);
        // The Rayleigh quotient of the polished vector: >= the smallest eigenvalue and equal
        // to it to second order, where the solver's own estimate has an absolute error of
        // u |H| (useless for a depth of 1e-21 beside |H| ~ 1).
        if (vv != CGAL::NULL_VECTOR)
          estimate = CGAL::to_double(piece_quadratic(c.piece, vv) / vv.squared_length());
        for (double sign : {1.0, -1.0}) {
          const Vec3 n{sign * v[0], sign * v[1], sign * v[2]};
          if (optimal_at(c, n)) offer(c, n);
        }
      }
      c.mu = certified_min_eigenvalue(c.piece.H, estimate);
      // One more step of inverse iteration, exact and not rounded: x = adj(H - mu I) v. A
      // double normal (any rounding of the eigenvector) is off by an angle ~u, which puts its
      // value ~|H| u^2 above the eigenvalue: a relative excess of ~1e-6 for a depth of 1e-27
      // beside |H| ~ 1 (nearly coplanar faces), far above the 1e-12 gap. With mu within a few
      // ulps of lambda_1 the step divides the angle by ~(lambda_2 - mu)/(lambda_1 - mu), and the
      // rational x is the witness (its value is decided exactly like any other).
      if (e.allFinite() && e.norm() > 0 && c.mu > 0) {
        const Vec3 v = {e(0), e(1), e(2)};
        const Rational sigma(c.mu);
        Rational m[3][3];
        for (int r = 0; r < 3; ++r)
          for (int k = 0; k < 3; ++k) m[r][k] = c.piece.H[r][k] - (r == k ? sigma : Rational(0));
        Rational x[3];
        for (int r = 0; r < 3; ++r) {
          x[r] = 0;
          for (int k = 0; k < 3; ++k) {
            const int r1 = (k + 1) % 3, r2 = (k + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
            x[r] += (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) * Rational(v[k]);
          }
        }
        // scaled to integers: the witness is handed to CGAL's QP solver, which takes dyadic
        // numbers only (to_qp_number); any positive multiple of a normal is the same normal
        const Rational d = Rational(x[0].denominator()) * Rational(x[1].denominator()) *
                           Rational(x[2].denominator());
        const Vector xv(x[0] * d, x[1] * d, x[2] * d);
        // Taken only where it matters for the gap (it beats the witness by more than 1e-13,
        // a tenth of the default gap): elsewhere a double normal is as good and far shorter
        // to print (the rational x has ~300 digits per component).
        if (xv != CGAL::NULL_VECTOR)
          for (const Vector& n : {xv, -xv})
            if (piece_is_optimal_at(c.piece, n)) {
              const Rational value = piece_quadratic(c.piece, n) / n.squared_length();
              if (value < best_value * Rational(9999999999999, 10000000000000))
                best_value = value, best_normal = n, best_set = c.piece.set;
            }
      }
    }
    // Witnesses on the piece's walls (wall_point), both orientations, each decided exactly.
    for (int i = 0; i < 4; ++i)
      for (int side = 0; side < 2; ++side) {
        const Vec3& l = side ? c.Ed[i] : c.Dd[i];
        const bool active = ((side ? c.piece.set.b : c.piece.set.a) >> i) & 1u;
        for (const Vec3& n : wall_points(H, l, active ? 1.0 : -1.0))
          if (optimal_at(c, n)) offer(c, n);
      }
    return cache_.emplace(s, std::move(c)).first->second;
  }

  // The piece optimal at the witness (nullptr when none is: a start witness outside every
  // piece cannot happen for an intersecting pair, but nothing relies on it).
  const CachedPiece* witness_piece() {
    if (best_set) return &piece(*best_set);
    if (witness_normal_ != best_normal) {  // the start witness: its set, decided once
      witness_normal_ = best_normal;
      witness_set_ = exact_active_set(best_normal);
    }
    return witness_set_ ? &piece(*witness_set_) : nullptr;
  }

  void offer_exact(const CachedPiece& cp, const Vector& v) {  // cp optimal at v
    if (v == CGAL::NULL_VECTOR) return;
    const Rational exact = piece_quadratic(cp.piece, v) / v.squared_length();
    if (exact < best_value) best_value = exact, best_normal = v, best_set = cp.piece.set;
  }

  // Bound (D) with the piece's multipliers at n computed exactly: l_A,i = max(0, D_i.n) for
  // the active vertices (likewise l_B), as dual_bound takes them in doubles; admissible and
  // balanced the same way, so the bound holds whatever n is.
  double exact_multiplier_bound(const CachedPiece& cp, const Vector& n,
                                const std::array<Vector, 4>& corners) const {
    std::array<Rational, 4> a, b;
    bool anyA = false, anyB = false;
    for (int i = 0; i < 4; ++i) {
      a[i] = b[i] = 0;
      if (cp.piece.set.a >> i & 1u) {
        const Rational d = cp.piece.D[i] * n;
        if (d > 0) a[i] = d, anyA = true;
      }
      if (cp.piece.set.b >> i & 1u) {
        const Rational e = cp.piece.E[i] * n;
        if (e > 0) b[i] = e, anyB = true;
      }
    }
    if (!anyA || !anyB) return 0;
    return exact_dual_bound(a, b, corners);
  }

  // The active set optimal at n, by the threshold structure on exact heights (16 candidates).
  std::optional<ActiveSet> exact_active_set(const Vec3& n) { return exact_active_set(to_vector(n)); }
  std::optional<ActiveSet> exact_active_set(const Vector& v) {
    std::array<Rational, 4> a, b;
    std::array<int, 4> ia{0, 1, 2, 3}, ib{0, 1, 2, 3};
    for (int i = 0; i < 4; ++i) a[i] = (pair_.A[i] - CGAL::ORIGIN) * v, b[i] = (pair_.B[i] - CGAL::ORIGIN) * v;
    std::sort(ia.begin(), ia.end(), [&](int x, int y) { return a[x] > a[y]; });
    std::sort(ib.begin(), ib.end(), [&](int x, int y) { return b[x] < b[y]; });
    for (int mA = 1; mA <= 4; ++mA)
      for (int mB = 1; mB <= 4; ++mB) {
        ActiveSet s;
        for (int k = 0; k < mA; ++k) s.a |= 1u << ia[k];
        for (int k = 0; k < mB; ++k) s.b |= 1u << ib[k];
        if (piece_is_optimal_at(piece(s).piece, v)) return s;
      }
    return std::nullopt;
  }

  // The piece's KKT sign conditions at n: by intervals, exactly where they cannot tell.
  bool optimal_at(const CachedPiece& cp, const Vec3& n) const {
    bool exact_needed = false;
    for (int i = 0; i < 4; ++i) {
      for (int side = 0; side < 2; ++side) {
        const Interval v = idot(side ? cp.E[i] : cp.D[i], n);
        const bool active = ((side ? cp.piece.set.b : cp.piece.set.a) >> i) & 1u;
        if (active ? v.sup() < 0 : v.inf() > 0) return false;
        if (active ? v.inf() < 0 : v.sup() > 0) exact_needed = true;
      }
    }
    return !exact_needed || piece_is_optimal_at(cp.piece, to_vector(n));
  }

  void offer(const CachedPiece& cp, const Vec3& n) {
    const Vector v = to_vector(n);
    if (v == CGAL::NULL_VECTOR) return;
    Interval q = 0;
    for (int r = 0; r < 3; ++r) q += idot(cp.H[r], n) * n[r];
    const Interval value = q / (n[0] * Interval(n[0]) + n[1] * Interval(n[1]) + n[2] * Interval(n[2]));
    if (Rational(value.inf()) >= best_value) return;  // cannot improve: skip the exact work
    const Rational exact = piece_quadratic(cp.piece, v) / v.squared_length();
    if (exact < best_value) best_value = exact, best_normal = v, best_set = cp.piece.set;
  }

  // Bound (D) of relaxed_pieces.h. The certificate: l_A = the piece's multipliers at nc in
  // doubles, clamped at 0 (exact numbers), and l_B' = r l_B with l_B likewise and
  // r = sum l_A / sum l_B (an exact real): admissible, exactly balanced. g and K are enclosed
  // by intervals; g uses positions relative to s0, which balance makes equivalent.
  double dual_bound(const CachedPiece& cp, const Vec3& nc, const std::array<Vec3, 4>& corners) const {
    double lA[4], lB[4], sA = 0, sB = 0;
    for (int i = 0; i < 4; ++i) {
      lA[i] = (cp.piece.set.a >> i & 1u) ? std::max(0.0, dot(cp.Dd[i], nc)) : 0.0;
      lB[i] = (cp.piece.set.b >> i & 1u) ? std::max(0.0, dot(cp.Ed[i], nc)) : 0.0;
      if (!std::isfinite(lA[i]) || !std::isfinite(lB[i])) return 0;
      sA += lA[i], sB += lB[i];
    }
    if (!(sA > 0) || !(sB > 0)) return 0;
    Interval sumA = 0, sumB = 0, qA = 0, qB = 0;
    IVec gA{0, 0, 0}, gB{0, 0, 0};
    for (int i = 0; i < 4; ++i) {
      sumA += lA[i], sumB += lB[i];
      qA += Interval(lA[i]) * lA[i], qB += Interval(lB[i]) * lB[i];
      for (int k = 0; k < 3; ++k) gA[k] += relA_[i][k] * lA[i], gB[k] += relB_[i][k] * lB[i];
    }
    const Interval r = sumA / sumB;
    IVec g;
    for (int k = 0; k < 3; ++k) g[k] = gA[k] - r * gB[k];
    const Interval K = 5 * qA - CGAL::square(sumA) + CGAL::square(r) * (5 * qB - CGAL::square(sumB));
    double lower = INFINITY;
    bool undecided = !(K.inf() > 0);
    for (std::size_t k = 0; k < corners.size() && !undecided; ++k) {
      const Vec3& n = corners[k];
      const Interval gn = idot(g, n);
      if (gn.sup() <= 0) return 0;  // g.n <= 0 at a corner: (D) gives nothing here
      if (!(gn.inf() > 0)) {
        undecided = true;
        break;
      }
      const Interval nn = n[0] * Interval(n[0]) + n[1] * Interval(n[1]) + n[2] * Interval(n[2]);
      lower = std::min(lower, (CGAL::square(gn) / (4 * K * nn)).inf());
    }
    if (undecided) return exact_dual_bound(lA, lB, corners);
    return std::isfinite(lower) ? lower : 0;
  }

  // The same certificate in exact rationals (cancellation beyond the intervals' reach); the
  // bound is rounded down to a double.
  double exact_dual_bound(const double lA[4], const double lB[4],
                          const std::array<Vec3, 4>& corners) const {
    std::array<Rational, 4> a, b;
    std::array<Vector, 4> c;
    for (int i = 0; i < 4; ++i) a[i] = lA[i], b[i] = lB[i], c[i] = to_vector(corners[i]);
    return exact_dual_bound(a, b, c);
  }
  double exact_dual_bound(const std::array<Rational, 4>& lA, const std::array<Rational, 4>& lB,
                          const std::array<Vector, 4>& corners) const {
    Rational sA = 0, sB = 0, qA = 0, qB = 0;
    Vector gA = CGAL::NULL_VECTOR, gB = CGAL::NULL_VECTOR;
    for (int i = 0; i < 4; ++i) {
      const Rational& a = lA[i];
      const Rational& b = lB[i];
      sA += a, sB += b, qA += a * a, qB += b * b;
      gA = gA + (pair_.A[i] - pair_.A[0]) * a;
      gB = gB + (pair_.B[i] - pair_.A[0]) * b;
    }
    const Rational r = sA / sB;
    const Vector g = gA - gB * r;
    const Rational K = 5 * qA - sA * sA + r * r * (5 * qB - sB * sB);
    if (K <= 0) return 0;
    double lower = INFINITY;
    for (const Vector& v : corners) {
      const Rational gn = g * v;
      if (gn <= 0) return 0;
      lower = std::min(lower, CGAL::to_interval(gn * gn / (4 * K * v.squared_length())).first);
    }
    return std::isfinite(lower) ? lower : 0;
  }

  const ExactPair& pair_;
  DoublePair dpair_;
  Vector witness_normal_ = CGAL::NULL_VECTOR;  // witness_piece()'s cache
  std::optional<ActiveSet> witness_set_;
  std::array<IVec, 4> relA_, relB_;
  std::map<ActiveSet, CachedPiece> cache_;
};

// 2^e exactly, for any int e (doubles stop at 2^+-1023).
Rational power_of_two(int e) {
  Rational r = 1, b = e >= 0 ? Rational(2) : Rational(1, 2);
  for (unsigned k = static_cast<unsigned>(e >= 0 ? e : -e); k; k >>= 1, b = b * b)
    if (k & 1u) r = r * b;
  return r;
}

}  // namespace

GlobalPdd global_pdd(const ExactPair& pair, const Vector& start, const Rational& start_value,
                     const ExactTet& start_q1_A, const ExactTet& start_q1_B,
                     const GlobalOptions& options) {
  // The search runs on P' = (P - s0) 2^-e, with e making the largest coordinate of P' about 1:
  // relaxed values scale by 4^-e exactly and are translation invariant, so every bound and
  // witness carries over exactly, and the doubles and intervals of the search stay in range
  // whatever the pair's scale (2^-300, 2^260, ...).
  double largest = 0;
  for (int t = 0; t < 2; ++t)
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k)
        largest = std::max(largest, std::fabs(CGAL::to_double(((t ? pair.B : pair.A)[i][k]) - pair.A[0][k])));
  int e = 0;
  if (!std::isfinite(largest)) e = 1026;  // differences beyond the double range (|x| ~ 1e308)
  else if (largest > 0) std::frexp(largest, &e);
  const Rational down = power_of_two(-e);  // exact, whatever e (2^-1100 .. 2^1100)
  ExactPair P;
  for (int i = 0; i < 4; ++i) {
    P.A[i] = CGAL::ORIGIN + (pair.A[i] - pair.A[0]) * down;
    P.B[i] = CGAL::ORIGIN + (pair.B[i] - pair.A[0]) * down;
  }
  const Rational value_scale = down * down;  // relaxed(P') = value_scale * relaxed(P)

  CGAL::Protect_FPU_rounding<true> outward;  // Interval_nt<false> needs rounding towards +inf
  Search search(P);
  search.max_hull_bounds = options.max_hull_bounds;
  search.best_value = start_value * value_scale;
  search.best_normal = start;

  std::priority_queue<Patch, std::vector<Patch>, ByLower> open;
  std::vector<ExactRect> rects;  // the corners of the patches below the doubles' grid
  constexpr int kInitialSplit = 4;  // 4 x 4 patches per face to begin with
  for (int face = 0; face < 6; ++face)
    for (int i = 0; i < kInitialSplit; ++i)
      for (int j = 0; j < kInitialSplit; ++j) {
        const double w = 2.0 / kInitialSplit;
        Patch p{face, -1 + i * w, -1 + (i + 1) * w, -1 + j * w, -1 + (j + 1) * w, 0};
        p.lower = search.evaluate(p);
        open.push(p);
      }

  const Rational keep = Rational(1) - options.gap;
  Rational target = search.best_value * keep;
  double target_d = CGAL::to_interval(target).second;  // >= target
  search.want = target_d;
  bool gap_met = false;
  while (!open.empty()) {
    const Patch& top = open.top();
    if (top.lower >= target_d || Rational(top.lower) >= target) {
      gap_met = true;
      break;
    }
    if (search.evaluations >= options.max_patches || rects.size() > options.max_exact_patches) break;
    Patch p = top;
    open.pop();
    const double am = (p.a0 + p.a1) / 2, bm = (p.b0 + p.b1) / 2;
    if (p.exact < 0 && !(p.a0 < am && am < p.a1 && p.b0 < bm && bm < p.b1)) {
      // 2^-52 wide: the doubles cannot split it; its corners go on exactly (the same normals)
      p.exact = int(rects.size());
      rects.push_back({Rational(p.a0), Rational(p.a1), Rational(p.b0), Rational(p.b1)});
    }
    if (p.exact >= 0) {
      const ExactRect r = rects[p.exact];
      const Rational am_x = (r.a0 + r.a1) / 2, bm_x = (r.b0 + r.b1) / 2;
      for (const ExactRect& c : {ExactRect{r.a0, am_x, r.b0, bm_x}, ExactRect{am_x, r.a1, r.b0, bm_x},
                                 ExactRect{r.a0, am_x, bm_x, r.b1}, ExactRect{am_x, r.a1, bm_x, r.b1}}) {
        Patch child{p.face, 0, 0, 0, 0, 0, int(rects.size())};
        rects.push_back(c);
        child.lower = std::max(search.evaluate_exact(p.face, c), p.lower);
        open.push(child);
      }
    } else {
      for (Patch c : {Patch{p.face, p.a0, am, p.b0, bm, 0}, Patch{p.face, am, p.a1, p.b0, bm, 0},
                      Patch{p.face, p.a0, am, bm, p.b1, 0}, Patch{p.face, am, p.a1, bm, p.b1, 0}}) {
        c.lower = std::max(search.evaluate(c), p.lower);  // the parent's bound holds on the child
        open.push(c);
      }
    }
    if (search.best_value * keep != target) {
      target = search.best_value * keep;
      target_d = CGAL::to_interval(target).second;
      search.want = target_d;
    }
  }

  GlobalPdd out;
  out.patches = search.evaluations;
  out.gap_met = gap_met;
  out.lower = (open.empty() ? search.best_value
                            : std::min(Rational(open.top().lower), search.best_value)) / value_scale;
  if (options.floor > out.lower) out.lower = options.floor;
  out.normal = search.best_normal;
  if (!search.best_set) {
    out.value = start_value, out.q1_A = start_q1_A, out.q1_B = start_q1_B;
    return out;
  }
  // The witness's value from CGAL's QP solver, which must agree with the closed form exactly.
  CandidateDirection dir;
  dir.n = search.best_normal;
  const auto qp = direction_qp(pair, dir, PddCase::Relaxed, QpFormulation::Reduced);
  if (!qp || qp->value * value_scale != search.best_value)
    throw std::logic_error("global_pdd: the closed-form relaxed optimum disagrees with the QP");
  out.value = qp->value, out.q1_A = qp->q1_A, out.q1_B = qp->q1_B;
  return out;
}

}  // namespace pdd::reference
