// rigid_depth.cpp — definitions §4. See the header.
#include "kernel/rigid_depth.h"

#include <algorithm>
#include <limits>

#include "certification/certify.h"
#include "certification/refine.h"
#include "certification/value_bounds.h"
#include "hot_path.h"

#include "certification/tie_tolerance.h"
#include "kernel/superset_depth.h"

namespace pdd::fast {

namespace {

// First tied minimum of delta², certified (value_bounds.h: every candidate's exact delta² is
// >= lower_of(delta~², its bound)).
template <class List>
Choice rigid_of(const List& s) {
  Choice ch;
  ch.index = first_tied_minimum(s.delta_sq, s.count, s.tie_kappa);
  if (ch.index < 0) return {};  // NaN: not certified
  ch.value = s.delta_sq[ch.index];
  ch.code = label_code(s, ch.index);
  double lo_min = std::numeric_limits<double>::infinity();
  const double far = 2 * ch.value;  // certify.h: candidates above it with a small bound skipped
  for (int i = 0; i < s.count; ++i) {
    if (s.delta_sq[i] > far && detail::rigid_rel_small(s, i)) continue;
    double lo = lower_of(s.delta_sq[i], detail::rigid_rel(s, i));
    if (!(lo >= 0.0)) lo = 0.0;
    lo_min = lo < lo_min ? lo : lo_min;
  }
  const double hi = upper_of(ch.value, detail::rigid_rel(s, ch.index));
  ch.certified = certified_choice(hi, lo_min);
  if (!ch.certified)
    detail::refine_minimum(
        s, [&s](int i) { return lower_of(s.delta_sq[i], detail::rigid_rel(s, i)); }, hi,
        [](const detail::ExactCandidate& c, detail::Q& v) {
          v = detail::exact_delta2(c);
          return true;
        },
        ch);
  return ch;
}

}  // namespace

Choice rigid_pd2(const CandidateSet& set) {
  if (!set.intersecting) return {};
  return rigid_of(set);
}

Choice rigid_pd2(const QuickCandidates& q) { return rigid_of(q); }

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
  double best = -1.0, best_hi = 0.0, lo_min = std::numeric_limits<double>::infinity();
  double hi_sure = std::numeric_limits<double>::infinity();  // min upper bound, sure overlaps
  bool sure = true;
  double lo[kMaxCandidates];  // certified lower bound of each value; −1: sign uncertain
  for (int i = 0; i < set.count; ++i) {
    const Candidate c = candidate(set, i);
    const double loA = *std::min_element(c.hA, c.hA + 4), hiA = *std::max_element(c.hA, c.hA + 4);
    const double loB = *std::min_element(c.hB, c.hB + 4), hiB = *std::max_element(c.hB, c.hB + 4);
    const double overlap = (hiA - loA) + (hiB - loB) - (std::max(hiA, hiB) - std::min(loA, loB));
    const DegreeBounds db = degree_bounds_of(set.fb, c);
    const double eO = 6 * db.e_h + 21 * kUnitRoundoff * detail::max_height(c);
    if (overlap <= -eO) return 0.0;  // exactly <= 0: E11 = 0, certified
    lo[i] = -1.0;
    if (!(overlap > eO)) sure = false;  // sign unknown: keep scanning for a sure zero
    if (overlap <= 0.0) {
      best = 0.0;
      continue;
    }
    const double v = overlap * overlap / c.nn;
    const double r = finish_root_rel(eO / overlap, c.nn, db.e_n);
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
  const bool ok = sure && best > 0.0 && certified_choice(best_hi, lo_min);
  if (ok) return best;
  // Refinement: contenders lo < 0 (sign uncertain) or lo <= hi_sure.
  int idx[detail::kMaxRefined], m = 0;
  if (detail::contenders(set, [&lo](int i) { return lo[i]; }, hi_sure, idx, m)) {
    const detail::ExactFrame f = detail::exact_frame(*set.A, *set.B);
    detail::Q e11;
    bool zero = false;
    for (int j = 0; j < m && !zero; ++j) {
      const detail::ExactCandidate c =
          detail::exact_candidate(f, unpack_label(label_code(set, idx[j])));
      const detail::Q overlap = detail::exact_overlap(c);
      if (sgn(overlap) <= 0) {
        zero = true;
        break;
      }
      const detail::Q v = overlap * overlap / c.nn;
      if (j == 0 || v < e11) e11 = v;
    }
    bool in_range = true;
    const double d = zero ? 0.0 : detail::rounded_value(detail::unscaled(f, e11, 2), in_range);
    if (in_range) {
      if (refined) *refined = true;
      return d;
    }
  }
  if (certified) *certified = false;
  return best > 0.0 ? best : 0.0;
}

Choice rigid_pd2_choice(const TetVertices& A, const TetVertices& B) {
  // superset_uncertified: the fused branch ran on power_scaled(A, B) and declined or did not
  // certify. rigid_superset on that same scaled pair is the same computation bit for bit
  // (superset_depth.h), so the run does not repeat it and goes to the candidate set.
  bool superset_uncertified = false;
  return detail::fused_hot_path(
      A, B,
      // rigid_superset on the rescaled pair, the run's first branch (superset_depth.h)
      [&A, &B, &superset_uncertified](Choice& ch, int& e) {
        bool ran = false;
        const bool done = rigid_superset_scaled(A, B, ch, e, nullptr, nullptr, nullptr, &ran);
        superset_uncertified = ran && !(done && ch.certified);
        return done;
      },
      [&superset_uncertified](const TetVertices& As, const TetVertices& Bs, Choice& ch) {
        if (!superset_uncertified && rigid_superset(As, Bs, ch) && ch.certified) return true;
        CandidateSet set;
        if (build_candidates_reusing(As, Bs, set) != BuildStatus::Ok || !set.intersecting) return false;
        ch = rigid_pd2(set);
        return true;
      },
      [](const PairResult<double>& r, std::optional<DirectionLabel>& l) {
        l = r.rigid_dir;
        return r.rigid_pd2;
      });
}

}  // namespace pdd::fast
