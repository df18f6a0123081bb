// direction_qp.cpp — closed-form per-direction QP; derivation and proof in the header.
#include "pdd/fast/direction_qp.h"

#include <algorithm>
#include <limits>

namespace pdd::fast {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

inline void cswap_asc(double& a, double& b) {
  const double lo = std::min(a, b), hi = std::max(a, b);
  a = lo;
  b = hi;
}

// Sorting network, ascending, n <= 4.
inline void sort_small(double* v, int n) {
  if (n == 2) {
    cswap_asc(v[0], v[1]);
  } else if (n == 3) {
    cswap_asc(v[0], v[1]);
    cswap_asc(v[1], v[2]);
    cswap_asc(v[0], v[1]);
  } else if (n == 4) {
    cswap_asc(v[0], v[1]);
    cswap_asc(v[2], v[3]);
    cswap_asc(v[0], v[2]);
    cswap_asc(v[1], v[3]);
    cswap_asc(v[1], v[2]);
  }
}

inline void sort_small_desc(double* v, int n) {
  for (int i = 0; i < n; ++i) v[i] = -v[i];
  sort_small(v, n);
  for (int i = 0; i < n; ++i) v[i] = -v[i];
}

// A side at plane offset c with constrained (ncon at hcon) and the first k of f active.
// Returns sum_active (c − H)² + (sum_active (c − H))² / (5 − m), writes S = sum/(5 − m).
// (The sum form avoids cancellation in m c − P.)
inline double side_cost(int ncon, double hcon, const double* f, int k, double c, double* S) {
  const double dc = c - hcon;
  double s1 = ncon * dc, s2 = ncon * dc * dc;
  for (int i = 0; i < k; ++i) {
    const double d = c - f[i];
    s1 += d;
    s2 += d * d;
  }
  *S = s1 / (5 - ncon - k);
  return s2 + s1 * *S;
}

struct SortedSide {
  int ncon;
  double hcon;
  int nfree;
  double f[4];
};

// The merged-breakpoint walk of the header. fa sorted descending, fb ascending.
DirectionSolution two_sided(const SortedSide& A, const SortedSide& B) {
  int kA = A.nfree, kB = 0;
  int mA = A.ncon + A.nfree, mB = B.ncon;
  double PA = A.ncon * A.hcon, PB = B.ncon * B.hcon;
  for (int i = 0; i < A.nfree; ++i) PA += A.f[i];
  double X = 0.0;
  while (kA > 0 || kB < B.nfree) {
    const double XA = kA > 0 ? (5 - mA) * A.f[kA - 1] + PA : kInf;
    const double XB = kB < B.nfree ? (5 - mB) * B.f[kB] + PB : kInf;
    const bool takeA = XA <= XB;
    X = takeA ? XA : XB;
    if ((mA * X - 5 * PA) * (5 - mB) + (mB * X - 5 * PB) * (5 - mA) >= 0) break;
    if (takeA) {
      --kA;
      --mA;
      PA -= A.f[kA];
    } else {
      PB += B.f[kB];
      ++kB;
      ++mB;
    }
  }
  DirectionSolution s;
  const int den = mA * (5 - mB) + mB * (5 - mA);
  s.c = den == 0 ? X / 5 : (PA * (5 - mB) + PB * (5 - mA)) / den;
  s.cost = side_cost(A.ncon, A.hcon, A.f, kA, s.c, &s.sumA) +
           side_cost(B.ncon, B.hcon, B.f, kB, s.c, &s.sumB);
  return s;
}

SortedSide sorted(const SideProblem& p, bool descending) {
  SortedSide s{p.ncon, p.hcon, p.nfree, {p.hfree[0], p.hfree[1], p.hfree[2], p.hfree[3]}};
  if (descending)
    sort_small_desc(s.f, s.nfree);
  else
    sort_small(s.f, s.nfree);
  return s;
}

// Root of S_B alone (B ascending): minimiser of phi_B; −inf when S_B = 0 on a half-line.
double root_of_side(const SortedSide& B) {
  int kB = 0, mB = B.ncon;
  double PB = B.ncon * B.hcon;
  if (mB == 0) return -kInf;  // phi_B = 0 for all c <= min free height
  while (kB < B.nfree) {
    const double X = (5 - mB) * B.f[kB] + PB;
    if (mB * X - 5 * PB >= 0) break;
    PB += B.f[kB];
    ++kB;
    ++mB;
  }
  return PB / mB;
}

}  // namespace

DirectionSolution solve_deformable(const SideProblem& A, const SideProblem& B) {
  return two_sided(sorted(A, true), sorted(B, false));
}

DirectionSolution solve_static(const SideProblem& A, const SideProblem& B) {
  const SortedSide sb = sorted(B, false);
  DirectionSolution s;
  if (A.ncon > 0) {
    s.c = A.hcon;
  } else {
    double amax = -kInf;
    for (int i = 0; i < A.nfree; ++i) amax = std::max(amax, A.hfree[i]);
    s.c = std::max(amax, root_of_side(sb));
  }
  int kB = 0;
  double PB = sb.ncon * sb.hcon;
  while (kB < sb.nfree && (5 - sb.ncon - kB) * sb.f[kB] + PB <= 5 * s.c) PB += sb.f[kB++];
  s.cost = side_cost(sb.ncon, sb.hcon, sb.f, kB, s.c, &s.sumB);
  return s;
}

DirectionSolution solve_relaxed(const double hA[4], const double hB[4]) {
  SortedSide a{0, 0.0, 4, {hA[0], hA[1], hA[2], hA[3]}};
  SortedSide b{0, 0.0, 4, {hB[0], hB[1], hB[2], hB[3]}};
  sort_small_desc(a.f, 4);
  sort_small(b.f, 4);
  return two_sided(a, b);
}

}  // namespace pdd::fast
