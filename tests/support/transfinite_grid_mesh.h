// transfinite_grid_mesh.h — a structured tetrahedral mesh for tests: n^3 cubes of side h cut
// into six tetrahedra each the way Gmsh cuts a transfinite box (`Transfinite Volume` of a unit
// box, `gmsh -3`: every cube alike, three prisms' worth of tetrahedra, no main diagonal shared
// by the six, unlike kuhn_grid_mesh.h), moved by t: each coordinate i h + t_k, rounded once.
// Vertex (i, j, k) has index (i (n + 1) + j) (n + 1) + k.
#pragma once

#include <array>
#include <cstddef>

#include "pdd/mesh.h"

namespace pdd::test {

inline mesh::Mesh transfinite_grid(int n, double h, const Vec3d& t) {
  // The cube's six tetrahedra as Gmsh lists them, corners as steps (x, y, z) from the cube's
  // lowest corner (read from a Gmsh 4.8 mesh of the unit box, 8 cells a side).
  static const int kTets[6][4][3] = {{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, {1, 0, 0}},
                                     {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}, {1, 0, 1}},
                                     {{1, 0, 1}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}},
                                     {{0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}},
                                     {{1, 1, 0}, {0, 1, 0}, {1, 0, 1}, {0, 1, 1}},
                                     {{1, 1, 0}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  mesh::Mesh m;
  auto id = [n](int i, int j, int k) { return std::size_t((i * (n + 1) + j) * (n + 1) + k); };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) m.vertices.push_back({i * h + t[0], j * h + t[1], k * h + t[2]});
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& tet : kTets) {
          std::array<std::size_t, 4> e;
          for (int c = 0; c < 4; ++c) e[c] = id(i + tet[c][0], j + tet[c][1], k + tet[c][2]);
          m.tets.push_back(e);
        }
  return m;
}

}  // namespace pdd::test
