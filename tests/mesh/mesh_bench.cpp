// mesh_bench — time per stage of pdd::mesh::contacts on two meshes, and the broadphase side by
// side with FCL's broadphase managers on the same element boxes (issue 11, item 5). Not a
// CTest; run by hand:
//   bash scripts/make-meshes.sh --large /tmp/large
//   build/bin/mesh_bench /tmp/large/large-a.msh /tmp/large/large-b.msh [variants] [threads]
// FCL's managers test closed boxes (touching boxes overlap), CGAL's box_intersection_d is run
// with half-open boxes here, as in contacts(): the pair counts may differ by boxes that only touch.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree_array.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <numeric>
#include <string>

#include "pdd/mesh.h"

using namespace pdd;
using Clock = std::chrono::steady_clock;
static double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct FclSet {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<fcl::CollisionObjectd*> raw;
};

static FclSet fcl_boxes(const mesh::Mesh& m, std::size_t tag0) {
  FclSet s;
  for (std::size_t i = 0; i < m.tets.size(); ++i) {
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
    o->setUserData(reinterpret_cast<void*>(tag0 + i));
    o->computeAABB();
    s.raw.push_back(o.get());
    s.objects.push_back(std::move(o));
  }
  return s;
}

static bool count_pair(fcl::CollisionObjectd*, fcl::CollisionObjectd*, void* data) {
  ++*static_cast<std::size_t*>(data);
  return false;  // keep going: every pair
}

template <class Manager>
static void fcl_run(const char* name, const mesh::Mesh& A, const mesh::Mesh& B) {
  FclSet a = fcl_boxes(A, 0), b = fcl_boxes(B, A.tets.size());
  auto t = Clock::now();
  Manager ma, mb;
  ma.registerObjects(a.raw);
  mb.registerObjects(b.raw);
  ma.setup();
  mb.setup();
  const double build = since(t);
  std::size_t n = 0;
  t = Clock::now();
  ma.collide(&mb, &n, count_pair);
  const double query = since(t);
  std::printf("  FCL %-32s %9zu pairs  setup %.4f s + query %.4f s = %.4f s\n", name, n, build, query,
              build + query);
}

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: mesh_bench A B [variants] [threads]\n");
    return 2;
  }
  const unsigned variants = mesh::parse_variants(argc > 3 ? argv[3] : "rigid,accel1");
  const int threads = argc > 4 ? std::stoi(argv[4]) : 0;
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  auto t = Clock::now();
  const mesh::Mesh A = mesh::read_mesh(argv[1]), B = mesh::read_mesh(argv[2]);
  const double read = since(t);
  std::printf("A %zu tetrahedra, B %zu; variants %s; threads %s\n", A.tets.size(), B.tets.size(),
              mesh::variant_names(variants).c_str(), threads ? argv[4] : "all");
  for (int rep = 0; rep < 3; ++rep) {
    t = Clock::now();
    const mesh::Contacts<double> c = mesh::contacts(A, B, {variants, {}});
    const double total = since(t);
    std::printf("run %d: read %.3f s | boxes %.4f s, broadphase (CGAL) %.4f s -> %zu box pairs, "
                "exact decision %.4f s -> %zu intersecting, depth %.4f s | after reading %.4f s, "
                "%.0f intersecting pairs/s\n",
                rep, read, c.seconds_boxes, c.seconds_broadphase, c.box_pairs, c.seconds_decision,
                c.pairs.size(), c.seconds_depth, total, c.pairs.size() / total);
  }
  std::vector<std::size_t> ea(A.tets.size()), eb(B.tets.size());
  std::iota(ea.begin(), ea.end(), 0);
  std::iota(eb.begin(), eb.end(), 0);
  t = Clock::now();
  const std::size_t n = mesh::box_pairs(A, ea, &B, eb).size();
  std::printf("broadphase on the same boxes:\n  CGAL box_intersection_d (half-open)  %9zu pairs  %.4f s (boxes included)\n",
              n, since(t));
  fcl_run<fcl::DynamicAABBTreeCollisionManagerd>("DynamicAABBTreeCollisionManager", A, B);
  fcl_run<fcl::DynamicAABBTreeCollisionManager_Arrayd>("DynamicAABBTreeCollisionManager_Array", A, B);
  // SaPCollisionManager did not finish within 500 s on the 7·10^4-element balls: left out.
  return 0;
}
