#include <algorithm>
#include <atomic>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>

#include <tbb/parallel_for.h>

#include "pdd/cli/exit_codes.h"
#include "pdd/compare/engine_comparison.h"
#include "pdd/compare/engines.h"
#include "pdd/compare/research_commands.h"
#include "pdd/compare/stats.h"
#include "pdd/io/output.h"
#include "pdd/io/progress.h"
#include "pdd/io/streaming.h"

namespace pdd::compare {
using io::FixtureFile;
using io::Json;
using io::read_fixture_file;
namespace {

struct CompareArgs {
  std::string input;
  bool json = false;
};

// stats.h's median; 0 when nothing was compared (the column is printed all the same).
double median_or_zero(const std::vector<double>& v) { return v.empty() ? 0 : median(v); }

Json comparison_json(const PairComparison& c) {
  Json j;
  j["name"] = c.name;
  j["over_tolerance"] = c.over_tolerance();
  if (c.exact_error || c.fast_error) {
    j["exact_error"] = c.exact_error ? Json(*c.exact_error) : Json(nullptr);
    j["fast_error"] = c.fast_error ? Json(*c.fast_error) : Json(nullptr);
    return j;
  }
  j["intersect_agree"] = c.intersect_agree;
  j["condition"] = c.condition;
  for (std::size_t k = 0; k < kValueCount; ++k)
    j[std::string(kValueKeys[k])] = {{"exact", c.exact_value[k]}, {"fast", c.fast_value[k]},
                                     {"rel_error", c.rel_error[k]}, {"tolerance", c.tolerance[k]}};
  j["position_error"] = c.position_error;
  j["position_tolerance"] = c.position_tolerance;
  j["separated"] = c.separated;
  j["pdd2_global"] = {{"exact", c.global_exact},
                      {"exact_lower", c.global_lower},
                      {"fast", c.global_declined ? Json(nullptr) : Json(c.global_fast)},
                      {"declined", c.global_declined ? Json(c.global_decline) : Json(nullptr)},
                      {"error", c.global_error},
                      {"normal_error", c.global_normal_error}};
  for (std::size_t k = 0; k < kLabelCount; ++k)
    j[std::string(kLabelKeys[k])] = {{"exact", c.exact_label[k]}, {"fast", c.fast_label[k]}, {"verdict", to_string(c.labels[k])}};
  return j;
}

void print_over(const PairComparison& c) {
  std::cout << "OVER TOLERANCE " << printable(c.name);
  if (!c.rejections_agree) {
    std::cout << ": exact " << (c.exact_error ? "rejects (" + *c.exact_error + ")" : "accepts")
              << ", fast " << (c.fast_error ? "rejects (" + *c.fast_error + ")" : "accepts") << "\n";
    return;
  }
  std::cout << " (R/PD = " << c.condition << ")\n";
  if (!c.intersect_agree) std::cout << "  intersecting: exact " << c.intersecting << ", fast " << !c.intersecting << "\n";
  for (std::size_t k = 0; k < kValueCount; ++k)
    if (!(c.rel_error[k] <= c.tolerance[k]))
      std::cout << "  " << kValueKeys[k] << ": exact " << std::setprecision(17) << c.exact_value[k]
                << " fast " << c.fast_value[k] << " rel error " << std::setprecision(3) << c.rel_error[k]
                << " > " << c.tolerance[k] << "\n";
  if (!(c.position_error <= c.position_tolerance))
    std::cout << "  q1 positions: object norm off pdd2 by " << c.position_error << " > "
              << c.position_tolerance << "\n";
  if (!c.separated) std::cout << "  q1 positions: not separated by the pdd2 plane up to 1e-9 R\n";
  if (c.global_declined && !(c.global_error <= kContractRel))
    std::cout << "  pdd2_global: the fast engine declined it where the contract requires it ("
              << c.global_decline << "); exact " << std::setprecision(17) << c.global_exact << "\n";
  else if (!(c.global_error <= kContractRel))
    std::cout << "  pdd2_global: fast " << std::setprecision(17) << c.global_fast
              << " outside the exact interval [" << c.global_lower << ", " << c.global_exact
              << "] by " << std::setprecision(3) << c.global_error << " relative\n";
  if (!(c.global_normal_error <= kContractRel))
    std::cout << "  pdd2_global_normal: the exact relaxed value along it is off the fast value by "
              << c.global_normal_error << "\n";
  for (std::size_t k = 0; k < kLabelCount; ++k)
    if (c.labels[k] == LabelVerdict::Differ)
      std::cout << "  " << kLabelKeys[k] << ": exact " << c.exact_label[k] << " fast " << c.fast_label[k] << "\n";
}

int run_compare(const CompareArgs& a) {
  const FixtureFile file = read_fixture_file(a.input);
  if (file.error) {
    std::cerr << "pdd compare: " << *file.error << "\n";
    return kExitFileError;
  }
  // The fast engine first (microseconds a pair), then the exact one pair by pair; with --json
  // each pair's object is written as soon as it and every one before it are compared
  // (streaming.h), so an interrupted run leaves whole objects in input order.
  const auto fast = run_fast(file.entries);
  const std::size_t n = file.entries.size();
  std::vector<PairComparison> cs(n);
  io::Progress progress("pdd: reference engine", n, 2.0);
  io::OrderedLines lines(std::cout);
  lines.start(n);
  std::atomic<bool> stop{false};
  const auto compare_all = [&] {
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t k) {
      if (stop) return;
      const io::FixtureEntry& e = file.entries[k];
      reference::ExactResult exact;
      exact.name = e.pair.name;
      if (e.error)
        exact.error = *e.error;
      else
        exact = solve_reference(e.pair, {QpFormulation::Reduced});
      cs[k] = compare_pair(e.pair, exact, fast[k]);
      if (a.json) lines.done(k, comparison_json(cs[k]).dump());
      progress.tick();
    });
  };
  if (a.json)
    io::run_interruptible(compare_all, lines, stop);
  else
    compare_all();  // the report is printed at the end
  progress.finish();

  std::array<std::vector<double>, kValueCount> errs;
  std::vector<double> pos, global, global_normal;
  double pos_share = 0;  // the largest position error as a share of its pair's allowance
  std::array<std::array<int, 5>, kLabelCount> verdicts{};  // per label, per LabelVerdict (5)
  int over = 0, intersect_agree = 0, compared = 0, rejected = 0;
  for (const auto& c : cs) {
    if (c.over_tolerance()) {
      ++over;
      if (!a.json) print_over(c);
    }
    if (c.exact_error || c.fast_error) {
      ++rejected;
      if (c.rejections_agree)
        std::cerr << "pdd compare: pair '" << printable(c.name) << "' rejected: "
                  << (c.fast_error ? *c.fast_error : *c.exact_error)
                  << (c.allowed_because.empty() ? "" : "; allowed: " + c.allowed_because) << "\n";
      continue;
    }
    ++compared;
    intersect_agree += c.intersect_agree;
    if (c.global_declined)
      // (the engine's own message names pdd2_global: "pdd2_global declined: ...")
      std::cerr << "pdd compare: pair '" << printable(c.name) << "': "
                << (c.allowed_because.empty() ? "the fast engine declined pdd2_global where the contract requires it: " : "")
                << c.global_decline << (c.allowed_because.empty() ? "" : "; allowed: " + c.allowed_because) << "\n";
    if (!c.intersecting) continue;
    for (std::size_t k = 0; k < kValueCount; ++k) errs[k].push_back(c.rel_error[k]);
    pos.push_back(c.position_error);
    pos_share = std::max(pos_share, c.position_error / c.position_tolerance);
    if (!c.global_declined || c.allowed_because.empty()) {
      global.push_back(c.global_error);
      global_normal.push_back(c.global_normal_error);
    }
    for (std::size_t k = 0; k < kLabelCount; ++k) ++verdicts[k][int(c.labels[k])];
  }
  std::ostream& s = a.json ? std::cerr : std::cout;
  s << "\nfast vs exact on " << compared << " pairs (" << rejected << " rejected by an engine), "
    << "the fast engine's accuracy contract (docs/definitions.md §8): relative error <= 1e-9, "
       "labels by exact value\n"
    << "intersecting agrees on " << intersect_agree << " of " << compared << "\n\n"
    << std::left << std::setw(18) << "quantity" << std::setw(14) << "max rel err" << std::setw(14) << "median" << "\n";
  for (std::size_t k = 0; k < kValueCount; ++k) {
    const double mx = errs[k].empty() ? 0 : *std::max_element(errs[k].begin(), errs[k].end());
    s << std::setw(18) << kValueKeys[k] << std::setw(14) << std::setprecision(3) << mx << std::setw(14) << median_or_zero(errs[k]) << "\n";
  }
  auto row = [&s](const char* key, const std::vector<double>& e, const char* note) {
    s << std::setw(18) << key << std::setw(14) << (e.empty() ? 0 : *std::max_element(e.begin(), e.end()))
      << std::setw(14) << median_or_zero(e) << note << "\n";
  };
  row("pdd2_global", global, "(outside the exact [pdd2_global_lower, pdd2_global])");
  row("global normal", global_normal, "(|exact relaxed along the fast normal - fast| / that)");
  s << std::setw(18) << "q1 positions" << std::setw(14) << (pos.empty() ? 0 : *std::max_element(pos.begin(), pos.end()))
    << std::setw(14) << median_or_zero(pos) << "(|sigma(q1) - pdd2| / pdd2, exact; each pair's allowance is 1e-9\n"
    << std::setw(46) << "" << "plus the rounding of positions to doubles, relative to pdd2:\n"
    << std::setw(46) << "" << "the largest error here is " << std::setprecision(3) << pos_share << " of its allowance)\n\n"
    << std::setw(18) << "label" << "same / tie / near-tie / differ\n";
  for (std::size_t k = 0; k < kLabelCount; ++k)
    s << std::setw(18) << kLabelKeys[k] << verdicts[k][0] << " / " << verdicts[k][1] << " / " << verdicts[k][2] << " / " << verdicts[k][3] << "\n";
  s << "\n" << over << " pair(s) over the contract, " << rejected << " rejected\n";
  return over || rejected ? kExitCheckFailed : kExitOk;
}

}  // namespace

void add_compare_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "Run both engines on every pair; report every disagreement.");
  cmd->add_option("--input", a->input, "Fixture file")->required();
  cmd->add_flag("--json", a->json, "One JSON object per pair on standard output (summary to stderr)");
  cmd->callback([a, &exit_code] { exit_code = run_compare(*a); });
}

}  // namespace pdd::compare
