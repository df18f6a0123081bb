// peer_ccd.h — libccd (Debian libccd-dev 2.1, double precision) as a peer for the rigid PD.
//
// Input : a pair (A, B) of tetrahedra (doubles, as given) and a CcdConfig.
// Output: PeerDepth (peer_result.h): libccd's penetration depth PD(A, B) (not squared) or
//         "not intersecting" or a failure.
//
// What libccd computes: ccdGJKPenetration, GJK on the Minkowski difference A ⊕ (−B) (support
// function: the vertex of the 4 maximising the dot product with the direction, for A; for B
// libccd queries the support along −d and subtracts), then EPA (expanding polytope) from the
// terminal simplex; depth = distance from the origin to the nearest element of the final
// polytope. That is the rigid PD of definitions §4 up to EPA's stopping rule.
// Why GJK+EPA and not ccdMPRPenetration: MPR (Minkowski portal refinement) follows the ray
// from an interior point of the difference (the difference of the centres) through the origin
// and returns the distance from the origin to the plane of the boundary facet that ray crosses:
// an upper bound of PD, equal only when that facet happens to be the nearest one. It is not PD. (FCL's default GST_LIBCCD solver uses exactly that MPR call; see peer_fcl.h.)
//
// Tolerances (all explicit in CcdConfig, libccd's CCD_INIT defaults in brackets):
//   epa_tolerance  [1e-4]  EPA stops expanding the nearest element (distance d from the origin,
//                  witness w, |w| = d) when the new support point v has v.w − d² < tol, i.e.
//                  h − d < tol/d with h = the support value along w/|w|; or when v lies within
//                  squared distance tol of that element. d <= PD <= h always (the polytope is
//                  inside the difference; h is a support value), so in exact arithmetic
//                      |PD_ccd − PD| <= max(tol/PD_ccd, sqrt(tol))       (the second term
//                  from the squared-distance test, bounding h − d for a face element).
//   max_iterations [2^64−1]  GJK iterations (EPA's loop in libccd 2.1 has no iteration cap;
//                  it ends because a tetrahedron pair's difference has at most 16 vertices).
//   first_dir      libccd's default (1, 0, 0).
// Measured (`pdd bench`, 10^4 paper pairs, seed 1): 253 pairs with PD² under ours by more than
// 1% (never over; down to ~1e-11 for a PD² of 0.059), at either tolerance: EPA stopping
// early, cause not diagnosed.
// libccd returns depth 0 with "intersecting" for a touching contact; we report that as
// Intersecting with pd = 0 (the caller compares with the exact PD, which is then 0).
#pragma once

#include "pdd/compare/peer_result.h"
#include "pdd/tet_pair.h"

namespace pdd::compare {

struct CcdConfig {
  double epa_tolerance = 1e-4;             // libccd default
  unsigned long max_iterations = ~0UL;     // libccd default (unbounded)
};

// libccd's version as found by CMake (libccd has no version macro).
const char* ccd_version();

PeerDepth ccd_penetration_depth(const TetVertices& A, const TetVertices& B,
                                const CcdConfig& config = {});

// The same through ccdMPRPenetration (informational row of `pdd bench` only: not PD, see
// above). mpr_tolerance is libccd's default 1e-4 unless given.
PeerDepth ccd_mpr_depth(const TetVertices& A, const TetVertices& B, double mpr_tolerance = 1e-4);

}  // namespace pdd::compare
