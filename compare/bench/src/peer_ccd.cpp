// peer_ccd.cpp — libccd's GJK+EPA (and, informational, MPR) on a pair of tetrahedra.
#include "pdd/compare/peer_ccd.h"

#include <ccd/ccd.h>
#include <ccd/vec3.h>

#include <cmath>
#include <limits>

namespace pdd::compare {
namespace {

// libccd support function: the vertex of the tetrahedron furthest along `dir` (first on ties).
void tet_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const TetVertices& T = *static_cast<const TetVertices*>(obj);
  int best = 0;
  double best_dot = T[0][0] * dir->v[0] + T[0][1] * dir->v[1] + T[0][2] * dir->v[2];
  for (int i = 1; i < 4; ++i) {
    const double d = T[i][0] * dir->v[0] + T[i][1] * dir->v[1] + T[i][2] * dir->v[2];
    if (d > best_dot) best_dot = d, best = i;
  }
  ccdVec3Set(out, T[best][0], T[best][1], T[best][2]);
}

// Centroid, used by MPR only.
void tet_center(const void* obj, ccd_vec3_t* out) {
  const TetVertices& T = *static_cast<const TetVertices*>(obj);
  ccdVec3Set(out, (T[0][0] + T[1][0] + T[2][0] + T[3][0]) / 4,
             (T[0][1] + T[1][1] + T[2][1] + T[3][1]) / 4,
             (T[0][2] + T[1][2] + T[2][2] + T[3][2]) / 4);
}

PeerDepth interpret(int ret, double depth) {
  PeerDepth out;
  if (ret == -1) {
    out.status = PeerStatus::NotIntersecting;
    out.pd = 0.0;
  } else if (ret != 0 || !std::isfinite(depth) || depth < 0) {
    out.status = PeerStatus::Failed;
    out.pd = std::numeric_limits<double>::quiet_NaN();
  } else {
    out.status = PeerStatus::Intersecting;
    out.pd = depth;
  }
  return out;
}

}  // namespace

#ifndef PDD_CCD_VERSION
#define PDD_CCD_VERSION "unknown"
#endif
const char* ccd_version() { return PDD_CCD_VERSION; }

PeerDepth ccd_penetration_depth(const TetVertices& A, const TetVertices& B,
                                const CcdConfig& config) {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = tet_support;
  ccd.support2 = tet_support;
  ccd.max_iterations = config.max_iterations;
  ccd.epa_tolerance = config.epa_tolerance;
  ccd_real_t depth = 0;
  ccd_vec3_t dir, pos;
  const int ret = ccdGJKPenetration(&A, &B, &ccd, &depth, &dir, &pos);
  return interpret(ret, depth);
}

PeerDepth ccd_mpr_depth(const TetVertices& A, const TetVertices& B, double mpr_tolerance) {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = tet_support;
  ccd.support2 = tet_support;
  ccd.center1 = tet_center;
  ccd.center2 = tet_center;
  ccd.mpr_tolerance = mpr_tolerance;
  ccd_real_t depth = 0;
  ccd_vec3_t dir, pos;
  const int ret = ccdMPRPenetration(&A, &B, &ccd, &depth, &dir, &pos);
  return interpret(ret, depth);
}

}  // namespace pdd::compare
