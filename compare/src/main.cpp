// pdd — penetration depth between tetrahedra: rigid PD and deformable PD_d (Kim & Kim).
// See README.md and SPEC.md. Exit status (exit_codes.h): 0 success, 1 some pair rejected or
// over tolerance, 2 unreadable input, usage error, failed write or unexpected error.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstring>
#include <exception>
#include <iostream>

#include "pdd/compare/commands.h"
#include "pdd/compare/exit_codes.h"

int main(int argc, char** argv) {
  using namespace pdd::compare;
  CLI::App app{
      "pdd: rigid and deformable penetration depth between tetrahedra (Kim & Kim), with an "
      "exact reference engine and a fast double-precision engine."};
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  } catch (const std::exception& e) {  // never abort: say what went wrong
    std::cerr << "pdd: error: " << e.what() << "\n";
    return kExitFileError;
  }
  // Whatever a command wrote to standard output must have arrived (a full disk, a closed
  // pipe): results that were lost are an error, not a success.
  errno = 0;
  std::cout.flush();
  if (!std::cout && exit_code != kExitFileError) {  // not said already by the command
    std::cerr << "pdd: cannot write to standard output"
              << (errno ? std::string(": ") + std::strerror(errno) : std::string()) << "\n";
    return kExitFileError;
  }
  return std::cout ? exit_code : kExitFileError;
}
