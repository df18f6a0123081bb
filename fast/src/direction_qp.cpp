// direction_qp.cpp — closed-form per-direction QP on doubles; derivation and proof in the
// header, the algorithm (written once for doubles and rationals) in src/direction_qp_impl.h.
#include "direction_qp.h"

#include "direction_qp_impl.h"

namespace pdd::fast {
namespace {

using detail::SideT;
using detail::SolutionT;

SideT<double> side(const SideProblem& p) {
  SideT<double> s;
  s.ncon = p.ncon;
  s.hcon = p.hcon;
  s.nfree = p.nfree;
  for (int i = 0; i < 4; ++i) s.f[i] = p.hfree[i];
  return s;
}

DirectionSolution solution(const SolutionT<double>& t) { return {t.cost, t.c, t.sumA, t.sumB}; }

}  // namespace

DirectionSolution solve_deformable(const SideProblem& A, const SideProblem& B) {
  return solution(detail::solve_deformable_sorted(side(A), side(B)));
}

DirectionSolution solve_static(const SideProblem& A, const SideProblem& B) {
  return solution(detail::solve_static_sides(side(A), side(B)));
}

DirectionSolution solve_relaxed(const double hA[4], const double hB[4]) {
  return solution(detail::solve_relaxed_heights(hA, hB));
}

}  // namespace pdd::fast
