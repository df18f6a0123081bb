// tet_pair.h — the input of every engine: a named pair (A, B) of tetrahedra (definitions §1).
//
// A is the paper's T1 (vertices s0..s3), B is T2 (rest vertices r0..r3). Coordinates are
// IEEE-754 doubles exactly as read; the exact engine takes each double as the rational it
// denotes, the fast engine reads the same doubles. Plain data, no algorithms.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace pdd {

using Vec3d = std::array<double, 3>;
using TetVertices = std::array<Vec3d, 4>;  // vertices 0..3 of one tetrahedron

struct TetPair {
  std::string name;
  std::vector<std::string> tags;
  TetVertices A{};  // s0..s3
  TetVertices B{};  // r0..r3
};

}  // namespace pdd
