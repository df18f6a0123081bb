// prism_grid_mesh.h — a structured tetrahedral mesh for tests: nx x ny x nz cubes of side h, each
// cut by the vertical plane through its xy diagonal from corner 0 to corner 3 into two
// triangular prisms, each prism (bottom triangle a, b, c, top d, e, f) into the three
// tetrahedra (a, b, c, d), (b, c, d, e), (c, d, e, f); corner b of a cube at bit 0 x, bit 1 y,
// bit 2 z. This is scripts/mesher-survey.py's prism grid: neighbouring cubes cut their shared
// faces normal to y along crossing diagonals, so it is a tiling of the block (no two elements
// overlap) whose faces there are not shared, not a conforming mesh. Moved by t: each coordinate
// i h + t_k, rounded once. Vertex (i, j, k) has index (k (ny + 1) + j) (nx + 1) + i; every
// element positively oriented (its orientation decided in doubles: a determinant of size h^3
// against rounding errors of about 1e-16 h^3).
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include "pdd/mesh.h"

namespace pdd::test {

inline mesh::Mesh prism_grid(int nx, int ny, int nz, double h, const Vec3d& t) {
  mesh::Mesh m;
  auto id = [&](int i, int j, int k) { return std::size_t((k * (ny + 1) + j) * (nx + 1) + i); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.vertices.push_back({i * h + t[0], j * h + t[1], k * h + t[2]});
  const int prisms[2][6] = {{0, 1, 3, 4, 5, 7}, {0, 3, 2, 4, 7, 6}};
  const int cuts[3][4] = {{0, 1, 2, 3}, {1, 2, 3, 4}, {2, 3, 4, 5}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        std::size_t c[8];
        for (int b = 0; b < 8; ++b) c[b] = id(i + (b & 1), j + (b >> 1 & 1), k + (b >> 2 & 1));
        for (const auto& p : prisms)
          for (const auto& q : cuts) {
            std::array<std::size_t, 4> tet{c[p[q[0]]], c[p[q[1]]], c[p[q[2]]], c[p[q[3]]]};
            const Vec3d &x = m.vertices[tet[0]], &y = m.vertices[tet[1]], &z = m.vertices[tet[2]],
                        &w = m.vertices[tet[3]];
            const double u[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]}, v[3] = {z[0] - x[0], z[1] - x[1], z[2] - x[2]},
                         s[3] = {w[0] - x[0], w[1] - x[1], w[2] - x[2]};
            const double det = u[0] * (v[1] * s[2] - v[2] * s[1]) - u[1] * (v[0] * s[2] - v[2] * s[0]) +
                               u[2] * (v[0] * s[1] - v[1] * s[0]);
            if (det < 0) std::swap(tet[1], tet[2]);
            m.tets.push_back(tet);
          }
      }
  return m;
}

}  // namespace pdd::test
