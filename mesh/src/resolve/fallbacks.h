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

bool translate_and_relax(Run& run, std::size_t budget);

bool resolve_bodies(Run& run);

}  // namespace pdd::mesh::detail
