// resolve_report.h — the report of a mesh resolution (pdd::mesh::ResolveReport, mesh.h) as JSON
// (`pdd resolve --report`, and the dict `pdd.resolve` returns in Python: the same keys) and as
// an aligned summary for people (`pdd resolve --summary`).
//
// Keys, in this order:
//   variant                "global" | "pdd2" | "rigid": the per-pair solution that drove the vertices
//   method                 "rounds" | "translation" | "bodies" | "pdd2 rounds" | "rigid rounds" | "none": what produced the
//                          result (mesh.h's ResolveMethod)
//   stopped_because        why the run stopped early without resolving (every vertex fixed,
//                          no finite per-pair solution), or null
//   inputs                 {a, b: the files (CLI only; b null for self-contact), self, fix ("a",
//                          "b" or null), max_rounds, min_volume_ratio, min_shape_ratio,
//                          elements_a, vertices_a, elements_b, vertices_b (0 for self-contact),
//                          fixed_vertices_a, fixed_vertices_b}
//   resolved               r1 && r2 && r3 && r4, decided exactly on the positions written out
//   r1, r2, r3, r4         no element pair intersects; no element inverted or flat; every fixed
//                          vertex bit-for-bit unchanged; every element's V1/V0 in [rho, 1/rho]
//                          and eta1/eta0 >= kappa
//   rounds                 [{round, pairs, max_pd2, cost, seconds}, ...]: per round the
//                          intersecting pairs at its start, the largest per-pair squared depth
//                          of the variant, the cost after it, its wall time; when a fallback
//                          undid the last rounds, a closing row gives the state written (its
//                          intersecting pairs, 0 when resolved; max_pd2 0)
//   cost, cost_a, cost_b   the mesh object norm of the displacement (volume-weighted mean squared
//                          displacement; a translation by t costs |t|^2): A + B, A, B
//   max_displacement       largest |p1 - p0| over all vertices
//   min_volume_ratio       smallest V1 / V0 over all elements (signed)
//   max_volume_ratio       largest V1 / V0 over all elements
//   min_shape_ratio        smallest eta1 / eta0 over all elements
//   volume_ratio_histogram {edges, counts}: counts[0] elements below edges[0], counts[k]
//                          in [edges[k-1], edges[k]), the last above edges' last
//   shape_ratio_histogram  the same for eta1 / eta0
//   worst_elements         [{mesh, index, volume_ratio, shape_ratio}, ...]: the ten elements
//                          of smallest quality margin min(V1/V0 / rho, rho^-1 V0/V1, (eta1/eta0) / kappa)
//                          (below 1: short of R4), smallest first
//   remaining_pairs        [[a, b], ...]: element pairs that still intersect (empty when r1)
//   bad_elements           [["A" | "B", index], ...]: elements inverted or flat (empty when r2)
//   poor_elements          [["A" | "B", index], ...]: elements short of R4 (empty when r4)
//   moved_fixed_vertices   [["A" | "B", index], ...]: fixed vertices that moved (empty when r3)
//   skipped                [{mesh, index, reason}, ...]: input elements that cannot be computed
//   seconds_contacts, seconds_solve, seconds_move, seconds_verify, seconds_total
//                          wall time per stage over the whole run
// Numbers are JSON numbers that read back as the same double.
#pragma once

#include <algorithm>
#include <cmath>
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

// {edges, counts} of the finite values of a and b (see the keys above).
inline Json ratio_histogram(const std::vector<double>& edges, const std::vector<double>& a,
                            const std::vector<double>& b) {
  std::vector<std::size_t> counts(edges.size() + 1, 0);
  for (const std::vector<double>* v : {&a, &b})
    for (double x : *v)
      if (!std::isnan(x)) ++counts[std::upper_bound(edges.begin(), edges.end(), x) - edges.begin()];
  return Json{{"edges", edges}, {"counts", counts}};
}

// The n elements of smallest quality margin (see worst_elements above).
inline Json worst_elements(const mesh::ResolveReport& r, std::size_t n) {
  struct Item {
    double margin;
    char mesh;
    std::size_t index;
    double volume, shape;
  };
  std::vector<Item> items;
  const double rho = r.limits.min_volume_ratio, kappa = r.limits.min_shape_ratio;
  auto add = [&](char m, const std::vector<double>& vr, const std::vector<double>& sr) {
    for (std::size_t i = 0; i < vr.size(); ++i) {
      if (std::isnan(vr[i])) continue;
      const double margin = vr[i] > 0 ? std::min({vr[i] / rho, 1 / (vr[i] * rho), sr[i] / kappa}) : vr[i] / rho;
      items.push_back({margin, m, i, vr[i], sr[i]});
    }
  };
  add('A', r.volume_ratio_a, r.shape_ratio_a);
  add('B', r.volume_ratio_b, r.shape_ratio_b);
  const std::size_t k = std::min(n, items.size());
  std::partial_sort(items.begin(), items.begin() + std::ptrdiff_t(k), items.end(), [](const Item& x, const Item& y) {
    return x.margin < y.margin || (x.margin == y.margin && (x.mesh < y.mesh || (x.mesh == y.mesh && x.index < y.index)));
  });
  Json out = Json::array();
  for (std::size_t i = 0; i < k; ++i)
    out.push_back({{"mesh", std::string(1, items[i].mesh)}, {"index", items[i].index},
                   {"volume_ratio", items[i].volume}, {"shape_ratio", items[i].shape}});
  return out;
}

inline Json resolve_report_json(const mesh::ResolveReport& r, const ResolveInputs& in) {
  Json j;
  j["variant"] = mesh::resolve_variant_name(r.variant);
  j["method"] = mesh::resolve_method_name(r.method);
  j["stopped_because"] = r.stopped_because.empty() ? Json(nullptr) : Json(r.stopped_because);
  Json inputs;
  if (in.files) {
    inputs["a"] = in.a;
    inputs["b"] = in.self ? Json(nullptr) : Json(in.b);
  }
  inputs["self"] = in.self;
  inputs["fix"] = in.fix ? Json(std::string(1, in.fix)) : Json(nullptr);
  inputs["max_rounds"] = in.max_rounds;
  inputs["min_volume_ratio"] = r.limits.min_volume_ratio;
  inputs["min_shape_ratio"] = r.limits.min_shape_ratio;
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
  j["r4"] = r.r4;
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
  j["max_volume_ratio"] = r.max_volume_ratio;
  j["min_shape_ratio"] = r.min_shape_ratio;
  j["volume_ratio_histogram"] = ratio_histogram({0, 0.125, 0.25, 0.5, 1, 2, 4, 8}, r.volume_ratio_a, r.volume_ratio_b);
  j["shape_ratio_histogram"] = ratio_histogram({0.125, 0.25, 0.5, 0.75, 1, 1.5}, r.shape_ratio_a, r.shape_ratio_b);
  j["worst_elements"] = worst_elements(r, 10);
  Json pairs = Json::array();
  for (const auto& p : r.remaining_pairs) pairs.push_back({p[0], p[1]});
  j["remaining_pairs"] = pairs;
  auto tagged = [](const std::vector<std::pair<char, std::size_t>>& v) {
    Json out = Json::array();
    for (const auto& [m, i] : v) out.push_back({std::string(1, m), i});
    return out;
  };
  j["bad_elements"] = tagged(r.bad_elements);
  j["poor_elements"] = tagged(r.poor_elements);
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
  s += " (variant " + j.at("variant").get<std::string>() + ", method " + j.at("method").get<std::string>() + ", " +
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
  if (j.at("stopped_because").is_string()) s += summary_line("stopped", j.at("stopped_because").get<std::string>());
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
  const Json& pe = j.at("poor_elements");
  const std::string limits = "V1/V0 in [" + summary_number(in.at("min_volume_ratio").get<double>()) + ", 1/" +
                             summary_number(in.at("min_volume_ratio").get<double>()) + "], eta1/eta0 >= " +
                             summary_number(in.at("min_shape_ratio").get<double>());
  s += summary_line("R4 usable", j.at("r4").get<bool>() ? "yes: every element " + limits + " (checked exactly)" + except
                                                        : "NO: " + std::to_string(pe.size()) + " elements short of " + limits + listed(pe, false));
  if (!j.at("skipped").empty()) {
    std::string t = std::to_string(j.at("skipped").size()) + " input elements cannot be computed";
    for (std::size_t k = 0; k < std::min<std::size_t>(j.at("skipped").size(), 3); ++k)
      t += "\n" + j.at("skipped")[k].at("reason").get<std::string>();
    s += summary_line("skipped", t);
  }
  s += summary_line("cost", summary_cost(j.at("cost").get<double>()) +
                                (self ? std::string() : "  (A " + summary_cost(j.at("cost_a").get<double>()) + ", B " +
                                                            summary_cost(j.at("cost_b").get<double>()) + ")") +
                                "  volume-weighted mean squared displacement");
  s += summary_line("max displacement", summary_number(j.at("max_displacement").get<double>()));
  s += summary_line("volume ratio", summary_number(j.at("min_volume_ratio").get<double>()) + " to " +
                                        summary_number(j.at("max_volume_ratio").get<double>()) + "  (V1 / V0 over the elements)");
  s += summary_line("min shape ratio", summary_number(j.at("min_shape_ratio").get<double>()) + "  (eta1 / eta0, mean-ratio quality)");
  auto histogram = [](const Json& h) {
    const Json& e = h.at("edges");
    const Json& c = h.at("counts");
    std::string t;
    for (std::size_t k = 0; k < c.size(); ++k) {
      const std::string range = k == 0 ? "< " + summary_number(e[0].get<double>())
                                : k == e.size() ? ">= " + summary_number(e[k - 1].get<double>())
                                                : summary_number(e[k - 1].get<double>()) + "-" + summary_number(e[k].get<double>());
      t += (k ? ", " : "") + range + ": " + std::to_string(c[k].get<std::size_t>());
    }
    return t;
  };
  s += summary_line("volume ratios", histogram(j.at("volume_ratio_histogram")));
  s += summary_line("shape ratios", histogram(j.at("shape_ratio_histogram")));
  {
    std::string t;
    const Json& w = j.at("worst_elements");
    for (std::size_t k = 0; k < std::min<std::size_t>(w.size(), 5); ++k)
      t += (k ? ", " : "") + w[k].at("mesh").get<std::string>() + " " + std::to_string(w[k].at("index").get<std::size_t>()) +
           " (" + summary_number(w[k].at("volume_ratio").get<double>()) + ", " +
           summary_number(w[k].at("shape_ratio").get<double>()) + ")";
    s += summary_line("worst elements", t + "  (volume ratio, shape ratio)");
  }
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
           padded_left(summary_cost(r.at("cost").get<double>()), 12) + "  " +
           padded_left(summary_number(r.at("seconds").get<double>()), 9) + '\n';
    }
  }
  return s;
}

}  // namespace pdd::io
