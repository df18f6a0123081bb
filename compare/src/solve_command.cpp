#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include <tbb/global_control.h>

#include "pdd/compare/commands.h"
#include "pdd/compare/engines.h"
#include "pdd/compare/result_json.h"

namespace pdd::compare {
namespace {

struct SolveArgs {
  std::string engine = "reference";
  std::string input;
  std::string output;
  std::string formulation = "full";
  bool quiet = false;
  int threads = 0;  // 0: all cores
};

// Exit codes shared by every subcommand: 0 all good, 1 some pair rejected, 2 nothing read.
constexpr int kPairRejected = 1;
constexpr int kFileError = 2;

template <class R, class Record>
int write_results(const std::vector<PairResult<R>>& results, Record record, std::ostream& out) {
  int status = 0;
  for (const auto& r : results) {
    out << record(r).dump() << '\n';
    if (r.error) {
      std::cerr << "pdd solve: pair '" << r.name << "' rejected: " << *r.error << '\n';
      status = kPairRejected;
    }
  }
  return status;
}

int run_solve(const SolveArgs& args) {
  const FixtureFile file = read_fixture_file(args.input);
  if (file.error) {
    std::cerr << "pdd solve: " << *file.error << '\n';
    return kFileError;
  }
  std::ofstream file_out;
  if (!args.output.empty()) {
    file_out.open(args.output);
    if (!file_out) {
      std::cerr << "pdd solve: cannot write '" << args.output << "'\n";
      return kFileError;
    }
  }
  std::ostream& out = args.output.empty() ? std::cout : file_out;
  std::optional<tbb::global_control> limit;
  if (args.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, args.threads);

  if (args.engine == "fast") {
    std::cerr << "pdd solve: " << file.entries.size() << " pairs, fast engine\n";
    std::size_t slow = 0;
    const auto results = run_fast(file.entries, &slow);
    std::cerr << "pdd solve: " << slow << " of " << file.entries.size()
              << " pairs took the exact path (SPEC §8: error bound wider than 1e-9)\n";
    return write_results(results, fast_record, out);
  }
  reference::SolveOptions options;
  options.formulation = args.formulation == "reduced" ? reference::QpFormulation::Reduced
                                                      : reference::QpFormulation::Full;
  std::cerr << "pdd solve: " << file.entries.size() << " pairs, reference engine, "
            << reference::to_string(options.formulation) << " QP formulation\n";
  const auto results = run_reference(file.entries, options, !args.quiet);
  return write_results(results, exact_record, out);
}

}  // namespace

void add_solve_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* cmd = app.add_subcommand(
      "solve", "Compute every SPEC §6 quantity for each pair of a fixture file; write JSON Lines.");
  cmd->add_option("--engine", args->engine,
                  "Engine: 'reference' (exact, numbers as \"p/q\" strings) or 'fast' (doubles, "
                  "JSON numbers that read back to the same double)")
      ->check(CLI::IsMember({"reference", "fast"}))
      ->capture_default_str();
  cmd->add_option("--input", args->input, "Fixture file (JSON, SPEC §1)")->required();
  cmd->add_option("--output", args->output, "Write JSON Lines here instead of standard output");
  cmd->add_option("--formulation", args->formulation,
                  "Reference QP formulation: 'full' (the paper's 27 variables) or 'reduced' "
                  "(SPEC §5 scalar form, same exact values, faster)")
      ->check(CLI::IsMember({"full", "reduced"}))
      ->capture_default_str();
  cmd->add_option("--threads", args->threads, "Worker threads (0: all cores)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag("--quiet", args->quiet, "No progress lines on standard error");
  cmd->callback([args, &exit_code] { exit_code = run_solve(*args); });
}

}  // namespace pdd::compare
