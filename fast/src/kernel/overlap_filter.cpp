// overlap_filter.cpp — pdd::fast::overlap_filter and pdd::fast::interiors_intersect (pdd.h): the
// exact intersection decision of definitions §4 (touching is not intersecting), with a certified
// separating-axis filter in doubles first. Meant for the many mostly disjoint pairs of a mesh
// broadphase (mesh/), where rigid_pd2 would build the candidate list of every disjoint pair.
//
// Input:  tetrahedra A (s0..s3), B (r0..r3), raw doubles (no rescaling needed, see below).
// Output: overlap_filter: Disjoint / Intersecting when certain, Unknown otherwise;
//         interiors_intersect: the exact decision (false for a rejected pair, definitions §1).
//
// ---- Stage 1: the 8 face axes, scalar, stopping at the first that separates (most disjoint
// pairs of a broadphase are separated by a face plane; about 1/10 of the kernel's work).
// For face (i, j, k) of T with opposite vertex l, and the other tetrahedron O:
//   N = (T_j − T_i) × (T_k − T_i); heights relative to T_i: 0 for T_i, T_j, T_k (exactly),
//   hl = N.(T_l − T_i), h_m = N.(O_m − T_i);
//   separated along  N if  min_m h_m − max(0, hl) > E3,   along −N if  min(0, hl) − max_m h_m > E3.
// Each height is a triple product of differences (first-order error <= 48 u L³, filter_bounds.h);
// the difference of two heights adds one rounding of a value <= 12 L³: error <= 108 u L³ < E3.
// So a computed difference > E3 means the exact one is > 0: every vertex of one tetrahedron is
// strictly below every vertex of the other along N (or −N): disjoint. No orientation is needed
// (both signs of N are tried). Non-finite input: Unknown before anything else.
//
// ---- Stage 2: the superset kernel (superset_kernel.h), reused as is: no second SAT; where
// unresolved edge pairs (nearly parallel edges) spoil its minimum depth, those pairs bounded by
// near_parallel_bound.h (intersecting_without_unresolved below).
//
// interiors_intersect, for Unknown: the exact separating-axis decision (exact_sat.h: the 44
// axes in doubles, then floating-point expansions for the signs left open: no rationals), and
// only when that is out of the expansions' range the candidate set's exact depth signs. A pair
// with a touching face (stage 1: some face plane's computed gap within E3 of 0, the common case
// of aligned meshes, where faces and vertices lie exactly in each other's planes) has its face
// axes decided exactly first, before the kernel: most such pairs are separated by that plane.
#include "certification/filter_bounds.h"
#include "exact/exact_sat.h"
#include "kernel/candidate_directions.h"
#include "kernel/near_parallel_bound.h"
#include "kernel/power_scale.h"
#include "kernel/rigid_depth.h"
#include "kernel/superset_kernel.h"
#include "pdd/pdd.h"

#include <cmath>
#include <cstdint>

namespace pdd::fast {

namespace {

// Stage 1 (header), for the face planes of T against O: Separate when one certainly separates;
// Touching when none does but one's computed gap is within E3 of 0 (its test fails by <= E3:
// min_m h_m − max(0, hl) >= −E3, or the mirror), so that only exact signs can tell; else Open.
// The values it computed go to `hl` and `h` (exact_sat.h's FacePlaneValues, faces of T).
enum class FacePlanes { Separate, Touching, Open };
inline FacePlanes face_planes(const TetVertices& T, const TetVertices& O, double e3, double* hl_out,
                              double (*h_out)[4]) {
  static constexpr int kFace[4][4] = {{1, 2, 3, 0}, {0, 2, 3, 1}, {0, 1, 3, 2}, {0, 1, 2, 3}};
  bool touching = false;
  for (int i = 0; i < 4; ++i) {
    const auto& f = kFace[i];
    const Vec3d& p = T[f[0]];
    double u[3], v[3], w[3], n[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = T[f[1]][k] - p[k];
      v[k] = T[f[2]][k] - p[k];
      w[k] = T[f[3]][k] - p[k];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    const double hl = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
    hl_out[i] = hl;
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (int m = 0; m < 4; ++m) {
      const double h = n[0] * (O[m][0] - p[0]) + n[1] * (O[m][1] - p[1]) + n[2] * (O[m][2] - p[2]);
      h_out[i][m] = h;
      lo = h < lo ? h : lo;
      hi = h > hi ? h : hi;
    }
    const double gap = std::max(lo - (hl > 0.0 ? hl : 0.0), (hl < 0.0 ? hl : 0.0) - hi);
    if (gap > e3) return FacePlanes::Separate;
    touching = touching || gap >= -e3;
  }
  return touching ? FacePlanes::Touching : FacePlanes::Open;
}

// Stage 2 on an aligned pair: the kernel's minimum depth is spoilt by edge pairs the doubles cannot
// resolve (n = eB × eA possibly 0). Every facet of A ⊕ (−B) has a positive offset — the interiors
// intersect (definitions §4) — when the faces and the resolved edge pairs have computed depths
// D > E3 in both orientations (the kernel's test) and near_parallel_bound gives each unresolved
// pair a positive lower bound (near_parallel_bound.h: it bounds every facet such a pair can be).
bool intersecting_without_unresolved(const detail::SupersetLanes& K) {
  const FilterBounds fb = filter_bounds_of_extent(K.extent);
  const std::uint64_t unresolved = detail::unresolved_edge_pairs(K, fb);
  if (!unresolved) return false;
  for (int f = 0; f < 8; ++f) {
    double D = K.H[0][f];
    for (int j = 1; j < 4; ++j) D = D > K.H[j][f] ? D : K.H[j][f];
    if (!(D > fb.deg3)) return false;
  }
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b)
      if (!(unresolved >> (8 * a + b) & 1u) && !(K.dp[a][b] > fb.deg3 && K.dm[a][b] > fb.deg3))
        return false;
  for (std::uint64_t bits = unresolved; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits);
    if (!detail::near_parallel_positive(K, fb, lane / kLaneStride, lane % kLaneStride)) return false;
  }
  return true;
}

// Stage 1: Disjoint when a face plane certainly separates, else Unknown (touching: a face
// plane's gap is within E3 of 0, face_planes; finite: every coordinate finite, else nothing is
// computed).
Overlap face_stage(const TetVertices& A, const TetVertices& B, bool& finite, bool& touching,
                   detail::FacePlaneValues& values) {
  touching = false;
  double z = 0.0;  // 0 when every coordinate is finite (x·0 is NaN for inf and NaN)
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) z += A[i][k] * 0.0 + B[i][k] * 0.0;
  finite = z == 0.0;
  if (!finite) return Overlap::Unknown;
  const double e3_faces = filter_bounds(A, B).deg3;  // +inf when L is out of range
  const FacePlanes a = face_planes(A, B, e3_faces, values.hl, values.h);
  if (a == FacePlanes::Separate) return Overlap::Disjoint;
  const FacePlanes b = face_planes(B, A, e3_faces, values.hl + 4, values.h + 4);
  if (b == FacePlanes::Separate) return Overlap::Disjoint;
  touching = a == FacePlanes::Touching || b == FacePlanes::Touching;
  return Overlap::Unknown;
}

// Stage 2 on a finite pair stage 1 left Unknown, its lanes kept in K.
Overlap kernel_stage(const TetVertices& A, const TetVertices& B, detail::SupersetLanes& K) {
  detail::superset_kernel(A, B, K, nullptr);
  if (!(K.finite == 0.0)) return Overlap::Unknown;  // non-finite input: garbage lanes
  const double e3 = filter_bounds_of_extent(K.extent).deg3;  // +inf outside the range guard
  if (!(std::fabs(K.det[3]) > e3) || !(std::fabs(K.det[7]) > e3)) return Overlap::Unknown;
  if (K.lo < -e3) return Overlap::Disjoint;
  if (K.lo > e3) return Overlap::Intersecting;
  return intersecting_without_unresolved(K) ? Overlap::Intersecting : Overlap::Unknown;
}

// The edge pairs whose axis may separate: bit 8a + b unless both computed depths D(+n), D(−n)
// of the kernel exceed E3 (their error is <= 174 u L³ < E3, filter_bounds.h: the exact depths
// are then > 0 and neither ±n separates).
std::uint64_t open_edge_pairs(const detail::SupersetLanes& K) {
  const double e3 = filter_bounds_of_extent(K.extent).deg3;
  std::uint64_t mask = 0;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b)
      if (!(K.dp[a][b] > e3 && K.dm[a][b] > e3)) mask |= std::uint64_t{1} << (8 * a + b);
  return mask;
}

}  // namespace

Overlap overlap_filter(const TetVertices& A, const TetVertices& B) {
  bool finite = false, touching = false;
  detail::FacePlaneValues values;
  const Overlap o = face_stage(A, B, finite, touching, values);
  if (o != Overlap::Unknown || !finite) return o;
  detail::SupersetLanes K;
  return kernel_stage(A, B, K);
}

bool interiors_intersect(const TetVertices& A, const TetVertices& B) {
  bool finite = false, touching = false;
  detail::FacePlaneValues values;  // (the face stage's values, for the face axes' signs)
  Overlap o = face_stage(A, B, finite, touching, values);
  if (o == Overlap::Disjoint) return false;
  // A touching face: the face axes exactly (exact_sat.h) before the kernel. (One integer frame
  // for both exact calls: its scale found once, where a sign needs it.)
  detail::IntegerFrame frame(A, B);
  bool faces_decided = false;
  if (touching) {
    const detail::SatVerdict v = detail::face_axes_sat(A, B, &frame, &values);
    if (v == detail::SatVerdict::Disjoint) return false;
    faces_decided = v == detail::SatVerdict::Intersecting;  // (no face axis separates)
  }
  detail::SupersetLanes K;
  if (finite) o = kernel_stage(A, B, K);
  if (o != Overlap::Unknown) return o == Overlap::Intersecting;
  // The exact separating-axis decision (exact_sat.h: doubles, then expansions; no rationals).
  // Undecided only outside the expansions' range or capacity.
  const std::uint64_t open = finite && K.finite == 0.0 ? open_edge_pairs(K) : ~std::uint64_t{0};
  const detail::SatVerdict v = detail::interiors_intersect_sat(A, B, &open, faces_decided, &frame);
  if (v != detail::SatVerdict::Undecided) return v == detail::SatVerdict::Intersecting;
  // The decision alone (no depth to certify): the candidate set's exact depth signs on the pair
  // rescaled by a power of two (power_scale.h: signs unchanged when the scaling is exact).
  const detail::ScaledPair sp = detail::power_scaled(A, B);
  if (sp.finite && sp.exact) {
    thread_local CandidateSet set;  // (~20 KB: off the stack, allocated once per thread)
    if (build_candidates(sp.A, sp.B, set) == BuildStatus::Ok) return set.intersecting;
    return false;  // flat (decided exactly): rejected, definitions §1
  }
  return rigid_pd2_choice(A, B).value != 0.0;  // NaN (not representable) != 0: intersecting
}

}  // namespace pdd::fast
