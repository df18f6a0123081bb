// engine_comparison.h — the fast engine judged against the exact one, pair by pair.
//
// Input : a pair, its exact result, its fast result, the tolerance factor K.
// Output: intersect agreement, the exact relative error of each squared value and of the
//         deformed positions, a verdict on each label, and whether anything is over tolerance.
//
// The judge is definitions §8, the fast engine's contract, checked exactly (nothing
// grows with R/PD):
// - the two engines reject the same pairs, except that the fast engine may reject a pair as
//   "not representable" when some non-zero exact value is outside the normal double range
//   (checked here on the exact values);
// - `intersecting` is the same;
// - every value: |fast − exact| <= 1e-9 · exact, computed exactly (so 0 iff exact 0);
// - every label: the same, or an exact tie, or a candidate whose exact value is within 1e-9
//   of the exact minimum (a near tie); otherwise it differs;
// - q1: the object norm of the fast positions, computed exactly, attains the exact pdd2 to
//   1e-9 up to the rounding of the coordinates themselves (a displacement given by absolute
//   coordinates of size Q cannot be closer than u·Q: allowance 4 u Q per vertex, which moves
//   sqrt(sigma) by <= sqrt(6) · 4 u Q, see value_bounds.h's norm argument), and the positions
//   are separated by the plane of the fast pdd2 label's exact direction up to 1e-9 · R;
// - pdd2_global (definitions §9): the fast value lies in the exact engine's certified interval
//   [pdd2_global_lower, pdd2_global] widened by 1e-9 relative, and the fast normal reproduces
//   it: the exact relaxed optimum along the fast normal (CGAL's QP) is within 1e-9 of it; the
//   fast engine may decline pdd2_global alone (pdd2_global_error) only where no double normal
//   need attain it (the exact pdd2_relaxed below 1e-14 of the pair's extent squared) or where
//   the exact value is outside the double range.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "pdd/pair_result.h"
#include "pdd/reference/relative_error.h"
#include "pdd/reference/solve_exact.h"

namespace pdd::compare {

inline constexpr double kContractRel = 1e-9;  // definitions §8

enum class LabelVerdict { Same, Tie, NearTie, Differ, None };
const char* to_string(LabelVerdict v);

// Values and labels in definitions §6 order: kValueKeys, kLabelKeys (pdd/pair_result.h).

struct PairComparison {
  std::string name;
  std::optional<std::string> exact_error, fast_error;  // rejections
  bool rejections_agree = true;
  // Where only the fast engine rejected and that is allowed: why (for the message).
  std::string allowed_because;
  bool intersecting = false;          // exact
  bool intersect_agree = true;
  double condition = 0;               // R / PD (reported; the contract does not depend on it)
  std::array<double, kValueCount> tolerance{};  // relative, per kValueKeys: kContractRel
  std::array<double, kValueCount> rel_error{};  // per kValueKeys
  std::array<double, kValueCount> exact_value{}, fast_value{};
  // |sigma(q1_fast) − pdd2_exact| / pdd2_exact, exactly, and its allowance (see above)
  double position_error = 0, position_tolerance = 0;
  bool separated = true;  // q1 separated by the fast label's plane up to 1e-9 R
  // definitions §9: distance of the fast pdd2_global outside [lower, witness] (relative; 0 inside),
  // and |exact relaxed value along the fast normal − fast value| / that exact value.
  double global_error = 0, global_normal_error = 0;
  double global_exact = 0, global_lower = 0, global_fast = 0;
  // The fast engine declined pdd2_global (pdd2_global_error, in global_decline; global_fast is
  // then NaN): allowed when allowed_because says so, else global_error is infinite.
  bool global_declined = false;
  std::string global_decline;
  std::array<LabelVerdict, kLabelCount> labels{};
  std::array<std::string, kLabelCount> exact_label, fast_label;

  bool over_tolerance() const;
};

PairComparison compare_pair(const TetPair& pair, const reference::ExactResult& exact,
                            const PairResult<double>& fast);

// |fast - exact| / |exact|, computed exactly (0 when both are 0, +inf when only exact is 0).
using reference::relative_error;

}  // namespace pdd::compare
