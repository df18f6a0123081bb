#include "pdd/reference/direction_qp.h"

#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>

#include <gmp.h>

#include <stdexcept>
#include <vector>

namespace pdd::reference {
namespace {

using Program = CGAL::Quadratic_program<QpNumber>;
using Solution = CGAL::Quadratic_program_solution<QpNumber>;

Rational to_rational(const CGAL::Quotient<QpNumber>& q) {
  return reference::to_rational(q.numerator()) / reference::to_rational(q.denominator());
}

// The relation of vertex i of a tetrahedron to the plane, per eq. 10 and the variant.
CGAL::Comparison_result relation(bool constrained, bool is_A, PddCase c) {
  if (constrained && c != PddCase::Relaxed) return CGAL::EQUAL;
  return is_A ? CGAL::SMALLER : CGAL::LARGER;  // A on n.x <= c, B on n.x >= c
}

Program free_program() { return Program(CGAL::EQUAL, false, 0, false, 0); }  // unbounded vars

Solution solve(const Program& qp) {
  Solution s = CGAL::solve_quadratic_program(qp, QpNumber());
  if (!s.is_optimal() && !s.is_infeasible())
    throw std::logic_error("direction_qp: QP neither optimal nor infeasible (unbounded?)");
  return s;
}

// ---------------------------------------------------------------- full formulation
// Objective 20 sigma = sum_k (x_k - x0_k)^T M (x_k - x0_k), M = I + J (4x4), per coordinate k.
// CGAL minimises x^T D x + c^T x + c0 and takes 2D: 2D = 2M, c = -2 M x0, c0 = x0^T M x0.
void add_full_objective(Program& qp, int offset, const ExactTet& rest, QpNumber& c0) {
  for (int k = 0; k < 3; ++k) {
    QpNumber column_sum = 0;
    for (int i = 0; i < 4; ++i) column_sum = column_sum + to_qp_number(rest[i][k]);
    for (int i = 0; i < 4; ++i) {
      const QpNumber x0 = to_qp_number(rest[i][k]);
      for (int j = 0; j <= i; ++j)
        qp.set_d(offset + 3 * i + k, offset + 3 * j + k, QpNumber(i == j ? 4 : 2));
      qp.set_c(offset + 3 * i + k, QpNumber(-2) * (x0 + column_sum));
      c0 = c0 + x0 * x0;
    }
    c0 = c0 + column_sum * column_sum;
  }
}

// Row: n.x_i - n.p_s (rel) 0 for a moving vertex; -n.p_s (rel) -n.x_i for a fixed one.
void add_full_row(Program& qp, int row, int vertex_offset, int ps_offset, const Vector& n,
                  const Point& rest, CGAL::Comparison_result rel) {
  QpNumber rhs = 0;
  for (int k = 0; k < 3; ++k) {
    const QpNumber nk = to_qp_number(n[k]);
    qp.set_a(ps_offset + k, row, -nk);
    if (vertex_offset >= 0) qp.set_a(vertex_offset + k, row, nk);
    else rhs = rhs - nk * to_qp_number(rest[k]);
  }
  qp.set_b(row, rhs);
  qp.set_r(row, rel);
}

std::optional<DirectionOptimum> full_qp_axes(const ExactPair& p, const CandidateDirection& dir,
                                             PddCase c) {
  const bool a_moves = (c != PddCase::Static);
  const int off_A = a_moves ? 0 : -1, off_B = a_moves ? 12 : 0, off_ps = off_B + 12;
  Program qp = free_program();
  QpNumber c0 = 0;
  if (a_moves) add_full_objective(qp, off_A, p.A, c0);
  add_full_objective(qp, off_B, p.B, c0);
  qp.set_c0(c0);
  for (int i = 0; i < 4; ++i) {
    add_full_row(qp, i, a_moves ? off_A + 3 * i : -1, off_ps, dir.n, p.A[i],
                 relation(dir.constrained_A[i], true, c));
    add_full_row(qp, 4 + i, off_B + 3 * i, off_ps, dir.n, p.B[i],
                 relation(dir.constrained_B[i], false, c));
  }
  const Solution s = solve(qp);
  if (s.is_infeasible()) return std::nullopt;

  DirectionOptimum out{to_rational(s.objective_value()) / 20, p.A, p.B};
  std::vector<Rational> x;
  for (auto it = s.variable_values_begin(); it != s.variable_values_end(); ++it)
    x.push_back(to_rational(*it));
  x.resize(off_ps + 3);  // trailing variables absent from every row/objective read as 0
  for (int i = 0; i < 4; ++i) {
    if (a_moves) out.q1_A[i] = Point(x[off_A + 3 * i], x[off_A + 3 * i + 1], x[off_A + 3 * i + 2]);
    out.q1_B[i] = Point(x[off_B + 3 * i], x[off_B + 3 * i + 1], x[off_B + 3 * i + 2]);
  }
  return out;
}

// The same 27-variable QP in the orthogonal frame (n, u, v), u = n x e_a, v = n x u, e_a the
// axis of n's smallest component (so u != 0). Exact change of variables, per moving vertex i
//   x_i = x0_i + (alpha_i / n.n) n + beta_i u + gamma_i v,   p_s = (P / n.n) n + rho u + tau v,
// and the objective multiplied by n.n > 0. As n, u, v are pairwise orthogonal,
//   n.n * 20 sigma = sum_T alpha_T^T M alpha_T + n.n u.u beta_T^T M beta_T + n.n v.v gamma_T^T M gamma_T
// (M = I + J), and a row n.(x_i - p_s) (rel) 0 reads alpha_i - P (rel) -n.x0_i. Every variable
// of the paper's formulation is still free; only the coordinates differ. In the axis-aligned
// form the QP's matrix holds n's components, whose exact mantissas are as wide as the pair's
// magnitude range (a pair mixing 1e308 with 5e-324 gives thousands of bits), and the
// solver's fraction-free basis inverse multiplies them together: tens of thousands of bits per
// entry. In this frame the matrix is 0, +-1 and the objective's small integers, and the wide
// numbers stay in the right-hand side.
std::optional<DirectionOptimum> full_qp_frame(const ExactPair& p, const CandidateDirection& dir,
                                              PddCase c) {
  const Vector& n = dir.n;
  int a = 0;
  for (int k = 1; k < 3; ++k)
    if (CGAL::abs(n[k]) < CGAL::abs(n[a])) a = k;
  const Vector e(a == 0 ? 1 : 0, a == 1 ? 1 : 0, a == 2 ? 1 : 0);
  const Vector u = CGAL::cross_product(n, e), v = CGAL::cross_product(n, u);
  const Rational nn = n.squared_length();
  const QpNumber weight_u = to_qp_number(nn * u.squared_length());
  const QpNumber weight_v = to_qp_number(nn * v.squared_length());

  // Variables: per moving tetrahedron alpha (4), beta (4), gamma (4); then P, rho, tau.
  const bool a_moves = (c != PddCase::Static);
  const int off_A = a_moves ? 0 : -1, off_B = a_moves ? 12 : 0, off_ps = off_B + 12;
  Program qp = free_program();
  auto objective = [&](int offset) {
    for (int block = 0; block < 3; ++block) {
      const QpNumber w = block == 0 ? QpNumber(1) : block == 1 ? weight_u : weight_v;
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j <= i; ++j)
          qp.set_d(offset + 4 * block + i, offset + 4 * block + j, QpNumber(i == j ? 4 : 2) * w);
    }
  };
  if (a_moves) objective(off_A);
  objective(off_B);
  auto row = [&](int r, int alpha, const Point& rest, CGAL::Comparison_result rel) {
    if (alpha >= 0) qp.set_a(alpha, r, QpNumber(1));
    qp.set_a(off_ps, r, QpNumber(-1));
    qp.set_b(r, -to_qp_number(n * (rest - CGAL::ORIGIN)));
    qp.set_r(r, rel);
  };
  for (int i = 0; i < 4; ++i) {
    row(i, a_moves ? off_A + i : -1, p.A[i], relation(dir.constrained_A[i], true, c));
    row(4 + i, off_B + i, p.B[i], relation(dir.constrained_B[i], false, c));
  }
  const Solution s = solve(qp);
  if (s.is_infeasible()) return std::nullopt;

  DirectionOptimum out{to_rational(s.objective_value()) / (20 * nn), p.A, p.B};
  std::vector<Rational> y;
  for (auto it = s.variable_values_begin(); it != s.variable_values_end(); ++it)
    y.push_back(to_rational(*it));
  y.resize(off_ps + 3);
  auto moved = [&](const Point& rest, int offset, int i) {
    return rest + (y[offset + i] / nn) * n + y[offset + 4 + i] * u + y[offset + 8 + i] * v;
  };
  for (int i = 0; i < 4; ++i) {
    if (a_moves) out.q1_A[i] = moved(p.A[i], off_A, i);
    out.q1_B[i] = moved(p.B[i], off_B, i);
  }
  return out;
}

// Axis-aligned while n's exact components have short mantissas, so that the paper's own
// coordinates are what the solver sees and full == reduced is an independent check there; the
// frame above when a component's mantissa exceeds kAxisAlignedBits. Every shipped fixture
// stays below (at most 166 bits: paper pairs ~110, a vertex 1e18 away ~166); pairs mixing
// magnitudes 1e20 and 1e-20 reach ~370 bits and took 6 s axis-aligned against 0.1 s reduced.
constexpr std::size_t kAxisAlignedBits = 256;
std::optional<DirectionOptimum> full_qp(const ExactPair& p, const CandidateDirection& dir,
                                        PddCase c) {
  return full_qp_uses_frame(dir.n) ? full_qp_frame(p, dir, c) : full_qp_axes(p, dir, c);
}

// ---------------------------------------------------------------- reduced formulation
// Variables mu_A (4, not in Static), mu_B (4), C; objective sum_T mu_T^T (I + J) mu_T,
// i.e. 2D = 2 (I + J) per moving tetrahedron; the optimum is that over 20 n.n.
void add_reduced_objective(Program& qp, int offset) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j <= i; ++j) qp.set_d(offset + i, offset + j, QpNumber(i == j ? 4 : 2));
}

// Row: mu_i - C (rel) -n.x_i for a moving vertex; -C (rel) -n.x_i for a fixed one.
void add_reduced_row(Program& qp, int row, int mu, int c_var, const Rational& a,
                     CGAL::Comparison_result rel) {
  if (mu >= 0) qp.set_a(mu, row, QpNumber(1));
  qp.set_a(c_var, row, QpNumber(-1));
  qp.set_b(row, -to_qp_number(a));
  qp.set_r(row, rel);
}

std::optional<DirectionOptimum> reduced_qp(const ExactPair& p, const CandidateDirection& dir,
                                           PddCase c) {
  const bool a_moves = (c != PddCase::Static);
  const int off_A = a_moves ? 0 : -1, off_B = a_moves ? 4 : 0, c_var = off_B + 4;
  Program qp = free_program();
  if (a_moves) add_reduced_objective(qp, off_A);
  add_reduced_objective(qp, off_B);
  const Vector& n = dir.n;
  for (int i = 0; i < 4; ++i) {
    add_reduced_row(qp, i, a_moves ? off_A + i : -1, c_var, n * (p.A[i] - CGAL::ORIGIN),
                    relation(dir.constrained_A[i], true, c));
    add_reduced_row(qp, 4 + i, off_B + i, c_var, n * (p.B[i] - CGAL::ORIGIN),
                    relation(dir.constrained_B[i], false, c));
  }
  const Solution s = solve(qp);
  if (s.is_infeasible()) return std::nullopt;

  const Rational nn = n.squared_length();
  DirectionOptimum out{to_rational(s.objective_value()) / (20 * nn), p.A, p.B};
  std::vector<Rational> mu;
  for (auto it = s.variable_values_begin(); it != s.variable_values_end(); ++it)
    mu.push_back(to_rational(*it));
  mu.resize(c_var + 1);
  for (int i = 0; i < 4; ++i) {
    if (a_moves) out.q1_A[i] = p.A[i] + (mu[off_A + i] / nn) * n;
    out.q1_B[i] = p.B[i] + (mu[off_B + i] / nn) * n;
  }
  return out;
}

}  // namespace

Rational relaxed_hull_minimum(const ExactPair& p, const std::vector<Vector>& normals,
                              std::vector<Rational>* lambda) {
  const int m = static_cast<int>(normals.size());
  if (m < 1 || m > 8) throw std::invalid_argument("relaxed_hull_minimum: 1 to 8 normals");
  // Variables: lambda (m, >= 0), mu_A (4), mu_B (4), C; rows 0..7 as reduced_qp's (Relaxed),
  // with n.x_i = sum_k lambda_k normals_k.x_i on the left; row 8: sum lambda = 1.
  const int off_A = m, off_B = m + 4, c_var = m + 8;
  Program qp = free_program();
  add_reduced_objective(qp, off_A);
  add_reduced_objective(qp, off_B);
  for (int k = 0; k < m; ++k) {
    qp.set_l(k, true, QpNumber(0));
    qp.set_a(k, 8, QpNumber(1));
  }
  qp.set_b(8, QpNumber(1));
  qp.set_r(8, CGAL::EQUAL);
  for (int i = 0; i < 8; ++i) {
    const Point& x = i < 4 ? p.A[i] : p.B[i - 4];
    add_reduced_row(qp, i, (i < 4 ? off_A : off_B - 4) + i, c_var, Rational(0),
                    relation(false, i < 4, PddCase::Relaxed));
    for (int k = 0; k < m; ++k) qp.set_a(k, i, to_qp_number(normals[k] * (x - CGAL::ORIGIN)));
  }
  const Solution s = solve(qp);
  if (!s.is_optimal()) throw std::logic_error("relaxed_hull_minimum: the QP has no optimum");
  if (lambda) {
    lambda->clear();
    for (auto it = s.variable_values_begin(); it != s.variable_values_end(); ++it)
      lambda->push_back(to_rational(*it));
    lambda->resize(m);
  }
  return to_rational(s.objective_value()) / 20;
}

bool full_qp_uses_frame(const Vector& n) {
  for (int k = 0; k < 3; ++k)
    if (n[k] != 0) {  // the denominator is a power of two: the mantissa is num / 2^(trailing 0s)
      const mpz_srcptr num = mpq_numref(n[k].mpq());
      if (mpz_sizeinbase(num, 2) - mpz_scan1(num, 0) > kAxisAlignedBits) return true;
    }
  return false;
}


std::optional<DirectionOptimum> direction_qp(const ExactPair& pair, const CandidateDirection& dir,
                                             PddCase pdd_case, QpFormulation formulation) {
  return formulation == QpFormulation::Full ? full_qp(pair, dir, pdd_case)
                                            : reduced_qp(pair, dir, pdd_case);
}

}  // namespace pdd::reference
