// exact_candidate.h — internal to fast/src: one definitions §3 candidate on exact rationals and its
// definitions §4/§5 values, written once for the two exact users: the exact slow path
// (exact_path.cpp, every candidate) and the refinement of the double path (refine.h, the one or few
// candidates whose certified error intervals the double path could not separate).
//
// Input:  a valid pair (finite, both volumes non-zero), as an ExactFrame: every coordinate taken
//         as the rational it denotes, minus s_0, times 2^shift so that all are integers (every
//         double is an integer times a power of two; integer rationals make GMP skip the gcd
//         work of power-of-two denominators). Values of the frame are those of the pair times
//         2^(2 shift) (squared lengths), displacements times 2^shift; unscaled() undoes it.
// Output: ExactCandidate — n (definitions §3, oriented), n.n, heights n.(x − s_0) of the 8
//         vertices, D = max hA − min hB and the constrained masks; and its exact delta², eq. 11 overlap
//         and QP values (direction_qp_impl.h on mpq_class), rounded once by rounded_value().
#pragma once

#include <array>
#include <utility>

#include "exact/exact_geometry.h"
#include "pdd/direction_label.h"
#include "pdd/pair_result.h"
#include "pdd/tet_pair.h"
#include "qp/direction_qp.h"

namespace pdd::fast::detail {

struct ExactFrame {
  QTet s, r;       // (s_i − s_0)·2^shift, (r_j − s_0)·2^shift: integers
  long shift = 0;  // may be negative (huge coordinates): still exact
};
ExactFrame exact_frame(const TetVertices& A, const TetVertices& B);

// q / 2^(times · shift): a frame value back in the pair's units (times = 2 for squared values,
// 1 for displacements), exactly.
Q unscaled(const ExactFrame& f, Q q, long times);

struct ExactCandidate {
  DirectionLabel label;
  QV n;
  Q nn, D, hA[4], hB[4];
  unsigned conA = 0, conB = 0;
};

// The candidate with normal n (already oriented) and masks: heights, D.
ExactCandidate exact_candidate(const ExactFrame& f, const DirectionLabel& l, const QV& n,
                               unsigned conA, unsigned conB);
// The candidate a definitions §3 label names (the label of an existing candidate of the pair: an EE
// label is not colinear, its orientation is the rule's, or ':+'/':-' of an undecidable pair).
ExactCandidate exact_candidate(const ExactFrame& f, const DirectionLabel& l);

// definitions §4: delta² = D²/(n.n); eq. 11: overlap = L_n(A) + L_n(B) − L_n(A ∪ B) (unnormalised).
Q exact_delta2(const ExactCandidate& c);
Q exact_overlap(const ExactCandidate& c);
// definitions §5 per-direction values, F/(20 n.n) (direction_qp.h). Static: the caller skips
// undecidable EE candidates (infeasible). `sol` (optional): the case-2 solution.
Q exact_static_value(const ExactCandidate& c);
Q exact_deformable_value(const ExactCandidate& c, Solution<Q>* sol = nullptr);
Q exact_relaxed_value(const ExactCandidate& c);

// The deformed positions x + (T/n.n) n of the case-2 solution `sol` of candidate c (of frame f,
// of the pair A, B), rounded once; `ok` cleared when a coordinate overflows (a subnormal one is
// a fine position: its absolute error <= 2^-1075 is far below the 1e-9 R of definitions §8).
void exact_positions(const TetVertices& A, const TetVertices& B, const ExactFrame& f,
                     const ExactCandidate& c, const Solution<Q>& sol, Positions<double>& qA,
                     Positions<double>& qB, bool& ok);

// Rounds a value of the pair's units (a squared length) to double (mpq_get_d: truncation,
// relative error < 2^-52); `ok` cleared when a non-zero value is not a normal double.
double rounded_value(const Q& q, bool& ok);

// A normal's direction in doubles: n times the exact power of two that brings its largest
// component near 1, rounded componentwise (each component to 2^-53 of itself, so a normal
// tilted by 2^-60 from an axis keeps its tilt). Zero for the zero vector.
std::array<double, 3> rounded_normal(const QV& n);

}  // namespace pdd::fast::detail
