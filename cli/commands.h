// commands.h — the product subcommands of the `pdd` program; each registers itself on the
// CLI11 app. The research subcommands come from compare/ (pdd/compare/research_commands.h).
#pragma once

#include <CLI/CLI.hpp>

namespace pdd::compare {

// `pdd solve --engine reference|fast --input FILE [--output FILE] [--formulation reduced|full]
//   [--no-global | --gradient]`
void add_solve_command(CLI::App& app, int& exit_code);

// `pdd generate --family NAME --seed S --count N [--output FILE] | --list`
void add_generate_command(CLI::App& app, int& exit_code);

// `pdd golden --check | --update [--fixtures DIR]`
void add_golden_command(CLI::App& app, int& exit_code);

// `pdd mesh --a A.msh (--b B.msh | --self) [--variants LIST] [--engine fast|reference] ...`
void add_mesh_command(CLI::App& app, int& exit_code);

// `pdd resolve --a A.msh (--b B.msh | --self) --out-a A1.msh [--out-b B1.msh] [--fix a|b] ...`
void add_resolve_command(CLI::App& app, int& exit_code);

}  // namespace pdd::compare
