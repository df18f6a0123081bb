// integer_normals.cpp — see integer_normals.h.
#include "global/integer_normals.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace pdd::fast::global {
namespace {

// Run-time dispatch on x86-64 with GCC, as superset_kernel.cpp (integer operations only: every
// clone returns the same tries).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PDD_TRIES_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define PDD_TRIES_CLONES
#endif

// The loop's screen: of the n tries j0 .. j0 + n − 1 (n a multiple of 16), those whose metric
// may be below the loop's current worst, in increasing j, into out (returns how many). F0, F1:
// the fractional parts at try j0 (64-bit fixed point); each step subtracts A0, A1 (mod 2^64),
// as the loop does. The test is on integers, four tries a vector: with s_t the part read as a
// signed 64-bit integer and h_t = s_t >> 32 where s_t >= 0, (−s_t − 1) >> 32 (its bits
// complemented) where s_t < 0, so that h_t 2^32 <= |s_t| (below 2^31 either way), the loop's
// d_t = |double(s_t)| >= h_t 2^32 (a double, and rounding is monotone), so its metric
// fl(fl(d0 d0) + fl(d1 d1)) >= (h0² + h1²) 2^64 (1 − u)² >= (h0 + h1)² 2^63 (1 − u)². The caller's
// S (screen_bound) has (S + 1)² 2^63 (1 − u)² > worst, so a try with h0 + h1 > S has metric >
// worst: the loop's consider keeps nothing of it (it keeps metric < worst), and skipping it
// changes no output. A sum and a compare a try instead of a square: passes are rare once
// `keep` tries are kept, and each one passed is decided by consider.
PDD_TRIES_CLONES int may_improve(std::uint64_t F0, std::uint64_t F1, std::uint64_t A0, std::uint64_t A1, int j0,
                                 int n, std::int64_t S, int* out) {
  typedef std::uint64_t u4 __attribute__((vector_size(32)));
  typedef std::int64_t i4 __attribute__((vector_size(32)));
  u4 f0 = {F0, F0 - A0, F0 - 2 * A0, F0 - 3 * A0}, f1 = {F1, F1 - A1, F1 - 2 * A1, F1 - 3 * A1};
  const u4 step0 = u4{} + 4 * A0, step1 = u4{} + 4 * A1;
  const i4 bound = i4{} + S;
  auto skip = [&](i4& skipped) {  // the four tries at f0, f1; then a step (an out-parameter: a
                                  // vector returned by value would change the default clone's ABI)
    const i4 s0 = i4(f0), s1 = i4(f1);
    const i4 h = i4((u4(s0 ^ (s0 < 0)) >> 32) + (u4(s1 ^ (s1 < 0)) >> 32));  // (s < 0: all ones)
    f0 -= step0, f1 -= step1;
    skipped = h > bound;
  };
  int m = 0;
  for (int i = 0; i < n; i += 16) {
    i4 p[4];
    for (i4& q : p) skip(q);
    const i4 all = p[0] & p[1] & p[2] & p[3];
    if ((all[0] & all[1] & all[2] & all[3]) == -1) continue;
    for (int g = 0; g < 4; ++g)
      for (int k = 0; k < 4; ++k)
        if (!p[g][k]) out[m++] = j0 + i + 4 * g + k;
  }
  return m;
}

// may_improve's S for the loop's current worst: x = sqrt(t2) (1 + 2^-40) rounded, t2 =
// fl(2^-63 worst (1 + 2^-48)), and S = floor(x), so that S + 1 > x >= sqrt(2^-63 worst) (1 + 2^-49)
// (each rounding within u): (S + 1)² 2^63 (1 − u)² > worst. No bound (every try passes) where x
// is not below 2^62 (h0 + h1 is at most 2^32).
std::int64_t screen_bound(double worst) {
  const double x = std::sqrt(worst * 0x1p-63 * (1 + 0x1p-48)) * (1 + 0x1p-40);
  return !(x < 0x1p62) ? std::numeric_limits<std::int64_t>::max() : std::int64_t(x);
}

// The window's tries where both fractional parts drift by little (a direction a rounding away
// from a coordinate plane or a diagonal: alpha_t within ~2^-19 of an integer, 2^18 tries),
// including a part that starts near a half at the window's first try (c0 alpha_t ~1/2 mod 1,
// as where alpha_t is an integer plus ~2^-54): each part's signed offset from its nearest
// integer is x_t - k_t 2^64 with x_t = s_t - j a_t (s_t, a_t: F_t and A_t read as signed 64-bit
// integers, x_t exact in 128 bits) and k_t the integer that puts it in [-2^63, 2^63). With
// tries |a_t| < 2^63, x_t spans less than 2^63 over the window, so k_t changes at most once
// (where x_t crosses +-2^63, the part crossing a half); on each of the (at most three) segments
// between such changes the metric sum_t (x_t - k_t 2^64)^2 is a convex quadratic in j, least at
// its vertex j* clamped to the segment. Its least values on a segment lie at the integers
// nearest j*; those, and each segment's first and last tries, are considered in increasing j by
// the loop's own `consider` (the same metric from the same integers, the same insertion): the
// same outputs wherever the quadratic's steps exceed the metric's rounding; where they do not
// (the whole window within a few roundings of one metric), the tries returned are as near y's
// direction as the loop's, to that rounding. False (the caller runs the loop over every try)
// otherwise.
template <class Consider>
bool slow_drift(const std::uint64_t (&F)[2], const std::uint64_t (&A)[2], int tries, int keep, Consider&& consider) {
  constexpr __int128 kHalf = __int128(1) << 63, kOne = __int128(1) << 64;
  __int128 s[2], a[2];
  for (int t = 0; t < 2; ++t) {
    s[t] = std::int64_t(F[t]), a[t] = std::int64_t(A[t]);
    if (__int128(tries) * (a[t] < 0 ? -a[t] : a[t]) >= kHalf) return false;
  }
  auto offset_integer = [&](int t, int j) -> __int128 {  // k_t at try j
    const __int128 x = s[t] - __int128(j) * a[t];
    return x >= kHalf ? 1 : x < -kHalf ? -1 : 0;
  };
  // the segments: k_t is monotone in j (x_t is), so its one change is found by bisection
  int ends[4] = {0, tries, tries, tries}, n_ends = 1;
  for (int t = 0; t < 2; ++t) {
    const __int128 k0 = offset_integer(t, 0);
    if (offset_integer(t, tries - 1) == k0) continue;
    int lo = 0, hi = tries - 1;  // k(lo) = k0, k(hi) != k0
    while (hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      (offset_integer(t, mid) == k0 ? lo : hi) = mid;
    }
    ends[n_ends++] = hi;
  }
  ends[n_ends++] = tries;
  if (n_ends == 4 && ends[1] > ends[2]) std::swap(ends[1], ends[2]);  // (the two changes in order)
  int js[3 * (4 * 8 + 2)], n = 0;  // (per segment: keep at each end, 2 keep + 2 about j*; keep <= 8)
  for (int e = 0; e + 1 < n_ends; ++e) {
    const int first = ends[e], last = ends[e + 1] - 1;
    if (first > last) continue;
    auto add = [&](int j) {
      if (j >= first && j <= last) js[n++] = j;
    };
    __int128 sk[2];
    for (int t = 0; t < 2; ++t) sk[t] = s[t] - offset_integer(t, first) * kOne;
    const long double sa = (long double)sk[0] * (long double)a[0] + (long double)sk[1] * (long double)a[1];
    const long double aa = (long double)(a[0] * a[0] + a[1] * a[1]);  // (each product below 2^126)
    long double vertex = aa > 0 ? sa / aa : first;
    vertex = std::clamp(vertex, (long double)first, (long double)last);
    const int j0 = int(vertex);
    for (int j = first; j < first + keep; ++j) add(j);
    for (int j = j0 - keep; j <= j0 + keep + 1; ++j) add(j);
    for (int j = last - keep + 1; j <= last; ++j) add(j);
  }
  std::sort(js, js + n);
  n = int(std::unique(js, js + n) - js);
  for (int i = 0; i < n; ++i) {
    double d[2];
    for (int t = 0; t < 2; ++t) d[t] = std::fabs(double(s[t] - __int128(js[i]) * a[t] - offset_integer(t, js[i]) * kOne));
    consider(js[i], d[0], d[1]);
  }
  return true;
}

// The tries in q interleaved classes j = q i + r (q = 2, 3, 4), where the step A_t is within a
// few roundings a multiple of 2^64 / q for both parts (alpha_t a rounding away from a multiple
// of 1/q: a direction across a cube's diagonal planes, alpha_t ~ 1/2, where the parts alternate
// between near an integer and near a half and slow_drift's single drift does not apply): class r
// starts at F - r A and steps by q A, slowly, so slow_drift finds its candidates (the least
// values of its metric, per segment); the union of the classes' candidates holds the least
// values over all the tries, and they are considered in increasing j with the loop's own
// metric (the part F - j A, exactly as the loop's wrapping steps give it). The same outputs as
// the loop where slow_drift's are, per class. False where no q applies (the caller's loop).
template <class Consider>
bool interleaved_drift(const std::uint64_t (&F)[2], const std::uint64_t (&A)[2], int tries, int keep,
                       Consider&& consider) {
  constexpr int kMaxPerClass = 3 * (4 * 8 + 2);  // slow_drift's bound (keep <= 8)
  for (std::uint64_t q = 2; q <= 4; ++q) {
    const std::uint64_t Aq[2] = {q * A[0], q * A[1]};  // (mod 2^64: the step of a class)
    int js[4 * kMaxPerClass], n = 0;
    bool all = true;
    for (std::uint64_t r = 0; r < q && all; ++r) {
      const int tries_r = int((std::uint64_t(tries) + q - 1 - r) / q);
      if (tries_r <= 0) continue;
      const std::uint64_t Fr[2] = {F[0] - r * A[0], F[1] - r * A[1]};
      all = slow_drift(Fr, Aq, tries_r, keep, [&](int i, double, double) { js[n++] = int(q) * i + int(r); });
    }
    if (!all) continue;
    std::sort(js, js + n);
    for (int i = 0; i < n; ++i) {
      const std::uint64_t j = std::uint64_t(js[i]);
      const std::uint64_t f0 = F[0] - j * A[0], f1 = F[1] - j * A[1];
      consider(js[i], std::fabs(double(std::int64_t(f0))), std::fabs(double(std::int64_t(f1))));
    }
    return true;
  }
  return false;
}

}  // namespace

// A double triple rounded from a unit vector misses y's direction by ~u, and along a generic
// direction (a contact not along a coordinate plane) the neighbouring doubles do no better; but
// the normal need not be a unit vector. With y_m its largest component and alpha_i = y_i / y_m
// (|alpha_i| <= 1), the triple c (alpha_0, alpha_1, alpha_2) with c an integer below 2^53 and the other two
// components rounded to integers is a double triple (every integer up to 2^53 is) whose
// direction misses y's by (frac distance of c alpha_i) / c: for the c among `tries` consecutive
// integers below 2^53 where both fractional parts are small (they are equidistributed: the best
// of M tries has both within ~1/sqrt(M)), that angle is ~1/sqrt(M) of a rounded unit vector's.
// The fractional parts are tracked in 64-bit fixed point (wrapping arithmetic is arithmetic mod
// 1): the first exactly, then minus alpha_i 2^64 rounded down per step, so after j steps they
// are off by < j 2^-64, beside the ~2^-9 that selects; the chosen triples' integers are then
// computed exactly. Only a search: each triple is evaluated exactly by the caller.
void integer_normals(const detail::Q (&y)[3], int tries, int keep, std::vector<V3>& out) {
  using detail::Q;
  int m = 0;
  for (int i = 1; i < 3; ++i)
    if (abs(y[i]) > abs(y[m])) m = i;
  if (sgn(y[m]) == 0) return;
  const int idx[2] = {(m + 1) % 3, (m + 2) % 3};
  const std::uint64_t c0 = (std::uint64_t(1) << 53) - 1;
  Q alpha[2];
  std::uint64_t A[2], F[2];
  for (int t = 0; t < 2; ++t) {
    alpha[t] = y[idx[t]] / y[m];
    auto frac64 = [&](unsigned long c) {  // floor(c alpha 2^64) mod 2^64
      mpz_class num = alpha[t].get_num() * c, q, r;
      mpz_mul_2exp(num.get_mpz_t(), num.get_mpz_t(), 64);
      mpz_fdiv_q(q.get_mpz_t(), num.get_mpz_t(), alpha[t].get_den_mpz_t());
      mpz_fdiv_r_2exp(r.get_mpz_t(), q.get_mpz_t(), 64);  // in [0, 2^64)
      return std::uint64_t(mpz_get_ui(r.get_mpz_t()));
    };
    A[t] = frac64(1), F[t] = frac64(static_cast<unsigned long>(c0));
  }
  // (metric, c), the `keep` best in increasing metric, a new one before equal ones. An array
  // with insertion in place: along a direction a rounding away from a coordinate plane or a
  // diagonal (a contact made by rounding), the fractional parts drift by ~1e-17 a try and
  // nearly every try improves on the last, so the insertion runs on most of the 2^18 tries.
  constexpr int kKeepMax = 8;
  keep = std::min(keep, kKeepMax);
  std::pair<double, std::uint64_t> top[kKeepMax];
  int kept = 0;
  // The distance to the nearest integer, times 2^64: f below 2^63, else 2^64 - f, as a double.
  // Read as a signed integer s (two's complement), that is |s| (2^63 for s = -2^63), and
  // round-to-nearest is symmetric, so |double(s)| is the same double: one signed conversion
  // (the unsigned one takes a branch and several instructions without AVX-512).
  auto dist = [](std::uint64_t f) { return std::fabs(double(std::int64_t(f))); };
  double worst = INFINITY;  // the largest kept metric once `keep` are kept (else +inf)
  auto consider = [&](int j, double d0, double d1) {
    const double metric = d0 * d0 + d1 * d1;
    if (metric < worst) {
      int i = kept < keep ? kept++ : keep - 1;  // (full: the last one goes)
      for (; i > 0 && top[i - 1].first >= metric; --i) top[i] = top[i - 1];
      top[i] = {metric, c0 - std::uint64_t(j)};
      if (kept == keep) worst = top[keep - 1].first;
    }
  };
  if (!slow_drift(F, A, tries, keep, consider) && !interleaved_drift(F, A, tries, keep, consider)) {
    // Every try in increasing j, its parts F - j A (mod 2^64: c -> c - 1 is mod 1), screened
    // in chunks by may_improve against the worst kept at the chunk's start (worst only falls,
    // and consider tests each passed try against the current one): the loop's outputs.
    constexpr int kChunk = 1024;
    int passed[kChunk];
    int j = 0;
    for (; j + 16 <= tries; j += kChunk) {
      const int n = std::min(kChunk, (tries - j) / 16 * 16);
      const std::uint64_t F0 = F[0] - std::uint64_t(j) * A[0], F1 = F[1] - std::uint64_t(j) * A[1];
      const int m = may_improve(F0, F1, A[0], A[1], j, n, screen_bound(worst), passed);
      for (int i = 0; i < m; ++i) {
        const std::uint64_t k = std::uint64_t(passed[i]);
        consider(passed[i], dist(F[0] - k * A[0]), dist(F[1] - k * A[1]));
      }
      if (n < kChunk) {
        j += n;
        break;
      }
    }
    for (; j < tries; ++j) consider(j, dist(F[0] - std::uint64_t(j) * A[0]), dist(F[1] - std::uint64_t(j) * A[1]));
  }
  const double s = sgn(y[m]) > 0 ? 1.0 : -1.0;
  for (int r = 0; r < kept; ++r) {
    const std::uint64_t c = top[r].second;
    V3 v;
    v[m] = s * double(c);
    for (int t = 0; t < 2; ++t) {  // round(c alpha) = floor((2 c num + den) / (2 den)), exactly
      mpz_class num = alpha[t].get_num(), den = alpha[t].get_den(), q;
      num *= static_cast<unsigned long>(c);
      num = 2 * num + den;
      den *= 2;
      mpz_fdiv_q(q.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
      v[idx[t]] = s * q.get_d();  // |q| <= c < 2^53: exact
    }
    out.push_back(v);
  }
}

}  // namespace pdd::fast::global
