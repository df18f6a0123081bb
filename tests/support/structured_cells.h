// structured_cells.h — the tetrahedra of one cube of a structured grid, for tests: the cube with
// corner o and side h cut into six Kuhn tetrahedra (one per path along the axes) or into five
// (four corners and the middle one, in the even or odd orientation, so that neighbouring cubes
// share their faces' diagonals). Coordinates o + {0, h} per axis, each rounded once: edges
// along the axes are exactly parallel, the others parallel up to that rounding.
#pragma once

#include <cmath>
#include <string>
#include <vector>

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

// The pairs of A x B whose interiors meet (fast rigid PD² > 0) and whose PD² `keep` accepts, up
// to `max_pairs`, named "<name> a<i> b<j>".
template <class Keep>
std::vector<TetPair> intersecting_pairs(const std::vector<TetVertices>& A, const std::vector<TetVertices>& B,
                                        const std::string& name, int max_pairs, Keep keep) {
  std::vector<TetPair> out;
  for (std::size_t a = 0; a < A.size(); ++a)
    for (std::size_t b = 0; b < B.size() && int(out.size()) < max_pairs; ++b) {
      const fast::Depth d = fast::rigid_pd2(A[a], B[b]);
      if (d.status != fast::DepthStatus::Ok || !(d.pd2 > 0) || !keep(d.pd2)) continue;
      TetPair p;
      p.name = name + " a" + std::to_string(a) + " b" + std::to_string(b);
      p.A = A[a], p.B = B[b];
      out.push_back(p);
    }
  return out;
}

// The Kuhn tetrahedra of an n^3 block of cubes of side h (A) and the same moved by `shift` (B:
// each coordinate of A's plus the shift's, rounded once), in the same order.
inline void kuhn_block_and_moved_copy(int n, double h, const Vec3d& shift, std::vector<TetVertices>& A,
                                      std::vector<TetVertices>& B) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (int perm = 0; perm < 6; ++perm) {
          A.push_back(kuhn_cell_tet({i * h, j * h, k * h}, h, perm));
          TetVertices b = A.back();
          for (auto& v : b)
            for (int c = 0; c < 3; ++c) v[c] += shift[c];
          B.push_back(b);
        }
}

// Contacts made by rounding: the Kuhn tetrahedra of an n^3 grid of cubes of side h = 1/8
// against those of the same grid shifted by h/10 along (1, 1, 1) (each coordinate i h + h/10
// rounded once). In exact arithmetic the shift lies in the planes x - y = c, y - z = c of the
// cells' diagonal faces, so such faces of the two grids coincide; once rounded they are ~1e-17
// apart, and the element pairs whose interiors meet only through that rounding (rigid PD² below
// 1e-20 here) are what this returns, up to `max_pairs` of them: no double value of theirs has
// a correct digit.
inline std::vector<TetPair> rounding_contact_pairs(int n, int max_pairs) {
  const double h = 0.125, s = h / 10;
  std::vector<TetVertices> A, B;
  kuhn_block_and_moved_copy(n, h, {s, s, s}, A, B);
  return intersecting_pairs(A, B, "rounding", max_pairs, [](double pd2) { return pd2 < 1e-20; });
}

// A vertex on an edge by rounding: the Kuhn tetrahedra of the n^3 cubes from cube (first, first,
// first) of a grid of decimal cells (h = 0.1, coordinates i h rounded once) and those of the same grid moved a quarter cell along (1, 1, 1)
// (each coordinate plus h / 4, rounded once). The shift runs along the cells' diagonals
// (h, h, h), so a vertex of one grid lies on a diagonal edge of the other a quarter along it, up
// to rounding. The element pairs whose interiors meet only through rounding (rigid PD² below
// 1e-20) with such a vertex (within 1e-12 of an edge's line, strictly between its ends), up to
// `max_pairs`.
inline std::vector<TetPair> vertex_on_edge_rounding_pairs(int first, int n, int max_pairs) {
  const double h = 0.1;
  std::vector<TetVertices> A, B;
  for (int i = first; i < first + n; ++i)
    for (int j = first; j < first + n; ++j)
      for (int k = first; k < first + n; ++k)
        for (int perm = 0; perm < 6; ++perm) {
          A.push_back(kuhn_cell_tet({i * h, j * h, k * h}, h, perm));
          TetVertices b = A.back();
          for (auto& v : b)
            for (int c = 0; c < 3; ++c) v[c] += h / 4;
          B.push_back(b);
        }
  auto on_edge = [](const TetVertices& E, const TetVertices& W) {
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        for (const Vec3d& w : W) {
          double e[3], d[3], ee = 0, de = 0;
          for (int c = 0; c < 3; ++c) e[c] = E[j][c] - E[i][c], d[c] = w[c] - E[i][c], ee += e[c] * e[c], de += d[c] * e[c];
          const double t = de / ee;
          double off = 0;
          for (int c = 0; c < 3; ++c) off += (d[c] - t * e[c]) * (d[c] - t * e[c]);
          if (t > 1e-6 && t < 1 - 1e-6 && off < 1e-24) return true;
        }
    return false;
  };
  std::vector<TetPair> out;
  for (const TetPair& p : intersecting_pairs(A, B, "vertex on edge by rounding", 1 << 30,
                                             [](double pd2) { return pd2 < 1e-20; }))
    if (int(out.size()) < max_pairs && (on_edge(p.A, p.B) || on_edge(p.B, p.A))) out.push_back(p);
  return out;
}

// Contacts made by rounding on the diagonal planes of stacked blocks: the Kuhn tetrahedra of an
// n^3 block of cubes of side h = 1/6 and those of the same block moved by (h/10, h/10, n h -
// h/3) (each coordinate rounded once from A's): a third of a cell deep along z, and moved
// across along x and y alike, so that the cells' diagonal faces x - y = c of the two blocks
// coincide up to rounding. The element pairs whose interiors meet only through that rounding
// (rigid PD² below 1e-20), up to `max_pairs`: an edge or a vertex of one on a face or an edge of
// the other, the minimiser of definitions §9 where pieces meet.
inline std::vector<TetPair> diagonal_stack_rounding_pairs(int n, int max_pairs) {
  const double h = 1.0 / 6, s = h / 10;
  std::vector<TetVertices> A, B;
  kuhn_block_and_moved_copy(n, h, {s, s, n * h - h / 3}, A, B);
  return intersecting_pairs(A, B, "diagonal stack by rounding", max_pairs, [](double pd2) { return pd2 < 1e-20; });
}

// A resting contact of structured blocks: the Kuhn tetrahedra of an n x n x 1 layer of cubes
// of side h = 1/8 and those of the same layer moved by (0.37 h, 0.21 h, h - depth), B's bottom
// `depth` below A's top; the element pairs whose interiors meet, up to `max_pairs`. A
// simulator's resting contact between two blocks: faces exactly parallel, the candidates of
// the contact's direction tied exactly, every value ~depth^2.
inline std::vector<TetPair> resting_contact_pairs(int n, double depth, int max_pairs) {
  const double h = 0.125;
  const Vec3d shift = {0.37 * h, 0.21 * h, h - depth};
  std::vector<TetVertices> A, B;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int perm = 0; perm < 6; ++perm) {
        A.push_back(kuhn_cell_tet({i * h, j * h, 0.0}, h, perm));
        B.push_back(kuhn_cell_tet({i * h + shift[0], j * h + shift[1], shift[2]}, h, perm));
      }
  return intersecting_pairs(A, B, "resting", max_pairs, [](double) { return true; });
}

// Blocks resting on each other's columns: the Kuhn tetrahedra of an n x n x 1 layer of decimal
// cells (h = 0.1, coordinates (i + v) h each rounded once, its top 0.1) and those of the same
// layer moved up by h - depth, its columns exactly over A's (the same x and y coordinates).
// Every contact is a face, an edge or a vertex of B's bottom on the same one of A's top, and a
// vertex of one on the line of a vertical edge of the other makes three active vertices nearly
// (or exactly) collinear: pieces with a second eigenvalue ~depth^2 beside a structural 0. The
// element pairs whose interiors meet, up to `max_pairs`.
inline void column_resting_blocks(int n, double depth, std::vector<TetVertices>& A, std::vector<TetVertices>& B) {
  const double h = 0.1;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int perm = 0; perm < 6; ++perm) {
        TetVertices a = kuhn_cell_tet({0, 0, 0}, 1.0, perm), b = a;
        for (int v = 0; v < 4; ++v) {
          a[v] = {(i + a[v][0]) * h, (j + a[v][1]) * h, a[v][2] * h};
          b[v] = {(i + b[v][0]) * h, (j + b[v][1]) * h, h - depth + b[v][2] * h};
        }
        A.push_back(a), B.push_back(b);
      }
}
inline std::vector<TetPair> column_resting_pairs(int n, double depth, int max_pairs) {
  std::vector<TetVertices> A, B;
  column_resting_blocks(n, depth, A, B);
  return intersecting_pairs(A, B, "on columns", max_pairs, [](double) { return true; });
}

// The same blocks turned together by 0.3 rad about (1, 2, 3) through (n h / 2, n h / 2, h)
// (each coordinate rounded once): the same resting contact with no face along a coordinate
// plane, B's bottom edges now translates of A's top edges only up to a rounding. The pairs
// whose PD^2 lies above 1e-30 (the resting contacts, ~1e-19; the turn's rounding also makes
// contacts between neighbouring columns, ~1e-33), up to `max_pairs`.
// x turned by 0.3 rad about the axis (1, 2, 3) through o (Rodrigues' rotation, in doubles).
inline Vec3d turned_about_123(const Vec3d& x, const Vec3d& o) {
  const double c = std::cos(0.3), s = std::sin(0.3), w = 1 / std::sqrt(14.0);
  const double k[3] = {w, 2 * w, 3 * w};
  double R[3][3];
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q) R[r][q] = (r == q ? c : 0) + (1 - c) * k[r] * k[q];
  R[0][1] -= s * k[2], R[0][2] += s * k[1], R[1][0] += s * k[2];
  R[1][2] -= s * k[0], R[2][0] -= s * k[1], R[2][1] += s * k[0];
  const double d[3] = {x[0] - o[0], x[1] - o[1], x[2] - o[2]};
  Vec3d y;
  for (int r = 0; r < 3; ++r) y[r] = o[r] + R[r][0] * d[0] + R[r][1] * d[1] + R[r][2] * d[2];
  return y;
}
inline std::vector<TetPair> turned_column_resting_pairs(int n, double depth, int max_pairs) {
  const double h = 0.1;
  std::vector<TetVertices> A, B;
  column_resting_blocks(n, depth, A, B);
  for (std::vector<TetVertices>* side : {&A, &B})
    for (TetVertices& t : *side)
      for (Vec3d& x : t) x = turned_about_123(x, {n * h / 2, n * h / 2, h});
  return intersecting_pairs(A, B, "turned on columns", max_pairs, [](double pd2) { return pd2 > 1e-30; });
}

// The same with cubes cut into five, the cuts alternating across the contact (A's cube (i, j)
// cut odd where i + j is, B's the other way): a vertex of B's bottom rests on a vertex of A's
// top, or an edge on the collinear edge, and the overlap is least along two to four facet
// normals of A - B through that vertex at once (the minimisers of definitions §9 tied or ~1e-8
// apart, on either side of the vertical).
inline void five_column_resting_blocks(int n, double depth, std::vector<TetVertices>& A, std::vector<TetVertices>& B) {
  const double h = 0.1;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int c = 0; c < 5; ++c) {
        TetVertices a = five_cell_tet({0, 0, 0}, 1.0, c, (i + j) % 2 == 1);
        TetVertices b = five_cell_tet({0, 0, 0}, 1.0, c, (i + j) % 2 == 0);
        for (int v = 0; v < 4; ++v) {
          a[v] = {(i + a[v][0]) * h, (j + a[v][1]) * h, a[v][2] * h};
          b[v] = {(i + b[v][0]) * h, (j + b[v][1]) * h, h - depth + b[v][2] * h};
        }
        A.push_back(a), B.push_back(b);
      }
}
inline std::vector<TetPair> five_column_resting_pairs(int n, double depth, int max_pairs) {
  std::vector<TetVertices> A, B;
  five_column_resting_blocks(n, depth, A, B);
  return intersecting_pairs(A, B, "five alternating on columns", max_pairs, [](double) { return true; });
}
// The same turned together as turned_column_resting_pairs turns the Kuhn blocks (the pairs
// whose PD^2 lies above 1e-30: the resting contacts).
inline std::vector<TetPair> turned_five_column_resting_pairs(int n, double depth, int max_pairs) {
  std::vector<TetVertices> A, B;
  five_column_resting_blocks(n, depth, A, B);
  for (std::vector<TetVertices>* side : {&A, &B})
    for (TetVertices& t : *side)
      for (Vec3d& x : t) x = turned_about_123(x, {n * 0.1 / 2, n * 0.1 / 2, 0.1});
  return intersecting_pairs(A, B, "five turned on columns", max_pairs, [](double pd2) { return pd2 > 1e-30; });
}

// Cells that coincide up to rounding: the Kuhn tetrahedra of an n x n x 1 layer of cubes of
// the decimal side h = 0.1 at height index 5 (vertex coordinates (i + v) h, each rounded once)
// against those of the same grid one cell up, its layer 4 (coordinates h + (i + v) h): 6 h
// rounds to 0.6000000000000001 and h + 5 h to 0.6, so each cube of B lies on a cube of A up to a
// rounding of its top. Its six tetrahedra overlap A's six deeply, tied along several
// directions, and touch the neighbouring cubes' through the rounding. The element pairs whose
// interiors meet, up to `max_pairs`.
inline std::vector<TetPair> coincident_cell_pairs(int n, int max_pairs) {
  const double h = 0.1;
  std::vector<TetVertices> A, B;
  auto layer = [h, n](double oz, int k, std::vector<TetVertices>& out) {
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int perm = 0; perm < 6; ++perm) {
          TetVertices t = kuhn_cell_tet({0, 0, 0}, 1.0, perm);
          const int c[3] = {i, j, k};
          for (auto& v : t)
            for (int a = 0; a < 3; ++a) v[a] = (a == 2 ? oz : 0.0) + (c[a] + v[a]) * h;
          out.push_back(t);
        }
  };
  layer(0.0, 5, A);
  layer(h, 4, B);
  return intersecting_pairs(A, B, "coincident", max_pairs, [](double) { return true; });
}

// Blocks stacked by rounding, as users place them: the Kuhn tetrahedra of an n x n x 3 block of
// decimal cells (coordinates c h, h = 0.1, each rounded once: its top 3 h = 0.30000000000000004)
// and those of an n x n x 1 block set on it at 0.3, moved across by (0.37 h, 0.21 h) (its
// coordinates 0.3 + c h and c h + 0.037 ...); B's bottom lies ~5.6e-17 below A's top. The
// element pairs whose interiors meet only through that rounding (rigid PD² below 1e-30), up
// to `max_pairs`: every value ~1e-34, the minimiser of definitions §9 tilted ~1e-16 off the
// axis.
inline std::vector<TetPair> rounding_stack_pairs(int n, int max_pairs) {
  const double h = 0.1;
  std::vector<TetVertices> A, B;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int perm = 0; perm < 6; ++perm) {
        const TetVertices t = kuhn_cell_tet({0, 0, 0}, 1.0, perm);
        TetVertices a = t, b = t;
        for (int v = 0; v < 4; ++v) {
          a[v] = {(i + t[v][0]) * h, (j + t[v][1]) * h, (2 + t[v][2]) * h};
          b[v] = {(i + t[v][0]) * h + 0.037, (j + t[v][1]) * h + 0.021, 0.3 + t[v][2] * h};
        }
        A.push_back(a), B.push_back(b);
      }
  return intersecting_pairs(A, B, "stacked by rounding", max_pairs, [](double pd2) { return pd2 < 1e-30; });
}

// A's cells (n x n columns at height index 2, top 3 h = 0.30000000000000004) and B's (bottom at
// 0.3 + c h), from cell(i, j, c, b): cell c of column (i, j) in unit coordinates, B's when b.
template <class Cell>
std::vector<TetPair> column_rounding_blocks(int n, int cells, Cell cell, const std::string& name, int max_pairs) {
  const double h = 0.1;
  std::vector<TetVertices> A, B;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int c = 0; c < cells; ++c) {
        const TetVertices ta = cell(i, j, c, false), tb = cell(i, j, c, true);
        TetVertices a = ta, b = tb;
        for (int v = 0; v < 4; ++v) {
          a[v] = {(i + ta[v][0]) * h, (j + ta[v][1]) * h, (2 + ta[v][2]) * h};
          b[v] = {(i + tb[v][0]) * h, (j + tb[v][1]) * h, 0.3 + tb[v][2] * h};
        }
        A.push_back(a), B.push_back(b);
      }
  return intersecting_pairs(A, B, name, max_pairs, [](double) { return true; });
}

// Blocks stacked by rounding on each other's columns, as two copies of one mesh are set on each
// other: the tetrahedra of an n x n x 3 block of decimal cells cut into five (coordinates c h,
// h = 0.1, each rounded once: its top 3 h = 0.30000000000000004) and those of an n x n x 1
// block of the same cells set on it at 0.3 (coordinates 0.3 + c h, the same x and y), each cell
// of B cut as the cell of A below it (the cuts alternate with i + j + k, and A's top layer k = 2
// has the parity of B's bottom layer k = 0, as for a copy of one mesh). Every contact is a face,
// an edge or a vertex of B's bottom on the same one of A's top, ~5.6e-17 deep; the minimisers
// of definitions §9 lie where several pieces meet (a vertex on a vertex: the edge of the
// separating cone). The element pairs whose interiors meet, up to `max_pairs`.
// With `alternate`, B's cubes are cut the other way (B's cube (i, j) as A's (i + 1, j)): the cuts
// alternate across the contact, and a vertex of B's bottom rests on a vertex of A's top
// whose edges leave it the other way (lone_pair_certificate.h's contacts).
inline std::vector<TetPair> column_rounding_stack_pairs(int n, int max_pairs, bool alternate = false) {
  const auto cell = [alternate](int i, int j, int c, bool b) {
    return five_cell_tet({0, 0, 0}, 1.0, c, (i + j + (b && alternate)) % 2 == 1);
  };
  return column_rounding_blocks(n, 5, cell,
                                alternate ? "five alternating on columns by rounding" : "five on columns by rounding",
                                max_pairs);
}

// The same with Kuhn cells (six tetrahedra a cube, A's and B's cut alike). A vertex of B's bottom
// on a vertex of A's top with their edges leaving it on different sides makes a minimiser that
// moves one vertex of each (a tilted normal, value PD^2 / 32), an edge on an edge one with two
// of each.
inline std::vector<TetPair> kuhn_column_rounding_stack_pairs(int n, int max_pairs) {
  const auto cell = [](int, int, int c, bool) { return kuhn_cell_tet({0, 0, 0}, 1.0, c); };
  return column_rounding_blocks(n, 6, cell, "Kuhn on columns by rounding", max_pairs);
}

// Kuhn blocks placed up to a rounding and stacked a third of a cell deep, as a mesh generator
// leaves a grid (`pdd bench mesh`'s placed case): an n x n x n/2 block of cubes of side h = 1/8
// whose grid points' coordinates are moved by -2..2 ulps (the amount from the point's index and
// the axis), and the same block moved up by (n/2) h - h/3 (each coordinate rounded once). Faces
// and edges that meet across the two blocks' side walls are parallel and collinear up to those
// ulps: an edge resting on a collinear edge, a vertex of each on the other's edge. The element
// pairs whose interiors meet only through that rounding (rigid PD² below 1e-25), up to
// `max_pairs`.
inline std::vector<TetPair> placed_kuhn_stack_rounding_pairs(int n, int max_pairs) {
  const double h = 0.125;
  const int nz = n / 2;
  auto index = [&](int i, int j, int k) { return (i * (n + 1) + j) * (nz + 1) + k; };
  std::vector<Vec3d> V((n + 1) * (n + 1) * (nz + 1));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= nz; ++k) {
        const int v = index(i, j, k);
        const double x[3] = {i * h, j * h, k * h};
        for (int c = 0; c < 3; ++c) {
          double y = x[c];
          for (int u = (v * 7 + c * 3) % 5 - 2; y != 0 && u != 0; u += u > 0 ? -1 : 1)
            y = std::nextafter(y, u > 0 ? INFINITY : -INFINITY);
          V[v][c] = y;
        }
      }
  static const int kKuhn[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  const double up = nz * h - h / 3;
  std::vector<TetVertices> A, B;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < nz; ++k)
        for (const auto& t : kKuhn) {
          TetVertices a, b;
          for (int q = 0; q < 4; ++q) {
            const int c = t[q];
            a[q] = V[index(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1))];
            b[q] = {a[q][0], a[q][1], a[q][2] + up};
          }
          A.push_back(a), B.push_back(b);
        }
  return intersecting_pairs(A, B, "placed Kuhn stacked by rounding", max_pairs, [](double pd2) { return pd2 < 1e-25; });
}

}  // namespace pdd::test
