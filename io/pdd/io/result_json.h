// result_json.h — one JSON Lines record (definitions §6) from a PairResult of either engine, and
// back.
//
// Keys in the record's order (definitions §6): name, intersecting, the seven values, the four
// labels, q1_A, q1_B, error, then definitions §9's pdd2_global, pdd2_global_normal, q1_A_global,
// q1_B_global and (exact engine) pdd2_global_lower or (fast engine) pdd2_global_error: null, or why
// the §9 keys are null while the others are reported; last pdd2_global_grad (8 x [x, y, z], A's
// vertices first) when the record has it. A rejected pair is {"name", "error"} only. The number
// writer decides how R is written: exact rationals as "p/q" strings, doubles as JSON numbers that
// read back to the same double (nlohmann writes the shortest round-trip form). result_from_json
// reads such a record back with a number reader (the inverse of the writer).
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "pdd/pair_result.h"

namespace pdd::io {

using Json = nlohmann::ordered_json;

template <class R>
using NumberWriter = std::function<Json(const R&)>;
template <class R>
using NumberReader = std::function<R(const Json&)>;

// The record's keys in order (above), each with its value, handed to `out`: result_json builds
// the JSON object from them, record_line.h writes the text directly. `out` provides
//   key(k)      -> bool: write key k (false: its value is skipped);
//   number(x)   a value R; null(); boolean(b); text(s) a string;
//   rows(a)     an array of [x, y, z] arrays (positions, the gradient); row(v) one [x, y, z].
template <class R, class Out>
void emit_record(const PairResult<R>& r, Out& out) {
  if (out.key("name")) out.text(r.name);
  if (r.error) {
    if (out.key("error")) out.text(*r.error);
    return;
  }
  if (out.key("intersecting")) out.boolean(r.intersecting);
  for (std::size_t k = 0; k < kValueCount; ++k)
    if (out.key(kValueKeys[k])) out.number(record_value(r, k));
  for (std::size_t k = 0; k < kLabelCount; ++k)
    if (out.key(kLabelKeys[k])) {
      const auto& l = record_label(r, k);
      l ? out.text(l->str()) : out.null();
    }
  if (out.key("q1_A")) out.rows(r.q1_A);
  if (out.key("q1_B")) out.rows(r.q1_B);
  if (out.key("error")) out.null();
  // definitions §9 (the table's order: after error); null keys where pdd2_global alone could not be
  // had (fast engine: pdd2_global_error, written by the fast engine's records only)
  const bool global_ok = !r.pdd2_global_error;
  if (out.key("pdd2_global")) global_ok ? out.number(r.pdd2_global) : out.null();
  if (out.key("pdd2_global_normal")) r.pdd2_global_normal && global_ok ? out.row(*r.pdd2_global_normal) : out.null();
  if (out.key("q1_A_global")) global_ok ? out.rows(r.q1_A_global) : out.null();
  if (out.key("q1_B_global")) global_ok ? out.rows(r.q1_B_global) : out.null();
  if (r.pdd2_global_lower && out.key("pdd2_global_lower")) out.number(*r.pdd2_global_lower);
  if constexpr (std::is_floating_point_v<R>)
    if (out.key("pdd2_global_error")) global_ok ? out.null() : out.text(*r.pdd2_global_error);
  // asked for (SolveOptions::gradient); null with pdd2_global
  if (r.pdd2_global_grad && out.key("pdd2_global_grad")) global_ok ? out.rows(*r.pdd2_global_grad) : out.null();
}

namespace detail {
// emit_record's keys into a JSON object (result_json).
template <class R>
struct JsonBuilder {
  Json& j;
  const NumberWriter<R>& write;
  const char* at = nullptr;
  bool key(const char* k) {
    at = k;
    return true;
  }
  void number(const R& x) { j[at] = write(x); }
  void null() { j[at] = nullptr; }
  void boolean(bool b) { j[at] = b; }
  void text(const std::string& s) { j[at] = s; }
  Json triple(const std::array<R, 3>& v) const { return Json::array({write(v[0]), write(v[1]), write(v[2])}); }
  void row(const std::array<R, 3>& v) { j[at] = triple(v); }
  template <class Rows>
  void rows(const Rows& a) {
    Json x = Json::array();
    for (const auto& v : a) x.push_back(triple(v));
    j[at] = std::move(x);
  }
};
}  // namespace detail

template <class R>
Json result_json(const PairResult<R>& r, const NumberWriter<R>& number) {
  Json j;
  detail::JsonBuilder<R> b{j, number};
  emit_record(r, b);
  return j;
}

// Whether a record of `variants` (below) keeps key k.
inline bool asked_key(std::string_view key, unsigned variants) {
  bool keep = true;
  for (std::size_t k = 0; k < kValueCount; ++k)
    if (key == kValueKeys[k] || (kLabelOfValue[k] >= 0 && key == kLabelKeys[kLabelOfValue[k]]))
      keep = variants >> k & 1u;
  if (key == "q1_A" || key == "q1_B") keep = variants >> 3 & 1u;  // kValueKeys[3] = "pdd2"
  if (key.find("_global") != std::string_view::npos) keep = variants >> kValueCount & 1u;
  return keep;
}

// The record with only the keys of the values asked. `variants`: bit k < kValueCount asks for
// kValueKeys[k] with its label (kLabelOfValue), q1_A and q1_B coming with pdd2 (bit 3); bit
// kValueCount for definitions §9's keys (pdd2_global, its normal and positions,
// pdd2_global_lower, pdd2_global_error, pdd2_global_grad) — the bits of pdd::mesh::Variant, as
// `pdd solve --variants`, `pdd mesh --variants` and Python's variants= parse them. name,
// intersecting and error stay; a rejected pair's record is unchanged.
inline Json asked_keys(const Json& record, unsigned variants) {
  Json j;
  for (const auto& [key, value] : record.items())
    if (asked_key(key, variants)) j[key] = value;
  return j;
}
static_assert(std::string_view(kValueKeys[3]) == "pdd2", "asked_keys: q1_A, q1_B come with bit 3");

// The record written by result_json, read back; throws (nlohmann::json's exceptions, or
// std::runtime_error for a malformed label) when a key is missing or mistyped.
template <class R>
PairResult<R> result_from_json(const Json& j, const NumberReader<R>& number) {
  PairResult<R> r;
  r.name = j.at("name").template get<std::string>();
  if (!j.at("error").is_null()) {
    r.error = j.at("error").template get<std::string>();
    return r;
  }
  auto label = [](const Json& l) -> std::optional<DirectionLabel> {
    if (l.is_null()) return std::nullopt;
    auto parsed = DirectionLabel::parse(l.template get<std::string>());
    if (!parsed) throw std::runtime_error("bad label " + l.dump());
    return parsed;
  };
  auto positions = [&](const Json& q) {
    Positions<R> out;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) out[i][k] = number(q.at(i).at(k));
    return out;
  };
  r.intersecting = j.at("intersecting").template get<bool>();
  r.rigid_pd2 = number(j.at("rigid_pd2"));
  r.eq11_pd2 = number(j.at("eq11_pd2"));
  r.pdd2_static = number(j.at("pdd2_static"));
  r.pdd2 = number(j.at("pdd2"));
  r.pdd2_relaxed = number(j.at("pdd2_relaxed"));
  r.pdd2_accel1 = number(j.at("pdd2_accel1"));
  r.pdd2_accel6 = number(j.at("pdd2_accel6"));
  r.rigid_dir = label(j.at("rigid_dir"));
  r.pdd2_static_dir = label(j.at("pdd2_static_dir"));
  r.pdd2_dir = label(j.at("pdd2_dir"));
  r.pdd2_relaxed_dir = label(j.at("pdd2_relaxed_dir"));
  r.q1_A = positions(j.at("q1_A"));
  r.q1_B = positions(j.at("q1_B"));
  if (const auto e = j.find("pdd2_global_error"); e != j.end() && !e->is_null()) {
    r.pdd2_global_error = e->template get<std::string>();
    if constexpr (std::is_floating_point_v<R>) {  // the fields' values for a declined pdd2_global
      const R nan = std::numeric_limits<R>::quiet_NaN();
      r.pdd2_global = nan;
      for (Positions<R>* q : {&r.q1_A_global, &r.q1_B_global})
        for (auto& x : *q) x = {nan, nan, nan};
    }
    return r;
  }
  r.pdd2_global = number(j.at("pdd2_global"));
  if (const Json& n = j.at("pdd2_global_normal"); !n.is_null())
    r.pdd2_global_normal = std::array<R, 3>{number(n.at(0)), number(n.at(1)), number(n.at(2))};
  r.q1_A_global = positions(j.at("q1_A_global"));
  r.q1_B_global = positions(j.at("q1_B_global"));
  if (j.contains("pdd2_global_lower")) r.pdd2_global_lower = number(j.at("pdd2_global_lower"));
  if (const auto g = j.find("pdd2_global_grad"); g != j.end() && !g->is_null()) {
    PairGradient<R> grad;
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k) grad[i][k] = number(g->at(i).at(k));
    r.pdd2_global_grad = grad;
  }
  return r;
}

}  // namespace pdd::io
