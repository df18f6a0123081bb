// mesh_bench.h — `pdd bench mesh`: the speed of pdd::mesh::contacts (include/pdd/mesh.h,
// definitions §10) on two overlapping tetrahedral meshes, per stage, on one core and on all cores,
// and its broadphase side by side with FCL's broadphase managers on the same element boxes in the
// same process. FCL is linked here only (compare/bench).
//
// Input:  two mesh files (--a, --b), or two generated balls (make_bench_ball below) of about
//         `size` tetrahedra each, written to a temporary legacy VTK file each and read back so
//         that reading is timed too.
// Output: MeshBenchReport: medians over `repeats` runs (after one untimed warm-up run) of each
//         stage's wall time (read; then contacts()'s boxes, broadphase, decision, depth), on one
//         core (a tbb::task_arena of 1 thread) and on all cores (an arena of TBB's default
//         concurrency), runs interleaved; the decision stage's filter alone against the
//         a decision by rigid_pd2 > 0 (one core, per box pair); the depth calls one at a
//         time on the sample's intersecting pairs (median, mean, exact-path share); every broadphase (CGAL's
//         box_intersection_d as contacts() runs it, and FCL's managers) on the same boxes.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "pdd/compare/timing.h"
#include "pdd/mesh.h"

namespace pdd::compare {

// A ball of radius `radius` centred at `centre`, tessellated by the Kuhn (Freudenthal)
// subdivision of a cubic grid (6 tetrahedra per cube, conforming) over the cubes whose centre
// lies inside the ball, every grid vertex moved by a deterministic jitter of up to 0.1 h per
// coordinate (h the grid step; the smallest height of a Kuhn tetrahedron is h/√2, so no
// element flips), then rotated by `angle` radians about `axis` (about the centre). Grid step
// chosen so that the ball has about `target` tetrahedra, at most the radius (48 tetrahedra at
// least, for any target). The same arguments give the same mesh.
mesh::Mesh make_bench_ball(std::size_t target, const std::array<double, 3>& centre,
                           double radius, const std::array<double, 3>& axis, double angle,
                           std::uint64_t seed);

// The rotation by `angle` radians about `axis` (need not be unit; Rodrigues' formula), as a
// row-major matrix R: a point p rotates to R p.
std::array<std::array<double, 3>, 3> rotation_matrix(const std::array<double, 3>& axis, double angle);

struct MeshBenchOptions {
  std::string a, b;            // mesh files; both empty: two generated balls
  std::size_t size = 100000;   // tetrahedra per generated ball
  double distance = 1.88;      // centre distance of the generated balls (radius 1): ~10^4 pairs
  unsigned variants = mesh::kRigid | mesh::kAccel1;
  int repeats = 5;
  std::string write_meshes;    // non-empty: keep the generated meshes in this directory
  int aligned_cells = 4;       // cells per axis of the aligned cases' blocks; 0: no aligned cases
};

struct StageTimes {
  double read = 0, boxes = 0, broadphase = 0, decision = 0, depth = 0;
  double after_read = 0;  // boxes + broadphase + decision + depth, measured around contacts()
};

struct MeshRun {
  int threads = 0;
  StageTimes median;                // per stage, median over the runs
  std::size_t box_pairs = 0, intersecting = 0;
  double pairs_per_second = 0;      // intersecting pairs / median after_read
  double box_pairs_per_second = 0;  // box pairs / median decision (the exact decision's rate)
};

// One broadphase on the same boxes: its pairs and its median setup and query time.
struct BroadphaseRow {
  std::string name;
  std::size_t pairs = 0;
  double setup = 0, query = 0, total = 0;  // seconds, medians over repeats
  double ratio = 0;                        // total / ours (CGAL, same boxes, one core)
};

struct DecisionCosts {     // one core, on a sample of the box pairs
  std::size_t sample = 0;
  std::size_t disjoint = 0, intersecting = 0, unknown = 0;  // overlap_filter's verdicts
  double filter_ns = 0;     // fast::overlap_filter, median ns per pair over passes
  double decision_ns = 0;   // fast::interiors_intersect (filter + exact fallback)
  double rigid_ns = 0;      // fast::rigid_pd2 > 0 (the decision without the filter)
};

// The depth stage's calls one at a time, one core, on the intersecting pairs of the decision
// sample: per requested variant (eq11 excepted; global: "solve_pair", the call the depth
// stage makes for it) the median and the mean single-call time, and the share of the time
// spent in calls over 50 µs (for the single variants, the fast engine's refined or exact
// path, definitions §8; most solve_pair calls take about that long).
struct DepthCost {
  std::string name;
  double median_ns = 0, mean_ns = 0;
  std::size_t slow_calls = 0;   // calls over 50 µs
  double slow_share = 0;        // their share of the total time
};

// The aligned and structured cases (run_mesh_bench, --aligned-cells): meshes whose faces and
// edges are parallel to the other's, each beside the same meshes with B rotated by a generic
// angle (0.3 rad about (1, 2, 3) through B's centre), and beside the whole scene turned by that
// angle about the centre of both (the same scene in no axis-aligned frame, its faces and edges
// parallel to each other up to rounding; faces that touch exactly in the aligned scene may
// intersect by rounding there, more pairs), one core, in the same run.
struct AlignedRun {
  std::size_t elements_a = 0, elements_b = 0, box_pairs = 0, intersecting = 0;
  double decision_ns = 0;  // contacts()' decision stage / box pairs (median over repeats)
  double depth_ns = 0;     // contacts()' depth stage / intersecting pairs (median)
  // solve_pair (the options' variants) on up to 2000 intersecting pairs: its record statistics
  std::size_t sampled = 0, slow_path = 0, refined = 0;
};
struct AlignedCase {
  std::string name;
  AlignedRun aligned, rotated, scene;  // scene: A and B turned together
};

// m with every coordinate moved by a few ulps, as a mesh generator places a grid (Gmsh's
// transfinite boxes give 0.1 as 0.09999999999999992 ... 0.1000000000000001, each node its own):
// −2 to +2 ulps by a fixed pattern of the vertex index and the axis (zeros stay zero). Faces and
// edges that coincide or are parallel in exact arithmetic are then so only up to a rounding.
mesh::Mesh placed_up_to_rounding(mesh::Mesh m);

// Structured blocks: n[0] x n[1] x n[2] cubes of side h from `origin`, each cut into six Kuhn
// tetrahedra, five (alternating by cell parity) or 24 around its centre (body-centred: each
// face cut into four triangles around its centre, each triangle joined to the cube's centre;
// centres at origin + (index + 1/2)·h), then rotated by `angle` about `axis` through the
// block's centre (angle 0: coordinates origin + index·h, rounded once).
enum class CubeSplit { Kuhn6, Five, BodyCentred24 };
mesh::Mesh make_structured_block(const std::array<int, 3>& n, double h, const std::array<double, 3>& origin,
                                 CubeSplit split, double angle = 0, const std::array<double, 3>& axis = {1, 2, 3});

// Two Kuhn blocks of n x n x layers cubes of side h = 1/n, B's columns exactly over A's (the
// same x and y coordinates), B's bottom face `depth` h below A's top face (depth 0: the faces
// touch exactly; every vertical face of B in the plane of one of A's). tilt != 0: B rotated by
// `tilt` rad about (1, 2, 3) through the centre of its bottom face: the same contact, no face of
// B parallel to one of A's (the generic twin of the aligned case).
struct BlockPair {
  mesh::Mesh a, b;
  std::string description;
};
BlockPair stacked_blocks(int n, int layers, double depth, double tilt);

struct MeshBenchReport {
  MeshBenchOptions options;
  MachineInfo machine;
  std::string source_a, source_b;    // file names, or how the balls were made
  std::size_t elements_a = 0, elements_b = 0;
  double generate_seconds = 0;       // generated balls only
  MeshRun one_core, all_cores;
  DecisionCosts decision;
  std::size_t depth_sample = 0;  // intersecting pairs of the decision sample
  std::vector<DepthCost> depth;
  // Broadphase on all the element boxes (no pruning) and on the boxes contacts() keeps after
  // pruning by the other mesh's bounding box; ours first (one core), then FCL's managers.
  std::vector<BroadphaseRow> broadphase_all, broadphase_pruned;
  std::size_t pruned_a = 0, pruned_b = 0;  // boxes left after pruning
  double ours_all_cores_pruned = 0;        // contacts()'s broadphase (pruned, all cores), median
  std::vector<AlignedCase> aligned;
  std::vector<std::string> notes;
  double seconds = 0;
};

// Runs everything (progress on stderr). Throws std::invalid_argument on bad options and
// mesh::ReadError when a file cannot be read.
MeshBenchReport run_mesh_bench(const MeshBenchOptions& options);

}  // namespace pdd::compare
