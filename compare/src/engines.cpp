#include "pdd/compare/engines.h"

#include <tbb/parallel_for.h>

#include <exception>
#include <string>

#include "pdd/compare/progress.h"

namespace pdd::compare {

std::vector<reference::ExactResult> run_reference(const std::vector<FixtureEntry>& entries,
                                                  const reference::SolveOptions& options,
                                                  bool show_progress) {
  std::vector<reference::ExactResult> out(entries.size());
  Progress progress("pdd: reference engine", entries.size(), show_progress ? 2.0 : 1e300);
  tbb::parallel_for(std::size_t{0}, entries.size(), [&](std::size_t k) {
    const FixtureEntry& e = entries[k];
    if (e.error) {
      out[k].name = e.pair.name;
      out[k].error = *e.error;
    } else {
      try {
        out[k] = reference::solve_pair(e.pair, options);
      } catch (const std::exception& ex) {  // an engine invariant failed: report, never crash
        out[k] = reference::ExactResult{};
        out[k].name = e.pair.name;
        out[k].error = std::string("internal error in the reference engine: ") + ex.what();
      }
    }
    progress.tick();
  });
  progress.finish();
  return out;
}

Json exact_record(const reference::ExactResult& r) {
  static const NumberWriter<reference::Rational> exact = [](const reference::Rational& q) {
    return Json(reference::to_string(q));
  };
  return result_json(r, exact);
}

}  // namespace pdd::compare
