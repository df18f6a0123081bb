// engines.h — running an engine over the entries of a fixture file, in input order.
//
// Malformed entries become error records without reaching an engine; every other pair is
// computed even when some are rejected (definitions §1). The reference engine runs pairs in
// parallel with TBB (GMP and CGAL's exact types are thread-safe per object).
#pragma once

#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "pdd/io/fixture_io.h"
#include "pdd/io/progress.h"
#include "pdd/io/result_json.h"
#include "pdd/pair_result.h"
#include "pdd/solve_options.h"
#include "pdd/reference/solve_exact.h"

namespace pdd::compare {

// Applies `compute(pair, index)` to every well-formed entry in parallel (TBB), in input order,
// with progress on stderr; a malformed entry becomes a default T with `name` and `error` set.
// T has members `name` and `error` (std::optional<std::string>).
// This form ticks a caller's `progress` (one Progress over several calls, e.g. chunks).
template <class T, class Compute>
std::vector<T> map_entries(const std::vector<io::FixtureEntry>& entries, io::Progress& progress,
                           Compute compute) {
  std::vector<T> out(entries.size());
  tbb::parallel_for(std::size_t{0}, entries.size(), [&](std::size_t k) {
    const io::FixtureEntry& e = entries[k];
    if (e.error) {
      out[k].name = e.pair.name;
      out[k].error = *e.error;
    } else {
      out[k] = compute(e.pair, k);
    }
    progress.tick();
  });
  return out;
}

template <class T, class Compute>
std::vector<T> map_entries(const std::vector<io::FixtureEntry>& entries, const std::string& what,
                           bool show_progress, Compute compute) {
  io::Progress progress(what, entries.size(), show_progress ? 2.0 : io::Progress::kNever);
  std::vector<T> out = map_entries<T>(entries, progress, compute);
  progress.finish();
  return out;
}

// reference::solve_exact on one pair, never throwing: an engine invariant that fails becomes
// the record's error ("internal error in the reference engine: ..."). `budget`: solve_exact's.
reference::ExactResult solve_reference(const TetPair& pair, const reference::SolveOptions& options,
                                       const reference::GlobalOptions& budget = {});

std::vector<reference::ExactResult> run_reference(const std::vector<io::FixtureEntry>& entries,
                                                  const reference::SolveOptions& options,
                                                  bool show_progress);
// The same, ticking the caller's `progress` once per entry.
std::vector<reference::ExactResult> run_reference(const std::vector<io::FixtureEntry>& entries,
                                                  const reference::SolveOptions& options,
                                                  io::Progress& progress);

// The fast engine over the same entries: malformed entries become error records, the rest go
// through pdd::fast::solve_batch (all cores) with `options`, results in input order.
std::vector<PairResult<double>> run_fast(const std::vector<io::FixtureEntry>& entries,
                                         const fast::SolveOptions& options = {});

// Every value and definitions §9: the default of fast_record and exact_record.
inline constexpr unsigned kEveryValue = (2u << kValueCount) - 1;

// The definitions §6 record of a fast result: numbers as JSON numbers that read back to the
// same double. `variants`: the values whose keys the record has (io::asked_keys, result_json.h:
// bit k < kValueCount the value kValueKeys[k], bit kValueCount definitions §9's keys), for
// results computed with only those. pdd2_global_grad is written when the result has it (the
// options asked for it) and §9 is asked.
io::Json fast_record(const PairResult<double>& r, unsigned variants = kEveryValue);

// definitions §6 record of an exact result: every number as an exact "p/q" string.
io::Json exact_record(const reference::ExactResult& r, unsigned variants = kEveryValue);

}  // namespace pdd::compare
