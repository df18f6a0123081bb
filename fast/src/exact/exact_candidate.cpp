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
  // throughout, each difference written into its rational's numerator over the denominator 1
  // it starts with: the same values as Q(x)·2^shift, without the rationals' canonicalising gcds.
  auto integer = [&](double x, mpz_t z) {
    if (x == 0.0) return mpz_set_ui(z, 0);
    int e;
    const double m = std::frexp(x, &e);
    mpz_set_si(z, static_cast<long>(std::ldexp(m, 53)));
    mpz_mul_2exp(z, z, static_cast<mp_bitcnt_t>(e - 53 + f.shift));
  };
  mpz_class s0[3], x;
  for (int k = 0; k < 3; ++k) integer(A[0][k], s0[k].get_mpz_t());
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      integer(A[i][k], x.get_mpz_t());
      mpz_sub(mpq_numref(f.s[i].x[k].get_mpq_t()), x.get_mpz_t(), s0[k].get_mpz_t());
      integer(B[i][k], x.get_mpz_t());
      mpz_sub(mpq_numref(f.r[i].x[k].get_mpq_t()), x.get_mpz_t(), s0[k].get_mpz_t());
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

namespace {

// The candidate of a label on the frame's integers (every coordinate of an ExactFrame has
// denominator 1: exact_frame): exact_geometry.h's normals, orientation rule and heights, the
// same integers, taken on the numerators with mpz (each rational operation would canonicalise:
// a gcd per operation, ~5x the instructions on a contact made by rounding's candidates).
struct ZV {
  mpz_class x[3];
};
const mpz_class& num(const Q& q) { return q.get_num(); }
ZV difference(const QV& a, const QV& b) {
  ZV d;
  for (int k = 0; k < 3; ++k) mpz_sub(d.x[k].get_mpz_t(), num(a.x[k]).get_mpz_t(), num(b.x[k]).get_mpz_t());
  return d;
}
ZV cross(const ZV& a, const ZV& b) {
  ZV c;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    mpz_mul(c.x[k].get_mpz_t(), a.x[i].get_mpz_t(), b.x[j].get_mpz_t());
    mpz_submul(c.x[k].get_mpz_t(), a.x[j].get_mpz_t(), b.x[i].get_mpz_t());
  }
  return c;
}
void dot(mpz_class& out, const ZV& a, const ZV& b) {
  mpz_mul(out.get_mpz_t(), a.x[0].get_mpz_t(), b.x[0].get_mpz_t());
  mpz_addmul(out.get_mpz_t(), a.x[1].get_mpz_t(), b.x[1].get_mpz_t());
  mpz_addmul(out.get_mpz_t(), a.x[2].get_mpz_t(), b.x[2].get_mpz_t());
}
void dot(mpz_class& out, const ZV& a, const QV& b) {
  mpz_mul(out.get_mpz_t(), a.x[0].get_mpz_t(), num(b.x[0]).get_mpz_t());
  mpz_addmul(out.get_mpz_t(), a.x[1].get_mpz_t(), num(b.x[1]).get_mpz_t());
  mpz_addmul(out.get_mpz_t(), a.x[2].get_mpz_t(), num(b.x[2]).get_mpz_t());
}
int dot_sign(const ZV& a, const ZV& b) {
  mpz_class d;
  dot(d, a, b);
  return sgn(d);
}
void negate(ZV& a) {
  for (mpz_class& c : a.x) mpz_neg(c.get_mpz_t(), c.get_mpz_t());
}
bool is_zero(const ZV& a) { return sgn(a.x[0]) == 0 && sgn(a.x[1]) == 0 && sgn(a.x[2]) == 0; }

// face_normal_out_of (exact_geometry.h) on integers.
ZV face_normal_out_of_z(const QTet& T, int i) {
  const auto& f = kFace[i];
  ZV n = cross(difference(T[f[1]], T[f[0]]), difference(T[f[2]], T[f[0]]));
  if (dot_sign(n, difference(T[i], T[f[0]])) > 0) negate(n);
  return n;
}

// edge_pair_normal and side_rule (exact_geometry.h) on integers; the normal oriented as the
// label says (Minus, or Decided where the rule flips).
ZV edge_pair_normal_z(const ExactFrame& f, const DirectionLabel& l) {
  const int u = kEdges[l.a][0], v = kEdges[l.a][1], x = kEdges[l.b][0], y = kEdges[l.b][1];
  const ZV e = difference(f.s[v], f.s[u]);
  ZV n = cross(difference(f.r[y], f.r[x]), e);
  if (is_zero(n)) {  // parallel edges: (e.e) w − (w.e) e, w = r_x − s_u
    const ZV w = difference(f.r[x], f.s[u]);
    mpz_class ee, we;
    dot(ee, e, e);
    dot(we, w, e);
    for (int k = 0; k < 3; ++k) {
      mpz_mul(n.x[k].get_mpz_t(), w.x[k].get_mpz_t(), ee.get_mpz_t());
      mpz_submul(n.x[k].get_mpz_t(), e.x[k].get_mpz_t(), we.get_mpz_t());
    }
  }
  bool minus = l.orientation == EdgeOrientation::Minus;
  if (l.orientation == EdgeOrientation::Decided) {
    const int g1 = dot_sign(n, difference(f.s[kOffEdge[l.a][0]], f.s[u]));
    const int g2 = dot_sign(n, difference(f.s[kOffEdge[l.a][1]], f.s[u]));
    minus = !(g1 <= 0 && g2 <= 0) && g1 >= 0 && g2 >= 0;  // (side_rule's Flip)
  }
  if (minus) negate(n);
  return n;
}

bool integer_frame(const ExactFrame& f) {
  for (const QTet* T : {&f.s, &f.r})
    for (const QV& p : *T)
      for (const Q& c : p.x)
        if (mpz_cmp_ui(c.get_den_mpz_t(), 1) != 0) return false;
  return true;
}

}  // namespace

ExactCandidate exact_candidate(const ExactFrame& f, const DirectionLabel& l) {
  unsigned conA = 0, conB = 0;
  if (!integer_frame(f)) {  // (not exact_frame's: the rationals' own functions)
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
  ZV n;
  switch (l.kind) {
    case ContactKind::FV:
      n = face_normal_out_of_z(f.s, l.a), conA = mask_without(l.a);
      break;
    case ContactKind::VF:
      n = face_normal_out_of_z(f.r, l.a), conB = mask_without(l.a);
      negate(n);  // (into B)
      break;
    default:
      n = edge_pair_normal_z(f, l), conA = edge_mask(l.a), conB = edge_mask(l.b);
  }
  ExactCandidate c;
  c.label = l;
  c.conA = conA, c.conB = conB;
  mpz_class h;
  for (int k = 0; k < 3; ++k) mpq_set_z(c.n.x[k].get_mpq_t(), n.x[k].get_mpz_t());
  dot(h, n, n);
  mpq_set_z(c.nn.get_mpq_t(), h.get_mpz_t());
  mpz_class hi, lo;
  for (int i = 0; i < 4; ++i) {
    dot(h, n, f.s[i]);
    mpq_set_z(c.hA[i].get_mpq_t(), h.get_mpz_t());
    if (i == 0 || hi < h) hi = h;
    dot(h, n, f.r[i]);
    mpq_set_z(c.hB[i].get_mpq_t(), h.get_mpz_t());
    if (i == 0 || h < lo) lo = h;
  }
  mpz_sub(h.get_mpz_t(), hi.get_mpz_t(), lo.get_mpz_t());
  mpq_set_z(c.D.get_mpq_t(), h.get_mpz_t());
  return c;
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
