// solve_exact.h — the exact engine's answer for one pair: the definitions §6 record.
//
// Input : a pair of tetrahedra (doubles, taken exactly) and the options of pdd.h.
// Output: PairResult<Rational>: intersecting; rigid PD^2 (Minkowski difference, definitions §4) and
//         its direction (first candidate attaining min delta); E11^2 (eq. 11); PD_d^2 for
//         static, deformable, relaxed (minimum over candidates, first in canonical order
//         among ties) and accel1/accel6 (case 2 on the 1/6 shallowest candidates, case 3);
//         q1_A, q1_B attaining pdd2; definitions §9's pdd2_global with its witness normal, positions
//         and proved lower bound (global_pdd.h), and on request its gradient (pdd.h). A
//         rejected pair has `error` set (definitions §1).
#pragma once

#include "pdd/pair_result.h"
#include "pdd/solve_options.h"
#include "pdd/reference/direction_qp.h"
#include "pdd/reference/exact_kernel.h"
#include "pdd/reference/global_pdd.h"

namespace pdd::reference {

using ExactResult = PairResult<Rational>;

// `options`: pdd.h's (formulation, with_global, gradient). `budget`: the branch and bound's
// target gap and limits (global_pdd.h; its `floor` is set here, PD^2 / 32).
ExactResult solve_exact(const TetPair& pair, const SolveOptions& options = {},
                        const GlobalOptions& budget = {});

}  // namespace pdd::reference
