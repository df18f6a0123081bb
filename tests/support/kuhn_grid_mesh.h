// kuhn_grid_mesh.h — a structured tetrahedral mesh for tests: a Kuhn grid of n^3 cubes of side h
// (six tetrahedra a cube around its diagonal), moved by t: each coordinate i h + t_k, rounded
// once. Vertex (i, j, k) has index (k (n + 1) + j) (n + 1) + i.
#pragma once

#include <array>
#include <cstddef>

#include "pdd/mesh.h"

namespace pdd::test {

inline mesh::Mesh kuhn_grid(int n, double h, const Vec3d& t) {
  mesh::Mesh m;
  auto id = [n](int i, int j, int k) { return std::size_t((k * (n + 1) + j) * (n + 1) + i); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.vertices.push_back({i * h + t[0], j * h + t[1], k * h + t[2]});
  const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& ax : axes) {
          int c[3] = {i, j, k};
          std::array<std::size_t, 4> tet{id(i, j, k), 0, 0, 0};
          for (int s = 0; s < 3; ++s) ++c[ax[s]], tet[s + 1] = id(c[0], c[1], c[2]);
          m.tets.push_back(tet);
        }
  return m;
}

}  // namespace pdd::test
