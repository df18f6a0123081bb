// research_commands.h — the research subcommands of the `pdd` program, each registered on the
// program's CLI11 app: the exact audits of the paper's claims, the engines judged against each
// other, the paper's experiment and the benchmark. The program (cli/) parses and dispatches;
// what each command computes and prints lives here, in compare/.
#pragma once

#include <CLI/CLI.hpp>

namespace pdd::compare {

// `pdd theorem --input FILE [--json] [--nef N]`
void add_theorem_command(CLI::App& app, int& exit_code);

// `pdd audit-ee --input FILE [--json]`
void add_audit_ee_command(CLI::App& app, int& exit_code);

// `pdd compare --input FILE [--json]`
void add_compare_command(CLI::App& app, int& exit_code);

// `pdd paper [--seed S] [--count N] [--out DIR] [--exact-sample M]`
void add_paper_command(CLI::App& app, int& exit_code);

// `pdd bench [--count N] [--seed S] [--repeats R] [--exact-sample M] [--json [FILE]]`
void add_bench_command(CLI::App& app, int& exit_code);

}  // namespace pdd::compare
