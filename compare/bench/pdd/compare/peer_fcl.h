// peer_fcl.h — FCL (Debian libfcl-dev 0.7.0, double) as a peer for the rigid PD.
//
// Input : a pair (A, B) of tetrahedra (doubles, as given) and an FclConfig.
// Output: PeerDepth (peer_result.h): FCL's penetration depth (not squared) from the first
//         contact of fcl::collide, or "not intersecting" (no contact), or a failure.
//
// What FCL computes: each tetrahedron is an fcl::Convex<double> (its 4 vertices and 4
// triangular faces, counter-clockwise seen from outside), identity transforms;
// fcl::collide(A, I, B, I, CollisionRequest(num_max_contacts = 1, enable_contact = true)).
//   FclSolver::Indep  (gjk_solver_type = GST_INDEP; the one `pdd bench` judges): FCL's own
//                     GJK, then EPA on the Minkowski difference (FCL's port of Bullet's
//                     GJK/EPA, fcl/narrowphase/detail/convexity_based_algorithm/{gjk,epa}.h);
//                     the contact's penetration_depth is the EPA depth, i.e. the rigid PD of
//                     definitions §4 up to EPA's stopping rule. FCL 0.7 reports it NEGATED on this
//                     path (`depth = -epa.depth` in gjk_solver_indep-inl.h; observed −0.5 on
//                     a PD = 0.5 pair); we return its magnitude.
//   FclSolver::Libccd (GST_LIBCCD, FCL's default): FCL calls libccd's ccdMPRPenetration, whose
//                     depth is NOT the PD (an upper bound, see peer_ccd.h); informational only.
//
// Tolerances (explicit in FclConfig; FCL's defaults in brackets). fcl::collide copies
// request.gjk_tolerance [1e-6] into the solver:
//   Indep:  gjk_tolerance and epa_tolerance both = tol. EPA stops when the support value h
//           along the nearest face's normal exceeds that face's distance d by at most tol
//           (`wdist > tolerance` in epa-inl.h); d <= PD <= h, so in exact arithmetic
//               |PD_fcl − PD| <= tol   (absolute),
//           unless EPA ends on a resource limit (fixed by collide() at the solver's defaults:
//           gjk_max_iterations 128, epa_max_face_num 128, epa_max_vertex_num 64,
//           epa_max_iterations 255), or on an invalid hull; collide() does not expose EPA's
//           status, so such an end is indistinguishable from success. GJK's failure or "Valid"
//           (separated) verdict gives no contact: reported as NotIntersecting.
//           Measured (`pdd bench`, 10^4 paper pairs, seed 1): 16 intersecting pairs (PD up to
//           1.37) reported as not intersecting, 243 pairs with PD² over ours by more than 1%
//           (never under), at either tolerance; cause not diagnosed.
//   Libccd: collision_tolerance = tol, used as libccd's mpr_tolerance.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "pdd/compare/peer_result.h"
#include "pdd/tet_pair.h"

namespace pdd::compare {

enum class FclSolver { Indep, Libccd };

struct FclConfig {
  FclSolver solver = FclSolver::Indep;
  double gjk_tolerance = 1e-6;  // CollisionRequest's default
};

// FCL's version as compiled against (FCL_VERSION of fcl/config.h).
const char* fcl_version();

// One pair, shapes built on the fly (fcl::Convex construction included).
PeerDepth fcl_penetration_depth(const TetVertices& A, const TetVertices& B,
                                const FclConfig& config = {});

// Shapes built once for a whole set of pairs, so that timing measures fcl::collide alone
// (favourable to FCL: our own functions start from the raw vertices).
class FclPairs {
 public:
  explicit FclPairs(const std::vector<TetPair>& pairs);
  ~FclPairs();
  FclPairs(const FclPairs&) = delete;
  FclPairs& operator=(const FclPairs&) = delete;
  PeerDepth depth(std::size_t k, const FclConfig& config = {}) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pdd::compare
