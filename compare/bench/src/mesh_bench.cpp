// mesh_bench.cpp — `pdd bench mesh` (mesh_bench.h): the FCL broadphase runs and the stage
// timings (medians, one core and all cores), and the decision costs.
//
// FCL's managers test closed boxes (boxes that only touch overlap), CGAL's box_intersection_d
// is run with half-open boxes as in contacts(): FCL's pair counts may exceed ours by boxes that
// only touch. Managers: DynamicAABBTree and DynamicAABBTree_Array (FCL's recommended ones) and
// IntervalTree; SaP and SSaP are left out: SaPCollisionManager did not finish within 500 s on
// two balls of 7·10^4 elements, SSaP (sorted sweep on one axis, then a scan) is quadratic in the
// number of boxes overlapping on that axis; Naive is quadratic by design.
#include "pdd/compare/mesh_bench.h"

#include <fcl/config.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree_array.h>
#include <fcl/broadphase/broadphase_interval_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "pdd/compare/stats.h"

namespace pdd::compare {
namespace {

// Contact options computing the variants `v` (every other option at its default).
mesh::ContactOptions computing(unsigned v) {
  mesh::ContactOptions o;
  o.variants = v;
  return o;
}

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
double unit(std::uint64_t x) { return double(splitmix(x) >> 11) * 0x1p-53; }  // [0, 1)

// ---- FCL ------------------------------------------------------------------------------

struct FclSet {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<fcl::CollisionObjectd*> raw;
};

FclSet fcl_boxes(const mesh::Mesh& m, const std::vector<std::size_t>& elements) {
  FclSet s;
  for (std::size_t i : elements) {
    const TetVertices t = mesh::element(m, i);
    fcl::Vector3d lo, hi;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(std::min(t[0][k], t[1][k]), std::min(t[2][k], t[3][k]));
      hi[k] = std::max(std::max(t[0][k], t[1][k]), std::max(t[2][k], t[3][k]));
    }
    auto box = std::make_shared<fcl::Boxd>(hi - lo);
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.translation() = (lo + hi) / 2;
    auto o = std::make_unique<fcl::CollisionObjectd>(box, tf);
    o->computeAABB();
    s.raw.push_back(o.get());
    s.objects.push_back(std::move(o));
  }
  return s;
}

bool count_pair(fcl::CollisionObjectd*, fcl::CollisionObjectd*, void* data) {
  ++*static_cast<std::size_t*>(data);
  return false;  // keep going: every pair
}

struct Sample {
  std::size_t pairs = 0;
  double setup = 0, query = 0;
};

template <class Manager>
Sample fcl_once(FclSet& a, FclSet& b) {
  Sample s;
  auto t = Clock::now();
  Manager ma, mb;
  ma.registerObjects(a.raw);
  mb.registerObjects(b.raw);
  ma.setup();
  mb.setup();
  s.setup = since(t);
  t = Clock::now();
  ma.collide(&mb, &s.pairs, count_pair);
  s.query = since(t);
  return s;
}

// Every broadphase on the boxes of elements ea of A and eb of B, `repeats` interleaved
// rounds, one core; row 0 is ours.
std::vector<BroadphaseRow> broadphase_rows(const mesh::Mesh& A, const std::vector<std::size_t>& ea,
                                           const mesh::Mesh& B, const std::vector<std::size_t>& eb,
                                           int repeats) {
  FclSet fa = fcl_boxes(A, ea), fb = fcl_boxes(B, eb);
  tbb::task_arena one(1);
  using Run = std::function<Sample()>;
  const std::vector<std::pair<std::string, Run>> runs = {
      {"CGAL box_intersection_d (ours)",
       [&] {
         Sample s;
         const auto t = Clock::now();
         one.execute([&] { s.pairs = mesh::box_pairs(A, ea, B, eb, {false, false}).size(); });
         s.query = since(t);
         return s;
       }},
      {"FCL DynamicAABBTreeCollisionManager", [&] { return fcl_once<fcl::DynamicAABBTreeCollisionManagerd>(fa, fb); }},
      {"FCL DynamicAABBTreeCollisionManager_Array",
       [&] { return fcl_once<fcl::DynamicAABBTreeCollisionManager_Arrayd>(fa, fb); }},
      {"FCL IntervalTreeCollisionManager", [&] { return fcl_once<fcl::IntervalTreeCollisionManagerd>(fa, fb); }},
  };
  std::vector<std::vector<Sample>> samples(runs.size());
  for (int r = 0; r < repeats; ++r)
    for (std::size_t k = 0; k < runs.size(); ++k) samples[k].push_back(runs[k].second());
  std::vector<BroadphaseRow> rows;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    BroadphaseRow row;
    row.name = runs[k].first;
    row.pairs = samples[k].front().pairs;
    std::vector<double> setup, query, total;
    for (const Sample& s : samples[k]) {
      setup.push_back(s.setup);
      query.push_back(s.query);
      total.push_back(s.setup + s.query);
    }
    row.setup = median(setup);
    row.query = median(query);
    row.total = median(total);
    rows.push_back(row);
  }
  for (auto& row : rows) row.ratio = row.total / rows[0].total;
  return rows;
}

// ---- contacts() per stage ---------------------------------------------------------------

struct RunSample {
  StageTimes t;
  std::size_t box_pairs = 0, intersecting = 0;
};

RunSample run_once(tbb::task_arena& arena, const mesh::Mesh& A, const mesh::Mesh& B, unsigned variants) {
  RunSample s;
  arena.execute([&] {
    const auto t = Clock::now();
    const mesh::Contacts<double> c = mesh::contacts(A, B, computing(variants));
    s.t.after_read = since(t);
    s.t.boxes = c.seconds_boxes;
    s.t.broadphase = c.seconds_broadphase;
    s.t.decision = c.seconds_decision;
    s.t.depth = c.seconds_depth;
    s.box_pairs = c.box_pairs;
    s.intersecting = c.pairs.size();
  });
  return s;
}

MeshRun summarise(int threads, const std::vector<RunSample>& runs, const std::vector<double>& read) {
  MeshRun m;
  m.threads = threads;
  auto med = [&](double StageTimes::*f) {
    std::vector<double> v;
    for (const RunSample& r : runs) v.push_back(r.t.*f);
    return median(v);
  };
  m.median.read = median(read);
  m.median.boxes = med(&StageTimes::boxes);
  m.median.broadphase = med(&StageTimes::broadphase);
  m.median.decision = med(&StageTimes::decision);
  m.median.depth = med(&StageTimes::depth);
  m.median.after_read = med(&StageTimes::after_read);
  m.box_pairs = runs.front().box_pairs;
  m.intersecting = runs.front().intersecting;
  m.pairs_per_second = double(m.intersecting) / m.median.after_read;
  m.box_pairs_per_second = double(m.box_pairs) / m.median.decision;
  return m;
}

// Median ns per pair of `f` over the sample, `repeats` passes (one warm-up), one thread.
double ns_per_pair(const std::vector<std::array<TetVertices, 2>>& sample, int repeats,
                   const std::function<int(const TetVertices&, const TetVertices&)>& f) {
  volatile int sink = 0;
  std::vector<double> passes;
  for (int r = 0; r <= repeats; ++r) {
    const auto t = Clock::now();
    int acc = 0;
    for (const auto& p : sample) acc += f(p[0], p[1]);
    const double s = since(t);
    sink = sink + acc;
    if (r > 0) passes.push_back(s * 1e9 / double(sample.size()));
  }
  return median(passes);
}

std::vector<std::size_t> all_elements(const mesh::Mesh& m) {
  std::vector<std::size_t> e(m.tets.size());
  std::iota(e.begin(), e.end(), std::size_t{0});
  return e;
}

// The elements of A and B whose boxes contacts()'s pruning keeps (the same rounds as
// mesh/src/contacts.cpp: boxes that overlap the other mesh's bounding box, half-open, repeated
// while it removes boxes, at most 4 rounds).
void pruned(const mesh::Mesh& A, const mesh::Mesh& B, std::vector<std::size_t>& ea, std::vector<std::size_t>& eb) {
  struct Bx {
    std::size_t i;
    double lo[3], hi[3];
  };
  auto boxes = [](const mesh::Mesh& m) {
    std::vector<Bx> v;
    for (std::size_t i = 0; i < m.tets.size(); ++i) {
      const TetVertices t = mesh::element(m, i);
      Bx b{i, {}, {}};
      for (int k = 0; k < 3; ++k) {
        b.lo[k] = std::min(std::min(t[0][k], t[1][k]), std::min(t[2][k], t[3][k]));
        b.hi[k] = std::max(std::max(t[0][k], t[1][k]), std::max(t[2][k], t[3][k]));
      }
      v.push_back(b);
    }
    return v;
  };
  auto bounds = [](const std::vector<Bx>& v) {
    std::array<double, 6> u = {HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const Bx& x : v)
      for (int k = 0; k < 3; ++k) u[k] = std::min(u[k], x.lo[k]), u[3 + k] = std::max(u[3 + k], x.hi[k]);
    return u;
  };
  auto keep = [](std::vector<Bx>& v, const std::array<double, 6>& u) {
    v.erase(std::remove_if(v.begin(), v.end(),
                           [&](const Bx& x) {
                             for (int k = 0; k < 3; ++k)
                               if (!(x.lo[k] < u[3 + k] && u[k] < x.hi[k])) return true;
                             return false;
                           }),
            v.end());
  };
  std::vector<Bx> ba = boxes(A), bb = boxes(B);
  for (int round = 0; round < 4; ++round) {
    const std::size_t before = ba.size() + bb.size();
    const auto ua = bounds(ba), ub = bounds(bb);
    keep(ba, ub);
    keep(bb, ua);
    if (ba.size() + bb.size() == before) break;
  }
  ea.clear();
  eb.clear();
  for (const Bx& x : ba) ea.push_back(x.i);
  for (const Bx& x : bb) eb.push_back(x.i);
}
}  // namespace

std::array<std::array<double, 3>, 3> rotation_matrix(const std::array<double, 3>& axis, double angle) {
  const double an = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  const double x = axis[0] / an, y = axis[1] / an, z = axis[2] / an, c = std::cos(angle),
               s = std::sin(angle), C = 1 - c;
  return {{{c + x * x * C, x * y * C - z * s, x * z * C + y * s},
           {y * x * C + z * s, c + y * y * C, y * z * C - x * s},
           {z * x * C - y * s, z * y * C + x * s, c + z * z * C}}};
}

namespace {

// m translated by t, then rotated by `angle` about `axis` through its centre (angle 0: only
// translated, each coordinate rounded once).
mesh::Mesh moved(const mesh::Mesh& m, const std::array<double, 3>& t, double angle,
                 const std::array<double, 3>& axis = {1, 2, 3}) {
  mesh::Mesh out = m;
  double c[3] = {0, 0, 0};
  for (const Vec3d& v : m.vertices)
    for (int k = 0; k < 3; ++k) c[k] += v[k] / double(m.vertices.size());
  const auto R = rotation_matrix(axis, angle);
  for (Vec3d& v : out.vertices) {
    if (angle == 0) {
      for (int k = 0; k < 3; ++k) v[k] += t[k];
      continue;
    }
    const double p[3] = {v[0] - c[0], v[1] - c[1], v[2] - c[2]};
    for (int r = 0; r < 3; ++r) v[r] = c[r] + t[r] + R[r][0] * p[0] + R[r][1] * p[1] + R[r][2] * p[2];
  }
  return out;
}

// A and B turned together by `angle` about `axis` through the centre of all their vertices:
// the scene as it is, in another frame.
std::pair<mesh::Mesh, mesh::Mesh> turned_together(const mesh::Mesh& A, const mesh::Mesh& B, double angle,
                                                  const std::array<double, 3>& axis = {1, 2, 3}) {
  double c[3] = {0, 0, 0};
  const double n = double(A.vertices.size() + B.vertices.size());
  for (const mesh::Mesh* m : {&A, &B})
    for (const Vec3d& v : m->vertices)
      for (int k = 0; k < 3; ++k) c[k] += v[k] / n;
  const auto R = rotation_matrix(axis, angle);
  std::pair<mesh::Mesh, mesh::Mesh> out{A, B};
  for (mesh::Mesh* m : {&out.first, &out.second})
    for (Vec3d& v : m->vertices) {
      const double p[3] = {v[0] - c[0], v[1] - c[1], v[2] - c[2]};
      for (int r = 0; r < 3; ++r) v[r] = c[r] + R[r][0] * p[0] + R[r][1] * p[1] + R[r][2] * p[2];
    }
  return out;
}

// One aligned case's meshes (A, B) on one core: contacts() `repeats` times after a warm-up call
// (medians per stage), then solve_pair's record statistics (the values of `variants`) on up to
// 2000 intersecting pairs.
AlignedRun aligned_run(const mesh::Mesh& A, const mesh::Mesh& B, unsigned variants, int repeats) {
  tbb::task_arena one(1);
  AlignedRun a;
  a.elements_a = A.tets.size();
  a.elements_b = B.tets.size();
  std::vector<double> dec, dep;
  mesh::Contacts<double> c;
  one.execute([&] { c = mesh::contacts(A, B, computing(variants)); });
  for (int r = 0; r < repeats; ++r)
    one.execute([&] {
      c = mesh::contacts(A, B, computing(variants));
      dec.push_back(c.seconds_decision);
      dep.push_back(c.seconds_depth);
    });
  a.box_pairs = c.box_pairs;
  a.intersecting = c.pairs.size();
  a.decision_ns = a.box_pairs ? median(dec) * 1e9 / double(a.box_pairs) : 0;
  a.depth_ns = a.intersecting ? median(dep) * 1e9 / double(a.intersecting) : 0;
  fast::SolveOptions so;  // what the depth stage computes (mesh/src/contacts.cpp)
  so.with_global = (variants & mesh::kGlobal) != 0;
  so.values = variants & ~unsigned(mesh::kGlobal);
  const std::size_t step = std::max<std::size_t>(1, c.pairs.size() / 2000);
  for (std::size_t k = 0; k < c.pairs.size(); k += step) {
    const auto r = fast::solve_pair(TetPair{"", {}, mesh::element(A, c.pairs[k].a), mesh::element(B, c.pairs[k].b)}, so);
    ++a.sampled;
    a.slow_path += r.stats.slow_path;
    a.refined += r.stats.refined;
  }
  return a;
}

// The records' storage reused from call to call (glibc). contacts() returns ~0.9 KB a record
// (PairResult<double>), and glibc maps every block above its mmap threshold (at most 32 MiB:
// ~36,000 records) afresh, so such a call pays the first touch of every page of its records
// each time (page faults: 1.5-2.5 us a record on the 2-CPU VM of docs/performance.md, several
// times rigid and accel1's own work on a pair), while a smaller block comes back from the heap.
// The depth stage's time per pair then followed a case's pair count and its place in the run,
// not its alignment: the rotated twins of the 8^3 Kuhn grids (~39,000 pairs) took 2.8-2.9 us a
// pair, a smaller twin 0.6 us. With mmap off and freed memory kept, every case runs on storage a
// warm-up call left (aligned_run), and the per-pair times compare the engine's work.
void keep_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

std::vector<AlignedCase> aligned_cases(const MeshBenchOptions& o) {
  std::vector<AlignedCase> out;
  const int n = o.aligned_cells;
  if (n <= 0) return out;
  keep_freed_memory();
  const double h = 1.0 / n;
  const std::array<double, 3> shift = {0.37 * h, 0.21 * h, 0.13 * h};  // not on the grid
  auto run = [&](const std::string& name, const mesh::Mesh& A, const mesh::Mesh& B, const mesh::Mesh& Brot) {
    std::cerr << "pdd bench mesh: aligned case: " << name << "\n";
    AlignedCase c;
    c.name = name;
    c.aligned = aligned_run(A, B, o.variants, o.repeats);
    c.rotated = aligned_run(A, Brot, o.variants, o.repeats);
    const auto [As, Bs] = turned_together(A, B, 0.3);
    c.scene = aligned_run(As, Bs, o.variants, o.repeats);
    out.push_back(c);
  };
  for (CubeSplit split : {CubeSplit::Kuhn6, CubeSplit::Five}) {
    const mesh::Mesh A = make_structured_block({n, n, n}, h, {0, 0, 0}, split);
    const mesh::Mesh B = make_structured_block({n, n, n}, h, shift, split);
    run(std::string(split == CubeSplit::Kuhn6 ? "Kuhn grids" : "5-tetrahedra grids") + ", one shifted by a non-grid offset",
        A, B, moved(B, {0, 0, 0}, 0.3));
  }
  {  // a Kuhn grid against its copy shifted by half a cell along (1, 1, 1): B's vertices on A's
     // cube diagonals, diagonal edges colinear, diagonal faces coplanar, candidates tied in
     // symmetric groups (the cell a power of two, so that the shift is exact)
    const double hp = std::ldexp(1.0, -int(std::ceil(std::log2(double(n)))));
    const mesh::Mesh A = make_structured_block({n, n, n}, hp, {0, 0, 0}, CubeSplit::Kuhn6);
    const mesh::Mesh B = make_structured_block({n, n, n}, hp, {hp / 2, hp / 2, hp / 2}, CubeSplit::Kuhn6);
    run("Kuhn grids, one shifted half a cell along (1, 1, 1)", A, B, moved(B, {0, 0, 0}, 0.3));
    // the same shifted a tenth of a cell instead, a shift with no short binary form: faces
    // that coincide in exact arithmetic (x = y: x + s and y + s round apart) overlap by ~1e-17
    // of the cell, contacts made by rounding (docs/performance.md)
    const mesh::Mesh C = make_structured_block({n, n, n}, hp, {hp / 10, hp / 10, hp / 10}, CubeSplit::Kuhn6);
    run("Kuhn grids, one shifted a tenth of a cell along (1, 1, 1)", A, C, moved(C, {0, 0, 0}, 0.3));
  }
  {  // another decomposition: cubes cut into 24 tetrahedra around their centres, cell 0.1 (half
     // as many cubes a side: four times the Kuhn grid's tetrahedra a cube), a copy shifted a
     // quarter cell along (1, 1, 1): the diagonal planes coincide up to rounding, so about half
     // the pairs are contacts made by rounding, the rest near ties of nearly parallel faces
    const int m = std::max(2, n / 2);
    const mesh::Mesh A = make_structured_block({m, m, m}, 0.1, {0, 0, 0}, CubeSplit::BodyCentred24);
    const mesh::Mesh B = make_structured_block({m, m, m}, 0.1, {0.025, 0.025, 0.025}, CubeSplit::BodyCentred24);
    run("24-tetrahedra grids of cell 0.1, shifted a quarter cell", A, B, moved(B, {0, 0, 0}, 0.3));
  }
  {  // a jittered (unstructured-looking) mesh against a copy of itself shifted off the grid
    const mesh::Mesh A = make_bench_ball(std::size_t(6) * n * n * n, {0, 0, 0}, 1, {1, 2, 3}, 0.3, 7);
    run("a jittered mesh against its shifted copy", A, moved(A, {0.061, 0.043, 0.029}, 0),
        moved(A, {0.061, 0.043, 0.029}, 0.3));
  }
  {  // blocks stacked along z, a third of a cell deep, faces parallel across the whole contact
    const int nz = std::max(1, n / 2);
    const mesh::Mesh A = make_structured_block({n, n, nz}, h, {0, 0, 0}, CubeSplit::Five);
    const mesh::Mesh B = make_structured_block({n, n, nz}, h, {shift[0], shift[1], nz * h - h / 3}, CubeSplit::Five);
    run("5-tetrahedra blocks stacked a third of a cell deep", A, B, moved(B, {0, 0, 0}, 0.3));
  }
  {  // a grid as a mesh generator places it: every coordinate a few ulps off the grid's
     // (placed_up_to_rounding), so faces that coincide in exact arithmetic overlap or part by a
     // rounding; against its copy shifted off the grid, and stacked on its copy's columns a third
     // of a cell deep (their side faces: contacts made by rounding, most of the pairs)
    const mesh::Mesh A = placed_up_to_rounding(make_structured_block({n, n, n}, h, {0, 0, 0}, CubeSplit::Kuhn6));
    run("Kuhn grids placed up to a rounding, one shifted off the grid", A, moved(A, shift, 0), moved(A, shift, 0.3));
    const int nz = std::max(1, n / 2);
    const mesh::Mesh S = placed_up_to_rounding(make_structured_block({n, n, nz}, h, {0, 0, 0}, CubeSplit::Kuhn6));
    const std::array<double, 3> up = {0, 0, nz * h - h / 3};
    run("Kuhn blocks placed up to a rounding, stacked a third of a cell deep", S, moved(S, up, 0), moved(S, up, 0.3));
  }
  return out;
}

}  // namespace

namespace {
// The 24 tetrahedra of cube (i, j, k) around its centre (make_structured_block's body-centred
// split): per face, its centre (shared with the neighbour: keyed by the doubled index) and the
// four triangles it cuts the face into, each joined to the cube's centre.
template <class Corner>
void body_centred_cube(mesh::Mesh& out, const std::array<int, 3>& n, double h, const std::array<double, 3>& origin,
                       const std::array<int, 3>& cell, Corner corner,
                       std::map<std::array<int, 3>, std::size_t>& face_centres) {
  (void)n;
  auto point = [&](const std::array<int, 3>& twice) {  // origin + (twice / 2)·h
    Vec3d p;
    for (int a = 0; a < 3; ++a) p[a] = origin[a] + (twice[a] / 2 + (twice[a] % 2 ? 0.5 : 0.0)) * h;
    return p;
  };
  const std::size_t centre = out.vertices.size();
  out.vertices.push_back(point({2 * cell[0] + 1, 2 * cell[1] + 1, 2 * cell[2] + 1}));
  for (int ax = 0; ax < 3; ++ax)
    for (int side = 0; side < 2; ++side) {
      std::array<int, 3> twice = {2 * cell[0] + 1, 2 * cell[1] + 1, 2 * cell[2] + 1};
      twice[ax] = 2 * (cell[ax] + side);
      auto [it, fresh] = face_centres.try_emplace(twice, out.vertices.size());
      if (fresh) out.vertices.push_back(point(twice));
      const int u = (ax + 1) % 3, v = (ax + 2) % 3;
      int ring[4];  // the face's corners in order around it (corner bits: 1 x, 2 y, 4 z)
      const int step[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      for (int q = 0; q < 4; ++q) ring[q] = (side << ax) | (step[q][0] << u) | (step[q][1] << v);
      for (int q = 0; q < 4; ++q)
        out.tets.push_back({centre, it->second, corner(ring[q]), corner(ring[(q + 1) % 4])});
    }
}
}  // namespace

mesh::Mesh placed_up_to_rounding(mesh::Mesh m) {
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    for (int k = 0; k < 3; ++k) {
      double& x = m.vertices[v][k];
      if (x == 0) continue;
      for (int u = int((v * 7 + std::size_t(k) * 3) % 5) - 2; u != 0; u += u > 0 ? -1 : 1)
        x = std::nextafter(x, u > 0 ? HUGE_VAL : -HUGE_VAL);
    }
  return m;
}

mesh::Mesh make_structured_block(const std::array<int, 3>& n, double h, const std::array<double, 3>& origin,
                                 CubeSplit split, double angle, const std::array<double, 3>& axis) {
  mesh::Mesh out;
  auto id = [&](int i, int j, int k) { return (std::size_t(i) * (n[1] + 1) + j) * (n[2] + 1) + k; };
  for (int i = 0; i <= n[0]; ++i)
    for (int j = 0; j <= n[1]; ++j)
      for (int k = 0; k <= n[2]; ++k)
        out.vertices.push_back({origin[0] + i * h, origin[1] + j * h, origin[2] + k * h});
  static const int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  // corners: bit 0 x, bit 1 y, bit 2 z; five tetrahedra: four corners cut off and the centre one
  static const int kEven[5][4] = {{0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}, {1, 2, 4, 7}};
  static const int kOdd[5][4] = {{1, 0, 3, 5}, {2, 0, 3, 6}, {4, 0, 5, 6}, {7, 3, 5, 6}, {0, 3, 5, 6}};
  std::map<std::array<int, 3>, std::size_t> face_centres;  // body-centred: by doubled index
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        auto corner = [&](int c) { return id(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1)); };
        if (split == CubeSplit::Kuhn6) {
          for (const auto& p : kPerm) {  // the path (0,0,0) -> +e_p0 -> +e_p1 -> +e_p2
            int d[3] = {0, 0, 0};
            std::array<std::size_t, 4> t;
            t[0] = id(i, j, k);
            for (int q = 0; q < 3; ++q) {
              d[p[q]] = 1;
              t[q + 1] = id(i + d[0], j + d[1], k + d[2]);
            }
            out.tets.push_back(t);
          }
        } else if (split == CubeSplit::Five) {
          const auto& T = ((i + j + k) & 1) ? kOdd : kEven;
          for (const auto& c : T) out.tets.push_back({corner(c[0]), corner(c[1]), corner(c[2]), corner(c[3])});
        } else {
          body_centred_cube(out, n, h, origin, {i, j, k}, corner, face_centres);
        }
      }
  return angle == 0 ? out : moved(out, {0, 0, 0}, angle, axis);
}

BlockPair stacked_blocks(int n, int layers, double depth, double tilt) {
  const double h = 1.0 / n;
  BlockPair out;
  out.a = make_structured_block({n, n, layers}, h, {0, 0, 0}, CubeSplit::Kuhn6);
  out.b = make_structured_block({n, n, layers}, h, {0, 0, layers * h - depth * h}, CubeSplit::Kuhn6);
  char buf[200];
  std::snprintf(buf, sizeof buf, "Kuhn blocks of %dx%dx%d cubes, B on A's columns %.3g cell deep", n, n, layers,
                depth);
  out.description = buf;
  if (tilt != 0) {
    const auto R = rotation_matrix({1, 2, 3}, tilt);
    const double c[3] = {0.5, 0.5, layers * h - depth * h};  // centre of B's bottom face
    for (Vec3d& v : out.b.vertices) {
      const double p[3] = {v[0] - c[0], v[1] - c[1], v[2] - c[2]};
      for (int r = 0; r < 3; ++r) v[r] = c[r] + R[r][0] * p[0] + R[r][1] * p[1] + R[r][2] * p[2];
    }
    std::snprintf(buf, sizeof buf, ", B tilted %.3g rad about (1, 2, 3) through its bottom face's centre", tilt);
    out.description += buf;
  }
  return out;
}

mesh::Mesh make_bench_ball(std::size_t target, const std::array<double, 3>& centre, double radius,
                           const std::array<double, 3>& axis, double angle, std::uint64_t seed) {
  // 6 (4π/3) (R/h)³ tetrahedra: h = R (8π / target)^(1/3), at most R: the eight cubes about
  // the centre have their centres at (√3/2) h <= 0.87 R, inside, so even the smallest target
  // gives a mesh (48 tetrahedra; uncapped, a target below 17 makes h > 2R/√3: no cube inside).
  const double h = radius * std::min(1.0, std::cbrt(8 * M_PI / double(std::max<std::size_t>(target, 1))));
  const int m = int(std::ceil(radius / h)) + 1;  // grid points −m..m per axis
  const int side = 2 * m + 1;
  auto gid = [&](int i, int j, int k) { return (std::size_t(i + m) * side + std::size_t(j + m)) * side + std::size_t(k + m); };
  std::vector<long long> index(std::size_t(side) * side * side, -1);
  mesh::Mesh out;
  // Rotation (Rodrigues) about the unit axis.
  const double an = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  const double x = axis[0] / an, y = axis[1] / an, z = axis[2] / an, c = std::cos(angle),
               s = std::sin(angle), C = 1 - c;
  const double R[3][3] = {{c + x * x * C, x * y * C - z * s, x * z * C + y * s},
                          {y * x * C + z * s, c + y * y * C, y * z * C - x * s},
                          {z * x * C - y * s, z * y * C + x * s, c + z * z * C}};
  auto vertex = [&](int i, int j, int k) -> std::size_t {
    long long& v = index[gid(i, j, k)];
    if (v < 0) {
      const std::uint64_t key = splitmix(seed) ^ gid(i, j, k);
      const double p[3] = {(i + 0.2 * (unit(3 * key) - 0.5)) * h, (j + 0.2 * (unit(3 * key + 1) - 0.5)) * h,
                           (k + 0.2 * (unit(3 * key + 2) - 0.5)) * h};
      Vec3d q;
      for (int r = 0; r < 3; ++r) q[r] = centre[r] + R[r][0] * p[0] + R[r][1] * p[1] + R[r][2] * p[2];
      v = (long long)out.vertices.size();
      out.vertices.push_back(q);
    }
    return std::size_t(v);
  };
  static const int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int i = -m; i < m; ++i)
    for (int j = -m; j < m; ++j)
      for (int k = -m; k < m; ++k) {
        const double cx = (i + 0.5) * h, cy = (j + 0.5) * h, cz = (k + 0.5) * h;
        if (cx * cx + cy * cy + cz * cz > radius * radius) continue;
        for (const auto& p : kPerm) {  // Kuhn: the path (0,0,0) -> +e_p0 -> +e_p1 -> +e_p2
          int d[3] = {0, 0, 0};
          std::array<std::size_t, 4> t;
          t[0] = vertex(i, j, k);
          for (int q = 0; q < 3; ++q) {
            d[p[q]] = 1;
            t[q + 1] = vertex(i + d[0], j + d[1], k + d[2]);
          }
          out.tets.push_back(t);
        }
      }
  return out;
}

MeshBenchReport run_mesh_bench(const MeshBenchOptions& o) {
  if (o.a.empty() != o.b.empty()) throw std::invalid_argument("give both --a and --b, or neither");
  if (o.repeats < 1) throw std::invalid_argument("--repeats must be at least 1");
  const auto t_all = Clock::now();
  MeshBenchReport rep;
  rep.options = o;
  rep.machine = machine_info();
  rep.machine.fcl_version = FCL_VERSION;
  std::string pa = o.a, pb = o.b;
  std::filesystem::path tmp;
  if (pa.empty()) {
    std::cerr << "pdd bench mesh: generating two balls of about " << o.size << " tetrahedra\n";
    const auto t = Clock::now();
    const mesh::Mesh A = make_bench_ball(o.size, {0, 0, 0}, 1, {1, 2, 3}, 0.3, 1);
    const double d = o.distance;
    const mesh::Mesh B = make_bench_ball(o.size, {d * 0.99, d * 0.1, d * 0.07}, 1, {-2, 1, 1}, 0.7, 2);
    rep.generate_seconds = since(t);
    std::filesystem::path dir;
    if (!o.write_meshes.empty()) {
      dir = o.write_meshes;
      std::filesystem::create_directories(dir);
    } else {
      tmp = dir = std::filesystem::temp_directory_path() /
                  ("pdd-bench-mesh-" + std::to_string(::getpid()));
      std::filesystem::create_directories(dir);
    }
    pa = (dir / "ball-a.vtk").string();
    pb = (dir / "ball-b.vtk").string();
    mesh::write_vtk_self(pa, A, mesh::Contacts<double>{}, 0);
    mesh::write_vtk_self(pb, B, mesh::Contacts<double>{}, 0);
    char buf[200];
    std::snprintf(buf, sizeof buf, "generated ball (Kuhn grid, jittered), centre (0, 0, 0), radius 1");
    rep.source_a = buf;
    std::snprintf(buf, sizeof buf,
                  "generated ball, centre %.4g x (0.99, 0.1, 0.07), radius 1, rotated", d);
    rep.source_b = buf;
    rep.notes.push_back("meshes written as legacy VTK (ASCII) to " + dir.string() +
                        (tmp.empty() ? "" : " and removed afterwards") + "; read back for the read stage");
  } else {
    rep.source_a = pa;
    rep.source_b = pb;
  }

  // Reading, then contacts() on one core and on all cores, interleaved, after one warm-up run.
  std::cerr << "pdd bench mesh: reading\n";
  std::vector<double> read;
  mesh::Mesh A, B;
  for (int r = 0; r < o.repeats; ++r) {
    const auto t = Clock::now();
    A = mesh::read_mesh(pa);
    B = mesh::read_mesh(pb);
    read.push_back(since(t));
  }
  if (!tmp.empty()) std::filesystem::remove_all(tmp);
  rep.elements_a = A.tets.size();
  rep.elements_b = B.tets.size();
  tbb::task_arena one(1), all(tbb::info::default_concurrency());
  std::cerr << "pdd bench mesh: " << A.tets.size() << " x " << B.tets.size()
            << " tetrahedra; contacts() warm-up\n";
  run_once(all, A, B, o.variants);
  std::vector<RunSample> r1, ra;
  for (int r = 0; r < o.repeats; ++r) {
    std::cerr << "pdd bench mesh: run " << r + 1 << " of " << o.repeats << "\n";
    r1.push_back(run_once(one, A, B, o.variants));
    ra.push_back(run_once(all, A, B, o.variants));
  }
  rep.one_core = summarise(1, r1, read);
  rep.all_cores = summarise(tbb::info::default_concurrency(), ra, read);

  // The decision stage's costs on a sample of the box pairs (every k-th), one core.
  std::cerr << "pdd bench mesh: decision costs\n";
  const auto cand = mesh::box_pairs(A, all_elements(A), B, all_elements(B));
  std::vector<std::array<TetVertices, 2>> sample;
  const std::size_t step = std::max<std::size_t>(1, cand.size() / 5000);
  for (std::size_t k = 0; k < cand.size(); k += step)
    sample.push_back({mesh::element(A, cand[k][0]), mesh::element(B, cand[k][1])});
  DecisionCosts& dc = rep.decision;
  dc.sample = sample.size();
  for (const auto& p : sample) switch (fast::overlap_filter(p[0], p[1])) {
      case fast::Overlap::Disjoint: ++dc.disjoint; break;
      case fast::Overlap::Intersecting: ++dc.intersecting; break;
      case fast::Overlap::Unknown: ++dc.unknown; break;
    }
  if (!sample.empty()) {
    dc.filter_ns = ns_per_pair(sample, o.repeats, [](const TetVertices& a, const TetVertices& b) {
      return int(fast::overlap_filter(a, b));
    });
    dc.decision_ns = ns_per_pair(sample, o.repeats, [](const TetVertices& a, const TetVertices& b) {
      return int(fast::interiors_intersect(a, b));
    });
    dc.rigid_ns = ns_per_pair(sample, std::min(o.repeats, 3), [](const TetVertices& a, const TetVertices& b) {
      return int(fast::rigid_pd2(a, b).pd2 > 0);
    });
  }

  // The depth stage's calls one at a time on the intersecting pairs of the sample.
  std::vector<std::array<TetVertices, 2>> hits;
  for (const auto& p : sample)
    if (fast::interiors_intersect(p[0], p[1])) hits.push_back(p);
  rep.depth_sample = hits.size();
  using DepthFn = std::function<double(const TetVertices&, const TetVertices&)>;
  const std::vector<std::pair<unsigned, std::pair<const char*, DepthFn>>> calls = {
      {mesh::kRigid, {"rigid_pd2", [](const TetVertices& a, const TetVertices& b) { return fast::rigid_pd2(a, b).pd2; }}},
      {mesh::kStatic, {"pdd2_static", [](const TetVertices& a, const TetVertices& b) { return fast::pdd2_static(a, b).pd2; }}},
      {mesh::kPdd2, {"pdd2", [](const TetVertices& a, const TetVertices& b) { return fast::pdd2(a, b).pd2; }}},
      {mesh::kRelaxed, {"pdd2_relaxed", [](const TetVertices& a, const TetVertices& b) { return fast::pdd2_relaxed(a, b).pd2; }}},
      {mesh::kAccel1, {"pdd2_accel1", [](const TetVertices& a, const TetVertices& b) { return fast::pdd2_accel(a, b, 1).pd2; }}},
      {mesh::kAccel6, {"pdd2_accel6", [](const TetVertices& a, const TetVertices& b) { return fast::pdd2_accel(a, b, 6).pd2; }}},
      // global: what the depth stage calls for it (mesh.h), one solve_pair (every value)
      {mesh::kGlobal, {"solve_pair", [](const TetVertices& a, const TetVertices& b) {
         return fast::solve_pair(TetPair{"", {}, a, b}).pdd2_global; }}},
  };
  for (const auto& entry : calls) {  // not a structured binding: the lambda below captures call
    const auto& call = entry.second;
    if (!(o.variants & entry.first) || hits.empty()) continue;
    volatile double sink = 0;
    const std::vector<double> ns = time_each_call(hits.size(), [&](std::size_t k) {
      sink = sink + call.second(hits[k][0], hits[k][1]);
    });
    DepthCost d;
    d.name = call.first;
    d.median_ns = median(ns);
    double total = 0, slow = 0;
    for (double x : ns) {
      total += x;
      if (x > 50e3) slow += x, ++d.slow_calls;
    }
    d.mean_ns = total / double(ns.size());
    d.slow_share = total > 0 ? slow / total : 0;
    rep.depth.push_back(d);
  }

  // Broadphase against FCL, one core, on all boxes and on the pruned boxes.
  std::cerr << "pdd bench mesh: broadphase against FCL (all boxes)\n";
  rep.broadphase_all = broadphase_rows(A, all_elements(A), B, all_elements(B), o.repeats);
  std::vector<std::size_t> pa_el, pb_el;
  pruned(A, B, pa_el, pb_el);
  rep.pruned_a = pa_el.size();
  rep.pruned_b = pb_el.size();
  std::cerr << "pdd bench mesh: broadphase against FCL (pruned boxes)\n";
  rep.broadphase_pruned = broadphase_rows(A, pa_el, B, pb_el, o.repeats);
  rep.ours_all_cores_pruned = rep.all_cores.median.broadphase;
  rep.aligned = aligned_cases(o);
  rep.seconds = since(t_all);
  rep.machine.load_after = read_first_line("/proc/loadavg");
  return rep;
}

}  // namespace pdd::compare
