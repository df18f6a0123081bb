// pdd — penetration depth between tetrahedra: rigid PD and deformable PD_d (Kim & Kim).
// See README.md and docs/definitions.md. Exit status (exit_codes.h): 0 success, 1 some pair
// rejected or over tolerance, 2 unreadable input, usage error, failed write or unexpected error.
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <string>

#include "commands.h"
#include "pdd/cli/exit_codes.h"
#include "pdd/compare/research_commands.h"
#include "pdd/io/output.h"
#include "pdd/io/streaming.h"

int main(int argc, char** argv) {
  using namespace pdd::compare;
  using namespace pdd::io;
  CLI::App app{
      "pdd: rigid and deformable penetration depth between tetrahedra (Kim & Kim), with an "
      "exact reference engine and a fast double-precision engine."};
  app.set_version_flag("--version", std::string("pdd ") + PDD_VERSION);
  app.require_subcommand(1);
  int exit_code = kExitOk;
  add_solve_command(app, exit_code);
  add_generate_command(app, exit_code);
  add_golden_command(app, exit_code);
  add_theorem_command(app, exit_code);
  add_audit_ee_command(app, exit_code);
  add_compare_command(app, exit_code);
  add_paper_command(app, exit_code);
  add_bench_command(app, exit_code);
  add_mesh_command(app, exit_code);
  add_resolve_command(app, exit_code);
  // The command runs under run_watched (streaming.h): SIGINT or SIGTERM is answered by the
  // command's InterruptScope (what it kept), or ends a command that writes its results at its
  // end with a word on standard error; either way the status is 128 + the signal.
  std::string command = "pdd";
  for (int k = 1; k < argc; ++k)
    if (argv[k][0] != '-') {
      command += std::string(" ") + argv[k];
      break;
    }
  try {
    run_watched(command, [&] {
      app.parse(argc, argv);
      return 0;
    });
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  } catch (const std::exception& e) {  // never abort: say what went wrong
    std::cerr << "pdd: error: " << e.what() << "\n";
    return kExitFileError;
  }
  // A command stopped by SIGINT or SIGTERM (streaming.h) ends with 128 + the signal.
  if (const int sig = pending_signal()) {
    std::cout.flush();
    return interrupted_exit(sig);
  }
  // Whatever a command wrote to standard output must have arrived (a full disk, a closed
  // pipe): results that were lost are an error, not a success.
  if (const auto why = flush_error(std::cout, "standard output")) {
    if (exit_code != kExitFileError) std::cerr << "pdd: " << *why << "\n";  // else said already
    return kExitFileError;
  }
  return exit_code;
}
