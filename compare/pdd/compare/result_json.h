// result_json.h — one SPEC §6 JSON Lines record from a PairResult of either engine.
//
// Keys in SPEC order: name, intersecting, the seven values, the four labels, q1_A, q1_B,
// error. A rejected pair is {"name", "error"} only. The number writer decides how R is
// written: exact rationals as "p/q" strings, doubles as JSON numbers that read back to the
// same double (nlohmann writes the shortest round-trip form).
#pragma once

#include <functional>
#include <nlohmann/json.hpp>

#include "pdd/pair_result.h"

namespace pdd::compare {

using Json = nlohmann::ordered_json;

template <class R>
using NumberWriter = std::function<Json(const R&)>;

template <class R>
Json result_json(const PairResult<R>& r, const NumberWriter<R>& number) {
  Json j;
  j["name"] = r.name;
  if (r.error) {
    j["error"] = *r.error;
    return j;
  }
  j["intersecting"] = r.intersecting;
  j["rigid_pd2"] = number(r.rigid_pd2);
  j["eq11_pd2"] = number(r.eq11_pd2);
  j["pdd2_static"] = number(r.pdd2_static);
  j["pdd2"] = number(r.pdd2);
  j["pdd2_relaxed"] = number(r.pdd2_relaxed);
  j["pdd2_accel1"] = number(r.pdd2_accel1);
  j["pdd2_accel6"] = number(r.pdd2_accel6);
  auto label = [](const std::optional<DirectionLabel>& l) { return l ? Json(l->str()) : Json(nullptr); };
  j["rigid_dir"] = label(r.rigid_dir);
  j["pdd2_static_dir"] = label(r.pdd2_static_dir);
  j["pdd2_dir"] = label(r.pdd2_dir);
  j["pdd2_relaxed_dir"] = label(r.pdd2_relaxed_dir);
  auto positions = [&](const Positions<R>& q) {
    Json a = Json::array();
    for (const auto& v : q) a.push_back(Json::array({number(v[0]), number(v[1]), number(v[2])}));
    return a;
  };
  j["q1_A"] = positions(r.q1_A);
  j["q1_B"] = positions(r.q1_B);
  j["error"] = nullptr;
  return j;
}

}  // namespace pdd::compare
