#include "pdd/reference/candidate_directions.h"

namespace pdd::reference {
namespace {

// Unnormalised normal of the face opposite `opposite`, pointing out of `tet`.
Vector outward_face_normal(const ExactTet& tet, int opposite) {
  const auto& f = kFace[opposite];  // pdd/tet_tables.h
  Vector n = CGAL::cross_product(tet[f[1]] - tet[f[0]], tet[f[2]] - tet[f[0]]);
  if (n * (tet[opposite] - tet[f[0]]) > 0) n = -n;  // the opposite vertex lies inside
  return n;
}

CandidateDirection face_candidate(const DirectionLabel& label, const Vector& n, int opposite,
                                  bool face_of_A) {
  CandidateDirection c{label, n, {}, {}, std::nullopt};
  auto& constrained = face_of_A ? c.constrained_A : c.constrained_B;
  for (int i = 0; i < 4; ++i) constrained[i] = (i != opposite);
  return c;
}

// definitions §3 edge-pair normal before orientation; the zero vector for colinear edges.
Vector edge_pair_normal(const ExactPair& p, int a, int b, EdgePairKind& kind) {
  const Point& su = p.A[kEdges[a][0]];
  const Vector e = p.A[kEdges[a][1]] - su;
  const Vector f = p.B[kEdges[b][1]] - p.B[kEdges[b][0]];
  Vector n = CGAL::cross_product(f, e);
  kind = EdgePairKind::Generic;
  if (n != CGAL::NULL_VECTOR) return n;
  const Vector w = p.B[kEdges[b][0]] - su;
  n = (e * e) * w - (w * e) * e;  // (e.e) times the definitions' w - (w.e / e.e) e
  kind = (n == CGAL::NULL_VECTOR) ? EdgePairKind::Colinear : EdgePairKind::Parallel;
  return n;
}

void add_edge_pair(const ExactPair& p, int a, int b, std::vector<CandidateDirection>& out) {
  EdgePairKind kind;
  const Vector n = edge_pair_normal(p, a, b, kind);
  if (kind == EdgePairKind::Colinear) return;
  const int u = kEdges[a][0], v = kEdges[a][1];
  CandidateDirection c{DirectionLabel::ee(a, b), n, {}, {}, kind};
  for (int i = 0; i < 4; ++i) {
    c.constrained_A[i] = (i == u || i == v);
    c.constrained_B[i] = (i == kEdges[b][0] || i == kEdges[b][1]);
  }
  bool all_nonpositive = true, all_nonnegative = true;
  for (int k = 0; k < 4; ++k) {
    if (k == u || k == v) continue;
    const CGAL::Sign g = CGAL::sign(n * (p.A[k] - p.A[u]));
    all_nonpositive = all_nonpositive && g != CGAL::POSITIVE;
    all_nonnegative = all_nonnegative && g != CGAL::NEGATIVE;
  }
  if (all_nonpositive) {
    out.push_back(c);
  } else if (all_nonnegative) {
    c.n = -n;
    out.push_back(c);
  } else {  // undecidable: both orientations, ':+' first
    c.label.orientation = EdgeOrientation::Plus;
    out.push_back(c);
    c.label.orientation = EdgeOrientation::Minus;
    c.n = -n;
    out.push_back(c);
  }
}

}  // namespace

std::vector<CandidateDirection> candidate_directions(const ExactPair& p) {
  std::vector<CandidateDirection> out;
  out.reserve(8 + 2 * 36);  // 8 faces, at most two orientations of each of the 36 edge pairs
  for (int i = 0; i < 4; ++i)
    out.push_back(face_candidate(DirectionLabel::fv(i), outward_face_normal(p.A, i), i, true));
  for (int j = 0; j < 4; ++j)  // into B = against B's outward normal
    out.push_back(face_candidate(DirectionLabel::vf(j), -outward_face_normal(p.B, j), j, false));
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) add_edge_pair(p, a, b, out);
  return out;
}

std::vector<std::array<int, 2>> colinear_edge_pairs(const ExactPair& p) {
  std::vector<std::array<int, 2>> out;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      EdgePairKind kind;
      edge_pair_normal(p, a, b, kind);
      if (kind == EdgePairKind::Colinear) out.push_back({a, b});
    }
  return out;
}

}  // namespace pdd::reference
