// tet_tables.h — the definitions §3 tables of a tetrahedron's faces and edges, for both engines
// (plain data, no arithmetic).
//
//   kEdges[k]   edge k joins vertices kEdges[k][0] < kEdges[k][1]   (the order of EE:a:b labels)
//   kFace[i]    the face opposite vertex i, its vertices in increasing order (FV:i, VF:j)
//   kOffEdge[k] the two vertices not on edge k, in increasing order
//   EdgePairKind  how an edge pair resolves (definitions §3): Generic (e_a x e_b != 0: one direction),
//                 Parallel (e_a x e_b = 0, the edges' lines distinct: the direction is the
//                 common perpendicular), Colinear (one line: no direction).
#pragma once

#include <array>

namespace pdd {

inline constexpr std::array<std::array<int, 2>, 6> kEdges = {
    {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

inline constexpr std::array<std::array<int, 3>, 4> kFace = {
    {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}};

inline constexpr std::array<std::array<int, 2>, 6> kOffEdge = {
    {{2, 3}, {1, 3}, {1, 2}, {0, 3}, {0, 2}, {0, 1}}};

enum class EdgePairKind { Generic, Parallel, Colinear };

}  // namespace pdd
