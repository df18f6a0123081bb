// bench.cpp — see bench.h for the method.
#include "pdd/compare/bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <stdexcept>

#include "kernel/superset_depth.h"  // fast/src (pdd_fast_internal): the uncertified baseline
#include "pdd/compare/engine_comparison.h"
#include "pdd/compare/generate.h"
#include "pdd/compare/peer_ccd.h"
#include "pdd/compare/peer_fcl.h"
#include "pdd/compare/stats.h"
#include "pdd/io/progress.h"
#include "pdd/pdd.h"
#include "pdd/reference/minkowski_pd.h"
#include "pdd/reference/solve_exact.h"

namespace pdd::compare {
using io::Progress;
namespace {

using Clock = std::chrono::steady_clock;

double ns_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::nano>(b - a).count();
}

// Squared value a peer implies, with failures folded in for the error statistics.
double peer_relative_error(const PeerDepth& d, const reference::Rational& exact_pd2) {
  if (d.status == PeerStatus::Failed) return std::numeric_limits<double>::infinity();
  return relative_error(d.pd * d.pd, exact_pd2);
}

const VariantTiming& find_timing(const std::vector<VariantTiming>& v, const std::string& name) {
  for (const auto& t : v)
    if (t.name == name) return t;
  throw std::logic_error("no timing named " + name);
}

}  // namespace

MachineInfo bench_machine_info() {
  MachineInfo m = machine_info();
  m.fcl_version = fcl_version();
  m.ccd_version = ccd_version();
  return m;
}

BenchReport run_bench(const BenchOptions& o) {
  if (o.count == 0) throw std::invalid_argument("--count must be >= 1");
  if (o.repeats < 1) throw std::invalid_argument("--repeats must be >= 1");
  const auto start = Clock::now();
  BenchReport rep;
  rep.options = o;
  rep.machine = bench_machine_info();

  std::cerr << "pdd bench: generating " << o.count << " pairs (family paper, seed " << o.seed
            << ")\n";
  const std::vector<TetPair> pairs = generate_family("paper", o.seed, o.count);
  rep.pairs = pairs.size();
  const std::size_t M = std::min(o.exact_sample, pairs.size());

  // Our values on all pairs (the peers' reference for failures and deviations).
  std::vector<double> fast_pd2(pairs.size());
  std::vector<char> fast_inter(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    fast_pd2[k] = fast::rigid_pd2(pairs[k].A, pairs[k].B).pd2;
    fast_inter[k] = fast_pd2[k] > 0;
  }

  // ---- fast engine and peers, one core, interleaved passes ----
  std::cerr << "pdd bench: timing the fast engine and the peers (" << o.repeats
            << " passes each)\n";
  const FclPairs fcl_shapes(pairs);
  struct PeerSpec {
    std::string name, config;
    bool judged;
    std::function<PeerDepth(std::size_t)> depth;
  };
  const FclConfig fcl_default{FclSolver::Indep, 1e-6};
  const FclConfig fcl_tight{FclSolver::Indep, 1e-12};
  const FclConfig fcl_mpr{FclSolver::Libccd, 1e-6};
  const CcdConfig ccd_default{1e-4, ~0UL};
  const CcdConfig ccd_tight{1e-12, ~0UL};
  const std::vector<PeerSpec> specs = {
      {"FCL GJK/EPA (GST_INDEP)", "gjk_tolerance = epa_tolerance = 1e-6 (FCL default)", true,
       [&](std::size_t k) { return fcl_shapes.depth(k, fcl_default); }},
      {"FCL GJK/EPA (GST_INDEP), tight", "gjk_tolerance = epa_tolerance = 1e-12", false,
       [&](std::size_t k) { return fcl_shapes.depth(k, fcl_tight); }},
      {"FCL GJK/EPA, shapes built per call", "as the first FCL row, fcl::Convex construction timed too",
       false, [&](std::size_t k) { return fcl_penetration_depth(pairs[k].A, pairs[k].B, fcl_default); }},
      {"FCL default solver (GST_LIBCCD = MPR)", "collision_tolerance = 1e-6; MPR depth, not PD",
       false, [&](std::size_t k) { return fcl_shapes.depth(k, fcl_mpr); }},
      {"libccd GJK+EPA (ccdGJKPenetration)", "epa_tolerance = 1e-4 (libccd default)", true,
       [&](std::size_t k) { return ccd_penetration_depth(pairs[k].A, pairs[k].B, ccd_default); }},
      {"libccd GJK+EPA, tight", "epa_tolerance = 1e-12", false,
       [&](std::size_t k) { return ccd_penetration_depth(pairs[k].A, pairs[k].B, ccd_tight); }},
      {"libccd MPR (ccdMPRPenetration)", "mpr_tolerance = 1e-4 (libccd default); not PD", false,
       [&](std::size_t k) { return ccd_mpr_depth(pairs[k].A, pairs[k].B, 1e-4); }},
  };

  std::vector<TimedFunction> fns = fast_timed_functions(pairs);
  const std::size_t n_fast = fns.size();
  fns.push_back({"rigid_pd2, no certification", [&pairs](std::size_t k) {
                   fast::Choice ch;
                   return fast::rigid_superset_uncertified(pairs[k].A, pairs[k].B, ch) ? ch.value : 0.0;
                 }});
  const std::size_t n_uncertified = fns.size() - 1;
  for (const auto& s : specs) {
    auto depth = s.depth;
    fns.push_back({s.name, [depth](std::size_t k) { return depth(k).pd; }});
  }
  const auto timings = time_functions(pairs.size(), fns, o.repeats);
  rep.fast.assign(timings.begin(), timings.begin() + n_fast);
  const VariantTiming& ours = find_timing(rep.fast, "rigid_pd2");
  rep.certification.rigid_uncertified_ns = timings[n_uncertified].median_ns_per_pair;
  rep.certification.rigid_certified_ns = ours.median_ns_per_pair;

  // ---- peers: failures and deviations on all pairs, errors on the exact sample ----
  std::cerr << "pdd bench: exact PD² on a sample of " << M << " pairs\n";
  std::vector<reference::Rational> exact_pd2(M);
  std::vector<double> exact_rigid_ns;
  for (int r = 0; r < o.repeats; ++r) {
    const auto ns = time_each_call(M, [&](std::size_t k) {
      auto mk = reference::minkowski_pd(reference::to_exact(pairs[k]));
      if (r == 0) exact_pd2[k] = mk.pd2;
    });
    exact_rigid_ns.insert(exact_rigid_ns.end(), ns.begin(), ns.end());
  }

  for (std::size_t i = 0; i < specs.size(); ++i) {
    PeerReport p;
    p.name = specs[i].name;
    p.config = specs[i].config;
    p.judged = specs[i].judged;
    p.timing = timings[n_uncertified + 1 + i];
    p.time_ratio = p.timing.median_ns_per_pair / ours.median_ns_per_pair;
    p.call_ratio = p.timing.median_call_ns / ours.median_call_ns;
    std::vector<double> err;
    p.max_rel_dev_vs_fast = -1;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const PeerDepth d = specs[i].depth(k);
      double dev = 0;
      if (d.status == PeerStatus::Failed) {
        ++p.failed;
        dev = std::numeric_limits<double>::infinity();
      } else {
        if (fast_inter[k] && (d.status == PeerStatus::NotIntersecting || d.pd == 0))
          ++p.not_intersecting;
        if (fast_pd2[k] > 0) dev = std::abs(d.pd * d.pd - fast_pd2[k]) / fast_pd2[k];
      }
      p.off_1e6 += dev > 1e-6;
      p.off_1e2 += dev > 1e-2;
      if (dev > p.max_rel_dev_vs_fast) {
        p.max_rel_dev_vs_fast = dev;
        p.worst_pair = pairs[k].name;
        p.worst_peer_pd2 = d.pd * d.pd;
        p.worst_fast_pd2 = fast_pd2[k];
      }
      if (k < M) err.push_back(peer_relative_error(d, exact_pd2[k]));
    }
    p.sample = M;
    if (M) {
      p.max_rel_error = *std::max_element(err.begin(), err.end());
      p.median_rel_error = median(err);
    }
    rep.peers.push_back(std::move(p));
  }

  // ---- our time against the exact engine's, on the sample ----
  ExactComparison& ex = rep.exact;
  ex.sample = M;
  if (M) {
    const std::vector<TetPair> sample(pairs.begin(), pairs.begin() + M);
    std::vector<TimedFunction> sf = fast_timed_functions(sample);
    std::vector<TimedFunction> two;
    for (auto& f : sf)
      if (f.name == "rigid_pd2" || f.name == "solve_pair") two.push_back(f);
    const auto st = time_functions(M, two, o.repeats);
    ex.fast_rigid_median_ns = find_timing(st, "rigid_pd2").median_ns_per_pair;
    ex.fast_solve_median_ns = find_timing(st, "solve_pair").median_ns_per_pair;
    ex.exact_rigid_median_ns = median(exact_rigid_ns);
    ex.rigid_ratio = ex.exact_rigid_median_ns / ex.fast_rigid_median_ns;

    std::vector<double> err;
    for (std::size_t k = 0; k < M; ++k) err.push_back(relative_error(fast_pd2[k], exact_pd2[k]));
    ex.fast_max_rel_error = *std::max_element(err.begin(), err.end());
    ex.fast_median_rel_error = median(err);

    std::cerr << "pdd bench: exact engine (reference::solve_exact, Reduced) on " << M
              << " pairs, one pass, one core\n";
    Progress progress("pdd bench: exact solve_pair", M);
    // (a call into another library that allocates: it cannot be elided)
    const std::vector<double> solve_ns = time_each_call(M, [&](std::size_t k) {
      (void)reference::solve_exact(sample[k], {QpFormulation::Reduced});
      progress.tick();
    });
    progress.finish();
    ex.exact_solve_median_ns = median(solve_ns);
    ex.solve_ratio = ex.exact_solve_median_ns / ex.fast_solve_median_ns;
  }

  // ---- the cost of the pairs that needed more than the double path (definitions §8) ----
  {
    CertificationCost& cc = rep.certification;
    std::vector<std::size_t> refined, slow;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const SolveStats s = fast::solve_pair(pairs[k]).stats;
      if (s.slow_path) slow.push_back(k);
      else if (s.refined) refined.push_back(k);
    }
    cc.refined = refined.size();
    cc.slow_paths = slow.size();
    double sum = 0;
    auto timed = [&](const std::vector<std::size_t>& which) {
      std::vector<double> all;
      for (int r = 0; r < o.repeats; ++r) {
        const auto ns = time_each_call(which.size(), [&](std::size_t i) {
          (void)fast::solve_pair(pairs[which[i]]);
        });
        all.insert(all.end(), ns.begin(), ns.end());
      }
      for (double x : all) sum += x / o.repeats;
      return all.empty() ? 0.0 : median(all);
    };
    cc.refined_median_ns = timed(refined);
    cc.slow_median_ns = timed(slow);
    const double total = find_timing(rep.fast, "solve_pair").median_ns_per_pair * double(pairs.size());
    cc.share_of_solve_pair = total > 0 ? sum / total : 0.0;
  }

  // ---- batch, all cores ----
  std::cerr << "pdd bench: batch API on all cores\n";
  rep.batch = time_batch(pairs, o.repeats);

  // ---- targets (pdd's speed targets): median per pair, one core ----
  auto add = [&](std::string what, std::string bound, double measured, bool pass) {
    rep.targets.push_back({std::move(what), std::move(bound), measured, pass});
  };
  const double rigid = ours.median_ns_per_pair;
  add("rigid_pd2 time per pair", "<= 250 ns", rigid, rigid <= 250);
  for (const auto& p : rep.peers)
    if (p.judged)
      add("rigid_pd2 speed-up over " + p.name, ">= 10x", p.time_ratio, p.time_ratio >= 10);
  const double st = find_timing(rep.fast, "pdd2_static").median_ns_per_pair;
  add("pdd2_static time per pair", "<= 1000 ns", st, st <= 1000);
  const double d2 = find_timing(rep.fast, "pdd2").median_ns_per_pair;
  add("pdd2 time per pair", "<= 1500 ns", d2, d2 <= 1500);
  const double a1 = find_timing(rep.fast, "pdd2_accel1").median_ns_per_pair;
  add("pdd2_accel1 time per pair", "<= 350 ns", a1, a1 <= 350);
  const double gl = find_timing(rep.fast, "pdd2_global").median_ns_per_pair;
  add("pdd2_global time per pair", "<= 5000 ns", gl, gl <= 5000);
  // the bound a simulator's Newton loop needs: the contact energy is built from pdd2_global
  add("pdd2_global time per pair, in a contact energy's Newton loop", "<= 3000 ns", gl, gl <= 3000);

  rep.machine.load_after = read_first_line("/proc/loadavg");
  rep.seconds = ns_between(start, Clock::now()) * 1e-9;
  return rep;
}

}  // namespace pdd::compare
