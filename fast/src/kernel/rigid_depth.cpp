// rigid_depth.cpp — definitions §4. See the header.
#include "kernel/rigid_depth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "certification/certify.h"
#include "certification/refine.h"
#include "certification/tight_delta.h"
#include "certification/value_bounds.h"
#include "exact/exact_predicates.h"
#include "exact/integer_depth.h"
#include "hot_path.h"
#include "kernel/pair_memo.h"

#include "certification/tie_tolerance.h"
#include "kernel/superset_depth.h"

namespace pdd::fast {

namespace {

// refine_tight's tie order for delta²: the position in c[0..n) (canonical order) of the first
// exact minimum, or -1 where it cannot be decided (certify.h's first_least_delta2: compensated
// depths, exact direction, then expansions of D_p² n_q.n_q against D_q² n_p.n_p).
template <class List>
int exact_first(const List& s, const int* c, int n) {
  return detail::first_least_delta2(s, c, n);
}

// The contenders {i : lower(i) <= hi} (refine.h: the exact minimisers and their ties among
// them, every other candidate's exact delta² above hi >= the minimum) along one axis direction
// (certify.h's one_axis_direction: an aligned pair's face, the edge pairs in its plane and the
// touching face of the other tetrahedron, as blocks resting on each other meet them):
// their exact delta² are one value, the minimum, first attained by the first of them in
// canonical order. One interval then certifies it (its width within definitions §8), instead of
// an interval for each contender and their exact order. False: not so, or the interval too wide.
// (A candidate with rigid_rel_small and 0.98 delta² > hi has lower bound > hi: certify.h.)
template <class List, class Lower, class Interval>
bool one_direction_choice(const List& s, Lower lower, double hi, Interval interval, Choice& ch) {
  // the double choice is a contender: along no axis, no test (two components exactly 0)
  const unsigned zeros = detail::structural_zero_components(*s.A, *s.B, unpack_label(label_code(s, ch.index)));
  if (zeros != 3u && zeros != 5u && zeros != 6u) return false;
  int idx[kMaxCandidates], m = 0;
  ApproxNormal a[kMaxCandidates];
  for (int i = 0; i < s.count; ++i) {
    if ((detail::kSmallRigidLower * s.delta_sq[i] > hi && detail::rigid_rel_small(s, i)) || lower(i) > hi) continue;
    idx[m] = i;
    if (!detail::one_axis_direction(s, idx, m + 1, a, m)) return false;  // (the first one off ends it)
    ++m;
  }
  double v = 0, r = 1;
  if (m < 1 || !interval(idx[0], v, r) || !(r < 1) || !certified_choice(upper_of(v, r), lower_of(v, r))) return false;
  ch.value = v;
  ch.index = idx[0];
  ch.code = label_code(s, idx[0]);
  ch.certified = ch.refined = ch.exact_first = true;
  return true;
}

// First tied minimum of delta², certified (value_bounds.h: every candidate's exact delta² is
// >= lower_of(delta~², its bound)). An edge pair along a face of A other than the choice is left
// out (along_face_of_A: its exact delta² is its face's, whose bound is counted, and it follows
// the face in canonical order).
template <class List>
Choice rigid_of(const List& s) {
  Choice ch;
  ch.index = first_tied_minimum(s.delta_sq, s.count, s.tie_kappa);
  if (ch.index < 0) return {};  // NaN: not certified
  ch.value = s.delta_sq[ch.index];
  ch.code = label_code(s, ch.index);
  double lo_min = std::numeric_limits<double>::infinity(), lo_others = lo_min;
  const double far = 2 * ch.value;  // certify.h: candidates above it with a small bound skipped
  for (int i = 0; i < s.count; ++i) {
    if ((s.delta_sq[i] > far && detail::rigid_rel_small(s, i)) || (along_face_of_A(s, i) >= 0 && i != ch.index)) continue;
    double lo = lower_of(s.delta_sq[i], detail::rigid_rel(s, i));
    if (!(lo >= 0.0)) lo = 0.0;
    lo_min = lo < lo_min ? lo : lo_min;
    if (i != ch.index) lo_others = lo < lo_others ? lo : lo_others;
  }
  const double hi = upper_of(ch.value, detail::rigid_rel(s, ch.index));
  ch.certified = certified_choice(hi, lo_min);
  // every other exact delta² above the choice's (the skipped ones too: certified, hi is within
  // 1e-9 of the value, below their 1.96 v): the choice is the exact minimum, alone
  ch.exact_first = ch.certified && lo_others > hi;
  if (ch.certified) return ch;
  const int chosen = ch.index;
  auto lower = [&s, chosen](int i) {
    if (along_face_of_A(s, i) >= 0 && i != chosen) return std::numeric_limits<double>::infinity();
    return std::max(lower_of(s.delta_sq[i], detail::rigid_rel(s, i)), delta2_known_lower(s, i));
  };
  auto exact = [](const detail::ExactCandidate& c, detail::Q& v) {
    v = detail::exact_delta2(c);
    return true;
  };
  // Over the pair's integer frame where it has one (integer_depth.h: the exact depth and n.n,
  // each rounded once, memoised per pair: the tie order below and the pair's other values take
  // the same depths again at no cost), else on compensated heights, then expansions.
  detail::IntegerFrame frame(*s.A, *s.B);
  auto interval = [&s, &frame](int i, double& v, double& r) {
    detail::FramedDepth framed;
    if (frame.usable() && detail::framed_depth(frame, unpack_label(label_code(s, i)), framed) &&
        detail::framed_delta2(frame, framed, v, r))
      return true;
    if (!detail::tight_delta2(s, i, v, r)) return false;
    double ve, re;
    if (!(r < 1 && certified_choice(upper_of(v, r), lower_of(v, r))) &&
        delta2_by_expansions(*s.A, *s.B, unpack_label(label_code(s, i)), ve, re))
      v = ve, r = re;
    return true;
  };
  auto tie_order = [&s](const int* c, int n) { return exact_first(s, c, n); };
  if (one_direction_choice(s, lower, hi, interval, ch)) return ch;
  // Compensated intervals first (refine.h: ~1 us for the contenders of a shallow contact, whose
  // double bounds carry u L^3 beside a value ~|n| depth), then expansions for the contenders
  // those leave too wide (exact_predicates.h), the contenders in rationals (~10-30 us each) only
  // where neither can certify. The value is then within definitions §8 of the exact one
  // (typically a few u) rather than its correctly rounded double.
  if (!detail::refine_tight(s, lower, hi, interval, exact, tie_order, ch)) detail::refine_minimum(s, lower, hi, exact, ch);
  return ch;
}

}  // namespace

Choice rigid_pd2(const CandidateSet& set) {
  if (!set.intersecting) return {};
  return rigid_of(set);
}

Choice rigid_pd2(const QuickCandidates& q) { return rigid_of(q); }

namespace {

// A candidate's overlap L_A + L_B - L_{A u B} = min(hiA, hiB) - max(loA, loB) on
// compensated_heights.h's heights, with its error: each extreme within its near vertices'
// largest e_i (tight_delta.h's largest and smallest), the lesser of the two tops and the
// greater of the two bottoms within theirs (lesser, greater), and one rounding: eO = e_top +
// e_bottom + u |overlap~|. False where the compensated heights do not apply.
bool eq11_tight_overlap(const CandidateSet& set, const Candidate& c, double& overlap, double& eO, double& nn,
                        double& e_n) {
  detail::CompensatedHeights h;
  if (!detail::compensated_heights(*set.A, *set.B, c, h)) return false;
  const detail::Extreme hiA = detail::largest(h.hA, h.eA), loA = detail::smallest(h.hA, h.eA);
  const detail::Extreme hiB = detail::largest(h.hB, h.eB), loB = detail::smallest(h.hB, h.eB);
  const detail::Extreme top = detail::lesser(hiA, hiB), bottom = detail::greater(loA, loB);
  overlap = top.value - bottom.value;
  eO = (top.error + bottom.error + kUnitRoundoff * std::fabs(overlap)) * (1 + 0x1p-40);
  nn = h.nn, e_n = h.e_n;
  return true;
}

// One pass of eq11_pd2 over every candidate, with the double overlaps or (tight) the
// compensated ones where they apply. Returns true when certified: `zero` (some overlap surely
// <= 0: E11 = 0) or `best`. Else lo[i] (a certified lower bound, -1 where the sign is
// uncertain) and hi_sure (the least upper bound among sure overlaps) for the refinement.
bool eq11_pass(const CandidateSet& set, bool tight, double* lo, double& best_out, double& hi_sure, bool& zero) {
  double best = -1.0, best_hi = 0.0, lo_min = std::numeric_limits<double>::infinity();
  hi_sure = std::numeric_limits<double>::infinity();
  bool sure = true;
  for (int i = 0; i < set.count; ++i) {
    const Candidate c = candidate(set, i);
    double overlap, eO, nn = c.nn, e_n;
    if (!(tight && set.A && eq11_tight_overlap(set, c, overlap, eO, nn, e_n))) {
      const double loA = *std::min_element(c.hA, c.hA + 4), hiA = *std::max_element(c.hA, c.hA + 4);
      const double loB = *std::min_element(c.hB, c.hB + 4), hiB = *std::max_element(c.hB, c.hB + 4);
      overlap = (hiA - loA) + (hiB - loB) - (std::max(hiA, hiB) - std::min(loA, loB));
      const DegreeBounds db = degree_bounds_of(set.fb, c);
      eO = 6 * db.e_h + 21 * kUnitRoundoff * detail::max_height(c);
      e_n = db.e_n;
    }
    if (overlap <= -eO) {  // exactly <= 0: E11 = 0, certified
      zero = true;
      return true;
    }
    lo[i] = -1.0;
    if (!(overlap > eO)) sure = false;  // sign unknown: keep scanning for a sure zero
    if (overlap <= 0.0) {
      best = 0.0;
      continue;
    }
    const double v = overlap * overlap / nn;
    const double r = finish_root_rel(eO / overlap, nn, e_n);
    double l = lower_of(v, r);
    if (!(l >= 0.0)) l = 0.0;
    lo_min = l < lo_min ? l : lo_min;
    if (overlap > eO) {
      lo[i] = l;
      const double h = upper_of(v, r);
      hi_sure = h < hi_sure ? h : hi_sure;
    }
    if (best < 0.0 || v < best) {
      best = v;
      best_hi = upper_of(v, r);
    }
  }
  best_out = best;
  return sure && best > 0.0 && certified_choice(best_hi, lo_min);
}

}  // namespace

// definitions §8 (value_bounds.h): the overlap combines six heights (error <= e_h each) in five
// roundings of values <= 4 Hm, so |overlap~ − overlap| <= eO = 6 e_h + 21 u Hm; its sign is
// certain beyond eO, and its root bound is finish_root_rel(eO/|overlap~|).
// Not certified: refined (refine.h) over the contenders = the candidates whose overlap sign is
// uncertain, and those whose certified lower bound is <= best_hi (a certified upper bound of
// one candidate's exact value, when some overlap is surely > 0). If one contender's exact overlap
// is <= 0, E11 = 0 exactly; else every non-contender's overlap is surely > 0 and its value
// > best_hi >= the minimum, so the minimum over the contenders is E11 (refine.h's proof).
double eq11_pd2(const CandidateSet& set, bool* certified, bool* refined) {
  if (certified) *certified = true;
  if (refined) *refined = false;
  if (!set.intersecting) return 0.0;
  double lo[kMaxCandidates];  // certified lower bound of each value; −1: sign uncertain
  double best = 0.0, hi_sure = 0.0;
  bool zero = false;
  // The double overlaps, then (not certified) every overlap on compensated heights where they
  // apply (eq11_tight_overlap: contacts far shallower than the pair), then the contenders exactly.
  if (eq11_pass(set, false, lo, best, hi_sure, zero) || eq11_pass(set, true, lo, best, hi_sure, zero))
    return zero ? 0.0 : best;
  // Expansions next, on every contender (any number of them: a contact made by rounding leaves
  // most signs uncertain): an overlap exactly <= 0 gives E11 = 0 whatever the others; else the
  // least O²/(n.n), decided exactly, within a few u (exact_predicates.h). Every non-contender's
  // overlap is surely > 0 with a value above hi_sure, an upper bound of some candidate's value.
  if (set.A) {
    DirectionLabel l[kMaxCandidates];
    int n = 0;
    for (int i = 0; i < set.count; ++i)
      if (!(lo[i] > hi_sure)) l[n++] = unpack_label(label_code(set, i));
    bool exact_zero = false;
    double v = 0, r = 1;
    if (n > 0 && eq11_by_expansions(*set.A, *set.B, l, n, exact_zero, v, r) &&
        (exact_zero || (r < 1 && certified_choice(upper_of(v, r), lower_of(v, r))))) {
      if (refined) *refined = true;
      return exact_zero ? 0.0 : v;
    }
  }
  // Rationals where expansions cannot: a zero first, the candidates whose overlap sign is
  // uncertain, exactly; then the contenders' values.
  int idx[detail::kMaxRefined], m = 0;
  if (detail::contenders(set, [&lo](int i) { return lo[i] < 0.0 ? -1.0 : INFINITY; }, 0.0, idx, m)) {
    const detail::ExactFrame f = detail::exact_frame(*set.A, *set.B);
    for (int j = 0; j < m; ++j)
      if (sgn(detail::exact_overlap(detail::exact_candidate(f, unpack_label(label_code(set, idx[j]))))) <= 0) {
        if (refined) *refined = true;
        return 0.0;
      }
  }
  // Refinement: contenders lo < 0 (sign uncertain) or lo <= hi_sure.
  if (detail::contenders(set, [&lo](int i) { return lo[i]; }, hi_sure, idx, m)) {
    const detail::ExactFrame f = detail::exact_frame(*set.A, *set.B);
    detail::Q e11;
    bool exact_zero = false;
    for (int j = 0; j < m && !exact_zero; ++j) {
      const detail::ExactCandidate c =
          detail::exact_candidate(f, unpack_label(label_code(set, idx[j])));
      const detail::Q overlap = detail::exact_overlap(c);
      if (sgn(overlap) <= 0) {
        exact_zero = true;
        break;
      }
      const detail::Q v = overlap * overlap / c.nn;
      if (j == 0 || v < e11) e11 = v;
    }
    bool in_range = true;
    const double d = exact_zero ? 0.0 : detail::rounded_value(detail::unscaled(f, e11, 2), in_range);
    if (in_range) {
      if (refined) *refined = true;
      return d;
    }
  }
  if (certified) *certified = false;
  return best > 0.0 ? best : 0.0;
}

Choice rigid_pd2_reusing(const CandidateSet& set) {
  if (!set.A) return rigid_pd2(set);
  thread_local detail::PairMemo<Choice, 1> last;
  Choice ch;
  last.get(*set.A, *set.B, 0, ch, [&set](Choice& c) {
    c = rigid_pd2(set);
    return true;
  });
  return ch;
}

Choice rigid_pd2_choice(const TetVertices& A, const TetVertices& B) { return rigid_pd2_choice(A, B, nullptr); }

Choice rigid_pd2_choice(const TetVertices& A, const TetVertices& B, const SupersetFirstTry* first) {
  // superset_uncertified: the fused branch ran on power_scaled(A, B) and declined or did not
  // certify. rigid_superset on that same scaled pair is the same computation bit for bit
  // (superset_depth.h), so the run does not repeat it and goes to the candidate set.
  bool superset_uncertified = false;
  return detail::fused_hot_path(
      A, B,
      // rigid_superset on the rescaled pair, the run's first branch (superset_depth.h)
      [&A, &B, &superset_uncertified, first](Choice& ch, int& e) {
        bool ran = false, unresolved = false, done = false;
        if (first)
          ran = first->ran, unresolved = first->unresolved, done = first->done, ch = first->ch, e = first->e;
        else
          done = rigid_superset_scaled(A, B, ch, e, nullptr, nullptr, nullptr, &ran, &unresolved);
        superset_uncertified = ran && !(done && ch.certified);
        if (superset_uncertified) remember_uncertified_superset(A, B, unresolved);
        return done;
      },
      [&superset_uncertified](const TetVertices& As, const TetVertices& Bs, Choice& ch) {
        if (!superset_uncertified && rigid_superset(As, Bs, ch) && ch.certified) return true;
        BuildStatus status;
        const CandidateSet& set = build_candidates_reusing(As, Bs, status);
        if (status != BuildStatus::Ok || !set.intersecting) return false;
        ch = rigid_pd2_reusing(set);
        return true;
      },
      [](const PairResult<double>& r, std::optional<DirectionLabel>& l) {
        l = r.rigid_dir;
        return r.rigid_pd2;
      });
}

}  // namespace pdd::fast
