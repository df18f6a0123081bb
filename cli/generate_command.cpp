#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include <unistd.h>

#include "commands.h"
#include "pdd/cli/cli_checks.h"
#include "pdd/cli/exit_codes.h"
#include "pdd/compare/generate.h"
#include "pdd/io/fixture_io.h"
#include "pdd/io/output.h"
#include "pdd/io/progress.h"
#include "pdd/io/streaming.h"

namespace pdd::compare {
using io::InterruptGuard;
using io::InterruptScope;
using io::PartialFile;
using io::Progress;
using io::check_writable;
using io::close_error;
using io::fixture_json_entry;
using io::flush_error;
using io::interrupted_exit;
using io::kFixtureJsonHead;
using io::kFixtureJsonTail;
using io::pending_signal;
using io::replaced_by_rename;
namespace {

struct GenerateArgs {
  std::string family;
  std::uint64_t seed = 1;
  std::size_t count = 10;
  std::string output;
  bool list = false;
  bool quiet = false;
};

int run_generate(const GenerateArgs& a) {
  if (a.list || a.family.empty()) {
    for (const auto& f : fixture_families()) std::cout << f.name << "\t" << f.description << "\n";
    if (!a.list) std::cerr << "pdd generate: give --family NAME (one of the above) or --list\n";
    return a.list ? kExitOk : kExitUsage;
  }
  bool known = false;
  for (const auto& f : fixture_families()) known = known || f.name == a.family;
  if (!known) {
    std::cerr << "pdd generate: unknown family '" << a.family << "' (see pdd generate --list)\n";
    return kExitUsage;
  }
  // Pairs are written as they are made (memory does not grow with --count). A new or regular
  // --output file is written under a temporary name and renamed when complete (output.h).
  // Interrupted (SIGINT, SIGTERM): an existing file is left as it was (the temporary removed);
  // a new file, or standard output, is closed as a valid fixture file holding the pairs made
  // so far. A second signal removes the temporary (PartialFile).
  const std::string tmp = a.output.empty() || !replaced_by_rename(a.output)
                              ? "" : a.output + ".partial-" + std::to_string(::getpid());
  std::error_code exists_ec;
  const bool existed = !tmp.empty() && std::filesystem::exists(a.output, exists_ec);
  const PartialFile partial(tmp);
  const InterruptScope polled = InterruptScope::Polled();
  std::ofstream file;
  if (!a.output.empty()) {
    if (auto why = check_writable(a.output)) {
      std::cerr << "pdd generate: " << *why << "\n";
      return kExitFileError;
    }
    file.open(tmp.empty() ? a.output : tmp, std::ios::binary);
    if (!file) {
      std::cerr << "pdd generate: cannot write '" << (tmp.empty() ? a.output : tmp) << "'\n";
      return kExitFileError;
    }
  }
  std::ostream& out = a.output.empty() ? std::cout : file;
  const std::string where = a.output.empty() ? "standard output" : "'" + a.output + "'";
  Progress progress("pdd generate: " + a.family, a.count, a.quiet ? Progress::kNever : 2.0);
  InterruptGuard interrupts;
  std::size_t written = 0;
  out << kFixtureJsonHead;
  try {
    generate_family(a.family, a.seed, a.count, {}, [&](TetPair&& p) {
      out << (written++ ? ",\n  " : "  ") << fixture_json_entry(p);  // fixture_json's bytes
      progress.tick();
      return !pending_signal() && bool(out);
    });
  } catch (const std::exception& e) {
    std::cerr << "pdd generate: " << e.what() << "\n";
    if (!tmp.empty()) std::remove(tmp.c_str());
    return kExitUsage;
  }
  out << (written ? "\n" : "") << kFixtureJsonTail;
  progress.finish();
  std::optional<std::string> why = a.output.empty() ? flush_error(out, where) : close_error(file, a.output);
  std::error_code ec;
  if (const int sig = pending_signal(); sig && existed) {
    std::remove(tmp.c_str());
    std::cerr << "pdd generate: interrupted (signal " << sig << "): " << written << " of " << a.count
              << " pairs made; " << where << " left as it was (an existing file is replaced whole or not at all)\n";
    return interrupted_exit(sig);
  }
  if (!why && !tmp.empty()) {
    std::filesystem::rename(tmp, a.output, ec);
    if (ec) why = "cannot write " + where + ": " + ec.message();
  }
  if (why) {
    if (!tmp.empty()) std::remove(tmp.c_str());
    std::cerr << "pdd generate: " << *why << "\n";
    return kExitFileError;
  }
  if (const int sig = pending_signal()) {
    std::cerr << "pdd generate: interrupted (signal " << sig << "): " << written << " of " << a.count
              << " pairs written, as a complete fixture file (" << where << ")\n";
    return interrupted_exit(sig);
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
  cmd->add_flag("--quiet", a->quiet, "No progress on standard error");
  cmd->callback([a, &exit_code] { exit_code = run_generate(*a); });
}

}  // namespace pdd::compare
