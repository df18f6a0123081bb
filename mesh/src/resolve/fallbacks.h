// fallbacks.h — what resolve does when its rounds stall (resolve.h, "Fallbacks").
//
// translate_and_relax (two meshes; deep overlaps): the cheapest separating rigid translation
//   over a few candidate directions (the centroid line, the mean per-pair pdd2 normal, the
//   principal axes of the contact region; each bisected with the exact contact stage, the
//   shortest kept; a rigid translation keeps R2 and R4 up to rounding, which is checked), then
//   walked back towards the rest pose by steps of gamma (kFirstGamma down to kLastGamma) of
//   every free vertex's way back, each followed by a few projective-dynamics rounds (which keep
//   R2 and R4; two meshes' rounds that stop on kFewPairs pairs or fewer finished by up to
//   kFinishRounds per-pair rounds, rounds.h); a step that does not end resolved and cheaper is
//   undone. True when it ends resolved (R1 by the contact stage); false, positions unchanged,
//   when it does not apply (both meshes have fixed vertices, no separating translation found,
//   or the translated rest pose flips an element by rounding).
// rigid_rounds_from_rest (two meshes under the global or pdd2 variant whose first rounds, finished
//   per pair where they stopped on a few pairs, did not resolve them): the projective-dynamics
//   rounds again from the rest pose with the rigid variant's per-pair planes, within `budget`
//   rounds, finished per pair (the rigid variant's per-pair rounds) where they stop on kFewPairs
//   pairs or fewer (rounds.h), as the first rounds are. Where two meshes nearly coincide, each
//   pair's cheapest deformable plane can point any way, and rounds that push a few hundred pairs
//   back and forth do not recover (the Gmsh transfinite box of 8^3 cubes against its copy moved
//   (0.37, 0.21, 0.13) of a cell: 37,679 pairs at rest, ~440 from round 16 on; continued from there
//   with the rigid planes they stall too). From rest the rigid variant's planes, which neighbouring
//   pairs share (candidate directions: face normals and edge crossings), resolve it, cheaper than
//   the translation's walk (that box as tests/support/transfinite_grid_mesh.h rebuilds it: 44
//   rounds in all, cost 0.235, against the translation's 172 rounds and 0.329). True when resolved;
//   false otherwise, the positions wherever the rounds stopped and run.depth_scale as before (the
//   translation starts from rest, its gaps as without this attempt). Its rounds count against
//   max_rounds.
// resolve_bodies (self-contact of several bodies, the connected components by shared vertices):
//   when every intersecting pair at rest joins two different bodies and every connected group
//   of contacting bodies is a pair, each pair is cut out as two meshes and resolved from rest
//   as A x B (every fallback of two meshes included: the translation tries several directions).
//   A larger group (a chain, whose two meshes would be the outer bodies as one rigid whole
//   against the middle one, or three bodies meeting pairwise, which two colours cannot split),
//   or a pair that does not end resolved, makes the bodies spread instead: each cluster of
//   contacting bodies (connected component of the graph) moved rigidly, body k by t (c_k - c),
//   c_k its vertex centroid and c the cluster's (or that of its one body with fixed vertices,
//   which stays), t the smallest factor at which the contact stage (exact) finds the cluster
//   apart (bisected to kBisection), then walked back towards rest as translate_and_relax is
//   (a 2-colourable larger group goes to the two meshes when the spread does not apply).
//   True when it ended resolved (the caller's exact verdict on the whole mesh judges the
//   result); false, positions unchanged, when neither applies: a body meets itself, a cluster
//   holds two bodies with fixed vertices, two bodies in contact share their centroid, or no
//   factor separates.
#pragma once

#include <cstddef>

#include "state.h"

namespace pdd::mesh::detail {

bool rigid_rounds_from_rest(Run& run, std::size_t budget);

bool translate_and_relax(Run& run, std::size_t budget);

bool resolve_bodies(Run& run);

}  // namespace pdd::mesh::detail
