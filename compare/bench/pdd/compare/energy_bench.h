// energy_bench.h — `pdd bench energy`: the speed of pdd::mesh::contact_energy
// (pdd/mesh/contact_energy.h, definitions §12) on shallow contacts of two meshes of about 10^5
// tetrahedra each.
//
// Input:  EnergyBenchOptions (cases, size, repeats; defaults in the struct).
// Output: EnergyBenchReport: per case and per thread count (one core: a tbb::task_arena of 1
//         thread; all cores: TBB's default concurrency), medians over `repeats` runs (after one
//         untimed warm-up run) of contact_energy's wall time without the Hessian (E + gradient)
//         and with it (E + gradient + Hessian), split into finding the pairs (boxes,
//         broadphase, exact decision: ContactEnergy::seconds_found) and everything after it
//         (the pairs' minimisers, weights, gradient, Hessian), the process CPU time of the
//         latter, and intersecting pairs per second after the broadphase.
// Cases: "grids": two Kuhn grids of 26^3 cubes (105,456 tetrahedra each, side 1), B tilted by
//        0.01 rad about (1, 2, 3) and lowered onto A's top face by `grid_depth`;
//        "balls": two jittered, rotated Kuhn balls (make_bench_ball, mesh_bench.h: the meshes
//        `pdd bench mesh` uses, the real-mesh kind: no face of one parallel to the other's) of
//        `size` tetrahedra and radius 1 at centre distance `ball_distance` (a shallow overlap);
//        "stacked": two Kuhn blocks of stacked_cells x stacked_cells x 3 cubes, B on A's columns a
//        third of a cell deep (stacked_blocks, mesh_bench.h: faces parallel, vertical faces
//        coplanar), then the same with B tilted 0.01 rad ("stacked-tilted": no face parallel)
//        and 1e-6 rad ("stacked-nearly": a resting contact a step after touching, the vertical
//        faces crossing ~1e-7 of a cell deep); and two blocks of decimal cells 0.1 set on each
//        other at 0.3, A's top 3 x 0.1 = 0.30000000000000004 ("stacked-rounding": touching by
//        rounding, ~5.6e-17 deep) beside B turned 0.3 rad ("stacked-rounding-turned"); the same
//        blocks with B on A's columns, its bottom 1e-9 below A's top ("stacked-resting": faces,
//        edges and vertices of B resting on the same ones of A) or at 0.3 ("stacked-columns":
//        the same contacts by rounding), each beside B turned 0.3 rad ("-turned"); blocks of
//        cubes cut into five, B on A's columns 1e-9 deep with the cuts alternating across the
//        contact ("stacked-five-resting": minimisers tied at a vertex) beside B turned 0.3 rad;
//        Kuhn blocks of decimal cells, B a third of a cell deep and moved by (0.01, 0.01)
//        ("stacked-diagonal": the cells' diagonal faces x - y = c of both together by rounding)
//        beside B turned 0.3 rad;
//        each aligned case names its twin (rotated_twin), and the ratios of the times per pair;
//        the resting cases also their scene twins ("stacked-resting-scene-turned",
//        "stacked-five-resting-scene-turned": both blocks turned 0.3 rad about (1, 2, 3) through
//        their common centroid, the same resting contact 1e-9 deep, no face along an axis), and
//        the ratios of the times per call.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "pdd/compare/timing.h"

namespace pdd::compare {

struct EnergyBenchOptions {
  std::string cases = "grids,balls,stacked";
  std::size_t size = 100000;    // tetrahedra per generated ball
  double grid_depth = 0.004;    // grids: B's lowest vertex below A's top face (cell 1/26)
  double ball_distance = 1.9;   // balls: centre distance (radius 1): ~10^4 pairs
  int stacked_cells = 12;       // stacked: cubes per side of each block (3 layers)
  int repeats = 5;
};

struct EnergyTimes {
  double found = 0;         // seconds finding the pairs (median)
  double energy = 0;        // E + gradient after the pairs are found (median wall seconds)
  double energy_cpu = 0;    // its process CPU seconds (median)
  double hessian = 0;       // E + gradient + Hessian after the pairs are found
  double hessian_cpu = 0;
  double pairs_per_second = 0;  // pairs / hessian
};

struct EnergyCase {
  std::string name, description;
  std::size_t elements_a = 0, elements_b = 0, pairs = 0, hessian_nonzeros = 0;
  double energy = 0, max_pdd2_global = 0;
  EnergyTimes one_core, all_cores;
  int threads = 0;  // all cores
  std::string rotated_twin;  // the same case with B tilted (aligned cases); empty: none
  // The same two meshes turned together (the resting cases): the same contact in general
  // position; empty: none. Its pair count differs by the contacts the turn's rounding makes
  // (bounded, ~2 us each), so the two are compared per call.
  std::string scene_twin;
};

struct EnergyBenchReport {
  EnergyBenchOptions options;
  MachineInfo machine;
  std::vector<EnergyCase> cases;
  double seconds = 0;
};

// Throws std::invalid_argument on an unknown case name.
EnergyBenchReport run_energy_bench(const EnergyBenchOptions& options);

}  // namespace pdd::compare
