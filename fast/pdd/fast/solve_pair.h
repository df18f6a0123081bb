// solve_pair.h — every SPEC §6 quantity of one pair, and of a batch on all cores.
//
// Input:  TetPair (A = paper's T1, static in case 1; B = T2).
// Output: PairResult<double>:
//   error        set when A or B is invalid (SPEC §1): a non-finite coordinate, or zero volume
//                decided exactly (filtered orient3d, GMP fallback). Message names the
//                tetrahedron and the reason; the caller prefixes the pair name.
//   intersecting min delta > 0, decided exactly (candidate_directions.h).
//   rigid_pd2 + rigid_dir, eq11_pd2                      (rigid_depth.h, SPEC §4)
//   pdd2_static/_dir, pdd2/_dir, pdd2_relaxed/_dir,
//   pdd2_accel1, pdd2_accel6                             (deformable_depth.h, SPEC §5)
//   q1_A, q1_B   case-2 deformed positions along pdd2_dir.
// A non-intersecting pair: all values 0, labels empty, q1 = rest pose.
// solve_batch: same results, in input order, computed with TBB parallel_for.
#pragma once

#include <vector>

#include "pdd/pair_result.h"
#include "pdd/tet_pair.h"

namespace pdd::fast {

PairResult<double> solve_pair(const TetPair& pair);

std::vector<PairResult<double>> solve_batch(const std::vector<TetPair>& pairs);

}  // namespace pdd::fast
