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
// tie (pdd2 = pdd2_accel1 when the shallowest candidate is the optimum, computed along two
// paths). Each violated relation lowers the smaller side x to the bound b. That keeps the
// definitions §8 contract: with |v - e| <= eps e for both (eps = 1e-9; b final before it is
// used, by the order below), e_x <= e_b and v_x > b,
//     b >= (1 - eps) e_b >= (1 - eps) e_x   and   b < v_x <= (1 + eps) e_x,
// so |b - e_x| <= eps e_x; and e_x = 0 forces v_x = 0, never above b >= 0, so zeros stay.
// rigid_pd2 / 2 is exact (a normal double halves exactly down to the subnormal range, where
// the relation is left alone). Labels and positions are not touched: the contract measures
// them against the exact values, not against the printed ones. rigid_pd2 and pdd2_accel1,
// the tops of the chains, never change, and pdd2_static and pdd2_accel6 depend on them alone
// (mesh/src/contacts.cpp repeats those two on its hot path).
inline void keep_exact_relations(PairResult<double>& r) {
  auto at_most = [](double& x, double b) {
    if (x > b) x = b;
  };
  at_most(r.pdd2_static, r.rigid_pd2);
  at_most(r.pdd2_accel6, r.pdd2_accel1);
  at_most(r.pdd2, r.pdd2_static);
  at_most(r.pdd2, r.pdd2_accel6);
  if (std::isnormal(r.rigid_pd2 / 2)) at_most(r.pdd2, r.rigid_pd2 / 2);
  at_most(r.pdd2_relaxed, r.pdd2);
  if (!r.pdd2_global_error) at_most(r.pdd2_global, r.pdd2_relaxed);  // NaN when declined
}

}  // namespace pdd::fast
