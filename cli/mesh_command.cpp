// `pdd mesh --a A.msh [--b B.msh | --self] [--variants LIST] [--engine fast|reference]
//           [--output pairs.jsonl] [--vtk out.vtk] [--summary] [--threads N] [--quiet]`
//          or `pdd mesh --a A [--b B | --self] --energy [--rest-a RA] [--rest-b RB] [--engine E] [--output energy.json]`
// Every intersecting element pair of two tetrahedral meshes (or of one mesh with itself) and
// its penetration depths (definitions §10; library: include/pdd/mesh.h). One JSON Lines record per
// pair, sorted by (a, b): {"a": i, "b": j, "intersecting", the requested values and their
// labels, q1_A and q1_B when pdd2 is requested, "error", and with global definitions §9's
// pdd2_global, pdd2_global_normal, q1_A_global, q1_B_global (and pdd2_global_lower with the
// reference engine)} — definitions §6's keys and order, with a and b in place of name (`--variants
// all`: every key). Exit status as for `pdd solve`: 0,
// 1 when an element was skipped (flat, non-finite) or a pair rejected, 2 when a mesh cannot be
// read, the command line is wrong or an output cannot be written.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>

#include <tbb/global_control.h>

#include "commands.h"
#include "pdd/cli/cli_checks.h"
#include "pdd/cli/exit_codes.h"
#include "pdd/io/output.h"
#include "pdd/io/progress.h"
#include "pdd/io/record_line.h"
#include "pdd/io/result_json.h"
#include "pdd/io/streaming.h"
#include "pdd/io/summary_text.h"
#include "pdd/mesh.h"

namespace pdd::compare {
using io::OrderedLines;
using io::run_interruptible;
using io::Json;
using io::Progress;
using io::close_error;
using io::flush_error;
using io::summary_line;
using io::summary_number;
using io::tetrahedra;
using io::padded_left;
using io::kSummaryLabel;
namespace {

struct MeshArgs {
  std::string a, b, engine = "fast", output, vtk, rest_a, rest_b;
  std::string variants = mesh::variant_names(mesh::ContactOptions{}.variants);  // the library's default
  bool self = false, summary = false, quiet = false, energy = false;
  int threads = 0;
};

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

double as_double(double x) { return x; }
double as_double(const Rational& x) { return x.get_d(); }

// The note on standard error that goes with a record (written when the record is).
template <class R>
std::string contact_note(const mesh::Contact<R>& p, unsigned variants) {
  std::ostringstream note;
  if (p.result.error)
    note << "pdd mesh: pair (" << p.a << ", " << p.b << ") rejected: " << *p.result.error << '\n';
  else if (p.result.pdd2_global_error && (variants & mesh::kGlobal))
    note << "pdd mesh: pair (" << p.a << ", " << p.b << "): " << *p.result.pdd2_global_error
         << " (its keys are null; the other values are reported)\n";
  return note.str();
}

// What follows the records: the skipped elements, the VTK file and the summary. The records
// were written as they were computed (run_mesh).
template <class R>
int report(const MeshArgs& args, const mesh::Mesh& A, const mesh::Mesh* B,
           const mesh::Contacts<R>& c, unsigned variants, double read_seconds) {
  int status = kExitOk;
  for (const auto& s : c.skipped) {
    std::cerr << "pdd mesh: skipped " << s.reason << '\n';
    status = kExitPairRejected;
  }
  std::size_t errors = 0;
  for (const auto& p : c.pairs) {
    if (p.result.error) ++errors;
    if (p.result.error || (p.result.pdd2_global_error && (variants & mesh::kGlobal))) status = kExitPairRejected;
  }
  if (!args.vtk.empty()) {
    try {
      if (B) mesh::write_vtk(args.vtk, A, *B, c, variants);
      else mesh::write_vtk_self(args.vtk, A, c, variants);
    } catch (const std::exception& e) {
      std::cerr << "pdd mesh: " << e.what() << '\n';
      return kExitFileError;
    }
  }
  if (args.summary) {
    // One rule for every command: the summary goes to standard output unless standard output
    // holds the records (no --output), then to standard error.
    std::ostringstream s;
    s << "pdd mesh: " << (B ? "A against B" : "self-contact of A") << " ("
      << (args.engine == "fast" ? "fast" : "reference") << " engine, variants "
      << mesh::variant_names(variants) << ")\n"
      << summary_line("mesh A", args.a + ": " + tetrahedra(c.elements_a));
    if (B) s << summary_line("mesh B", args.b + ": " + tetrahedra(c.elements_b));
    std::string skipped = std::to_string(c.skipped.size()) + " elements";
    for (std::size_t k = 0; k < std::min<std::size_t>(c.skipped.size(), 3); ++k) skipped += "\n" + c.skipped[k].reason;
    s << summary_line("skipped", skipped)
      << summary_line("box pairs", std::to_string(c.box_pairs) + (B ? "" : " (sharing no vertex)"))
      << summary_line("intersecting", std::to_string(c.pairs.size()) + " pairs" +
                                          (errors ? " (" + std::to_string(errors) + " rejected)" : ""))
      << summary_line("time (s)", summary_number(read_seconds + c.seconds_boxes + c.seconds_broadphase +
                                                 c.seconds_decision + c.seconds_depth) +
                                      " total: read " + summary_number(read_seconds) + ", boxes " +
                                      summary_number(c.seconds_boxes) + ", broadphase " +
                                      summary_number(c.seconds_broadphase) + ", exact decision " +
                                      summary_number(c.seconds_decision) + ", depth " +
                                      summary_number(c.seconds_depth));
    // One row per requested value: its sum and maximum over the pairs, and the pair attaining it.
    const std::string indent(2 + kSummaryLabel, ' ');
    s << "  " << std::string("value") << std::string(kSummaryLabel - 5, ' ') << padded_left("sum", 12) << "  "
      << padded_left("max", 12) << "  at (a, b)\n";
    for (std::size_t k = 0; k < mesh::kVariantCount; ++k) {
      if (!(variants & (1u << k))) continue;
      double sum = 0, best = -1;
      const mesh::Contact<R>* arg = nullptr;
      for (const auto& p : c.pairs) {
        if (p.result.error) continue;
        const double v = as_double(mesh::variant_value(p.result, k));
        if (std::isnan(v)) continue;  // pdd2_global declined (named above)
        sum += v;
        if (v > best) best = v, arg = &p;
      }
      const std::string key = mesh::kVariantKeys[k];
      s << "  " << key << std::string(key.size() < kSummaryLabel ? kSummaryLabel - key.size() : 1, ' ')
        << padded_left(summary_number(sum), 12) << "  " << padded_left(summary_number(arg ? best : 0.0), 12);
      if (arg) s << "  (" << arg->a << ", " << arg->b << ")";
      s << "\n";
    }
    if (args.output.empty()) {
      std::cerr << s.str();
    } else {
      // The records (and the VTK file) are complete on disk by now: say so if the summary fails.
      std::cout << s.str();
      if (auto why = flush_error(std::cout, "standard output")) {
        std::cerr << "pdd mesh: the summary (--summary) could not be written: " << *why << "; '"
                  << args.output << "'" << (args.vtk.empty() ? "" : ", '" + args.vtk + "'")
                  << " written, complete\n";
        return kExitFileError;
      }
    }
  }
  return status;
}

// --energy: the contact energy (definitions §12) at the meshes' positions, one JSON object:
// energy, pairs, max_pdd2_global, max_force (largest |dE/dp| over the vertices), max_force_vertex
// (its index, A's vertices first), skipped (the elements left out, as pdd.contact_energy's),
// seconds (docs/definitions.md "Contact energy"). Exit status as without --energy: 1 when an
// element was skipped.
// The weights: a side's rest shape where given (--rest-a, --rest-b: the same tetrahedra, its
// vertices the rest positions; held constant, as a simulator's), else the file's own positions,
// following them (as Python's rest_A=None: the gradient then includes the weights' derivative,
// which grows like V^(-2/3) on a nearly flat element).
int run_energy(const MeshArgs& args, const mesh::Mesh& A, const mesh::Mesh* B) {
  mesh::ContactEnergyOptions o;
  o.engine = args.engine == "fast" ? mesh::EnergyEngine::Fast : mesh::EnergyEngine::Exact;
  mesh::Mesh read_a, read_b;  // the rest files' meshes, where given
  const mesh::Mesh* rest_a = &A;
  const mesh::Mesh* rest_b = B;
  auto rest_of = [](const std::string& path, const mesh::Mesh& current, const char* flag, mesh::Mesh& rest,
                    const mesh::Mesh*& use) {
    if (path.empty()) return true;
    try {
      rest = mesh::read_mesh(path);
      use = &rest;
    } catch (const mesh::ReadError& e) {
      std::cerr << "pdd mesh: " << flag << ": " << e.what() << '\n';
      return false;
    }
    if (rest.vertices.size() != current.vertices.size() || rest.tets != current.tets) {
      std::cerr << "pdd mesh: " << flag << " '" << path << "' is not the same mesh (" << rest.vertices.size()
                << " vertices, " << rest.tets.size() << " tetrahedra against " << current.vertices.size() << " and "
                << current.tets.size() << ", or other tetrahedra): a rest shape has the mesh's vertices and tetrahedra\n";
      return false;
    }
    return true;
  };
  if (!rest_of(args.rest_a, A, "--rest-a", read_a, rest_a) || (B && !rest_of(args.rest_b, *B, "--rest-b", read_b, rest_b)))
    return kExitFileError;
  o.weights_follow_a = args.rest_a.empty();
  o.weights_follow_b = args.rest_b.empty();
  const auto t0 = Clock::now();
  const mesh::ContactEnergy e = B ? mesh::contact_energy(*rest_a, *rest_b, A.vertices, B->vertices, o)
                                  : mesh::contact_energy_self(*rest_a, A.vertices, o);
  double max_force = 0;
  std::size_t at = 0;
  for (std::size_t v = 0; v < e.gradient.size(); ++v) {
    const auto& g = e.gradient[v];
    const double f = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    if (f > max_force) max_force = f, at = v;
  }
  Json j = {{"energy", e.energy}, {"pairs", e.pair_count}, {"max_pdd2_global", e.max_pdd2_global},
            {"max_force", max_force}, {"max_force_vertex", e.pair_count ? Json(at) : Json(nullptr)},
            {"skipped", Json::array()}, {"seconds", since(t0)}};
  int status = kExitOk;
  for (const auto& s : e.skipped) {
    j["skipped"].push_back({{"mesh", std::string(1, s.mesh)}, {"index", s.index}, {"reason", s.reason}});
    std::cerr << "pdd mesh: skipped " << s.reason << '\n';
    status = kExitPairRejected;
  }
  if (args.output.empty()) {
    std::cout << j.dump() << '\n';
  } else {
    std::ofstream out(args.output);
    out << j.dump() << '\n';
    if (!out) {
      std::cerr << "pdd mesh: cannot write " << args.output << '\n';
      return kExitFileError;
    }
  }
  return status;
}

int run_mesh(const MeshArgs& args) {
  if (args.self == !args.b.empty()) {
    std::cerr << "pdd mesh: give either --b B or --self\n";
    return kExitUsage;
  }
  if (!args.energy && (!args.rest_a.empty() || !args.rest_b.empty())) {  // (CLI11's needs() cannot say why)
    std::cerr << "pdd mesh: --rest-a and --rest-b are the contact energy's weights: give them with --energy\n";
    return kExitUsage;
  }
  for (const auto& [flag, path] : {std::pair{"--a", args.a}, std::pair{"--b", args.b}, std::pair{"--rest-a", args.rest_a},
                                   std::pair{"--rest-b", args.rest_b}, std::pair{"--output", args.output}})
    for (const auto& [oflag, opath] : {std::pair{"--output", args.output}, std::pair{"--vtk", args.vtk}})
      if (std::string(flag) != oflag && same_file(path, opath)) {
        std::cerr << "pdd mesh: " << oflag << " '" << opath << "' is the same file as " << flag
                  << " (it would be overwritten)\n";
        return kExitUsage;
      }
  unsigned variants = 0;
  try {
    variants = mesh::parse_variants(args.variants);
  } catch (const std::exception& e) {
    std::cerr << "pdd mesh: --variants: " << e.what() << '\n';
    return kExitUsage;
  }
  std::optional<tbb::global_control> limit;
  if (args.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, args.threads);

  const auto t0 = Clock::now();
  mesh::Mesh A, B;
  try {
    A = mesh::read_mesh(args.a);
    if (!args.self) B = mesh::read_mesh(args.b);
  } catch (const mesh::ReadError& e) {
    std::cerr << "pdd mesh: " << e.what() << '\n';
    return kExitFileError;
  }
  const double read_seconds = since(t0);
  const bool fast = args.engine == "fast";
  if (!args.quiet) {
    std::cerr << "pdd mesh: A " << tetrahedra(A.tets.size());
    if (!args.self) std::cerr << ", B " << tetrahedra(B.tets.size());
    std::cerr << ", " << (fast ? "fast" : "reference") << " engine, "
              << (args.energy ? std::string("contact energy") : "variants " + mesh::variant_names(variants)) << '\n';
  }

  if (args.energy) return run_energy(args, A, args.self ? nullptr : &B);

  std::once_flag once;
  std::unique_ptr<Progress> progress;
  mesh::ContactOptions options;
  options.variants = variants;
  const mesh::Mesh* Bp = args.self ? nullptr : &B;

  // Records are written as they are computed, in (a, b) order (streaming.h): an interrupted
  // run leaves whole records, a prefix of the complete output.
  std::ofstream file_out;
  if (!args.output.empty()) {
    errno = 0;
    file_out.open(args.output, std::ios::binary);
    if (!file_out) {
      std::cerr << "pdd mesh: cannot write '" << args.output << "'"
                << (errno ? std::string(": ") + std::strerror(errno) : std::string()) << '\n';
      return kExitFileError;
    }
  }
  std::ostream& out = args.output.empty() ? std::cout : file_out;
  OrderedLines lines(out);
  std::atomic<bool> stop{false};
  options.cancel = &stop;
  options.progress = [&](std::size_t n, std::size_t total) {
    std::call_once(once, [&] {
      lines.start(total);  // n = 0 comes first, before any pair
      progress = std::make_unique<Progress>("pdd mesh: pairs", total, args.quiet ? 1e300 : 2.0);
    });
    progress->tick(n);
  };
  // (each line the definitions §6 record of one contact, keys of unrequested variants dropped,
  // a and b first)
  options.fast_pair = [&](std::size_t h, const mesh::Contact<double>& c) {
    lines.done(h, io::contact_line(c.a, c.b, c.result, variants), contact_note(c, variants));
  };
  options.exact_pair = [&](std::size_t h, const mesh::Contact<Rational>& c) {
    lines.done(h, io::contact_line(c.a, c.b, c.result, variants), contact_note(c, variants));
  };
  std::optional<mesh::Contacts<double>> fast_result;
  std::optional<mesh::Contacts<Rational>> exact_result;
  run_interruptible(
      [&] {
        if (fast)
          fast_result = args.self ? mesh::contacts_self(A, options) : mesh::contacts(A, B, options);
        else
          exact_result = args.self ? mesh::contacts_exact_self(A, options) : mesh::contacts_exact(A, B, options);
      },
      lines, stop, "(a, b) order");
  lines.flush();
  if (progress) progress->finish();
  const std::string where = args.output.empty() ? "standard output" : "'" + args.output + "'";
  if (auto why = args.output.empty() ? flush_error(out, where) : close_error(file_out, args.output)) {
    std::cerr << "pdd mesh: " << *why << "; results lost\n";
    return kExitFileError;
  }
  const int status = fast ? report(args, A, Bp, *fast_result, variants, read_seconds)
                          : report(args, A, Bp, *exact_result, variants, read_seconds);
  return status;
}

}  // namespace

void add_mesh_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<MeshArgs>();
  CLI::App* cmd = app.add_subcommand(
      "mesh",
      "Every intersecting element pair of two tetrahedral meshes (Gmsh .msh 2.2/4.1, legacy "
      ".vtk) and its penetration depths (docs/definitions.md §10); JSON Lines sorted by (a, b), each written as soon as it and those before it are computed "
      "(Ctrl-C keeps them: exit 130).");
  cmd->add_option("--a", args->a, "Mesh A (.msh or .vtk)")->required();
  cmd->add_option("--b", args->b, "Mesh B (.msh or .vtk); not with --self");
  cmd->add_flag("--self", args->self, "Self-contact of A: element pairs a < b sharing no vertex");
  CLI::Option* variants = cmd->add_option("--variants", args->variants,
                  "Comma-separated: rigid, eq11, static, pdd2, relaxed, accel1, accel6, global "
                  "(pdd2_global, PD_d² over every separating plane; tens of microseconds a pair "
                  "with the fast engine, up to milliseconds on contacts made by rounding, README "
                  "\"Limits\"), or all")
      ->capture_default_str();
  cmd->add_option("--engine", args->engine,
                  "'fast' (doubles within the accuracy contract of docs/definitions.md §8; the "
                  "default here, as in Python) or 'reference' (exact rationals as \"p/q\" strings; "
                  "milliseconds per pair; the default of pdd solve)")
      ->check(CLI::IsMember({"fast", "reference"}))
      ->capture_default_str();
  cmd->add_option("--output", args->output, "Write JSON Lines here instead of standard output");
  CLI::Option* vtk = cmd->add_option("--vtk", args->vtk,
                  "Also write both meshes with per-element contact data and a per-vertex "
                  "displacement field (legacy VTK, for ParaView; fields: docs/definitions.md §10)");
  CLI::Option* summary = cmd->add_flag("--summary", args->summary,
                "A readable summary: elements, pairs, time per stage, and the sum and maximum of "
                "each value with the pair attaining it; on standard output with --output, else "
                "on standard error (standard output holds the records)");
  cmd->add_option("--threads", args->threads, "Worker threads (0: all cores)")
      ->check(integer_in(0, 4096))
      ->capture_default_str();
  cmd->add_flag("--quiet", args->quiet, "Nothing on standard error but errors and skipped elements");
  // (the energy has no per-pair records, variants, VTK file or summary: asked with it, refused)
  cmd->add_flag("--energy", args->energy,
                "Instead of the pairs, the contact energy E = sum (V_a V_b)^(1/3) pdd2_global "
                "(docs/definitions.md \"Contact energy\") as one JSON object: energy, pairs, "
                "max_pdd2_global, max_force (largest |dE/dp| of a vertex), max_force_vertex")
      ->excludes(vtk)
      ->excludes(summary)
      ->excludes(variants);
  cmd->add_option("--rest-a", args->rest_a,
                  "With --energy: A's rest shape (the same mesh at rest, .msh or .vtk) for the weights "
                  "(V_a V_b)^(1/3), held constant as in a simulator; without it A's positions, the "
                  "weights following them (their derivative in max_force)");
  CLI::Option* rest_b = cmd->add_option("--rest-b", args->rest_b, "With --energy: B's rest shape, as --rest-a");
  rest_b->excludes(cmd->get_option("--self"));
  cmd->callback([args, &exit_code] { exit_code = run_mesh(*args); });
}

}  // namespace pdd::compare
