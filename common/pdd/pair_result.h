// pair_result.h — one output record of definitions §6, for either engine.
//
// R is the engine's number type: an exact rational in the reference engine, double in the
// fast one. A rejected pair has `error` set and nothing else meaningful. A pair whose
// interiors do not intersect has every value 0, every label empty, and q1 = the rest pose.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>

#include "pdd/direction_label.h"

namespace pdd {

template <class R>
using Positions = std::array<std::array<R, 3>, 4>;  // 4 vertices x [x, y, z]

// A derivative with respect to the pair's eight vertices: A's s0..s3, then B's r0..r3.
template <class R>
using PairGradient = std::array<std::array<R, 3>, 8>;

// How the fast engine computed a record (its accuracy contract, pdd.h): diagnostics, not values.
// The exact engine leaves both false.
struct SolveStats {
  bool slow_path = false;  // the whole pair was recomputed on the engine's exact path
  bool refined = false;    // a few candidates were evaluated exactly instead (not slow_path)
};

template <class R>
struct PairResult {
  std::string name;
  std::optional<std::string> error;  // set when the pair was rejected (definitions §1)

  bool intersecting = false;
  R rigid_pd2{}, eq11_pd2{}, pdd2_static{}, pdd2{}, pdd2_relaxed{}, pdd2_accel1{}, pdd2_accel6{};
  std::optional<DirectionLabel> rigid_dir, pdd2_static_dir, pdd2_dir, pdd2_relaxed_dir;
  Positions<R> q1_A{}, q1_B{};  // case-2 deformed positions attaining pdd2

  // definitions §9: PD_d^2 over every separating plane (paper eq. 5). pdd2_global is the relaxed
  // optimum along pdd2_global_normal (A -> B; nullopt when not intersecting), attained by the
  // deformed positions q1_A_global, q1_B_global (the rest pose when not intersecting). The
  // normal's scale: pdd.h (fast engine: largest |component| in [1, 2); exact: as found).
  // pdd2_global_lower: the exact engine's proved lower bound (nullopt from the fast engine).
  R pdd2_global{};
  std::optional<std::array<R, 3>> pdd2_global_normal;
  Positions<R> q1_A_global{}, q1_B_global{};
  std::optional<R> pdd2_global_lower;
  // Set when pdd2_global alone cannot be had (fast engine only: no normal in doubles was
  // certified to attain it, or it lies outside the double range). The candidate-based values
  // above are still reported; pdd2_global and q1_*_global are then NaN and there is no normal,
  // so that none of them can be read as a depth. Written as null keys in a record.
  std::optional<std::string> pdd2_global_error;
  // The gradient of pdd2_global with respect to the eight vertices at their current positions,
  // the pair as given (pdd.h, "The gradient of pdd2_global"): set only when the options asked for it (SolveOptions::gradient); NaN
  // where pdd2_global is declined (pdd2_global_error), 0 when not intersecting.
  std::optional<PairGradient<R>> pdd2_global_grad;

  SolveStats stats;  // fast engine only
};

// The record's values and labels by name (the candidate-based values of definitions §5–§6; the §9
// keys are fields of their own above), in definitions §6 order, for code that treats them alike
// (comparisons, tables, bindings): record_value(r, k) is the field named kValueKeys[k],
// record_label(r, k) the one named kLabelKeys[k]; kLabelOfValue[k] is the label of value k
// (-1: it has none).
inline constexpr std::size_t kValueCount = 7, kLabelCount = 4;
inline constexpr std::array<const char*, kValueCount> kValueKeys = {
    "rigid_pd2", "eq11_pd2", "pdd2_static", "pdd2", "pdd2_relaxed", "pdd2_accel1", "pdd2_accel6"};
inline constexpr std::array<const char*, kLabelCount> kLabelKeys = {
    "rigid_dir", "pdd2_static_dir", "pdd2_dir", "pdd2_relaxed_dir"};
inline constexpr std::array<int, kValueCount> kLabelOfValue = {0, -1, 1, 2, 3, -1, -1};

template <class R>
R& record_value(PairResult<R>& r, std::size_t k) {
  R* const f[kValueCount] = {&r.rigid_pd2, &r.eq11_pd2, &r.pdd2_static, &r.pdd2,
                             &r.pdd2_relaxed, &r.pdd2_accel1, &r.pdd2_accel6};
  return *f[k];
}
template <class R>
const R& record_value(const PairResult<R>& r, std::size_t k) {
  return record_value(const_cast<PairResult<R>&>(r), k);
}
template <class R>
std::optional<DirectionLabel>& record_label(PairResult<R>& r, std::size_t k) {
  std::optional<DirectionLabel>* const f[kLabelCount] = {&r.rigid_dir, &r.pdd2_static_dir,
                                                         &r.pdd2_dir, &r.pdd2_relaxed_dir};
  return *f[k];
}
template <class R>
const std::optional<DirectionLabel>& record_label(const PairResult<R>& r, std::size_t k) {
  return record_label(const_cast<PairResult<R>&>(r), k);
}

}  // namespace pdd
