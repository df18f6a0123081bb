// aligned_bench.cpp — `pdd bench --family aligned` (aligned_bench.h).
#include "pdd/compare/aligned_bench.h"

#include <chrono>
#include <iostream>
#include <stdexcept>

#include "pdd/compare/generate.h"
#include "pdd/compare/mesh_bench.h"
#include "pdd/pdd.h"

namespace pdd::compare {
namespace {

using Clock = std::chrono::steady_clock;

// The timed rows of one set: the exact decision, then the fast variants.
std::vector<TimedFunction> set_functions(const std::vector<TetPair>& pairs) {
  const std::vector<TetPair>* p = &pairs;
  std::vector<TimedFunction> fns = {
      {"interiors_intersect", [p](std::size_t k) { return double(fast::interiors_intersect((*p)[k].A, (*p)[k].B)); }}};
  for (auto& f : fast_timed_functions(pairs)) fns.push_back(std::move(f));
  return fns;
}

void count_paths(const std::vector<TetPair>& pairs, AlignedPairSet& set) {
  for (const auto& p : pairs) {
    const SolveStats s = fast::solve_pair(p).stats;
    set.slow_path += s.slow_path;
    set.refined += s.refined;
  }
}

// The "all" case from the kinds': per row, the kinds' times per pair weighted by their pair
// counts (the time per pair over every pair), their statistics summed.
AlignedPairCase combined(const std::vector<AlignedPairCase>& kinds) {
  AlignedPairCase all;
  all.name = "all";
  for (const auto& c : kinds) all.pairs += c.pairs;
  for (int s = 0; s < 2; ++s) {
    AlignedPairSet& out = s ? all.rotated : all.aligned;
    for (const auto& c : kinds) {
      const AlignedPairSet& in = s ? c.rotated : c.aligned;
      if (out.timings.empty()) {
        out.timings = in.timings;
        for (auto& t : out.timings) {
          t.median_ns_per_pair = t.min_ns_per_pair = t.max_ns_per_pair = t.median_call_ns = 0;
          t.pairs = 0;
        }
      }
      const double w = all.pairs ? double(c.pairs) / double(all.pairs) : 0;
      for (std::size_t r = 0; r < out.timings.size(); ++r) {
        VariantTiming& t = out.timings[r];
        t.median_ns_per_pair += w * in.timings[r].median_ns_per_pair;
        t.min_ns_per_pair += w * in.timings[r].min_ns_per_pair;
        t.max_ns_per_pair += w * in.timings[r].max_ns_per_pair;
        t.median_call_ns += w * in.timings[r].median_call_ns;
        t.pairs += in.timings[r].pairs;
      }
      out.slow_path += in.slow_path;
      out.refined += in.refined;
    }
  }
  return all;
}

}  // namespace

TetPair rotated_b(const TetPair& pair, double angle, const std::array<double, 3>& axis) {
  TetPair out = pair;
  const auto R = rotation_matrix(axis, angle);
  double c[3] = {0, 0, 0};
  for (const Vec3d& v : pair.B)
    for (int i = 0; i < 3; ++i) c[i] += v[i] / 4;
  for (Vec3d& v : out.B) {
    const double p[3] = {v[0] - c[0], v[1] - c[1], v[2] - c[2]};
    for (int i = 0; i < 3; ++i) v[i] = c[i] + R[i][0] * p[0] + R[i][1] * p[1] + R[i][2] * p[2];
  }
  return out;
}

AlignedBenchReport run_aligned_bench(const AlignedBenchOptions& o) {
  if (o.count == 0) throw std::invalid_argument("--count must be >= 1");
  if (o.repeats < 1) throw std::invalid_argument("--repeats must be >= 1");
  const auto start = Clock::now();
  AlignedBenchReport rep;
  rep.options = o;
  rep.machine = machine_info();
  std::cerr << "pdd bench: generating " << o.count << " pairs (family aligned, seed " << o.seed << ")\n";
  const std::vector<TetPair> drawn = generate_family("aligned", o.seed, o.count);
  rep.drawn = drawn.size();

  // Per kind (the family's second tag), the pairs whose rotated B still meets A.
  std::vector<std::string> kinds;
  std::vector<std::vector<TetPair>> aligned, rotated;
  for (const TetPair& p : drawn) {
    TetPair r = rotated_b(p, o.angle, o.axis);
    if (!fast::interiors_intersect(r.A, r.B)) {
      ++rep.dropped;
      continue;
    }
    const std::string kind = p.tags.size() > 1 ? p.tags[1] : "aligned";
    std::size_t k = 0;
    while (k < kinds.size() && kinds[k] != kind) ++k;
    if (k == kinds.size()) kinds.push_back(kind), aligned.emplace_back(), rotated.emplace_back();
    aligned[k].push_back(p);
    rotated[k].push_back(std::move(r));
  }

  std::vector<AlignedPairCase> cases;
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    std::cerr << "pdd bench: " << kinds[k] << ", " << aligned[k].size() << " pairs aligned and rotated ("
              << o.repeats << " passes each)\n";
    AlignedPairCase c;
    c.name = kinds[k];
    c.pairs = aligned[k].size();
    // Both sets in one call: their passes interleaved, so that a change of load hits both alike.
    std::vector<TimedFunction> fns = set_functions(aligned[k]);
    const std::size_t rows = fns.size();
    for (auto& f : set_functions(rotated[k])) fns.push_back(std::move(f));
    const auto t = time_functions(c.pairs, fns, o.repeats);
    c.aligned.timings.assign(t.begin(), t.begin() + rows);
    c.rotated.timings.assign(t.begin() + rows, t.end());
    count_paths(aligned[k], c.aligned);
    count_paths(rotated[k], c.rotated);
    cases.push_back(std::move(c));
  }
  rep.cases.push_back(combined(cases));
  for (auto& c : cases) rep.cases.push_back(std::move(c));
  rep.machine.load_after = read_first_line("/proc/loadavg");
  rep.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return rep;
}

}  // namespace pdd::compare
