// exact_candidate.cpp — see exact_candidate.h.
#include "exact/exact_candidate.h"

#include <algorithm>
#include <cfloat>
#include <climits>
#include <cmath>

#include "qp/direction_qp_impl.h"

namespace pdd::fast::detail {

ExactFrame exact_frame(const TetVertices& A, const TetVertices& B) {
  ExactFrame f;
  int lowest = 0;
  bool nonzero = false;
  for (const TetVertices* T : {&A, &B})
    for (const auto& p : *T)
      for (double x : p) {
        if (x == 0.0) continue;
        int e;
        std::frexp(x, &e);  // x = m 2^e, m in [1/2, 1) with 53 bits: an integer times 2^(e − 53)
        lowest = nonzero ? std::min(lowest, e - 53) : e - 53;
        nonzero = true;
      }
  f.shift = nonzero ? -long(lowest) : 0;
  // x·2^shift as an integer: x = m·2^e, m·2^53 an integer below 2^53 (subnormals included:
  // frexp normalises m), and e − 53 >= lowest = −shift, so the power is >= 0. Integers (mpz)
  // throughout, each difference an integer rational with denominator 1: the same values as
  // Q(x)·2^shift, without the rationals' canonicalising gcds (most of this function's time).
  auto integer = [&](double x) {
    mpz_class z;
    if (x == 0.0) return z;
    int e;
    const double m = std::frexp(x, &e);
    mpz_set_si(z.get_mpz_t(), static_cast<long>(std::ldexp(m, 53)));
    mpz_mul_2exp(z.get_mpz_t(), z.get_mpz_t(), static_cast<mp_bitcnt_t>(e - 53 + f.shift));
    return z;
  };
  mpz_class s0[3];
  for (int k = 0; k < 3; ++k) s0[k] = integer(A[0][k]);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      f.s[i].x[k] = Q(mpz_class(integer(A[i][k]) - s0[k]));
      f.r[i].x[k] = Q(mpz_class(integer(B[i][k]) - s0[k]));
    }
  return f;
}

Q unscaled(const ExactFrame& f, Q q, long times) {
  const long k = times * f.shift;
  if (k > 0) mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), k);
  if (k < 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), -k);
  return q;
}

ExactCandidate exact_candidate(const ExactFrame& f, const DirectionLabel& l, const QV& n,
                               unsigned conA, unsigned conB) {
  ExactCandidate c;
  c.label = l;
  c.n = n;
  c.nn = dot(n, n);
  for (int i = 0; i < 4; ++i) {
    c.hA[i] = dot(n, f.s[i]);
    c.hB[i] = dot(n, f.r[i]);
  }
  Q hi = c.hA[0], lo = c.hB[0];
  for (int i = 1; i < 4; ++i) {
    if (hi < c.hA[i]) hi = c.hA[i];
    if (c.hB[i] < lo) lo = c.hB[i];
  }
  c.D = hi - lo;
  c.conA = conA;
  c.conB = conB;
  return c;
}

ExactCandidate exact_candidate(const ExactFrame& f, const DirectionLabel& l) {
  switch (l.kind) {
    case ContactKind::FV:
      return exact_candidate(f, l, face_normal_out_of(f.s, l.a), mask_without(l.a), 0);
    case ContactKind::VF:
      return exact_candidate(f, l, face_normal_into(f.r, l.a), 0, mask_without(l.a));
    default: {
      EdgePairKind kind;
      QV n = edge_pair_normal(f.s, f.r, l.a, l.b, &kind);
      const bool minus = l.orientation == EdgeOrientation::Minus ||
                         (l.orientation == EdgeOrientation::Decided &&
                          side_rule(f.s, n, l.a) == EdgePairSide::Flip);
      if (minus) n = negated(n);
      return exact_candidate(f, l, n, edge_mask(l.a), edge_mask(l.b));
    }
  }
}

Q exact_delta2(const ExactCandidate& c) { return c.D * c.D / c.nn; }

Q exact_overlap(const ExactCandidate& c) {
  Q loA = c.hA[0], hiA = c.hA[0], loB = c.hB[0], hiB = c.hB[0];
  for (int i = 1; i < 4; ++i) {
    if (c.hA[i] < loA) loA = c.hA[i];
    if (hiA < c.hA[i]) hiA = c.hA[i];
    if (c.hB[i] < loB) loB = c.hB[i];
    if (hiB < c.hB[i]) hiB = c.hB[i];
  }
  return (hiA - loA) + (hiB - loB) - ((hiA < hiB ? hiB : hiA) - (loA < loB ? loA : loB));
}

Q exact_static_value(const ExactCandidate& c) {
  return solve_static_sides(side_of(c.hA, c.conA), side_of(c.hB, c.conB)).cost / (20 * c.nn);
}

Q exact_deformable_value(const ExactCandidate& c, Solution<Q>* sol) {
  Solution<Q> s = solve_deformable_sorted(side_of(c.hA, c.conA), side_of(c.hB, c.conB));
  Q v = s.cost / (20 * c.nn);
  if (sol) *sol = std::move(s);
  return v;
}

Q exact_relaxed_value(const ExactCandidate& c) {
  return solve_relaxed_heights(c.hA, c.hB).cost / (20 * c.nn);
}

void exact_positions(const TetVertices& A, const TetVertices& B, const ExactFrame& f,
                     const ExactCandidate& c, const Solution<Q>& sol, Positions<double>& qA,
                     Positions<double>& qB, bool& ok) {
  auto rounded_coordinate = [&ok](const Q& q) {
    const double d = q.get_d();
    if (!(std::fabs(d) <= DBL_MAX)) ok = false;
    return d;
  };
  for (int i = 0; i < 4; ++i) {
    const Q tA = displacement_below(c.hA[i], (c.conA >> i & 1u) != 0, sol) / c.nn;
    const Q tB = displacement_above(c.hB[i], (c.conB >> i & 1u) != 0, sol) / c.nn;
    for (int k = 0; k < 3; ++k) {
      qA[i][k] = rounded_coordinate(Q(A[i][k]) + unscaled(f, tA * c.n.x[k], 1));
      qB[i][k] = rounded_coordinate(Q(B[i][k]) + unscaled(f, tB * c.n.x[k], 1));
    }
  }
}

double rounded_value(const Q& q, bool& ok) {
  const double d = q.get_d();
  if (sgn(q) != 0 && !(std::fabs(d) >= DBL_MIN && std::fabs(d) <= DBL_MAX)) ok = false;
  return d;
}

std::array<double, 3> rounded_normal(const QV& n) {
  long top = LONG_MIN;  // log2 of the largest component, within 1
  for (const Q& x : n.x) top = std::max(top, log2_estimate(x));
  std::array<double, 3> out{};
  if (top == LONG_MIN) return out;
  for (int k = 0; k < 3; ++k) {
    Q x = n.x[k];
    scale_pow2(x, -top);
    out[k] = x.get_d();
  }
  return out;
}

}  // namespace pdd::fast::detail
