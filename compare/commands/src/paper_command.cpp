// `pdd paper`: the paper's Sec. VI experiment reproduced (Table I, direction statistics,
// Fig. 2, Fig. 3), fast engine on every pair, exact engine on a random sample.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>

#include "pdd/cli/cli_checks.h"
#include "pdd/cli/exit_codes.h"
#include "pdd/compare/engine_comparison.h"
#include "pdd/compare/engines.h"
#include "pdd/compare/family_global_cost.h"
#include "pdd/compare/generate.h"
#include "pdd/compare/paper_experiment.h"
#include "pdd/compare/paper_figures.h"
#include "pdd/compare/paper_sample.h"
#include "pdd/compare/research_commands.h"
#include "pdd/compare/stats.h"
#include "pdd/compare/timing.h"
#include "pdd/io/output.h"
#include "pdd/io/progress.h"
#include "pdd/pdd.h"

namespace pdd::compare {
using io::write_file;
namespace {

struct PaperArgs {
  std::uint64_t seed = 1;
  std::size_t count = 10000;
  std::string out = "paper-out";
  std::size_t exact_sample = 200;
  int repeats = 5;
  double min_volume = 0.1, max_volume = 130;
  std::string fixtures = "fixtures";
  bool fixtures_given = false;  // --fixtures on the command line: a missing folder is then an error
};

std::string machine_description() {
  const MachineInfo m = machine_info();
  return m.cpu_model + ", " + std::to_string(m.logical_cpus) + " logical CPUs, " + m.compiler +
         (m.assertions ? ", assertions on (timings not representative)" : "");
}

std::string percent(const RatioStats& s) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(2) << 100 * s.mean << "% (" << 100 * s.std << "%)";
  return o.str();
}

std::string time_string(double ns) {
  std::ostringstream o;
  o << std::setprecision(3);
  if (ns < 1e3) o << ns << " ns";
  else if (ns < 1e6) o << ns / 1e3 << " µs";
  else o << ns / 1e6 << " ms";
  return o.str();
}

int run_paper_checked(const PaperArgs& a) {
  namespace fs = std::filesystem;
  if (!(a.min_volume < a.max_volume)) {
    std::cerr << "pdd paper: --min-volume (" << a.min_volume << ") must be below --max-volume ("
              << a.max_volume << ")\n";
    return kExitUsage;
  }
  if (a.fixtures_given && !fs::is_directory(a.fixtures + "/families")) {
    std::cerr << "pdd paper: --fixtures: no folder '" << a.fixtures << "/families'\n";
    return kExitUsage;
  }
  std::error_code ec;
  fs::create_directories(a.out, ec);
  if (ec || !fs::is_directory(a.out)) {
    std::cerr << "pdd paper: cannot make the output folder '" << a.out
              << "': " << (ec ? ec.message() : std::string("a file of that name exists")) << "\n";
    return kExitFileError;
  }
  // The same on the shipped fixture families (fast engine here, exact from their golden files),
  // first: a bad family or golden file then fails in seconds, before the long run.
  std::vector<FamilyGlobalCost> families;
  std::string families_note;
  if (a.fixtures_given || std::filesystem::is_directory(a.fixtures + "/families")) {
    std::cerr << "pdd paper: the fixture families in " << a.fixtures << "/families\n";
    families = family_global_costs(a.fixtures);
  } else {
    families_note = "(not run: no folder `" + a.fixtures + "/families`; run `pdd paper` from the repository's root or pass `--fixtures`)";
  }

  const PaperProtocol protocol{10.0, a.min_volume, a.max_volume};
  std::cerr << "pdd paper: generating " << a.count << " pairs (seed " << a.seed << ")\n";
  const auto pairs = generate_family("paper", a.seed, a.count, protocol);
  const auto unfiltered = generate_family("paper", a.seed, a.count, PaperProtocol{10.0, 0.0, std::numeric_limits<double>::infinity()});

  std::cerr << "pdd paper: fast engine on every pair\n";
  const auto fast = fast::solve_batch(pairs);
  const PaperStats fs_stats = paper_statistics(fast, [](double x) { return x; });
  std::cerr << "pdd paper: timing the fast engine (" << a.repeats << " repeats, one core)\n";
  const auto timings = time_fast_variants(pairs, a.repeats);
  auto timing_of = [&](const std::string& name) {
    for (const auto& t : timings)
      if (t.name == name) return time_string(t.median_ns_per_pair);
    return std::string("-");
  };

  const ExactSample sample = run_exact_sample(pairs, fast, a.exact_sample, a.seed);
  const PaperStats ex_stats = paper_statistics(sample.results, [](const reference::Rational& q) { return CGAL::to_double(q); });

  // definitions §9: the minimum over every plane, against the candidates.
  const GlobalStats fs_global = global_statistics(pairs, fast, [](double x) { return x; }, candidate_normals_rounded);
  std::vector<TetPair> sample_pairs;
  for (std::size_t i : sample.indices) sample_pairs.push_back(pairs[i]);
  const GlobalStats ex_global = global_statistics(
      sample_pairs, sample.results, [](const reference::Rational& q) { return CGAL::to_double(q); },
      candidate_normals_rounded);

  std::string why;
  const bool fig_global = write_global_figure(a.out, fs_global, why);
  if (!fig_global) std::cerr << "pdd paper: " << why << "\n";
  const bool fig3 = write_fig3(a.out, fs_stats, why);
  if (!fig3) std::cerr << "pdd paper: " << why << "\n";
  const PairConfigurations conf = pair_configurations(pairs[sample.indices[figure_pair(sample, pairs)]]);
  const bool fig2 = write_fig2(a.out, conf, why);
  if (!fig2) std::cerr << "pdd paper: " << why << "\n";
  write_vtk(a.out + "/pair_before_after.vtk", conf);

  // ------------------------------------------------------------------ the report
  std::ostringstream md;
  md << std::fixed << std::setprecision(2);
  md << "# pdd paper: Kim & Kim, Sec. VI, reproduced\n\n"
     << "Run: `pdd paper --seed " << a.seed << " --count " << a.count << " --exact-sample " << a.exact_sample
     << " --repeats " << a.repeats << "`. Protocol (docs/definitions.md §7): vertices uniform "
     << "in a cube of side 10; each "
     << "tetrahedron's volume in [" << a.min_volume << ", " << a.max_volume << "] (the paper's reported range); "
     << "intersecting pairs only. Machine: " << machine_description() << ".\n\n"
     << "PD_d/PD is sqrt(pdd2_x / rigid_pd2) per pair, PD the exact Minkowski-difference depth "
     << "(docs/definitions.md §4); "
     << "mean (sample standard deviation) over the pairs.\n\n"
     << "## Table I\n\n"
     << "| | STAT/DEF | DEF/DEF | DEF/DEF (ACCEL, first 1) | DEF/DEF (first 6) | DEF/DEF relaxed |\n"
     << "| --- | --- | --- | --- | --- | --- |\n| time per pair, paper (Gurobi, Ryzen 7 1700X) |";
  for (const auto& c : kPaperTableI) md << ' ' << c.time << " |";
  md << "\n| time per pair, pdd fast engine (one core, median of " << a.repeats << " runs) |";
  for (const char* v : kTimedVariant) md << ' ' << timing_of(v) << " |";
  md << "\n| time per pair, pdd exact engine (median over the exact sample, all variants together) | "
     << time_string(median(sample.call_ns)) << " | | | | |\n| PD_d/PD, paper |";
  for (const auto& c : kPaperTableI) md << ' ' << c.ratio << " |";
  md << "\n| PD_d/PD, pdd fast, " << fs_stats.pairs << " pairs |";
  for (const auto& s : fs_stats.over_pd) md << ' ' << percent(s) << " |";
  md << "\n| PD_d/PD, pdd exact, " << ex_stats.pairs << "-pair sample |";
  for (const auto& s : ex_stats.over_pd) md << ' ' << percent(s) << " |";
  md << "\n| PD_d/E11 (eq. 11 in place of PD), pdd fast |";
  for (const auto& s : fs_stats.over_e11) md << ' ' << percent(s) << " |";
  md << "\n\n## Directions\n\n| | paper | pdd fast | pdd exact sample |\n| --- | --- | --- | --- |\n"
     << "| rigid direction = optimal case-2 direction | 52.33% | "
     << 100.0 * fs_stats.rigid_is_optimal / fs_stats.pairs << "% | "
     << 100.0 * ex_stats.rigid_is_optimal / ex_stats.pairs << "% |\n"
     << "| case-2 optimum among the first six (depth order) | more than 90% | "
     << 100.0 * fs_stats.optimum_in_first_six / fs_stats.pairs << "% | "
     << 100.0 * ex_stats.optimum_in_first_six / ex_stats.pairs << "% |\n\n";

  auto quantile = [](std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::size_t(q * double(v.size() - 1))];
  };
  auto row = [&](const char* what, const RatioStats& f, const RatioStats& e) {
    md << "| " << what << " | " << std::setprecision(4) << f.mean << " (" << f.std << ") | "
       << quantile(f.values, 0.5) << " | " << quantile(f.values, 1.0) << " | " << e.mean << " ("
       << e.std << ") | " << quantile(e.values, 0.5) << " | " << quantile(e.values, 1.0) << " |\n";
  };
  md << "## What the paper's 44 directions cost (eq. 5 over every plane, docs/definitions.md §9)\n\n"
     << "pdd2_global is the minimum of the relaxed QP over every unit normal: the deformable depth "
     << "the paper defines in eq. 5 (its Sec. IV restricts the normal to the candidate directions). "
     << "The exact engine proves it to 1e-12 (a rational witness normal and a certified lower bound); "
     << "the fast engine enumerates the stationary points. Ratios of squared values (>= 1).\n\n"
     << "| | fast: mean (std) | median | max | exact sample: mean (std) | median | max |\n"
     << "| --- | --- | --- | --- | --- | --- | --- |\n";
  row("PD_d_global / PD", fs_global.global_over_pd, ex_global.global_over_pd);
  row("pdd2 / pdd2_global", fs_global.pdd2_over_global, ex_global.pdd2_over_global);
  row("pdd2_relaxed / pdd2_global", fs_global.relaxed_over_global, ex_global.relaxed_over_global);
  row("angle to the nearest candidate (degrees)", fs_global.angle_degrees, ex_global.angle_degrees);
  md << std::setprecision(2) << "\nThe global optimum is a candidate direction's (pdd2_relaxed within 1e-9 of it) on "
     << 100.0 * double(fs_global.at_candidate) / double(std::max<std::size_t>(1, fs_global.pairs))
     << "% of the " << fs_global.pairs << " pairs (fast) and "
     << 100.0 * double(ex_global.at_candidate) / double(std::max<std::size_t>(1, ex_global.pairs))
     << "% of the " << ex_global.pairs << " exact ones. Histograms: `global_cost.png`"
     << (fig_global ? "" : " (not drawn: gnuplot failed)") << ".\n\n";

  md << "### The same on the fixture families\n\n";
  if (families.empty()) {
    md << families_note << "\n\n";
  } else {
    md << "Every shipped family of `" << a.fixtures << "/families` (`pdd generate --list` says what each "
       << "covers): the fast engine run here, the exact engine's values read from the golden files. "
       << "Pairs counted: those that intersect and that neither engine rejects. Squared ratios, mean "
       << "(max); angle in degrees, mean (max); at candidate: pdd2_relaxed within 1e-9 of pdd2_global.\n\n"
       << "| family | pairs | counted (fast / exact) | pdd2_relaxed / pdd2_global, fast | exact | "
       << "pdd2 / pdd2_global, fast | PD_d_global / PD, fast | angle, fast | at candidate (fast / exact) |\n"
       << "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    auto mean_max = [](const RatioStats& s, int digits) {
      std::ostringstream o;
      if (s.n == 0) return std::string("-");
      o << std::setprecision(digits) << s.mean << " ("
        << *std::max_element(s.values.begin(), s.values.end()) << ")";
      return o.str();
    };
    for (const FamilyGlobalCost& f : families)
      md << "| " << f.family << " | " << f.pairs << " | " << f.fast.pairs << " / " << f.exact.pairs << " | "
         << mean_max(f.fast.relaxed_over_global, 5) << " | " << mean_max(f.exact.relaxed_over_global, 5) << " | "
         << mean_max(f.fast.pdd2_over_global, 5) << " | " << mean_max(f.fast.global_over_pd, 4) << " | "
         << mean_max(f.fast.angle_degrees, 3) << " | " << f.fast.at_candidate << " / " << f.exact.at_candidate
         << " |\n";
    md << "\n";
  }

  md << "## Exact sample: fast engine against exact arithmetic\n\n"
     << sample.indices.size() << " pairs drawn at random (seed " << a.seed << ") and solved exactly: "
     << sample.over_tolerance << " over the tolerance of `engine_comparison.h`, " << sample.labels_differ
     << " label disagreements. Largest relative errors:";
  md << std::scientific << std::setprecision(2);
  for (std::size_t v = 0; v < kValueCount; ++v)
    md << ' ' << kValueKeys[v] << ' ' << sample.max_rel_error[v] << (v + 1 < kValueCount ? "," : ".\n\n");
  md << std::fixed;

  const std::vector<double> probs = {0, 0.01, 0.05, 0.25, 0.5, 0.75, 0.95, 0.99, 1};
  const auto qf = quantiles(tetrahedron_volumes(pairs), probs);
  const auto qu = quantiles(tetrahedron_volumes(unfiltered), probs);
  md << "## Tetrahedron volumes\n\nThe paper reports volumes \"from 0.1 to 130\". Quantiles of the "
     << "volumes of A and B over the intersecting pairs, with the default filter and without it:\n\n"
     << "| | min | 1% | 5% | 25% | 50% | 75% | 95% | 99% | max |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  md << "| filtered [" << a.min_volume << ", " << a.max_volume << "] |";
  for (double q : qf) md << ' ' << std::setprecision(3) << q << " |";
  md << "\n| unfiltered |";
  for (double q : qu) md << ' ' << q << " |";
  md << "\n\n## Pictures\n\n";
  if (fig3) md << "![PD_d/PD histograms](fig3_histograms.png)\n\n";
  else md << "(fig. 3 not drawn: " << why << ")\n\n";
  md << std::setprecision(4) << "Pair `" << conf.name << "` (def/def ratio within 10% of the sample median, the largest PD for its size among those): PD = " << conf.pd
     << ", PD_d static/def = " << conf.pdd_static << ", def/def = " << conf.pdd
     << ". `pair_before_after.vtk` holds the same tetrahedra for ParaView (cell scalar `configuration`: "
     << "0 A rest, 1 B rest, 2 B static/def, 3 A def/def, 4 B def/def, 5 B rigid).\n\n";
  if (fig2) md << "![pair before and after](fig2_pair.png)\n";
  std::string text = md.str();
  if (auto why = write_file(a.out + "/report.md", text)) {
    std::cerr << "pdd paper: " << *why << "\n";
    return kExitFileError;
  }
  std::cout << text;
  std::cerr << "pdd paper: wrote " << a.out << "/report.md\n";
  return sample.over_tolerance ? kExitCheckFailed : kExitOk;
}

int run_paper(const PaperArgs& a) {
  try {
    return run_paper_checked(a);
  } catch (const std::exception& e) {  // e.g. no pair in the volume window, a failed write
    std::cerr << "pdd paper: " << e.what() << "\n";
    return kExitFileError;
  }
}

}  // namespace

void add_paper_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<PaperArgs>();
  CLI::App* cmd = app.add_subcommand("paper", "Reproduce the paper's experiment: Table I, direction statistics, Fig. 2 and 3.");
  cmd->add_option("--seed", a->seed, "Random seed (0 to 2^64-1)")->check(seed_value())->capture_default_str();
  cmd->add_option("--count", a->count, "Number of intersecting pairs")
      ->check(integer_in(1, 100000000))
      ->capture_default_str();
  cmd->add_option("--out", a->out, "Output folder (report.md, pictures, VTK)")->capture_default_str();
  cmd->add_option("--exact-sample", a->exact_sample, "Pairs also solved exactly (at least 200 for a fair check)")
      ->check(integer_in(1, 100000000))
      ->capture_default_str();
  cmd->add_option("--repeats", a->repeats, "Timing repeats (median)")
      ->check(integer_in(1, 1000))
      ->capture_default_str();
  cmd->add_option("--min-volume", a->min_volume, "Smallest tetrahedron volume kept")
      ->check(finite_number(0, false))
      ->capture_default_str();
  cmd->add_option("--max-volume", a->max_volume, "Largest tetrahedron volume kept")
      ->check(finite_number(0, true))
      ->capture_default_str();
  CLI::Option* fixtures = cmd->add_option(
      "--fixtures", a->fixtures,
      "Fixtures folder whose families/*.json (with their golden files) get the table of what "
      "the candidate directions cost against every plane too")
      ->capture_default_str();
  cmd->callback([a, fixtures, &exit_code] {
    a->fixtures_given = fixtures->count() > 0;
    exit_code = run_paper(*a);
  });
}

}  // namespace pdd::compare
