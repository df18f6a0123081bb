// refine.h — internal to fast/src: when a minimum over candidates cannot be certified in doubles
// (definitions §8, value_bounds.h), evaluate exactly only the candidates that can still be the
// minimum ("contenders") instead of the whole pair on the exact path.
//
// Input:  a candidate list (CandidateSet or QuickCandidates, which know their pair), for each
//         candidate i a certified lower bound lo(i) of its exact value (value_bounds.h; +inf for
//         a candidate that is not in the family, e.g. infeasible), and hi, a certified upper
//         bound of the exact value of one candidate of the family (the double path's choice).
// Output: the exact minimum over the family, rounded once (exact_candidate.h), with the label of
//         the first candidate in canonical order attaining it — the exact path's value and
//         label, bit for bit — and certified = refined = true; or false (nothing changed) when
//         there are more than kMaxRefined contenders or the value is not a normal double.
//
// Why it is the exact minimum (proof). Let x* be the exact minimum over the family. The choice's
// exact value is >= x* and <= hi, so x* <= hi. Every candidate j with exact value <= x* has
// lo(j) <= x* <= hi, so it is a contender: the exact minimisers, and all exact ties with them,
// are among the contenders, and every other candidate's exact value is > x*. The minimum over
// the contenders, first in canonical order among equals (indices ascend), is therefore the
// family's, with the exact path's tie rule (canonical order).
// Cost: a few exact candidates (~10–30 µs each) on the rare pairs that need it (shallow
// contacts whose double error bound exceeds 1e-9 relative), instead of the whole exact path.
#pragma once

#include <algorithm>
#include <limits>
#include <optional>

#include "exact/exact_candidate.h"
#include "kernel/candidate_directions.h"
#include "certification/tie_tolerance.h"
#include "certification/value_bounds.h"
#include "kernel/rigid_depth.h"

namespace pdd::fast::detail {

inline constexpr int kMaxRefined = 8;  // more contenders: the whole exact path is as cheap

// The contenders {i : !(lo(i) > hi)} (NaN counts as a contender) in canonical order; false
// when there are more than kMaxRefined.
template <class List, class Lo>
bool contenders(const List& s, Lo lo, double hi, int* idx, int& m) {
  m = 0;
  for (int i = 0; i < s.count; ++i)
    if (!(lo(i) > hi)) {
      if (m == kMaxRefined) return false;
      idx[m++] = i;
    }
  return m > 0;
}

// `exact_value(c, q)`: the family's exact value of candidate c into q; false when c is not in
// the family (e.g. an undecidable EE direction in case 1).
template <class List, class Lo, class ExactValue>
bool refine_minimum(const List& s, Lo lo, double hi, ExactValue exact_value, Choice& ch) {
  int idx[kMaxRefined], m = 0;
  if (!s.A || !contenders(s, lo, hi, idx, m)) return false;
  const ExactFrame f = exact_frame(*s.A, *s.B);
  Q best, v;
  int bi = -1;
  for (int j = 0; j < m; ++j) {
    const ExactCandidate c = exact_candidate(f, unpack_label(label_code(s, idx[j])));
    if (!exact_value(c, v)) continue;
    if (bi < 0 || v < best) {
      best = v;
      bi = idx[j];
    }
  }
  if (bi < 0) return false;
  bool ok = true;
  const double d = rounded_value(unscaled(f, best, 2), ok);
  if (!ok || !(d > 0.0)) return false;
  ch.value = d;
  ch.index = bi;
  ch.code = label_code(s, bi);
  ch.certified = ch.refined = ch.exact_first = true;  // (every contender's exact value compared)
  return true;
}

// A minimum the double bounds could not certify, certified on tighter intervals: after
// refine_minimum declines (more than kMaxRefined contenders), or first (rigid_pd2,
// rigid_depth.cpp: the contenders of a shallow contact certify on compensated heights at a
// fraction of the rationals' cost; its value is then within definitions §8 of the exact one,
// not its correctly rounded double).
// Input:  lo and hi as for refine_minimum; `interval(i, v, r)`: candidate i's value v and root
//         bound r (value_bounds.h: its exact value lies in [lower_of(v, r), upper_of(v, r)]),
//         false when i is not in the family (the callers give compensated_heights.h's where
//         they apply: heights within u of themselves plus a u^2 term, where the engine's
//         doubles carry u L^3; else the double one); `exact_value` as for refine_minimum;
//         `tie_order(c, n)`: for candidate indices c[0..n) ascending in canonical order, the
//         position of the first exact minimum, or -1 when the caller cannot tell.
// Output: the choice (value, label), certified = refined = true; or false, ch unchanged.
// Method and proof. The candidates with lo(i) <= hi, by ascending lo(i), take their interval
// until the next lo(i) exceeds H, the least upper bound so far (the rest cannot be least: their
// exact values exceed H >= x*, the exact minimum). Where an interval reaching H is still too
// wide to certify (a parallel edge pair, a margin within its bound), the exact value is taken,
// at most kMaxRefined of them, rounded once (within 2^-52 of it). So x* lies in [lo_min, H],
// lo_min the least lower bound over every candidate; the choice, the least value (the first in
// canonical order among equal ones), is certified when its interval and lo_min pass
// certified_choice: its value and its label's exact value are then within the contract of x*.
// Near ties (another interval reaching below the choice's upper bound) may each be the exact
// minimum and each is within the contract of it (definitions §8 lets either side be named):
// tie_order orders them exactly where it can, so the label is the exact engine's; else the
// first in canonical order is named, the exact engine's too when the tie is exact.
// The pairs that need it: contacts made by rounding (a grid against its copy shifted by a
// non-dyadic offset: faces that coincide in exact arithmetic overlap by ~1e-17 of the size
// once the shifted coordinates are rounded), where no double value has a correct digit: ~20
// compensated candidates instead of the whole exact path (~0.5 ms).
template <class List, class Lo, class Interval, class ExactValue, class TieOrder>
bool refine_tight(const List& s, Lo lo, double hi, Interval interval, ExactValue exact_value, TieOrder tie_order,
                  Choice& ch) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!s.A) return false;
  // The candidates by ascending lower bound (equal ones in canonical order); each takes its
  // tight interval until the next lower bound exceeds H (the least upper bound so far): the rest
  // cannot be least. On aligned pairs nearly every candidate has lo(i) <= hi and only the first
  // few are taken, so the least is taken first (one scan), and only the candidates whose lower
  // bound is within its upper bound are then ordered (sorting all ~50 cost more than the
  // intervals): the others cannot be reached, since H only decreases.
  struct Key {  // a candidate's lower bound x and index i
    double x;
    int i;
  };
  Key keys[kMaxCandidates];
  int count = 0;
  double lo_min = kInf;  // lo_min: first over the candidates above hi
  for (int i = 0; i < s.count; ++i) {
    const double y = lo(i), x = y >= 0.0 ? y : 0.0;  // (NaN: no bound)
    if (x > hi) {
      lo_min = x < lo_min ? x : lo_min;
      continue;
    }
    keys[count++] = {x, i};
  }
  if (count == 0) return false;
  int idx[kMaxCandidates];
  double v[kMaxCandidates], lower[kMaxCandidates], upper[kMaxCandidates], H = kInf;
  int n = 0;
  auto take = [&](int i) {  // candidate i's interval as the n-th taken; H updated
    idx[n] = i;
    double r = kInf;
    if (!interval(i, v[n], r)) {
      v[n] = lower[n] = upper[n] = kInf;  // not in the family
    } else {
      lower[n] = r < 1 ? lower_of(v[n], r) : 0.0;
      upper[n] = r < 1 ? upper_of(v[n], r) : kInf;
      if (!(lower[n] >= 0.0)) lower[n] = 0.0;  // (NaN)
      if (!(upper[n] >= lower[n])) upper[n] = v[n] = kInf;  // (NaN: no value; its exact one is due)
      H = upper[n] < H ? upper[n] : H;
    }
    ++n;
  };
  int first = 0;
  for (int j = 1; j < count; ++j) first = keys[j].x < keys[first].x ? j : first;  // (ties: the earlier)
  take(keys[first].i);
  // the others with x <= H, ascending (keys are in canonical order: insertion keeps ties so)
  Key near[kMaxCandidates];
  int q = 0;
  double beyond = kInf;  // the least lower bound left out
  for (int j = 0; j < count; ++j) {
    if (j == first) continue;
    const Key k = keys[j];
    if (k.x > H) {
      beyond = k.x < beyond ? k.x : beyond;
      continue;
    }
    int t = q++;
    for (; t > 0 && k.x < near[t - 1].x; --t) near[t] = near[t - 1];
    near[t] = k;
  }
  int r = 0;
  for (; r < q && !(near[r].x > H); ++r) take(near[r].i);
  if (r < q) beyond = near[r].x < beyond ? near[r].x : beyond;
  lo_min = beyond < lo_min ? beyond : lo_min;  // the least not reached
  const int m = n;
  int exact = 0;
  std::optional<ExactFrame> f;
  // contender j exactly (rounded once: within 2^-52 of it)
  auto take_exact = [&](int j) {
    if (!f) f = exact_frame(*s.A, *s.B);
    Q x;
    if (!exact_value(exact_candidate(*f, unpack_label(label_code(s, idx[j]))), x)) {
      v[j] = lower[j] = upper[j] = kInf;  // not in the family
      return true;
    }
    bool ok = true;
    const double d = rounded_value(unscaled(*f, x, 2), ok);
    if (!ok) return false;
    v[j] = d, lower[j] = d * (1 - 0x1p-52), upper[j] = d * (1 + 0x1p-52);
    return true;
  };
  for (int j = 0; j < m; ++j)
    if (lower[j] <= H && !certified_choice(upper[j], lower[j]) && (exact++ == kMaxRefined || !take_exact(j)))
      return false;
  int b = 0;  // the first least value in canonical order (the intervals are tight: no tie band)
  for (int j = 1; j < m; ++j) b = v[j] < v[b] || (v[j] == v[b] && idx[j] < idx[b]) ? j : b;
  if (!(v[b] > 0.0) || !(v[b] < kInf)) return false;
  for (int j = 0; j < m; ++j) lo_min = lower[j] < lo_min ? lower[j] : lo_min;
  if (!certified_choice(upper[b], lo_min)) return false;
  // near ties (above): ordered by tie_order, else the first in canonical order
  // Every exact minimiser is among the ties: its exact value x* <= H <= upper[b] puts it, and
  // each candidate exactly equal to it, in the ties (lower <= x*), and its lo <= x* <= H had it
  // reached above. One tie, or the tie order's first kept: the exact engine's choice.
  int ties[kMaxCandidates], cand[kMaxCandidates], t = 0;
  for (int j = 0; j < m; ++j)
    if (lower[j] <= upper[b] && v[j] < kInf) ties[t++] = j;
  bool exact_first = t == 1;
  if (t > 1) {
    std::sort(ties, ties + t, [&idx](int x, int y) { return idx[x] < idx[y]; });
    for (int k = 0; k < t; ++k) cand[k] = idx[ties[k]];
    const int first = tie_order(cand, t), w = ties[first >= 0 ? first : 0];
    if (certified_choice(upper[w], lo_min)) b = w, exact_first = first >= 0;  // (its interval within the contract too)
  }
  ch.value = v[b];
  ch.index = idx[b];
  ch.code = label_code(s, idx[b]);
  ch.certified = ch.refined = true;
  ch.exact_first = exact_first;
  return true;
}

}  // namespace pdd::fast::detail
