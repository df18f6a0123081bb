// quick_candidates.cpp — the hot path's candidate list (no labels emitted, no exact
// fallback: it declines instead). See quick_candidates.h.
#include "kernel/quick_candidates.h"

#include <cmath>

#include "certification/filter_bounds.h"
#include "kernel/direction_geometry.h"
#include "kernel/superset_kernel.h"

namespace pdd::fast {

using namespace detail;

namespace {

bool lanes_clear(const EdgeLanes& L) {
  double any = 0.0;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) any += L.unclear[kLaneStride * a + b];
  return any == 0.0;
}

}  // namespace

// The canonical list of the lanes (Builder::edge_pairs without labels): delta² and source.
void quick_edge_list(QuickCandidates& q) {
  const EdgeLanes& L = q.edges;
  int k = 8;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const int i = kLaneStride * a + b;
      const bool pos1 = L.g1[i] > 0.0, pos2 = L.g2[i] > 0.0;
      const bool flip = pos1 & pos2, undecidable = pos1 ^ pos2;
      q.delta_sq[k] = L.first[i];
      q.delta_sq[k + 1] = L.d2minus[i];
      q.depth[k] = flip ? L.dminus[i] : L.dplus[i];
      q.depth[k + 1] = L.dminus[i];
      q.nn[k] = q.nn[k + 1] = L.nn[i];
      q.src[k] = std::int16_t(8 + 2 * i + flip);
      q.src[k + 1] = std::int16_t(8 + 2 * i + 1);
      k += 1 + undecidable;
    }
  q.count = k;
}

// The arithmetic is the superset kernel's (superset_kernel.h), which also writes the lanes.
bool quick_lanes(const TetVertices& A, const TetVertices& B, QuickCandidates& q, bool all_faces,
                 SupersetLanes* kernel) {
  q.count = 0;
  q.faces_filled = false;
  q.A = &A;
  q.B = &B;
  SupersetLanes own;
  SupersetLanes& K = kernel ? *kernel : own;
  superset_kernel(A, B, K, &q.edges);
  if (!(K.finite == 0.0)) return false;
  const FilterBounds fb = filter_bounds_of_extent(K.extent);
  if (!(std::fabs(K.det[3]) > fb.deg3) || !(std::fabs(K.det[7]) > fb.deg3)) return false;
  q.tie_kappa = K.kappa;
  q.fb = fb;
  // All eight drafts first, then the candidates: finish_face's wide loads right after
  // face_draft's narrow stores of the same Draft cannot be store-forwarded (a stall per
  // load); eight calls later those stores have reached the cache.
  Draft drafts[8];
  for (int f = 0; f < 8; ++f) face_draft(K, f, drafts[f]);
  bool certain = true;
  for (int f = 0; f < 8; ++f) {
    DirectionGeometry& g = q.faces[f];
    finish_face(drafts[f], g);
    if (!(g.depth > fb.deg3)) {
      if (!all_faces) return false;
      certain = false;
    }
    q.delta_sq[f] = g.depth * g.depth / g.nn;
    q.depth[f] = g.depth;
    q.nn[f] = g.nn;
    q.src[f] = std::int16_t(f);
  }
  q.faces_filled = all_faces;
  if (!certain) return false;
  q.count = 8;
  return lanes_clear(q.edges);
}

bool quick_candidates(const TetVertices& A, const TetVertices& B, QuickCandidates& q) {
  if (!quick_lanes(A, B, q)) return false;
  quick_edge_list(q);
  return true;
}

LabelCode entry_label_code(const QuickCandidates& q, int src) {
  if (src < 8)
    return src < 4 ? pack_label(ContactKind::FV, src, 0, EdgeOrientation::Decided)
                   : pack_label(ContactKind::VF, src - 4, 0, EdgeOrientation::Decided);
  const int i = (src - 8) / 2;
  const bool minus = (src - 8) % 2;
  const bool undecidable = (q.edges.g1[i] > 0.0) != (q.edges.g2[i] > 0.0);
  return pack_label(ContactKind::EE, i / kLaneStride, i % kLaneStride,
                    !undecidable ? EdgeOrientation::Decided
                    : minus      ? EdgeOrientation::Minus
                                 : EdgeOrientation::Plus);
}

Candidate entry_candidate(const QuickCandidates& q, int src) {
  Candidate c;
  c.label = unpack_label(entry_label_code(q, src));
  if (src < 8) {
    static_cast<DirectionGeometry&>(c) = q.faces[src];
    return c;
  }
  lane_candidate(q.edges, (src - 8) / 2, (src - 8) % 2 ? -1.0 : 1.0, c);
  return c;
}

}  // namespace pdd::fast
