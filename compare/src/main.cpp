// pdd — penetration depth between tetrahedra: rigid PD and deformable PD_d (Kim & Kim).
// See README.md and SPEC.md. Exit status: 0 success, 1 some pair rejected or over
// tolerance, 2 unreadable input or usage error.
#include <CLI/CLI.hpp>

#include "pdd/compare/commands.h"

int main(int argc, char** argv) {
  CLI::App app{
      "pdd: rigid and deformable penetration depth between tetrahedra (Kim & Kim), with an "
      "exact reference engine and a fast double-precision engine."};
  app.require_subcommand(1);
  int exit_code = 0;
  pdd::compare::add_solve_command(app, exit_code);
  pdd::compare::add_generate_command(app, exit_code);
  pdd::compare::add_golden_command(app, exit_code);
  pdd::compare::add_theorem_command(app, exit_code);
  pdd::compare::add_audit_ee_command(app, exit_code);
  pdd::compare::add_compare_command(app, exit_code);
  pdd::compare::add_paper_command(app, exit_code);
  pdd::compare::add_bench_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  return exit_code;
}
