// resolve_bench.cpp — `pdd bench resolve` (resolve_bench.h).
#include "pdd/compare/resolve_bench.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "pdd/compare/mesh_bench.h"
#include "pdd/compare/stats.h"

namespace pdd::compare {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

mesh::Mesh translated(mesh::Mesh m, const Vec3d& t) {
  for (Vec3d& v : m.vertices)
    for (int k = 0; k < 3; ++k) v[k] += t[k];
  return m;
}

// The smallest t (to 1e-4 relative) after which B translated by t * dir (unit) intersects A in
// no element pair, by bisection with the exact R1 of check_resolution; t^2 / 2 is the cost of
// that motion split half and half (resolve_bench.h). Returns t, or -1 when even `hi` does not
// separate. B null: not computed.
double rigid_separation_t(const mesh::Mesh& A, const mesh::Mesh& B, const Vec3d& dir, double hi) {
  auto separated = [&](double t) {
    const mesh::Mesh Bt = translated(B, {dir[0] * t, dir[1] * t, dir[2] * t});
    return mesh::check_resolution(A, A.vertices, Bt, Bt.vertices).r1;
  };
  if (!separated(hi)) return -1;
  double lo = 0;
  while (hi - lo > 1e-4 * hi) {
    const double mid = (lo + hi) / 2;
    (separated(mid) ? hi : lo) = mid;
  }
  return hi;
}

struct Input {
  std::string name, description;
  mesh::Mesh A, B;
  bool self = false, fix_a = false, fix_b = false;
  double read_seconds = 0;
  Vec3d line{};      // for the rigid comparison; zero: none
  double line_hi = 0;
};

std::vector<std::string> split(const std::string& list, char sep) {
  std::vector<std::string> out;
  std::stringstream s(list);
  std::string w;
  while (std::getline(s, w, sep))
    if (!w.empty()) out.push_back(w);
  return out;
}

// The variants named in `list` (resolve_variant_name), in that order.
std::vector<mesh::ResolveVariant> parse_variants(const std::string& list) {
  std::vector<mesh::ResolveVariant> out;
  for (const std::string& w : split(list, ',')) {
    bool found = false;
    for (mesh::ResolveVariant v : {mesh::ResolveVariant::Global, mesh::ResolveVariant::Pdd2, mesh::ResolveVariant::Rigid})
      if (w == mesh::resolve_variant_name(v)) out.push_back(v), found = true;
    if (!found) throw std::invalid_argument("unknown variant '" + w + "' (global, pdd2, rigid)");
  }
  if (out.empty()) throw std::invalid_argument("--variants names no variant");
  return out;
}

std::string file_name(std::string s) {
  for (char& ch : s)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '.') ch = '_';
  return s;
}

ResolveBenchCase run_case(const Input& in, const ResolveBenchOptions& o) {
  ResolveBenchCase c;
  c.name = in.name;
  c.description = in.description;
  c.elements_a = in.A.tets.size();
  c.elements_b = in.self ? 0 : in.B.tets.size();
  c.read_seconds = in.read_seconds;
  c.fixed_a = in.fix_a;
  c.fixed_b = in.fix_b;
  for (mesh::ResolveVariant v : parse_variants(o.variants)) {
    std::cerr << "pdd bench resolve: " << in.name << ", " << mesh::resolve_variant_name(v) << "\n";
    ResolveBenchRow row;
    row.variant = mesh::resolve_variant_name(v);
    std::vector<double> total, contacts, solve, move, verify, per_round;
    for (int r = 0; r < o.repeats; ++r) {
      mesh::ResolveOptions ro;
      ro.variant = v;
      ro.max_rounds = o.max_rounds;
      ro.fix_a = in.fix_a;
      ro.fix_b = in.fix_b;
      const mesh::Resolution res = in.self ? mesh::resolve_self(in.A, ro) : mesh::resolve(in.A, in.B, ro);
      const mesh::ResolveReport& p = res.report;
      total.push_back(p.seconds_total);
      contacts.push_back(p.seconds_contacts);
      solve.push_back(p.seconds_solve);
      move.push_back(p.seconds_move);
      verify.push_back(p.seconds_verify);
      per_round.push_back(p.rounds.empty() ? 0 : (p.seconds_total - p.seconds_verify) / p.rounds.size());
      if (r == 0) {
        row.resolved = p.resolved, row.r1 = p.r1, row.r2 = p.r2, row.r3 = p.r3, row.r4 = p.r4;
        row.method = mesh::resolve_method_name(p.method);
        row.poor_elements = p.poor_elements.size();
        row.max_volume_ratio = p.max_volume_ratio;
        row.min_shape_ratio = p.min_shape_ratio;
        row.rounds = p.rounds.size();
        row.first_pairs = p.rounds.empty() ? 0 : p.rounds[0].pairs;
        row.remaining_pairs = p.remaining_pairs.size();
        row.bad_elements = p.bad_elements.size();
        row.cost = p.cost;
        row.max_displacement = p.max_displacement;
        row.min_volume_ratio = p.min_volume_ratio;
        row.round_log = p.rounds;
        c.skipped = p.skipped.size();
        if (!o.write_dir.empty()) {
          const std::string stem = o.write_dir + "/" + file_name(in.name) + "-" + row.variant;
          mesh::write_mesh(stem + "-a.vtk", in.A, res.a);
          if (!in.self) mesh::write_mesh(stem + "-b.vtk", in.B, res.b);
        }
      }
    }
    row.total = median(total);
    row.contacts = median(contacts);
    row.solve = median(solve);
    row.move = median(move);
    row.verify = median(verify);
    row.per_round = median(per_round);
    c.rows.push_back(row);
  }
  if (!in.self && (in.line[0] != 0 || in.line[1] != 0 || in.line[2] != 0)) {
    std::cerr << "pdd bench resolve: " << in.name << ", rigid separation along the line\n";
    c.rigid_t = rigid_separation_t(in.A, in.B, in.line, in.line_hi);
    // Both meshes free: t split half and half, 2 (t/2)^2; one fixed: the other moves by t.
    if (c.rigid_t > 0) c.rigid_separation = c.rigid_t * c.rigid_t / (in.fix_a || in.fix_b ? 1 : 2);
  }
  return c;
}

bool wanted(const ResolveBenchOptions& o, const std::string& name) {
  for (const std::string& w : split(o.cases, ','))
    if (w == name) return true;
  return false;
}

Vec3d unit(const Vec3d& v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / n, v[1] / n, v[2] / n};
}

// The cases of DIR/cases.tsv (resolve_bench.h, `real`), read and timed. Throws
// std::invalid_argument naming the line when it cannot be understood.
std::vector<Input> read_case_list(const std::string& dir) {
  const std::string path = dir + "/cases.tsv";
  std::ifstream f(path);
  if (!f) throw std::invalid_argument("cannot read " + path + " (make it with scripts/make-resolve-cases.sh)");
  std::vector<Input> out;
  std::string line;
  for (int n = 1; std::getline(f, line); ++n) {
    if (line.empty()) continue;
    const std::vector<std::string> cols = [&] {
      std::vector<std::string> c;
      std::stringstream s(line);
      std::string w;
      while (std::getline(s, w, '\t')) c.push_back(w);
      return c;
    }();
    const std::string where = path + " line " + std::to_string(n);
    if (cols.size() < 2) throw std::invalid_argument(where + ": expected name, resolve options, check options");
    Input in;
    in.name = cols[0];
    std::string a, b;
    auto tokens = split(cols[1], ' ');
    for (std::size_t k = 0; k < tokens.size(); ++k) {
      const std::string& t = tokens[k];
      const bool has_value = k + 1 < tokens.size();
      if (t == "--a" && has_value) a = tokens[++k];
      else if (t == "--b" && has_value) b = tokens[++k];
      else if (t == "--self") in.self = true;
      else if (t == "--fix" && has_value) {
        const std::string& w = tokens[++k];
        if (w != "a" && w != "b") throw std::invalid_argument(where + ": --fix takes a or b");
        (w == "a" ? in.fix_a : in.fix_b) = true;
      } else throw std::invalid_argument(where + ": unknown resolve option '" + t + "'");
    }
    if (a.empty() || in.self == !b.empty())
      throw std::invalid_argument(where + ": needs --a and either --b or --self");
    const auto t0 = Clock::now();
    in.A = mesh::read_mesh(a);
    if (!in.self) in.B = mesh::read_mesh(b);
    in.read_seconds = since(t0);
    std::ostringstream d;
    d << (in.self ? "one file (--self): " : "") << std::filesystem::path(a).filename().string();
    if (!in.self) d << " x " << std::filesystem::path(b).filename().string();
    if (in.fix_a || in.fix_b) d << ", " << (in.fix_a ? "a" : "b") << " fixed";
    in.description = d.str();
    const auto check = cols.size() > 2 ? split(cols[2], ' ') : std::vector<std::string>{};
    bool per_body = false;
    for (std::size_t k = 0; k + 1 < check.size(); ++k) {
      if (check[k] == "--rigid-hi") in.line_hi = std::stod(check[k + 1]);
      if (check[k] == "--rigid-body") per_body = true;
      if (check[k] == "--rigid-dir") {
        const auto xyz = split(check[k + 1], ',');
        if (xyz.size() != 3) throw std::invalid_argument(where + ": --rigid-dir takes x,y,z");
        in.line = unit({std::stod(xyz[0]), std::stod(xyz[1]), std::stod(xyz[2])});
      }
    }
    if (per_body || in.line_hi <= 0) in.line = {0, 0, 0};
    out.push_back(std::move(in));
  }
  return out;
}

}  // namespace

std::size_t round_pairs(const ResolveBenchRow& row) {
  std::size_t n = 0;
  for (const auto& r : row.round_log) n += r.pairs;
  return n;
}

ResolveBenchReport run_resolve_bench(const ResolveBenchOptions& o) {
  if (o.repeats < 1) throw std::invalid_argument("--repeats must be at least 1");
  if (o.max_rounds < 1) throw std::invalid_argument("--max-rounds must be at least 1");
  for (const std::string& w : split(o.cases, ','))
    if (w != "shallow" && w != "deep" && w != "self" && w != "shipped" && w != "stacked")
      throw std::invalid_argument("unknown case '" + w + "' (shallow, deep, self, shipped, stacked)");
  if (o.stacked_cells < 1) throw std::invalid_argument("--stacked-cells must be at least 1");
  parse_variants(o.variants);
  if (!o.write_dir.empty()) std::filesystem::create_directories(o.write_dir);
  const auto t_all = Clock::now();
  ResolveBenchReport rep;
  rep.options = o;
  rep.machine = machine_info();

  // The balls as `pdd bench mesh` makes them: B's centre is d (0.99, 0.1, 0.07).
  const Vec3d dir_b = {0.99, 0.1, 0.07};
  const double dir_len = std::sqrt(0.99 * 0.99 + 0.1 * 0.1 + 0.07 * 0.07);
  for (const char* which : {"shallow", "deep"}) {
    if (!wanted(o, which)) continue;
    const double d = std::string(which) == "shallow" ? o.shallow_distance : o.deep_distance;
    std::cerr << "pdd bench resolve: generating two balls of about " << o.size << " tetrahedra (" << which << ")\n";
    const mesh::Mesh A0 = make_bench_ball(o.size, {0, 0, 0}, 1, {1, 2, 3}, 0.3, 1);
    const mesh::Mesh B0 = make_bench_ball(o.size, {d * dir_b[0], d * dir_b[1], d * dir_b[2]}, 1, {-2, 1, 1}, 0.7, 2);
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("pdd-bench-resolve-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string pa = (dir / "ball-a.vtk").string(), pb = (dir / "ball-b.vtk").string();
    mesh::write_vtk_self(pa, A0, mesh::Contacts<double>{}, 0);
    mesh::write_vtk_self(pb, B0, mesh::Contacts<double>{}, 0);
    Input in;
    const auto t = Clock::now();
    in.A = mesh::read_mesh(pa);
    in.B = mesh::read_mesh(pb);
    in.read_seconds = since(t);
    std::filesystem::remove_all(dir);
    in.name = which;
    std::ostringstream s;
    s << "two generated balls of radius 1, " << in.A.tets.size() << " and " << in.B.tets.size()
      << " tetrahedra, centres " << d * dir_len << " apart";
    in.description = s.str();
    in.line = unit(dir_b);
    in.line_hi = 2.5 - d * dir_len;
    rep.cases.push_back(run_case(in, o));
  }
  const std::string m = o.meshes + "/";
  if (wanted(o, "self")) {
    Input in;
    in.name = "self";
    in.description = "two-spheres.msh: two balls meshed independently in one mesh (self-contact)";
    in.A = mesh::read_mesh(m + "two-spheres.msh");
    in.self = true;
    rep.cases.push_back(run_case(in, o));
  }
  if (wanted(o, "shipped")) {
    const mesh::Mesh a = mesh::read_mesh(m + "sphere-a.msh"), b = mesh::read_mesh(m + "sphere-b.msh");
    const Vec3d cb = {1.1, 0.35, 0.2};
    const double lb = std::sqrt(cb[0] * cb[0] + cb[1] * cb[1] + cb[2] * cb[2]);
    {
      Input in;
      in.name = "boxes 0.1";
      in.description = "touching-a.msh x touching-b.msh moved by -0.1 in x (a slab of depth 0.1; rigid: 0.005)";
      in.A = mesh::read_mesh(m + "touching-a.msh");
      in.B = translated(mesh::read_mesh(m + "touching-b.msh"), {-0.1, 0, 0});
      in.line = {1, 0, 0};
      in.line_hi = 0.5;
      rep.cases.push_back(run_case(in, o));
    }
    {
      Input in;
      in.name = "balls 0.08";
      in.description = "sphere-a.msh x sphere-b.msh moved along the centres' line to centres 1.82 apart";
      in.A = a;
      const double s = 1.82 / lb - 1;
      in.B = translated(b, {cb[0] * s, cb[1] * s, cb[2] * s});
      in.line = unit(cb);
      in.line_hi = 0.5;
      rep.cases.push_back(run_case(in, o));
    }
    {
      Input in;
      in.name = "torus+box 0.05";
      in.description = "torus.msh x box.vtk lifted by 0.7 in z (the tube's top 0.05 inside the box)";
      in.A = mesh::read_mesh(m + "torus.msh");
      in.B = translated(mesh::read_mesh(m + "box.vtk"), {0, 0, 0.7});
      in.line = {0, 0, 1};
      in.line_hi = 0.5;
      rep.cases.push_back(run_case(in, o));
    }
    {
      Input in;
      in.name = "ball+slivers 0.05";
      in.description = "sphere-a.msh x slivers.msh moved by 0.45 in x";
      in.A = a;
      in.B = translated(mesh::read_mesh(m + "slivers.msh"), {0.45, 0, 0});
      in.line = {1, 0, 0};
      in.line_hi = 0.5;
      rep.cases.push_back(run_case(in, o));
    }
    {
      Input in;
      in.name = "balls deep";
      in.description = "sphere-a.msh x sphere-b.msh as shipped (overlap 0.73 along the centres' line)";
      in.A = a;
      in.B = b;
      in.line = unit(cb);
      in.line_hi = 2;
      rep.cases.push_back(run_case(in, o));
    }
    {
      Input in;
      in.name = "torus+box deep";
      in.description = "torus.msh x box.vtk as shipped (the box through the tube)";
      in.A = mesh::read_mesh(m + "torus.msh");
      in.B = mesh::read_mesh(m + "box.vtk");
      in.line = {0, 0, 1};
      in.line_hi = 2;
      rep.cases.push_back(run_case(in, o));
    }
  }
  if (wanted(o, "stacked")) {
    const int layers = 3;
    for (double tilt : {0.0, 0.01}) {
      BlockPair blocks = stacked_blocks(o.stacked_cells, layers, 1.0 / 3, tilt);
      Input in;
      in.name = tilt == 0 ? "stacked" : "stacked-tilted";
      in.description = blocks.description;
      in.A = std::move(blocks.a);
      in.B = std::move(blocks.b);
      in.line = {0, 0, 1};
      in.line_hi = 1.0 / o.stacked_cells;  // a cell: more than the third of a cell to undo
      rep.cases.push_back(run_case(in, o));
    }
    rep.cases[rep.cases.size() - 2].rotated_twin = rep.cases.back().name;
  }
  if (!o.cases_dir.empty())
    for (const Input& in : read_case_list(o.cases_dir)) {
      std::cerr << "pdd bench resolve: " << in.name << " (" << o.cases_dir << ")\n";
      rep.cases.push_back(run_case(in, o));
    }
  rep.machine.load_after = read_first_line("/proc/loadavg");
  rep.seconds = since(t_all);
  return rep;
}

}  // namespace pdd::compare
