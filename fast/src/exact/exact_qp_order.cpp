// exact_qp_order.cpp — the closed forms of exact_qp_order.h on expansions.
#include "exact/exact_qp_order.h"

#include "exact/exact_predicates.h"

namespace pdd::fast {

using detail::Expansion;
using detail::ExpVec;

namespace {

Expansion times(const Expansion& e, int k) { return detail::scaled(e, double(k)); }

// e + f by Shewchuk's FAST-EXPANSION-SUM (his Theorem 13; predicates.c's
// fast_expansion_sum_zeroelim): the components of both merged by increasing magnitude, then
// one pass of two_sum, O(|e| + |f|) where expansion.h's sum grows each component of f through
// all of e. Its precondition, both strongly nonoverlapping under round-to-nearest-even (the
// IEEE default, which the engine never changes; no FMA contraction: fast/CMakeLists.txt),
// holds for every expansion built here: two_sum's and two_product's results are nonadjacent
// under round-to-even, and grow, scale-expansion, compress (nonadjacent) and this sum keep
// strongly nonoverlapping ones so (his Theorems 10, 13, 19, 23). Zero components dropped.
Expansion merged_sum(const Expansion& e, const Expansion& f) {
  Expansion h;
  h.ok = e.ok && f.ok;
  const int total = e.n + f.n;
  if (!h.ok || total > detail::kExpansionCapacity) {
    h.ok = false;
    return h;
  }
  if (total == 0) return h;
  int i = 0, j = 0;
  auto next = [&] {  // the remaining component of least magnitude (e's on a tie of magnitudes)
    const bool from_e = j == f.n || (i < e.n && (f.c[j] > e.c[i]) == (f.c[j] > -e.c[i]));
    return from_e ? e.c[i++] : f.c[j++];
  };
  double q = next(), x, y;
  if (total > 1) {
    detail::fast_two_sum(next(), q, x, y);  // (the second is not smaller than the first)
    q = x;
    if (y != 0.0) h.c[h.n++] = y;
  }
  for (int k = 2; k < total; ++k) {
    detail::two_sum(q, next(), x, y);
    q = x;
    if (y != 0.0) h.c[h.n++] = y;
  }
  if (q != 0.0) h.c[h.n++] = q;
  return h;
}
Expansion minus(const Expansion& e, const Expansion& f) { return merged_sum(e, detail::negated(f)); }

// e · f compressed: the partial products e · f_i (scale-expansion) summed by merged_sum, the
// running sum compressed after each (it stays about the value's own length).
Expansion short_product(const Expansion& e, const Expansion& f) {
  const Expansion& a = e.n >= f.n ? e : f;
  const Expansion& b = e.n >= f.n ? f : e;
  if (!a.ok || !b.ok) {
    Expansion r;
    r.ok = false;
    return r;
  }
  if (b.n == 1) return detail::compressed(detail::scaled(a, b.c[0]));
  Expansion r;
  for (int i = 0; i < b.n; ++i) r = detail::compressed(merged_sum(r, detail::scaled(a, b.c[i])));
  return r;
}
Expansion square(const Expansion& e) {
  const Expansion c = detail::compressed(e);
  return short_product(c, c);
}
Expansion plus(const Expansion& e, const Expansion& f) { return detail::compressed(merged_sum(e, f)); }

// The sums of d_i² and of d_i over the vertices of `at` (heights h), d_i = E − k h_i.
struct Deviations {
  Expansion squares, total;
};
Deviations deviations(const Expansion& E, int k, const Expansion* h, unsigned at) {
  Deviations s;
  for (int i = 0; i < 4; ++i) {
    if (!(at >> i & 1u)) continue;
    const Expansion d = detail::compressed(minus(E, times(h[i], k)));
    s.squares = plus(s.squares, square(d));
    s.total = plus(s.total, d);
  }
  return s;
}

}  // namespace

QpParts qp_parts_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                       const QpPattern& pattern, bool a_static) {
  QpParts out;
  ExpVec n;
  if (!normal_for_degree_ten(A, B, label, n)) return out;
  bool ok = true;
  for (Expansion& c : n.x) c = detail::compressed(c);
  // The origin o: a vertex at the plane (case 1: the constrained vertex of A that gives C), so
  // that the heights of the vertices level with it are exactly 0 (short expansions) on aligned
  // pairs; case 2's value does not depend on it (header), case 1's C is then 0 exactly.
  const unsigned needA = !a_static ? pattern.atA : pattern.conA ? pattern.conA & (~pattern.conA + 1u) : 0xFu;
  const unsigned originA = a_static ? pattern.conA : pattern.atA;
  const Vec3d& o = originA ? A[__builtin_ctz(originA)] : pattern.atB ? B[__builtin_ctz(pattern.atB)] : A[0];
  auto height = [&](const Vec3d& x) {
    const ExpVec v = detail::difference(x, o);
    Expansion h;
    for (int k = 0; k < 3; ++k)
      if (v.x[k].n != 0 && n.x[k].n != 0) h = merged_sum(h, short_product(n.x[k], v.x[k]));
    h = detail::compressed(h);
    ok = ok && h.ok;
    return h;
  };
  // the heights the closed form reads: case 1's C (one constrained vertex of A, or all four)
  Expansion hA[4], hB[4];
  for (int i = 0; i < 4; ++i) {
    if (needA >> i & 1u) hA[i] = height(A[i]);
    if (pattern.atB >> i & 1u) hB[i] = height(B[i]);
  }
  const int mA = __builtin_popcount(pattern.atA), mB = __builtin_popcount(pattern.atB);
  Expansion F;
  int K;
  if (a_static) {
    Expansion C = hA[__builtin_ctz(needA)];
    if (!pattern.conA)
      for (int i = 1; i < 4; ++i)
        if (minus(hA[i], C).sign() > 0) C = hA[i];
    const Deviations b = deviations(C, 1, hB, pattern.atB);
    F = plus(times(b.squares, 5 - mB), square(b.total));
    K = 5 - mB;
  } else {
    const int wA = 5 - mB, wB = 5 - mA, den = mA * wA + mB * wB;
    if (den == 0 || mA > 4 || mB > 4) return out;
    Expansion PA, PB;
    for (int i = 0; i < 4; ++i) {
      if (pattern.atA >> i & 1u) PA = plus(PA, hA[i]);
      if (pattern.atB >> i & 1u) PB = plus(PB, hB[i]);
    }
    const Expansion E = detail::compressed(plus(times(PA, wA), times(PB, wB)));
    const Deviations a = deviations(E, den, hA, pattern.atA), b = deviations(E, den, hB, pattern.atB);
    F = plus(plus(times(plus(a.squares, b.squares), wA * wB), times(square(a.total), wA)),
             times(square(b.total), wB));
    K = den * den * wA * wB;
  }
  out.F = detail::compressed(F);
  Expansion nn;
  for (int k = 0; k < 3; ++k) nn = plus(nn, square(n.x[k]));
  out.Knn = detail::compressed(times(nn, K));
  out.ok = ok && out.F.ok && out.Knn.ok && out.Knn.sign() > 0;
  return out;
}

std::optional<int> compare_qp_exact(const QpParts& p, const QpParts& q) {
  const Expansion d = minus(short_product(p.F, q.Knn), short_product(q.F, p.Knn));
  if (!d.ok) return std::nullopt;
  return d.sign();
}

}  // namespace pdd::fast
