#include "pdd/compare/generate.h"
#include "pdd/compare/random.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>

#include "pdd/reference/minkowski_pd.h"
#include "pdd/pdd.h"
#include "pdd/reference/solve_exact.h"
#include "pdd/reference/validate_pair.h"

namespace pdd::compare {
namespace {

using reference::Rational;

using Rng = ReproducibleRng;  // random.h: the same draws with every standard library

constexpr double kGridStep = 1.0 / 16;  // degenerate families: coordinates k/16 in [0, 10]
constexpr int kMaxTries = 200000;

Vec3d add(const Vec3d& a, const Vec3d& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3d mul(double s, const Vec3d& a) { return {s * a[0], s * a[1], s * a[2]}; }

Vec3d random_point(Rng& r, double side) { return {r.uniform(0, side), r.uniform(0, side), r.uniform(0, side)}; }
Vec3d grid_point(Rng& r) {
  return {r.grid(0, 10, kGridStep), r.grid(0, 10, kGridStep), r.grid(0, 10, kGridStep)};
}
TetVertices grid_tet(Rng& r) { return {grid_point(r), grid_point(r), grid_point(r), grid_point(r)}; }

double volume(const TetVertices& t) { return tetrahedron_volume(t); }

bool valid(const TetVertices& t) { return !reference::validate_tetrahedron(t, 'A').has_value(); }

// The exact intersection decision: the fast engine's certified separating-axis filter
// (pdd.h's overlap_filter: Disjoint or Intersecting only when certain, ~100 ns), and where it
// cannot tell (touching, nearly touching, parallel edges), the exact Minkowski difference.
// Smallest facet offset of A (+) (-B): > 0 intersecting, == 0 touching, < 0 disjoint.
Rational min_facet_offset(const TetPair& p) {
  const auto m = reference::minkowski_pd(reference::to_exact(p));
  Rational lo = m.facets.front().offset;
  for (const auto& f : m.facets) lo = CGAL::min(lo, f.offset);
  return lo;
}
bool intersecting(const TetPair& p) {
  if (!valid(p.A) || !valid(p.B)) return false;
  switch (fast::overlap_filter(p.A, p.B)) {
    case fast::Overlap::Disjoint: return false;
    case fast::Overlap::Intersecting: return true;
    case fast::Overlap::Unknown: break;
  }
  return min_facet_offset(p) > 0;
}

TetPair pair_of(const TetVertices& a, const TetVertices& b) {
  TetPair p;
  p.A = a, p.B = b;
  return p;
}

// A vertex combination f0 + a (f1 - f0) + b (f2 - f0) of a face, a and b multiples of 1/8.
Vec3d face_point(const TetVertices& t, int opposite, double a, double b) {
  int f[3], k = 0;
  for (int i = 0; i < 4; ++i)
    if (i != opposite) f[k++] = i;
  return add(t[f[0]], add(mul(a, sub(t[f[1]], t[f[0]])), mul(b, sub(t[f[2]], t[f[0]]))));
}

// ---------------------------------------------------------------- the families
// Each maker is one attempt: nullopt when the draw lacks the family's property (then
// generate_family draws again, at most kMaxTries times).
using Attempt = std::optional<TetPair>;

Attempt paper_pair(Rng& r, const PaperProtocol& pp) {
  auto tet = [&]() -> std::optional<TetVertices> {
    TetVertices t;
    for (auto& v : t) v = random_point(r, pp.cube_side);
    const double vol = volume(t);
    if (vol < pp.min_volume || vol > pp.max_volume || !valid(t)) return std::nullopt;
    return t;
  };
  const auto a = tet();
  if (!a) return std::nullopt;
  const auto b = tet();
  if (!b) return std::nullopt;
  TetPair p = pair_of(*a, *b);
  if (!intersecting(p)) return std::nullopt;
  return p;
}

bool strictly_inside(const TetVertices& outer, const Vec3d& x) {
  const auto t = reference::to_exact(outer);
  const reference::Point q{Rational(x[0]), Rational(x[1]), Rational(x[2])};
  const auto whole = CGAL::orientation(t[0], t[1], t[2], t[3]);
  for (int i = 0; i < 4; ++i) {
    auto tt = t;
    tt[i] = q;
    if (CGAL::orientation(tt[0], tt[1], tt[2], tt[3]) != whole) return false;
  }
  return true;
}

// Keep the pair when A is valid and the pair intersects.
Attempt if_intersecting(const TetVertices& a, const TetVertices& b) {
  TetPair p = pair_of(a, b);
  if (!valid(a) || !intersecting(p)) return std::nullopt;
  return p;
}

Attempt nested_pair(Rng& r) {
  TetVertices a, b;
  for (auto& v : a) v = random_point(r, 10);
  if (volume(a) < 50) return std::nullopt;
  const Vec3d c = mul(0.25, add(add(a[0], a[1]), add(a[2], a[3])));
  const double size = r.uniform(0.2, 1.0);
  for (auto& v : b) v = add(c, {r.uniform(-size, size), r.uniform(-size, size), r.uniform(-size, size)});
  if (!valid(b)) return std::nullopt;
  if (!std::all_of(b.begin(), b.end(), [&](const Vec3d& x) { return strictly_inside(a, x); }))
    return std::nullopt;
  return pair_of(a, b);
}

// B's edge 0 (r0, r1) is parallel to edge e of A: r1 = r0 + m (s_v - s_u), exact on the grid.
Attempt parallel_edges_pair(Rng& r) {
  const double ms[] = {0.5, -0.5, 0.25, -0.75, 1.0};
  const TetVertices a = grid_tet(r);
  const int e = r.integer(0, 5);
  const Vec3d dir = sub(a[kEdges[e][1]], a[kEdges[e][0]]);
  const Vec3d r0 = grid_point(r);
  return if_intersecting(a, {r0, add(r0, mul(ms[r.integer(0, 4)], dir)), grid_point(r), grid_point(r)});
}

// B's edge 0 lies on the line of edge e of A: r_k = s_u + alpha_k (s_v - s_u).
Attempt colinear_edges_pair(Rng& r) {
  const double alphas[] = {-0.25, 0.25, 0.5, 0.75, 1.25};
  const TetVertices a = grid_tet(r);
  const int e = r.integer(0, 5);
  const Vec3d su = a[kEdges[e][0]], dir = sub(a[kEdges[e][1]], su);
  const int i = r.integer(0, 4), j = (i + r.integer(1, 4)) % 5;
  return if_intersecting(a, {add(su, mul(alphas[i], dir)), add(su, mul(alphas[j], dir)),
                             grid_point(r), grid_point(r)});
}

// B's face (r0, r1, r2) lies in the plane of a face of A.
Attempt coplanar_faces_pair(Rng& r) {
  const TetVertices a = grid_tet(r);
  const int i = r.integer(0, 3);
  TetVertices b;
  for (int k = 0; k < 3; ++k) {
    const double v = r.grid(-0.25, 1, 0.125), u = r.grid(-0.25, 1, 0.125);
    b[k] = face_point(a, i, u, v);
  }
  b[3] = grid_point(r);
  return if_intersecting(a, b);
}

// B's first `shared` vertices are vertices of A.
Attempt shared_pair(Rng& r, int shared) {
  const TetVertices a = grid_tet(r);
  TetVertices b = grid_tet(r);
  for (int k = 0; k < shared; ++k) b[k] = a[k];
  return if_intersecting(a, b);
}

Attempt identical_pair(Rng& r) {
  TetVertices a;
  for (auto& v : a) v = random_point(r, 10);
  if (!valid(a)) return std::nullopt;
  TetVertices b = a;
  for (int k = 3; k > 0; --k) std::swap(b[k], b[r.integer(0, k)]);  // Fisher-Yates
  return pair_of(a, b);
}

// (Random draws: one per statement, never two in one call's arguments, whose order C++ leaves
// unspecified — GCC and clang differ. The order is the one the shipped fixtures were made with.)

// B stands on the outside of a face of A: three vertices in the face's plane, the apex
// beyond it. The interiors are disjoint and the boundaries meet: PD = 0 exactly.
Attempt touching_pair(Rng& r) {
  const TetVertices a = grid_tet(r);
  const int i = r.integer(0, 3);
  const Vec3d p = face_point(a, i, 0.25, 0.25);
  TetVertices b;
  for (int k = 0; k < 3; ++k) {
    const double v = r.grid(0, 0.5, 0.125), u = r.grid(0, 0.5, 0.125);
    b[k] = face_point(a, i, u, v);
  }
  b[3] = sub(p, mul(r.grid(0.25, 1, 0.25), sub(a[i], p)));
  TetPair q = pair_of(a, b);
  if (!valid(a) || !valid(b) || min_facet_offset(q) != 0) return std::nullopt;
  return q;
}

Attempt disjoint_pair(Rng& r) {
  TetVertices a, b;
  for (auto& v : a) v = random_point(r, 10);
  for (auto& v : b) {
    const Vec3d shift = {r.uniform(0, 12), r.uniform(0, 12), 0};
    v = add(random_point(r, 10), shift);
  }
  TetPair p = pair_of(a, b);
  if (!valid(a) || !valid(b) || min_facet_offset(p) >= 0) return std::nullopt;
  return p;
}

// A vertex of B pokes through a face of A by 2^-30 of the way to the opposite vertex:
// PD is about 1e-9 of the size. B's other three vertices lie beyond the face.
Attempt near_touching_pair(Rng& r) {
  const TetVertices a = grid_tet(r);
  const int i = r.integer(0, 3);
  const double pv = r.grid(0.125, 0.375, 0.125), pu = r.grid(0.125, 0.5, 0.125);
  const Vec3d p = face_point(a, i, pu, pv);
  const Vec3d d = sub(a[i], p);  // into A
  TetVertices b;
  for (int j = 0, k = 0; j < 4; ++j)
    if (j != i) b[k] = sub(add(p, mul(0.5, sub(a[j], p))), mul(0.5, d)), ++k;
  b[3] = add(p, mul(0x1.0p-30, d));
  return if_intersecting(a, b);
}

// A resting contact as meshes have them everywhere: B's face (r0, r1, r2) a depth
// d = 2^-50 .. 2^-37 (~1e-15 .. 7e-12) below A's face z = 0 (sizes ~8), flat (kind 0) or tilted
// by theta = +-2^-43 .. 2^-37 rad about an axis in the face plane through B's face centroid
// (kind 1: part of the face out of contact); kind 2 is kind 1 with y and z swapped (the face in
// y = 0), kind 3 kind 1 under a random rotation (a generic plane: no normal near an axis). The
// tilt moves z only (x, y change by theta z ~ 1e-11, far below the face's size: left out), so
// the depths are not lost to rounding in the coordinate planes.
bool squared_outputs_normal(const TetPair& p);

Attempt near_coplanar_pair(Rng& r, std::size_t k) {
  const int kind = int(k % 4);
  const TetVertices a = {{{0, 0, 0}, {8, 0, 0}, {0, 8, 0}, {r.uniform(0, 2), r.uniform(0, 2), -r.uniform(6, 8)}}};
  const double depth = std::ldexp(1.0, -r.integer(37, 50));
  const double x0 = r.uniform(0.5, 1.5), y0 = r.uniform(0.5, 1.5), w = r.uniform(2, 4), h = r.uniform(2, 4);
  TetVertices b = {{{x0, y0, -depth}, {x0 + w, y0, -depth}, {x0, y0 + h, -depth},
                    {x0 + r.uniform(0, 1), y0 + r.uniform(0, 1), r.uniform(4, 8)}}};
  if (kind > 0) {
    const double theta = (r.integer(0, 1) ? 1 : -1) * std::ldexp(1.0, -r.integer(37, 43));
    const double phi = r.uniform(0, 6.283185307179586);
    const double ux = std::cos(phi), uy = std::sin(phi);
    const double cx = x0 + w / 3, cy = y0 + h / 3;
    for (int i = 0; i < 3; ++i) b[i][2] += (ux * (b[i][1] - cy) - uy * (b[i][0] - cx)) * theta;
  }
  TetVertices aa = a;
  if (kind == 2)
    for (auto* t : {&aa, &b})
      for (auto& v : *t) std::swap(v[1], v[2]);
  if (kind == 3) {  // rotation about a random unit axis by a random angle (Rodrigues)
    Vec3d u = {r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)};
    const double n = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (n < 0.1) return std::nullopt;
    for (double& c : u) c /= n;
    const double t = r.uniform(0.3, 3), c = std::cos(t), s = std::sin(t), C = 1 - c;
    const double R[3][3] = {{c + u[0] * u[0] * C, u[0] * u[1] * C - u[2] * s, u[0] * u[2] * C + u[1] * s},
                            {u[1] * u[0] * C + u[2] * s, c + u[1] * u[1] * C, u[1] * u[2] * C - u[0] * s},
                            {u[2] * u[0] * C - u[1] * s, u[2] * u[1] * C + u[0] * s, c + u[2] * u[2] * C}};
    for (auto* tet : {&aa, &b})
      for (auto& v : *tet) {
        const Vec3d x = v;
        for (int i = 0; i < 3; ++i) v[i] = R[i][0] * x[0] + R[i][1] * x[1] + R[i][2] * x[2];
      }
  }
  Attempt p = if_intersecting(aa, b);
  if (!p || !valid(b) || !squared_outputs_normal(*p)) return std::nullopt;
  p->tags = {kind == 0 ? "flat" : kind == 1 ? "tilted" : kind == 2 ? "tilted-y-plane" : "tilted-generic-plane"};
  return p;
}

Attempt scaled_pair(Rng& r, const PaperProtocol& pp, int exponent) {
  Attempt p = paper_pair(r, pp);
  if (!p) return p;
  for (auto* t : {&p->A, &p->B})
    for (auto& v : *t)
      for (double& x : v) x = std::ldexp(x, exponent);  // exact: no overflow or underflow
  return p;
}

// B's fourth vertex sits about 1e-5 off the plane of its other three (size 10).
Attempt sliver_pair(Rng& r) {
  TetVertices a, b;
  for (auto& v : a) v = random_point(r, 10);
  if (volume(a) < 10) return std::nullopt;
  for (int k = 0; k < 3; ++k) b[k] = random_point(r, 10);
  const Vec3d off = {r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)};
  const double t2 = r.uniform(0, 1), t1 = r.uniform(0, 1);
  const Vec3d in_plane = add(mul(t1, sub(b[1], b[0])), mul(t2, sub(b[2], b[0])));
  b[3] = add(add(b[0], in_plane), mul(0x1.0p-20 * 10, off));
  if (!valid(b)) return std::nullopt;
  return if_intersecting(a, b);
}

// Paper-protocol pairs whose exact case-2 optimum is an undecidable edge pair.
Attempt undecidable_optimum_pair(Rng& r, const PaperProtocol& pp) {
  Attempt p = paper_pair(r, pp);
  if (!p) return p;
  reference::SolveOptions options;
  options.with_global = false;  // the candidates' optimum only
  const auto res = reference::solve_exact(*p, options);
  if (!res.pdd2_dir || res.pdd2_dir->orientation == EdgeOrientation::Decided) return std::nullopt;
  return p;
}

// A vertex of B pokes through the face z = 0 of the corner tetrahedron A (legs L) to depth t,
// with t below its distance to every other face, and B's base at z = -h, h >= t/4. Then
// PD = t along FV:3 and PD_d^2 (A static) = t^2/16 along FV:3 (derivation in
// tests/reference/test_closed_form.cpp); both recorded as tags.
Attempt closed_form_pair(Rng& r) {
  const double L = r.grid(6, 12, 1);
  const double t = r.grid(0.125, 1, 0.125);
  const double x = r.grid(0.5, 3, 0.125), y = r.grid(0.5, 3, 0.125);
  const double rest = L - x - y - t;  // rest / sqrt(3): the apex's distance to the slanted face
  const double h = r.grid(0.25, 2, 0.125);
  if (!(t < x && t < y && rest > 0 && rest * rest > 3 * t * t && h >= t / 4)) return std::nullopt;
  TetPair p = pair_of({{{0, 0, 0}, {L, 0, 0}, {0, L, 0}, {0, 0, L}}},
                      {{{r.grid(0, 4, 0.25), r.grid(-2, 0, 0.25), -h},
                        {r.grid(4, 6, 0.25), r.grid(0, 4, 0.25), -h},
                        {r.grid(-2, 0, 0.25), r.grid(4, 6, 0.25), -h},
                        {x, y, t}}});
  if (!valid(p.B) || !intersecting(p)) return std::nullopt;
  const Rational t2 = Rational(t) * Rational(t);
  p.tags = {"rigid_pd2=" + reference::to_string(t2), "rigid_dir=FV:3",
            "pdd2_static=" + reference::to_string(t2 / 16), "pdd2_static_dir=FV:3"};
  return p;
}

// ---------------------------------------------------------------- adversarial
// Valid pairs that defeat naive double arithmetic (cancellation, overflow, underflow, lost
// ulps). Pair k is of kind k % kAdversarialKinds, so every kind appears once in every run of
// kAdversarialKinds consecutive pairs. Every coordinate is a double computed here by exact
// operations (or by one correctly rounded addition, for the translated kind: the pair is
// then what the rounded doubles say); validity (non-zero volume) and every promised property
// are decided with the exact engine, and every exact squared output must be 0 or a normal
// double (definitions §8), else the draw is repeated.
constexpr int kAdversarialKinds = 10;
const char* const kAdversarialKind[kAdversarialKinds] = {
    "ulp-sliver", "ulp-needle",     "nearly-flat",   "near-touching-in", "near-touching-out",
    "nearly-parallel-edges", "nearly-coplanar-faces", "power-of-two-scale", "far-translated",
    "far-vertex"};

Vec3d paper_point(Rng& r) { return random_point(r, 10); }
TetVertices paper_tet(Rng& r) { return {paper_point(r), paper_point(r), paper_point(r), paper_point(r)}; }
// A small dyadic vector: components multiples of 1/16 in [-1, 1], not all zero.
Vec3d small_grid_vector(Rng& r) {
  Vec3d w;
  do w = {r.grid(-1, 1, kGridStep), r.grid(-1, 1, kGridStep), r.grid(-1, 1, kGridStep)};
  while (w[0] == 0 && w[1] == 0 && w[2] == 0);
  return w;
}
// x moved by `ulps` units in the last place (exact: the neighbouring doubles).
double nudge(double x, int ulps) {
  const double to = ulps > 0 ? HUGE_VAL : -HUGE_VAL;
  for (int k = 0; k < std::abs(ulps); ++k) x = std::nextafter(x, to);
  return x;
}

bool normal_or_zero(const Rational& v) {
  if (v == 0) return true;
  const Rational a = CGAL::abs(v);
  return a >= Rational(std::numeric_limits<double>::min()) &&
         a <= Rational(std::numeric_limits<double>::max());
}
// Every squared value of definitions §6 is 0 or a normal double (exact, reduced formulation).
bool squared_outputs_normal(const TetPair& p) {
  reference::SolveOptions options;
  options.with_global = false;  // the seven values below only
  const auto r = reference::solve_exact(p, options);
  if (r.error) return false;
  for (const Rational* v : {&r.rigid_pd2, &r.eq11_pd2, &r.pdd2_static, &r.pdd2, &r.pdd2_relaxed,
                            &r.pdd2_accel1, &r.pdd2_accel6})
    if (!normal_or_zero(*v)) return false;
  return true;
}

// A paper-protocol B against an adversarial A; kept when B is valid and the pair intersects.
Attempt with_random_b(Rng& r, const TetVertices& a) {
  const TetVertices b = paper_tet(r);
  if (!valid(b)) return std::nullopt;
  return if_intersecting(a, b);
}

Attempt adversarial_attempt(Rng& r, int kind) {
  switch (kind) {
    case 0: {  // ulp-sliver: s3 is s2 with one coordinate moved by 1 ulp; A is a flat sliver
      TetVertices a = paper_tet(r);
      a[3] = a[2];
      const int c = r.integer(0, 2);
      a[3][c] = nudge(a[3][c], r.integer(0, 1) ? 1 : -1);
      return with_random_b(r, a);
    }
    case 1: {  // ulp-needle: s1, s2 within 1 and 2 ulps of s0 (different axes), s3 far: a needle
      TetVertices a = paper_tet(r);
      const int c = r.integer(0, 2), d = (c + r.integer(1, 2)) % 3;
      a[1] = a[0], a[2] = a[0];
      a[1][c] = nudge(a[0][c], 1);
      a[2][d] = nudge(a[0][d], -2);
      return with_random_b(r, a);
    }
    case 2: {  // nearly-flat: s3 = an exact point of the plane of s0 s1 s2 + 2^-40 w (grid A)
      TetVertices a = grid_tet(r);
      const Vec3d w = small_grid_vector(r);
      const double v = r.grid(0, 1, 0.125), u = r.grid(0, 1, 0.125);
      a[3] = add(face_point(a, 3, u, v), mul(0x1.0p-40, w));  // multiples of 2^-44 below 2^5: exact
      return with_random_b(r, a);
    }
    case 3:
    case 4: {  // near-touching: a vertex of B 2^-60 of A's height inside (3) / outside (4) a
      // face of A. The pair is translated (exactly, on the 1/128 grid) so the contact point p
      // is the origin; then r3 = +-2^-60 (s_i - p) is exact. B's other vertices lie beyond
      // the face, so kind 4 is disjoint at distance ~2^-60 and kind 3 has PD ~2^-60.
      TetVertices a = grid_tet(r);
      const int i = r.integer(0, 3);
      const double pv = r.grid(0.125, 0.375, 0.125), pu = r.grid(0.125, 0.5, 0.125);
      const Vec3d p = face_point(a, i, pu, pv);
      for (auto& v : a) v = sub(v, p);
      const Vec3d d = a[i];  // from the contact point into A
      TetVertices b;
      for (int j = 0, k = 0; j < 4; ++j)
        if (j != i) b[k] = sub(mul(0.5, a[j]), mul(0.5, d)), ++k;
      b[3] = mul(kind == 3 ? 0x1.0p-60 : -0x1.0p-60, d);
      TetPair q = pair_of(a, b);
      if (!valid(a) || !valid(b)) return std::nullopt;
      const Rational m = min_facet_offset(q);
      if (kind == 3 ? !(m > 0) : !(m < 0)) return std::nullopt;
      return q;
    }
    case 5: {  // nearly-parallel-edges: r1 = r0 + m (s_v - s_u) + 2^-40 w (grid: exact)
      const double ms[] = {0.5, -0.5, 0.25, -0.75, 1.0};
      const TetVertices a = grid_tet(r);
      const int e = r.integer(0, 5);
      const Vec3d dir = sub(a[kEdges[e][1]], a[kEdges[e][0]]);
      const Vec3d r0 = grid_point(r);
      const Vec3d w = small_grid_vector(r);
      const double m = ms[r.integer(0, 4)];
      const Vec3d r1 = add(add(r0, mul(m, dir)), mul(0x1.0p-40, w));
      return if_intersecting(a, {r0, r1, grid_point(r), grid_point(r)});
    }
    case 6: {  // nearly-coplanar-faces: r0..r2 = points of a face plane of A + 2^-40 w_k
      const TetVertices a = grid_tet(r);
      const int i = r.integer(0, 3);
      TetVertices b;
      for (int k = 0; k < 3; ++k)
      {
        const Vec3d w = small_grid_vector(r);
        const double v = r.grid(-0.25, 1, 0.125), u = r.grid(-0.25, 1, 0.125);
        b[k] = add(face_point(a, i, u, v), mul(0x1.0p-40, w));
      }
      b[3] = grid_point(r);
      if (!valid(b)) return std::nullopt;
      return if_intersecting(a, b);
    }
    case 7: {  // power-of-two-scale: a paper pair times 2^e, e uniform in [-450, 450] (exact)
      Attempt p = paper_pair(r, {});
      if (!p) return p;
      const int e = r.integer(-450, 450);
      for (auto* t : {&p->A, &p->B})
        for (auto& v : *t)
          for (double& x : v) x = std::ldexp(x, e);
      p->tags.push_back("scale-2^" + std::to_string(e));
      return p;
    }
    case 8: {  // far-translated: a paper pair + (+-T, +-T, +-T), T in {1e6, 1e12}; each sum is
      // rounded once (ulp 2^-33 or 2^-13), and the pair is the rounded doubles.
      Attempt p = paper_pair(r, {});
      if (!p) return p;
      const double T = r.integer(0, 1) ? 1e12 : 1e6;
      const Vec3d t = {r.integer(0, 1) ? T : -T, r.integer(0, 1) ? T : -T, r.integer(0, 1) ? T : -T};
      for (auto* tet : {&p->A, &p->B})
        for (auto& v : *tet) v = add(v, t);
      return if_intersecting(p->A, p->B);
    }
    case 9: {  // far-vertex: a vertex of A moved by D w, D in {1e15, 1e18}, w a grid vector with
      // max |w_k| = 1 (rounded once); A becomes a long spike and B meets it near its base.
      TetVertices a = paper_tet(r);
      const double D = r.integer(0, 1) ? 1e18 : 1e15;
      const int i = r.integer(0, 3);
      Vec3d w = small_grid_vector(r);
      w[r.integer(0, 2)] = r.integer(0, 1) ? 1 : -1;  // |w|_max = 1: the vertex is >= D away
      a[i] = add(a[i], mul(D, w));
      return with_random_b(r, a);
    }
  }
  throw std::logic_error("adversarial kind");
}

Attempt adversarial_pair(Rng& r, std::size_t k) {
  const int kind = int(k % kAdversarialKinds);
  Attempt p = adversarial_attempt(r, kind);
  if (!p || !squared_outputs_normal(*p)) return std::nullopt;
  p->tags.insert(p->tags.begin(), kAdversarialKind[kind]);
  return p;
}

// ---- aligned: elements of structured meshes, the way FEM meshes are made (a block cut into
// cubes, each cube into tetrahedra), one mesh against a shifted copy. Kind k % 3:
//   0  Kuhn cells (6 tetrahedra a cube, the path 0 -> e_p0 -> e_p0 + e_p1 -> 1) of two grids of
//      cell size h, the second shifted by a random non-grid offset;
//   1  cells cut into 5 tetrahedra (a corner cut off at each of 4 alternate corners, the
//      central one), the two grids shifted as in 0;
//   2  two blocks stacked along z a third of a cell deep (offset (dx, dy, h − h/3), dx, dy
//      random): the faces of the layers touch across their whole extent, parallel exactly.
// The grid origin and h are random decimals, so the coordinates are rounded doubles: edge
// directions are parallel exactly along the axes (two coordinates equal) and parallel up to
// rounding otherwise — the near-parallel pairs doubles cannot tell from parallel ones.
TetVertices kuhn_cell_tet(const Vec3d& o, double h, int perm) {
  static const int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  TetVertices t;
  int d[3] = {0, 0, 0};
  t[0] = o;
  for (int q = 0; q < 3; ++q) {
    d[kPerm[perm][q]] = 1;
    t[q + 1] = {o[0] + d[0] * h, o[1] + d[1] * h, o[2] + d[2] * h};
  }
  return t;
}
TetVertices five_cell_tet(const Vec3d& o, double h, int which, bool odd) {
  auto corner = [&](int c) -> Vec3d {  // bit 0: x, bit 1: y, bit 2: z
    return {o[0] + (c & 1) * h, o[1] + (c >> 1 & 1) * h, o[2] + (c >> 2 & 1) * h};
  };
  static const int kEven[5][4] = {{0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}, {1, 2, 4, 7}};
  static const int kOdd[5][4] = {{1, 0, 3, 5}, {2, 0, 3, 6}, {4, 0, 5, 6}, {7, 3, 5, 6}, {0, 3, 5, 6}};
  const int* c = odd ? kOdd[which] : kEven[which];
  return {corner(c[0]), corner(c[1]), corner(c[2]), corner(c[3])};
}
Attempt aligned_pair(Rng& r, std::size_t k) {
  const int kind = int(k % 3);
  const double h = r.uniform(0.5, 2.0);
  const Vec3d origin = {r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)};
  auto cell = [&](const Vec3d& base, int i, int j, int l) -> Vec3d {
    return {base[0] + i * h, base[1] + j * h, base[2] + l * h};
  };
  auto tet_at = [&](const Vec3d& base, int i, int j, int l) {
    const Vec3d o = cell(base, i, j, l);
    if (kind == 1) return five_cell_tet(o, h, r.integer(0, 4), ((i + j + l) & 1) != 0);
    return kuhn_cell_tet(o, h, r.integer(0, 5));
  };
  const TetVertices a = tet_at(origin, 0, 0, 0);
  Vec3d shift = {r.uniform(-1, 1) * h, r.uniform(-1, 1) * h, r.uniform(-1, 1) * h};
  if (kind == 2) shift = {r.uniform(-1, 1) * h, r.uniform(-1, 1) * h, h - h / 3};
  const Vec3d base_b = add(origin, shift);
  // B's cell: one whose box meets A's cell (cells -1..0 of B's grid along each axis; the stacked
  // block's bottom layer along z)
  const int bi = r.integer(-1, 0), bj = r.integer(-1, 0), bl = kind == 2 ? -1 : r.integer(-1, 0);
  const TetVertices b = tet_at(base_b, bi, bj, bl);
  if (!valid(b)) return std::nullopt;
  Attempt p = if_intersecting(a, b);
  if (p) p->tags.push_back(kind == 0 ? "kuhn-shifted" : kind == 1 ? "five-shifted" : "stacked");
  return p;
}

// ---- rounding-contacts: cells of structured meshes whose faces coincide in exact arithmetic
// and meet only through the rounding of their coordinates (contacts made by rounding: PD ~1e-17
// of the size), and cells of a copy turned by 2^-30 rad (nearly aligned, a hair deep). Kind k % 3:
//   0  Kuhn cells of a grid of cell 1/8 (every coordinate exact) and of its copy shifted a tenth
//      of a cell along (1, 1, 1): the diagonal planes x − y = c of both coincide exactly, but
//      x + s and y + s round apart, so cells facing across such a plane overlap by a rounding;
//   1  Kuhn cells of a decimal grid placed up to a rounding (every coordinate moved by −2..+2
//      ulps, as a mesh generator places a transfinite grid) and of the same grid so placed
//      independently and raised by two thirds of a cell (a block stacked a third of a cell
//      deep): the faces of facing cells coincide up to the placements;
//   2  a Kuhn cell of a decimal grid and one of the same grid turned by ±2^-30 rad about a random
//      axis through the grid's origin: faces and edges parallel to the other's up to ~1e-9.
// Kept when the pair intersects with PD² below 2^-80 L² (kinds 0, 1: made by rounding) or 2^-40
// L² (kind 2), L the largest |coordinate|, exactly, and every squared output is 0 or normal.
TetVertices placed_up_to_rounding(Rng& r, TetVertices t) {
  for (auto& v : t)
    for (double& x : v)
      for (int u = r.integer(-2, 2); u != 0; u += u > 0 ? -1 : 1)
        x = std::nextafter(x, u > 0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity());
  return t;
}
TetVertices turned_about(const TetVertices& t, const Vec3d& o, const Vec3d& axis, double s) {
  // I + s K + (s²/2) K² (K the axis' cross-product matrix): a rotation by s to second order,
  // in doubles alone (no libm)
  const Vec3d& u = axis;
  const double K[3][3] = {{0, -u[2], u[1]}, {u[2], 0, -u[0]}, {-u[1], u[0], 0}};
  double R[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double k2 = 0;
      for (int m = 0; m < 3; ++m) k2 += K[i][m] * K[m][j];
      R[i][j] = (i == j ? 1.0 : 0.0) + s * K[i][j] + 0.5 * s * s * k2;
    }
  TetVertices out;
  for (int v = 0; v < 4; ++v) {
    const Vec3d d = sub(t[v], o);
    for (int i = 0; i < 3; ++i) out[v][i] = o[i] + (R[i][0] * d[0] + R[i][1] * d[1] + R[i][2] * d[2]);
  }
  return out;
}
Attempt rounding_contact_pair(Rng& r, std::size_t k) {
  const int kind = int(k % 3);
  const double h = kind == 0 ? 0.125 : r.uniform(0.5, 2.0);
  const Vec3d origin = kind == 0 ? Vec3d{r.integer(-16, 16) * h, r.integer(-16, 16) * h, r.integer(-16, 16) * h}
                                 : Vec3d{r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)};
  auto cell = [&](int i, int j, int l) -> Vec3d { return {origin[0] + i * h, origin[1] + j * h, origin[2] + l * h}; };
  // (one draw a declaration: function arguments are evaluated in no fixed order)
  const int perm_a = r.integer(0, 5), bi = r.integer(-1, 1), bj = r.integer(-1, 1), bl = r.integer(-1, 1);
  const int perm_b = r.integer(0, 5);
  TetVertices a = kuhn_cell_tet(cell(0, 0, 0), h, perm_a);
  TetVertices b = kuhn_cell_tet(cell(bi, bj, bl), h, perm_b);
  const char* tag = "";
  if (kind == 0) {
    const double s = h / 10;  // (rounded: no short binary form)
    for (auto& v : b) v = {v[0] + s, v[1] + s, v[2] + s};
    tag = "diagonal-rounding";
  } else if (kind == 1) {
    for (auto& v : b) v[2] += 2 * h / 3;
    a = placed_up_to_rounding(r, a);
    b = placed_up_to_rounding(r, b);
    tag = "placed-stacked";
  } else {
    Vec3d u = {r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)};
    const double n = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (n < 0.1) return std::nullopt;
    for (double& c : u) c /= n;
    b = turned_about(b, origin, u, (r.integer(0, 1) ? 1 : -1) * std::ldexp(1.0, -30));
    tag = "turned-2^-30";
  }
  if (!valid(a) || !valid(b)) return std::nullopt;
  TetPair p = pair_of(a, b);
  if (!intersecting(p)) return std::nullopt;
  double L = 0;
  for (const auto* t : {&a, &b})
    for (const auto& v : *t)
      for (double x : v) L = std::max(L, std::abs(x));
  const Rational pd2 = reference::minkowski_pd(reference::to_exact(p)).pd2;
  if (!(pd2 < Rational(std::ldexp(L * L, kind == 2 ? -40 : -80)))) return std::nullopt;
  if (!squared_outputs_normal(p)) return std::nullopt;
  p.tags.push_back(tag);
  return p;
}

// One attempt at a pair of a family; nullopt when the draw does not have the property.
using Maker = std::function<std::optional<TetPair>(Rng&, std::size_t)>;

struct Family {
  FamilyInfo info;
  Maker make;
};

std::vector<Family> family_table(const PaperProtocol& pp) {
  return {
      {{"paper", "the paper's protocol (docs/definitions.md §7): uniform in a 10-cube, volumes in "
                 "[0.1, 130], intersecting"},
       [pp](Rng& r, std::size_t) { return paper_pair(r, pp); }},
      {{"nested", "B (size 0.2 to 1) strictly inside A (volume >= 50)"},
       [](Rng& r, std::size_t) { return nested_pair(r); }},
      {{"parallel-edges", "B's edge 0 parallel to an edge of A (grid coordinates)"},
       [](Rng& r, std::size_t) { return parallel_edges_pair(r); }},
      {{"colinear-edges", "B's edge 0 on the line of an edge of A"},
       [](Rng& r, std::size_t) { return colinear_edges_pair(r); }},
      {{"coplanar-faces", "B's face (r0, r1, r2) in the plane of a face of A"},
       [](Rng& r, std::size_t) { return coplanar_faces_pair(r); }},
      {{"shared-vertex", "B shares vertex s0 with A"}, [](Rng& r, std::size_t) { return shared_pair(r, 1); }},
      {{"shared-edge", "B shares edge (s0, s1) with A"}, [](Rng& r, std::size_t) { return shared_pair(r, 2); }},
      {{"shared-face", "B shares face (s0, s1, s2) with A"}, [](Rng& r, std::size_t) { return shared_pair(r, 3); }},
      {{"identical", "B is A with its vertices permuted"}, [](Rng& r, std::size_t) { return identical_pair(r); }},
      {{"touching", "B on the outside of a face of A, boundaries meeting: PD = 0 exactly"},
       [](Rng& r, std::size_t) { return touching_pair(r); }},
      {{"disjoint", "interiors and boundaries disjoint"}, [](Rng& r, std::size_t) { return disjoint_pair(r); }},
      {{"near-touching", "a vertex of B 2^-30 of A's height through a face of A: PD ~ 1e-9 of the size"},
       [](Rng& r, std::size_t) { return near_touching_pair(r); }},
      {{"scaled-large", "paper pairs scaled by 2^20, 2^40, 2^60 (exactly)"},
       [pp](Rng& r, std::size_t k) { return scaled_pair(r, pp, 20 * int(1 + k % 3)); }},
      {{"scaled-small", "paper pairs scaled by 2^-20, 2^-40, 2^-60 (exactly)"},
       [pp](Rng& r, std::size_t k) { return scaled_pair(r, pp, -20 * int(1 + k % 3)); }},
      {{"sliver", "B's fourth vertex 1e-5 off the plane of its other three"},
       [](Rng& r, std::size_t) { return sliver_pair(r); }},
      {{"undecidable-optimum", "paper pairs whose exact case-2 optimum is an undecidable edge pair"},
       [pp](Rng& r, std::size_t) { return undecidable_optimum_pair(r, pp); }},
      {{"closed-form", "a vertex of B through a face of A at depth t: PD^2 = t^2, static PD_d^2 = t^2/16 (tags)"},
       [](Rng& r, std::size_t) { return closed_form_pair(r); }},
      {{"near-coplanar",
        "a face of B 2^-50..2^-37 inside a face of A (sizes ~8), flat or tilted 2^-43..2^-37 rad, "
        "in z = 0, y = 0 or a generic plane: resting contacts"},
       [](Rng& r, std::size_t k) { return near_coplanar_pair(r, k); }},
      {{"aligned",
        "elements of structured meshes against a shifted copy, kind k % 3: Kuhn cells (6 a cube) "
        "and 5-tetrahedra cells shifted by a non-grid offset, blocks stacked a third of a cell "
        "deep; parallel faces and edges, exactly or up to rounding"},
       [](Rng& r, std::size_t k) { return aligned_pair(r, k); }},
      {{"rounding-contacts",
        "cells of structured meshes meeting through the rounding of their coordinates, kind k % 3: "
        "Kuhn cells of a grid of cell 1/8 and of its copy a tenth of a cell along (1, 1, 1), of a "
        "decimal grid placed up to a rounding and its copy stacked a third of a cell deep (PD^2 "
        "below 2^-80 L^2), and of a grid and its copy turned 2^-30 rad (PD^2 below 2^-40 L^2)"},
       [](Rng& r, std::size_t k) { return rounding_contact_pair(r, k); }},
      {{"adversarial",
        "valid pairs that break naive doubles, kind k % 10: 1-ulp sliver, 1-ulp needle, nearly flat "
        "(2^-40), vertex 2^-60 inside / outside a face, nearly parallel edges, nearly coplanar faces "
        "(2^-40), scaled by 2^-450..2^450, translated by 1e6 / 1e12, a vertex 1e15 / 1e18 away"},
       [](Rng& r, std::size_t k) { return adversarial_pair(r, k); }},
  };
}

}  // namespace

double tetrahedron_volume(const TetVertices& t) {
  const Vec3d a = sub(t[1], t[0]), b = sub(t[2], t[0]), c = sub(t[3], t[0]);
  return std::abs(a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                  a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
}

const std::vector<FamilyInfo>& fixture_families() {
  static const std::vector<FamilyInfo> infos = [] {
    std::vector<FamilyInfo> out;
    for (const auto& f : family_table({})) out.push_back(f.info);
    return out;
  }();
  return infos;
}

void generate_family(const std::string& family, std::uint64_t seed, std::size_t count,
                     const PaperProtocol& protocol, const std::function<bool(TetPair&&)>& sink) {
  for (const auto& f : family_table(protocol)) {
    if (f.info.name != family) continue;
    Rng rng(seed);
    for (std::size_t k = 0; k < count; ++k) {
      std::optional<TetPair> attempt;
      for (int tries = 0; !attempt && tries < kMaxTries; ++tries) attempt = f.make(rng, k);
      if (!attempt) throw std::runtime_error(family + ": no pair found in " + std::to_string(kMaxTries) + " draws");
      TetPair p = std::move(*attempt);
      p.name = family + "-" + std::to_string(seed) + "-" + std::to_string(k);
      p.tags.insert(p.tags.begin(), family);
      if (!sink(std::move(p))) return;
    }
    return;
  }
  throw std::invalid_argument("unknown family '" + family + "' (see pdd generate --list)");
}

std::vector<TetPair> generate_family(const std::string& family, std::uint64_t seed,
                                     std::size_t count, const PaperProtocol& protocol) {
  std::vector<TetPair> out;
  generate_family(family, seed, count, protocol, [&out](TetPair&& p) {
    out.push_back(std::move(p));
    return true;
  });
  return out;
}

std::vector<std::pair<std::string, std::string>> tag_expectations(const TetPair& pair) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& tag : pair.tags) {
    const auto eq = tag.find('=');
    if (eq != std::string::npos) out.emplace_back(tag.substr(0, eq), tag.substr(eq + 1));
  }
  return out;
}

}  // namespace pdd::compare
