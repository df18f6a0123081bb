// energy_bench.cpp — `pdd bench energy` (energy_bench.h).
#include "pdd/compare/energy_bench.h"

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "pdd/compare/mesh_bench.h"
#include "pdd/compare/stats.h"
#include "pdd/mesh.h"

namespace pdd::compare {
namespace {

using Clock = std::chrono::steady_clock;

double cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

// A and B turned together by `angle` about (1, 2, 3) through the centroid of their vertices:
// the same contact, its faces along no coordinate plane (each coordinate rounded once).
void turn_together(mesh::Mesh& A, mesh::Mesh& B, double angle) {
  Vec3d c{0, 0, 0};
  const double n = double(A.vertices.size() + B.vertices.size());
  for (const mesh::Mesh* m : {&A, &B})
    for (const Vec3d& v : m->vertices)
      for (int k = 0; k < 3; ++k) c[k] += v[k] / n;
  const auto R = rotation_matrix({1, 2, 3}, angle);
  for (mesh::Mesh* m : {&A, &B})
    for (Vec3d& v : m->vertices) {
      const double p[3] = {v[0] - c[0], v[1] - c[1], v[2] - c[2]};
      for (int r = 0; r < 3; ++r) v[r] = c[r] + R[r][0] * p[0] + R[r][1] * p[1] + R[r][2] * p[2];
    }
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

struct Sample {
  double found = 0, after = 0, cpu = 0;
};

// One contact_energy call in `arena`: its time finding the pairs, its wall time after that and
// the process CPU time of the call minus the share spent finding the pairs (at the same
// CPU/wall ratio as the whole call: the stages are not timed apart in CPU).
Sample run_once(tbb::task_arena& arena, const mesh::Mesh& A, const mesh::Mesh& B, bool hessian,
                mesh::ContactEnergy* keep) {
  mesh::ContactEnergyOptions o;
  o.hessian = hessian;
  Sample s;
  arena.execute([&] {
    const double c0 = cpu_seconds();
    const auto t0 = Clock::now();
    mesh::ContactEnergy e = mesh::contact_energy(A, B, A.vertices, B.vertices, o);
    const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
    const double cpu = cpu_seconds() - c0;
    s.found = e.seconds_found;
    s.after = wall - e.seconds_found;
    s.cpu = wall > 0 ? cpu * s.after / wall : 0;
    if (keep) *keep = std::move(e);
  });
  return s;
}

EnergyTimes time_case(tbb::task_arena& arena, const mesh::Mesh& A, const mesh::Mesh& B, int repeats,
                      std::size_t pairs) {
  std::vector<double> found, e, ecpu, h, hcpu;
  run_once(arena, A, B, true, nullptr);  // warm-up
  for (int r = 0; r < repeats; ++r) {    // interleaved: both rows see the same load
    const Sample a = run_once(arena, A, B, false, nullptr);
    const Sample b = run_once(arena, A, B, true, nullptr);
    found.push_back(a.found);
    found.push_back(b.found);
    e.push_back(a.after);
    ecpu.push_back(a.cpu);
    h.push_back(b.after);
    hcpu.push_back(b.cpu);
  }
  EnergyTimes t;
  t.found = median(found);
  t.energy = median(e);
  t.energy_cpu = median(ecpu);
  t.hessian = median(h);
  t.hessian_cpu = median(hcpu);
  t.pairs_per_second = t.hessian > 0 ? double(pairs) / t.hessian : 0;
  return t;
}

}  // namespace

EnergyBenchReport run_energy_bench(const EnergyBenchOptions& options) {
  if (options.repeats < 1) throw std::invalid_argument("--repeats must be at least 1");
  const auto t0 = Clock::now();
  EnergyBenchReport rep;
  rep.options = options;
  rep.machine = machine_info();
  if (options.stacked_cells < 1) throw std::invalid_argument("--stacked-cells must be at least 1");
  tbb::task_arena one(1), all(tbb::info::default_concurrency());
  std::vector<std::string> names;
  for (const std::string& name : split(options.cases))
    if (name == "stacked")
      names.insert(names.end(),
                   {"stacked", "stacked-tilted", "stacked-nearly", "stacked-rounding", "stacked-rounding-turned",
                    "stacked-resting", "stacked-resting-turned", "stacked-resting-scene-turned",
                    "stacked-columns", "stacked-columns-turned", "stacked-five-resting",
                    "stacked-five-resting-turned", "stacked-five-resting-scene-turned", "stacked-diagonal",
                    "stacked-diagonal-turned"});
    else names.push_back(name);
  for (const std::string& name : names) {
    EnergyCase c;
    c.name = name;
    mesh::Mesh A, B;
    if (name == "grids") {
      const int n = 26;
      const double h = 1.0 / n;
      A = make_structured_block({n, n, n}, h, {0, 0, 0}, CubeSplit::Kuhn6);
      B = make_structured_block({n, n, n}, h, {0.013, 0.021, 0}, CubeSplit::Kuhn6, 0.01);
      double low = INFINITY;
      for (const Vec3d& v : B.vertices) low = std::min(low, v[2]);
      for (Vec3d& v : B.vertices) v[2] += 1 - options.grid_depth - low;
      std::ostringstream d;
      d << "Kuhn grids of 26^3 cubes, B tilted 0.01 rad and " << options.grid_depth << " deep on A's top";
      c.description = d.str();
    } else if (name == "balls") {
      A = make_bench_ball(options.size, {0, 0, 0}, 1, {1, 2, 3}, 0.3, 7);
      B = make_bench_ball(options.size, {options.ball_distance, 0, 0}, 1, {3, 1, 2}, 0.7, 11);
      std::ostringstream d;
      d << "jittered Kuhn balls of radius 1, centres " << options.ball_distance << " apart";
      c.description = d.str();
    } else if (name == "stacked" || name == "stacked-tilted" || name == "stacked-nearly") {
      const double tilt = name == "stacked" ? 0 : name == "stacked-tilted" ? 0.01 : 1e-6;
      BlockPair blocks = stacked_blocks(options.stacked_cells, 3, 1.0 / 3, tilt);
      A = std::move(blocks.a);
      B = std::move(blocks.b);
      c.description = blocks.description;
      if (name == "stacked") c.rotated_twin = "stacked-tilted";
    } else if (name == "stacked-rounding" || name == "stacked-rounding-turned") {
      // decimal cells placed as users place them: A's top 3 x 0.1 = 0.30000000000000004, B's
      // bottom 0.3 (touching by rounding, ~5.6e-17 deep); the twin B turned 0.3 rad
      const int n = options.stacked_cells;
      const bool turned = name == "stacked-rounding-turned";
      A = make_structured_block({n, n, 3}, 0.1, {0, 0, 0}, CubeSplit::Kuhn6);
      B = make_structured_block({n, n, 3}, 0.1, {0.037, 0.021, 0.3}, CubeSplit::Kuhn6, turned ? 0.3 : 0.0);
      std::ostringstream d;
      d << "Kuhn blocks of " << n << "x" << n << "x3 cubes of 0.1, B set on A at 0.3 (A's top 3 x 0.1: touching by "
        << "rounding), moved by (0.037, 0.021)" << (turned ? ", B turned 0.3 rad about (1, 2, 3) through its centre" : "");
      c.description = d.str();
      if (!turned) c.rotated_twin = "stacked-rounding-turned";
    } else if (name == "stacked-resting" || name == "stacked-resting-turned" || name == "stacked-columns" ||
               name == "stacked-columns-turned" || name == "stacked-resting-scene-turned") {
      // B on A's columns (the same x and y), its bottom 1e-9 below A's top (resting: a contact as
      // a simulator leaves it) or at 0.3 (columns: touching by rounding, as two copies of one
      // mesh set on each other), every contact of a face, an edge or a vertex of B's bottom on
      // the same element of A's top; the twin B turned 0.3 rad
      const int n = options.stacked_cells;
      const bool scene = name == "stacked-resting-scene-turned";
      const bool turned = !scene && name.size() > 7 && name.compare(name.size() - 7, 7, "-turned") == 0;
      const bool resting = name.rfind("stacked-resting", 0) == 0;
      A = make_structured_block({n, n, 3}, 0.1, {0, 0, 0}, CubeSplit::Kuhn6);
      B = make_structured_block({n, n, 3}, 0.1, {0, 0, resting ? 0.3 - 1e-9 : 0.3}, CubeSplit::Kuhn6,
                                turned ? 0.3 : 0.0);
      if (scene) turn_together(A, B, 0.3);
      std::ostringstream d;
      d << "Kuhn blocks of " << n << "x" << n << "x3 cubes of 0.1, B on A's columns "
        << (resting ? "1e-9 deep" : "at 0.3 (A's top 3 x 0.1: touching by rounding)")
        << (turned ? ", B turned 0.3 rad about (1, 2, 3) through its centre" : "")
        << (scene ? ", both turned 0.3 rad about (1, 2, 3) through their centroid" : "");
      c.description = d.str();
      if (!turned && !scene) c.rotated_twin = name + "-turned";
      if (name == "stacked-resting") c.scene_twin = "stacked-resting-scene-turned";
    } else if (name == "stacked-five-resting" || name == "stacked-five-resting-turned" ||
               name == "stacked-five-resting-scene-turned") {
      // cubes cut into five, alternating with i + j + k: A two layers high (its top layer odd
      // where B's bottom one is even), B on A's columns 1e-9 deep, so the cuts alternate across
      // the contact (a vertex on a vertex, the overlap least along several facet normals at
      // once); the twin B turned 0.3 rad
      const int n = options.stacked_cells;
      const bool turned = name == "stacked-five-resting-turned";
      const bool scene = name == "stacked-five-resting-scene-turned";
      A = make_structured_block({n, n, 2}, 0.1, {0, 0, 0}, CubeSplit::Five);
      B = make_structured_block({n, n, 3}, 0.1, {0, 0, 0.2 - 1e-9}, CubeSplit::Five, turned ? 0.3 : 0.0);
      if (scene) turn_together(A, B, 0.3);
      std::ostringstream d;
      d << "blocks of " << n << "x" << n << " cubes of 0.1 cut into five (A 2 layers, B 3), B on A's columns 1e-9 "
        << "deep, the cuts alternating across the contact"
        << (turned ? ", B turned 0.3 rad about (1, 2, 3) through its centre" : "")
        << (scene ? ", both turned 0.3 rad about (1, 2, 3) through their centroid" : "");
      c.description = d.str();
      if (!turned && !scene) {
        c.rotated_twin = "stacked-five-resting-turned";
        c.scene_twin = "stacked-five-resting-scene-turned";
      }
    } else if (name == "stacked-diagonal" || name == "stacked-diagonal-turned") {
      // B a third of a cell deep, moved across by a tenth of a cell along x and y alike: the
      // cells' diagonal faces x - y = c of the two blocks together up to rounding (contacts made
      // by rounding there, beside the layers' real overlap); the twin B turned 0.3 rad
      const int n = options.stacked_cells;
      const bool turned = name == "stacked-diagonal-turned";
      A = make_structured_block({n, n, 3}, 0.1, {0, 0, 0}, CubeSplit::Kuhn6);
      B = make_structured_block({n, n, 3}, 0.1, {0.01, 0.01, 0.3 - 0.1 / 3}, CubeSplit::Kuhn6, turned ? 0.3 : 0.0);
      std::ostringstream d;
      d << "Kuhn blocks of " << n << "x" << n << "x3 cubes of 0.1, B a third of a cell deep on A, moved by (0.01, "
        << "0.01): diagonal faces together by rounding"
        << (turned ? ", B turned 0.3 rad about (1, 2, 3) through its centre" : "");
      c.description = d.str();
      if (!turned) c.rotated_twin = "stacked-diagonal-turned";
    } else {
      throw std::invalid_argument("--cases: unknown case '" + name + "' (grids, balls, stacked)");
    }
    std::cerr << "pdd bench energy: " << name << "...\n";
    c.elements_a = A.tets.size();
    c.elements_b = B.tets.size();
    mesh::ContactEnergy e;
    run_once(all, A, B, true, &e);
    c.pairs = e.pair_count;
    c.hessian_nonzeros = std::size_t(e.hessian.nonZeros());
    c.energy = e.energy;
    c.max_pdd2_global = e.max_pdd2_global;
    c.threads = tbb::info::default_concurrency();
    c.all_cores = time_case(all, A, B, options.repeats, c.pairs);
    c.one_core = time_case(one, A, B, options.repeats, c.pairs);
    rep.cases.push_back(c);
  }
  rep.machine.load_after = read_first_line("/proc/loadavg");
  rep.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return rep;
}

}  // namespace pdd::compare
