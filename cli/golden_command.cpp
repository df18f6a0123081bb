#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "pdd/cli/exit_codes.h"
#include "pdd/compare/golden.h"
#include "pdd/pdd.h"

namespace pdd::compare {
using io::golden_fixture_files;
namespace {

struct GoldenArgs {
  bool check = false, update = false;
  std::string fixtures = "fixtures";
  std::string formulation = to_string(reference::SolveOptions{}.formulation);  // pdd.h's default
  bool quiet = false;
};

int run_golden(const GoldenArgs& a) {
  const auto f = a.formulation == "full" ? QpFormulation::Full : QpFormulation::Reduced;
  std::error_code ec;
  if (!std::filesystem::is_directory(a.fixtures, ec)) {
    std::cerr << "pdd golden: no fixture folder '" << a.fixtures
              << "' (run from the repository's root, or give --fixtures DIR)\n";
    return kExitFileError;
  }
  try {
    if (a.update) {
      try {
        for (const auto& rel : update_golden(a.fixtures, f, !a.quiet)) std::cout << "wrote golden for " << rel << "\n";
      } catch (const GoldenRejection& e) {
        std::cerr << "pdd golden: " << e.what() << "\n";
        return kExitPairRejected;
      }
      return kExitOk;
    }
    const auto files = golden_fixture_files(a.fixtures);
    if (files.empty()) {  // a wrong folder must not pass the check
      std::cerr << "pdd golden: no fixture files under '" << a.fixtures << "'\n";
      return kExitFileError;
    }
    const auto mismatches = check_golden(a.fixtures, f, !a.quiet);
    for (const auto& m : mismatches) std::cout << "MISMATCH " << m.file << ": " << m.detail << "\n";
    std::cout << files.size() - mismatches.size() << " of " << files.size()
              << " golden files match the exact engine (" << to_string(f)
              << " formulation)\n";
    return mismatches.empty() ? kExitOk : kExitCheckFailed;
  } catch (const std::exception& e) {
    std::cerr << "pdd golden: " << e.what() << "\n";
    return kExitFileError;
  }
}

}  // namespace

void add_golden_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<GoldenArgs>();
  CLI::App* cmd = app.add_subcommand(
      "golden", "Check (digit for digit) or rewrite the exact engine's golden files.");
  auto* check = cmd->add_flag("--check", a->check, "Re-run the exact engine and compare");
  auto* update = cmd->add_flag("--update", a->update, "Rewrite fixtures/golden/ from the exact engine");
  check->excludes(update);
  cmd->add_option("--fixtures", a->fixtures, "Fixture folder")->capture_default_str();
  cmd->add_flag("--quiet", a->quiet, "No progress on standard error");
  cmd->add_option("--formulation", a->formulation,
                  "QP formulation ('reduced' equals 'full' exactly; see test_formulations)")
      ->check(CLI::IsMember({"full", "reduced"}))
      ->capture_default_str();
  cmd->callback([a, &exit_code, cmd] {
    if (!a->check && !a->update) throw CLI::ValidationError("golden", "give --check or --update");
    exit_code = run_golden(*a);
  });
}

}  // namespace pdd::compare
