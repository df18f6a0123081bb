// exact_sat.cpp — interiors_intersect_sat (exact_sat.h): the 8 face axes and the 36 edge-pair
// axes in doubles with the static filter E3, then the exact signs the filter left open (double
// words, then expansions), axis by axis, for the axes certain signs did not rule out.
#include "exact/exact_sat.h"

#include <algorithm>
#include <cstdint>
#include <optional>

#include "certification/compensated_heights.h"
#include "certification/filter_bounds.h"
#include "exact/exact_heights.h"
#include "exact/expansion.h"
#include "exact/integer_heights.h"
#include "pdd/tet_tables.h"

namespace pdd::fast::detail {
namespace {

inline void sub3(const Vec3d& p, const Vec3d& q, double* d) {
  for (int k = 0; k < 3; ++k) d[k] = p[k] - q[k];
}
inline void cross3(const double* a, const double* b, double* n) {
  n[0] = a[1] * b[2] - a[2] * b[1];
  n[1] = a[2] * b[0] - a[0] * b[2];
  n[2] = a[0] * b[1] - a[1] * b[0];
}
// n.(p − q) for n a computed cross product of two differences: a triple product of
// differences, error <= 48 u L³ (filter_bounds.h).
inline double height(const double* n, const Vec3d& p, const Vec3d& q) {
  return n[0] * (p[0] - q[0]) + n[1] * (p[1] - q[1]) + n[2] * (p[2] - q[2]);
}
// The certain sign of a filtered value: ±1, or 0 when |v| <= e3 (undecided, not "zero").
inline int certain(double v, double e3) { return v > e3 ? 1 : (v < -e3 ? -1 : 0); }

LazyNormal face_normal_exact(const TetVertices& T, int f) {
  const auto& v = kFace[f];
  return LazyNormal(T[v[1]], T[v[0]], T[v[2]], T[v[0]]);
}

// The expansions' range (expansion.h's in_exact_range), checked once a pair and only where an
// expansion is about to be formed: the filter's bound E3 (+inf outside its own range guard) and
// the double words' bounds (absolute terms for underflow, non-finite values refused) hold at
// any scale, and most pairs never reach the expansions.
class ExactRange {
 public:
  ExactRange(const TetVertices& A, const TetVertices& B) : A_(A), B_(B) {}
  bool ok() {
    if (state_ < 0) state_ = in_exact_range(A_, B_) ? 1 : 0;
    return state_ == 1;
  }

 private:
  const TetVertices& A_;
  const TetVertices& B_;
  int state_ = -1;  // not checked yet
};

// The exact orientation sign of T (det[t1 − t0, t2 − t0, t3 − t0]); ok = false outside the
// expansions' range when they are needed.
// (base: T's first vertex index in the integer frame, 0 for A, 4 for B)
int orientation(const TetVertices& T, int base, double e3, IntegerFrame& frame, ExactRange& range, bool& ok) {
  double u[3], v[3], n[3];
  sub3(T[1], T[0], u);
  sub3(T[2], T[0], v);
  cross3(u, v, n);
  const int s = certain(height(n, T[3], T[0]), e3);
  if (s != 0) return s;
  if (frame.usable()) return frame.height_sign(base + 1, base, base + 2, base, base + 3, base);
  if (!range.ok()) return ok = false, 0;
  LazyNormal ne = face_normal_exact(T, 3);  // (t1 − t0) × (t2 − t0)
  ok = ok && ne.ok;
  return exact_height_sign(ne, T[3], T[0], ok);
}

// The sign of n.(p − q), n = (p1 − p0) × (q1 − q0), where the double words decide it
// (compensated_heights.h: within 25 u² M of the exact value), else 0 (the expansions then
// decide it). The normal in double words is built on first use (`words`), once per axis.
int word_sign(std::optional<CompensatedNormal>& words, const Vec3d& p1, const Vec3d& p0, const Vec3d& q1,
              const Vec3d& q0, const Vec3d& p, const Vec3d& q) {
  if (!words) words = compensated_normal(p1, p0, q1, q0);
  int sign = 0;
  return compensated_height_sign(*words, p, q, sign) ? sign : 0;
}

// A face axis (header, case i): face f of T against the vertices of O, σ = orientation(T) ·
// kFaceParity[f]. True when certain signs already violate the test (not separating); fills
// the values' certain signs times σ (0: undecided) and the computed heights h.
bool face_ruled_out(const TetVertices& T, const TetVertices& O, int f, int sigma, double e3, int* s, double* h) {
  const auto& v = kFace[f];
  double u[3], w[3], n[3];
  sub3(T[v[1]], T[v[0]], u);
  sub3(T[v[2]], T[v[0]], w);
  cross3(u, w, n);
  for (int j = 0; j < 4; ++j) {
    h[j] = height(n, O[j], T[v[0]]);
    s[j] = sigma * certain(h[j], e3);
    if (s[j] > 0) return true;
  }
  return false;
}

// The face axis decided exactly, s[] its certain signs (times σ), h[] the computed heights:
// true when it separates. Where the pair has an integer frame (integer_heights.h) every
// undecided height is taken there. Otherwise: an undecided height the doubles computed as
// exactly 0 is most often an exact 0 (a vertex of a dyadic grid in a face plane of its copy:
// every product and sum exact), which only the expansions decide (exact_height_sign tries the
// exact doubles first); any other is most often not 0 by a rounding (a grid's copy shifted by
// a non-dyadic offset), which the face's normal in double words decides
// (compensated_heights.h: within 25 u² M of the exact height) at a fraction of the expansions'
// cost, the expansions taking the rest.
// (tb, ob: T's and O's first vertex indices in the integer frame)
bool face_separates_exact(const TetVertices& T, const TetVertices& O, int tb, int ob, int f, int sigma, const int* s,
                          const double* h, IntegerFrame& frame, ExactRange& range, bool& ok) {
  const auto& v = kFace[f];
  if (frame.usable()) {
    __int128 n[3];
    frame.normal(tb + v[1], tb + v[0], tb + v[2], tb + v[0], n);
    for (int j = 0; j < 4; ++j)
      if (s[j] == 0 && sigma * frame.dot_sign(n, ob + j, tb + v[0]) > 0) return false;
    return true;
  }
  std::optional<CompensatedNormal> words;
  int left[4], nleft = 0;  // the vertices the double words leave to the expansions
  for (int j = 0; j < 4; ++j) {
    if (s[j] < 0) continue;
    // a vertex of the face itself: its height is exactly 0 (n is orthogonal to the face's edges)
    if (O[j] == T[v[0]] || O[j] == T[v[1]] || O[j] == T[v[2]]) continue;
    const int sj = h[j] != 0.0 ? sigma * word_sign(words, T[v[1]], T[v[0]], T[v[2]], T[v[0]], O[j], T[v[0]]) : 0;
    if (sj > 0) return false;
    if (sj == 0) left[nleft++] = j;
  }
  if (nleft == 0) return true;
  if (!range.ok()) return ok = false;
  LazyNormal n = face_normal_exact(T, f);
  ok = ok && n.ok;
  if (!ok) return false;
  for (int i = 0; i < nleft; ++i)
    if (sigma * exact_height_sign(n, O[left[i]], T[v[0]], ok) > 0 || !ok) return false;
  return true;
}

// The five values of an edge-pair axis (header, case iii) in the order α_w1, α_w2, β_j1, β_j2,
// γ, as (p, q) of n.(p − q) (and as vertex indices of the integer frame: 0..3 A, 4..7 B), and
// the sign each must have for m = +n (−n: the opposite).
struct EdgeValues {
  const Vec3d* p[5];
  const Vec3d* q[5];
  int ip[5], iq[5];
};
constexpr int kPlusSign[5] = {-1, -1, +1, +1, -1};  // α <= 0, β >= 0, γ <= 0

EdgeValues edge_values(const TetVertices& A, const TetVertices& B, int a, int b) {
  const Vec3d& su = A[kEdges[a][0]];
  const Vec3d& rx = B[kEdges[b][0]];
  const int u = kEdges[a][0], x = 4 + kEdges[b][0];
  return {{&A[kOffEdge[a][0]], &A[kOffEdge[a][1]], &B[kOffEdge[b][0]], &B[kOffEdge[b][1]], &su},
          {&su, &su, &rx, &rx, &rx},
          {kOffEdge[a][0], kOffEdge[a][1], 4 + kOffEdge[b][0], 4 + kOffEdge[b][1], u},
          {u, u, x, x, x}};
}

// Updates the orientations still allowed by a value of sign sv (certain or exact).
inline void restrict_orientations(int sv, int i, bool& plus, bool& minus) {
  if (sv == -kPlusSign[i]) plus = false;
  if (sv == kPlusSign[i]) minus = false;
}

struct PendingEdge {
  int a, b;
  int s[5];     // certain signs of the values (0: undecided)
  double v[5];  // the values as computed
  bool plus, minus;
};


// x·y − z·w = 0 exactly, seen without arithmetic: both products have a zero factor (a computed
// difference is 0 iff the exact one is), or, for exact x, y, z, w, the products have the same
// factors. Parallel edges of aligned inputs are mostly of these kinds.
inline bool minor_is_zero(double x, double y, double z, double w, bool exact) {
  return (((x == 0.0) | (y == 0.0)) & ((z == 0.0) | (w == 0.0))) |
         (exact & (((x == z) & (y == w)) | ((x == w) & (y == z))));
}
// u × v = 0 exactly by minor_is_zero (false: not known, the exact pass decides).
inline bool normal_is_zero(const double* u, const double* v, bool exact) {
  return minor_is_zero(u[1], v[2], u[2], v[1], exact) & minor_is_zero(u[2], v[0], u[0], v[2], exact) &
         minor_is_zero(u[0], v[1], u[1], v[0], exact);
}

// Pass 1 for the 36 edge-pair axes: the five values of each in doubles, laid out for the
// compiler to vectorise. Cyclic forms of the triple product, all of the filter_bounds.h kind
// (a cross product of two differences dotted with a difference, error <= 48 u L³):
//   α_w = (e_a × e_b).(s_w − s_u) = e_b.((s_w − s_u) × e_a)   (12 crosses of A, once)
//   β_j = (e_a × e_b).(r_j − r_x) = e_a.(e_b × (r_j − r_x))   (12 crosses of B, once)
//   γ   = (e_a × e_b).(s_u − r_x)                             (per pair)
// Fills `open` with the pairs certain signs leave possible (either orientation); returns how many.
int open_edge_pairs(const TetVertices& A, const TetVertices& B, double e3, PendingEdge* open) {
  double ea[6][3], eb[6][3], ca[6][2][3], cb[6][2][3];
  bool exact_ea[6], exact_eb[6];  // every component of the edge vector exact in doubles
  for (int k = 0; k < 6; ++k) {
    exact_ea[k] = exact_difference(A[kEdges[k][1]], A[kEdges[k][0]], ea[k]);
    exact_eb[k] = exact_difference(B[kEdges[k][1]], B[kEdges[k][0]], eb[k]);
    for (int w = 0; w < 2; ++w) {
      double d[3];
      sub3(A[kOffEdge[k][w]], A[kEdges[k][0]], d);
      cross3(d, ea[k], ca[k][w]);
      sub3(B[kOffEdge[k][w]], B[kEdges[k][0]], d);
      cross3(eb[k], d, cb[k][w]);
    }
  }
  double v[5][36];  // the five values (α_w1, α_w2, β_j1, β_j2, γ) of pair p = 6a + b
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const int p = 6 * a + b;
      double n[3];
      cross3(ea[a], eb[b], n);
      for (int w = 0; w < 2; ++w) {
        v[w][p] = eb[b][0] * ca[a][w][0] + eb[b][1] * ca[a][w][1] + eb[b][2] * ca[a][w][2];
        v[2 + w][p] = ea[a][0] * cb[b][w][0] + ea[a][1] * cb[b][w][1] + ea[a][2] * cb[b][w][2];
      }
      v[4][p] = height(n, A[kEdges[a][0]], B[kEdges[b][0]]);
    }
  // Ruled out: a certain sign against m = +n and one against m = −n (kPlusSign: − − + + −).
  // (Two plain loops: the first, branch-free, vectorises.)
  double plus_out[36], minus_out[36];
  for (int p = 0; p < 36; ++p) {
    const double hi = std::max(std::max(v[0][p], v[1][p]), std::max(-v[2][p], std::max(-v[3][p], v[4][p])));
    const double lo = std::min(std::min(v[0][p], v[1][p]), std::min(-v[2][p], std::min(-v[3][p], v[4][p])));
    plus_out[p] = hi;   // > e3: a value certainly of the sign m = +n forbids
    minus_out[p] = lo;  // < −e3: likewise for m = −n
  }
  int count = 0;
  for (int p = 0; p < 36; ++p) {
    if (plus_out[p] > e3 && minus_out[p] < -e3) continue;
    if (normal_is_zero(ea[p / 6], eb[p % 6], exact_ea[p / 6] && exact_eb[p % 6])) continue;  // no facet
    PendingEdge& e = open[count++];
    e.a = p / 6, e.b = p % 6, e.plus = !(plus_out[p] > e3), e.minus = !(minus_out[p] < -e3);
    for (int i = 0; i < 5; ++i) e.s[i] = certain(v[i][p], e3), e.v[i] = v[i][p];
  }
  return count;
}

// Pass 1 from a caller's mask of the edge pairs that may separate (bit 8a + b): the five values
// of those only, in doubles (n = e_a × e_b, each value a triple product of differences). Each
// edge vector, and whether it is exact in doubles, is taken once (a mask of an aligned pair
// holds ~20 of the 36 pairs, each edge in several of them).
int open_edge_pairs_in(const TetVertices& A, const TetVertices& B, double e3, std::uint64_t mask,
                       PendingEdge* open) {
  double ea[6][3], eb[6][3];
  bool exact_ea[6], exact_eb[6];
  for (int k = 0; k < 6; ++k) {
    exact_ea[k] = exact_difference(A[kEdges[k][1]], A[kEdges[k][0]], ea[k]);
    exact_eb[k] = exact_difference(B[kEdges[k][1]], B[kEdges[k][0]], eb[k]);
  }
  int count = 0;
  for (std::uint64_t bits = mask & 0x3f3f3f3f3f3full; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits), a = lane / 8, b = lane % 8;
    if (normal_is_zero(ea[a], eb[b], exact_ea[a] && exact_eb[b])) continue;  // no facet
    double n[3];
    cross3(ea[a], eb[b], n);
    const EdgeValues ev = edge_values(A, B, a, b);
    PendingEdge& e = open[count];
    e.a = a, e.b = b, e.plus = true, e.minus = true;
    for (int k = 0; k < 5; ++k) {
      e.v[k] = height(n, *ev.p[k], *ev.q[k]);
      e.s[k] = certain(e.v[k], e3);
      restrict_orientations(e.s[k], k, e.plus, e.minus);
    }
    count += e.plus || e.minus;
  }
  return count;
}

// The exact orientations of A and B (flat: 0); false when out of range or capacity.
bool orientations(const TetVertices& A, const TetVertices& B, double e3, IntegerFrame& frame, ExactRange& range,
                  int& oa, int& ob) {
  bool ok = true;
  oa = orientation(A, 0, e3, frame, range, ok);
  if (ok) ob = orientation(B, 4, e3, frame, range, ok);
  return ok;
}

// The face axes, each in doubles and then exactly where certain signs do not rule it out (A and
// B not flat: orientations oa, ob).
SatVerdict face_axes(const TetVertices& A, const TetVertices& B, double e3, int oa, int ob, IntegerFrame& frame,
                     ExactRange& range, const FacePlaneValues* values = nullptr) {
  bool ok = true;
  for (int t = 0; t < 2; ++t)
    for (int f = 0; f < 4; ++f) {
      const int sigma = (t == 0 ? oa : ob) * kFaceParity[f];
      const TetVertices& T = t == 0 ? A : B;
      const TetVertices& O = t == 0 ? B : A;
      int s[4];
      double h[4];
      if (values) {
        bool out = false;
        for (int j = 0; j < 4; ++j) {
          h[j] = values->h[4 * t + f][j];
          s[j] = sigma * certain(h[j], e3);
          out = out || s[j] > 0;
        }
        if (out) continue;
      } else if (face_ruled_out(T, O, f, sigma, e3, s, h)) {
        continue;
      }
      if (face_separates_exact(T, O, 4 * t, 4 - 4 * t, f, sigma, s, h, frame, range, ok)) return SatVerdict::Disjoint;
      if (!ok) return SatVerdict::Undecided;
    }
  return SatVerdict::Intersecting;
}

}  // namespace

SatVerdict face_axes_sat(const TetVertices& A, const TetVertices& B, IntegerFrame* shared,
                         const FacePlaneValues* values) {
  const double e3 = filter_bounds(A, B).deg3;  // +inf outside its range guard: all exact
  IntegerFrame own(A, B);
  IntegerFrame& frame = shared ? *shared : own;
  ExactRange range(A, B);
  int oa = 0, ob = 0;
  // A certain hl of a face is the orientation times the face's parity (exact_sat.h's kFaceParity)
  auto known = [&](int t) {
    for (int f = 0; f < 4; ++f)
      if (const int s = certain(values->hl[4 * t + f], e3)) return s * kFaceParity[f];
    return 0;
  };
  const bool from_values = values && (oa = known(0)) != 0 && (ob = known(1)) != 0;
  if (!from_values && !orientations(A, B, e3, frame, range, oa, ob)) return SatVerdict::Undecided;
  if (oa == 0 || ob == 0) return SatVerdict::Disjoint;  // flat: no interior (definitions §1)
  return face_axes(A, B, e3, oa, ob, frame, range, values);
}

SatVerdict interiors_intersect_sat(const TetVertices& A, const TetVertices& B, const std::uint64_t* open_edges,
                                   bool faces_decided, IntegerFrame* shared) {
  const double e3 = filter_bounds(A, B).deg3;  // +inf outside its range guard: all exact
  IntegerFrame own(A, B);
  IntegerFrame& frame = shared ? *shared : own;
  ExactRange range(A, B);
  int oa = 0, ob = 0;
  if (!orientations(A, B, e3, frame, range, oa, ob)) return SatVerdict::Undecided;
  if (oa == 0 || ob == 0) return SatVerdict::Disjoint;  // flat: no interior (definitions §1)

  // The face axes first: a touching face decides most touching pairs, before any edge-pair
  // axis is computed.
  if (!faces_decided) {
    const SatVerdict v = face_axes(A, B, e3, oa, ob, frame, range);
    if (v != SatVerdict::Intersecting) return v;
  }
  // The edge-pair axes: pass 1 in doubles (the axes certain signs do not rule out), pass 2 exact.
  bool ok = true;
  PendingEdge pending[36];
  const int npending = open_edges ? open_edge_pairs_in(A, B, e3, *open_edges, pending)
                                  : open_edge_pairs(A, B, e3, pending);
  for (int k = 0; k < npending; ++k) {
    PendingEdge& e = pending[k];
    const Vec3d &a1 = A[kEdges[e.a][1]], &a0 = A[kEdges[e.a][0]], &b1 = B[kEdges[e.b][1]], &b0 = B[kEdges[e.b][0]];
    const EdgeValues ev = edge_values(A, B, e.a, e.b);
    // n = e_a x e_b over integers where the pair has an integer frame; else in double words
    // first, as the face axes, and the expansions for what is left
    // (the integer normal formed at the first value the doubles left open)
    const bool integers = frame.usable();
    __int128 ni[3];
    bool have_ni = false;
    std::optional<CompensatedNormal> words;
    int sv[5], left[5], nleft = 0;
    for (int i = 0; i < 5 && (e.plus || e.minus); ++i) {
      sv[i] = e.s[i];
      if (sv[i] == 0 && integers) {
        if (!have_ni) frame.normal(kEdges[e.a][1], kEdges[e.a][0], 4 + kEdges[e.b][1], 4 + kEdges[e.b][0], ni);
        have_ni = true;
        sv[i] = frame.dot_sign(ni, ev.ip[i], ev.iq[i]);
      }
      else if (sv[i] == 0 && e.v[i] != 0.0) sv[i] = word_sign(words, a1, a0, b1, b0, *ev.p[i], *ev.q[i]);
      if (sv[i] != 0 || integers) restrict_orientations(sv[i], i, e.plus, e.minus);
      else left[nleft++] = i;
    }
    if ((e.plus || e.minus) && nleft > 0) {
      if (!range.ok()) return SatVerdict::Undecided;
      LazyNormal n(a1, a0, b1, b0);
      if (!n.ok) return SatVerdict::Undecided;
      for (int r = 0; r < nleft && (e.plus || e.minus); ++r) {
        const int i = left[r];
        sv[i] = exact_height_sign(n, *ev.p[i], *ev.q[i], ok);
        if (!ok) return SatVerdict::Undecided;
        restrict_orientations(sv[i], i, e.plus, e.minus);
      }
    }
    // n = 0 (parallel edges: no facet, header) iff α_w1 = α_w2 = 0: n ⊥ e_a by construction,
    // and e_a, s_w1 − s_u, s_w2 − s_u span space for a non-flat A. (Both α are known here: an
    // orientation left possible means every value was decided.)
    if ((e.plus || e.minus) && (sv[0] | sv[1]) != 0) return SatVerdict::Disjoint;
  }
  return SatVerdict::Intersecting;
}

}  // namespace pdd::fast::detail
