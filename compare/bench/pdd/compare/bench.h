// bench.h — `pdd bench`: speed of the fast engine, of two peers (FCL, libccd) and of the
// exact engine, on the same pairs in the same process, timed by timing.h's protocol; and the
// peers' errors against the exact engine. The only part of pdd that links FCL and libccd.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "pdd/compare/timing.h"
#include "pdd/tet_pair.h"

namespace pdd::compare {

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
  // Every definitions §6 value: reference::solve_exact (Reduced formulation, one pass) vs
  // fast::solve_pair on the same sample.
  double exact_solve_median_ns = 0;
  double fast_solve_median_ns = 0;
  double solve_ratio = 0;
  // Our own rigid PD² against the exact one on the sample.
  double fast_max_rel_error = 0, fast_median_rel_error = 0;
};

// definitions §8 certification: how many pairs needed more than the double path, and what they
// cost. Refined pairs evaluate a few candidates exactly; slow-path pairs take the whole exact path.
// Their time is measured per call (fast::solve_pair, one core) and set against the time of
// solve_pair over all pairs (median pass time × pairs): the share of the total they take.
// The bound checks of the double path itself run on every pair, inside the same functions, and
// are not timed apart.
struct CertificationCost {
  std::size_t refined = 0, slow_paths = 0;
  double refined_median_ns = 0, slow_median_ns = 0;  // median solve_pair call on those pairs
  double share_of_solve_pair = 0;  // (sum of their calls) / (solve_pair time over all pairs)
  // The certification of rigid_pd2 on every pair: rigid_pd2 against the same kernel and pick
  // with no certification at all (no rescaling, no certify pass, no exact path; fast/src/
  // superset_depth.h's rigid_superset_uncertified), timed in the same passes (ns per pair,
  // median over passes). The bound lanes the kernel computes beside the values are in both.
  double rigid_uncertified_ns = 0, rigid_certified_ns = 0;
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
  CertificationCost certification;
  std::vector<BenchTarget> targets;
  double seconds = 0;                // whole run
};

// Runs everything (progress on stderr). Throws std::invalid_argument on bad options.
BenchReport run_bench(const BenchOptions& options);

// machine_info() with the FCL and libccd versions.
MachineInfo bench_machine_info();

}  // namespace pdd::compare
