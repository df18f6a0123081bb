// step_limit.h — the step limit of a round: moves one side by the steps proposed in its
// accumulators, keeping R2 and R4 (with a margin) on every element.
//
// Inputs:  the side at P_k (every valid element passing R2 and R4), per vertex a proposed step
//          D_v = acc_v / weight_v (weight 0: no step), the overshoot omega.
// Outputs: P_{k+1,v} = P_{k,v} + t_v D_v, t_v = omega first; every element with a moved vertex
//          that is inverted or flat (exact orientation) or fails R4 with the margin
//          (usable_with_margin, doubles) halves t of its moved vertices, and after kMaxHalvings
//          halvings sets them to 0, until every element passes. Clears the accumulators.
// Why it ends with every element passing: an element with all its t at 0 has its vertices bit
// for bit at P_k (P + 0 * D == P for finite D), where it passed; each pass lowers some t, and
// after kMaxHalvings passes every offending vertex is at 0.
#pragma once

#include <array>
#include <cstddef>

#include "state.h"

namespace pdd::mesh::detail {

// How a vertex combines the target displacements of its pairs in the per-pair rounds.
enum class Combine {
  Longest,       // the longest target (weight 1)
  WeightedMean,  // the mean weighted by the element's rest volume
};

// Adds element e's share d of a pair's move to its free vertices' accumulators.
void accumulate(Side& s, std::size_t e, const std::array<Vec3d, 4>& d, Combine combine);

// Proposes the step d for free vertex v (replacing any other).
inline void propose(Side& s, std::size_t v, const Vec3d& d) {
  s.acc[v] = d;
  s.weight[v] = 1;
}

// The step limit (above): moves s by omega times its proposed steps.
void move_side(Side& s, double overshoot);

}  // namespace pdd::mesh::detail
