#include "pdd/reference/solve_exact.h"

#include <stdexcept>

#include "pdd/reference/candidate_table.h"
#include "pdd/reference/eq11.h"
#include "pdd/reference/global_pdd.h"
#include "pdd/reference/minkowski_pd.h"
#include "pdd/reference/validate_pair.h"

namespace pdd::reference {
namespace {

Positions<Rational> to_positions(const ExactTet& tet) {
  Positions<Rational> out;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) out[i][k] = tet[i][k];
  return out;
}

// Running minimum that keeps the first index attaining it (canonical order among ties).
struct FirstMinimum {
  std::optional<std::size_t> index;
  Rational value;
  void offer(std::size_t k, const Rational& v) {
    if (!index || v < value) index = k, value = v;
  }
};

// Rigid direction: the first candidate whose oriented depth equals PD (definitions §4).
std::size_t rigid_direction(const std::vector<CandidateRow>& rows, const Rational& pd2) {
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (rows[k].depth_signed_square == pd2) return k;
  throw std::logic_error("no candidate direction attains the Minkowski PD");
}

void fill_intersecting(const ExactPair& exact, const std::vector<CandidateDirection>& dirs,
                       const std::vector<CandidateRow>& rows, const MinkowskiPd& mink,
                       ExactResult& out) {
  out.rigid_pd2 = mink.pd2;
  out.rigid_dir = rows[rigid_direction(rows, mink.pd2)].direction.label;
  out.eq11_pd2 = eq11(exact, dirs).e11_squared;

  FirstMinimum st, def, rel;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (rows[k].static_case) st.offer(k, rows[k].static_case->value);
    def.offer(k, rows[k].deformable.value);
    rel.offer(k, rows[k].relaxed.value);
  }
  out.pdd2_static = st.value, out.pdd2_static_dir = rows[*st.index].direction.label;
  out.pdd2 = def.value, out.pdd2_dir = rows[*def.index].direction.label;
  out.pdd2_relaxed = rel.value, out.pdd2_relaxed_dir = rows[*rel.index].direction.label;
  out.q1_A = to_positions(rows[*def.index].deformable.q1_A);
  out.q1_B = to_positions(rows[*def.index].deformable.q1_B);

  const std::vector<std::size_t> order = depth_order(rows);  // case 3
  FirstMinimum accel6;
  for (std::size_t r = 0; r < order.size() && r < 6; ++r)
    accel6.offer(order[r], rows[order[r]].deformable.value);
  out.pdd2_accel1 = rows[order.front()].deformable.value;
  out.pdd2_accel6 = accel6.value;
}

// definitions §9, starting from the best relaxed candidate (so pdd2_global <= pdd2_relaxed).
void fill_global(const ExactPair& exact, const std::vector<CandidateRow>& rows,
                 GlobalOptions global, ExactResult& out) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < rows.size(); ++k)
    if (rows[k].relaxed.value < rows[best].relaxed.value) best = k;
  const CandidateRow& row = rows[best];
  global.floor = out.rigid_pd2 / 32;  // every relaxed value is >= PD^2/32 (global_pdd.h)
  const GlobalPdd g = global_pdd(exact, row.direction.n, row.relaxed.value, row.relaxed.q1_A,
                                 row.relaxed.q1_B, global);
  out.pdd2_global = g.value;
  out.pdd2_global_lower = g.lower;
  out.pdd2_global_normal = std::array<Rational, 3>{g.normal.x(), g.normal.y(), g.normal.z()};
  out.q1_A_global = to_positions(g.q1_A);
  out.q1_B_global = to_positions(g.q1_B);
}

// The gradient of pdd2_global (definitions §9), exactly, at the witness positions: -d sigma/d d at
// d = q1_global - rest, per tetrahedron d sigma/d d_i = (d_i + sum_k d_k) / 10 (object_norm.h's
// sigma = 1/20 (sum_i |d_i|^2 + |sum_k d_k|^2)). 0 at the rest pose (not intersecting).
PairGradient<Rational> global_gradient(const ExactPair& exact, const ExactResult& r) {
  PairGradient<Rational> g;
  for (int t = 0; t < 2; ++t) {
    const ExactTet& P = t ? exact.B : exact.A;
    const Positions<Rational>& Q = t ? r.q1_B_global : r.q1_A_global;
    for (int k = 0; k < 3; ++k) {
      Rational sum = 0;
      for (int i = 0; i < 4; ++i) sum += Q[i][k] - P[i][k];
      for (int i = 0; i < 4; ++i) g[4 * t + i][k] = -(Q[i][k] - P[i][k] + sum) / Rational(10);
    }
  }
  return g;
}

}  // namespace

ExactResult solve_exact(const TetPair& pair, const SolveOptions& options, const GlobalOptions& budget) {
  ExactResult out;
  out.name = pair.name;
  if (auto why = validate_pair(pair)) {
    out.error = *why;
    return out;
  }
  const ExactPair exact = to_exact(pair);
  out.q1_A = to_positions(exact.A);
  out.q1_B = to_positions(exact.B);
  out.q1_A_global = out.q1_A, out.q1_B_global = out.q1_B;
  out.pdd2_global_lower = Rational(0);
  const MinkowskiPd mink = minkowski_pd(exact);
  out.intersecting = mink.intersecting;
  if (options.with_global && options.gradient) out.pdd2_global_grad = global_gradient(exact, out);
  if (!mink.intersecting) return out;  // definitions §6: every value 0, labels null, rest pose

  const auto candidates = candidate_directions(exact);
  const auto rows = candidate_table(exact, candidates, {options.formulation});
  fill_intersecting(exact, candidates, rows, mink, out);
  if (options.with_global) fill_global(exact, rows, budget, out);
  if (options.with_global && options.gradient) out.pdd2_global_grad = global_gradient(exact, out);
  return out;
}

}  // namespace pdd::reference
