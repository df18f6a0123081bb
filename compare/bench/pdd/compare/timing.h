// timing.h — the one benchmark protocol of pdd: how `pdd bench` and `pdd paper` time
// anything (the fast engine, the peers, the exact engine). No FCL or libccd here (bench.h).
//
// Method (no Google Benchmark dependency; the same idea):
//   * single core: every function runs in the calling thread, nothing pinned;
//   * one untimed warm-up pass over all pairs per function, then `repeats` timed passes, the
//     functions interleaved pass by pass (f1 f2 .. fn, f1 f2 .. fn, ...) so that a change of
//     machine load hits all of them alike;
//   * a pass = one call per pair, in order, cycling through all pairs (branch predictors are
//     not trained on one pair); its wall time / pair count is that pass's time per pair;
//     median_ns_per_pair = the median over the passes;
//   * in addition, `repeats` per-call passes time each call alone with steady_clock;
//     median_call_ns = the median over all those samples minus the median timer overhead
//     (two back-to-back clock reads, measured in the same passes): the median over pairs;
//   * each result is folded into a sink read through an empty asm barrier (DoNotOptimize), so
//     no call is elided; the functions live in other translation units (no LTO) anyway.
//   Calls go through std::function (~1–2 ns, the same for every row).
//   * a function too slow to repeat (the exact engine) is timed by time_each_call: one call
//     per item, in order, on the calling thread, each timed alone with steady_clock; the
//     caller reports the median over the calls.
// Every median here is stats.h's.
// Speed is never asserted in tests; it is reported here, as medians and ratios.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "pdd/tet_pair.h"

namespace pdd::compare {

struct VariantTiming {
  std::string name;
  double median_ns_per_pair = 0;  // median over passes of (pass wall time / pairs)
  double min_ns_per_pair = 0;     // fastest pass
  double max_ns_per_pair = 0;     // slowest pass
  double median_call_ns = 0;      // median single-call time, timer overhead subtracted
  int repeats = 0;
  std::size_t pairs = 0;
};

// A function timed over pair indices 0..count−1; it returns a value folded into the sink.
struct TimedFunction {
  std::string name;
  std::function<double(std::size_t)> call;
};

// Times every function as described above (interleaved passes). repeats >= 1.
std::vector<VariantTiming> time_functions(std::size_t count, const std::vector<TimedFunction>& fns,
                                          int repeats);

// The fast engine's functions as TimedFunctions over `pairs` (kept by reference), named and
// ordered as below.
std::vector<TimedFunction> fast_timed_functions(const std::vector<TetPair>& pairs);

// The fast engine from raw vertices, one core: rigid_pd2, pdd2_static, pdd2, pdd2_relaxed,
// pdd2_accel1, pdd2_accel6 (pdd::fast convenience overloads), and solve_pair (every definitions §6
// value of the pair), in that order, named so.
std::vector<VariantTiming> time_fast_variants(const std::vector<TetPair>& pairs, int repeats);

// The batch API (pdd::fast::solve_batch, TBB on all cores) over the whole set.
struct BatchTiming {
  std::size_t pairs = 0;
  int threads = 0;               // TBB's default concurrency
  int repeats = 0;
  double median_seconds = 0;     // one solve_batch call over all pairs, median over repeats
  double pairs_per_second = 0;   // pairs / median_seconds
  std::size_t slow_paths = 0;    // pairs that took the fast engine's exact path (definitions §8)
  std::size_t refined = 0;       // pairs refined instead (a few candidates evaluated exactly)
};
BatchTiming time_batch(const std::vector<TetPair>& pairs, int repeats);

// Calls `call(k)` for k = 0..count−1 in order on the calling thread, each timed alone
// (steady_clock); returns the nanoseconds of each call, in order.
std::vector<double> time_each_call(std::size_t count, const std::function<void(std::size_t)>& call);

struct MachineInfo {
  std::string cpu_model;
  unsigned logical_cpus = 0;
  std::string compiler;
  bool assertions = false;        // NDEBUG not defined
  std::string load_before, load_after;  // /proc/loadavg
  std::string fcl_version, ccd_version;  // filled by `pdd bench` (bench.h), empty otherwise
};

// The machine, compiler and load now (fcl_version and ccd_version left empty).
MachineInfo machine_info();

// The first line of a file ("" when it cannot be read), e.g. /proc/loadavg.
std::string read_first_line(const char* path);

}  // namespace pdd::compare
