#include "pdd/compare/engines.h"

#include <exception>
#include <string>

#include "pdd/io/progress.h"
#include "pdd/pdd.h"

namespace pdd::compare {
using io::FixtureEntry;
using io::Json;
using io::NumberWriter;
using io::Progress;
using io::result_json;

std::vector<reference::ExactResult> run_reference(const std::vector<FixtureEntry>& entries,
                                                  const reference::SolveOptions& options,
                                                  bool show_progress) {
  Progress progress("pdd: reference engine", entries.size(), show_progress ? 2.0 : 1e300);
  auto out = run_reference(entries, options, progress);
  progress.finish();
  return out;
}

reference::ExactResult solve_reference(const TetPair& pair, const reference::SolveOptions& options,
                                       const reference::GlobalOptions& budget) {
  try {
    return reference::solve_exact(pair, options, budget);
  } catch (const std::exception& ex) {  // an engine invariant failed: report, never crash
    reference::ExactResult r;
    r.name = pair.name;
    r.error = std::string("internal error in the reference engine: ") + ex.what();
    return r;
  }
}

std::vector<reference::ExactResult> run_reference(const std::vector<FixtureEntry>& entries,
                                                  const reference::SolveOptions& options,
                                                  Progress& progress) {
  return map_entries<reference::ExactResult>(
      entries, progress, [&](const TetPair& pair, std::size_t) { return solve_reference(pair, options); });
}

std::vector<PairResult<double>> run_fast(const std::vector<FixtureEntry>& entries,
                                         const fast::SolveOptions& options) {
  std::vector<TetPair> valid;
  for (const auto& e : entries)
    if (!e.error) valid.push_back(e.pair);
  std::vector<PairResult<double>> computed = fast::solve_batch(valid, options);
  std::vector<PairResult<double>> out(entries.size());
  for (std::size_t k = 0, v = 0; k < entries.size(); ++k) {
    if (entries[k].error) {
      out[k].name = entries[k].pair.name;
      out[k].error = *entries[k].error;
    } else {
      out[k] = std::move(computed[v++]);
      out[k].name = entries[k].pair.name;
    }
  }
  return out;
}

Json fast_record(const PairResult<double>& r, unsigned variants) {
  static const NumberWriter<double> number = [](const double& x) { return Json(x); };
  return io::asked_keys(result_json(r, number), variants);
}

Json exact_record(const reference::ExactResult& r, unsigned variants) {
  static const NumberWriter<reference::Rational> exact = [](const reference::Rational& q) {
    return Json(reference::to_string(q));
  };
  return io::asked_keys(result_json(r, exact), variants);
}

}  // namespace pdd::compare
