// eq11.h — the paper's eq. 11 (and its appendix Theorem 1), as definitions §4 states it.
//
//   E11 = min over candidates n of (L_n(A) + L_n(B) - L_n(A u B)) / |n|,
//   L_n(T) = max_{x in T} n.x - min_{x in T} n.x   (the width of T's projection on n),
//   E11 = 0 when some candidate overlap is <= 0.
//
// When A's and B's projected intervals overlap partially, the overlap equals the oriented
// depth along n or -n; when one interval nests in the other it is the inner one's width,
// which can be smaller than both oriented depths: the appendix's E11 = PD fails there.
#pragma once

#include <vector>

#include "pdd/reference/candidate_directions.h"

namespace pdd::reference {

// L_n(A) + L_n(B) - L_n(A u B), in units of |n| (the unnormalised overlap).
Rational eq11_overlap(const ExactPair& pair, const Vector& n);

// Whether the projected intervals of A and B on n nest (one contains the other).
bool projections_nest(const ExactPair& pair, const Vector& n);

struct Eq11Result {
  Rational e11_squared;        // E11^2, 0 when some overlap <= 0
  std::size_t argmin = 0;      // index of the first candidate attaining it (if positive)
  bool positive = false;       // every candidate overlap > 0
};

Eq11Result eq11(const ExactPair& pair, const std::vector<CandidateDirection>& candidates);

}  // namespace pdd::reference
