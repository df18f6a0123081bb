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
// SPEC §8: every value is within 1e-9 relative of the exact one and every label names a
// candidate within that of the exact minimum. The pair is rescaled by a power of two (exact),
// computed in doubles with an error bound per value (value_bounds.h); where a bound is too wide
// the pair is recomputed on the exact path (src/exact_path.h: this engine's closed forms on GMP
// rationals). A result outside the normal double range: an error record saying so. The
// deformed positions attain pdd2 to 1e-9 relative up to the rounding of their coordinates
// (they are the exact positions rounded when the double path cannot certify them).
// solve_batch: same results, in input order, computed with TBB parallel_for.
#pragma once

#include <cstddef>
#include <vector>

#include "pdd/pair_result.h"
#include "pdd/tet_pair.h"

namespace pdd::fast {

// `slow_path` (optional): set when the pair took the exact path (SPEC §8).
PairResult<double> solve_pair(const TetPair& pair, bool* slow_path = nullptr);

// `slow_paths` (optional): the number of pairs that took the exact path.
std::vector<PairResult<double>> solve_batch(const std::vector<TetPair>& pairs,
                                            std::size_t* slow_paths = nullptr);

}  // namespace pdd::fast
