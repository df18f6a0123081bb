// fast_bench.cpp — per-pair timings of the fast engine's variants (paper Sec. VI protocol).
//
// Pairs: tetrahedra with vertices uniform in [0, 10]^3 (fixed seed), intersecting pairs only.
// Each timed call goes from the raw pair to the value (candidate construction included):
//   rigid_pd2, pdd2_static, pdd2 (all candidates), pdd2_accel1, pdd2_accel6, solve_pair.
// Two reports, one thread:
// (1) "median per pair": each call timed alone with steady_clock while cycling through all
//     pairs (so branch predictors are not trained on one pair), 5 passes, timer overhead (the
//     median of empty timings) subtracted, median over all samples;
// (2) Google Benchmark: mean time per call cycling through the whole set.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include "pdd/fast/candidate_directions.h"
#include "pdd/fast/deformable_depth.h"
#include "pdd/fast/rigid_depth.h"
#include "pdd/fast/solve_pair.h"

namespace {

using namespace pdd;
using namespace pdd::fast;

std::vector<TetPair> make_pairs(int count) {
  std::mt19937_64 rng(20240601);
  std::uniform_real_distribution<double> U(0.0, 10.0);
  std::vector<TetPair> pairs;
  CandidateSet set;
  while (int(pairs.size()) < count) {
    TetPair p;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        p.A[i][k] = U(rng);
        p.B[i][k] = U(rng);
      }
    if (build_candidates(p.A, p.B, set) == BuildStatus::Ok && set.intersecting)
      pairs.push_back(p);
  }
  return pairs;
}

const std::vector<TetPair>& pairs() {
  static const std::vector<TetPair> p = make_pairs(2000);
  return p;
}

template <class F>
void BM(benchmark::State& state, F f) {
  const auto& ps = pairs();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f(ps[i]));
    if (++i == ps.size()) i = 0;
  }
}

double v_rigid(const TetPair& p) { return rigid_pd2(p.A, p.B).value; }
double v_static(const TetPair& p) { return pdd2_static(p.A, p.B).value; }
double v_pdd2(const TetPair& p) { return pdd2(p.A, p.B).value; }
double v_accel1(const TetPair& p) { return pdd2_accel(p.A, p.B, 1).value; }
double v_accel6(const TetPair& p) { return pdd2_accel(p.A, p.B, 6).value; }
double v_solve(const TetPair& p) { return solve_pair(p).pdd2; }

template <class F>
double median_ns(F f) {
  using clock = std::chrono::steady_clock;
  constexpr int kPasses = 5;
  std::vector<double> t, empty;
  double sink = 0;
  for (int pass = 0; pass < kPasses; ++pass)
    for (const auto& p : pairs()) {
      const auto t0 = clock::now();
      sink += f(p);
      const auto t1 = clock::now();
      const auto t2 = clock::now();
      t.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
      empty.push_back(std::chrono::duration<double, std::nano>(t2 - t1).count());
    }
  benchmark::DoNotOptimize(sink);
  auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  return median(t) - median(empty);
}

void print_medians() {
  std::printf("median per pair over %zu intersecting pairs (ns): rigid %.0f  static %.0f  "
              "pdd2 %.0f  accel1 %.0f  accel6 %.0f  solve_pair %.0f\n",
              pairs().size(), median_ns(v_rigid), median_ns(v_static), median_ns(v_pdd2),
              median_ns(v_accel1), median_ns(v_accel6), median_ns(v_solve));
}

}  // namespace

BENCHMARK_CAPTURE(BM, rigid_pd2, v_rigid);
BENCHMARK_CAPTURE(BM, pdd2_static, v_static);
BENCHMARK_CAPTURE(BM, pdd2, v_pdd2);
BENCHMARK_CAPTURE(BM, pdd2_accel1, v_accel1);
BENCHMARK_CAPTURE(BM, pdd2_accel6, v_accel6);
BENCHMARK_CAPTURE(BM, solve_pair, v_solve);

int main(int argc, char** argv) {
  print_medians();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
