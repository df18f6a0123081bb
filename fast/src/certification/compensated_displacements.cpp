// compensated_displacements.cpp — case 2's closed form on Bounded double words. See the header.
#include "certification/compensated_displacements.h"

#include <cmath>

#include "certification/compensated_heights.h"

namespace pdd::fast::detail {
namespace {

using dw::Bounded;
using dw::kU;

// Case 2's plane for a pattern: m_X the counts at the plane, w_A = 5 − m_B, w_B = 5 − m_A,
// den = m_A w_A + m_B w_B and E = w_A sum_A h + w_B sum_B h (C = E / den); false when no vertex
// is at the plane (den = 0).
struct Plane {
  int mA = 0, mB = 0, wA = 0, wB = 0, den = 0;
  Bounded E;
};
bool plane_of(const Bounded (&hA)[4], const Bounded (&hB)[4], const AtPlane& pattern, Plane& p) {
  p.mA = __builtin_popcount(pattern.atA), p.mB = __builtin_popcount(pattern.atB);
  p.wA = 5 - p.mB, p.wB = 5 - p.mA, p.den = p.mA * p.wA + p.mB * p.wB;
  if (p.den == 0 || p.mA > 4 || p.mB > 4) return false;
  Bounded PA, PB;
  for (int i = 0; i < 4; ++i) {
    if (pattern.atA >> i & 1u) PA = dw::plus(PA, hA[i]);
    if (pattern.atB >> i & 1u) PB = dw::plus(PB, hB[i]);
  }
  p.E = dw::plus(dw::times(PA, p.wA), dw::times(PB, p.wB));
  return true;
}

// The closed form (header) on heights given as Bounded values.
bool displacements_of(const Bounded (&hA)[4], const Bounded (&hB)[4], const AtPlane& pattern,
                      CompensatedDisplacements& out) {
  Plane pl;
  if (!plane_of(hA, hB, pattern, pl)) return false;
  const int mA = pl.mA, mB = pl.mB, den = pl.den;
  const Bounded& E = pl.E;
  // x / k rounded, and its distance to x* / k
  auto divided = [](const Bounded& x, int k, double& t, double& e) {
    t = x.v.hi / k;
    e = ((x.e + kU * std::fabs(x.v.hi)) / k + kU * std::fabs(t)) * (1 + 0x1p-40);
    return std::isfinite(t) && std::isfinite(e);
  };
  for (int side = 0; side < 2; ++side) {
    const Bounded(&h)[4] = side ? hB : hA;
    const unsigned at = side ? pattern.atB : pattern.atA;
    const int m = side ? mB : mA;
    double* t = side ? out.tB : out.tA;
    double* e = side ? out.eB : out.eA;
    Bounded total;
    for (int i = 0; i < 4; ++i) {
      if (!(at >> i & 1u)) continue;
      const Bounded d = dw::minus(E, dw::times(h[i], den));
      total = dw::plus(total, d);
      if (!divided(d, den, t[i], e[i])) return false;
    }
    if (m == 4) continue;
    double S = 0, eS = 0;
    if (!divided(total, den * (5 - m), S, eS)) return false;
    for (int i = 0; i < 4; ++i)
      if (!(at >> i & 1u)) t[i] = -S, e[i] = eS;
  }
  return true;
}

}  // namespace

bool compensated_displacements(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                               const AtPlane& pattern, CompensatedDisplacements& out) {
  DoubleWordHeights w;
  if (!double_word_heights(A, B, label, w)) return false;
  // n* = e1 x e2 certainly not 0: the label's direction (not an edge pair's taken as ± by its
  // label while its edges are parallel, whose direction is another vector)
  Bounded nn;
  for (int k = 0; k < 3; ++k) nn = dw::plus(nn, dw::times(Bounded{w.n[k], w.en[k]}, Bounded{w.n[k], w.en[k]}));
  if (!(dw::certain_sign(nn) > 0)) return false;
  Bounded hA[4], hB[4];
  for (int i = 0; i < 4; ++i) hA[i] = {w.hA[i], w.eA[i]}, hB[i] = {w.hB[i], w.eB[i]};
  return displacements_of(hA, hB, pattern, out);
}

bool compensated_displacements(const CompensatedHeights& h, const AtPlane& pattern, CompensatedDisplacements& out) {
  Bounded hA[4], hB[4];
  for (int i = 0; i < 4; ++i) hA[i] = {{h.hA[i], 0.0}, h.eA[i]}, hB[i] = {{h.hB[i], 0.0}, h.eB[i]};
  return displacements_of(hA, hB, pattern, out);
}

}  // namespace pdd::fast::detail
