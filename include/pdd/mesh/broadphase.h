// mesh/broadphase.h — stage 2 of contacts() alone (contacts.h): the element pairs whose
// bounding boxes overlap. A building block, for tests and benchmarks.
//
// Inputs   meshes A and B and the elements of each to consider (indices), BroadphaseOptions
//          (defaults in the struct).
// Outputs  the box pairs (a, b), sorted by (a, b).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "pdd/mesh/mesh.h"

namespace pdd::mesh {

// Stage 2 alone over the given elements (indices into A and B; box_pairs_self: A with itself,
// a < b, vertex-sharing pairs kept unless options.drop_shared_vertex): the box pairs, sorted
// by (a, b).
//   prune     (two meshes) first drop the boxes that miss the other mesh's bounding box;
//   parallel  CGAL's parallel box_intersection_d (Parallel_tag, on TBB's threads);
//   drop_shared_vertex  (self) leave out the pairs whose elements share a vertex index.
// The pair set does not depend on `prune` and `parallel`.
struct BroadphaseOptions {
  bool prune = true;
  bool parallel = true;
  bool drop_shared_vertex = false;
};
std::vector<std::array<std::size_t, 2>> box_pairs(const Mesh& A, const std::vector<std::size_t>& ea,
                                                  const Mesh& B, const std::vector<std::size_t>& eb,
                                                  const BroadphaseOptions& options = {});
std::vector<std::array<std::size_t, 2>> box_pairs_self(const Mesh& A, const std::vector<std::size_t>& ea,
                                                       const BroadphaseOptions& options = {});

}  // namespace pdd::mesh
