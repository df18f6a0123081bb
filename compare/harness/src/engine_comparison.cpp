#include "pdd/compare/engine_comparison.h"

#include <cmath>
#include <limits>

#include "pdd/reference/candidate_table.h"
#include "pdd/reference/direction_qp.h"
#include "pdd/rejection.h"

namespace pdd::compare {

using reference::Rational;

const char* to_string(LabelVerdict v) {
  switch (v) {
    case LabelVerdict::Same: return "same";
    case LabelVerdict::Tie: return "tie";
    case LabelVerdict::NearTie: return "near-tie";
    case LabelVerdict::Differ: return "differ";
    case LabelVerdict::None: return "none";
  }
  return "?";
}

bool PairComparison::over_tolerance() const {
  if (!rejections_agree || !intersect_agree) return true;
  for (std::size_t k = 0; k < kValueCount; ++k)
    if (!(rel_error[k] <= tolerance[k])) return true;
  if (!(position_error <= position_tolerance) || !separated) return true;
  if (!(global_error <= kContractRel) || !(global_normal_error <= kContractRel)) return true;
  for (auto l : labels)
    if (l == LabelVerdict::Differ) return true;
  return false;
}

namespace {

// The exact value of quantity `which` (0 rigid, 1 static, 2 deformable, 3 relaxed) along the
// candidate labelled `label`; nullopt when the exact engine has no such candidate (or, for
// static, its QP is infeasible).
std::optional<Rational> exact_value_at(const reference::ExactPair& p, const DirectionLabel& label,
                                       int which) {
  const auto row = reference::candidate_row(p, label, {QpFormulation::Reduced});
  if (!row) return std::nullopt;
  switch (which) {
    case 0: return row->depth_signed_square;
    case 1: return row->static_case ? std::optional<Rational>(row->static_case->value) : std::nullopt;
    case 2: return row->deformable.value;
    default: return row->relaxed.value;
  }
}

LabelVerdict label_verdict(const reference::ExactPair& p, const std::optional<DirectionLabel>& exact,
                           const std::optional<DirectionLabel>& fast, const Rational& exact_min,
                           int which, double tolerance) {
  if (!exact && !fast) return LabelVerdict::None;
  if (exact && fast && *exact == *fast) return LabelVerdict::Same;
  if (!exact || !fast) return LabelVerdict::Differ;
  const auto at_fast = exact_value_at(p, *fast, which);
  if (!at_fast) return LabelVerdict::Differ;
  if (*at_fast == exact_min) return LabelVerdict::Tie;
  const double gap = CGAL::to_double(CGAL::abs(*at_fast - exact_min) / CGAL::abs(exact_min));
  return gap <= tolerance ? LabelVerdict::NearTie : LabelVerdict::Differ;
}

double largest_coordinate(const TetPair& pair) {
  double r = 0;
  for (const auto* t : {&pair.A, &pair.B})
    for (const auto& v : *t)
      for (double x : v) r = std::max(r, std::abs(x));
  return r;
}

// Some non-zero exact value is outside the normal double range (definitions §8's reason to reject).
bool unrepresentable(const reference::ExactResult& e) {
  for (const Rational* v : {&e.rigid_pd2, &e.eq11_pd2, &e.pdd2_static, &e.pdd2, &e.pdd2_relaxed,
                            &e.pdd2_accel1, &e.pdd2_accel6}) {
    if (*v == 0) continue;
    const double d = std::abs(CGAL::to_double(*v));
    if (!(d >= std::numeric_limits<double>::min() && d <= std::numeric_limits<double>::max()))
      return true;
  }
  return false;
}

// The fast engine's pdd2_global_error kGlobalNotRepresentable (no normal in doubles attains
// pdd2_global; the pair's other values stay) is
// allowed where a double normal's rounding, u R at a vertex R away, can exceed 1e-9 of the
// depth: the exact relaxed value below 1e-14 of the extent squared (R: the largest |x - s0|
// coordinate, exactly). fuzz/fuzz_fast_engine.cpp holds the engine to the same rule.
bool global_normal_unresolvable(const TetPair& pair, const reference::ExactResult& e) {
  if (!e.intersecting) return false;
  Rational R = 0;
  for (const auto* t : {&pair.A, &pair.B})
    for (const auto& v : *t)
      for (int k = 0; k < 3; ++k) {
        Rational d = Rational(v[k]) - Rational(pair.A[0][k]);
        if (d < 0) d = -d;
        if (d > R) R = d;
      }
  return e.pdd2_relaxed < Rational(1e-14) * R * R;
}

// pdd2_global's exact interval lies in the normal double range (or is 0).
bool representable_global(const reference::ExactResult& e) {
  for (const Rational& v : {e.pdd2_global, e.pdd2_global_lower.value_or(e.pdd2_global)}) {
    if (v == 0) continue;
    const double d = std::abs(CGAL::to_double(v));
    if (!(d >= std::numeric_limits<double>::min() && d <= std::numeric_limits<double>::max())) return false;
  }
  return true;
}

// Object norm (definitions §2) of both tetrahedra moved from the pair to q1, exactly.
Rational object_norm_of(const TetPair& pair, const PairResult<double>& fast) {
  Rational total = 0;
  for (int t = 0; t < 2; ++t) {
    const TetVertices& X = t ? pair.B : pair.A;
    const Positions<double>& Q = t ? fast.q1_B : fast.q1_A;
    Rational sq = 0, sum[3] = {0, 0, 0};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        const Rational d = Rational(Q[i][k]) - Rational(X[i][k]);
        sq += d * d;
        sum[k] += d;
      }
    total += (sq + sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]) / 20;
  }
  return total;
}

// q1 separated by the plane of `label`'s exact direction n up to slack |n| (1e-9 R).
bool separated_by(const reference::ExactPair& p, const DirectionLabel& label,
                  const PairResult<double>& fast, double R) {
  using namespace reference;
  for (const auto& d : candidate_directions(p)) {
    if (d.label != label) continue;
    auto height = [&](const std::array<double, 3>& x) {
      return d.n.x() * Rational(x[0]) + d.n.y() * Rational(x[1]) + d.n.z() * Rational(x[2]);
    };
    Rational hiA = height(fast.q1_A[0]), loB = height(fast.q1_B[0]);
    for (int i = 1; i < 4; ++i) {
      hiA = std::max(hiA, height(fast.q1_A[i]));
      loB = std::min(loB, height(fast.q1_B[i]));
    }
    const Rational gap = hiA - loB;  // <= 0 when separated
    if (gap <= 0) return true;
    const double n2 = CGAL::to_double(d.n.squared_length());
    return CGAL::to_double(gap * gap) <= kContractRel * kContractRel * R * R * n2;
  }
  return false;
}

// definitions §9: the fast pdd2_global against the exact interval, its normal re-evaluated exactly.
void judge_global(const reference::ExactPair& p, const reference::ExactResult& exact,
                  const PairResult<double>& fast, PairComparison& c) {
  using namespace reference;
  const Rational lower = exact.pdd2_global_lower ? *exact.pdd2_global_lower : exact.pdd2_global;
  c.global_fast = fast.pdd2_global;
  if (!std::isfinite(fast.pdd2_global)) {
    c.global_error = c.global_normal_error = std::numeric_limits<double>::infinity();
    return;
  }
  const Rational v(fast.pdd2_global);
  if (v < lower) c.global_error = relative_error(fast.pdd2_global, lower);
  if (v > exact.pdd2_global) c.global_error = relative_error(fast.pdd2_global, exact.pdd2_global);
  if (!exact.intersecting || !fast.intersecting) {
    c.global_normal_error = (fast.pdd2_global == 0 && !fast.pdd2_global_normal) ? 0.0
                            : std::numeric_limits<double>::infinity();
    return;
  }
  if (!fast.pdd2_global_normal) {
    c.global_normal_error = std::numeric_limits<double>::infinity();
    return;
  }
  const auto& n = *fast.pdd2_global_normal;
  CandidateDirection dir;
  dir.n = Vector(Rational(n[0]), Rational(n[1]), Rational(n[2]));
  if (dir.n == CGAL::NULL_VECTOR) {
    c.global_normal_error = std::numeric_limits<double>::infinity();
    return;
  }
  const auto qp = direction_qp(p, dir, PddCase::Relaxed, QpFormulation::Reduced);
  c.global_normal_error = qp ? relative_error(fast.pdd2_global, qp->value)
                             : std::numeric_limits<double>::infinity();
}

}  // namespace

PairComparison compare_pair(const TetPair& pair, const reference::ExactResult& exact,
                            const PairResult<double>& fast) {
  PairComparison c;
  c.name = pair.name;
  c.exact_error = exact.error, c.fast_error = fast.error;
  const bool fast_unrepresentable =
      fast.error && fast.error->rfind("not representable", 0) == 0;
  const bool out_of_range = !exact.error && fast_unrepresentable && unrepresentable(exact);
  c.rejections_agree = exact.error.has_value() == fast.error.has_value() || out_of_range;
  if (out_of_range)
    c.allowed_because = "the exact engine confirms: a value is outside the double range";
  if (exact.error || fast.error) return c;

  c.intersecting = exact.intersecting;
  c.intersect_agree = exact.intersecting == fast.intersecting;
  constexpr double eps = std::numeric_limits<double>::epsilon() / 2;  // 2^-53
  const double R = largest_coordinate(pair);
  const double pd = std::sqrt(CGAL::to_double(exact.rigid_pd2));
  c.condition = exact.intersecting ? R / pd : 0;

  for (std::size_t k = 0; k < kValueCount; ++k) {
    const Rational& ev = record_value(exact, k);
    const double fv = record_value(fast, k);
    c.rel_error[k] = relative_error(fv, ev);
    c.exact_value[k] = CGAL::to_double(ev);
    c.fast_value[k] = fv;
    c.tolerance[k] = kContractRel;
  }
  const auto p = reference::to_exact(pair);
  bool finite_positions = true;
  for (const Positions<double>* q : {&fast.q1_A, &fast.q1_B})
    for (const auto& x : *q)
      for (double v : x) finite_positions = finite_positions && std::isfinite(v);
  if (!finite_positions) {  // a non-finite position can attain nothing: over the contract
    c.position_error = std::numeric_limits<double>::infinity();
    c.separated = false;
  } else if (exact.intersecting && fast.intersecting) {
    double Q = R;
    for (const Positions<double>* q : {&fast.q1_A, &fast.q1_B})
      for (const auto& x : *q)
        for (double v : x) Q = std::max(Q, std::abs(v));
    const double root = std::sqrt(c.exact_value[3]);
    const double allowance = std::sqrt(6.0) * 4 * eps * Q / root;  // relative, on sqrt(sigma)
    c.position_tolerance = kContractRel + 2 * allowance + allowance * allowance;
    c.position_error = relative_error(CGAL::to_double(object_norm_of(pair, fast)), exact.pdd2);
    c.separated = fast.pdd2_dir && separated_by(p, *fast.pdd2_dir, fast, Q);
  }

  // the exact interval the fast pdd2_global is judged against (declined or not)
  c.global_exact = CGAL::to_double(exact.pdd2_global);
  c.global_lower = CGAL::to_double(exact.pdd2_global_lower ? *exact.pdd2_global_lower : exact.pdd2_global);
  if (!fast.pdd2_global_error) {
    judge_global(p, exact, fast, c);
  } else {
    // declined: no fast value (global_decline says why)
    c.global_declined = true;
    c.global_decline = *fast.pdd2_global_error;
    c.global_fast = std::numeric_limits<double>::quiet_NaN();
    if ((c.global_decline == kGlobalNotRepresentable && global_normal_unresolvable(pair, exact)) ||
        (c.global_decline == kGlobalOutOfRange && !representable_global(exact)))
      c.allowed_because = c.global_decline == kGlobalOutOfRange
                              ? "the exact engine confirms it is outside the double range"
                              : "the exact pdd2_relaxed is below 1e-14 of the pair's extent squared, where "
                                "no double normal need attain it";
    else  // declined where the contract requires a value
      c.global_error = c.global_normal_error = std::numeric_limits<double>::infinity();
  }

  for (std::size_t k = 0; k < kLabelCount; ++k) {
    const auto& el = record_label(exact, k);
    const auto& fl = record_label(fast, k);
    // the value this label minimises: the one whose kLabelOfValue is k
    std::size_t v = 0;
    while (kLabelOfValue[v] != int(k)) ++v;
    c.labels[k] = label_verdict(p, el, fl, record_value(exact, v), int(k), kContractRel);
    c.exact_label[k] = el ? el->str() : "null";
    c.fast_label[k] = fl ? fl->str() : "null";
  }
  return c;
}

}  // namespace pdd::compare
