// value_relations.h — the exact relations between one pair's values, kept by its doubles.
//
// Inputs:  a fast record r of an intersecting pair, every value certified (definitions §8).
// Outputs: r with each value that rounded above a value it is exactly at most lowered to it.
// Equations: definitions §5 and §9.
#pragma once

#include <cmath>

#include "pdd/pair_result.h"

namespace pdd::fast {

// definitions §5 and §9: relations that hold exactly between the values of one pair,
//     pdd2 <= pdd2_static <= rigid_pd2,  pdd2 <= rigid_pd2 / 2,
//     pdd2_global <= pdd2_relaxed <= pdd2 <= pdd2_accel6 <= pdd2_accel1,
// kept by the printed doubles: each certified value may round to the other side of an exact
// tie (pdd2 = pdd2_accel6 when the optimum is among the six shallowest candidates, computed
// along two paths). A violated relation x <= b is kept by lowering x to b, or by raising b to x
// (pdd2_accel6 only). Both keep the definitions §8 contract: with |v - e| <= eps e for both
// (eps = 1e-9; the other side final before it is used, by the order below) and e_x <= e_b,
//   lowering, v_x > b:   b >= (1 - eps) e_b >= (1 - eps) e_x  and  b < v_x <= (1 + eps) e_x;
//   raising, x > v_b:    x <= (1 + eps) e_x <= (1 + eps) e_b  and  x > v_b >= (1 - eps) e_b;
// and e = 0 forces v = 0 (never above a bound >= 0, never raised above 0: e_x <= e_b = 0), so
// zeros stay. rigid_pd2 / 2 is exact (a normal double halves exactly down to the subnormal
// range, where the relation is left alone). Labels and positions are not touched: the contract
// measures them against the exact values, not against the printed ones.
// The order makes each value depend on as few others as possible, so that a record of some
// values (SolveOptions::values) holds the full record's bits for them: rigid_pd2, eq11_pd2 and
// pdd2_accel1 never change; pdd2_static depends on rigid_pd2; pdd2 on pdd2_static, pdd2_accel1 and
// rigid_pd2 (pdd2 <= pdd2_accel1, which the chain through pdd2_accel6 implies exactly);
// pdd2_accel6 on pdd2 and pdd2_accel1 (raised to pdd2, then lowered to pdd2_accel1 >= pdd2);
// pdd2_relaxed on pdd2; pdd2_global on pdd2_relaxed (global_minimiser.cpp repeats the chain,
// mesh/src/contacts.cpp pdd2_static's relation on its hot path).
// `computed` (bit k: the value kValueKeys[k]): the values the record holds, with those each one
// depends on (solve_pair.cpp's computed_values); the others are left alone.
inline void keep_exact_relations(PairResult<double>& r, unsigned computed = (1u << kValueCount) - 1) {
  auto at_most = [](double& x, double b) {
    if (x > b) x = b;
  };
  auto has = [computed](std::size_t k) { return (computed >> k & 1u) != 0; };
  constexpr std::size_t kStatic = 2, kPdd2 = 3, kRelaxed = 4, kAccel6 = 6;  // kValueKeys' order
  if (has(kStatic)) at_most(r.pdd2_static, r.rigid_pd2);
  if (has(kPdd2)) {
    at_most(r.pdd2, r.pdd2_static);
    at_most(r.pdd2, r.pdd2_accel1);
    if (std::isnormal(r.rigid_pd2 / 2)) at_most(r.pdd2, r.rigid_pd2 / 2);
  }
  if (has(kAccel6)) {
    if (r.pdd2_accel6 < r.pdd2) r.pdd2_accel6 = r.pdd2;
    at_most(r.pdd2_accel6, r.pdd2_accel1);
  }
  if (has(kRelaxed)) at_most(r.pdd2_relaxed, r.pdd2);
  if (!r.pdd2_global_error) at_most(r.pdd2_global, r.pdd2_relaxed);  // NaN when declined
}

}  // namespace pdd::fast
