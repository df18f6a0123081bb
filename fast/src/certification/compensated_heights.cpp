// compensated_heights.cpp — see compensated_heights.h for the arithmetic and its bounds.
#include "certification/compensated_heights.h"

#include <cmath>

#include "certification/double_word.h"
#include "kernel/direction_geometry.h"

namespace pdd::fast::detail {
namespace {

using dw::add;
using dw::DW;
using dw::kU;
using dw::mul;
using dw::neg;
using dw::two_sum;

struct DV {
  DW x[3];
};
DV diff(const std::array<double, 3>& p, const std::array<double, 3>& o) {  // exact
  return {{two_sum(p[0], -o[0]), two_sum(p[1], -o[1]), two_sum(p[2], -o[2])}};
}

}  // namespace

bool compensated_heights(const TetVertices& A, const TetVertices& B, const Candidate& c,
                         CompensatedHeights& out) {
  if (c.parallel) return false;
  const DirectionLabel& l = c.label;
  // The direction's two spanning vectors e1, e2 (n* = e1 x e2 up to sign) and the origin o, a
  // vertex of the constrained set whose heights are exactly 0 (A's face or edge; B's face).
  const TetVertices* T = &A;
  std::array<double, 3> o, p1, p2, q1, q2;
  switch (l.kind) {
    case ContactKind::FV:
    case ContactKind::VF: {
      T = l.kind == ContactKind::FV ? &A : &B;
      const auto& f = kFace[l.a];
      o = (*T)[f[0]], p1 = (*T)[f[1]], q1 = o, p2 = (*T)[f[2]], q2 = o;
      break;
    }
    default: {
      const int u = kEdges[l.a][0], v = kEdges[l.a][1], x = kEdges[l.b][0], y = kEdges[l.b][1];
      o = A[u], p1 = B[y], q1 = B[x], p2 = A[v], q2 = A[u];  // eB x eA (definitions §3)
      break;
    }
  }
  const DV e1 = diff(p1, q1), e2 = diff(p2, q2);
  DW n[3];
  double N[3];  // |e1_r e2_s| + |e1_s e2_r| from the high parts
  for (int k = 0; k < 3; ++k) {
    const int r = (k + 1) % 3, s = (k + 2) % 3;
    n[k] = add(mul(e1.x[r], e2.x[s]), neg(mul(e1.x[s], e2.x[r])));
    N[k] = std::fabs(e1.x[r].hi * e2.x[s].hi) + std::fabs(e1.x[s].hi * e2.x[r].hi);
  }
  constexpr double kGrow = 1 + 0x1p-40;  // the bounds' own roundings (header)
  for (int k = 0; k < 3; ++k) out.n[k] = n[k].hi;
  // orientation: the candidate's (c.n approximates +-n*; their product is ~|n|^2 either way)
  const double orient = out.n[0] * c.n[0] + out.n[1] * c.n[1] + out.n[2] * c.n[2];
  if (!(std::fabs(orient) > 0) || !std::isfinite(orient)) return false;
  const double sign = orient > 0 ? 1.0 : -1.0;
  out.e_n = 0;
  for (int k = 0; k < 3; ++k) {
    out.n[k] *= sign;
    out.e_n = std::fmax(out.e_n, (kU * std::fabs(out.n[k]) * (1 + kU) + 10.5 * kU * kU * N[k]) * kGrow);
  }
  out.nn = out.n[0] * out.n[0] + out.n[1] * out.n[1] + out.n[2] * out.n[2];
  if (!(out.nn > 0) || !std::isfinite(out.nn)) return false;
  auto height = [&](const std::array<double, 3>& x, double& h, double& e) {
    const DV d = diff(x, o);
    DW s = mul(n[0], d.x[0]);
    s = add(s, mul(n[1], d.x[1]));
    s = add(s, mul(n[2], d.x[2]));
    const double M = N[0] * std::fabs(d.x[0].hi) + N[1] * std::fabs(d.x[1].hi) + N[2] * std::fabs(d.x[2].hi);
    h = sign * s.hi;
    e = (kU * std::fabs(h) + 25 * kU * kU * M) * kGrow + 0x1p-1040;
  };
  for (int i = 0; i < 4; ++i) {
    height(A[i], out.hA[i], out.eA[i]);
    height(B[i], out.hB[i], out.eB[i]);
  }
  // Constrained vertices: exactly on the plane through o (0), or (B's edge of an edge pair)
  // at one common height, that of its first vertex.
  for (int i = 0; i < 4; ++i) {
    if (l.kind == ContactKind::FV && (c.conA >> i & 1u)) out.hA[i] = 0, out.eA[i] = 0;
    if (l.kind == ContactKind::VF && (c.conB >> i & 1u)) out.hB[i] = 0, out.eB[i] = 0;
    if (l.kind == ContactKind::EE && (c.conA >> i & 1u)) out.hA[i] = 0, out.eA[i] = 0;
  }
  if (l.kind == ContactKind::EE) {
    const int x = kEdges[l.b][0], y = kEdges[l.b][1];
    out.hB[y] = out.hB[x], out.eB[y] = out.eB[x];
  }
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(out.hA[i]) || !std::isfinite(out.hB[i]) || !std::isfinite(out.eA[i]) ||
        !std::isfinite(out.eB[i]))
      return false;
  return true;
}

bool compensated_heights_along(const TetVertices& A, const TetVertices& B, const std::array<double, 3>& v,
                               CompensatedHeights& out) {
  int top = 0;
  double best = -INFINITY;
  for (int i = 0; i < 4; ++i) {
    const double h = v[0] * (A[i][0] - A[0][0]) + v[1] * (A[i][1] - A[0][1]) + v[2] * (A[i][2] - A[0][2]);
    if (h > best) best = h, top = i;  // (a heuristic choice: any vertex is a valid origin)
  }
  const std::array<double, 3> o = A[top];
  for (int k = 0; k < 3; ++k) out.n[k] = v[k];
  out.e_n = 0;
  out.nn = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  if (!(out.nn > 0) || !std::isfinite(out.nn)) return false;
  constexpr double kGrow = 1 + 0x1p-40;  // the bounds' own roundings (header)
  // A height v.(x − o): the difference exact (two_sum), three products of a double and a
  // double word (mul, at most the header's 6.2 u^2 each) and two adds: within the header's
  // 25 u^2 M, M = sum |v_k| |d_k| (no normal error here), then rounded to its high part (u).
  auto height = [&](const std::array<double, 3>& x, double& h, double& e) {
    const DV d = diff(x, o);
    DW s = mul(DW{v[0], 0.0}, d.x[0]);
    s = add(s, mul(DW{v[1], 0.0}, d.x[1]));
    s = add(s, mul(DW{v[2], 0.0}, d.x[2]));
    const double M = std::fabs(v[0] * d.x[0].hi) + std::fabs(v[1] * d.x[1].hi) + std::fabs(v[2] * d.x[2].hi);
    h = s.hi;
    e = (kU * std::fabs(h) + 25 * kU * kU * M) * kGrow + 0x1p-1040;
  };
  for (int i = 0; i < 4; ++i) {
    height(A[i], out.hA[i], out.eA[i]);
    height(B[i], out.hB[i], out.eB[i]);
  }
  out.hA[top] = 0, out.eA[top] = 0;  // the origin itself: exactly 0
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(out.hA[i]) || !std::isfinite(out.hB[i]) || !std::isfinite(out.eA[i]) ||
        !std::isfinite(out.eB[i]))
      return false;
  return true;
}

}  // namespace pdd::fast::detail
