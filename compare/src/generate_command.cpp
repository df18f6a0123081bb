#include <fstream>
#include <iostream>
#include <memory>

#include "pdd/compare/commands.h"
#include "pdd/compare/fixture_io.h"
#include "pdd/compare/generate.h"

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
    return a.list ? 0 : 2;
  }
  std::vector<TetPair> pairs;
  try {
    pairs = generate_family(a.family, a.seed, a.count);
  } catch (const std::exception& e) {
    std::cerr << "pdd generate: " << e.what() << "\n";
    return 2;
  }
  const std::string text = fixture_json(pairs);
  if (a.output.empty()) {
    std::cout << text;
    return 0;
  }
  std::ofstream out(a.output);
  if (!(out << text)) {
    std::cerr << "pdd generate: cannot write '" << a.output << "'\n";
    return 2;
  }
  return 0;
}

}  // namespace

void add_generate_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<GenerateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "generate", "Write a reproducible fixture family (same seed and count, same bytes).");
  cmd->add_option("--family", a->family, "Family name (see --list)");
  cmd->add_option("--seed", a->seed, "Random seed")->capture_default_str();
  cmd->add_option("--count", a->count, "Number of pairs")->capture_default_str();
  cmd->add_option("--output", a->output, "Write here instead of standard output");
  cmd->add_flag("--list", a->list, "List the families and what each covers");
  cmd->callback([a, &exit_code] { exit_code = run_generate(*a); });
}

}  // namespace pdd::compare
