// engines.h — running an engine over the entries of a fixture file, in input order.
//
// Malformed entries become error records without reaching an engine; every other pair is
// computed even when some are rejected (SPEC §1). The reference engine runs pairs in
// parallel with TBB (GMP and CGAL's exact types are thread-safe per object).
#pragma once

#include <vector>

#include "pdd/compare/fixture_io.h"
#include "pdd/compare/result_json.h"
#include "pdd/pair_result.h"
#include "pdd/reference/solve_pair.h"

namespace pdd::compare {

std::vector<reference::ExactResult> run_reference(const std::vector<FixtureEntry>& entries,
                                                  const reference::SolveOptions& options,
                                                  bool show_progress);

// The fast engine over the same entries: malformed entries become error records, the rest go
// through pdd::fast::solve_batch (all cores), results in input order.
std::vector<PairResult<double>> run_fast(const std::vector<FixtureEntry>& entries);

// SPEC §6 record of a fast result: numbers as JSON numbers that read back to the same double.
Json fast_record(const PairResult<double>& r);

// SPEC §6 record of an exact result: every number as an exact "p/q" string.
Json exact_record(const reference::ExactResult& r);

}  // namespace pdd::compare
