// contact_energy.cpp — pdd::mesh::contact_energy (definitions §12; include/pdd/mesh/contact_energy.h
// derives every formula used here).
#include "pdd/mesh/contact_energy.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_set>
#include <utility>

#include "pdd/global_minimiser.h"
#include "pdd/mesh.h"
#include "translation_memo.h"

namespace pdd::mesh {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

std::string to_text(double x) {  // the shortest decimal that reads back as x
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

// t's edge vectors e[j] = t[j + 1] − t[0] scaled exactly by 2^-k, 2^k the binade above their
// largest component (k set; 0 when that is 0); returns that component, NaN where one is (kept:
// std::max would drop it, and a NaN vertex 0 would read as a flat element).
double scaled_edges(const TetVertices& t, double (&e)[3][3], int& k) {
  double big = 0;
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 3; ++c) {
      e[j][c] = t[j + 1][c] - t[0][c];
      const double a = std::abs(e[j][c]);
      if (!(a <= big)) big = a;
    }
  k = 0;
  if (!std::isfinite(big) || big == 0) return big;
  std::frexp(big, &k);  // big in [2^(k-1), 2^k)
  for (auto& row : e)
    for (double& x : row) x = std::ldexp(x, -k);
  return big;
}

// The cube root of tetrahedron i's rest volume, (|det| / 6)^(1/3) of m's `vertices`, at any
// scale: the edge vectors are first scaled exactly by 2^-k, 2^k the binade above their largest
// component, so the determinant (a degree-3 product) neither overflows nor underflows where the
// root itself is a normal double, and the root is scaled back by 2^k. (The weight is the product
// of two roots: (V_a V_b)^(1/3) formed directly overflows for elements larger than ~1e51 and
// underflows below ~1e-51, where E and the weight themselves are ordinary doubles.) 0: flat; not
// finite: a coordinate or an edge vector is not.
double rest_volume_root(const Mesh& m, std::size_t i) {
  double e[3][3];
  int k = 0;
  const double big = scaled_edges(element(m, i), e, k);
  if (!std::isfinite(big)) return std::numeric_limits<double>::infinity();
  if (big == 0) return 0;
  const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                     e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                     e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  return std::ldexp(std::cbrt(std::abs(det) / 6), k);
}

// d V / d x_i divided by V for tetrahedron t's vertex i (V its signed volume, dV/dx_i the cross
// product of the two edges from x_0 opposite to it, x_0's the negated sum): the weight's
// derivative is w / 3 times this (header: weights_follow_a / _b). On the edge vectors scaled
// exactly by 2^-k as rest_volume_root scales them: cross / det in those units, times 2^-k (the
// ratio has the units of 1 / length), so no product overflows where the ratio is a double. The
// signs of V and dV cancel. Precondition: t not flat (its pairs have a weight).
std::array<Vec3d, 4> volume_log_derivative(const TetVertices& t) {
  double e[3][3];
  int s = 0;
  scaled_edges(t, e, s);
  auto cross = [](const double* a, const double* b) {
    return Vec3d{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  const Vec3d c1 = cross(e[1], e[2]), c2 = cross(e[2], e[0]), c3 = cross(e[0], e[1]);
  const double det = e[0][0] * c1[0] + e[0][1] * c1[1] + e[0][2] * c1[2];
  std::array<Vec3d, 4> d;
  for (int c = 0; c < 3; ++c) {
    d[1][c] = std::ldexp(c1[c] / det, -s);
    d[2][c] = std::ldexp(c2[c] / det, -s);
    d[3][c] = std::ldexp(c3[c] / det, -s);
    d[0][c] = -(d[1][c] + d[2][c] + d[3][c]);
  }
  return d;
}

// The header's Qs in closed form. On an active set S = (S_A, S_B) with n_g = |S_g| (g = A, B),
// the free vertices of a tetrahedron share one displacement t = -D_g / (5 - n_g) (stationarity
// of (|t|^2 + (sum t)^2) / 20 in them, D_g = sum over S_g of d_k, d_k = c - s_k), which leaves
//     V_S = 1/20 sum_g [ sum_{k in S_g} d_k^2 + alpha_g D_g^2 ],   alpha_g = 1 / (5 - n_g),
// minimised over c at c = sum_g alpha_g sum_{S_g} s_k / W, W = sum_g alpha_g n_g. Its gradient
// in s is -(d_k + alpha_g D_g) / 10 (k in S_g; 0 off S), and differentiating once more
//     Qs_km = ( [k = m] + alpha_g [g(m) = g] - 5 alpha_g alpha_g(m) / W ) / 10   (k, m in S)
// and 0 in a row or column off S. qs_kkt (below) solves the KKT system instead: the
// tests hold the two equal on all 225 active sets. Symmetric bit for bit (a_k a_m = a_m a_k).
// PieceFactors holds the formula's factors (72 bytes, where the matrix takes 512): the energy
// keeps them per pair and evaluates an entry where the Hessian needs it, with the same
// operations as qs_closed (the same bits).
struct PieceFactors {
  std::array<double, 8> a{};            // alpha_g(k) on S, 0 off S
  double W = 0;                         // sum_g alpha_g n_g (0: S empty)
  std::array<std::uint8_t, 8> on{};     // S's indices, ascending: on[0 .. count)
  int count = 0;
  double entry(int k, int m) const {    // Qs_km, k and m in S (W > 0 there)
    const double same = (k / 4 == m / 4) ? a[k] : 0.0;
    return ((k == m ? 1.0 : 0.0) + same - 5 * (a[k] * a[m]) / W) / 10;
  }
};
PieceFactors piece_factors(const std::array<bool, 8>& active) {
  int n[2] = {0, 0};
  for (int k = 0; k < 8; ++k) n[k / 4] += active[k];
  const double alpha[2] = {1.0 / (5 - n[0]), 1.0 / (5 - n[1])};
  PieceFactors f;
  f.W = alpha[0] * n[0] + alpha[1] * n[1];
  for (int k = 0; k < 8; ++k) {
    f.a[k] = active[k] ? alpha[k / 4] : 0.0;
    if (active[k] && f.W > 0) f.on[f.count++] = std::uint8_t(k);
  }
  return f;
}
Eigen::Matrix<double, 8, 8> qs_closed(const std::array<bool, 8>& active) {
  const PieceFactors f = piece_factors(active);
  Eigen::Matrix<double, 8, 8> Qs = Eigen::Matrix<double, 8, 8>::Zero();
  for (int i = 0; i < f.count; ++i)
    for (int j = 0; j < f.count; ++j) Qs(f.on[i], f.on[j]) = f.entry(f.on[i], f.on[j]);
  return Qs;
}

// The KKT matrix of the fixed-plane QP's equality problem on the active set `active`: unknowns
// the eight moves x_k (A's vertices 0-3, B's 4-7), the plane offset c (index 8) and one
// multiplier per active vertex (9 + r, in vertex order); H = the object norm's blocks (2 on the
// diagonal, 1 off, over 10: definitions §2) on the moves, and the row x_k - c = -s_k of each
// active vertex k (its right side set by the caller).
Eigen::MatrixXd kkt_matrix(const std::array<bool, 8>& active) {
  int m = 0;
  for (bool a : active) m += a;
  const int n = 9 + m;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (int blk = 0; blk < 2; ++blk)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) K(4 * blk + i, 4 * blk + j) = (i == j ? 2.0 : 1.0) / 10;
  for (int k = 0, r = 0; k < 8; ++k) {
    if (!active[k]) continue;
    K(9 + r, k) = K(k, 9 + r) = 1;
    K(9 + r, 8) = K(8, 9 + r) = -1;
    ++r;
  }
  return K;
}

// The KKT solve of the header's "Hessian" for the active set `active` (not empty): the 8 x 8
// matrix Qs = S^T X^T H X S (fixed_plane's independent route).
Eigen::Matrix<double, 8, 8> qs_kkt(const std::array<bool, 8>& active) {
  const Eigen::MatrixXd K = kkt_matrix(active);
  const int m = int(K.rows()) - 9;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(K.rows(), m);
  for (int r = 0; r < m; ++r) rhs(9 + r, r) = 1;
  const Eigen::MatrixXd Z = K.partialPivLu().solve(rhs);
  const Eigen::MatrixXd X = Z.topRows(9);
  const Eigen::MatrixXd W = X.transpose() * K.topLeftCorner(9, 9) * X;  // X^T H X (m x m)
  Eigen::Matrix<double, 8, 8> Qs = Eigen::Matrix<double, 8, 8>::Zero();
  for (int i = 0, ri = 0; i < 8; ++i) {
    if (!active[i]) continue;
    for (int j = 0, rj = 0; j < 8; ++j) {
      if (!active[j]) continue;
      Qs(i, j) = 0.5 * (W(ri, rj) + W(rj, ri));
      ++rj;
    }
    ++ri;
  }
  return Qs;
}

// The eight heights along u relative to A's first vertex, s_k = u.(p_k - A[0]): every value of
// the header's "Hessian" is invariant under a common shift of the heights (Qs 1 = 0), and
// heights of differences carry rounding relative to the pair's extent, not to its distance from
// the origin.
std::array<double, 8> projections(const TetVertices& A, const TetVertices& B, const Vec3d& u) {
  auto height = [&](const Vec3d& p) {
    return u[0] * (p[0] - A[0][0]) + u[1] * (p[1] - A[0][1]) + u[2] * (p[2] - A[0][2]);
  };
  std::array<double, 8> s{};
  for (int i = 0; i < 4; ++i) {
    s[i] = height(A[i]);
    s[4 + i] = height(B[i]);
  }
  return s;
}

// The active set of V_u at the heights s (header, "Hessian"): the piece whose KKT conditions
// hold. With multipliers lambda (A's constraints) and mu (B's), stationarity gives t_A = -10
// (lambda - sum lambda / 5) and t_B = 10 (mu - sum mu / 5): a free vertex of A moves by
// 2 sum lambda, one of B by -2 sum mu. On S (d_k = c - s_k, D_g = sum over S_g of d_k,
// alpha_g = 1 / (5 - n_g)) that is 2 sum lambda = -alpha_A D_A and 2 sum mu = alpha_B D_B, and
// sum lambda = sum mu fixes c as piece_factors' comment has it. Then lambda_k >= 0 on S_A and
// feasibility off it read as one threshold: s_k >= c + alpha_A D_A on S_A and s_i <= it off
// S_A; for B, s_k <= c + alpha_B D_B on S_B and s_j >= it off S_B. So S_A is a top set of A's
// heights and S_B a bottom set of B's: the sixteen pieces (n_A, n_B) are tried, each with its
// largest violation of those inequalities (0 on the optimal piece, up to rounding), and the
// least violated is S (the first of equals, n_A then n_B ascending). No tolerance: a vertex
// off the plane at P by any fraction of a shallow contact's depth is off S (a tolerance
// relative to the pair's extent would count it on the plane and give a neighbouring piece's
// Hessian); within rounding of a kink of V_u either piece is a one-sided Hessian.
std::array<bool, 8> fixed_plane_active_set(const std::array<double, 8>& s) {
  int a[4] = {0, 1, 2, 3}, b[4] = {4, 5, 6, 7};  // A's by height descending, B's ascending
  std::stable_sort(a, a + 4, [&s](int x, int y) { return s[x] > s[y]; });
  std::stable_sort(b, b + 4, [&s](int x, int y) { return s[x] < s[y]; });
  double best = std::numeric_limits<double>::infinity();
  int best_a = 4, best_b = 4;
  double sum_a = 0;
  for (int na = 1; na <= 4; ++na) {
    sum_a += s[a[na - 1]];
    double sum_b = 0;
    for (int nb = 1; nb <= 4; ++nb) {
      sum_b += s[b[nb - 1]];
      const double alpha_a = 1.0 / (5 - na), alpha_b = 1.0 / (5 - nb);
      const double c = (alpha_a * sum_a + alpha_b * sum_b) / (alpha_a * na + alpha_b * nb);
      const double top = c + alpha_a * (na * c - sum_a), bottom = c + alpha_b * (nb * c - sum_b);
      double v = std::max(top - s[a[na - 1]], s[b[nb - 1]] - bottom);
      if (na < 4) v = std::max(v, s[a[na]] - top);
      if (nb < 4) v = std::max(v, bottom - s[b[nb]]);
      if (v < best) best = v, best_a = na, best_b = nb;
    }
  }
  std::array<bool, 8> active{};
  for (int k = 0; k < best_a; ++k) active[a[k]] = true;
  for (int k = 0; k < best_b; ++k) active[b[k]] = true;
  return active;
}

Vec3d unit(const Vec3d& n) {
  const double l = std::sqrt(dot(n, n));
  if (!(l > 0) || !std::isfinite(l)) throw std::invalid_argument("contact_energy: null or non-finite normal");
  return {n[0] / l, n[1] / l, n[2] / l};
}

// pdd2_global gradient -d sigma / d d at d = q - p, per tetrahedron (header, "Gradient").
void object_norm_gradient(const TetVertices& p, const TetVertices& q, Vec3d* g) {
  Vec3d sum{0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) sum[k] += q[i][k] - p[i][k];
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) g[i][k] = -((q[i][k] - p[i][k]) + sum[k]) / 10;
}

// pair_terms (header) without Qs and the piece's value: the gradient, u and the active set S.
PairTerms plane_terms(const TetVertices& A, const TetVertices& B, const TetVertices& qA,
                      const TetVertices& qB, const Vec3d& normal) {
  PairTerms t;
  object_norm_gradient(A, qA, t.gradient.data());
  object_norm_gradient(B, qB, t.gradient.data() + 4);
  const Vec3d u = unit(normal);
  t.unit_normal = u;
  t.active = fixed_plane_active_set(projections(A, B, u));
  return t;
}

// One intersecting pair as the energy needs it: the positions attaining pdd2_global and the
// normal, from either engine (rounded to double for the exact one).
struct PairSolution {
  std::size_t a = 0, b = 0;
  double value = 0;
  TetVertices qA{}, qB{};
  Vec3d normal{};
  // fast::global_minimiser's `bounded` (a contact made by rounding, not certified): value is
  // its estimate, `upper` a certified upper bound on its pdd2_global (settle_bounded below)
  bool bounded = false;
  double upper = 0;
};

template <class R>
double to_double(const R& x) {
  if constexpr (std::is_same_v<R, double>) return x;
  else return x.get_d();
}

// The exact engine's normal as doubles. Its witness has no fixed length, and a pair whose
// depth is far below its extent gets components outside the double range (numerators of ~800
// bits: get_d gives inf or 0); so the three are first scaled exactly by one power of two
// that brings the largest magnitude into (1/2, 2) (bit lengths of numerator and denominator
// bound log2 |x| within 1), then converted (mpq_get_d: truncated, relative error < 2^-52). The
// direction is the witness's to that error (a component that underflows is below 2^-1000 of the
// largest).
Vec3d rounded_direction(const std::array<Rational, 3>& n) {
  long e = 0;
  bool any = false;
  for (const Rational& x : n) {
    if (sgn(x) == 0) continue;
    const long b = long(mpz_sizeinbase(x.get_num_mpz_t(), 2)) - long(mpz_sizeinbase(x.get_den_mpz_t(), 2));
    e = any ? std::max(e, b) : b;
    any = true;
  }
  Vec3d out{0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    Rational q = n[k];
    if (e > 0) mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(e));
    if (e < 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(-e));
    out[k] = q.get_d();
  }
  return out;
}
Vec3d rounded_direction(const std::array<double, 3>& n) { return n; }

template <class R>
PairSolution solution_of(std::size_t a, std::size_t b, const PairResult<R>& r) {
  PairSolution s;
  s.a = a;
  s.b = b;
  s.value = to_double(r.pdd2_global);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      s.qA[i][k] = to_double(r.q1_A_global[i][k]);
      s.qB[i][k] = to_double(r.q1_B_global[i][k]);
    }
  s.normal = rounded_direction(*r.pdd2_global_normal);
  return s;
}

void check_positions(const Mesh& m, const std::vector<Vec3d>& p, const char* which) {
  if (p.size() != m.vertices.size())
    throw std::invalid_argument(std::string("contact_energy: positions of mesh ") + which + " have " +
                                std::to_string(p.size()) + " entries, the mesh has " +
                                std::to_string(m.vertices.size()) + " vertices");
}

// Positions p (as many as m's vertices) that are m's vertices bit for bit: m itself is the mesh
// at p, with nothing to copy (two meshes of 10^5 elements: ~8 MB of indices otherwise).
bool at_rest(const Mesh& m, const std::vector<Vec3d>& p) {
  static_assert(sizeof(Vec3d) == 3 * sizeof(double));
  return p.empty() || p.data() == m.vertices.data() ||
         std::memcmp(p.data(), m.vertices.data(), p.size() * sizeof(Vec3d)) == 0;
}

// m with p as its vertices (its arrays copied side by side).
Mesh at_positions(const Mesh& m, const std::vector<Vec3d>& p) {
  Mesh out;
  tbb::parallel_invoke(
      [&] {
        out.vertices = p;
        out.vertex_sources = m.vertex_sources;  // messages name a non-finite vertex where it was read
      },
      [&] { out.tets = m.tets; }, [&] { out.source_ids = m.source_ids; });
  return out;
}

// One pair's global minimiser by the fast engine: fast::global_minimiser (solve_pair's
// definitions §9 fields alone, bit for bit), else the whole solve_pair where that declines, else
// (pdd2_global declined: no certified normal in doubles) the exact engine's witness. With
// `bound` (MinimiserOptions::bound_shallow), a contact made by rounding is returned bounded.
// Through `memo` (translation_memo.h: pairs equal up to translation computed once, the same bits).
PairSolution fast_solution(std::size_t a, std::size_t b, const TetVertices& Ta, const TetVertices& Tb,
                           detail::TranslationMemo<std::optional<fast::GlobalMinimiser>>& memo, bool bound) {
  fast::MinimiserOptions mo;
  mo.bound_shallow = bound;
  const auto minimiser = [&mo](const TetVertices& x, const TetVertices& y) { return fast::global_minimiser(x, y, mo); };
  const auto move = [](std::optional<fast::GlobalMinimiser>& g, const fast::AnchoredPair& m, const TetVertices& x,
                       const TetVertices& y) { return !g || fast::move_positions(*g, m, x, y); };
  if (const auto m = memo.get(Ta, Tb, minimiser, move)) {
    PairSolution s;
    s.a = a;
    s.b = b;
    s.value = m->pd2;
    s.qA = m->q1_A;
    s.qB = m->q1_B;
    s.normal = m->normal;
    s.bounded = m->bounded;
    s.upper = m->upper;
    return s;
  }
  fast::SolveOptions fo;
  fo.with_global = true;
  fo.values = kRigid;  // definitions §9's fields alone are read (the same bits: solve_options.h)
  const PairResult<double> r = fast::solve_pair(TetPair{"", {}, Ta, Tb}, fo);
  if (!r.error && !r.pdd2_global_error) return solution_of(a, b, r);
  reference::SolveOptions so;
  return solution_of(a, b, reference::solve_pair(TetPair{"", {}, Ta, Tb}, so));
}

// The intersecting pairs at the current positions (definitions §10's decision, no variant),
// each with its global minimiser (contacts made by rounding bounded unless options.per_pair asks
// for every pair's value: settle_bounded); `seconds_found`: the time to find them.
std::vector<PairSolution> solutions(const Mesh& A, const Mesh* B, const ContactEnergyOptions& o,
                                    std::vector<SkippedElement>& skipped, double& seconds_found) {
  const auto t0 = Clock::now();
  const auto cancelled = [&] { return o.cancel && o.cancel->load(std::memory_order_relaxed); };
  ContactOptions co;
  co.cancel = o.cancel;
  std::vector<PairSolution> out;
  if (o.engine == EnergyEngine::Exact) {
    co.variants = kGlobal;
    const Contacts<Rational> c = B ? contacts_exact(A, *B, co) : contacts_exact_self(A, co);
    skipped = c.skipped;
    for (const auto& k : c.pairs) out.push_back(solution_of(k.a, k.b, k.result));
    seconds_found = seconds_since(t0);
    return out;
  }
  co.variants = 0;  // the pairs only (contacts(): an intersecting pair's record is then empty)
  const Contacts<double> c = B ? contacts(A, *B, co) : contacts_self(A, co);
  skipped = c.skipped;
  seconds_found = seconds_since(t0);
  const Mesh& Bm = B ? *B : A;
  out.resize(c.pairs.size());
  detail::TranslationMemo<std::optional<fast::GlobalMinimiser>> memo;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, c.pairs.size(), 16),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      if (cancelled()) return;
                      for (std::size_t j = range.begin(); j != range.end(); ++j) {
                        const auto& k = c.pairs[j];
                        out[j] = fast_solution(k.a, k.b, element(A, k.a), element(Bm, k.b), memo, !o.per_pair);
                      }
                    });
  if (cancelled()) throw Cancelled();
  return out;
}

// One kept pair's share: its eight vertices (A's, then B's, as gradient rows), weight,
// gradient of pdd2_global, u and Qs as its factors (pair_terms' values without the matrix).
struct PairShare {
  std::array<std::size_t, 8> v{};
  double w = 0;
  std::array<Vec3d, 8> gradient{};
  Vec3d u{};
  PieceFactors qs;
  // Row i of w Qs: bit k set where w Qs_ik != 0 (k in S; i off S: none), for the Hessian.
  std::array<std::uint8_t, 8> row{};
};

// The kept pairs' shares, in storage that the parallel loop filling them constructs them in (a
// vector would first value-initialise every share on one thread, ~0.4 KB a pair: the largest
// serial step of the assembly). A share holds plain numbers: nothing to destroy.
static_assert(std::is_trivially_destructible_v<PairShare>);
class ShareArray {
 public:
  explicit ShareArray(std::size_t count) : count_(count), p_(std::allocator<PairShare>().allocate(count)) {}
  ~ShareArray() { std::allocator<PairShare>().deallocate(p_, count_); }
  ShareArray(const ShareArray&) = delete;
  ShareArray& operator=(const ShareArray&) = delete;
  PairShare& construct(std::size_t j) { return *new (p_ + j) PairShare; }
  const PairShare& operator[](std::size_t j) const { return p_[j]; }
  std::size_t size() const { return count_; }

 private:
  std::size_t count_;
  PairShare* p_;
};

// The pairs incident to each vertex, in pair order (CSR: pairs of vertex x are
// at[start[x] .. start[x + 1]), each as 8 * pair + local index): every per-vertex sum below
// runs over them in that order, so that the gradient and the Hessian are the sums over pairs
// in pair order, independent of the threads, and entries (v, x) and (x, v) are the same sum.
struct Incidence {
  std::vector<std::size_t> start, at;
};
// `vertices(j)`: pair j's eight vertices (A's, then B's, as gradient rows), j < pairs.
template <class Vertices>
Incidence incidence(std::size_t pairs, std::size_t n, const Vertices& vertices) {
  Incidence inc;
  inc.start.assign(n + 1, 0);
  for (std::size_t j = 0; j < pairs; ++j)
    for (std::size_t x : vertices(j)) ++inc.start[x + 1];
  for (std::size_t x = 0; x < n; ++x) inc.start[x + 1] += inc.start[x];
  inc.at.resize(8 * pairs);
  std::vector<std::size_t> fill(inc.start.begin(), inc.start.end() - 1);
  for (std::size_t j = 0; j < pairs; ++j) {
    const std::array<std::size_t, 8> v = vertices(j);
    for (int i = 0; i < 8; ++i) inc.at[fill[v[i]]++] = 8 * j + i;
  }
  return inc;
}

// Each thread's view of the vertices while it builds rows (hessian() below): stamp[y] equals the
// row's stamp when y is already a neighbour of the row vertex, and then slot[y] is y's place
// among its neighbours. Each row of each pass has its own non-zero stamp, so nothing is cleared
// between rows.
struct RowScratch {
  explicit RowScratch(std::size_t n) : stamp(n, 0), slot(n, 0) {}
  std::vector<std::size_t> stamp, slot, ys;
  std::vector<double> block;
};

// The vertices sharing a pair with x through a non-zero Qs entry, each once, in first-seen
// order (ys); marks them in `s` with `stamp`.
void neighbours(const ShareArray& shares, const Incidence& inc, std::size_t x, std::size_t stamp,
                RowScratch& s) {
  s.ys.clear();
  for (std::size_t e = inc.start[x]; e < inc.start[x + 1]; ++e) {
    const PairShare& p = shares[inc.at[e] / 8];
    for (unsigned bits = p.row[inc.at[e] % 8]; bits != 0; bits &= bits - 1) {
      const std::size_t y = p.v[__builtin_ctz(bits)];
      if (s.stamp[y] != stamp) {
        s.stamp[y] = stamp;
        s.ys.push_back(y);
      }
    }
  }
}

// The sparse Hessian sum over pairs of w Qs (x) u u^T, built row by row in parallel: vertex x's
// rows 3x..3x+2 hold a 3x3 block per vertex y sharing a pair with x through a non-zero Qs entry
// (y ascending), each entry summed over the pairs in pair order (starting from 0). The matrix is
// symmetric bit for bit (Qs is, u_a u_b = u_b u_a, the same pairs in the same order), so its
// compressed rows are its compressed columns: written straight into the column-major storage.
// Each thread keeps a stamp and a slot per vertex (RowScratch): a neighbour is found once, with
// no sort of the repeated entries and no search per term.
Eigen::SparseMatrix<double> hessian(const ShareArray& shares, const Incidence& inc,
                                    std::size_t n) {
  tbb::enumerable_thread_specific<RowScratch> scratch([n] { return RowScratch(n); });
  std::vector<std::size_t> degree(n + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const tbb::blocked_range<std::size_t>& r) {
    RowScratch& s = scratch.local();
    for (std::size_t x = r.begin(); x != r.end(); ++x) {
      neighbours(shares, inc, x, x + 1, s);
      degree[x + 1] = s.ys.size();
    }
  });
  for (std::size_t x = 0; x < n; ++x) degree[x + 1] += degree[x];  // blocks before vertex x
  using Index = Eigen::SparseMatrix<double>::StorageIndex;
  if (9 * degree[n] > std::size_t(std::numeric_limits<Index>::max()) ||
      3 * n > std::size_t(std::numeric_limits<Index>::max()))
    throw std::length_error("contact_energy: the Hessian has more entries than Eigen's index type holds");
  Eigen::SparseMatrix<double> H(Eigen::Index(3 * n), Eigen::Index(3 * n));
  H.resizeNonZeros(Eigen::Index(9 * degree[n]));
  Index* outer = H.outerIndexPtr();
  Index* inner = H.innerIndexPtr();
  double* value = H.valuePtr();
  // The second pass stamps with n + 1 + x (the first pass's stamps are x + 1 <= n).
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const tbb::blocked_range<std::size_t>& r) {
    RowScratch& s = scratch.local();
    for (std::size_t x = r.begin(); x != r.end(); ++x) {
      neighbours(shares, inc, x, n + 1 + x, s);
      std::vector<std::size_t>& ys = s.ys;
      std::sort(ys.begin(), ys.end());
      const std::size_t m = ys.size();
      for (std::size_t c = 0; c < m; ++c) s.slot[ys[c]] = c;
      s.block.assign(9 * m, 0.0);
      for (std::size_t e = inc.start[x]; e < inc.start[x + 1]; ++e) {
        const PairShare& p = shares[inc.at[e] / 8];
        const int i = int(inc.at[e] % 8);
        if (p.row[i] == 0) continue;
        double uu[9];
        for (int a = 0; a < 3; ++a)
          for (int c = 0; c < 3; ++c) uu[3 * a + c] = p.u[a] * p.u[c];
        for (unsigned bits = p.row[i]; bits != 0; bits &= bits - 1) {
          const int k = __builtin_ctz(bits);
          const double q = p.w * p.qs.entry(i, k);
          double* b = s.block.data() + 9 * s.slot[p.v[k]];
          for (int c = 0; c < 9; ++c) b[c] += q * uu[c];
        }
      }
      // rows 3x + a: for each neighbour y (ascending), columns 3y, 3y + 1, 3y + 2
      for (int a = 0; a < 3; ++a) {
        const std::size_t row = 3 * x + a, first = 9 * degree[x] + 3 * m * a;
        outer[row] = Index(first);
        for (std::size_t c = 0; c < m; ++c)
          for (int b = 0; b < 3; ++b) {
            inner[first + 3 * c + b] = Index(3 * ys[c] + b);
            value[first + 3 * c + b] = s.block[9 * c + 3 * a + b];
          }
      }
    }
  });
  outer[3 * n] = Index(9 * degree[n]);
  return H;
}

// The bounded pairs' share of E (fast engine: a contact made by rounding, ~1e-17 of its elements
// deep, whose certificate takes the shallow certificate or the exact pieces: tens of
// microseconds to milliseconds a pair, where its term is ~1e-30 of a real overlap's). Each
// bounded pair's term w * value lies in (0, w * upper] (its exact pdd2_global is > 0: the pair
// intersects). Kept bounded: the pairs of least w * upper while their bounds sum to at most
// kBoundedShare of the certified terms' sum (so E is within kBoundedShare of the sum of exact
// terms beyond what the certified terms' own definitions §8 error allows), and none whose upper
// bound reaches the largest certified pdd2_global (max_pdd2_global stays a certified value).
// Every other bounded pair is computed in full (fast_solution without `bound`: certified or a
// witness, as without bounds). Where no pair is certified (blocks resting on each other by
// rounding alone: E is made of such terms) every pair is computed in full.
constexpr double kBoundedShare = 1e-12;

// Returns the pairs kept bounded.
std::size_t settle_bounded(std::vector<PairSolution>& sol, const std::vector<double>& weight, const Mesh& A,
                           const Mesh& Bm, const ContactEnergyOptions& o) {
  double certified = 0, largest = 0;
  std::vector<std::size_t> bounded;
  for (std::size_t j = 0; j < sol.size(); ++j) {
    if (sol[j].bounded) {
      bounded.push_back(j);
    } else {
      certified += weight[j] * sol[j].value;
      largest = std::max(largest, sol[j].value);
    }
  }
  if (bounded.empty()) return 0;
  // least w * upper first, each kept while the sum stays within the share (and its bound below
  // the largest certified value)
  std::stable_sort(bounded.begin(), bounded.end(), [&](std::size_t x, std::size_t y) {
    return weight[x] * sol[x].upper < weight[y] * sol[y].upper;
  });
  const double share = kBoundedShare * certified * (1 - 1e-6);  // (the sums' rounding: < 1e-6 of them)
  double kept = 0;
  std::vector<std::size_t> full;
  for (std::size_t j : bounded) {
    const double term = weight[j] * sol[j].upper;
    if (kept + term <= share && sol[j].upper < largest) kept += term;
    else full.push_back(j);
  }
  detail::TranslationMemo<std::optional<fast::GlobalMinimiser>> memo;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, full.size(), 4), [&](const tbb::blocked_range<std::size_t>& r) {
    if (o.cancel && o.cancel->load(std::memory_order_relaxed)) return;
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      PairSolution& s = sol[full[i]];
      s = fast_solution(s.a, s.b, element(A, s.a), element(Bm, s.b), memo, false);
    }
  });
  if (o.cancel && o.cancel->load()) throw Cancelled();
  return bounded.size() - full.size();
}

// p's gradient rows first..first + 3 (one element's) += value / 3 times d (its dV/dx / V).
void add_weight_derivative(PairShare& p, int first, const std::array<Vec3d, 4>& d, double value) {
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) p.gradient[first + i][c] += value / 3 * d[i][c];
}

ContactEnergy run(const Mesh& A, const Mesh* B, const std::vector<Vec3d>& pa,
                  const std::vector<Vec3d>* pb, const ContactEnergyOptions& o) {
  const auto t0 = Clock::now();
  check_positions(A, pa, "A");
  if (B) check_positions(*B, *pb, "B");
  std::optional<Mesh> copy_a, copy_b;  // the meshes at the positions, where not at rest
  tbb::parallel_invoke([&] { if (!at_rest(A, pa)) copy_a = at_positions(A, pa); },
                       [&] { if (B && !at_rest(*B, *pb)) copy_b = at_positions(*B, *pb); });
  const Mesh& Ap = copy_a ? *copy_a : A;
  const Mesh* Bp = B ? (copy_b ? &*copy_b : B) : nullptr;
  ContactEnergy e;
  std::vector<PairSolution> sol = solutions(Ap, Bp, o, e.skipped, e.seconds_found);
  e.seconds_contacts = seconds_since(t0);
  const auto t1 = Clock::now();

  const Mesh& Bm = B ? *B : A;
  const Mesh& Bpm = B ? *Bp : Ap;
  const std::size_t nA = A.vertices.size();
  const std::size_t n = nA + (B ? B->vertices.size() : 0);
  const std::size_t offset_b = B ? nA : 0;

  // Weights from the rest volumes' cube roots (each pair's two, in parallel); an element flat at
  // rest has no weight: listed once (per side, in pair order), its pairs left out. (With
  // weights_follow_a / _b, that side's positions are its rest.)
  const bool follow_a = o.weights_follow_a, follow_b = B ? o.weights_follow_b : o.weights_follow_a;
  const Mesh& weighted_a = follow_a ? Ap : A;
  const Mesh& weighted_b = follow_b ? Bpm : Bm;
  std::vector<std::array<double, 2>> volume(sol.size());  // the two cube roots
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sol.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j)
      volume[j] = {rest_volume_root(weighted_a, sol[j].a), rest_volume_root(weighted_b, sol[j].b)};
  });
  // No weight: flat at rest, or a rest volume that is not finite (a non-finite rest coordinate,
  // or an edge vector that overflows).
  const auto unweighted = [](double w) { return w == 0 || !std::isfinite(w); };
  std::unordered_set<std::size_t> listed[2];  // the elements listed, per side (rare)
  // A rest shape given with a non-finite coordinate is bad input wherever it lies: every element
  // using such a vertex is listed first, in element order, whether or not it is in a pair now (its
  // pairs, later, have no weight). (A side whose weights follow its positions has no rest shape
  // of its own: contacts() lists the positions' non-finite coordinates.)
  auto list_non_finite_rest = [&](const Mesh& rest, int side, char which) {
    std::vector<char> bad(rest.vertices.size(), 0);
    bool any = false;
    for (std::size_t v = 0; v < rest.vertices.size(); ++v)
      for (double c : rest.vertices[v])
        if (!std::isfinite(c)) bad[v] = 1, any = true;
    if (!any) return;
    for (std::size_t i = 0; i < rest.tets.size(); ++i) {
      const auto& t = rest.tets[i];
      if (!(bad[t[0]] || bad[t[1]] || bad[t[2]] || bad[t[3]])) continue;
      listed[side].insert(i);
      e.skipped.push_back({which, i, *element_problem(rest, i, which) + " at rest: it has no contact weight"});
    }
  };
  const int side_b = B ? 1 : 0;  // (self-contact: one mesh, one list)
  if (!follow_a) list_non_finite_rest(weighted_a, 0, 'A');
  if (B && !follow_b) list_non_finite_rest(weighted_b, 1, 'B');
  auto list_unweighted = [&](double w, int side, const Mesh& rest, std::size_t i, char which) {
    if (!unweighted(w) || !listed[side].insert(i).second) return;
    const std::string element_i = "element " + std::to_string(i) + " of mesh " + which;
    std::string why = element_i + " is flat at rest (volume 0): it has no contact weight";
    if (!std::isfinite(w)) {
      const auto problem = element_problem(rest, i, which);
      why = (problem ? *problem + " at rest" : element_i + ": an edge at rest exceeds the double range") +
            ": it has no contact weight";
    }
    e.skipped.push_back({which, i, why});
  };
  std::size_t kept = 0;  // the weighted pairs, moved to the front in pair order
  for (std::size_t j = 0; j < sol.size(); ++j) {
    list_unweighted(volume[j][0], 0, weighted_a, sol[j].a, 'A');
    list_unweighted(volume[j][1], side_b, weighted_b, sol[j].b, B ? 'B' : 'A');
    if (unweighted(volume[j][0]) || unweighted(volume[j][1])) continue;
    if (kept != j) sol[kept] = sol[j], volume[kept] = volume[j];
    ++kept;
  }
  sol.resize(kept);
  volume.resize(kept);
  double seconds_settled = 0;  // (pairs computed again in full: seconds_contacts' share)
  {
    const auto ts = Clock::now();
    std::vector<double> weight(kept);
    for (std::size_t j = 0; j < kept; ++j) weight[j] = o.weight == EnergyWeight::Unit ? 1.0 : volume[j][0] * volume[j][1];
    e.bounded_pairs = settle_bounded(sol, weight, Ap, Bpm, o);
    seconds_settled = seconds_since(ts);
    e.seconds_contacts += seconds_settled;
  }

  const auto vertices = [&](std::size_t j) {
    std::array<std::size_t, 8> v;
    for (int k = 0; k < 4; ++k) {
      v[k] = A.tets[sol[j].a][k];
      v[4 + k] = offset_b + Bm.tets[sol[j].b][k];
    }
    return v;
  };
  ShareArray shares(sol.size());
  Incidence inc;  // (serial: built by one task while the others fill the shares)
  tbb::parallel_invoke([&] { inc = incidence(sol.size(), n, vertices); }, [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sol.size(), 64), [&](const tbb::blocked_range<std::size_t>& r) {
      if (o.cancel && o.cancel->load(std::memory_order_relaxed)) return;
      for (std::size_t j = r.begin(); j != r.end(); ++j) {
        const auto& s = sol[j];
        PairShare& p = shares.construct(j);
        p.v = vertices(j);
        p.w = o.weight == EnergyWeight::Unit ? 1.0 : volume[j][0] * volume[j][1];
        const PairTerms t = plane_terms(element(Ap, s.a), element(Bpm, s.b), s.qA, s.qB, s.normal);
        p.gradient = t.gradient;
        if (o.weight == EnergyWeight::Area) {
          // + pdd2_global dw/dx on a side that follows, as w times pdd2_global / 3 dV/dx / V
          // (the assembly's factor w)
          if (follow_a) add_weight_derivative(p, 0, volume_log_derivative(element(Ap, s.a)), s.value);
          if (follow_b) add_weight_derivative(p, 4, volume_log_derivative(element(Bpm, s.b)), s.value);
        }
        p.u = t.unit_normal;
        p.qs = piece_factors(t.active);
        for (int a = 0; a < p.qs.count; ++a)
          for (int c = 0; c < p.qs.count; ++c) {
            const int i = p.qs.on[a], k = p.qs.on[c];
            if (p.w * p.qs.entry(i, k) != 0) p.row[i] |= std::uint8_t(1u << k);
          }
      }
    });
  });
  if (o.cancel && o.cancel->load()) throw Cancelled();

  e.pair_count = sol.size();
  for (std::size_t j = 0; j < sol.size(); ++j) {  // in pair order (one sum, its order fixed)
    const auto& s = sol[j];
    const double term = shares[j].w * s.value;
    // Every term is > 0 (a weight and an intersecting pair's value, normal doubles); one below
    // the normal range (E ~ L^4: coordinates below ~1e-67) has lost its relative accuracy, and
    // an energy made of such terms would read as 0, "nothing intersects".
    if (!(term >= std::numeric_limits<double>::min()))
      throw std::underflow_error("contact_energy: the energy is below the double range (pair (" +
                                 std::to_string(s.a) + ", " + std::to_string(s.b) + "): weight " + to_text(shares[j].w) +
                                 " times pdd2_global " + to_text(s.value) + "): scale the positions up");
    e.energy += term;
    e.max_pdd2_global = std::max(e.max_pdd2_global, s.value);
    if (o.per_pair) e.pairs.push_back({s.a, s.b, shares[j].w, s.value, shares[j].w * s.value});
  }
  // Every weight and value is a normal double (or 0); their sum E ~ L^4 leaves the double range
  // for coordinates beyond ~1e77, where no double can report it.
  if (!std::isfinite(e.energy))
    throw std::overflow_error("contact_energy: the energy exceeds the double range (" + std::to_string(sol.size()) +
                              " pairs, largest pdd2_global " + to_text(e.max_pdd2_global) +
                              "): scale the positions down");
  e.gradient.assign(n, Vec3d{0, 0, 0});
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t x = r.begin(); x != r.end(); ++x)
      for (std::size_t k = inc.start[x]; k < inc.start[x + 1]; ++k) {
        const PairShare& p = shares[inc.at[k] / 8];
        const Vec3d& g = p.gradient[inc.at[k] % 8];
        for (int c = 0; c < 3; ++c) e.gradient[x][c] += p.w * g[c];
      }
  });
  if (o.hessian) {
    // swapped in: Eigen 3.4's SparseMatrix has no move assignment (`=` would copy the arrays)
    Eigen::SparseMatrix<double> H = hessian(shares, inc, n);
    e.hessian.swap(H);
  }
  e.seconds_assembly = seconds_since(t1) - seconds_settled;
  return e;
}

}  // namespace

PairTerms pair_terms(const TetVertices& A, const TetVertices& B, const TetVertices& qA,
                     const TetVertices& qB, const Vec3d& normal) {
  PairTerms t = plane_terms(A, B, qA, qB, normal);
  bool any = false;
  for (bool a : t.active) any = any || a;
  if (!any) return t;  // not reached for an intersecting pair (both sides touch the plane)
  const std::array<double, 8> s = projections(A, B, t.unit_normal);
  const Eigen::Matrix<double, 8, 8> Qs = qs_closed(t.active);
  Eigen::Matrix<double, 8, 1> sv;
  for (int i = 0; i < 8; ++i) sv[i] = s[i];
  t.piece_value = 0.5 * sv.dot(Qs * sv);
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 8; ++k) t.qs[i][k] = Qs(i, k);
  return t;
}

FixedPlane fixed_plane(const TetVertices& A, const TetVertices& B, const Vec3d& normal) {
  const Vec3d u = unit(normal);
  const std::array<double, 8> s = projections(A, B, u);
  FixedPlane best;
  double maxA = std::max({s[0], s[1], s[2], s[3]}), minB = std::min({s[4], s[5], s[6], s[7]});
  if (maxA <= minB) return best;  // t = 0 is feasible: value 0
  best.value = std::numeric_limits<double>::infinity();
  Eigen::Matrix<double, 8, 1> sv;
  for (int i = 0; i < 8; ++i) sv[i] = s[i];
  for (unsigned mask = 1; mask < 256; ++mask) {
    std::array<bool, 8> active{};
    for (int k = 0; k < 8; ++k) active[k] = (mask >> k) & 1u;
    // The equality QP's solution x = (t, c) for this set: solve the KKT system directly.
    const Eigen::MatrixXd K = kkt_matrix(active);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(K.rows());
    for (int k = 0, r = 0; k < 8; ++k)
      if (active[k]) rhs(9 + r++) = -s[k];
    const Eigen::VectorXd x = K.partialPivLu().solve(rhs);
    // Feasible: every constraint holds (to rounding relative to the pair's spread).
    const double spread = std::max(std::abs(maxA), std::abs(minB)) + (maxA - minB);
    bool feasible = true;
    for (int k = 0; k < 8 && feasible; ++k) {
      const double slack = k < 4 ? x[8] - (s[k] + x[k]) : (s[k] + x[k]) - x[8];
      feasible = slack >= -1e-12 * spread;
    }
    if (!feasible) continue;
    const double value = 0.5 * x.head(8).dot(K.topLeftCorner(8, 8) * x.head(8));
    if (value < best.value) {
      best.value = value;
      const Eigen::Matrix<double, 8, 8> Qs = qs_kkt(active);
      const Eigen::Matrix<double, 8, 1> g = Qs * sv;
      for (int k = 0; k < 8; ++k)
        for (int c = 0; c < 3; ++c) best.gradient[k][c] = g[k] * u[c];
    }
  }
  return best;
}

namespace {
std::array<std::array<double, 8>, 8> to_array(const Eigen::Matrix<double, 8, 8>& m) {
  std::array<std::array<double, 8>, 8> out{};
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 8; ++k) out[i][k] = m(i, k);
  return out;
}
}  // namespace

std::array<std::array<double, 8>, 8> piece_matrix(const std::array<bool, 8>& active) {
  return to_array(qs_closed(active));
}
std::array<std::array<double, 8>, 8> piece_matrix_kkt(const std::array<bool, 8>& active) {
  return to_array(qs_kkt(active));
}

ContactEnergy contact_energy(const Mesh& A, const Mesh& B, const std::vector<Vec3d>& pa,
                             const std::vector<Vec3d>& pb, const ContactEnergyOptions& options) {
  return run(A, &B, pa, &pb, options);
}

ContactEnergy contact_energy_self(const Mesh& A, const std::vector<Vec3d>& pa,
                                  const ContactEnergyOptions& options) {
  return run(A, nullptr, pa, nullptr, options);
}

}  // namespace pdd::mesh
