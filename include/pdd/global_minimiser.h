// global_minimiser.h — definitions §9's minimiser of one pair by the fast engine, alone: the
// value pdd2_global, its normal and the deformed positions attaining it, without the rest of
// the record. For callers that need only those, many times (the contact energy,
// pdd/mesh/contact_energy.h).
//
// Inputs:  A, B  the tetrahedra's vertices s0..s3 and r0..r3 (any orientation).
//          options  MinimiserOptions (defaults in the struct: every value certified).
// Outputs: GlobalMinimiser, or nothing ("declined" below).
//   pd2       pdd2_global (definitions §9; the definitions §8 contract), unless `bounded`
//   normal    the normal attaining it (A -> B), scaled as solve_pair's pdd2_global_normal
//   q1_A, q1_B  the deformed positions attaining it (q1_*_global)
// Equal bit for bit to the fields of the same name of pdd::fast::solve_pair(pair, with_global)
// whenever that returns a record with pdd2_global: the same computation (the same rescaled
// pair, the same start, pdd2_relaxed's candidate from the same lane sweep, the same pruning
// value rigid_pd2, global_depth.h's enumeration, the same scaling back), minus every other
// value of the record. solve_pair lowers pdd2_global to pdd2_relaxed when it rounds above it
// (value_relations.h), and pdd2_relaxed may itself be lowered along the chain of definitions
// §5; every value of that chain is certified to 1e-9 of an exact value >= the exact relaxed
// value e, so each is >= (1 - 1e-9) e >= (1 - 1e-9) / (1 + 1e-9) pdd2_relaxed > (1 - 2.1e-9)
// pdd2_relaxed. A value below (1 - kClampMargin) pdd2_relaxed is therefore never lowered; above
// that (a tie: the best plane is pdd2_relaxed's candidate, common where faces are nearly
// parallel) the chain's other values are computed as solve_pair computes them and the same
// relations applied.
// Declined (std::nullopt): whenever the common double path does not apply as a whole — a pair
// that is not valid, not intersecting, or whose lane sweeps (the candidate set's sweeps, as
// solve_pair's, where the quick lanes decline: parallel edges, coplanar faces) or candidate
// choices are not certified in doubles; an enumeration not certified (one computed in
// rationals is taken again exactly on the pair as given, as solve_pair takes it); a value or a
// position outside the double range; at a tie, a value of the chain not certified in doubles
// or outside the double range (solve_pair's exact path). The caller
// then takes solve_pair (which gives the same fields, or declines pdd2_global itself).
// Witnesses: where solve_pair declines pdd2_global because no normal in doubles attains it
// (kGlobalNotRepresentable: a depth ~1e-17 of the pair's size, faces meant to coincide that
// rounding made cross — blocks stacked face to face, a grid against its shifted copy), the
// value may still be certified along an exact rational normal; global_minimiser then returns
// it with `witness` set, its normal and positions that witness's rounded (as the exact
// engine's witness is rounded to doubles), instead of declining.
// Bounds (options.bound_shallow): such a pair, and any valid intersecting pair whose depth is as
// far below its size, returned `bounded` instead (an estimate and a certified upper bound, not a
// certified value) in a few microseconds: where the quick lanes decline and one of the eight
// face normals' overlaps D(d) puts the bound D(d)^2 / d.d below 1e-20 of the pair's scale
// squared (a uniform move of B by the overlap along d separates at object-norm cost D(d)^2),
// else where the search's start is that shallow (its value's bound from value_error's chain).
// Where a bound's value or positions leave the double range, the pair is computed as without it.
#pragma once

#include <array>
#include <optional>

#include "pdd/pair_result.h"
#include "pdd/tet_pair.h"

namespace pdd::fast {

inline constexpr double kClampMargin = 4e-9;

struct GlobalMinimiser {
  double pd2 = 0.0;
  std::array<double, 3> normal{};
  Positions<double> q1_A{}, q1_B{};
  // pd2 certified (definitions §8), attained along a rational normal that no double triple
  // represents; `normal` and the positions are that witness rounded componentwise and do not
  // attain pd2 ("Witnesses" above). false on every pair solve_pair computes pdd2_global of.
  bool witness = false;
  // pd2 NOT certified (MinimiserOptions::bound_shallow): `upper` is a certified upper bound on
  // pdd2_global (below 1e-20 of the pair's scale squared), pd2 the doubles' estimate (0 < pd2
  // <= upper), `normal` the face normal of least bound or the search's start, and the positions
  // along it (displacements of object norm below sqrt(upper), as the minimiser's: within ~1e-9
  // of the pair's size of them). false on every other result.
  bool bounded = false;
  double upper = 0;
};

struct MinimiserOptions {
  // A depth so far below the pair's size (~1e-10 of it or less: a contact made by rounding,
  // faces meant to coincide) that certifying pd2 would take the shallow certificate or the
  // exact pieces (tens of microseconds to milliseconds): return `bounded` instead, in about the
  // time of a certified pair. For a caller summing many pairs that can bound such pairs' share
  // of the sum and compute in full only those whose share matters (the contact energy).
  bool bound_shallow = false;
};

std::optional<GlobalMinimiser> global_minimiser(const TetVertices& A, const TetVertices& B,
                                                const MinimiserOptions& options = {});

// pdd/pdd.h's "Translation" for a minimiser: with m = anchored_pair(A, B), global_minimiser(A, B)
// is global_minimiser(m.A, m.B) with its positions moved by this (move_positions' rule), unless
// it returns false (a coordinate would leave the double range: global_minimiser then computes
// the pair as given).
struct AnchoredPair;
bool move_positions(GlobalMinimiser& g, const AnchoredPair& m, const TetVertices& A, const TetVertices& B);

}  // namespace pdd::fast
