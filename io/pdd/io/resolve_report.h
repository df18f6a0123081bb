// resolve_report.h — the report of a mesh resolution (pdd::mesh::ResolveReport, mesh.h) as JSON
// (`pdd resolve --report`, and the dict `pdd.resolve` returns in Python: the same keys) and as
// an aligned summary for people (`pdd resolve --summary`).
//
// Keys, in this order:
//   variant                "global" | "pdd2" | "rigid": the per-pair solution that drove the vertices
//   inputs                 {a, b: the files (CLI only; b null for self-contact), self, fix ("a",
//                          "b" or null), max_rounds, elements_a, vertices_a, elements_b,
//                          vertices_b (0 for self-contact), fixed_vertices_a, fixed_vertices_b}
//   resolved               r1 && r2 && r3, decided exactly on the positions written out
//   r1, r2, r3             no element pair intersects; no element inverted or flat; every fixed
//                          vertex bit-for-bit unchanged
//   rounds                 [{round, pairs, max_pd2, cost, seconds}, ...]: per round the
//                          intersecting pairs at its start, the largest per-pair squared depth
//                          of the variant, the cost after it, its wall time
//   cost, cost_a, cost_b   the mesh object norm of the displacement (volume-weighted mean squared
//                          displacement; a translation by t costs |t|^2): A + B, A, B
//   max_displacement       largest |p1 - p0| over all vertices
//   min_volume_ratio       smallest V1 / V0 over all elements (signed)
//   remaining_pairs        [[a, b], ...]: element pairs that still intersect (empty when r1)
//   bad_elements           [["A" | "B", index], ...]: elements inverted or flat (empty when r2)
//   moved_fixed_vertices   [["A" | "B", index], ...]: fixed vertices that moved (empty when r3)
//   skipped                [{mesh, index, reason}, ...]: input elements that cannot be computed
//   seconds_contacts, seconds_solve, seconds_move, seconds_verify, seconds_total
//                          wall time per stage over the whole run
// Numbers are JSON numbers that read back as the same double.
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "pdd/io/result_json.h"
#include "pdd/io/summary_text.h"
#include "pdd/mesh.h"

namespace pdd::io {

// What was asked, for the report's "inputs" (paths empty: not from files, e.g. Python).
struct ResolveInputs {
  std::string a, b;  // file names (b empty for self-contact)
  bool self = false;
  char fix = 0;      // 'a', 'b' or 0
  std::size_t max_rounds = 0;
  std::size_t elements_a = 0, vertices_a = 0, elements_b = 0, vertices_b = 0;
  std::size_t fixed_vertices_a = 0, fixed_vertices_b = 0;  // whole mesh or per-vertex flags
  bool files = true;  // whether a and b are file names (the CLI) or absent (Python)
};

inline Json resolve_report_json(const mesh::ResolveReport& r, const ResolveInputs& in) {
  Json j;
  j["variant"] = mesh::resolve_variant_name(r.variant);
  Json inputs;
  if (in.files) {
    inputs["a"] = in.a;
    inputs["b"] = in.self ? Json(nullptr) : Json(in.b);
  }
  inputs["self"] = in.self;
  inputs["fix"] = in.fix ? Json(std::string(1, in.fix)) : Json(nullptr);
  inputs["max_rounds"] = in.max_rounds;
  inputs["elements_a"] = in.elements_a;
  inputs["vertices_a"] = in.vertices_a;
  inputs["elements_b"] = in.elements_b;
  inputs["vertices_b"] = in.vertices_b;
  inputs["fixed_vertices_a"] = in.fixed_vertices_a;
  inputs["fixed_vertices_b"] = in.fixed_vertices_b;
  j["inputs"] = inputs;
  j["resolved"] = r.resolved;
  j["r1"] = r.r1;
  j["r2"] = r.r2;
  j["r3"] = r.r3;
  Json rounds = Json::array();
  for (const mesh::ResolveRound& k : r.rounds)
    rounds.push_back({{"round", k.round}, {"pairs", k.pairs}, {"max_pd2", k.max_pd2},
                      {"cost", k.cost}, {"seconds", k.seconds}});
  j["rounds"] = rounds;
  j["cost"] = r.cost;
  j["cost_a"] = r.cost_a;
  j["cost_b"] = r.cost_b;
  j["max_displacement"] = r.max_displacement;
  j["min_volume_ratio"] = r.min_volume_ratio;
  Json pairs = Json::array();
  for (const auto& p : r.remaining_pairs) pairs.push_back({p[0], p[1]});
  j["remaining_pairs"] = pairs;
  auto tagged = [](const std::vector<std::pair<char, std::size_t>>& v) {
    Json out = Json::array();
    for (const auto& [m, i] : v) out.push_back({std::string(1, m), i});
    return out;
  };
  j["bad_elements"] = tagged(r.bad_elements);
  j["moved_fixed_vertices"] = tagged(r.moved_fixed_vertices);
  Json skipped = Json::array();
  for (const mesh::SkippedElement& s : r.skipped)
    skipped.push_back({{"mesh", std::string(1, s.mesh)}, {"index", s.index}, {"reason", s.reason}});
  j["skipped"] = skipped;
  j["seconds_contacts"] = r.seconds_contacts;
  j["seconds_solve"] = r.seconds_solve;
  j["seconds_move"] = r.seconds_move;
  j["seconds_verify"] = r.seconds_verify;
  j["seconds_total"] = r.seconds_total;
  return j;
}

// The report (resolve_report_json's keys) in words: what was resolved, R1-R3 each with what
// remains, cost, displacement, volumes, times, and the rounds as an aligned table (the first
// and last ten rounds when there are more than twenty).
inline std::string resolve_summary(const Json& j) {
  const Json& in = j.at("inputs");
  const std::size_t rounds = j.at("rounds").size(), limit = in.at("max_rounds").get<std::size_t>();
  const bool self = in.at("self").get<bool>();
  const std::string fix = in.at("fix").is_null() ? "" : in.at("fix").get<std::string>();
  std::string s = "pdd resolve: ";
  s += j.at("resolved").get<bool>() ? "resolved" : "NOT resolved";
  s += " after " + std::to_string(rounds) + (rounds == 1 ? " round" : " rounds");
  s += " (variant " + j.at("variant").get<std::string>() + ", " +
       (self ? "self-contact of A" : "A against B") + ")\n";
  auto mesh_line = [&](const char* which) {
    const std::string w(which), lw = w == "A" ? "a" : "b";
    std::string t;
    if (in.contains(lw) && in.at(lw).is_string()) t += in.at(lw).get<std::string>() + ": ";
    t += tetrahedra(in.at("elements_" + lw).get<std::size_t>()) + ", " +
         std::to_string(in.at("vertices_" + lw).get<std::size_t>()) + " vertices";
    if (fix == lw) t += ", all fixed";
    else if (const auto f = in.at("fixed_vertices_" + lw).get<std::size_t>()) t += ", " + std::to_string(f) + " fixed";
    return summary_line("mesh " + w, t);
  };
  s += mesh_line("A");
  if (!self) s += mesh_line("B");
  auto listed = [](const Json& items, bool pairs) {
    std::string t;
    const std::size_t shown = std::min<std::size_t>(items.size(), 10);
    for (std::size_t k = 0; k < shown; ++k) {
      const Json& e = items[k];
      t += k ? ", " : ": ";
      t += pairs ? "(" + std::to_string(e[0].get<std::size_t>()) + ", " + std::to_string(e[1].get<std::size_t>()) + ")"
                 : e[0].get<std::string>() + " " + std::to_string(e[1].get<std::size_t>());
    }
    if (items.size() > shown) t += ", ... (" + std::to_string(items.size() - shown) + " more)";
    return t;
  };
  // Skipped input elements are in no pair and no check: said on every verdict line.
  const std::size_t skipped = j.at("skipped").size();
  const std::string except = skipped ? " (not the " + std::to_string(skipped) + " skipped elements)" : "";
  const Json& rp = j.at("remaining_pairs");
  const Json& be = j.at("bad_elements");
  const Json& mf = j.at("moved_fixed_vertices");
  s += summary_line("R1 no overlap", j.at("r1").get<bool>() ? "yes: no element pair intersects (checked exactly, every pair)" + except
                                                            : "NO: " + std::to_string(rp.size()) + " element pairs (a, b) intersect" + listed(rp, true));
  s += summary_line("R2 no inversion", j.at("r2").get<bool>() ? "yes: every element keeps the sign of its volume, none flat" + except
                                                              : "NO: " + std::to_string(be.size()) + " elements inverted or flat" + listed(be, false));
  s += summary_line("R3 fixed kept", j.at("r3").get<bool>() ? "yes: every fixed vertex bit-for-bit unchanged"
                                                            : "NO: " + std::to_string(mf.size()) + " fixed vertices moved" + listed(mf, false));
  if (!j.at("skipped").empty()) {
    std::string t = std::to_string(j.at("skipped").size()) + " input elements cannot be computed";
    for (std::size_t k = 0; k < std::min<std::size_t>(j.at("skipped").size(), 3); ++k)
      t += "\n" + j.at("skipped")[k].at("reason").get<std::string>();
    s += summary_line("skipped", t);
  }
  s += summary_line("cost", summary_number(j.at("cost").get<double>()) +
                                (self ? std::string() : "  (A " + summary_number(j.at("cost_a").get<double>()) + ", B " +
                                                            summary_number(j.at("cost_b").get<double>()) + ")") +
                                "  volume-weighted mean squared displacement");
  s += summary_line("max displacement", summary_number(j.at("max_displacement").get<double>()));
  s += summary_line("min volume ratio", summary_number(j.at("min_volume_ratio").get<double>()) + "  (V1 / V0 over the elements)");
  s += summary_line("time (s)", summary_number(j.at("seconds_total").get<double>()) + " total: contacts " +
                                    summary_number(j.at("seconds_contacts").get<double>()) + ", solve " +
                                    summary_number(j.at("seconds_solve").get<double>()) + ", move " +
                                    summary_number(j.at("seconds_move").get<double>()) + ", verify " +
                                    summary_number(j.at("seconds_verify").get<double>()));
  s += summary_line("rounds", std::to_string(rounds) + " of at most " + std::to_string(limit));
  if (rounds) {
    const std::string indent(2 + kSummaryLabel, ' ');
    s += indent + padded_left("round", 6) + padded_left("pairs", 9) + "  " + padded_left("max pd2", 12) +
         "  " + padded_left("cost", 12) + "  " + padded_left("seconds", 9) + '\n';
    for (std::size_t k = 0; k < rounds; ++k) {
      if (rounds > 20 && k == 10) s += indent + padded_left("...", 6) + '\n';
      if (rounds > 20 && k >= 10 && k < rounds - 10) continue;
      const Json& r = j.at("rounds")[k];
      s += indent + padded_left(std::to_string(r.at("round").get<std::size_t>()), 6) +
           padded_left(std::to_string(r.at("pairs").get<std::size_t>()), 9) + "  " +
           padded_left(summary_number(r.at("max_pd2").get<double>()), 12) + "  " +
           padded_left(summary_number(r.at("cost").get<double>()), 12) + "  " +
           padded_left(summary_number(r.at("seconds").get<double>()), 9) + '\n';
    }
  }
  return s;
}

}  // namespace pdd::io
