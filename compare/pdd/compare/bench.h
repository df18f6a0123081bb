// bench.h — speed of the fast engine, of two peers (FCL, libccd) and of the exact engine, on
// the same pairs in the same process (`pdd bench`; reusable by other commands).
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
// Speed is never asserted in tests; it is reported here, as medians and ratios.
#pragma once

#include <cstddef>
#include <cstdint>
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

// The fast engine from raw vertices, one core: rigid_pd2, pdd2_static, pdd2, pdd2_relaxed,
// pdd2_accel1, pdd2_accel6 (pdd::fast convenience overloads), and solve_pair (every SPEC §6
// value of the pair), in that order, named so.
std::vector<VariantTiming> time_fast_variants(const std::vector<TetPair>& pairs, int repeats);

// The batch API (pdd::fast::solve_batch, TBB on all cores) over the whole set.
struct BatchTiming {
  std::size_t pairs = 0;
  int threads = 0;               // TBB's default concurrency
  int repeats = 0;
  double median_seconds = 0;     // one solve_batch call over all pairs, median over repeats
  double pairs_per_second = 0;   // pairs / median_seconds
  std::size_t slow_paths = 0;    // pairs that took the fast engine's exact path (SPEC §8)
};
BatchTiming time_batch(const std::vector<TetPair>& pairs, int repeats);

// ---- `pdd bench` as a whole ------------------------------------------------------------

struct BenchOptions {
  std::size_t count = 10000;       // pairs of the paper's protocol (generate_family "paper")
  std::uint64_t seed = 1;
  int repeats = 5;
  std::size_t exact_sample = 200;  // the first M pairs are also solved by the exact engine
};

// One peer configuration, timed on all pairs and judged on the exact sample.
struct PeerReport {
  std::string name;    // e.g. "FCL GJK/EPA (GST_INDEP)"
  std::string config;  // its tolerances, in words
  bool judged = false; // counts toward the ">= 10x" target (false: informational row)
  VariantTiming timing;
  double time_ratio = 0;       // peer median_ns_per_pair / our rigid_pd2's
  double call_ratio = 0;       // the same on median_call_ns
  // On all pairs (every pair of the protocol intersects, decided exactly by the fast engine):
  std::size_t not_intersecting = 0;  // peer said "no intersection" (or depth 0)
  std::size_t failed = 0;            // peer error code or non-finite depth
  double max_rel_dev_vs_fast = 0;    // max |pd²_peer − pd²_fast| / pd²_fast over all pairs
  std::size_t off_1e6 = 0, off_1e2 = 0;  // pairs with that deviation > 1e-6, > 1e-2 (failures
                                         // included); ours is within 1e-10 of exact (tests)
  std::string worst_pair;            // the pair attaining max_rel_dev_vs_fast
  double worst_peer_pd2 = 0, worst_fast_pd2 = 0;
  // On the exact sample: relative error of PD² against the exact PD² (failures included:
  // "not intersecting" counts as relative error 1, a failure as +inf).
  std::size_t sample = 0;
  double max_rel_error = 0, median_rel_error = 0;
};

struct ExactComparison {
  std::size_t sample = 0;
  // Exact rigid PD² (reference::minkowski_pd: exact hull of the 16 differences) vs ours.
  double exact_rigid_median_ns = 0;  // median single call, over `repeats` passes of the sample
  double fast_rigid_median_ns = 0;   // our rigid_pd2 on the same sample (median_ns_per_pair)
  double rigid_ratio = 0;            // exact / fast
  // Every SPEC §6 value: reference::solve_exact (Reduced formulation, one pass) vs
  // fast::solve_pair on the same sample.
  double exact_solve_median_ns = 0;
  double fast_solve_median_ns = 0;
  double solve_ratio = 0;
  // Our own rigid PD² against the exact one on the sample.
  double fast_max_rel_error = 0, fast_median_rel_error = 0;
};

struct MachineInfo {
  std::string cpu_model;
  unsigned logical_cpus = 0;
  std::string compiler;
  bool assertions = false;        // NDEBUG not defined
  std::string load_before, load_after;  // /proc/loadavg
  std::string fcl_version, ccd_version;
};

struct BenchTarget {
  std::string what;       // e.g. "rigid_pd2 median per pair"
  std::string bound;      // e.g. "<= 250 ns"
  double measured = 0;    // ns, or a ratio
  bool pass = false;
};

struct BenchReport {
  BenchOptions options;
  MachineInfo machine;
  std::size_t pairs = 0;
  std::vector<VariantTiming> fast;   // time_fast_variants
  BatchTiming batch;
  std::vector<PeerReport> peers;
  ExactComparison exact;
  std::vector<BenchTarget> targets;
  double seconds = 0;                // whole run
};

// Runs everything (progress on stderr). Throws std::invalid_argument on bad options.
BenchReport run_bench(const BenchOptions& options);

MachineInfo bench_machine_info();

}  // namespace pdd::compare
