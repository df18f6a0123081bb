// timing.cpp — see timing.h for the protocol.
#include "pdd/compare/timing.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "pdd/compare/stats.h"
#include "pdd/pdd.h"

namespace pdd::compare {
namespace {

using Clock = std::chrono::steady_clock;

// DoNotOptimize: the value must be materialised; the compiler cannot see through the asm.
template <class T>
inline void do_not_optimize(const T& value) {
  asm volatile("" : : "r,m"(value) : "memory");
}

double ns_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::nano>(b - a).count();
}

}  // namespace

std::string read_first_line(const char* path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}


std::vector<VariantTiming> time_functions(std::size_t count, const std::vector<TimedFunction>& fns,
                                          int repeats) {
  if (repeats < 1) throw std::invalid_argument("repeats must be >= 1");
  std::vector<VariantTiming> out(fns.size());
  std::vector<std::vector<double>> pass_ns(fns.size()), call_ns(fns.size());
  std::vector<double> overhead;
  double sink = 0;
  // Warm-up: caches, lazily built tables (FCL's collision matrix), page faults.
  for (const auto& f : fns)
    for (std::size_t k = 0; k < count; ++k) sink += f.call(k);
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t i = 0; i < fns.size(); ++i) {
      const auto& call = fns[i].call;
      const auto t0 = Clock::now();
      for (std::size_t k = 0; k < count; ++k) {
        const double v = call(k);
        do_not_optimize(v);
        sink += v;
      }
      const auto t1 = Clock::now();
      pass_ns[i].push_back(ns_between(t0, t1) / double(count));
    }
    for (std::size_t i = 0; i < fns.size(); ++i) {
      const auto& call = fns[i].call;
      auto& samples = call_ns[i];
      samples.reserve(samples.size() + count);
      for (std::size_t k = 0; k < count; ++k) {
        const auto t0 = Clock::now();
        const double v = call(k);
        do_not_optimize(v);
        const auto t1 = Clock::now();
        const auto t2 = Clock::now();
        sink += v;
        samples.push_back(ns_between(t0, t1));
        if (i == 0) overhead.push_back(ns_between(t1, t2));
      }
    }
  }
  do_not_optimize(sink);
  const double timer = median(overhead);
  for (std::size_t i = 0; i < fns.size(); ++i) {
    auto& t = out[i];
    t.name = fns[i].name;
    t.repeats = repeats;
    t.pairs = count;
    t.median_ns_per_pair = median(pass_ns[i]);
    t.min_ns_per_pair = *std::min_element(pass_ns[i].begin(), pass_ns[i].end());
    t.max_ns_per_pair = *std::max_element(pass_ns[i].begin(), pass_ns[i].end());
    t.median_call_ns = std::max(0.0, median(call_ns[i]) - timer);
  }
  return out;
}

std::vector<TimedFunction> fast_timed_functions(const std::vector<TetPair>& pairs) {
  const std::vector<TetPair>* p = &pairs;
  return {
      {"rigid_pd2", [p](std::size_t k) { return fast::rigid_pd2((*p)[k].A, (*p)[k].B).pd2; }},
      {"pdd2_static", [p](std::size_t k) { return fast::pdd2_static((*p)[k].A, (*p)[k].B).pd2; }},
      {"pdd2", [p](std::size_t k) { return fast::pdd2((*p)[k].A, (*p)[k].B).pd2; }},
      {"pdd2_relaxed", [p](std::size_t k) { return fast::pdd2_relaxed((*p)[k].A, (*p)[k].B).pd2; }},
      {"pdd2_accel1", [p](std::size_t k) { return fast::pdd2_accel((*p)[k].A, (*p)[k].B, 1).pd2; }},
      {"pdd2_accel6", [p](std::size_t k) { return fast::pdd2_accel((*p)[k].A, (*p)[k].B, 6).pd2; }},
      {"pdd2_global", [p](std::size_t k) { return fast::pdd2_global((*p)[k].A, (*p)[k].B).pd2; }},
      {"solve_pair", [p](std::size_t k) { return fast::solve_pair((*p)[k]).pdd2; }},
  };
}


std::vector<VariantTiming> time_fast_variants(const std::vector<TetPair>& pairs, int repeats) {
  return time_functions(pairs.size(), fast_timed_functions(pairs), repeats);
}

BatchTiming time_batch(const std::vector<TetPair>& pairs, int repeats) {
  if (repeats < 1) throw std::invalid_argument("repeats must be >= 1");
  BatchTiming b;
  b.pairs = pairs.size();
  b.threads = tbb::this_task_arena::max_concurrency();
  b.repeats = repeats;
  std::vector<double> s;
  {
    auto warm = fast::solve_batch(pairs);
    for (const auto& r : warm) {
      b.slow_paths += r.stats.slow_path;
      b.refined += r.stats.refined;
    }
    do_not_optimize(warm.data());
  }
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    auto res = fast::solve_batch(pairs);
    const auto t1 = Clock::now();
    do_not_optimize(res.data());
    s.push_back(ns_between(t0, t1) * 1e-9);
  }
  b.median_seconds = median(s);
  b.pairs_per_second = double(pairs.size()) / b.median_seconds;
  return b;
}

std::vector<double> time_each_call(std::size_t count, const std::function<void(std::size_t)>& call) {
  std::vector<double> ns;
  ns.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    const auto t0 = Clock::now();
    call(k);
    const auto t1 = Clock::now();
    ns.push_back(ns_between(t0, t1));
  }
  return ns;
}

MachineInfo machine_info() {
  MachineInfo m;
  {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
      if (line.rfind("model name", 0) == 0) {
        const auto c = line.find(':');
        m.cpu_model = c == std::string::npos ? line : line.substr(c + 2);
        break;
      }
  }
  if (m.cpu_model.empty()) m.cpu_model = "unknown";
  m.logical_cpus = std::thread::hardware_concurrency();
#if defined(__clang__)
  m.compiler = std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
  m.compiler = std::string("gcc ") + __VERSION__;
#else
  m.compiler = "unknown";
#endif
#ifdef NDEBUG
  m.assertions = false;
#else
  m.assertions = true;
#endif
  m.load_before = read_first_line("/proc/loadavg");
  return m;
}

}  // namespace pdd::compare
