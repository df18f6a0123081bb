// family_global_cost.h — what the paper's restriction to the candidate directions costs
// (definitions §9) on the shipped fixture families, beside `pdd paper`'s numbers
// for the paper's protocol.
//
// Input : a fixtures folder (the repository's `fixtures/`): every `families/*.json` in it and
//         its golden file `golden/families/*.jsonl` (the exact engine's records, golden.h).
// Output: per family file, in name order: its pair count, how many intersect (exactly, from the
//         golden file), and paper_experiment.h's GlobalStats twice — from the fast engine (run
//         here on the file's pairs) and from the exact engine (read from the golden file: nothing
//         exact is recomputed). Pairs that do not intersect or that an engine rejects are
//         skipped by global_statistics, so a family of disjoint or touching pairs has none.
// Throws std::runtime_error naming the file when a family or golden file cannot be read, a
// family file has a malformed entry, or the two files do not have the same number of pairs.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "pdd/compare/paper_experiment.h"
#include "pdd/tet_pair.h"

namespace pdd::compare {

struct FamilyGlobalCost {
  std::string family;  // the file's stem, e.g. "sliver"
  std::size_t pairs = 0, intersecting = 0;
  GlobalStats fast, exact;
};

std::vector<FamilyGlobalCost> family_global_costs(const std::string& fixtures_dir);

// The pair's oriented candidate directions (definitions §3), rounded to doubles, for
// global_statistics' angle to the nearest candidate.
std::vector<std::array<double, 3>> candidate_normals_rounded(const TetPair& pair);

}  // namespace pdd::compare
