// structured_cells.h — the tetrahedra of one cube of a structured grid, for tests: the cube with
// corner o and side h cut into six Kuhn tetrahedra (one per path along the axes) or into five
// (four corners and the middle one, in the even or odd orientation, so that neighbouring cubes
// share their faces' diagonals). Coordinates o + {0, h} per axis, each rounded once: edges
// along the axes are exactly parallel, the others parallel up to that rounding.
#pragma once

#include "pdd/pdd.h"

namespace pdd::test {

// Kuhn tetrahedron `perm` (0..5): o, then one step of h along each axis in the order of the
// permutation.
inline TetVertices kuhn_cell_tet(const Vec3d& o, double h, int perm) {
  static const int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  TetVertices t;
  int d[3] = {0, 0, 0};
  t[0] = o;
  for (int q = 0; q < 3; ++q) {
    d[kPerm[perm][q]] = 1;
    t[q + 1] = {o[0] + d[0] * h, o[1] + d[1] * h, o[2] + d[2] * h};
  }
  return t;
}

// Tetrahedron `which` (0..4; 4 the middle one) of the cube cut into five, corners numbered by
// bits (bit 0: x, bit 1: y, bit 2: z); `odd` the mirrored cut.
inline TetVertices five_cell_tet(const Vec3d& o, double h, int which, bool odd) {
  auto corner = [&](int c) -> Vec3d {
    return {o[0] + (c & 1) * h, o[1] + (c >> 1 & 1) * h, o[2] + (c >> 2 & 1) * h};
  };
  static const int kEven[5][4] = {{0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}, {1, 2, 4, 7}};
  static const int kOdd[5][4] = {{1, 0, 3, 5}, {2, 0, 3, 6}, {4, 0, 5, 6}, {7, 3, 5, 6}, {0, 3, 5, 6}};
  const int* c = odd ? kOdd[which] : kEven[which];
  return {corner(c[0]), corner(c[1]), corner(c[2]), corner(c[3])};
}

}  // namespace pdd::test
