// local_step.h — the local step of a round: one intersecting element pair projected, in the
// object norm, onto the configurations in which a plane separates its two tetrahedra.
//
// Inputs:  the pair's tetrahedra A (element a of side sa) and B (element b of side sb) at the
//          current positions, which of their vertices are fixed, the variant.
// Outputs: solve_move: the variant's per-pair solution as displacements of the eight vertices,
//            all along the solution's unit normal u (A -> B), and its squared depth;
//          plane_targets (the projective-dynamics rounds): the plane u.x = c midway between q1_A
//            and q1_B (or along a patch's direction, patch_direction.h), opened by the gap
//            g = min(kPlaneGap (longest edge of the pair), the run's depth scale) (not below
//            finish_move's margin) and shifted past the fixed vertices of either side, as a
//            half-space for every free vertex on the
//            wrong side:  u.x <= c - g/2 (A's),  u.x >= c + g/2 (B's);
//          finish_move (the per-pair rounds): the fixed vertices' share of a move handed to the
//            other side and the two sides pushed mu = kMargin edge + kMarginUlp |x| apart.
// A pair whose per-pair solve fails (pdd2_global_error, a record error, no direction) falls back
// to pdd2's positions, then to the rigid translation along the rigid direction (or the centroid
// line when the rigid depth is not certified). Under the global variant, a contact far
// shallower than the pair's size (below about 1e-10 of it, where the fast engine's minimiser
// bounds pdd2_global instead of certifying it, or below 1e-12 of the extent by rigid_pd2:
// contacts made by rounding, nearly touching pairs) takes pdd2's positions at once: its
// pdd2_global would take the shallow certificate or an exact search, and its move is the plane
// gap either way (local_step.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "pdd/mesh.h"
#include "state.h"

namespace pdd::mesh::detail {

// One pair's local step: target displacements of its eight vertices, all along u (A -> B).
struct PairMove {
  std::array<Vec3d, 4> da{}, db{};
  Vec3d u{};
  double value = 0;  // the variant's squared depth used (ResolveRound::max_pd2)
  bool ok = false;
};

PairMove solve_move(const TetVertices& A, const TetVertices& B, ResolveVariant variant);
// The move from solve_pair's record (with rigid_pd2 first, for the shallow test): solve_move's
// where the minimiser (fast::global_minimiser, local_step.cpp) certifies the pair or declines it;
// where it bounds the pair, solve_move takes solve_move_by_record(A, B, ResolveVariant::Pdd2).
PairMove solve_move_by_record(const TetVertices& A, const TetVertices& B, ResolveVariant variant);

// A half-space n.x >= b that a vertex must reach (n of unit length), and the vertex it binds.
struct HalfSpace {
  Vec3d n{};
  double b = 0;
};
struct VertexTarget {
  std::size_t vertex = 0;
  HalfSpace h;
};

// The projective-dynamics local step of pair (ea of sa, eb of sb), solved as m (m.ok): appends
// the half-spaces of its free vertices to out_a / out_b; returns m.value (0: no finite plane).
// along: null, the plane of m (its normal, midway between q1_A and q1_B); else the unit *along
// (patch_direction.h), the plane then midway between the two tetrahedra's extents along it.
// depth_scale: the largest overlap the run's rounds have met (Run::depth_scale, overlap_along).
double plane_targets(const Side& sa, std::size_t ea, const Side& sb, std::size_t eb, const PairMove& m,
                     const Vec3d* along, double depth_scale, std::vector<VertexTarget>& out_a,
                     std::vector<VertexTarget>& out_b);

// The overlap of A and B along unit u: max_A u.a - min_B u.b.
double overlap_along(const TetVertices& A, const TetVertices& B, const Vec3d& u);

// The per-pair rounds' local step of pair (ea of sa, eb of sb): the variant's move with the fixed
// vertices' share moved to the other side and the margin mu added (m.ok must hold).
void finish_move(PairMove& m, const Side& sa, std::size_t ea, const Side& sb, std::size_t eb,
                 const TetVertices& A, const TetVertices& B);

}  // namespace pdd::mesh::detail
