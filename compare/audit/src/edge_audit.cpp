#include "pdd/compare/edge_audit.h"

#include "pdd/reference/candidate_table.h"
#include "pdd/reference/minkowski_pd.h"
#include "pdd/reference/validate_pair.h"

namespace pdd::compare {

using namespace reference;

namespace {

// The pair's results (min over the candidate table) and their argmin rows.
struct Minima {
  std::optional<Rational> st, def, rel;
  std::size_t st_k = 0, def_k = 0, rel_k = 0;
};

void offer(std::optional<Rational>& best, std::size_t& arg, std::size_t k, const Rational& v) {
  if (!best || v < *best) best = v, arg = k;
}

Minima minima(const std::vector<CandidateRow>& rows) {
  Minima m;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (rows[k].static_case) offer(m.st, m.st_k, k, rows[k].static_case->value);
    offer(m.def, m.def_k, k, rows[k].deformable.value);
    offer(m.rel, m.rel_k, k, rows[k].relaxed.value);
  }
  return m;
}

// The three case optima along one direction (static nullopt when infeasible).
struct DirectionOptima {
  std::optional<Rational> st;
  Rational def, rel;
};

DirectionOptima solve_all_cases(const ExactPair& p, const CandidateDirection& dir) {
  const auto f = QpFormulation::Reduced;
  DirectionOptima o;
  if (auto s = direction_qp(p, dir, PddCase::Static, f)) o.st = s->value;
  o.def = direction_qp(p, dir, PddCase::Deformable, f)->value;
  o.rel = direction_qp(p, dir, PddCase::Relaxed, f)->value;
  return o;
}

// Raises the flags where the direction's optima beat the pair's result.
void compare_with_result(const DirectionOptima& o, const Minima& m, CaseFlags& beats) {
  if (o.st && *o.st < *m.st) beats.static_case = true;
  if (o.def < *m.def) beats.deformable = true;
  if (o.rel < *m.rel) beats.relaxed = true;
}

void audit_orientation_rule(const ExactPair& p, const std::vector<CandidateRow>& rows,
                            const Minima& m, EdgeAudit& out) {
  for (const auto& row : rows) {
    const CandidateDirection& d = row.direction;
    if (d.label.kind != ContactKind::EE || d.label.orientation != EdgeOrientation::Decided) continue;
    CandidateDirection flipped = d;
    flipped.n = -d.n;
    const DirectionOptima o = solve_all_cases(p, flipped);  // each QP once
    ++out.decided_checked;
    out.discarded_smaller_deformable += o.def < row.deformable.value;
    out.discarded_smaller_relaxed += o.rel < row.relaxed.value;
    out.discarded_feasible_static += o.st.has_value();
    compare_with_result(o, m, out.discarded_changes_result);
  }
}

// Normals of the faces incident to edge `e` of `tet` (outward; the faces opposite the two
// vertices not on the edge).
std::vector<Vector> incident_face_normals(const ExactTet& tet, int e) {
  std::vector<Vector> out;
  for (int opp = 0; opp < 4; ++opp) {
    if (opp == kEdges[e][0] || opp == kEdges[e][1]) continue;
    int f[3], k = 0;
    for (int i = 0; i < 4; ++i)
      if (i != opp) f[k++] = i;
    Vector n = CGAL::cross_product(tet[f[1]] - tet[f[0]], tet[f[2]] - tet[f[0]]);
    if (n * (tet[opp] - tet[f[0]]) > 0) n = -n;
    out.push_back(n);
  }
  return out;
}

void audit_colinear(const ExactPair& p, const Minima& m, EdgeAudit& out) {
  for (const auto& ab : out.colinear) {
    std::vector<Vector> normals = incident_face_normals(p.A, ab[0]);
    for (const auto& n : incident_face_normals(p.B, ab[1])) normals.push_back(n);
    const int u = kEdges[ab[0]][0], v = kEdges[ab[0]][1];
    for (const Vector& n : normals) {
      CandidateDirection d{DirectionLabel::ee(ab[0], ab[1]), n, {}, {}, EdgePairKind::Colinear};
      for (int i = 0; i < 4; ++i) {
        d.constrained_A[i] = (i == u || i == v);
        d.constrained_B[i] = (i == kEdges[ab[1]][0] || i == kEdges[ab[1]][1]);
      }
      bool pos = false, neg = false;  // definitions §3's orientation rule on A's other two vertices
      for (int k = 0; k < 4; ++k) {
        if (k == u || k == v) continue;
        const auto s = CGAL::sign(n * (p.A[k] - p.A[u]));
        pos = pos || s == CGAL::POSITIVE, neg = neg || s == CGAL::NEGATIVE;
      }
      std::vector<Vector> orientations;
      if (!pos) orientations.push_back(n);
      if (!neg) orientations.push_back(-n);
      if (pos && neg) orientations = {n, -n};
      for (const Vector& o : orientations) {
        d.n = o;
        ++out.colinear_directions;
        compare_with_result(solve_all_cases(p, d), m, out.colinear_changes_result);
      }
    }
  }
}

void record_optimum_source(const std::vector<CandidateRow>& rows, const Minima& m, EdgeAudit& out) {
  auto flags = [&](std::size_t k, bool& par, bool& und) {
    par = rows[k].direction.edge_kind == EdgePairKind::Parallel;
    und = rows[k].direction.label.orientation != EdgeOrientation::Decided;
  };
  flags(m.st_k, out.optimum_parallel.static_case, out.optimum_undecidable.static_case);
  flags(m.def_k, out.optimum_parallel.deformable, out.optimum_undecidable.deformable);
  flags(m.rel_k, out.optimum_parallel.relaxed, out.optimum_undecidable.relaxed);
}

}  // namespace

EdgeAudit edge_audit(const TetPair& pair) {
  EdgeAudit out;
  out.name = pair.name;
  if (auto why = validate_pair(pair)) {
    out.error = why;
    return out;
  }
  const ExactPair p = to_exact(pair);
  const auto cands = candidate_directions(p);
  out.colinear = colinear_edge_pairs(p);
  for (const auto& d : cands) {
    const std::array<int, 2> ab = {d.label.a, d.label.b};
    if (d.edge_kind == EdgePairKind::Parallel) out.parallel.push_back(ab);
    if (d.label.orientation == EdgeOrientation::Plus) out.undecidable.push_back(ab);
  }
  out.intersecting = minkowski_pd(p).intersecting;
  if (!out.intersecting) return out;
  const auto rows = candidate_table(p, cands, {QpFormulation::Reduced});
  const Minima m = minima(rows);
  audit_orientation_rule(p, rows, m, out);
  audit_colinear(p, m, out);
  record_optimum_source(rows, m, out);
  return out;
}

}  // namespace pdd::compare
