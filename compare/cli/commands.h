// commands.h — the subcommands of the `pdd` tool; each registers itself on the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>

namespace pdd::compare {

// `pdd solve --engine reference|fast --input FILE [--output FILE] [--formulation full|reduced]`
void add_solve_command(CLI::App& app, int& exit_code);

// `pdd generate --family NAME --seed S --count N [--output FILE] | --list`
void add_generate_command(CLI::App& app, int& exit_code);

// `pdd golden --check | --update [--fixtures DIR]`
void add_golden_command(CLI::App& app, int& exit_code);

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

// `pdd mesh --a A.msh (--b B.msh | --self) [--variants LIST] [--engine fast|reference] ...`
void add_mesh_command(CLI::App& app, int& exit_code);

}  // namespace pdd::compare
