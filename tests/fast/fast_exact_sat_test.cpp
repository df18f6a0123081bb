// The exact separating-axis decision (fast/src/exact/exact_sat.h) and interiors_intersect, which
// takes it for the pairs its filter leaves Unknown, against the independent GMP-integer judge of
// tests/support/exact_overlap.h (definitions §4: touching is not intersecting), on the inputs it
// is there for: elements of structured meshes (Kuhn and five-tetrahedra cells of grids at random
// decimal origins and sizes, so the coordinates are rounded doubles), one grid against a copy
// shifted by a non-grid offset, against the same grid (neighbours sharing faces, edges,
// vertices: touching exactly; the same cell cut differently: coplanar faces, colinear edges),
// stacked by exactly one cell (whole faces touching), each also with one coordinate moved by
// one ulp either way (intersecting or disjoint by a rounding), flat tetrahedra, generic pairs,
// and pairs scaled by powers of two inside and outside the expansions' range. Both orders.
#define BOOST_TEST_MODULE fast_exact_sat
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "exact/exact_sat.h"
#include "exact_overlap.h"
#include "structured_cells.h"
#include "fast_test_util.h"
#include "pdd/compare/random.h"
#include "pdd/pdd.h"
#include "pdd/tet_tables.h"

using namespace pdd;
using fast::detail::interiors_intersect_sat;
using fast::detail::SatVerdict;
using pdd::test::five_cell_tet;
using pdd::test::kuhn_cell_tet;

namespace {

struct Tally {
  int pairs = 0, intersecting = 0, touching_or_apart = 0, undecided = 0, wrong = 0;
  int face_disjoint = 0;  // pairs face_axes_sat decides Disjoint
};

// One pair, both orders: the SAT verdict (when decided) and interiors_intersect equal the judge.
void check(const TetVertices& A, const TetVertices& B, Tally& t, const std::string& what) {
  for (int o = 0; o < 2; ++o) {
    const TetVertices& P = o ? B : A;
    const TetVertices& Q = o ? A : B;
    const bool want = pdd::test::exact_interiors_intersect(P, Q);
    const SatVerdict v = interiors_intersect_sat(P, Q);
    const bool got = fast::interiors_intersect(P, Q);
    // the face axes alone: Disjoint only for pairs whose interiors are disjoint
    const SatVerdict faces = fast::detail::face_axes_sat(P, Q);
    ++t.pairs;
    (want ? t.intersecting : t.touching_or_apart) += 1;
    if (v == SatVerdict::Undecided) ++t.undecided;
    if (faces == SatVerdict::Disjoint) ++t.face_disjoint;
    const bool sat_wrong = (v != SatVerdict::Undecided && (v == SatVerdict::Intersecting) != want) ||
                           (faces == SatVerdict::Disjoint && want);
    if (sat_wrong || got != want) {
      ++t.wrong;
      if (t.wrong <= 5) BOOST_TEST_MESSAGE(what << ": order " << o << " judge " << want << " sat " << int(v));
    }
  }
}

// A grid cell's tetrahedron (kind 0: Kuhn, 1: five-tetrahedra) with cell index (i, j, l).
struct Grid {
  Vec3d origin;
  double h;
  int kind;
  TetVertices tet(int i, int j, int l, int which) const {
    const Vec3d o = {origin[0] + i * h, origin[1] + j * h, origin[2] + l * h};
    return kind == 0 ? kuhn_cell_tet(o, h, which % 6) : five_cell_tet(o, h, which % 5, ((i + j + l) & 1) != 0);
  }
};

// B with coordinate (v, k) moved one ulp up or down.
TetVertices nudged(TetVertices B, int v, int k, bool up) {
  B[v][k] = std::nextafter(B[v][k], up ? HUGE_VAL : -HUGE_VAL);
  return B;
}

void check_with_nudges(const TetVertices& A, const TetVertices& B, compare::ReproducibleRng& r, Tally& t,
                       const std::string& what) {
  check(A, B, t, what);
  for (int n = 0; n < 2; ++n) check(A, nudged(B, r.integer(0, 3), r.integer(0, 2), n == 0), t, what + " nudged");
}

}  // namespace

// The face parity table of exact_sat.h, on random tetrahedra (exact orientations).
BOOST_AUTO_TEST_CASE(face_parity_table) {
  compare::ReproducibleRng r(7);
  for (int n = 0; n < 50; ++n) {
    TetVertices T;
    for (auto& v : T)
      for (double& x : v) x = r.uniform(-3, 3);
    const int o = pdd::test::exact_orientation(T);
    BOOST_REQUIRE(o != 0);
    for (int f = 0; f < 4; ++f) {
      const TetVertices P = {T[kFace[f][0]], T[kFace[f][1]], T[kFace[f][2]], T[f]};
      BOOST_TEST(pdd::test::exact_orientation(P) == fast::detail::kFaceParity[f] * o);
    }
  }
}

// Structured meshes: shifted, same grid, stacked; every cell pair near the origin cell.
BOOST_AUTO_TEST_CASE(structured_mesh_pairs) {
  compare::ReproducibleRng r(38);
  Tally t;
  for (int draw = 0; draw < 60; ++draw) {
    Grid g{{r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)}, r.uniform(0.5, 2.0), draw % 2};
    const TetVertices A = g.tet(0, 0, 0, r.integer(0, 5));
    // (a) a copy shifted by a non-grid offset
    Grid s = g;
    for (int k = 0; k < 3; ++k) s.origin[k] += r.uniform(-1, 1) * g.h;
    for (int i = -1; i <= 0; ++i)
      for (int j = -1; j <= 0; ++j)
        for (int l = -1; l <= 0; ++l) check_with_nudges(A, s.tet(i, j, l, r.integer(0, 5)), r, t, "shifted");
    // (b) the same grid: neighbours touching; (c) the same cell cut differently
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        for (int l = -1; l <= 1; ++l) check_with_nudges(A, g.tet(i, j, l, r.integer(0, 5)), r, t, "same grid");
    for (int which = 0; which < 6; ++which) check_with_nudges(A, g.tet(0, 0, 0, which), r, t, "same cell");
    // (d) a block stacked on A's layer, shifted in x and y by non-grid offsets
    Grid up = g;
    up.origin = {g.origin[0] + r.uniform(-1, 1) * g.h, g.origin[1] + r.uniform(-1, 1) * g.h, g.origin[2] + g.h};
    // layer 0 of `up` has z = g.origin[2] + h exactly (A's top face z), as in a stacked block
    for (int i = -1; i <= 0; ++i)
      for (int j = -1; j <= 0; ++j) check_with_nudges(A, up.tet(i, j, 0, r.integer(0, 5)), r, t, "stacked");
  }
  BOOST_TEST_MESSAGE("pairs " << t.pairs << ", intersecting " << t.intersecting << ", undecided " << t.undecided);
  BOOST_TEST(t.wrong == 0);
  BOOST_TEST(t.undecided == 0);  // in the expansions' range: never left to rationals
  // the family has both answers in numbers (the test can fail either way)
  BOOST_TEST(t.intersecting > t.pairs / 20);  // 1268 of 16200 with these seeds
  BOOST_TEST(t.touching_or_apart > t.pairs / 10);
}

// A Kuhn grid against its copy shifted along (1, 1, 1) by a fraction of a cell: B's vertices on
// A's diagonal planes (x = y, y = z and x = z through grid points) and A's on B's. With the cell
// a power of two and the shift a short binary fraction (1/2, 1/4) those contacts are exact
// touching; with 1/10 or 1/3 the shifted coordinates round, and the faces that coincide in real
// arithmetic overlap or part by ~1e-17 of the cell (contacts made by rounding). interiors_intersect
// decides such pairs by their touching face planes first (overlap_filter.cpp).
BOOST_AUTO_TEST_CASE(diagonally_shifted_grid_pairs) {
  compare::ReproducibleRng r(111);
  Tally exact_shift, rounded_shift;
  for (int draw = 0; draw < 40; ++draw) {
    const double h = std::ldexp(1.0, r.integer(-4, 1));
    Grid g{{h * r.integer(-8, 8), h * r.integer(-8, 8), h * r.integer(-8, 8)}, h, 0};
    const bool rounded = draw % 2 == 1;
    const double frac = rounded ? (draw % 4 == 1 ? 0.1 : 1.0 / 3.0) : (draw % 4 == 0 ? 0.5 : 0.25);
    Grid s = g;
    for (int k = 0; k < 3; ++k) s.origin[k] += frac * h;
    const TetVertices A = g.tet(0, 0, 0, r.integer(0, 5));
    for (int i = -1; i <= 0; ++i)
      for (int j = -1; j <= 0; ++j)
        for (int l = -1; l <= 0; ++l)
          for (int which = 0; which < 6; ++which)
            check(A, s.tet(i, j, l, which), rounded ? rounded_shift : exact_shift, "diagonal shift");
  }
  for (const Tally* t : {&exact_shift, &rounded_shift}) {
    BOOST_TEST_MESSAGE("pairs " << t->pairs << ", intersecting " << t->intersecting << ", face axes disjoint "
                                << t->face_disjoint);
    BOOST_TEST(t->wrong == 0);
    BOOST_TEST(t->undecided == 0);
    // both answers, and face planes that separate exactly, in numbers (the test can fail either way)
    BOOST_TEST(t->intersecting > t->pairs / 20);
    BOOST_TEST(t->face_disjoint > t->pairs / 10);
  }
}

// Generic pairs, flat tetrahedra, and scales inside / outside the expansions' range.
BOOST_AUTO_TEST_CASE(generic_flat_and_scaled_pairs) {
  Tally t;
  for (const TetPair& p : fast::test::random_pairs(300, 5, false)) check(p.A, p.B, t, p.name);
  BOOST_TEST(t.wrong == 0);
  BOOST_TEST(t.undecided == 0);
  BOOST_TEST(t.intersecting > 0);
  BOOST_TEST(t.touching_or_apart > 0);

  compare::ReproducibleRng r(3);
  Tally flat;
  for (int n = 0; n < 50; ++n) {
    Grid g{{r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)}, r.uniform(0.5, 2.0), 0};
    const TetVertices A = g.tet(0, 0, 0, r.integer(0, 5));
    TetVertices B = g.tet(0, 0, 0, r.integer(0, 5));
    B[3] = B[r.integer(0, 2)];  // a repeated vertex: flat
    check(A, B, flat, "flat");
    BOOST_TEST((interiors_intersect_sat(A, B) == SatVerdict::Disjoint));
  }
  BOOST_TEST(flat.wrong == 0);

  // Outside the expansions' range the integer frame (integer_heights.h) decides the pairs whose
  // coordinates it takes (below 2^60, spanning at most 60 bits); the others are Undecided (the
  // rational path decides them).
  Tally in_range, out_of_range_framed, out_of_range_unframed;
  for (int n = 0; n < 40; ++n) {
    Grid g{{r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)}, r.uniform(0.5, 2.0), n % 2};
    const TetVertices A0 = g.tet(0, 0, 0, r.integer(0, 5));
    const TetVertices B0 = g.tet(r.integer(-1, 1), r.integer(-1, 1), 0, r.integer(0, 5));
    for (int e : {-150, 150, -260, 260}) {
      TetVertices A = A0, B = B0;
      for (auto* T : {&A, &B})
        for (auto& v : *T)
          for (double& x : v) x = std::ldexp(x, e);  // exact
      const bool framed = fast::detail::IntegerFrame(A, B).usable();
      check(A, B, std::abs(e) < 200 ? in_range : framed ? out_of_range_framed : out_of_range_unframed, "scaled");
    }
  }
  BOOST_TEST(in_range.wrong == 0);
  BOOST_TEST(in_range.undecided == 0);
  BOOST_TEST(out_of_range_framed.wrong == 0);
  BOOST_TEST(out_of_range_framed.undecided == 0);
  BOOST_TEST(out_of_range_framed.pairs > 0);
  BOOST_TEST(out_of_range_unframed.wrong == 0);
  BOOST_TEST(out_of_range_unframed.undecided == out_of_range_unframed.pairs);
  BOOST_TEST(out_of_range_unframed.pairs > 0);
}
