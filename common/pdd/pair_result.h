// pair_result.h — one output record of SPEC §6, for either engine.
//
// R is the engine's number type: an exact rational in the reference engine, double in the
// fast one. A rejected pair has `error` set and nothing else meaningful. A pair whose
// interiors do not intersect has every value 0, every label empty, and q1 = the rest pose.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "pdd/direction_label.h"

namespace pdd {

template <class R>
using Positions = std::array<std::array<R, 3>, 4>;  // 4 vertices x [x, y, z]

template <class R>
struct PairResult {
  std::string name;
  std::optional<std::string> error;  // set when the pair was rejected (SPEC §1)

  bool intersecting = false;
  R rigid_pd2{}, eq11_pd2{}, pdd2_static{}, pdd2{}, pdd2_relaxed{}, pdd2_accel1{}, pdd2_accel6{};
  std::optional<DirectionLabel> rigid_dir, pdd2_static_dir, pdd2_dir, pdd2_relaxed_dir;
  Positions<R> q1_A{}, q1_B{};  // case-2 deformed positions attaining pdd2
};

}  // namespace pdd
