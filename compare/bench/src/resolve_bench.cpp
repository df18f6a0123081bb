// resolve_bench.cpp — `pdd bench resolve` (resolve_bench.h).
#include "pdd/compare/resolve_bench.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
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
    return mesh::check_resolution(A, A.vertices, &Bt, Bt.vertices).r1;
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
  bool self = false;
  double read_seconds = 0;
  Vec3d line{};      // for the rigid comparison; zero: none
  double line_hi = 0;
};

ResolveBenchCase run_case(const Input& in, const ResolveBenchOptions& o) {
  ResolveBenchCase c;
  c.name = in.name;
  c.description = in.description;
  c.elements_a = in.A.tets.size();
  c.elements_b = in.self ? 0 : in.B.tets.size();
  c.read_seconds = in.read_seconds;
  for (mesh::ResolveVariant v : {mesh::ResolveVariant::Global, mesh::ResolveVariant::Pdd2, mesh::ResolveVariant::Rigid}) {
    std::cerr << "pdd bench resolve: " << in.name << ", " << mesh::resolve_variant_name(v) << "\n";
    ResolveBenchRow row;
    row.variant = mesh::resolve_variant_name(v);
    std::vector<double> total, contacts, solve, move, verify, per_round;
    for (int r = 0; r < o.repeats; ++r) {
      mesh::ResolveOptions ro;
      ro.variant = v;
      ro.max_rounds = o.max_rounds;
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
    if (c.rigid_t > 0) c.rigid_separation = c.rigid_t * c.rigid_t / 2;
  }
  return c;
}

bool wanted(const ResolveBenchOptions& o, const std::string& name) {
  std::stringstream s(o.cases);
  std::string w;
  while (std::getline(s, w, ','))
    if (w == name) return true;
  return false;
}

Vec3d unit(const Vec3d& v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / n, v[1] / n, v[2] / n};
}

}  // namespace

ResolveBenchReport run_resolve_bench(const ResolveBenchOptions& o) {
  if (o.repeats < 1) throw std::invalid_argument("--repeats must be at least 1");
  if (o.max_rounds < 1) throw std::invalid_argument("--max-rounds must be at least 1");
  {
    std::stringstream s(o.cases);
    std::string w;
    while (std::getline(s, w, ','))
      if (w != "shallow" && w != "deep" && w != "self" && w != "shipped")
        throw std::invalid_argument("unknown case '" + w + "' (shallow, deep, self, shipped)");
  }
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
    mesh::write_vtk(pa, A0, nullptr, mesh::Contacts<double>{}, 0);
    mesh::write_vtk(pb, B0, nullptr, mesh::Contacts<double>{}, 0);
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
  rep.seconds = since(t_all);
  return rep;
}

}  // namespace pdd::compare
