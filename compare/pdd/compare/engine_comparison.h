// engine_comparison.h — the fast engine judged against the exact one, pair by pair.
//
// Input : a pair, its exact result, its fast result, the tolerance factor K.
// Output: intersect agreement, the exact relative error of each squared value and of the
//         deformed positions, a verdict on each label, and whether anything is over tolerance.
//
// Tolerance (argued; the harness reports every pair over it, nothing is filtered):
// every reported value v is a squared length, computed along its direction n from the
// projections h_i = n.x_i/|n| with |h_i| <= R, R = the largest coordinate magnitude of the
// pair (the fast engine never sees anything larger). Computing n (a cross product of
// differences) and h_i costs O(10) roundings, so each h_i carries an absolute error of at
// most ~10 eps R (eps = 2^-53). sqrt(v) is a difference of such h's (a depth, an overlap, or
// for PD_d displacements linear in them with coefficients <= 1 given the active set), so its
// relative error is ~20 eps R / sqrt(v), and v's twice that. We allow
//     relative error of v  <=  K eps R / sqrt(v),    K = 256 by default,
// a factor ~6 above that count for the minimum-taking and the QP's few extra operations.
// Each value is held to its own scale: eq. 11's overlap on a nested axis is the inner
// tetrahedron's width, far below PD for a sliver, and its error is relative to that width.
// R / PD is the pair's condition number: ~20 on the paper's protocol (tolerance ~1e-12), huge
// for near-touching pairs, whose tolerance grows accordingly and whose errors are reported.
// Positions (q1): max |q_fast - q_exact| / R <= K eps R / sqrt(pdd2), the same bound on
// displacements of size <= R.
//
// Labels: identical; or a tie (the exact value at the fast label equals the exact minimum);
// or a near tie (the two exact values differ by less than the value tolerance, so no double
// computation could separate them); otherwise a disagreement, over tolerance.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "pdd/pair_result.h"
#include "pdd/reference/solve_pair.h"

namespace pdd::compare {

inline constexpr double kDefaultToleranceFactor = 256;

enum class LabelVerdict { Same, Tie, NearTie, Differ, None };
const char* to_string(LabelVerdict v);

inline const std::array<const char*, 7> kValueKeys = {
    "rigid_pd2", "eq11_pd2", "pdd2_static", "pdd2", "pdd2_relaxed", "pdd2_accel1", "pdd2_accel6"};
inline const std::array<const char*, 4> kLabelKeys = {"rigid_dir", "pdd2_static_dir", "pdd2_dir",
                                                      "pdd2_relaxed_dir"};

struct PairComparison {
  std::string name;
  std::optional<std::string> exact_error, fast_error;  // rejections
  bool rejections_agree = true;
  bool intersecting = false;          // exact
  bool intersect_agree = true;
  double condition = 0;               // R / PD
  std::array<double, 7> tolerance{};  // relative, per kValueKeys: K eps R / sqrt(value)
  std::array<double, 7> rel_error{};  // per kValueKeys
  std::array<double, 7> exact_value{}, fast_value{};
  double position_error = 0, position_tolerance = 0;  // relative to R
  std::array<LabelVerdict, 4> labels{};
  std::array<std::string, 4> exact_label, fast_label;

  bool over_tolerance() const;
};

PairComparison compare_pair(const TetPair& pair, const reference::ExactResult& exact,
                            const PairResult<double>& fast, double tolerance_factor);

// |fast - exact| / |exact|, computed exactly (0 when both are 0, +inf when only exact is 0).
double relative_error(double fast, const reference::Rational& exact);

}  // namespace pdd::compare
