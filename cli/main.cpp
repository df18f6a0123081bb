// pdd — penetration depth between tetrahedra: rigid PD and deformable PD_d (Kim & Kim).
// See README.md and docs/definitions.md. Exit status (exit_codes.h): 0 success, 1 some pair
// rejected or over tolerance, 2 unreadable input, usage error, failed write or unexpected error.
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

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
  // Examples at the end of each command's --help, run as written from the source tree by the
  // test python_help_examples (python/tests/test_help_examples.py).
  const std::vector<std::pair<std::vector<std::string>, std::string>> examples = {
      {{"solve"},
       "pdd solve --input fixtures/smoke.json --engine fast --format table\n"
       "  pdd solve --input fixtures/smoke.json --gradient --output smoke.jsonl"},
      {{"generate"}, "pdd generate --list\n  pdd generate --family paper --seed 7 --count 100 --output paper-7.json"},
      {{"golden"}, "pdd golden --check --fixtures fixtures"},
      {{"theorem"}, "pdd theorem --input fixtures/smoke.json --json"},
      {{"audit-ee"}, "pdd audit-ee --input fixtures/adversarial.json"},
      {{"compare"}, "pdd compare --input fixtures/adversarial.json"},
      {{"paper"}, "pdd paper --seed 7 --count 120 --exact-sample 120 --repeats 1 --out paper-out"},
      {{"bench"},
       "pdd bench --count 1000 --exact-sample 20 --repeats 1 --json bench.json\n"
       "  pdd bench --family aligned --count 300 --repeats 1"},
      {{"bench", "mesh"},
       "pdd bench mesh --a fixtures/meshes/sphere-a.msh --b fixtures/meshes/sphere-b.msh --repeats 1"},
      {{"bench", "resolve"}, "pdd bench resolve --cases shipped --repeats 1"},
      {{"bench", "energy"}, "pdd bench energy --cases balls --size 5000 --repeats 3"},
      {{"mesh"},
       "pdd mesh --a fixtures/meshes/sphere-a.msh --b fixtures/meshes/sphere-b.msh --output pairs.jsonl --summary\n"
       "  pdd mesh --a fixtures/meshes/two-spheres.msh --self --energy"},
      {{"resolve"},
       "pdd resolve --a fixtures/meshes/tiny-a.msh --b fixtures/meshes/tiny-b.msh --fix a --out-a a1.msh \\\n"
       "      --out-b b1.vtk --report report.json --summary"},
  };
  for (const auto& [path, text] : examples) {
    CLI::App* sub = &app;
    for (const auto& name : path) sub = sub->get_subcommand(name);
    sub->footer("\nExamples (from the source tree; docs/definitions.md defines every key printed):\n  " + text);
  }
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
