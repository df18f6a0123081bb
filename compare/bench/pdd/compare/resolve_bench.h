// resolve_bench.h — `pdd bench resolve`: pdd::mesh::resolve / resolve_self (include/pdd/mesh.h)
// with every variant side by side on the same inputs: rounds, time per stage and per round,
// cost, largest displacement, smallest volume ratio, whether R1–R3 hold (the library's exact
// verdict), and, where it can be computed, the cost of the cheapest rigid separation along a
// given line for comparison.
//
// Cases:
//   shallow  two generated balls (make_bench_ball, mesh_bench.h) of about `size` tetrahedra
//            whose overlap is about one element layer (centres `shallow_distance` apart),
//            written as legacy VTK and read back (the read is timed);
//   deep     the same balls at `deep_distance` (the lens of `pdd bench mesh`);
//   self     two-spheres.msh of `meshes` (one mesh intersecting itself);
//   shipped  the small meshes of `meshes`, moved into shallow overlaps of known depth as in
//            tests/mesh/test_resolve.cpp, and the shipped deep pairs as they are;
//   stacked  two Kuhn blocks of stacked_cells x stacked_cells x 3 cubes, B on A's columns a third
//            of a cell deep (stacked_blocks, mesh_bench.h: faces parallel, vertical faces
//            coplanar), then the same with B tilted 0.01 rad ("stacked-tilted", no face parallel);
//            the aligned case names its twin (rotated_twin) and the tables give the time ratios;
//   real     with `cases_dir`: every line of DIR/cases.tsv as scripts/make-resolve-cases.sh writes
//            it (Gmsh and TetGen meshes: a ball on a fixed thin plate, two bodies, two bodies in
//            one file, a body against itself, two balls of 10^5 elements one layer deep, a ball
//            through the plate): `name <TAB> pdd resolve options <TAB> check-resolution.py
//            options`, of which --a, --b, --self, --fix a|b and --rigid-dir, --rigid-hi are read.
// Rigid comparison ("rigid separation"): B translated along the line of the balls' centres
// (boxes: along x) by the smallest t after which no element pair intersects (bisection on t
// with check_resolution's exact R1, to 1e-4 relative), split half and half between the meshes as
// PD_d splits a translation: cost 2 (t/2)^2 = t^2 / 2 (the cheapest rigid motion along that line);
// with one mesh fixed the other moves by all of t: cost t^2. Cases of one file (--self) have no
// rigid comparison here (check-resolution.py --rigid-body computes it per body).
// Quality columns (per variant, of the first run): smallest and largest V1/V0, smallest
// eta1/eta0, the R4 verdict, rounds, method; with `write_dir` the final meshes are written there
// as <case>-<variant>-a.vtk / -b.vtk so that scripts/check-resolution.py can judge them.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "pdd/compare/timing.h"
#include "pdd/mesh.h"

namespace pdd::compare {

struct ResolveBenchOptions {
  std::size_t size = 100000;        // tetrahedra per generated ball
  double shallow_distance = 1.99;   // centre distance, shallow case (about one layer at 10^5)
  double deep_distance = 1.88;      // centre distance, deep case (the lens of `pdd bench mesh`)
  std::string meshes = "fixtures/meshes";  // directory of the shipped meshes
  std::string cases = "shallow,deep,self,shipped,stacked";  // may be empty (only cases_dir)
  int stacked_cells = 8;            // stacked: cubes per side of each block (3 layers)
  std::string cases_dir;            // real-mesh cases: DIR/cases.tsv; empty: none
  std::string variants = "global,pdd2,rigid";  // comma-separated resolve variants to run
  std::string write_dir;            // final meshes of the first run per row; empty: not written
  std::size_t max_rounds = mesh::ResolveOptions{}.max_rounds;  // the library's default
  int repeats = 3;                  // runs per case and variant (median of the times)
};

struct ResolveBenchRow {
  std::string variant;
  bool resolved = false, r1 = false, r2 = false, r3 = false, r4 = false;
  std::string method;  // resolve_method_name of the report
  std::size_t rounds = 0, first_pairs = 0, remaining_pairs = 0, bad_elements = 0, poor_elements = 0;
  double cost = 0, max_displacement = 0, min_volume_ratio = 0, max_volume_ratio = 0, min_shape_ratio = 0;
  // Medians over the repeats (seconds).
  double total = 0, contacts = 0, solve = 0, move = 0, verify = 0, per_round = 0;
  std::vector<mesh::ResolveRound> round_log;  // of the first run
};

struct ResolveBenchCase {
  std::string name, description;
  std::size_t elements_a = 0, elements_b = 0, skipped = 0;
  double read_seconds = 0;      // generated balls: reading both files
  double rigid_separation = -1; // t^2 / 2 (header); -1: not computed
  double rigid_t = 0;
  bool fixed_a = false, fixed_b = false;  // a mesh kept bit for bit (--fix)
  std::vector<ResolveBenchRow> rows;  // global, pdd2, rigid
  std::string rotated_twin;           // the same case with B tilted (aligned cases); empty: none
};

// Round pairs of a row: the intersecting pairs summed over its rounds (the pairs solved).
std::size_t round_pairs(const ResolveBenchRow& row);

struct ResolveBenchReport {
  ResolveBenchOptions options;
  MachineInfo machine;
  std::vector<ResolveBenchCase> cases;
  std::vector<std::string> notes;
  double seconds = 0;
};

// Runs the cases (progress on stderr). Throws std::invalid_argument on bad options and
// mesh::ReadError when a shipped mesh cannot be read.
ResolveBenchReport run_resolve_bench(const ResolveBenchOptions& options);

}  // namespace pdd::compare
