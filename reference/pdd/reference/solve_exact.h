// solve_exact.h — the exact engine's answer for one pair: the SPEC §6 record.
//
// Input : a pair of tetrahedra (doubles, taken exactly) and the QP formulation to use.
// Output: PairResult<Rational>: intersecting; rigid PD^2 (Minkowski difference, SPEC §4) and
//         its direction (first candidate attaining min delta); E11^2 (eq. 11); PD_d^2 for
//         static, deformable, relaxed (minimum over candidates, first in canonical order
//         among ties) and accel1/accel6 (case 2 on the 1/6 shallowest candidates, case 3);
//         q1_A, q1_B attaining pdd2; SPEC §9's pdd2_global with its witness normal, positions
//         and proved lower bound (global_pdd.h). A rejected pair has `error` set (SPEC §1).
#pragma once

#include <cstddef>

#include "pdd/pair_result.h"
#include "pdd/reference/direction_qp.h"
#include "pdd/reference/exact_kernel.h"

namespace pdd::reference {

using ExactResult = PairResult<Rational>;

struct SolveOptions {
  QpFormulation formulation = QpFormulation::Full;
  bool global = true;  // SPEC §9 (pdd2_global and its keys); false leaves them 0 / null
  Rational global_gap = Rational(1) / Rational(1000000000000LL);  // 1e-12: SPEC §9's target
  std::size_t global_max_exact_patches = 1000;  // GlobalOptions::max_exact_patches
  std::size_t global_max_hull_bounds = 1000;    // GlobalOptions::max_hull_bounds
};

ExactResult solve_exact(const TetPair& pair, const SolveOptions& options = {});

}  // namespace pdd::reference
