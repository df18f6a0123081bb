// public_api.cpp — pdd::reference::solve_pair of pdd.h: the engine's record (solve_exact.h,
// CGAL::Gmpq inside the engine) converted to the public rational type (GMP's mpq_class) at the
// boundary. Both are GMP rationals in lowest terms: the conversion copies, it never rounds.
#include "pdd/pdd.h"
#include "pdd/reference/solve_exact.h"

namespace pdd::reference {
namespace {

pdd::Rational to_public(const Rational& q) { return pdd::Rational(q.mpq()); }

Positions<pdd::Rational> to_public(const Positions<Rational>& p) {
  Positions<pdd::Rational> out;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) out[i][k] = to_public(p[i][k]);
  return out;
}

}  // namespace

PairResult<pdd::Rational> solve_pair(const TetPair& pair, const SolveOptions& options) {
  const ExactResult e = solve_exact(pair, options);
  PairResult<pdd::Rational> r;
  r.name = e.name;
  r.error = e.error;
  r.intersecting = e.intersecting;
  r.rigid_pd2 = to_public(e.rigid_pd2);
  r.eq11_pd2 = to_public(e.eq11_pd2);
  r.pdd2_static = to_public(e.pdd2_static);
  r.pdd2 = to_public(e.pdd2);
  r.pdd2_relaxed = to_public(e.pdd2_relaxed);
  r.pdd2_accel1 = to_public(e.pdd2_accel1);
  r.pdd2_accel6 = to_public(e.pdd2_accel6);
  r.rigid_dir = e.rigid_dir;
  r.pdd2_static_dir = e.pdd2_static_dir;
  r.pdd2_dir = e.pdd2_dir;
  r.pdd2_relaxed_dir = e.pdd2_relaxed_dir;
  r.q1_A = to_public(e.q1_A);
  r.q1_B = to_public(e.q1_B);
  r.pdd2_global = to_public(e.pdd2_global);
  if (e.pdd2_global_normal) {
    const auto& n = *e.pdd2_global_normal;
    r.pdd2_global_normal = std::array<pdd::Rational, 3>{to_public(n[0]), to_public(n[1]), to_public(n[2])};
  }
  r.q1_A_global = to_public(e.q1_A_global);
  r.q1_B_global = to_public(e.q1_B_global);
  if (e.pdd2_global_lower) r.pdd2_global_lower = to_public(*e.pdd2_global_lower);
  if (e.pdd2_global_grad) {
    PairGradient<pdd::Rational> g;
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k) g[i][k] = to_public((*e.pdd2_global_grad)[i][k]);
    r.pdd2_global_grad = g;
  }
  return r;
}

}  // namespace pdd::reference
