#include <algorithm>
#include <atomic>
#include <sstream>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <type_traits>
#include <memory>
#include <optional>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "commands.h"
#include "pdd/cli/cli_checks.h"
#include "pdd/cli/exit_codes.h"
#include "pdd/compare/engines.h"
#include "pdd/io/output.h"
#include "pdd/io/progress.h"
#include "pdd/io/record_line.h"
#include "pdd/io/record_text.h"
#include "pdd/io/result_json.h"
#include "pdd/io/streaming.h"
#include "pdd/mesh/variants.h"
#include "pdd/pdd.h"

namespace pdd::compare {
using io::FixtureCheck;
using io::FixtureEntry;
using io::FixtureFile;
using io::FixtureSink;
using io::OrderedLines;
using io::Progress;
using io::RecordFormat;
using io::check_fixture_file;
using io::close_error;
using io::flush_error;
using io::read_fixture_file;
using io::record_header;
using io::record_row;
using io::run_interruptible;
using io::stream_fixture_file;
namespace {

struct SolveArgs {
  std::string engine = "reference";
  std::string input;
  std::string output;
  std::string formulation = to_string(reference::SolveOptions{}.formulation);  // pdd.h's default
  bool quiet = false;
  int threads = 0;  // 0: all cores
  double global_gap = 1e-12;  // definitions §9's target for pdd2_global - pdd2_global_lower
  bool no_global = false;     // skip definitions §9: records without its keys
  std::string variants = "all";  // the values computed and written (pdd mesh's names)
  bool gradient = false;      // add pdd2_global_grad
  std::string format = "jsonl";
};

// Pairs are read this many at a time, so memory does not grow with the file; within a chunk
// they are solved in parallel and each record is written as soon as it and every record before
// it are done (streaming.h), so an interrupted run leaves a valid prefix of the output.
constexpr std::size_t kChunk = 4096;

// The note on standard error that goes with a record (written when the record is).
template <class R>
std::string record_note(const PairResult<R>& r, double gap) {
  std::ostringstream note;
  if (r.error) {
    note << "pdd solve: pair '" << printable(r.name) << "' rejected: " << *r.error << '\n';
  } else if (r.pdd2_global_error) {  // the other values are in the record
    note << "pdd solve: pair '" << printable(r.name) << "': " << *r.pdd2_global_error
         << " (its keys are null; the other values are reported)\n";
  }
  if constexpr (!std::is_same_v<R, double>) {  // definitions §9: say when the proof fell short
    if (r.pdd2_global_lower && r.pdd2_global > 0 && *r.pdd2_global_lower < r.pdd2_global * (1 - R(gap)))
      note << "pdd solve: pair '" << printable(r.name) << "': pdd2_global - pdd2_global_lower = "
           << CGAL::to_double((r.pdd2_global - *r.pdd2_global_lower) / r.pdd2_global)
           << " * pdd2_global, above --global-gap " << gap
           << " (the search budget ran out; the lower bound is still proved)\n";
  }
  return note.str();
}

int run_solve(const SolveArgs& args) {
  unsigned variants = 0;  // bit k < kValueCount: kValueKeys[k]; mesh::kGlobal: definitions §9
  try {
    variants = mesh::parse_variants(args.variants);
  } catch (const std::invalid_argument& e) {
    std::cerr << "pdd solve: --variants: " << e.what() << '\n';
    return kExitUsage;
  }
  if (args.no_global) variants &= ~unsigned(mesh::kGlobal);
  if (!variants) {
    std::cerr << "pdd solve: --no-global leaves nothing of --variants " << args.variants << '\n';
    return kExitUsage;
  }
  if (args.gradient && !(variants & mesh::kGlobal)) {
    std::cerr << "pdd solve: --gradient needs pdd2_global ('global' in --variants, no --no-global)\n";
    return kExitUsage;
  }
  // The table and CSV formats have one column per scalar value; the gradient (8 x 3 numbers a
  // pair) has no column there, so the combination is refused rather than dropped.
  if (args.gradient && args.format != "jsonl") {
    std::cerr << "pdd solve: --gradient needs --format jsonl (the '" << args.format
              << "' format has no pdd2_global_grad column)\n";
    return kExitUsage;
  }
  // The whole file is checked before anything is computed or written, so that a file that
  // cannot be read produces no output. A regular file is then read a second time in chunks;
  // anything else (a pipe) can be read only once and is held in memory.
  if (same_file(args.input, args.output)) {
    std::cerr << "pdd solve: --output '" << args.output << "' is the input file (it would be emptied before it is read)\n";
    return kExitUsage;
  }
  std::error_code ec;
  const bool regular = std::filesystem::is_regular_file(args.input, ec);
  FixtureFile whole;
  std::size_t total = 0;
  if (regular) {
    // A big file takes seconds to check (~12 s for 10^6 pairs): say so before the silence.
    const auto bytes = std::filesystem::file_size(args.input, ec);
    if (!args.quiet && !ec && bytes > (std::uintmax_t(16) << 20))
      std::cerr << "pdd solve: checking '" << args.input << "' (" << (bytes >> 20)
                << " MB) before computing anything\n";
    const io::InterruptScope checking([] { return std::string("nothing written: the input was still being checked"); });
    const FixtureCheck check = check_fixture_file(args.input);
    if (check.error) {
      std::cerr << "pdd solve: " << *check.error << '\n';
      return kExitFileError;
    }
    total = check.entries;
  } else {
    const io::InterruptScope reading([] { return std::string("nothing written: the input was still being read"); });
    whole = read_fixture_file(args.input);
    if (whole.error) {
      std::cerr << "pdd solve: " << *whole.error << '\n';
      return kExitFileError;
    }
    total = whole.entries.size();
  }
  std::ofstream file_out;
  if (!args.output.empty()) {
    errno = 0;
    file_out.open(args.output, std::ios::binary);
    if (!file_out) {
      std::cerr << "pdd solve: cannot write '" << args.output << "'"
                << (errno ? std::string(": ") + std::strerror(errno) : std::string()) << '\n';
      return kExitFileError;
    }
  }
  std::ostream& out = args.output.empty() ? std::cout : file_out;
  const std::string where = args.output.empty() ? "standard output" : "'" + args.output + "'";
  std::optional<tbb::global_control> limit;
  if (args.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, args.threads);

  const bool fast = args.engine == "fast";
  reference::SolveOptions options;
  options.formulation = args.formulation == "reduced" ? QpFormulation::Reduced
                                                      : QpFormulation::Full;
  options.with_global = (variants & mesh::kGlobal) != 0;
  options.gradient = args.gradient;
  reference::GlobalOptions budget;
  budget.gap = reference::Rational(args.global_gap);
  fast::SolveOptions fast_options;
  fast_options.with_global = options.with_global;
  fast_options.gradient = options.gradient;
  fast_options.values = variants & ((1u << kValueCount) - 1);  // (the exact engine computes all)
  if (!args.quiet) {
    if (fast)
      std::cerr << "pdd solve: " << total << " pairs, fast engine\n";
    else
      std::cerr << "pdd solve: " << total << " pairs, reference engine, "
                << to_string(options.formulation) << " QP formulation\n";
  }
  Progress progress(fast ? "pdd: fast engine" : "pdd: reference engine", total,
                    args.quiet ? Progress::kNever : 2.0);

  std::atomic<int> status{kExitOk};
  std::atomic<std::size_t> slow_paths{0};  // fast engine: pairs that took its exact path (definitions §8)
  std::atomic<std::size_t> refined{0};     // fast engine: pairs where a few candidates were evaluated exactly
  std::optional<std::string> write_error;
  const RecordFormat format = args.format == "table" ? RecordFormat::Table
                              : args.format == "csv" ? RecordFormat::Csv
                                                     : RecordFormat::Jsonl;
  if (format != RecordFormat::Jsonl) out << record_header(format) << '\n';
  OrderedLines lines(out);
  std::atomic<bool> stop{false};
  // One record: computed, its line and note handed to `lines` (any thread).
  auto solve_one = [&](const FixtureEntry& e, std::size_t k) {
    int code = kExitOk;
    if (fast) {
      PairResult<double> r;
      r.name = e.pair.name;
      if (e.error) {
        r.error = *e.error;
      } else {
        r = fast::solve_pair(e.pair, fast_options);
        r.name = e.pair.name;
        slow_paths += r.stats.slow_path;
        refined += r.stats.refined;
      }
      code = r.error || r.pdd2_global_error ? kExitPairRejected : kExitOk;
      // (JSON Lines: the record's text written directly, the same bytes: record_line.h)
      lines.done(k, format == RecordFormat::Jsonl ? io::record_line(r, variants) : record_row(fast_record(r, variants), format),
                 record_note(r, args.global_gap));
    } else {
      reference::ExactResult r;
      r.name = e.pair.name;
      if (e.error)
        r.error = *e.error;
      else
        r = solve_reference(e.pair, options, budget);
      code = r.error ? kExitPairRejected : kExitOk;
      lines.done(k, record_row(exact_record(r, variants), format), record_note(r, args.global_gap));
    }
    for (int s = status.load(); code > s && !status.compare_exchange_weak(s, code);) {
    }
    progress.tick();
  };
  const FixtureSink solve_chunk = [&](std::vector<FixtureEntry>& chunk, std::size_t) {
    lines.start(chunk.size());
    run_interruptible(
        [&] {
          tbb::parallel_for(std::size_t{0}, chunk.size(), [&](std::size_t k) {
            if (!stop) solve_one(chunk[k], k);
          });
        },
        lines, stop);
    lines.flush();
    if (!out) write_error = flush_error(out, where).value_or("cannot write to " + where);
    return !write_error;  // stop early: the results would be lost
  };
  if (regular) {
    if (auto why = stream_fixture_file(args.input, kChunk, solve_chunk); why && !write_error) {
      std::cerr << "pdd solve: " << *why << '\n';  // the file changed since it was checked
      return kExitFileError;
    }
  } else {
    for (std::size_t k = 0; k < whole.entries.size() && !write_error; k += kChunk) {
      std::vector<FixtureEntry> chunk(whole.entries.begin() + k,
                                      whole.entries.begin() + std::min(k + kChunk, whole.entries.size()));
      solve_chunk(chunk, k);
    }
  }
  progress.finish();
  if (fast && !args.quiet)
    std::cerr << "pdd solve: " << slow_paths << " of " << total
              << " pairs took the exact path (an error bound wider than the accuracy contract's "
                 "1e-9); " << refined
              << " were refined (a few candidates evaluated exactly)\n";
  if (!write_error)
    write_error = args.output.empty() ? flush_error(out, where) : close_error(file_out, args.output);
  if (write_error) {
    std::cerr << "pdd solve: " << *write_error << "; results lost\n";
    return kExitFileError;
  }
  return status;
}

}  // namespace

void add_solve_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* cmd = app.add_subcommand(
      "solve", "Compute every quantity for each pair of a fixture file; write JSON Lines (or a table, or CSV).");
  cmd->add_option("--engine", args->engine,
                  "Engine: 'reference' (exact, numbers as \"p/q\" strings; the default here) or "
                  "'fast' (doubles, JSON numbers that read back to the same double; the default of "
                  "pdd mesh and of Python's pdd.solve)")
      ->check(CLI::IsMember({"reference", "fast"}))
      ->capture_default_str();
  cmd->add_option("--input", args->input,
                  "Fixture file (JSON: {\"pairs\": [{\"name\", \"A\", \"B\"}, ...]}), or - for standard input")
      ->required();
  cmd->add_option("--output", args->output, "Write the records here instead of standard output");
  cmd->add_option("--format", args->format,
                  "Records as 'jsonl' (one JSON object a pair, every value exact or round-trip), "
                  "'table' (aligned columns for people: values as decimals, exact ones correctly "
                  "rounded to 17 digits and marked '~' where rounded) or 'csv' (a header row, one "
                  "column per value, for pandas or a spreadsheet)")
      ->check(CLI::IsMember({"jsonl", "table", "csv"}))
      ->capture_default_str();
  cmd->add_option("--formulation", args->formulation,
                  "Reference QP formulation: 'reduced' (the displacement along the separating "
                  "direction only; the default: about 7 times faster) or 'full' (the paper's 27 "
                  "variables); both give exactly the same values")
      ->check(CLI::IsMember({"full", "reduced"}))
      ->capture_default_str();
  cmd->add_option("--global-gap", args->global_gap,
                  "Reference engine: prove pdd2_global (docs/definitions.md §9) to this relative gap "
                  "(pdd2_global - pdd2_global_lower <= gap * pdd2_global)")
      ->check(finite_number(0, true) & CLI::Range(0.0, 0.5))
      ->capture_default_str();
  cmd->add_option("--threads", args->threads, "Worker threads (0: all cores)")
      ->check(integer_in(0, 4096))
      ->capture_default_str();
  cmd->add_flag("--no-global", args->no_global,
                 "Skip pdd2_global, the deformable depth over every separating plane (its keys are "
                 "left out of the records): faster (fast engine: ~3.5 of ~13 us a pair; reference: "
                 "its branch and bound)");
  cmd->add_option("--variants", args->variants,
                  "Values to compute and write, comma-separated, as pdd mesh names them: rigid "
                  "(rigid_pd2), eq11 (eq11_pd2), static (pdd2_static), pdd2 (pdd2, q1_A, q1_B), "
                  "relaxed (pdd2_relaxed), accel1 (pdd2_accel1), accel6 (pdd2_accel6), global "
                  "(pdd2_global and its keys), or all; a value's label comes with it, the others' "
                  "keys are left out of the records. Fast engine: each value has the bits it has "
                  "in the full record, and only it (and what it is kept against) is computed")
      ->capture_default_str();
  CLI::Option* gradient =
      cmd->add_flag("--gradient", args->gradient,
                    "Add pdd2_global_grad: the gradient of pdd2_global with respect to the eight "
                    "vertices at their current positions (the pair as given; A's four, then B's), "
                    "8 x [x, y, z]; null where pdd2_global is");
  gradient->excludes("--no-global");
  cmd->add_flag("--quiet", args->quiet, "No progress lines on standard error");
  cmd->callback([args, &exit_code] { exit_code = run_solve(*args); });
}

}  // namespace pdd::compare
