// fast_direction_qp_test — the closed-form per-direction QP (direction_qp.h) against an
// independent method: exhaustive active-set enumeration with dense KKT solves (Eigen).
//
// Dense problem (n-scaled units, header of direction_qp.h): variables z = (T_A[4], T_B[4], C),
// cost F = T_A'(I+J)T_A + T_B'(I+J)T_B, rows  T_i − C = −H_i  (constrained), T_i − C <= −H_i
// (free in A), −(T_j − C) <= H_j (free in B); case 1 adds T_A = 0; relaxed makes every row an
// inequality. For every subset of inequality rows taken as equalities, the equality QP is solved
// by its KKT system when that is nonsingular; the minimum over the primal-feasible solutions is
// the QP optimum (the optimum solves the equality QP of its own active set, and every feasible
// point costs at least the optimum). 2^(#inequalities) <= 256 subsets.
//
// Tolerance: heights are O(10), F = O(10³); the closed form does O(10) flops per quantity and
// the 9..17-dimensional LU solve is backward stable with growth O(10), so both carry relative
// errors ~1e-13. We require agreement to 1e-9 relative (+1e-9 absolute for F near 0): four
// orders of margin, while any wrong active set changes F by O(1) on these instances.
#define BOOST_TEST_MODULE fast_direction_qp
#include <Eigen/Dense>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "pdd/compare/random.h"
#include "qp/direction_qp.h"

using namespace pdd::fast;

namespace {

enum class Mode { Deformable, Static, Relaxed };

struct Row {
  int var;     // index of T (0..7)
  double sgn;  // +1: T − C <= −H (A side), −1: −(T − C) <= H (B side)
  double H;
  bool equality;
};

std::vector<Row> rows_of(const SideProblem& A, const SideProblem& B, Mode mode) {
  std::vector<Row> rows;
  auto add = [&](const SideProblem& s, int base, double sgn) {
    int v = base;
    for (int i = 0; i < s.ncon; ++i) rows.push_back({v++, sgn, s.hcon, mode != Mode::Relaxed});
    for (int i = 0; i < s.nfree; ++i) rows.push_back({v++, sgn, s.hfree[i], false});
  };
  add(A, 0, 1.0);
  add(B, 4, -1.0);
  return rows;
}

// Dense optimum of F; +inf if no feasible equality-QP solution was found.
double dense_optimum(const SideProblem& A, const SideProblem& B, Mode mode) {
  const std::vector<Row> rows = rows_of(A, B, mode);
  std::vector<int> ineq;
  for (int r = 0; r < int(rows.size()); ++r)
    if (!rows[r].equality) ineq.push_back(r);
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(9, 9);
  for (int b = 0; b < 2; ++b)
    Q.block(4 * b, 4 * b, 4, 4) = 2.0 * (Eigen::MatrixXd::Identity(4, 4) +
                                         Eigen::MatrixXd::Ones(4, 4));
  double best = std::numeric_limits<double>::infinity();
  for (unsigned mask = 0; mask < (1u << ineq.size()); ++mask) {
    std::vector<Eigen::VectorXd> E;
    std::vector<double> rhs;
    for (int r = 0; r < int(rows.size()); ++r) {
      bool active = rows[r].equality;
      for (size_t k = 0; k < ineq.size(); ++k)
        if (ineq[k] == r && (mask >> k & 1u)) active = true;
      if (!active) continue;
      Eigen::VectorXd e = Eigen::VectorXd::Zero(9);
      e(rows[r].var) = 1.0;
      e(8) = -1.0;
      E.push_back(e);
      rhs.push_back(-rows[r].H);
    }
    if (mode == Mode::Static)
      for (int i = 0; i < 4; ++i) {
        Eigen::VectorXd e = Eigen::VectorXd::Zero(9);
        e(i) = 1.0;
        E.push_back(e);
        rhs.push_back(0.0);
      }
    const int m = int(E.size()), N = 9 + m;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(N);
    K.topLeftCorner(9, 9) = Q;
    for (int r = 0; r < m; ++r) {
      K.block(9 + r, 0, 1, 9) = E[r].transpose();
      K.block(0, 9 + r, 9, 1) = E[r];
      b(9 + r) = rhs[r];
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
    if (lu.rank() < N) continue;
    const Eigen::VectorXd z = lu.solve(b).head(9);
    bool feasible = true;
    for (const Row& r : rows) {
      const double g = r.sgn * (z(r.var) - z(8) + r.H);  // <= 0 required
      if (g > 1e-9 * (1.0 + std::fabs(r.H))) feasible = false;
    }
    if (!feasible) continue;
    best = std::min(best, 0.5 * z.dot(Q * z));
  }
  return best;
}

SideProblem random_side(pdd::compare::ReproducibleRng& rng, int ncon, int nfree, bool integer, double below) {
  auto draw = [&] { return integer ? double(rng.integer(-2, 2)) : rng.uniform(-10.0, 10.0); };
  SideProblem s;
  s.ncon = ncon;
  s.nfree = nfree;
  s.hcon = draw();
  for (int i = 0; i < nfree; ++i) {
    s.hfree[i] = draw();
    if (below < 0 && ncon > 0) s.hfree[i] = s.hcon - std::fabs(s.hfree[i]);  // static-feasible
  }
  return s;
}

double max_height(const SideProblem& s) {
  double m = s.ncon ? s.hcon : -1e300;
  for (int i = 0; i < s.nfree; ++i) m = std::max(m, s.hfree[i]);
  return m;
}
double min_height(const SideProblem& s) {
  double m = s.ncon ? s.hcon : 1e300;
  for (int i = 0; i < s.nfree; ++i) m = std::min(m, s.hfree[i]);
  return m;
}

void all_heights(const SideProblem& s, double* h) {
  int k = 0;
  for (int i = 0; i < s.ncon; ++i) h[k++] = s.hcon;
  for (int i = 0; i < s.nfree; ++i) h[k++] = s.hfree[i];
}

// (ncon, nfree) of A and B for FV, VF, EE (definitions §3).
constexpr int kPatterns[3][4] = {{3, 1, 0, 4}, {0, 4, 3, 1}, {2, 2, 2, 2}};

bool agree(double closed, double dense) {
  return std::fabs(closed - dense) <= 1e-9 * std::fabs(dense) + 1e-9;
}

// KKT certificate of a case-2 solution (header of direction_qp.h): feasibility, balance
// S_A + S_B = 0, sums consistent, multipliers l_i = −2(T_i + S_A) >= 0, m_j = 2(T_j + S_B) >= 0.
void check_certificate(const SideProblem& A, const SideProblem& B, const DirectionSolution& s) {
  const double tol = 1e-9 * (1.0 + std::fabs(s.c));
  double sumA = 0.0, sumB = 0.0;
  for (int i = 0; i < A.ncon + A.nfree; ++i) {
    const bool con = i < A.ncon;
    const double h = con ? A.hcon : A.hfree[i - A.ncon];
    const double T = displacement_below(h, con, s);
    sumA += T;
    BOOST_TEST(h + T <= s.c + tol);
    if (!con) BOOST_TEST(-2.0 * (T + s.sumA) >= -tol);
    if (!con && h + T < s.c - tol) BOOST_TEST(std::fabs(T + s.sumA) <= tol);  // l_i = 0
  }
  for (int j = 0; j < B.ncon + B.nfree; ++j) {
    const bool con = j < B.ncon;
    const double h = con ? B.hcon : B.hfree[j - B.ncon];
    const double T = displacement_above(h, con, s);
    sumB += T;
    BOOST_TEST(h + T >= s.c - tol);
    if (!con) BOOST_TEST(2.0 * (T + s.sumB) >= -tol);
  }
  BOOST_TEST(std::fabs(sumA - s.sumA) <= tol);
  BOOST_TEST(std::fabs(sumB - s.sumB) <= tol);
  BOOST_TEST(std::fabs(s.sumA + s.sumB) <= tol);
}

}  // namespace

BOOST_AUTO_TEST_CASE(deformable_matches_dense_enumeration) {
  pdd::compare::ReproducibleRng rng(7);
  for (int it = 0; it < 600; ++it) {
    const int* p = kPatterns[it % 3];
    const bool integer = it % 4 == 3;  // small-integer heights: ties and coincident breakpoints
    const SideProblem A = random_side(rng, p[0], p[1], integer, 0);
    const SideProblem B = random_side(rng, p[2], p[3], integer, 0);
    const DirectionSolution s = solve_deformable(A, B);
    const double dense = dense_optimum(A, B, Mode::Deformable);
    BOOST_TEST_CONTEXT("iteration " << it) {
      BOOST_TEST(agree(s.cost, dense), "closed " << s.cost << " dense " << dense);
      check_certificate(A, B, s);
    }
  }
}

BOOST_AUTO_TEST_CASE(static_matches_dense_enumeration) {
  pdd::compare::ReproducibleRng rng(11);
  for (int it = 0; it < 600; ++it) {
    const int* p = kPatterns[it % 3];
    const bool integer = it % 4 == 3;
    const SideProblem A = random_side(rng, p[0], p[1], integer, -1);  // free A below hcon
    const SideProblem B = random_side(rng, p[2], p[3], integer, 0);
    const double closed = solve_static(A, B).cost;
    const double dense = dense_optimum(A, B, Mode::Static);
    BOOST_TEST_CONTEXT("iteration " << it) {
      BOOST_TEST(agree(closed, dense), "closed " << closed << " dense " << dense);
    }
  }
}

BOOST_AUTO_TEST_CASE(relaxed_matches_dense_enumeration) {
  pdd::compare::ReproducibleRng rng(13);
  int tested = 0;
  for (int it = 0; tested < 600; ++it) {
    const int* p = kPatterns[it % 3];
    const bool integer = it % 4 == 3;
    const SideProblem A = random_side(rng, p[0], p[1], integer, 0);
    const SideProblem B = random_side(rng, p[2], p[3], integer, 0);
    if (!(max_height(A) > min_height(B))) continue;  // separated: C undetermined, cost 0
    ++tested;
    double hA[4], hB[4];
    all_heights(A, hA);
    all_heights(B, hB);
    const double closed = solve_relaxed(hA, hB).cost;
    const double dense = dense_optimum(A, B, Mode::Relaxed);
    BOOST_TEST_CONTEXT("iteration " << it) {
      BOOST_TEST(agree(closed, dense), "closed " << closed << " dense " << dense);
      BOOST_TEST(closed <= solve_deformable(A, B).cost * (1 + 1e-12) + 1e-12);
    }
  }
}

// Hand-derived: one free vertex per side, A at height 1, B at −1, nothing constrained
// (relaxed). By symmetry C = 0, each side moves one vertex by 1 and the three others by
// −S = −1/4: per side 1 + 3/16 + (1/4)² = 5/4, F = 5/2.
BOOST_AUTO_TEST_CASE(two_vertex_relaxed_by_hand) {
  const double hA[4] = {1, -5, -6, -7}, hB[4] = {-1, 5, 6, 7};
  const DirectionSolution s = solve_relaxed(hA, hB);
  BOOST_TEST(std::fabs(s.cost - 2.5) <= 1e-15);
  BOOST_TEST(std::fabs(s.c) <= 1e-15);
  BOOST_TEST(std::fabs(s.sumA + 0.25) <= 1e-15);
}
