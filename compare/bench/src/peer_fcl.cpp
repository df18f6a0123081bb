// peer_fcl.cpp — fcl::collide with contacts on two fcl::Convex<double> tetrahedra.
#include "pdd/compare/peer_fcl.h"

#include <fcl/config.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/collision.h>

#include <cmath>
#include <limits>

namespace pdd::compare {
namespace {

using Vec = fcl::Vector3d;

// The 4 faces of tetrahedron (v0..v3), each counter-clockwise seen from outside when the
// tetrahedron is positively oriented ((v1−v0)×(v2−v0).(v3−v0) > 0); reversed otherwise.
std::shared_ptr<const std::vector<int>> tet_faces(bool positive) {
  static const auto pos = std::make_shared<const std::vector<int>>(
      std::vector<int>{3, 0, 2, 1, 3, 0, 1, 3, 3, 0, 3, 2, 3, 1, 2, 3});
  static const auto neg = std::make_shared<const std::vector<int>>(
      std::vector<int>{3, 0, 1, 2, 3, 0, 3, 1, 3, 0, 2, 3, 3, 1, 3, 2});
  return positive ? pos : neg;
}

std::shared_ptr<fcl::Convexd> make_tet(const TetVertices& T) {
  auto v = std::make_shared<std::vector<Vec>>();
  v->reserve(4);
  for (const auto& p : T) v->emplace_back(p[0], p[1], p[2]);
  const Vec a = (*v)[1] - (*v)[0], b = (*v)[2] - (*v)[0], c = (*v)[3] - (*v)[0];
  const bool positive = a.cross(b).dot(c) > 0;
  return std::make_shared<fcl::Convexd>(std::shared_ptr<const std::vector<Vec>>(v), 4,
                                        tet_faces(positive));
}

PeerDepth collide(const fcl::Convexd& a, const fcl::Convexd& b, const FclConfig& config) {
  fcl::CollisionRequestd request(1, true);
  request.gjk_solver_type =
      config.solver == FclSolver::Indep ? fcl::GST_INDEP : fcl::GST_LIBCCD;
  request.gjk_tolerance = config.gjk_tolerance;
  fcl::CollisionResultd result;
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  const std::size_t n = fcl::collide(&a, I, &b, I, request, result);
  PeerDepth out;
  if (n == 0 || result.numContacts() == 0) {
    out.status = PeerStatus::NotIntersecting;
    out.pd = 0.0;
    return out;
  }
  const double d = result.getContact(0).penetration_depth;
  if (!std::isfinite(d)) {
    out.status = PeerStatus::Failed;
    out.pd = std::numeric_limits<double>::quiet_NaN();
    return out;
  }
  out.status = PeerStatus::Intersecting;
  out.pd = std::abs(d);  // GST_INDEP reports −depth for Convex pairs in FCL 0.7 (header)
  return out;
}

}  // namespace

const char* fcl_version() { return FCL_VERSION; }

PeerDepth fcl_penetration_depth(const TetVertices& A, const TetVertices& B,
                                const FclConfig& config) {
  const auto a = make_tet(A), b = make_tet(B);
  return collide(*a, *b, config);
}

struct FclPairs::Impl {
  std::vector<std::shared_ptr<fcl::Convexd>> a, b;
};

FclPairs::FclPairs(const std::vector<TetPair>& pairs) : impl_(std::make_unique<Impl>()) {
  impl_->a.reserve(pairs.size());
  impl_->b.reserve(pairs.size());
  for (const auto& p : pairs) {
    impl_->a.push_back(make_tet(p.A));
    impl_->b.push_back(make_tet(p.B));
  }
}

FclPairs::~FclPairs() = default;


PeerDepth FclPairs::depth(std::size_t k, const FclConfig& config) const {
  return collide(*impl_->a[k], *impl_->b[k], config);
}

}  // namespace pdd::compare
