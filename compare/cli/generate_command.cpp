#include <fstream>
#include <iostream>
#include <memory>

#include "cli_checks.h"
#include "commands.h"
#include "exit_codes.h"
#include "pdd/compare/fixture_io.h"
#include "pdd/compare/generate.h"
#include "pdd/compare/output.h"

namespace pdd::compare {
namespace {

struct GenerateArgs {
  std::string family;
  std::uint64_t seed = 1;
  std::size_t count = 10;
  std::string output;
  bool list = false;
};

int run_generate(const GenerateArgs& a) {
  if (a.list || a.family.empty()) {
    for (const auto& f : fixture_families()) std::cout << f.name << "\t" << f.description << "\n";
    if (!a.list) std::cerr << "pdd generate: give --family NAME (one of the above) or --list\n";
    return a.list ? kExitOk : kExitUsage;
  }
  std::vector<TetPair> pairs;
  try {
    pairs = generate_family(a.family, a.seed, a.count);
  } catch (const std::exception& e) {
    std::cerr << "pdd generate: " << e.what() << "\n";
    return kExitUsage;
  }
  const std::string text = fixture_json(pairs);
  std::optional<std::string> why;
  if (a.output.empty()) {
    std::cout << text;
    why = flush_error(std::cout, "standard output");
  } else {
    why = write_file(a.output, text);
  }
  if (why) {
    std::cerr << "pdd generate: " << *why << "\n";
    return kExitFileError;
  }
  return kExitOk;
}

}  // namespace

void add_generate_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<GenerateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "generate", "Write a reproducible fixture family (same seed and count, same bytes).");
  cmd->add_option("--family", a->family, "Family name (see --list)");
  cmd->add_option("--seed", a->seed, "Random seed (0 to 2^64-1)")
      ->check(seed_value())
      ->capture_default_str();
  cmd->add_option("--count", a->count, "Number of pairs")
      ->check(integer_in(0, 100000000))
      ->capture_default_str();
  cmd->add_option("--output", a->output, "Write here instead of standard output");
  cmd->add_flag("--list", a->list, "List the families and what each covers");
  cmd->callback([a, &exit_code] { exit_code = run_generate(*a); });
}

}  // namespace pdd::compare
