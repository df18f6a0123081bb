// direction_qp.cpp — closed-form per-direction QP on doubles; derivation and proof in the
// header, the algorithm (written once for doubles and rationals) in src/qp/direction_qp_impl.h.
#include "qp/direction_qp.h"

#include "qp/direction_qp_impl.h"

namespace pdd::fast {

DirectionSolution solve_deformable(const SideProblem& A, const SideProblem& B) {
  return detail::solve_deformable_sorted(A, B);
}

DirectionSolution solve_static(const SideProblem& A, const SideProblem& B) {
  return detail::solve_static_sides(A, B);
}

DirectionSolution solve_relaxed(const double hA[4], const double hB[4]) {
  return detail::solve_relaxed_heights(hA, hB);
}

}  // namespace pdd::fast
