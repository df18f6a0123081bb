#include "pdd/compare/engine_comparison.h"

#include <cmath>
#include <limits>

#include "pdd/reference/candidate_directions.h"
#include "pdd/reference/direction_qp.h"
#include "pdd/reference/oriented_depth.h"

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

double relative_error(double fast, const Rational& exact) {
  if (!std::isfinite(fast)) return std::numeric_limits<double>::infinity();
  const Rational diff = CGAL::abs(Rational(fast) - exact);
  if (exact == 0) return diff == 0 ? 0.0 : std::numeric_limits<double>::infinity();
  return CGAL::to_double(diff / CGAL::abs(exact));
}

bool PairComparison::over_tolerance() const {
  if (!rejections_agree || !intersect_agree) return true;
  for (int k = 0; k < 7; ++k)
    if (!(rel_error[k] <= tolerance[k])) return true;
  if (!(position_error <= position_tolerance)) return true;
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
  using namespace reference;
  for (const auto& d : candidate_directions(p)) {
    if (d.label != label) continue;
    if (which == 0) return oriented_depth_signed_square(p, d.n);
    const PddCase c = which == 1 ? PddCase::Static : which == 2 ? PddCase::Deformable : PddCase::Relaxed;
    auto opt = direction_qp(p, d, c, QpFormulation::Reduced);
    if (!opt) return std::nullopt;
    return opt->value;
  }
  return std::nullopt;
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

}  // namespace

PairComparison compare_pair(const TetPair& pair, const reference::ExactResult& exact,
                            const PairResult<double>& fast, double tolerance_factor) {
  PairComparison c;
  c.name = pair.name;
  c.exact_error = exact.error, c.fast_error = fast.error;
  c.rejections_agree = exact.error.has_value() == fast.error.has_value();
  if (exact.error || fast.error) return c;

  c.intersecting = exact.intersecting;
  c.intersect_agree = exact.intersecting == fast.intersecting;
  constexpr double eps = std::numeric_limits<double>::epsilon() / 2;  // 2^-53
  const double R = largest_coordinate(pair);
  const double pd = std::sqrt(CGAL::to_double(exact.rigid_pd2));
  c.condition = exact.intersecting ? R / pd : 0;

  const std::array<const Rational*, 7> ev = {&exact.rigid_pd2, &exact.eq11_pd2, &exact.pdd2_static, &exact.pdd2,
                                             &exact.pdd2_relaxed, &exact.pdd2_accel1, &exact.pdd2_accel6};
  const std::array<double, 7> fv = {fast.rigid_pd2, fast.eq11_pd2, fast.pdd2_static, fast.pdd2,
                                    fast.pdd2_relaxed, fast.pdd2_accel1, fast.pdd2_accel6};
  for (int k = 0; k < 7; ++k) {
    c.rel_error[k] = relative_error(fv[k], *ev[k]);
    c.exact_value[k] = CGAL::to_double(*ev[k]);
    c.fast_value[k] = fv[k];
    c.tolerance[k] = exact.intersecting ? tolerance_factor * eps * R / std::sqrt(c.exact_value[k]) : 0;
  }
  c.position_tolerance = c.tolerance[3];  // pdd2's
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      const double ea = CGAL::to_double(CGAL::abs(Rational(fast.q1_A[i][k]) - exact.q1_A[i][k]));
      const double eb = CGAL::to_double(CGAL::abs(Rational(fast.q1_B[i][k]) - exact.q1_B[i][k]));
      c.position_error = std::max({c.position_error, ea / R, eb / R});
    }

  const auto p = reference::to_exact(pair);
  const std::array<std::optional<DirectionLabel>, 4> el = {exact.rigid_dir, exact.pdd2_static_dir,
                                                           exact.pdd2_dir, exact.pdd2_relaxed_dir};
  const std::array<std::optional<DirectionLabel>, 4> fl = {fast.rigid_dir, fast.pdd2_static_dir,
                                                           fast.pdd2_dir, fast.pdd2_relaxed_dir};
  const std::array<const Rational*, 4> mins = {&exact.rigid_pd2, &exact.pdd2_static, &exact.pdd2,
                                               &exact.pdd2_relaxed};
  const std::array<double, 4> label_tolerance = {c.tolerance[0], c.tolerance[2], c.tolerance[3], c.tolerance[4]};
  for (int k = 0; k < 4; ++k) {
    c.labels[k] = label_verdict(p, el[k], fl[k], *mins[k], k, label_tolerance[k]);
    c.exact_label[k] = el[k] ? el[k]->str() : "null";
    c.fast_label[k] = fl[k] ? fl[k]->str() : "null";
  }
  return c;
}

}  // namespace pdd::compare
