// patch_direction.h — one separating direction per contact patch where the pairs' own planes
// disagree (SPEC §11: "one consistent separating direction per contact patch").
//
// Inputs:  the run (two meshes), this round's intersecting pairs and their local steps (each
//          pair's unit normal u_k, A -> B, and squared depth v_k; local_step.h).
// Outputs: per pair, the direction its half-spaces are built along (plane_targets' `along`), or
//          nothing: the pair keeps its own plane.
// Method. Patches: the pairs joined when their elements share a vertex, on either side. A patch
//   whose pairs agree, |sum_k w_k u_k| >= kAgree sum_k w_k with w_k = sqrt(v_k), keeps them. One
//   that does not (neighbouring pairs push a vertex opposite ways: two blocks stacked, or a ball
//   pressed deep, whose elements each find it cheapest to leave sideways, so the rounds hold the
//   vertex where it is) is pushed along one direction: among the normals of its kCandidates
//   deepest pairs and both signs of the principal axes of its vertices, the u that minimises
//   sum_k c_k(u)^2, c_k(u) = max(0, max u.s - min u.r) the rigid clearance of pair k along u.
// Never turned back. Where a deep overlap is one patch whose pairs' planes point every way (two
//   blocks nearly coincident), several candidates separate it at about the same cost, and the
//   least one changes with every round's move; chosen afresh, it turned by up to 180 degrees
//   from one round to the next, undoing the last push, and the rounds never separated (Kuhn
//   blocks of 6^3 cubes half a cell apart in x and y: the translation fallback after ~190
//   rounds). So a patch whose vertices were pushed along u last round (the direction most of
//   them had) takes the least of the candidates within 45 degrees of u (kTurn: within 90, the
//   same blocks of 10^3 cubes still turned around in two rounds).
// Self-contact keeps every pair's own plane: a pair names its elements in index order, so its
//   normal's sign says nothing about the patch's sides.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "local_step.h"
#include "state.h"

namespace pdd::mesh::detail {

std::vector<std::optional<Vec3d>> patch_directions(Run& run, const std::vector<std::array<std::size_t, 2>>& pairs,
                                                   const std::vector<PairMove>& moves);

}  // namespace pdd::mesh::detail
