// bench_command.cpp — `pdd bench`: the speed table (bench.h; the protocol: timing.h).
//
// pdd bench [--count N] [--seed S] [--repeats R] [--exact-sample M] [--json [FILE]]   (bench.h)
// pdd bench --family aligned [--count N] [--seed S] [--repeats R] [--json [FILE]] (aligned_bench.h)
// pdd bench mesh [--a A --b B | --size N [--distance D] [--write-meshes DIR]]
//                [--variants LIST] [--aligned-cells N] [--repeats R] [--json [FILE]]  (mesh_bench.h)
// pdd bench resolve [--cases LIST] [--size N] [--shallow-distance D] [--deep-distance D]
//                   [--stacked-cells N] [--meshes DIR] [--cases-dir DIR] [--variants LIST] [--write DIR]
//                   [--max-rounds K] [--repeats R] [--json [FILE]]
//                                                                   (resolve_bench.h)
// pdd bench energy [--cases LIST] [--size N] [--grid-depth D] [--ball-distance D]
//                  [--stacked-cells N] [--repeats R] [--json [FILE]]  (energy_bench.h)
// Table on standard output. --json FILE also writes the same numbers as one JSON object to
// FILE; --json alone writes the JSON to standard output and the table to standard error.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "pdd/cli/cli_checks.h"
#include "pdd/cli/exit_codes.h"
#include "pdd/compare/aligned_bench.h"
#include "pdd/compare/bench.h"
#include "pdd/compare/energy_bench.h"
#include "pdd/compare/mesh_bench.h"
#include "pdd/compare/research_commands.h"
#include "pdd/io/output.h"
#include "pdd/io/result_json.h"
#include "pdd/compare/resolve_bench.h"

namespace pdd::compare {
using io::Json;
using io::check_writable;
using io::write_file;
namespace {

// --json [FILE] of every bench subcommand: where the JSON goes (set when the command runs).
struct JsonOutput {
  std::string path;  // empty or "-": standard output
  bool wanted = false;
};

struct BenchArgs {
  BenchOptions options;
  AlignedBenchOptions aligned;
  std::string family = "paper";
  JsonOutput json;
};

std::string fmt(const char* f, double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return "nan";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string pad(std::string s, std::size_t w) {
  // Width in code points, so that "²" and "µ" do not shift the columns.
  std::size_t cps = 0;
  for (unsigned char c : s) cps += (c & 0xC0) != 0x80;
  if (cps < w) s.append(w - cps, ' ');
  return s;
}
std::string rpad(const std::string& s, std::size_t w) {
  std::size_t cps = 0;
  for (unsigned char c : s) cps += (c & 0xC0) != 0x80;
  return cps < w ? std::string(w - cps, ' ') + s : s;
}

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

// The `machine` object of every bench JSON; the peers' versions where the command has peers.
Json machine_json(const MachineInfo& m) {
  Json j;
  j["cpu_model"] = m.cpu_model;
  j["logical_cpus"] = m.logical_cpus;
  j["compiler"] = m.compiler;
  j["assertions"] = m.assertions;
  j["loadavg_before"] = m.load_before;
  j["loadavg_after"] = m.load_after;
  if (!m.fcl_version.empty()) j["fcl_version"] = m.fcl_version;
  if (!m.ccd_version.empty()) j["ccd_cmake_config_version"] = m.ccd_version;
  return j;
}

Json timing_json(const VariantTiming& t) {
  Json j;
  j["name"] = t.name;
  j["median_ns_per_pair"] = number(t.median_ns_per_pair);
  j["min_ns_per_pair"] = number(t.min_ns_per_pair);
  j["max_ns_per_pair"] = number(t.max_ns_per_pair);
  j["median_call_ns"] = number(t.median_call_ns);
  j["repeats"] = t.repeats;
  j["pairs"] = t.pairs;
  return j;
}

Json report_json(const BenchReport& r) {
  Json j;
  j["command"] = "pdd bench";
  j["family"] = "paper";
  j["count"] = r.options.count;
  j["seed"] = r.options.seed;
  j["repeats"] = r.options.repeats;
  j["exact_sample"] = r.exact.sample;
  j["pairs"] = r.pairs;
  j["machine"] = machine_json(r.machine);
  j["fast"] = Json::array();
  for (const auto& t : r.fast) j["fast"].push_back(timing_json(t));
  Json b;
  b["threads"] = r.batch.threads;
  b["pairs"] = r.batch.pairs;
  b["repeats"] = r.batch.repeats;
  b["median_seconds"] = number(r.batch.median_seconds);
  b["pairs_per_second"] = number(r.batch.pairs_per_second);
  b["slow_paths"] = r.batch.slow_paths;
  b["refined"] = r.batch.refined;
  j["batch"] = b;
  j["peers"] = Json::array();
  for (const auto& p : r.peers) {
    Json q;
    q["name"] = p.name;
    q["config"] = p.config;
    q["judged"] = p.judged;
    q["timing"] = timing_json(p.timing);
    q["time_ratio_to_rigid_pd2"] = number(p.time_ratio);
    q["call_ratio_to_rigid_pd2"] = number(p.call_ratio);
    q["not_intersecting"] = p.not_intersecting;
    q["failed"] = p.failed;
    q["max_rel_dev_pd2_vs_fast_all_pairs"] = number(p.max_rel_dev_vs_fast);
    q["pairs_dev_over_1e-6"] = p.off_1e6;
    q["pairs_dev_over_1e-2"] = p.off_1e2;
    q["worst_pair"] = p.worst_pair;
    q["worst_pair_peer_pd2"] = number(p.worst_peer_pd2);
    q["worst_pair_fast_pd2"] = number(p.worst_fast_pd2);
    q["sample"] = p.sample;
    q["max_rel_error_pd2"] = number(p.max_rel_error);
    q["median_rel_error_pd2"] = number(p.median_rel_error);
    j["peers"].push_back(q);
  }
  const auto& e = r.exact;
  Json x;
  x["sample"] = e.sample;
  x["exact_minkowski_pd_median_ns"] = number(e.exact_rigid_median_ns);
  x["fast_rigid_pd2_median_ns"] = number(e.fast_rigid_median_ns);
  x["rigid_ratio"] = number(e.rigid_ratio);
  x["exact_solve_pair_reduced_median_ns"] = number(e.exact_solve_median_ns);
  x["fast_solve_pair_median_ns"] = number(e.fast_solve_median_ns);
  x["solve_ratio"] = number(e.solve_ratio);
  x["fast_rigid_max_rel_error_pd2"] = number(e.fast_max_rel_error);
  x["fast_rigid_median_rel_error_pd2"] = number(e.fast_median_rel_error);
  j["exact"] = x;
  const auto& cc = r.certification;
  Json c;
  c["refined_pairs"] = cc.refined;
  c["slow_path_pairs"] = cc.slow_paths;
  c["refined_median_solve_pair_ns"] = number(cc.refined_median_ns);
  c["slow_path_median_solve_pair_ns"] = number(cc.slow_median_ns);
  c["share_of_solve_pair_time"] = number(cc.share_of_solve_pair);
  c["rigid_pd2_ns"] = number(cc.rigid_certified_ns);
  c["rigid_pd2_uncertified_ns"] = number(cc.rigid_uncertified_ns);
  j["certification"] = c;
  j["targets"] = Json::array();
  for (const auto& t : r.targets) {
    Json q;
    q["what"] = t.what;
    q["bound"] = t.bound;
    q["measured"] = number(t.measured);
    q["pass"] = t.pass;
    j["targets"].push_back(q);
  }
  j["seconds"] = r.seconds;
  return j;
}

void print_table(const BenchReport& r, std::ostream& s) {
  const auto& m = r.machine;
  s << "pdd bench: " << r.pairs << " pairs of the paper's protocol (family paper, seed "
    << r.options.seed << "), " << r.options.repeats << " timed passes per row\n"
    << "machine:   " << m.cpu_model << ", " << m.logical_cpus << " logical CPUs; " << m.compiler
    << (m.assertions ? ", assertions ON" : ", NDEBUG") << "\n"
    << "load avg:  before " << m.load_before << "; after " << m.load_after << "\n"
    << "peers:     FCL " << m.fcl_version << ", libccd (its CMake config says " << m.ccd_version
    << ")\n\n";

  s << "Fast engine, one core, from raw vertices (ns per pair: median over passes of pass time /\n"
       "pairs, with the fastest and slowest pass; per call: median of single-call timings, timer\n"
       "overhead subtracted)\n";
  s << "  " << pad("variant", 14) << rpad("ns/pair", 10) << rpad("min", 9) << rpad("max", 9)
    << rpad("per call", 10) << "\n";
  for (const auto& t : r.fast)
    s << "  " << pad(t.name, 14) << rpad(fmt("%.1f", t.median_ns_per_pair), 10)
      << rpad(fmt("%.1f", t.min_ns_per_pair), 9) << rpad(fmt("%.1f", t.max_ns_per_pair), 9)
      << rpad(fmt("%.1f", t.median_call_ns), 10) << "\n";
  const auto& b = r.batch;
  double single = 0;
  for (const auto& t : r.fast)
    if (t.name == "solve_pair") single = 1e9 / t.median_ns_per_pair;
  s << "  batch API (fast::solve_batch, every value, " << b.threads << " threads): "
    << fmt("%.0f", b.pairs_per_second) << " pairs/s (median of " << b.repeats << " runs, "
    << fmt("%.4f", b.median_seconds) << " s per " << b.pairs << " pairs); one core solve_pair: "
    << fmt("%.0f", single) << " pairs/s; speed-up " << fmt("%.2f", b.pairs_per_second / single)
    << "x\n"
    << "  slow path (exact rationals where an error bound is wider than 1e-9): "
    << b.slow_paths << " of " << b.pairs << " pairs ("
    << fmt("%.3g", b.pairs ? 100.0 * double(b.slow_paths) / double(b.pairs) : 0.0) << "%)\n"
    << "  refined (the few contending candidates evaluated exactly, no whole exact path): "
    << b.refined << " of " << b.pairs << " pairs ("
    << fmt("%.3g", b.pairs ? 100.0 * double(b.refined) / double(b.pairs) : 0.0) << "%)\n";
  const auto& cc = r.certification;
  s << "  their cost (solve_pair, one core, median call): refined " << fmt("%.1f", cc.refined_median_ns / 1e3)
    << " us, exact path " << fmt("%.1f", cc.slow_median_ns / 1e3) << " us; together "
    << fmt("%.2f", 100.0 * cc.share_of_solve_pair)
    << "% of solve_pair's time over all pairs\n"
    << "  certification on every pair (rigid_pd2 against the same kernel and pick with none: no "
       "rescaling, no certify pass, no exact path; same passes): "
    << fmt("%.1f", cc.rigid_certified_ns) << " vs " << fmt("%.1f", cc.rigid_uncertified_ns) << " ns per pair, "
    << fmt("%.1f", cc.rigid_certified_ns - cc.rigid_uncertified_ns) << " ns ("
    << fmt("%.0f", cc.rigid_certified_ns > 0 ? 100.0 * (cc.rigid_certified_ns - cc.rigid_uncertified_ns) /
                                                   cc.rigid_certified_ns
                                             : 0.0)
    << "% of rigid_pd2; the kernel's bound lanes are in both)\n\n";

  s << "Rigid PD by the peers, same pairs, same process, passes interleaved with ours\n";
  s << "  " << pad("peer", 40) << rpad("ns/pair", 10) << rpad("min", 9) << rpad("max", 9)
    << rpad("per call", 10) << rpad("ratio", 8) << rpad("call ratio", 11) << "\n";
  for (const auto& p : r.peers)
    s << "  " << pad(p.name + (p.judged ? " *" : ""), 40)
      << rpad(fmt("%.1f", p.timing.median_ns_per_pair), 10)
      << rpad(fmt("%.1f", p.timing.min_ns_per_pair), 9)
      << rpad(fmt("%.1f", p.timing.max_ns_per_pair), 9)
      << rpad(fmt("%.1f", p.timing.median_call_ns), 10) << rpad(fmt("%.1fx", p.time_ratio), 8)
      << rpad(fmt("%.1fx", p.call_ratio), 11) << "\n";
  s << "  (ratio = peer / our rigid_pd2; * = judged against the >= 10x target)\n\n";

  s << "Peer accuracy: 'no isect' and 'failed' over all " << r.pairs
    << " pairs (all intersect); rel. error of PD² against\n"
       "the exact PD² on the first "
    << r.exact.sample << " pairs (failures included: 'no isect' = 1, failed = inf); dev. vs\n"
       "fast = max relative deviation of PD² from our fast rigid_pd2 over all pairs\n";
  s << "  " << pad("peer", 40) << rpad("no isect", 9) << rpad("failed", 8)
    << rpad("max err", 10) << rpad("med err", 10) << rpad("dev vs fast", 12)
    << rpad(">1e-6", 7) << rpad(">1e-2", 7) << "\n";
  for (const auto& p : r.peers)
    s << "  " << pad(p.name, 40) << rpad(std::to_string(p.not_intersecting), 9)
      << rpad(std::to_string(p.failed), 8) << rpad(fmt("%.2e", p.max_rel_error), 10)
      << rpad(fmt("%.2e", p.median_rel_error), 10) << rpad(fmt("%.2e", p.max_rel_dev_vs_fast), 12)
      << rpad(std::to_string(p.off_1e6), 7) << rpad(std::to_string(p.off_1e2), 7) << "\n";
  const auto& e = r.exact;
  s << "  " << pad("ours: fast rigid_pd2", 40) << rpad("0", 9) << rpad("0", 8)
    << rpad(fmt("%.2e", e.fast_max_rel_error), 10) << rpad(fmt("%.2e", e.fast_median_rel_error), 10)
    << "\n";
  s << "  (>1e-6, >1e-2: pairs whose PD² deviates from ours by more than that, failures included)\n";
  for (const auto& p : r.peers)
    s << "    " << p.name << ": " << p.config << "; worst pair " << p.worst_pair << ": PD² "
      << fmt("%.6g", p.worst_peer_pd2) << " vs ours " << fmt("%.6g", p.worst_fast_pd2) << "\n";
  s << "\n";

  if (e.sample == 0) {
    s << "Exact engine against ours: not sampled (--exact-sample 0)\n\n";
  } else {
    s << "Exact engine against ours, one core, first " << e.sample << " pairs\n"
      << "  rigid PD²: reference::minkowski_pd " << fmt("%.1f", e.exact_rigid_median_ns / 1e3)
      << " us (median call, " << r.options.repeats << " passes) vs fast rigid_pd2 "
      << fmt("%.1f", e.fast_rigid_median_ns) << " ns: ratio " << fmt("%.0f", e.rigid_ratio) << "x\n"
      << "  every value: reference::solve_exact (Reduced) " << fmt("%.2f", e.exact_solve_median_ns / 1e6)
      << " ms (median call, 1 pass) vs fast solve_pair " << fmt("%.1f", e.fast_solve_median_ns)
      << " ns: ratio " << fmt("%.0f", e.solve_ratio) << "x\n\n";
  }

  s << "Targets (the speed pdd is built for; time = median over passes of the time per pair, one "
       "core)\n";
  for (const auto& t : r.targets) {
    const bool ratio = t.bound.find('x') != std::string::npos;
    s << "  " << pad(t.what, 62) << pad(t.bound, 11)
      << rpad(ratio ? fmt("%.1fx", t.measured) : fmt("%.1f ns", t.measured), 11) << "  "
      << (t.pass ? "pass" : "MISS") << "\n";
  }
  s << "(total " << fmt("%.1f", r.seconds) << " s)\n";
}

// ---- pdd bench --family aligned -----------------------------------------------------

Json aligned_set_json(const AlignedPairSet& set) {
  Json j;
  j["timings"] = Json::array();
  for (const auto& t : set.timings) j["timings"].push_back(timing_json(t));
  j["slow_path_pairs"] = set.slow_path;
  j["refined_pairs"] = set.refined;
  return j;
}

Json aligned_report_json(const AlignedBenchReport& r) {
  Json j;
  j["command"] = "pdd bench";
  j["family"] = "aligned";
  j["count"] = r.options.count;
  j["seed"] = r.options.seed;
  j["repeats"] = r.options.repeats;
  j["rotation_angle_rad"] = r.options.angle;
  j["rotation_axis"] = {r.options.axis[0], r.options.axis[1], r.options.axis[2]};
  j["pairs_drawn"] = r.drawn;
  j["pairs_dropped"] = r.dropped;
  j["machine"] = machine_json(r.machine);
  Json cases = Json::array();
  for (const auto& c : r.cases) {
    Json q;
    q["name"] = c.name;
    q["pairs"] = c.pairs;
    q["aligned"] = aligned_set_json(c.aligned);
    q["rotated"] = aligned_set_json(c.rotated);
    Json ratios = Json::array();
    for (std::size_t k = 0; k < c.aligned.timings.size(); ++k)
      ratios.push_back({{"name", c.aligned.timings[k].name},
                        {"time_ratio", number(c.aligned.timings[k].median_ns_per_pair /
                                              c.rotated.timings[k].median_ns_per_pair)},
                        {"call_ratio", number(c.aligned.timings[k].median_call_ns /
                                              c.rotated.timings[k].median_call_ns)}});
    q["ratios_aligned_to_rotated"] = ratios;
    cases.push_back(q);
  }
  j["cases"] = cases;
  j["seconds"] = r.seconds;
  return j;
}

void print_aligned_pairs_table(const AlignedBenchReport& r, std::ostream& s) {
  const auto& m = r.machine;
  const auto& o = r.options;
  s << "pdd bench: family aligned (seed " << o.seed << "), " << r.drawn << " pairs drawn, " << r.dropped
    << " left out (B rotated misses A); beside each pair, B rotated by " << o.angle << " rad about ("
    << o.axis[0] << ", " << o.axis[1] << ", " << o.axis[2] << ") through its centroid; "
    << o.repeats << " timed passes per row, the two sets interleaved\n"
    << "machine:   " << m.cpu_model << ", " << m.logical_cpus << " logical CPUs; " << m.compiler
    << (m.assertions ? ", assertions ON" : ", NDEBUG") << "\n"
    << "load avg:  before " << m.load_before << "; after " << m.load_after << "\n";
  auto pct = [](std::size_t x, std::size_t n) {
    return std::to_string(x) + " (" + fmt("%.1f", n ? 100.0 * double(x) / double(n) : 0.0) + "%)";
  };
  for (const auto& c : r.cases) {
    s << "\n" << (c.name == "all" ? std::string("every kind (the kinds' rows weighted by their pairs)") : c.name)
      << ": " << c.pairs << " pairs; ns, one core: per pair (median over passes) and per call (median)\n"
      << "  " << pad("", 20) << rpad("aligned", 12) << rpad("rotated", 12) << rpad("ratio", 9)
      << rpad("call aligned", 14) << rpad("call rotated", 14) << rpad("ratio", 9) << "\n";
    for (std::size_t k = 0; k < c.aligned.timings.size(); ++k) {
      const VariantTiming &x = c.aligned.timings[k], &y = c.rotated.timings[k];
      const double a = x.median_ns_per_pair, b = y.median_ns_per_pair;
      s << "  " << pad(x.name, 20) << rpad(fmt("%.0f", a), 12) << rpad(fmt("%.0f", b), 12)
        << rpad(fmt("%.2fx", a / b), 9) << rpad(fmt("%.0f", x.median_call_ns), 14)
        << rpad(fmt("%.0f", y.median_call_ns), 14) << rpad(fmt("%.2fx", x.median_call_ns / y.median_call_ns), 9)
        << (a <= 2 * b ? "" : "  over 2x") << "\n";
    }
    s << "  " << pad("slow path (pairs)", 20) << rpad(pct(c.aligned.slow_path, c.pairs), 12)
      << rpad(pct(c.rotated.slow_path, c.pairs), 12) << "\n"
      << "  " << pad("refined (pairs)", 20) << rpad(pct(c.aligned.refined, c.pairs), 12)
      << rpad(pct(c.rotated.refined, c.pairs), 12) << "\n";
  }
  s << "(per pair: pass time / pairs, the few slow pairs included; per call: the typical pair; 'every\n"
       " kind': per call the kinds' medians weighted; slow path: solve_pair took the exact path or computed\n"
       " pdd2_global in rationals; refined: a few candidates evaluated in rationals (definitions §8);\n"
       " target: aligned within 2x of rotated per pair; total "
    << fmt("%.1f", r.seconds) << " s)\n";
}

// One bench subcommand's run: check the JSON destination before the run, run, print the table
// (to standard error when the JSON goes to standard output), then write the JSON. `who` names
// the command in messages; run() throws std::invalid_argument for bad options (exit 2, usage)
// and other exceptions for files that cannot be read or written (exit 2, file error).
template <class Run, class Print, class ToJson>
int run_and_report(const char* who, const JsonOutput& out, Run run, Print print, ToJson to_json) {
  const bool json = out.wanted;
  const std::string& json_path = out.path;
  const bool json_stdout = json && (json_path.empty() || json_path == "-");
  if (json && !json_stdout)
    if (auto why = check_writable(json_path)) {  // before the run, not after it
      std::cerr << who << ": " << *why << "\n";
      return kExitFileError;
    }
  decltype(run()) rep;
  try {
    rep = run();
  } catch (const std::invalid_argument& e) {  // bad options
    std::cerr << who << ": " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& e) {  // mesh::ReadError, file system errors
    std::cerr << who << ": " << e.what() << "\n";
    return kExitFileError;
  }
  print(rep, json_stdout ? std::cerr : std::cout);
  if (json) {
    const std::string text = to_json(rep).dump(2) + "\n";
    if (json_stdout) {
      std::cout << text;
    } else if (auto why = write_file(json_path, text)) {
      std::cerr << who << ": " << *why << "\n";
      return kExitFileError;
    }
  }
  return kExitOk;
}

int run(const BenchArgs& a) {
  if (a.family == "aligned")
    return run_and_report(
        "pdd bench", a.json, [&] { return run_aligned_bench(a.aligned); },
        [](const AlignedBenchReport& r, std::ostream& os) { print_aligned_pairs_table(r, os); },
        aligned_report_json);
  return run_and_report(
      "pdd bench", a.json, [&] { return run_bench(a.options); },
      [](const BenchReport& r, std::ostream& os) { print_table(r, os); }, report_json);
}

// ---- pdd bench mesh ----------------------------------------------------------------

struct MeshBenchArgs {
  MeshBenchOptions options;
  std::string variants = "rigid,accel1";
  JsonOutput json;
};

Json stage_json(const MeshRun& r) {
  Json j;
  j["threads"] = r.threads;
  j["read_s"] = number(r.median.read);
  j["boxes_s"] = number(r.median.boxes);
  j["broadphase_s"] = number(r.median.broadphase);
  j["decision_s"] = number(r.median.decision);
  j["depth_s"] = number(r.median.depth);
  j["after_read_s"] = number(r.median.after_read);
  j["box_pairs"] = r.box_pairs;
  j["intersecting_pairs"] = r.intersecting;
  j["intersecting_pairs_per_s"] = number(r.pairs_per_second);
  j["box_pairs_decided_per_s"] = number(r.box_pairs_per_second);
  return j;
}

Json broadphase_json(const std::vector<BroadphaseRow>& rows) {
  Json a = Json::array();
  for (const auto& r : rows) {
    Json j;
    j["name"] = r.name;
    j["pairs"] = r.pairs;
    j["setup_s"] = number(r.setup);
    j["query_s"] = number(r.query);
    j["total_s"] = number(r.total);
    j["ratio_to_ours"] = number(r.ratio);
    a.push_back(j);
  }
  return a;
}

Json mesh_report_json(const MeshBenchReport& r) {
  Json j;
  j["command"] = "pdd bench mesh";
  j["a"] = r.source_a;
  j["b"] = r.source_b;
  j["elements_a"] = r.elements_a;
  j["elements_b"] = r.elements_b;
  j["variants"] = mesh::variant_names(r.options.variants);
  j["repeats"] = r.options.repeats;
  j["generate_s"] = number(r.generate_seconds);
  j["machine"] = machine_json(r.machine);
  j["one_core"] = stage_json(r.one_core);
  j["all_cores"] = stage_json(r.all_cores);
  Json d;
  d["sample"] = r.decision.sample;
  d["filter_disjoint"] = r.decision.disjoint;
  d["filter_intersecting"] = r.decision.intersecting;
  d["filter_unknown"] = r.decision.unknown;
  d["overlap_filter_ns"] = number(r.decision.filter_ns);
  d["interiors_intersect_ns"] = number(r.decision.decision_ns);
  d["rigid_pd2_ns"] = number(r.decision.rigid_ns);
  j["decision_one_core"] = d;
  Json dp = Json::array();
  for (const auto& c : r.depth) {
    Json q;
    q["name"] = c.name;
    q["median_call_ns"] = number(c.median_ns);
    q["mean_call_ns"] = number(c.mean_ns);
    q["calls_over_50us"] = c.slow_calls;
    q["share_of_time_over_50us"] = number(c.slow_share);
    dp.push_back(q);
  }
  j["depth_calls_one_core"] = {{"pairs", r.depth_sample}, {"calls", dp}};
  j["broadphase_all_boxes"] = broadphase_json(r.broadphase_all);
  j["broadphase_pruned_boxes"] = broadphase_json(r.broadphase_pruned);
  j["pruned_boxes_a"] = r.pruned_a;
  j["pruned_boxes_b"] = r.pruned_b;
  Json al = Json::array();
  for (const auto& c : r.aligned) {
    auto run = [](const AlignedRun& a) {
      Json q;
      q["elements_a"] = a.elements_a;
      q["elements_b"] = a.elements_b;
      q["box_pairs"] = a.box_pairs;
      q["intersecting"] = a.intersecting;
      q["decision_ns_per_box_pair"] = number(a.decision_ns);
      q["depth_ns_per_pair"] = number(a.depth_ns);
      q["sampled"] = a.sampled;
      q["slow_path"] = a.slow_path;
      q["refined"] = a.refined;
      return q;
    };
    al.push_back({{"name", c.name}, {"aligned", run(c.aligned)}, {"rotated", run(c.rotated)},
                  {"scene", run(c.scene)},
                  {"decision_ratio", number(c.aligned.decision_ns / c.rotated.decision_ns)},
                  {"depth_ratio", number(c.aligned.depth_ns / c.rotated.depth_ns)},
                  {"decision_ratio_scene", number(c.aligned.decision_ns / c.scene.decision_ns)},
                  {"depth_ratio_scene", number(c.aligned.depth_ns / c.scene.depth_ns)}});
  }
  j["aligned_cases_one_core"] = al;
  j["notes"] = r.notes;
  j["seconds"] = r.seconds;
  return j;
}

// The aligned cases: per case, the aligned meshes and the rotated ones, ratio aligned / rotated.
void print_aligned_table(const MeshBenchReport& r, std::ostream& s) {
  if (r.aligned.empty()) return;
  std::size_t w = 6;  // the case column: the longest name and two spaces
  for (const auto& c : r.aligned) w = std::max(w, c.name.size() + 2);
  s << "\nAligned and structured meshes (" << r.options.aligned_cells
    << " cells per axis), one core, medians; beside each, B rotated by 0.3 rad, and the scene\n"
    << "(A and B) turned by 0.3 rad together: the same scene in another frame (same run)\n  "
    << pad("case", w) << pad("", 9) << rpad("box pairs", 10) << rpad("pairs", 8)
    << rpad("ns/box pair", 13) << rpad("ns/pair", 11) << rpad("slow path", 11) << rpad("refined", 9) << "\n";
  for (const auto& c : r.aligned) {
    for (int k = 0; k < 3; ++k) {
      const AlignedRun& a = k == 0 ? c.aligned : k == 1 ? c.rotated : c.scene;
      auto pct = [&](std::size_t x) { return a.sampled ? fmt("%.1f%%", 100.0 * double(x) / double(a.sampled)) : std::string("-"); };
      s << "  " << pad(k ? "" : c.name, w) << pad(k == 0 ? "aligned" : k == 1 ? "rotated" : "scene", 9)
        << rpad(std::to_string(a.box_pairs), 10) << rpad(std::to_string(a.intersecting), 8)
        << rpad(fmt("%.0f", a.decision_ns), 13) << rpad(fmt("%.0f", a.depth_ns), 11)
        << rpad(pct(a.slow_path), 11) << rpad(pct(a.refined), 9) << "\n";
    }
    s << "  " << pad("", w) << pad("ratio", 9) << rpad("", 18)
      << rpad(fmt("%.2fx", c.aligned.decision_ns / c.rotated.decision_ns), 13)
      << rpad(fmt("%.2fx", c.aligned.depth_ns / c.rotated.depth_ns), 11) << "\n";
    s << "  " << pad("", w) << pad("/ scene", 9) << rpad("", 18)
      << rpad(fmt("%.2fx", c.aligned.decision_ns / c.scene.decision_ns), 13)
      << rpad(fmt("%.2fx", c.aligned.depth_ns / c.scene.depth_ns), 11) << "\n";
  }
  s << "  (slow path, refined: solve_pair's record statistics for the variants timed, on up to 2000\n"
       "   intersecting pairs; ratio: aligned / rotated, / scene: aligned / scene;\n"
       "   target: aligned within 2x of rotated per box pair and per intersecting pair)\n";
}

void print_mesh_table(const MeshBenchReport& r, std::ostream& s) {
  const auto& m = r.machine;
  s << "pdd bench mesh: " << r.elements_a << " x " << r.elements_b << " tetrahedra, variants "
    << mesh::variant_names(r.options.variants) << "; medians of " << r.options.repeats
    << " runs (after a warm-up run)\n"
    << "A:         " << r.source_a << "\nB:         " << r.source_b << "\n"
    << "machine:   " << m.cpu_model << ", " << m.logical_cpus << " logical CPUs; " << m.compiler
    << (m.assertions ? ", assertions ON" : ", NDEBUG") << "\n"
    << "load avg:  before " << m.load_before << "; after " << m.load_after << "\n"
    << "peer:      FCL " << m.fcl_version << "\n";
  for (const auto& n : r.notes) s << "note:      " << n << "\n";
  if (r.generate_seconds > 0) s << "generated in " << fmt("%.3f", r.generate_seconds) << " s\n";
  s << "\nStages of pdd::mesh::contacts (seconds, median)\n  " << pad("", 12) << rpad("read", 9)
    << rpad("boxes", 9) << rpad("broad", 9) << rpad("decision", 10) << rpad("depth", 9)
    << rpad("after read", 12) << rpad("pairs/s", 12) << rpad("box pairs/s", 13) << "\n";
  for (const MeshRun* run : {&r.one_core, &r.all_cores}) {
    const auto& t = run->median;
    s << "  " << pad(std::to_string(run->threads) + (run->threads == 1 ? " thread" : " threads"), 12)
      << rpad(fmt("%.4f", t.read), 9) << rpad(fmt("%.4f", t.boxes), 9)
      << rpad(fmt("%.4f", t.broadphase), 9) << rpad(fmt("%.4f", t.decision), 10)
      << rpad(fmt("%.4f", t.depth), 9) << rpad(fmt("%.4f", t.after_read), 12)
      << rpad(fmt("%.0f", run->pairs_per_second), 12) << rpad(fmt("%.3g", run->box_pairs_per_second), 13)
      << "\n";
  }
  s << "  box pairs " << r.all_cores.box_pairs << ", intersecting pairs " << r.all_cores.intersecting
    << " (pairs/s: intersecting pairs / after read; box pairs/s: box pairs / decision)\n\n";
  const auto& d = r.decision;
  s << "Decision per box pair, one core, " << d.sample << " box pairs (every k-th)\n"
    << "  overlap_filter (certified SAT in doubles)   " << rpad(fmt("%.1f ns", d.filter_ns), 12)
    << "  verdicts: " << d.disjoint << " disjoint, " << d.intersecting << " intersecting, "
    << d.unknown << " unknown\n"
    << "  interiors_intersect (filter + exact rest)   " << rpad(fmt("%.1f ns", d.decision_ns), 12) << "\n"
    << "  rigid_pd2 > 0 (the decision without filter) " << rpad(fmt("%.1f ns", d.rigid_ns), 12)
    << "  ratio " << fmt("%.1fx", d.rigid_ns / d.decision_ns) << "\n\n";
  s << "Depth stage, one call at a time, one core, on the " << r.depth_sample
    << " intersecting pairs of that sample\n";
  for (const auto& c : r.depth)
    s << "  " << pad(c.name, 14) << "median " << rpad(fmt("%.0f ns", c.median_ns), 10) << "  mean "
      << rpad(fmt("%.0f ns", c.mean_ns), 10) << "  " << c.slow_calls << " calls over 50 us: "
      << fmt("%.0f", 100 * c.slow_share) << "% of the time\n";
  s << "\n";
  auto table = [&](const char* title, const std::vector<BroadphaseRow>& rows) {
    s << title << "\n  " << pad("broadphase", 44) << rpad("pairs", 10) << rpad("setup s", 10)
      << rpad("query s", 10) << rpad("total s", 10) << rpad("ratio", 9) << "\n";
    for (const auto& b : rows)
      s << "  " << pad(b.name, 44) << rpad(std::to_string(b.pairs), 10)
        << rpad(fmt("%.4f", b.setup), 10) << rpad(fmt("%.4f", b.query), 10)
        << rpad(fmt("%.4f", b.total), 10) << rpad(fmt("%.1fx", b.ratio), 9) << "\n";
  };
  table("Broadphase on all element boxes, one core (median; ratio = time / ours)", r.broadphase_all);
  table(("Broadphase on the boxes left after pruning by the other mesh's bounding box (" +
         std::to_string(r.pruned_a) + " + " + std::to_string(r.pruned_b) + "), one core")
            .c_str(),
        r.broadphase_pruned);
  s << "  (ours: CGAL box_intersection_d, half-open boxes, boxes built inside the time; FCL: closed\n"
       "   boxes, objects built outside the time, setup = registerObjects + setup)\n";
  double best = 0;
  for (std::size_t k = 1; k < r.broadphase_all.size(); ++k)
    if (best == 0 || r.broadphase_all[k].ratio < best) best = r.broadphase_all[k].ratio;
  s << "\nTargets (the speed pdd mesh is built for)\n"
    << "  " << pad("everything after reading, all cores", 52) << pad("<= 0.100 s", 14)
    << rpad(fmt("%.4f s", r.all_cores.median.after_read), 10) << "  "
    << (r.all_cores.median.after_read <= 0.1 ? "pass" : "MISS") << "\n"
    << "  " << pad("broadphase vs best FCL manager, all boxes, one core", 52) << pad(">= 2x", 14)
    << rpad(fmt("%.1fx", best), 10) << "  " << (best >= 2 ? "pass" : "MISS") << "\n"
    ;
  print_aligned_table(r, s);
  s << "(total " << fmt("%.1f", r.seconds) << " s)\n";
}

int run_mesh(const MeshBenchArgs& a) {
  return run_and_report(
      "pdd bench mesh", a.json,
      [&] {
        MeshBenchOptions o = a.options;
        o.variants = mesh::parse_variants(a.variants);
        return run_mesh_bench(o);
      },
      [](const MeshBenchReport& r, std::ostream& os) { print_mesh_table(r, os); }, mesh_report_json);
}

// ---- pdd bench resolve -------------------------------------------------------------

struct ResolveBenchArgs {
  ResolveBenchOptions options;
  JsonOutput json;
};

// The case of `r` named `name`, or null.
const ResolveBenchCase* find_case(const ResolveBenchReport& r, const std::string& name) {
  for (const auto& c : r.cases)
    if (c.name == name) return &c;
  return nullptr;
}

// Of one variant, aligned case `a` against its rotated twin `b`: total time, and time per round
// pair (the pairs solved, summed over the rounds); NaN where a row or its pairs are missing.
struct ResolveRatios {
  double total = NAN, per_pair = NAN;
};
ResolveRatios resolve_ratios(const ResolveBenchCase& a, const ResolveBenchCase& b, const std::string& variant) {
  ResolveRatios q;
  for (const auto& x : a.rows)
    for (const auto& y : b.rows)
      if (x.variant == variant && y.variant == variant) {
        q.total = x.total / y.total;
        const double pa = double(round_pairs(x)), pb = double(round_pairs(y));
        if (pa > 0 && pb > 0) q.per_pair = (x.total / pa) / (y.total / pb);
      }
  return q;
}

Json resolve_report_json(const ResolveBenchReport& r) {
  Json j;
  j["command"] = "pdd bench resolve";
  j["size"] = r.options.size;
  j["shallow_distance"] = r.options.shallow_distance;
  j["deep_distance"] = r.options.deep_distance;
  j["max_rounds"] = r.options.max_rounds;
  j["repeats"] = r.options.repeats;
  j["cases_dir"] = r.options.cases_dir;
  j["variants"] = r.options.variants;
  j["stacked_cells"] = r.options.stacked_cells;
  j["machine"] = machine_json(r.machine);
  Json cases = Json::array();
  for (const auto& c : r.cases) {
    Json q;
    q["name"] = c.name;
    q["description"] = c.description;
    q["elements_a"] = c.elements_a;
    q["elements_b"] = c.elements_b;
    q["skipped"] = c.skipped;
    q["read_s"] = number(c.read_seconds);
    q["rigid_separation_cost"] = c.rigid_separation >= 0 ? Json(c.rigid_separation) : Json(nullptr);
    q["rigid_separation_t"] = number(c.rigid_t);
    q["fixed"] = c.fixed_a ? Json("a") : c.fixed_b ? Json("b") : Json(nullptr);
    const ResolveBenchCase* twin = c.rotated_twin.empty() ? nullptr : find_case(r, c.rotated_twin);
    q["rotated_twin"] = twin ? Json(twin->name) : Json(nullptr);
    Json rows = Json::array();
    for (const auto& w : c.rows) {
      Json x;
      x["variant"] = w.variant;
      x["resolved"] = w.resolved;
      x["r1"] = w.r1;
      x["r2"] = w.r2;
      x["r3"] = w.r3;
      x["r4"] = w.r4;
      x["method"] = w.method;
      x["rounds"] = w.rounds;
      x["first_pairs"] = w.first_pairs;
      x["remaining_pairs"] = w.remaining_pairs;
      x["bad_elements"] = w.bad_elements;
      x["cost"] = number(w.cost);
      x["cost_over_rigid"] = c.rigid_separation > 0 ? Json(w.cost / c.rigid_separation) : Json(nullptr);
      x["max_displacement"] = number(w.max_displacement);
      x["min_volume_ratio"] = number(w.min_volume_ratio);
      x["max_volume_ratio"] = number(w.max_volume_ratio);
      x["min_shape_ratio"] = number(w.min_shape_ratio);
      x["poor_elements"] = w.poor_elements;
      x["total_s"] = number(w.total);
      x["contacts_s"] = number(w.contacts);
      x["solve_s"] = number(w.solve);
      x["move_s"] = number(w.move);
      x["verify_s"] = number(w.verify);
      x["per_round_s"] = number(w.per_round);
      Json rounds = Json::array();
      for (const auto& k : w.round_log)
        rounds.push_back({{"round", k.round}, {"pairs", k.pairs}, {"max_pd2", number(k.max_pd2)},
                          {"cost", number(k.cost)}, {"seconds", number(k.seconds)}});
      x["rounds_log"] = rounds;
      x["round_pairs"] = round_pairs(w);
      if (twin) {
        const ResolveRatios q2 = resolve_ratios(c, *twin, w.variant);
        x["time_ratio_to_rotated"] = number(q2.total);
        x["per_pair_ratio_to_rotated"] = number(q2.per_pair);
      }
      rows.push_back(x);
    }
    q["variants"] = rows;
    cases.push_back(q);
  }
  j["cases"] = cases;
  j["notes"] = r.notes;
  j["seconds"] = r.seconds;
  return j;
}

void print_resolve_table(const ResolveBenchReport& r, std::ostream& s) {
  s << "pdd bench resolve: medians of " << r.options.repeats << " runs per row; " << r.machine.logical_cpus
    << " logical CPUs (" << r.machine.cpu_model << "), load " << r.machine.load_before << "\n";
  for (const auto& c : r.cases) {
    s << "\n" << c.name << ": " << c.description;
    if (c.read_seconds > 0) s << "; read " << fmt("%.3f s", c.read_seconds);
    if (c.skipped) s << "; " << c.skipped << " elements skipped";
    s << "\n";
    if (c.rigid_separation >= 0)
      s << "  rigid separation along the line: t = " << fmt("%.5g", c.rigid_t)
        << (c.fixed_a || c.fixed_b ? ", one mesh fixed, cost t^2 = " : ", cost t^2/2 = ")
        << fmt("%.4g", c.rigid_separation) << "\n";
    s << "  " << pad("variant", 8) << rpad("resolved", 9) << rpad("rounds", 7) << rpad("pairs", 7)
      << rpad("left", 6) << rpad("cost", 11) << rpad("vs rigid", 9) << rpad("max disp", 10)
      << rpad("min V1/V0", 10) << rpad("max V1/V0", 10) << rpad("min eta", 8) << rpad("R4", 4) << rpad("method", 12) << rpad("total s", 9) << rpad("contacts", 9) << rpad("solve", 8)
      << rpad("move", 8) << rpad("verify", 8) << rpad("s/round", 9) << "\n";
    for (const auto& w : c.rows)
      s << "  " << pad(w.variant, 8) << rpad(w.resolved ? "yes" : "NO", 9) << rpad(std::to_string(w.rounds), 7)
        << rpad(std::to_string(w.first_pairs), 7) << rpad(std::to_string(w.remaining_pairs), 6)
        << rpad(fmt("%.3e", w.cost), 11)
        << rpad(c.rigid_separation > 0 ? fmt("%.4f", w.cost / c.rigid_separation) : "-", 9)
        << rpad(fmt("%.4f", w.max_displacement), 10) << rpad(fmt("%.3f", w.min_volume_ratio), 10)
        << rpad(fmt("%.3f", w.max_volume_ratio), 10) << rpad(fmt("%.3f", w.min_shape_ratio), 8)
        << rpad(w.r4 ? "yes" : "NO", 4) << rpad(w.method, 12) << rpad(fmt("%.3f", w.total), 9) << rpad(fmt("%.3f", w.contacts), 9) << rpad(fmt("%.3f", w.solve), 8)
        << rpad(fmt("%.3f", w.move), 8) << rpad(fmt("%.3f", w.verify), 8) << rpad(fmt("%.4f", w.per_round), 9)
        << "\n";
    for (const auto& a : r.cases) {  // after the rotated twin of an aligned case: their ratios
      if (a.rotated_twin != c.name) continue;
      s << "  " << a.name << " / " << c.name << " (aligned / rotated), per variant: total time; time per round pair\n";
      for (const auto& w : a.rows) {
        const ResolveRatios q = resolve_ratios(a, c, w.variant);
        s << "  " << pad(w.variant, 8) << rpad(fmt("%.2fx", q.total), 9) << rpad(fmt("%.2fx", q.per_pair), 9)
          << (q.per_pair <= 2 ? "" : "  over 2x") << "\n";
      }
    }
  }
  s << "(pairs: intersecting pairs at the start; left: intersecting pairs at the end; vs rigid: cost "
       "over the rigid separation's; V1/V0 and eta: element volume and mean-ratio shape ratios, final "
       "over rest (resolved includes R4: V1/V0 in [1/4, 4], eta >= 1/2); method: what produced the "
       "result; total s after reading, the final exact check included; total "
    << fmt("%.1f", r.seconds) << " s)\n";
}

int run_resolve(const ResolveBenchArgs& a) {
  return run_and_report(
      "pdd bench resolve", a.json, [&] { return run_resolve_bench(a.options); },
      [](const ResolveBenchReport& r, std::ostream& os) { print_resolve_table(r, os); },
      [](const ResolveBenchReport& r) { return resolve_report_json(r); });
}

// ---- pdd bench energy --------------------------------------------------------------

struct EnergyBenchArgs {
  EnergyBenchOptions options;
  JsonOutput json;
};

Json energy_times_json(const EnergyTimes& t) {
  Json j;
  j["found_s"] = number(t.found);
  j["energy_gradient_s"] = number(t.energy);
  j["energy_gradient_cpu_s"] = number(t.energy_cpu);
  j["energy_gradient_hessian_s"] = number(t.hessian);
  j["energy_gradient_hessian_cpu_s"] = number(t.hessian_cpu);
  j["pairs_per_s"] = number(t.pairs_per_second);
  return j;
}

// Aligned case `a` against its rotated twin `b`, one core: the ratios of the times per
// intersecting pair of finding the pairs, of E + gradient, of E + gradient + Hessian.
std::array<double, 3> energy_ratios(const EnergyCase& a, const EnergyCase& b) {
  const double pa = double(a.pairs), pb = double(b.pairs);
  auto ratio = [&](double x, double y) { return pa > 0 && pb > 0 && y > 0 ? (x / pa) / (y / pb) : NAN; };
  return {ratio(a.one_core.found, b.one_core.found), ratio(a.one_core.energy, b.one_core.energy),
          ratio(a.one_core.hessian, b.one_core.hessian)};
}
// Per call (scene twins: the same contact, pair counts that differ by contacts made by rounding).
std::array<double, 3> energy_call_ratios(const EnergyCase& a, const EnergyCase& b) {
  auto ratio = [](double x, double y) { return y > 0 ? x / y : NAN; };
  return {ratio(a.one_core.found, b.one_core.found), ratio(a.one_core.energy, b.one_core.energy),
          ratio(a.one_core.hessian, b.one_core.hessian)};
}
const EnergyCase* find_case(const EnergyBenchReport& r, const std::string& name) {
  for (const auto& c : r.cases)
    if (c.name == name) return &c;
  return nullptr;
}

// The target for a simulator's Newton loop: E + gradient + Hessian of 10^4 shallow contact pairs
// of two meshes of about 10^5 tetrahedra in <= 50 ms on all cores, after the pairs are found;
// judged on the shallow cases (grids, balls) with the time scaled to 10^4 pairs.
std::vector<BenchTarget> energy_targets(const EnergyBenchReport& r) {
  std::vector<BenchTarget> out;
  for (const auto& c : r.cases) {
    if ((c.name != "grids" && c.name != "balls") || c.pairs == 0) continue;
    const double s = c.all_cores.hessian * 1e4 / double(c.pairs);
    out.push_back({c.name + ": E+grad+H of 10^4 pairs on " + std::to_string(c.threads) +
                       (c.threads == 1 ? " thread" : " threads"),
                   "<= 0.050 s", s, s <= 0.050});
  }
  return out;
}

Json energy_report_json(const EnergyBenchReport& r) {
  Json j;
  j["command"] = "pdd bench energy";
  j["cases"] = Json::array();
  j["repeats"] = r.options.repeats;
  j["machine"] = machine_json(r.machine);
  for (const auto& c : r.cases) {
    Json q;
    q["name"] = c.name;
    q["description"] = c.description;
    q["elements_a"] = c.elements_a;
    q["elements_b"] = c.elements_b;
    q["pairs"] = c.pairs;
    q["hessian_nonzeros"] = c.hessian_nonzeros;
    q["energy"] = number(c.energy);
    q["max_pdd2_global"] = number(c.max_pdd2_global);
    q["threads"] = c.threads;
    q["one_core"] = energy_times_json(c.one_core);
    q["all_cores"] = energy_times_json(c.all_cores);
    const EnergyCase* twin = c.rotated_twin.empty() ? nullptr : find_case(r, c.rotated_twin);
    q["rotated_twin"] = twin ? Json(twin->name) : Json(nullptr);
    auto ratios = [](const std::array<double, 3>& x) {
      return Json{{"found", number(x[0])}, {"energy_gradient", number(x[1])}, {"energy_gradient_hessian", number(x[2])}};
    };
    if (twin) q["per_pair_ratio_to_rotated"] = ratios(energy_ratios(c, *twin));
    const EnergyCase* scene = c.scene_twin.empty() ? nullptr : find_case(r, c.scene_twin);
    q["scene_twin"] = scene ? Json(scene->name) : Json(nullptr);
    if (scene) q["call_ratio_to_scene"] = ratios(energy_call_ratios(c, *scene));
    j["cases"].push_back(q);
  }
  j["targets"] = Json::array();
  for (const auto& t : energy_targets(r))
    j["targets"].push_back({{"what", t.what}, {"bound", t.bound}, {"measured", number(t.measured)}, {"pass", t.pass}});
  j["seconds"] = r.seconds;
  return j;
}

void print_energy_table(const EnergyBenchReport& r, std::ostream& s) {
  s << "pdd bench energy: pdd::mesh::contact_energy, medians of " << r.options.repeats << " runs per row; "
    << r.machine.logical_cpus << " logical CPUs (" << r.machine.cpu_model << "); load before "
    << r.machine.load_before << ", after " << r.machine.load_after << "\n";
  for (const auto& c : r.cases) {
    s << "\n" << c.name << ": " << c.description << "; " << c.elements_a << " + " << c.elements_b
      << " tetrahedra, " << c.pairs << " intersecting pairs, Hessian " << c.hessian_nonzeros
      << " non-zeros\n";
    s << "  " << pad("threads", 10) << rpad("find s", 9) << rpad("E+grad s", 10) << rpad("cpu s", 8)
      << rpad("E+grad+H s", 12) << rpad("cpu s", 8) << rpad("pairs/s", 11) << rpad("us/pair", 9) << "\n";
    auto row = [&](int threads, const EnergyTimes& t) {
      s << "  " << pad(std::to_string(threads), 10) << rpad(fmt("%.4f", t.found), 9)
        << rpad(fmt("%.4f", t.energy), 10) << rpad(fmt("%.3f", t.energy_cpu), 8)
        << rpad(fmt("%.4f", t.hessian), 12) << rpad(fmt("%.3f", t.hessian_cpu), 8)
        << rpad(fmt("%.0f", t.pairs_per_second), 11)
        << rpad(fmt("%.2f", c.pairs ? 1e6 * t.hessian / double(c.pairs) : 0.0), 9) << "\n";
    };
    row(1, c.one_core);
    row(c.threads, c.all_cores);
    auto ratio_line = [&](const EnergyCase& a, const std::array<double, 3>& x, const char* per) {
      s << "  " << a.name << " / " << c.name << " " << per << ", one core: find " << fmt("%.2fx", x[0])
        << ", E+grad " << fmt("%.2fx", x[1]) << ", E+grad+H " << fmt("%.2fx", x[2])
        << (x[1] <= 2 && x[2] <= 2 ? "" : "  (over 2x)") << "\n";
    };
    for (const auto& a : r.cases) {  // after the twins of an aligned case: their ratios
      if (a.rotated_twin == c.name) ratio_line(a, energy_ratios(a, c), "per intersecting pair");
      if (a.scene_twin == c.name) ratio_line(a, energy_call_ratios(a, c), "per call (the same contact)");
    }
  }
  const std::vector<BenchTarget> targets = energy_targets(r);
  if (!targets.empty()) s << "\nTargets (a simulator's Newton loop; the time after finding the pairs, scaled)\n";
  for (const auto& t : targets)
    s << "  " << pad(t.what, 52) << pad(t.bound, 12) << rpad(fmt("%.4f s", t.measured), 10) << "  "
      << (t.pass ? "pass" : "MISS") << "\n";
  s << "(find: boxes, broadphase and exact decision; E+grad, E+grad+H: everything after finding the "
       "pairs, wall and process CPU seconds; pairs/s and us/pair: intersecting pairs over E+grad+H; "
       "total "
    << fmt("%.1f", r.seconds) << " s)\n";
}

int run_energy(const EnergyBenchArgs& a) {
  return run_and_report(
      "pdd bench energy", a.json, [&] { return run_energy_bench(a.options); },
      [](const EnergyBenchReport& r, std::ostream& os) { print_energy_table(r, os); }, energy_report_json);
}

// The options every bench subcommand shares: --repeats (into `repeats`, help `what`) and
// --json [FILE] (into `json`); the command's callback records whether --json was given, then
// runs `run` and keeps its exit status.
void add_shared_options(CLI::App* cmd, int& repeats, const char* what, JsonOutput& json) {
  cmd->add_option("--repeats", repeats, what)->check(integer_in(1, 1000))->capture_default_str();
  cmd->add_option("--json", json.path,
                  "Also write the numbers as JSON to FILE (no FILE or '-': JSON on standard "
                  "output, table on standard error)")
      ->expected(0, 1);
}
template <class Args>
void on_run(CLI::App* cmd, std::shared_ptr<Args> args, int (*run)(const Args&), int& exit_code) {
  cmd->callback([cmd, args, run, &exit_code] {
    args->json.wanted = cmd->count("--json") > 0;
    exit_code = run(*args);
  });
}

}  // namespace

void add_bench_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<BenchArgs>();
  CLI::App* cmd = app.add_subcommand(
      "bench",
      "Time the fast engine, FCL and libccd (rigid PD) and the exact engine on the paper's "
      "protocol; medians of repeated passes, ratios in the same run. --family aligned: the fast "
      "engine on aligned pairs beside the same pairs with B rotated, ratios in the same run.");
  cmd->add_option("--family", a->family,
                  "paper: the paper's protocol with the peers and the exact engine; aligned: `pdd "
                  "generate --family aligned` beside the same pairs with B rotated by 0.3 rad")
      ->check(CLI::IsMember({"paper", "aligned"}))
      ->capture_default_str();
  cmd->add_option("--count", a->options.count,
                  "Pairs of the family (aligned: 3000 unless given; pairs whose rotated B misses A are left out)")
      ->check(integer_in(1, 100000000))
      ->capture_default_str();
  cmd->add_option("--seed", a->options.seed, "Random seed of the pairs (0 to 2^64-1)")
      ->check(seed_value())
      ->capture_default_str();
  cmd->add_option("--exact-sample", a->options.exact_sample,
                  "The first M pairs are also solved exactly (errors, exact-engine ratio; family paper)")
      ->check(integer_in(0, 100000000))
      ->capture_default_str();
  add_shared_options(cmd, a->options.repeats, "Timed passes per row (median reported)", a->json);

  auto ma = std::make_shared<MeshBenchArgs>();
  CLI::App* mesh_cmd = cmd->add_subcommand(
      "mesh",
      "Time pdd mesh per stage (read, boxes, broadphase, decision, depth) on two overlapping "
      "meshes, one core and all cores, and the broadphase against FCL's managers on the same "
      "boxes; medians of repeated runs.");
  mesh_cmd->add_option("--a", ma->options.a, "Mesh A (.msh or .vtk); with --b")->check(CLI::ExistingFile);
  mesh_cmd->add_option("--b", ma->options.b, "Mesh B (.msh or .vtk); with --a")->check(CLI::ExistingFile);
  mesh_cmd->add_option("--size", ma->options.size,
                       "Without --a/--b: tetrahedra per generated ball (two balls of radius 1)")
      ->check(integer_in(6, 20000000))
      ->capture_default_str();
  mesh_cmd->add_option("--distance", ma->options.distance,
                       "Without --a/--b: distance of the balls' centres (overlap: 2 - distance)")
      ->check(finite_number(0, false) & CLI::Range(0.0, 4.0))
      ->capture_default_str();
  mesh_cmd->add_option("--write-meshes", ma->options.write_meshes,
                       "Without --a/--b: keep the generated balls in DIR (ball-a.vtk, ball-b.vtk)");
  mesh_cmd->add_option("--variants", ma->variants, "Variants of the depth stage")->capture_default_str();
  mesh_cmd->add_option("--aligned-cells", ma->options.aligned_cells,
                       "Cells per axis of the aligned cases (Kuhn and 5-tetrahedra grids against a shifted "
                       "copy, a Kuhn grid against its copy shifted by half and by a tenth of a cell along "
                       "(1, 1, 1), body-centred grids of cell 0.1 (24 tetrahedra a cube, half as many cubes a "
                       "side) shifted a quarter cell along (1, 1, 1), a mesh against its shifted copy, stacked "
                       "blocks, a Kuhn grid placed a few ulps off the grid as mesh generators place it against "
                       "its shifted copy and stacked on it; each beside B rotated and beside the scene "
                       "turned); 0: none")
      ->capture_default_str()
      ->check(CLI::Range(0, 60));
  add_shared_options(mesh_cmd, ma->options.repeats, "Timed runs (median reported)", ma->json);
  on_run(mesh_cmd, ma, run_mesh, exit_code);

  auto ra = std::make_shared<ResolveBenchArgs>();
  CLI::App* resolve_cmd = cmd->add_subcommand(
      "resolve",
      "Resolve interpenetrating meshes with every variant (global, pdd2, rigid) side by side: "
      "rounds, time per stage, cost, largest displacement, exact verdict; shallow and deep "
      "overlaps of generated balls, self-contact, the shipped meshes and stacked blocks beside "
      "the same blocks tilted.");
  resolve_cmd->add_option("--cases", ra->options.cases,
                          "Cases, comma-separated: shallow, deep, self, shipped, stacked")
      ->capture_default_str();
  resolve_cmd->add_option("--size", ra->options.size, "Tetrahedra per generated ball")
      ->check(integer_in(6, 20000000))
      ->capture_default_str();
  resolve_cmd->add_option("--shallow-distance", ra->options.shallow_distance,
                          "Centre distance of the balls of the shallow case (their surface cells reach a little beyond radius 1: at 10^5 tetrahedra 1.99 overlaps by about one element layer)")
      ->check(finite_number(0, false) & CLI::Range(0.0, 4.0))
      ->capture_default_str();
  resolve_cmd->add_option("--deep-distance", ra->options.deep_distance, "Centre distance of the deep case")
      ->check(finite_number(0, false) & CLI::Range(0.0, 4.0))
      ->capture_default_str();
  resolve_cmd->add_option("--stacked-cells", ra->options.stacked_cells,
                          "stacked: cells per side of the two Kuhn blocks (N x N x 3 cubes each)")
      ->check(integer_in(1, 100))
      ->capture_default_str();
  resolve_cmd->add_option("--meshes", ra->options.meshes, "Directory of the shipped meshes (self, shipped)")
      ->capture_default_str();
  resolve_cmd->add_option("--cases-dir", ra->options.cases_dir,
                          "Also the real-mesh cases of DIR/cases.tsv (made by scripts/make-resolve-cases.sh DIR)");
  resolve_cmd->add_option("--variants", ra->options.variants, "Variants, comma-separated: global, pdd2, rigid")
      ->capture_default_str();
  resolve_cmd->add_option("--write", ra->options.write_dir,
                          "Write each row's final meshes to DIR/<case>-<variant>-a.vtk / -b.vtk (for check-resolution.py)");
  resolve_cmd->add_option("--max-rounds", ra->options.max_rounds, "Rounds before giving up")
      ->check(integer_in(1, 100000))
      ->capture_default_str();
  add_shared_options(resolve_cmd, ra->options.repeats, "Runs per case and variant (median of the times)", ra->json);
  on_run(resolve_cmd, ra, run_resolve, exit_code);

  auto ea = std::make_shared<EnergyBenchArgs>();
  CLI::App* energy_cmd = cmd->add_subcommand(
      "energy",
      "Time pdd::mesh::contact_energy (E + gradient, and with the Hessian) on shallow contacts of "
      "two meshes of about 10^5 tetrahedra, and on stacked blocks beside the same blocks tilted, "
      "after finding the pairs; one core and all cores, medians of repeated runs.");
  energy_cmd->add_option("--cases", ea->options.cases, "Cases, comma-separated: grids, balls, stacked")
      ->capture_default_str();
  energy_cmd->add_option("--size", ea->options.size, "Tetrahedra per generated ball (balls)")
      ->check(integer_in(6, 20000000))
      ->capture_default_str();
  energy_cmd->add_option("--grid-depth", ea->options.grid_depth,
                         "grids: depth of B's lowest vertex below A's top face (cell 1/26)")
      ->check(finite_number(0, false) & CLI::Range(0.0, 1.0))
      ->capture_default_str();
  energy_cmd->add_option("--ball-distance", ea->options.ball_distance, "balls: centre distance (radius 1)")
      ->check(finite_number(0, false) & CLI::Range(0.0, 4.0))
      ->capture_default_str();
  energy_cmd->add_option("--stacked-cells", ea->options.stacked_cells,
                         "stacked: cells per side of the two Kuhn blocks (N x N x 3 cubes each)")
      ->check(integer_in(1, 100))
      ->capture_default_str();
  add_shared_options(energy_cmd, ea->options.repeats, "Timed runs per row (median reported)", ea->json);
  on_run(energy_cmd, ea, run_energy, exit_code);

  cmd->callback([a, cmd, mesh_cmd, resolve_cmd, energy_cmd, &exit_code] {
    if (mesh_cmd->parsed() || resolve_cmd->parsed() || energy_cmd->parsed()) return;  // a subcommand ran
    a->json.wanted = cmd->count("--json") > 0;
    if (a->family == "aligned" && cmd->count("--exact-sample") > 0) {  // nothing is solved exactly there
      std::cerr << "pdd bench: --exact-sample applies to --family paper only\n";
      exit_code = kExitUsage;
      return;
    }
    a->aligned.seed = a->options.seed;
    a->aligned.repeats = a->options.repeats;
    if (cmd->count("--count") > 0) a->aligned.count = a->options.count;
    exit_code = run(*a);
  });
}

}  // namespace pdd::compare
