// `pdd resolve --a A.msh [--b B.msh | --self] [--fix a|b] [--variant global|pdd2|rigid]
//              [--max-rounds N] [--min-volume-ratio RHO] [--min-shape-ratio KAPPA] --out-a A1.msh|A1.vtk [--out-b B1.msh|B1.vtk]
//              [--report report.json] [--vtk both.vtk] [--summary] [--threads N] [--quiet]`
// New positions for the vertices of two tetrahedral meshes (or of one mesh with itself) after
// which no element pair intersects (R1), no element is inverted or flat (R2), fixed vertices
// are bit-for-bit unchanged (R3) and every element stays usable (R4: V1/V0 in [rho, 1/rho],
// eta1/eta0 >= kappa), each decided exactly on the doubles written out (library:
// pdd::mesh::resolve, include/pdd/mesh.h). The meshes are written with their connectivity
// unchanged (write_mesh: Gmsh 4.1 or legacy VTK by extension, every coordinate round-trip).
//
// Exit status: 0 when R1-R4 hold; 1 when the round limit was reached without them (the meshes
// are still written; standard error and the report name what remains), or when an input
// element was skipped (flat or non-finite: no check covers it; as `pdd mesh`); 2 when the command line
// is wrong, a mesh cannot be read or an output cannot be written (checked before the
// computation; nothing is written then); 130 / 143 on SIGINT / SIGTERM (the run stops after its
// current stage, nothing is written).
//
// Outputs are written as a set: each to a temporary file beside it, then all renamed, so that
// a failure leaves none of them (and no temporary file) rather than some.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <tuple>

#include <tbb/global_control.h>

#include "commands.h"
#include "pdd/cli/cli_checks.h"
#include "pdd/cli/exit_codes.h"
#include "pdd/io/output.h"
#include "pdd/io/resolve_report.h"
#include "pdd/io/streaming.h"
#include "pdd/mesh.h"

namespace pdd::compare {
using namespace pdd::io;  // file formats and streaming helpers
namespace {

// Defaults from mesh::ResolveOptions (the library's, printed by --help), typed nowhere else.
struct ResolveArgs {
  std::string a, b, fix, out_a, out_b, report, vtk;
  std::string variant = mesh::resolve_variant_name(mesh::ResolveOptions{}.variant);
  bool self = false, summary = false, quiet = false;
  std::size_t max_rounds = mesh::ResolveOptions{}.max_rounds;
  mesh::QualityLimits limits;  // --min-volume-ratio, --min-shape-ratio
  int threads = 0;
};

constexpr const char* kName = "pdd resolve";

std::string extension_of(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// Why `path` cannot be written, checked without changing anything: a file that will be
// replaced by a rename needs a new file in its folder (created and removed again here); a
// device, pipe or symbolic link is opened for appending (a pipe without a reader counts as
// writable: it would be opened when the results are ready).
std::optional<std::string> cannot_write(const std::string& path) {
  auto reason = [] { return errno ? std::string(": ") + std::strerror(errno) : std::string(); };
  if (replaced_by_rename(path)) {
    const std::string probe = path + ".partial-" + std::to_string(::getpid());
    errno = 0;
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd < 0) return "cannot write '" + path + "'" + reason();
    ::close(fd);
    ::unlink(probe.c_str());
    return std::nullopt;
  }
  errno = 0;
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_NONBLOCK);
  if (fd < 0 && errno != ENXIO) return "cannot write '" + path + "'" + reason();
  if (fd >= 0) ::close(fd);
  return std::nullopt;
}

// One output: written to `stage` (beside `path`, same extension) and renamed to `path` once
// every output is written; a device or pipe is written in place (stage == path).
struct Output {
  std::string path, stage;
  std::function<void(const std::string&)> write;
};

// Writes every output as described at the top; the reason when one failed (then none is left).
std::optional<std::string> write_outputs(std::vector<Output>& outputs) {
  std::error_code ec;
  std::optional<std::string> why;
  // Files first, devices and pipes last: a failure before the devices leaves nothing anywhere.
  std::stable_partition(outputs.begin(), outputs.end(), [](const Output& o) { return replaced_by_rename(o.path); });
  // A second signal (which ends the process at once) removes the staged files and the
  // temporaries they are themselves written through (atomic_file.h, output.h): no partial file
  // is left behind.
  std::vector<std::unique_ptr<PartialFile>> partial;
  std::size_t k = 0;
  for (; k < outputs.size() && !why; ++k) {
    Output& o = outputs[k];
    o.stage = replaced_by_rename(o.path)
                  ? o.path + ".partial-" + std::to_string(::getpid()) + extension_of(o.path)
                  : o.path;
    if (o.stage != o.path) {
      partial.push_back(std::make_unique<PartialFile>(o.stage));
      partial.push_back(std::make_unique<PartialFile>(o.stage + ".partial-" + std::to_string(::getpid())));
    }
    try {
      o.write(o.stage);
    } catch (const std::exception& e) {
      why = std::string(e.what());
      // the message names the temporary file: name the output instead
      for (std::size_t at; (at = why->find(o.stage)) != std::string::npos && o.stage != o.path;)
        why->replace(at, o.stage.size(), o.path);
    }
  }
  if (why) {
    for (std::size_t i = 0; i < k; ++i)
      if (outputs[i].stage != outputs[i].path) std::filesystem::remove(outputs[i].stage, ec);
    return why;
  }
  for (Output& o : outputs) {
    if (o.stage == o.path) continue;
    std::filesystem::rename(o.stage, o.path, ec);
    if (ec) {
      why = "cannot write '" + o.path + "': " + ec.message();
      std::filesystem::remove(o.stage, ec);
    }
  }
  return why;
}

int run_resolve(const ResolveArgs& args) {
  auto usage = [](const std::string& msg) {
    std::cerr << kName << ": " << msg << '\n';
    return kExitUsage;
  };
  if (args.self == !args.b.empty()) return usage("give either --b B or --self");
  if (args.self && args.fix == "b") return usage("--fix b: with --self there is no mesh B");
  if (args.self && !args.out_b.empty()) return usage("--out-b: with --self there is no mesh B (its result is --out-a)");
  if (!args.self && args.out_b.empty()) return usage("--out-b is missing: where to write the new mesh B");
  for (const auto& [flag, path] : {std::pair{"--out-a", args.out_a}, std::pair{"--out-b", args.out_b}})
    if (!path.empty() && extension_of(path) != ".msh" && extension_of(path) != ".vtk")
      return usage(std::string(flag) + " '" + path + "': unknown extension (.msh writes Gmsh 4.1, .vtk legacy VTK)");
  const std::vector<std::pair<const char*, std::string>> inputs = {{"--a", args.a}, {"--b", args.b}};
  const std::vector<std::pair<const char*, std::string>> outputs = {
      {"--out-a", args.out_a}, {"--out-b", args.out_b}, {"--report", args.report}, {"--vtk", args.vtk}};
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    for (const auto& [flag, path] : inputs)
      if (same_file(path, outputs[i].second))
        return usage(std::string(outputs[i].first) + " '" + outputs[i].second + "' is the same file as " + flag +
                     " (it would be overwritten)");
    for (std::size_t k = 0; k < i; ++k)
      if (same_file(outputs[k].second, outputs[i].second))
        return usage(std::string(outputs[i].first) + " '" + outputs[i].second + "' is the same file as " +
                     outputs[k].first);
  }
  mesh::ResolveOptions options;
  try {
    options.variant = mesh::parse_resolve_variant(args.variant);
  } catch (const std::exception& e) {
    return usage(std::string("--variant: ") + e.what());
  }
  options.fix_a = args.fix == "a";
  options.fix_b = args.fix == "b";
  options.max_rounds = args.max_rounds;
  static_cast<mesh::QualityLimits&>(options) = args.limits;

  mesh::Mesh A, B;
  try {
    A = mesh::read_mesh(args.a);
    if (!args.self) B = mesh::read_mesh(args.b);
  } catch (const mesh::ReadError& e) {
    std::cerr << kName << ": " << e.what() << '\n';
    return kExitFileError;
  }
  // Every output must be writable before the computation (which can take minutes).
  for (const auto& [flag, path] : outputs)
    if (!path.empty())
      if (auto why = cannot_write(path)) {
        std::cerr << kName << ": " << flag << ": " << *why << " (nothing computed, nothing written)\n";
        return kExitFileError;
      }

  std::optional<tbb::global_control> limit;
  if (args.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, args.threads);
  if (!args.quiet) {
    std::cerr << kName << ": A " << tetrahedra(A.tets.size());
    if (!args.self) std::cerr << ", B " << tetrahedra(B.tets.size());
    else std::cerr << " (self-contact)";
    std::cerr << ", variant " << args.variant;
    if (!args.fix.empty()) std::cerr << ", " << char(std::toupper(args.fix[0])) << " fixed";
    std::cerr << ", at most " << args.max_rounds << " rounds\n";
  }
  // Progress: the first round, then at most one line every 2 s (as Progress), and the last round.
  using Clock = std::chrono::steady_clock;
  Clock::time_point last_line{};
  bool said = false;
  std::size_t last_said = 0;
  mesh::ResolveRound last_round;
  options.progress = [&](const mesh::ResolveRound& r) {
    last_round = r;
    if (args.quiet) return;
    const auto now = Clock::now();
    if (said && now - last_line < std::chrono::seconds(2)) return;
    std::cerr << kName << ": round " << r.round << ": " << r.pairs << " intersecting pairs, max pd2 "
              << summary_number(r.max_pd2) << ", cost " << summary_cost(r.cost) << " ("
              << summary_number(r.seconds) << " s)\n";
    said = true, last_line = now, last_said = r.round;
  };
  std::atomic<bool> cancel{false};
  options.cancel = &cancel;

  // The solver runs on a thread of its own; this thread turns SIGINT / SIGTERM into `cancel`
  // (the solver stops at its next check) and waits for it. The scope lasts to the end: a signal
  // while the outputs are written lets them be written whole (write_outputs), then exits
  // 128 + signal (main).
  InterruptGuard interrupts;
  const InterruptScope polled = InterruptScope::Polled();
  std::optional<mesh::Resolution> result;
  std::exception_ptr failure;
  bool cancelled = false;
  {
    std::mutex m;
    std::condition_variable cv;
    bool finished = false;
    std::thread worker([&] {
      try {
        result = args.self ? mesh::resolve_self(A, options) : mesh::resolve(A, B, options);
      } catch (const mesh::Cancelled&) {
        cancelled = true;
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(m);
      finished = true;
      cv.notify_all();
    });
    std::unique_lock<std::mutex> lock(m);
    bool told = false;
    while (!cv.wait_for(lock, std::chrono::milliseconds(20), [&] { return finished; }))
      if (const int sig = pending_signal(); sig && !told) {
        cancel = true, told = true;
        std::cerr << "\n" << kName << ": interrupted (signal " << sig
                  << "): stopping after the current stage, nothing will be written (a second signal stops at once)\n";
      }
    lock.unlock();
    worker.join();
  }
  if (const int sig = pending_signal()) {
    std::cerr << kName << ": interrupted (signal " << sig << "): nothing written\n";
    return interrupted_exit(sig);
  }
  if (failure) {
    try {
      std::rethrow_exception(failure);
    } catch (const std::invalid_argument& e) {  // the library's check of the input: a bad mesh
      std::cerr << kName << ": " << e.what() << '\n';
      return kExitFileError;
    }
  }
  if (cancelled || !result) {  // cancel is set only on a signal, seen above
    std::cerr << kName << ": stopped; nothing written\n";
    return kExitFileError;
  }
  if (said && last_said != last_round.round) {  // the last round, if its line was skipped
    said = false;
    options.progress(last_round);
  }

  const mesh::Resolution& res = *result;
  const mesh::ResolveReport& rep = res.report;
  ResolveInputs in;
  in.a = args.a, in.b = args.b, in.self = args.self;
  in.fix = args.fix.empty() ? 0 : args.fix[0];
  in.max_rounds = args.max_rounds;
  in.elements_a = A.tets.size(), in.vertices_a = A.vertices.size();
  in.elements_b = B.tets.size(), in.vertices_b = B.vertices.size();
  in.fixed_vertices_a = options.fix_a ? A.vertices.size() : 0;
  in.fixed_vertices_b = options.fix_b ? B.vertices.size() : 0;
  const Json report = resolve_report_json(rep, in);

  std::vector<Output> files;
  files.push_back({args.out_a, "", [&](const std::string& p) { mesh::write_mesh(p, A, res.a); }});
  if (!args.self)
    files.push_back({args.out_b, "", [&](const std::string& p) { mesh::write_mesh(p, B, res.b); }});
  if (!args.report.empty())
    files.push_back({args.report, "", [&](const std::string& p) {
                       if (auto why = write_file(p, report.dump(2) + "\n")) throw std::runtime_error(*why);
                     }});
  if (!args.vtk.empty())
    files.push_back({args.vtk, "", [&](const std::string& p) {
                       if (args.self) mesh::write_resolution_vtk_self(p, A, res.a, rep);
                       else mesh::write_resolution_vtk(p, A, res.a, B, res.b, rep);
                     }});
  if (auto why = write_outputs(files)) {
    std::cerr << kName << ": " << *why << " (nothing written)\n";
    return kExitFileError;
  }

  for (const mesh::SkippedElement& s : rep.skipped) std::cerr << kName << ": skipped " << s.reason << '\n';
  if (args.summary) {
    // The meshes (and the report, the VTK) are complete on disk by now: a summary that cannot
    // be written is an output that could not be written (exit 2), and the message says the
    // files are whole so that nothing is recomputed for nothing.
    std::cout << resolve_summary(report);
    if (auto why = flush_error(std::cout, "standard output")) {
      std::string written;
      for (const Output& f : files) written += (written.empty() ? "'" : ", '") + f.path + "'";
      std::cerr << kName << ": the summary (--summary) could not be written: " << *why << "; "
                << written << " are written, each complete\n";
      return kExitFileError;
    }
  }
  if (rep.resolved) {
    if (!args.quiet)
      std::cerr << kName << ": resolved in " << rep.rounds.size()
                << (rep.rounds.size() == 1 ? " round" : " rounds") << " (method " << mesh::resolve_method_name(rep.method)
                << "; checked exactly: no pair intersects, no element inverted or flat, fixed vertices unchanged, "
                << "every element usable); cost " << summary_cost(rep.cost) << ", max displacement "
                << summary_number(rep.max_displacement) << ", volume ratio " << summary_number(rep.min_volume_ratio)
                << " to " << summary_number(rep.max_volume_ratio) << ", min shape ratio "
                << summary_number(rep.min_shape_ratio) << "\n";
    // As `pdd mesh`: a skipped element (flat or non-finite in the input) was in no pair and no
    // check, so the result is not vouched for there: exit 1, the elements named above.
    if (!rep.skipped.empty()) {
      std::cerr << kName << ": " << rep.skipped.size()
                << " input elements were skipped (named above): the checks do not cover them\n";
      return kExitPairRejected;
    }
    return kExitOk;
  }
  // Not resolved: what remains, always (also with --quiet).
  if (!rep.stopped_because.empty()) std::cerr << kName << ": stopped at once: " << rep.stopped_because << '\n';
  std::cerr << kName << ": NOT resolved after " << rep.rounds.size()
            << (rep.rounds.size() == 1 ? " round" : " rounds") << " (--max-rounds "
            << args.max_rounds << "); the meshes are written as they are\n";
  auto first = [](const auto& v, auto show) {
    std::string t;
    for (std::size_t k = 0; k < std::min<std::size_t>(v.size(), 10); ++k) t += (k ? ", " : "") + show(v[k]);
    if (v.size() > 10) t += ", ... (" + std::to_string(v.size() - 10) + " more)";
    return t;
  };
  auto tagged = [](const std::pair<char, std::size_t>& e) { return std::string(1, e.first) + " " + std::to_string(e.second); };
  if (!rep.r1)
    std::cerr << kName << ": " << rep.remaining_pairs.size() << " element pairs (a, b) still intersect: "
              << first(rep.remaining_pairs, [](const std::array<std::size_t, 2>& p) {
                   return "(" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ")";
                 })
              << '\n';
  if (!rep.r2)
    std::cerr << kName << ": " << rep.bad_elements.size() << " elements inverted or flat: " << first(rep.bad_elements, tagged) << '\n';
  if (!rep.r4)
    std::cerr << kName << ": " << rep.poor_elements.size() << " elements short of R4 (V1/V0 outside ["
              << summary_number(rep.limits.min_volume_ratio) << ", 1/" << summary_number(rep.limits.min_volume_ratio)
              << "] or eta1/eta0 below " << summary_number(rep.limits.min_shape_ratio)
              << "; smallest V1/V0 " << summary_number(rep.min_volume_ratio) << ", smallest eta1/eta0 "
              << summary_number(rep.min_shape_ratio) << "): " << first(rep.poor_elements, tagged) << '\n';
  if (!rep.r3)
    std::cerr << kName << ": " << rep.moved_fixed_vertices.size() << " fixed vertices moved: "
              << first(rep.moved_fixed_vertices, tagged) << '\n';
  return kExitCheckFailed;
}

}  // namespace

void add_resolve_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ResolveArgs>();
  CLI::App* cmd = app.add_subcommand(
      "resolve",
      "Move the vertices of two tetrahedral meshes (or of one, with itself) until no element pair "
      "intersects, no element is inverted or flat and fixed vertices are unchanged, each checked "
      "exactly on the numbers written; write the meshes with the same connectivity. Exit 0 "
      "resolved, 1 round limit reached (meshes still written, what remains named), 2 bad input "
      "or an output that could not be written (a mesh, the report or the VTK file: none is "
      "left; the --summary on standard output: the files are written whole and the message "
      "says so).");
  cmd->add_option("--a", args->a, "Mesh A (.msh or .vtk)")->required();
  cmd->add_option("--b", args->b, "Mesh B (.msh or .vtk); not with --self");
  cmd->add_flag("--self", args->self, "Self-contact of A: element pairs sharing no vertex");
  cmd->add_option("--fix", args->fix,
                  "Keep mesh 'a' or 'b' bit for bit where it is (only the other one moves); "
                  "default: both move")
      ->check(CLI::IsMember({"a", "b"}));
  cmd->add_option("--variant", args->variant,
                  "Per-pair solution that drives the vertices: 'global' (deformable depth over every "
                  "separating plane), 'pdd2' (over the candidate directions) or 'rigid' (each pair "
                  "pushed apart by its rigid translation: the baseline)")
      ->check(CLI::IsMember({"global", "pdd2", "rigid"}))
      ->capture_default_str();
  cmd->add_option("--max-rounds", args->max_rounds, "Rounds of contact solving before giving up (exit 1)")
      ->check(integer_in(1, 1000000))
      ->capture_default_str();
  for (auto [flag, value, what] :
       {std::tuple{"--min-volume-ratio", &args->limits.min_volume_ratio,
                   "R4: every element keeps V1/V0 in [rho, 1/rho]; rho in (0, 1]"},
        std::tuple{"--min-shape-ratio", &args->limits.min_shape_ratio,
                   "R4: every element keeps its mean-ratio shape quality eta1/eta0 >= kappa; kappa in (0, 1]"}})
    cmd->add_option(flag, *value, what)
        ->check(CLI::Validator(
            [](std::string& v) {
              double x = 0;
              std::size_t used = 0;
              try {
                x = std::stod(v, &used);
              } catch (const std::exception&) {
              }
              return used == v.size() && x > 0 && x <= 1 ? std::string() : "must be a number in (0, 1]; got " + v;
            },
            "(0, 1]", "ratio"))
        ->capture_default_str();
  cmd->add_option("--out-a", args->out_a, "Write the new mesh A here (.msh: Gmsh 4.1 ASCII, .vtk: legacy VTK)")
      ->required();
  cmd->add_option("--out-b", args->out_b, "Write the new mesh B here (.msh or .vtk); required with --b");
  cmd->add_option("--report", args->report,
                  "Write the report as JSON: per round the intersecting pairs, largest squared depth, "
                  "cost and time; at the end the three checks, what remains, cost, displacement, volumes, times");
  cmd->add_option("--vtk", args->vtk,
                  "Also write both new meshes in one legacy VTK file for ParaView, with the point "
                  "field 'displacement' and the cell fields mesh, element, volume_ratio, remaining, bad");
  cmd->add_flag("--summary", args->summary,
                "Print the report as a readable summary on standard output (the command writes "
                "nothing else there: its results are files)");
  cmd->add_option("--threads", args->threads, "Worker threads (0: all cores)")
      ->check(integer_in(0, 4096))
      ->capture_default_str();
  cmd->add_flag("--quiet", args->quiet,
                "No progress lines on standard error (what remains unresolved is still said)");
  cmd->callback([args, &exit_code] { exit_code = run_resolve(*args); });
}

}  // namespace pdd::compare
