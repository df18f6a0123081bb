// fuzz_fast_engine — pairs of tetrahedra into pdd::fast::solve_pair, checked against
// definitions §5's inequalities and §6/§8's contract, and every N-th input against the exact
// engine.
//
// Input format (fuzz/README.md has the same):
//   byte 0      header: bits 0-1 mode (0 = raw, otherwise structured);
//               bit 7 = compare this input with the exact engine whatever N is.
//   raw         bytes 1..192: 24 little-endian IEEE-754 doubles, A's s0..s3 then B's r0..r3,
//               each vertex x, y, z. Missing bytes read as 0, extra bytes are ignored.
//   structured  byte 1: base pair (index into kBases below, mod its size); then operations of
//               4 bytes each [op, a, b, c], applied in order (a trailing partial one is ignored):
//     op % 6 == 0  ulp nudge: coordinate a % 24 moves by int16(b | c << 8) ulps (nextafter);
//     op % 6 == 1  scale every coordinate by 2^e, e = int16(a | b << 8) clamped to [-1100, 1100];
//     op % 6 == 2  translate: axis a % 3 of A (a/3 % 3 == 0), B (1) or both (2) by
//                  int8(b) * 2^int8(c);
//     op % 6 == 3  copy coordinate b % 24 into coordinate a % 24 (exact coincidences);
//     op % 6 == 4  swap A and B;
//     op % 6 == 5  permute the vertices of A (a even) or B (a odd): swap vertices b % 4, c % 4.
//   The structured mode reaches near-degenerate and extreme-scale cases from a few bytes: a
//   known pair plus perturbations of a few ulps, power-of-two scales (exact), translations.
//
// Exact comparison: every PDD_FUZZ_EXACT_EVERY-th input (environment; default 256 under
// libFuzzer, 1 = every input, which the replay test uses), or when header bit 7 is set.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>

#include "pdd/pdd.h"
#include "pdd/reference/relative_error.h"  // exact |fast - exact| / |exact|
#include "pdd/reference/solve_exact.h"
#include "pdd/rejection.h"

namespace {

using pdd::TetPair;
using pdd::TetVertices;

// Base pairs of the structured mode: the reproductions of known trouble first, then smoke.json.
struct Base {
  const char* name;
  TetVertices A, B;
};
const Base kBases[] = {
    {"needle",
     {{{0, 0, 0}, {9, 0, 9}, {1.0000000000000002, 1, 1}, {1, 1, 1}}},
     {{{0, -10, 0}, {0, 0, 0}, {0, 0, 0.3}, {0.01, 1, 0}}}},
    {"sliver",
     {{{9, 5, 9}, {0, 9, 0}, {1, 1, 1}, {1.0000000000000002, 1, 1}}},
     {{{2.333, 4, 2.333}, {5.333, 4, 2.333}, {2.333, 7, 2.333}, {2.333, 4, 5.333}}}},
    {"nested-1",
     {{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}}},
     {{{2, 2, 2}, {2.5, 2, 2}, {2, 2.5, 2}, {2, 2, 2.5}}}},
    {"poke-vertex-through-face",
     {{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}}},
     {{{1, 1, -1}, {3, 1, -1}, {1, 3, -1}, {1.5, 1.5, 0.5}}}},
    {"random-1",
     {{{1.2, 3.4, 0.5}, {7.9, 2.2, 4.4}, {3.3, 8.1, 2.7}, {4.6, 4.0, 9.3}}},
     {{{5.0, 1.0, 6.0}, {2.0, 6.5, 5.5}, {6.2, 7.4, 1.1}, {0.7, 2.9, 7.8}}}},
    {"parallel-edges-1",
     {{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}}},
     {{{1, 0.5, 0.5}, {3, 0.5, 0.5}, {1, 2.5, 1}, {1, 1, 3}}}},
    {"touching-face-1",
     {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
     {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}}}},
    {"identical",
     {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
     {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}},
};
constexpr size_t kNumBases = sizeof(kBases) / sizeof(kBases[0]);

double& coord(TetPair& p, unsigned k) {  // k in 0..23: A then B, vertex-major
  k %= 24;
  TetVertices& t = k < 12 ? p.A : p.B;
  return t[(k % 12) / 3][k % 3];
}

TetPair decode(const uint8_t* data, size_t size, bool& force_exact) {
  TetPair p;
  p.name = "fuzz";
  force_exact = size > 0 && (data[0] & 0x80);
  const unsigned mode = size > 0 ? data[0] & 3 : 0;
  if (mode == 0) {
    uint8_t raw[192] = {};
    std::memcpy(raw, data + (size > 0), std::min<size_t>(size > 0 ? size - 1 : 0, 192));
    for (unsigned k = 0; k < 24; ++k) {
      uint64_t bits = 0;
      for (int i = 7; i >= 0; --i) bits = bits << 8 | raw[8 * k + i];
      std::memcpy(&coord(p, k), &bits, 8);
    }
    return p;
  }
  const Base& base = kBases[size > 1 ? data[1] % kNumBases : 0];
  p.name = base.name;
  p.A = base.A;
  p.B = base.B;
  for (size_t i = 2; i + 4 <= size; i += 4) {
    const uint8_t op = data[i], a = data[i + 1], b = data[i + 2], c = data[i + 3];
    switch (op % 6) {
      case 0: {
        double& x = coord(p, a);
        const int n = int16_t(uint16_t(b | c << 8));
        const double to = n < 0 ? -std::numeric_limits<double>::infinity()
                                : std::numeric_limits<double>::infinity();
        for (int s = 0; s < std::abs(n); ++s) x = std::nextafter(x, to);
        break;
      }
      case 1: {
        int e = int16_t(uint16_t(a | b << 8));
        e = std::max(-1100, std::min(1100, e));
        for (unsigned k = 0; k < 24; ++k) coord(p, k) = std::ldexp(coord(p, k), e);
        break;
      }
      case 2: {
        const double d = std::ldexp(double(int8_t(b)), int8_t(c));
        const unsigned axis = a % 3, which = a / 3 % 3;
        for (int v = 0; v < 4; ++v) {
          if (which != 1) p.A[v][axis] += d;
          if (which != 0) p.B[v][axis] += d;
        }
        break;
      }
      case 3: coord(p, a) = coord(p, b); break;
      case 4: std::swap(p.A, p.B); break;
      case 5: std::swap((a % 2 ? p.B : p.A)[b % 4], (a % 2 ? p.B : p.A)[c % 4]); break;
    }
  }
  return p;
}

std::string describe(const TetPair& p) {
  std::ostringstream os;
  os.precision(17);
  os << "pair " << p.name << "\n  A:";
  for (const auto& v : p.A) os << " [" << v[0] << ", " << v[1] << ", " << v[2] << "]";
  os << "\n  B:";
  for (const auto& v : p.B) os << " [" << v[0] << ", " << v[1] << ", " << v[2] << "]";
  return os.str();
}

const pdd::PairResult<double>* g_fast = nullptr;  // the result under test, for fail()

[[noreturn]] void fail(const TetPair& p, const std::string& what) {
  std::ostringstream os;
  os.precision(17);
  if (g_fast && g_fast->error) os << "\n  fast: error " << *g_fast->error;
  if (g_fast && !g_fast->error) {
    const auto& r = *g_fast;
    os << "\n  fast: intersecting " << r.intersecting << ", rigid_pd2 " << r.rigid_pd2 << ", eq11_pd2 "
       << r.eq11_pd2 << ", pdd2_static " << r.pdd2_static << ", pdd2 " << r.pdd2 << ", pdd2_relaxed "
       << r.pdd2_relaxed << ", pdd2_accel1 " << r.pdd2_accel1 << ", pdd2_accel6 " << r.pdd2_accel6;
  }
  std::fprintf(stderr, "fuzz_fast_engine: %s\n%s%s\n", what.c_str(), describe(p).c_str(), os.str().c_str());
  std::abort();
}

std::array<double, 7> values(const pdd::PairResult<double>& r) {
  return {r.rigid_pd2, r.eq11_pd2, r.pdd2_static, r.pdd2, r.pdd2_relaxed, r.pdd2_accel1,
          r.pdd2_accel6};
}

bool finite_input(const TetPair& p) {
  for (const auto* t : {&p.A, &p.B})
    for (const auto& v : *t)
      for (double x : v)
        if (!std::isfinite(x)) return false;
  return true;
}

// Slack of the definitions §5 inequalities as the fast engine reports them. definitions §8 lets
// each reported value v be off its exact value by 1e-9 relative: |v - x| <= eps x, eps = 1e-9. If
// x_a <= x_b holds exactly, then v_a <= (1 + eps) x_a <= (1 + eps) x_b <= (1 + eps) / (1 - eps)
// v_b. So the only slack definitions §8 grants is v_a <= v_b (1 + eps) / (1 - eps) = v_b (1 + 2 eps
// + O(eps^2)): 1e-9 on each side, both sides wrong in opposite directions. A tighter check (1e-9 in
// total) could flag a correct engine. The test's own rounding (one multiply, 2^-53 relative) is
// negligible against it; the halving in pdd2 <= PD^2 / 2 is exact.
constexpr double kEps = 1e-9;
constexpr double kSlack = (1 + kEps) / (1 - kEps) * (1 + 1e-15);

void check_le(const TetPair& p, const char* lhs, double a, const char* rhs, double b) {
  if (!(a <= b * kSlack)) {
    std::ostringstream os;
    os.precision(17);
    os << "inequality of docs/definitions.md §5 violated beyond the accuracy contract's slack: " << lhs
       << " = " << a << " > " << rhs
       << " = " << b << " (ratio - 1 = " << a / b - 1 << ")";
    fail(p, os.str());
  }
}

// ---------------------------------------------------------------------------------------------
// EXACT ENGINE HOOK. The exact answer the fast result is judged against. Today: the reference
// engine (exact rationals, reduced formulation, ~70 ms per pair in Release). When fast/ gains its
// own exact path (a function of pdd::fast that runs the engine's slow exact fallback on every
// value), switch here: either replace the call, or keep both and compare the two exact answers
// with each other (they must be equal) as well as the double one against them.
// The hot functions over raw tetrahedra (pdd.h: rigid_superset, and deformable_depth.cpp's
// lane sweeps pruned by qp_lower_bound.h, not solve_pair's candidate set): each is certified on
// its own (definitions §8), so each is within 1e-9 (1 + 1e-9) of the exact value, as solve_pair's
// is: the two differ by < 2.1e-9 relative, and are 0 together.
void check_hot(const TetPair& p, const pdd::PairResult<double>& r) {
  // the decision alone (pdd.h: rigid_pd2(A, B).pd2 > 0, NaN counted as intersecting; false for a
  // rejected pair), and solve_pair's decision where it has a record
  const bool decided = pdd::fast::interiors_intersect(p.A, p.B);
  const pdd::fast::Depth rigid = pdd::fast::rigid_pd2(p.A, p.B);
  const bool want = rigid.status != pdd::fast::DepthStatus::Rejected && !(rigid.pd2 <= 0);
  if (decided != want || (!r.error && decided != r.intersecting))
    fail(p, std::string("interiors_intersect gives ") + (decided ? "true" : "false") + ", rigid_pd2 " +
                std::to_string(rigid.pd2) + " (status " + std::to_string(int(rigid.status)) + "), solve_pair " +
                (r.error ? *r.error : r.intersecting ? "intersecting" : "not intersecting"));
  if (r.error) {  // rejected (flat, non-finite): no hot path may give a number that reads as a depth
    if (r.error->rfind("not representable", 0) == 0) return;  // some value only: others may be had
    for (const pdd::fast::Depth d : {pdd::fast::rigid_pd2(p.A, p.B), pdd::fast::pdd2(p.A, p.B)})
      if (d.status == pdd::fast::DepthStatus::Ok || !std::isnan(d.pd2))
        fail(p, "a pair solve_pair rejects has a hot-path value " + std::to_string(d.pd2));
    return;
  }
  const pdd::fast::Depth hot[4] = {pdd::fast::rigid_pd2(p.A, p.B), pdd::fast::pdd2_static(p.A, p.B),
                                   pdd::fast::pdd2(p.A, p.B), pdd::fast::pdd2_relaxed(p.A, p.B)};
  const double ref[4] = {r.rigid_pd2, r.pdd2_static, r.pdd2, r.pdd2_relaxed};
  const char* names[4] = {"rigid_pd2", "pdd2_static", "pdd2", "pdd2_relaxed"};
  for (int i = 0; i < 4; ++i)
    if (hot[i].status != pdd::fast::DepthStatus::Ok || !(std::fabs(hot[i].pd2 - ref[i]) <= 2.1e-9 * ref[i])) {
      std::ostringstream os;
      os.precision(17);
      os << "accuracy contract: the hot " << names[i] << "(A, B) gives " << hot[i].pd2 << " (status "
         << int(hot[i].status) << "), solve_pair " << ref[i];
      fail(p, os.str());
    }
  // rigid_pd2 with its label and pdd2_accel(A, B, 1) are the record's bit for bit (pdd.h: the
  // record takes the same certified routes; neither is ever lowered by its relations).
  const pdd::fast::Depth accel1 = pdd::fast::pdd2_accel(p.A, p.B, 1);
  if (std::memcmp(&hot[0].pd2, &r.rigid_pd2, sizeof(double)) != 0 || hot[0].dir != r.rigid_dir ||
      accel1.status != pdd::fast::DepthStatus::Ok || std::memcmp(&accel1.pd2, &r.pdd2_accel1, sizeof(double)) != 0) {
    std::ostringstream os;
    os.precision(17);
    os << "the hot rigid_pd2 " << hot[0].pd2 << " " << (hot[0].dir ? hot[0].dir->str() : "-") << " and pdd2_accel1 "
       << accel1.pd2 << " are not the record's " << r.rigid_pd2 << " " << (r.rigid_dir ? r.rigid_dir->str() : "-")
       << " and " << r.pdd2_accel1;
    fail(p, os.str());
  }
}

pdd::reference::ExactResult exact_answer(const TetPair& p) {
  pdd::reference::GlobalOptions budget;
  // definitions §9's patches below the doubles' grid cost ~100 ms each under ASan + UBSan +
  // coverage (~2 ms in Release); the default budget (1000) made the fuzzer time out (60 s) on pairs
  // that do not close. 50 of them: the fast value is judged against a wider (still proved)
  // interval.
  budget.max_exact_patches = 50;
  // The same for bound (Q)'s exact QPs (global_pdd.h; the far-vertex pairs need up to ~120).
  budget.max_hull_bounds = 50;
  return pdd::reference::solve_exact(p, {}, budget);
}
// ---------------------------------------------------------------------------------------------

// Whether an exact value has a normal double near it (definitions §8: otherwise the fast engine
// must reject the pair, and may).
bool representable(const pdd::reference::Rational& x) {
  if (x == 0) return true;
  const double d = CGAL::to_double(x);
  return std::isfinite(d) && std::fabs(d) >= std::numeric_limits<double>::min();
}

void compare_with_exact(const TetPair& p, const pdd::PairResult<double>& fast) {
  const pdd::reference::ExactResult exact = exact_answer(p);
  if (exact.error) {
    if (!fast.error) fail(p, "the exact engine rejects the pair, the fast one does not: " + *exact.error);
    return;
  }
  const std::array<pdd::reference::Rational, 7> xs = {
      exact.rigid_pd2, exact.eq11_pd2,     exact.pdd2_static, exact.pdd2,
      exact.pdd2_relaxed, exact.pdd2_accel1, exact.pdd2_accel6};
  if (!fast.error && fast.pdd2_global_error && *fast.pdd2_global_error == pdd::kGlobalNotRepresentable) {
    // Allowed only where a double normal's rounding (u R at a vertex R away) can exceed 1e-9 of
    // the depth: the exact relaxed value below 1e-14 of the extent squared (R: the largest
    // |x - s0| coordinate, exactly).
    pdd::reference::Rational R = 0;
    for (const auto* t : {&p.A, &p.B})
      for (const auto& v : *t)
        for (int k = 0; k < 3; ++k) {
          pdd::reference::Rational d = pdd::reference::Rational(v[k]) - pdd::reference::Rational(p.A[0][k]);
          if (d < 0) d = -d;
          if (d > R) R = d;
        }
    const pdd::reference::Rational tiny(1e-14);
    if (!exact.intersecting || !(exact.pdd2_relaxed < tiny * R * R))
      fail(p, "the fast engine declines pdd2_global where the depth is within the resolution of "
              "the extent: " + *fast.pdd2_global_error);
  }
  if (fast.error) {
    bool all_representable = true;
    for (const auto& x : xs) all_representable = all_representable && representable(x);
    if (all_representable)
      fail(p, "the fast engine rejects a pair whose exact results are all normal doubles: " +
                  *fast.error);
    return;
  }
  if (fast.intersecting != exact.intersecting)
    fail(p, std::string("intersecting: fast ") + (fast.intersecting ? "true" : "false") +
                ", exact " + (exact.intersecting ? "true" : "false"));
  // definitions §9: inside the exact engine's proved interval [lower, witness], with §8's 1e-9.
  if (!fast.pdd2_global_error && exact.intersecting && exact.pdd2_global_lower) {
    const pdd::reference::Rational g(fast.pdd2_global), e(kEps);
    if (!(g >= *exact.pdd2_global_lower * (1 - e) && g <= exact.pdd2_global * (1 + e))) {
      std::ostringstream os;
      os.precision(17);
      os << "pdd2_global fast " << fast.pdd2_global << " outside the exact interval ["
         << CGAL::to_double(*exact.pdd2_global_lower) << ", " << CGAL::to_double(exact.pdd2_global) << "]";
      fail(p, os.str());
    }
  }
  const auto vs = values(fast);
  for (size_t i = 0; i < 7; ++i) {
    // relative_error is exact: 0 when both are 0, +inf when only the exact value is 0, 1 when
    // only the fast value is 0; so "<= 1e-9" also checks "0 exactly when the exact value is 0".
    const double rel = pdd::reference::relative_error(vs[i], xs[i]);
    if (!(rel <= kEps)) {
      std::ostringstream os;
      os.precision(17);
      os << "accuracy contract: " << pdd::kValueKeys[i] << " fast " << vs[i] << ", exact "
         << pdd::reference::to_string(xs[i]) << " (~" << CGAL::to_double(xs[i])
         << "), relative error " << rel;
      fail(p, os.str());
    }
  }
}

long exact_every() {
  static const long n = [] {
    const char* s = std::getenv("PDD_FUZZ_EXACT_EVERY");
    const long v = s ? std::atol(s) : 256;
    return v > 0 ? v : 0;  // 0: never (unless the header asks)
  }();
  return n;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static unsigned long count = 0;
  bool force_exact = false;
  const TetPair p = decode(data, size, force_exact);
  const pdd::PairResult<double> r = pdd::fast::solve_pair(p);
  g_fast = &r;

  // The exact comparison first when it is due: its verdict (definitions §8) is the most
  // informative.
  const long every = exact_every();
  if (force_exact || (every > 0 && count++ % every == 0)) compare_with_exact(p, r);

  if (!finite_input(p) && !r.error) fail(p, "a non-finite coordinate is not rejected");
  check_hot(p, r);
  if (!r.error) {
    const auto vs = values(r);
    for (size_t i = 0; i < 7; ++i) {
      const double v = vs[i];
      if (std::isnan(v) || v < 0 || !(v == 0 || std::isnormal(v)))
        fail(p, std::string("output record / accuracy contract: ") + pdd::kValueKeys[i] + " = " +
                    std::to_string(v) + " is NaN, negative, infinite or subnormal");
    }
    for (const auto* q : {&r.q1_A, &r.q1_B})
      for (const auto& v : *q)
        for (double x : v)
          if (!std::isfinite(x)) fail(p, "a deformed position is not finite");
    if (!r.intersecting) {
      for (size_t i = 0; i < 7; ++i)
        if (vs[i] != 0) fail(p, std::string("not intersecting but ") + pdd::kValueKeys[i] + " != 0");
      if (r.rigid_dir || r.pdd2_static_dir || r.pdd2_dir || r.pdd2_relaxed_dir)
        fail(p, "not intersecting but a label is set");
      if (std::memcmp(&r.q1_A, &p.A, sizeof p.A) || std::memcmp(&r.q1_B, &p.B, sizeof p.B))
        fail(p, "not intersecting but q1 is not the rest pose");
      if (r.pdd2_global != 0 || r.pdd2_global_normal)
        fail(p, "not intersecting but pdd2_global or its normal is set");
    } else {
      if (!(r.rigid_pd2 > 0 && r.pdd2 > 0 && r.pdd2_static > 0 && r.pdd2_relaxed > 0))
        fail(p, "intersecting but a depth is 0");
      if (!r.rigid_dir || !r.pdd2_dir || !r.pdd2_relaxed_dir)
        fail(p, "intersecting but a label is missing");
      // definitions §5: pdd2 <= pdd2_static <= PD^2; pdd2 <= PD^2 / 2;
      //          pdd2_relaxed <= pdd2 <= pdd2_accel6 <= pdd2_accel1.
      check_le(p, "pdd2", r.pdd2, "pdd2_static", r.pdd2_static);
      check_le(p, "pdd2_static", r.pdd2_static, "rigid_pd2", r.rigid_pd2);
      check_le(p, "pdd2", r.pdd2, "rigid_pd2/2", r.rigid_pd2 / 2);
      check_le(p, "pdd2_relaxed", r.pdd2_relaxed, "pdd2", r.pdd2);
      check_le(p, "pdd2", r.pdd2, "pdd2_accel6", r.pdd2_accel6);
      check_le(p, "pdd2_accel6", r.pdd2_accel6, "pdd2_accel1", r.pdd2_accel1);
      // definitions §9: 0 < pdd2_global <= pdd2_relaxed, a non-zero finite normal, finite
      // positions; or, declined (pdd2_global_error), NaN value and positions and no normal
      if (r.pdd2_global_error) {
        if (!std::isnan(r.pdd2_global) || r.pdd2_global_normal || !std::isnan(r.q1_A_global[0][0]))
          fail(p, "pdd2_global declined but its value, normal or positions are set");
      } else if (!(r.pdd2_global > 0) || !std::isnormal(r.pdd2_global))
        fail(p, "intersecting but pdd2_global is 0 or not a normal double");
      if (!r.pdd2_global_error) check_le(p, "pdd2_global", r.pdd2_global, "pdd2_relaxed", r.pdd2_relaxed);
      if (!r.pdd2_global_error && !r.pdd2_global_normal) {
        fail(p, "intersecting but pdd2_global_normal is null");
      } else if (r.pdd2_global_normal) {
        const auto& n = *r.pdd2_global_normal;
        if (!(std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2])) ||
            (n[0] == 0 && n[1] == 0 && n[2] == 0))
          fail(p, "pdd2_global_normal is zero or not finite");
      }
      for (const auto* q : {&r.q1_A_global, &r.q1_B_global})
        for (const auto& v : *q)
          for (double x : v)
            if (!r.pdd2_global_error && !std::isfinite(x)) fail(p, "a deformed position of pdd2_global is not finite");
    }
  }

  g_fast = nullptr;
  return 0;
}
