// aligned_bench.h — `pdd bench --family aligned`: the fast engine per pair on the aligned family
// of `pdd generate` (elements of structured meshes against a shifted copy: parallel faces and
// edges, exactly touching faces) beside the same pairs with B rotated by a generic angle, in the
// same run, timed by timing.h's protocol.
//
// Input:  AlignedBenchOptions (defaults in the struct).
// Output: AlignedBenchReport: per case (every pair, then each kind of the family: kuhn-shifted,
//         five-shifted, stacked), for the aligned pairs and for the rotated ones, the time per
//         pair of the exact decision (pdd::fast::interiors_intersect) and of each fast variant
//         (timing.h's fast_timed_functions: rigid_pd2 .. pdd2_global, solve_pair), and
//         solve_pair's record statistics (PairResult::stats: slow_path = the exact path or
//         pdd2_global in rationals, refined = a few candidates evaluated in rationals); the
//         ratio aligned / rotated per row (target: at most 2).
// The rotated pair of aligned pair k: B rotated by `angle` about `axis` through B's vertex
// centroid (each coordinate rounded once), A unchanged: no face or edge of B parallel to A's.
// Pairs whose rotated B no longer meets A's interior (exact decision) are left out of both sets,
// so that both time the same pairs, all intersecting; `dropped` counts them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "pdd/compare/timing.h"
#include "pdd/tet_pair.h"

namespace pdd::compare {

struct AlignedBenchOptions {
  std::size_t count = 3000;  // pairs of the aligned family drawn (before the rotated ones are checked)
  std::uint64_t seed = 1;
  int repeats = 5;
  double angle = 0.3;                       // radians
  std::array<double, 3> axis = {1, 2, 3};   // rotation axis (need not be unit)
};

// One set of pairs (aligned, or rotated) of one case.
struct AlignedPairSet {
  std::vector<VariantTiming> timings;  // interiors_intersect, then fast_timed_functions' order
  std::size_t slow_path = 0, refined = 0;  // solve_pair's record statistics, pairs
};

struct AlignedPairCase {
  std::string name;  // "all", or a kind tag of the family
  std::size_t pairs = 0;
  AlignedPairSet aligned, rotated;
};

struct AlignedBenchReport {
  AlignedBenchOptions options;
  MachineInfo machine;
  std::size_t drawn = 0, dropped = 0;  // pairs drawn; left out (rotated B disjoint)
  std::vector<AlignedPairCase> cases;
  double seconds = 0;
};

// B of `pair` rotated by `angle` about `axis` through B's vertex centroid.
TetPair rotated_b(const TetPair& pair, double angle, const std::array<double, 3>& axis);

// Runs everything (progress on stderr). Throws std::invalid_argument on bad options.
AlignedBenchReport run_aligned_bench(const AlignedBenchOptions& options);

}  // namespace pdd::compare
