// best_offer.h — internal to fast/src/global: the normals offered to the global depth and the
// best of them.
//
// Input : offers v (double normals, A -> B) from the start, the descent step, the pieces'
//         eigenvectors, walls and Ritz vectors, and the suspects' representatives.
// Output: the lowest relaxed value offered, best = min_v relaxed(v), and its normal n:
//         double path, relaxed_at's value with value_error's bound (every offer kept, for the
//         driver's comparison of near ties, and the winner's solution and heights);
//         exact path (A set), relaxed_exact's value in rationals, qvalue, in the pair's units,
//         and value = qvalue 2^-2unit in the exact pieces' units. An offer only ever lowers the
//         best. Also the flags and suspects the enumeration leaves for the driver: needs_exact
//         (the doubles cannot resolve an in-window eigenvalue) and the suspects of
//         suspect_proof.h (exact path).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "global/integer_shift.h"
#include "global/relaxed_value.h"

namespace pdd::fast::global {

// The normals offered so far and the best. Compared by the double closed form with its error
// bound, or (slow path, where doubles cannot resolve the pair's depths) by the exact one.
struct Best {
  double value = INFINITY;
  V3 n{};
  const TetVertices* A = nullptr;  // set: compare exactly
  const TetVertices* B = nullptr;
  // Exact comparison (A set): the best exact value `qvalue` (the pair's units); `value` is it
  // times 2^-2unit (the coordinates' scale of the exact pieces), for the record only: pieces
  // compare eigenvalues in their own units through value_in().
  long unit = 0;
  detail::Q qvalue;
  bool have_q = false;
  struct Offer {
    double value, error;
    V3 n;
  };
  // Double path: every normal evaluated. One buffer per thread, cleared per call (its
  // allocations, three per pair as it grew, were ~2% of pdd2_global); global_depth() does not
  // recurse, and one Best lives at a time per thread.
  std::vector<Offer>& offers = offer_buffer();
  static std::vector<Offer>& offer_buffer() {
    static thread_local std::vector<Offer> buffer;
    buffer.clear();
    return buffer;
  }
  // Double path: an in-window eigenvalue so close to another that the doubles' eigenvector
  // may miss its value by more than the budget (consider_piece): the caller redoes it exactly.
  bool needs_exact = false;
  // Exact path: the exact H (the scaled pair's units) and the eigenvalue's index of every
  // eigenvector that held its piece's sign conditions when offered (suspect_proof.h).
  // With the piece's exact sign conditions (its cone R_S: l[c].n >= 0 for every c, each l[c]
  // its condition's vector times its sign, as integers: a positive multiple of it, all that
  // represent_suspect() needs of it), for represent_suspect().
  struct Suspect {
    std::array<std::array<detail::Q, 3>, 3> h;
    int k;  // the index (ascending) of the eigenvalue whose vector held its signs
    std::array<std::array<mpz_class, 3>, 8> l;
    IntegerMatrix hi;  // h over one denominator (integer_shift.h: its exact counts and polish)
  };
  std::vector<Suspect> suspects;
  // Exact path: the lowest relaxed value along a rational normal offered by suspect_proof.h (a
  // stationary point that no double normal represents), when it is below qvalue: the witness
  // normal n (A -> B, the pair's frame), its value (the pair's units), the QP solution and
  // heights along it. An offer only lowers it; the double offers' best is kept apart.
  // (Built only when offered: its 16 rationals would cost every call allocations otherwise.)
  struct Witness {
    QNormal n;
    detail::Q value;
    detail::Q hA[4], hB[4];
    Solution<detail::Q> sol;
  };
  std::optional<Witness> witness;
  void offer_witness(const QNormal& v) {
    Witness w;
    w.n = v;
    w.value = relaxed_exact(*A, *B, v, w.hA, w.hB, w.sol);
    if ((have_q && !(w.value < qvalue)) || (witness && !(w.value < witness->value))) return;
    witness = std::move(w);
  }
  // The best value in units scaled by 2^-extra (a piece's own scale, exact path), or as is.
  double value_in(long extra) const;
  // Exact path: the pair's own scale (Problem::scale of the pair, not of the scaled pieces).
  double pair_scale = 0;
  // Exact path: relaxed(v) certainly above qvalue, shown on compensated heights (best_offer.cpp);
  // false when not shown. Such an offer is not taken (offer() keeps only a lower exact value),
  // so skipping its rational evaluation changes nothing.
  bool certainly_above(const V3& v) const;
  void offer(const Problem& P, const V3& v) {
    if (!nonzero(v)) return;
    if (A) {
      if (have_q && certainly_above(v)) return;  // relaxed(v) > qvalue: the offer would not be taken
      detail::Q hA[4], hB[4];
      Solution<detail::Q> s;
      const detail::Q q = relaxed_exact(*A, *B, v, hA, hB, s);
      if (have_q && !(q < qvalue)) return;
      qvalue = q, have_q = true, n = v;
      value = value_in(0);
      return;
    }
    DirectionSolution& s = last;
    double hm = 0, hA[4], hB[4];
    const double x = relaxed_at(P, v, &s, &hm, hA, hB);
    const double error = value_error(P, v, s.cost, hm);
    offers.push_back({x, error, v});
    if (x < value) {
      value = x, n = v;
      win.n = v, win.sol = s, win.error = error;
      std::copy(hA, hA + 4, win.hA), std::copy(hB, hB + 4, win.hB);
    }
  }
  DirectionSolution last;  // double path: the last offer's solution (descent_step)
  // Double path: the lowest offer's solution, value_error and heights (relative to A[0]).
  struct Winner {
    V3 n{};
    DirectionSolution sol;
    double error = INFINITY;
    double hA[4], hB[4];
  } win;
};

}  // namespace pdd::fast::global
