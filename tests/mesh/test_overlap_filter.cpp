// tests/mesh/test_overlap_filter.cpp — pdd::fast::overlap_filter and interiors_intersect
// (pdd.h; fast/src/overlap_filter.cpp), the decision stage of pdd::mesh::contacts, against an
// independent exact judge: a separating-axis test on GMP integers
// (tests/support/exact_overlap.h, shared with test_resolve.cpp).
//
// The judge (definitions §4: touching is not intersecting): for non-flat tetrahedra A and B the
// interiors are disjoint iff the origin is not interior to M = A ⊕ (−B), iff some facet normal
// u of M has max_i u.s_i <= min_j u.r_j (u or −u). Every facet normal of M is parallel to a
// face normal of A or of B or to eA × eB for non-parallel edges (a facet is the sum of faces of
// A and −B of total dimension 2). So: disjoint iff one of those 44 exact axes (zero ones
// skipped) weakly separates the vertex sets. Flat or non-finite tetrahedra: no interior, so
// never intersecting (definitions §1 rejects them; interiors_intersect returns false).
//
// What is checked, on every pair below: a Disjoint or Intersecting verdict of the filter equals
// the judge's (Unknown is always allowed), and interiors_intersect equals the judge. Pairs:
//   * every box pair of the shipped meshes (fixtures/meshes), including the element pairs of
//     one conforming mesh that share a face, an edge or a vertex (touching exactly, never
//     intersecting) and the conforming and touching mesh pairs;
//   * those touching neighbours translated by tiny amounts (2^-30 .. 2^-52 of the element
//     size) towards and away from each other: intersecting and disjoint pairs within rounding
//     of touching;
//   * every shipped fixture pair (fixtures/*.json, fixtures/families/*.json: touching,
//     near-touching, shared faces/edges/vertices, parallel edges, coplanar faces, slivers,
//     scaled by 2^±300, degenerate) and 300 fresh pairs of each of those families from the
//     generator, both orders (A, B) and (B, A).
// And that the filter is useful: on two generic overlapping balls it decides all but a few
// of the box pairs (else the decision stage would fall back to the slow path everywhere).
#define BOOST_TEST_MODULE overlap_filter
#include <boost/test/unit_test.hpp>

#include <gmpxx.h>
#include <tbb/concurrent_vector.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <string>

#include "exact_overlap.h"
#include "fixtures.h"
#include "pdd/compare/generate.h"
#include "pdd/mesh.h"

using namespace pdd;
using namespace pdd::mesh;

namespace {

// The judge (header): tests/support/exact_overlap.h.
using pdd::test::exact_interiors_intersect;

struct Tally {
  std::atomic<std::size_t> pairs{0}, intersecting{0}, unknown{0}, wrong_filter{0}, wrong_decision{0};
  tbb::concurrent_vector<std::string> wrong;  // which pairs (Boost.Test is not thread-safe)
};

// Checks one pair; counts; returns false on a wrong answer (the caller records it).
bool check(const TetVertices& A, const TetVertices& B, Tally& t) {
  const bool want = exact_interiors_intersect(A, B);
  const fast::Overlap v = fast::overlap_filter(A, B);
  const bool decision = fast::interiors_intersect(A, B);
  ++t.pairs;
  if (want) ++t.intersecting;
  if (v == fast::Overlap::Unknown) ++t.unknown;
  bool ok = true;
  if (v != fast::Overlap::Unknown && (v == fast::Overlap::Intersecting) != want) ++t.wrong_filter, ok = false;
  if (decision != want) ++t.wrong_decision, ok = false;
  return ok;
}

void report(const std::string& what, const Tally& t, bool expect_pairs = true) {
  BOOST_TEST_MESSAGE(what << ": " << t.pairs << " pairs, " << t.intersecting << " intersecting, "
                          << t.unknown << " left to the exact path");
  for (const auto& w : t.wrong) BOOST_TEST_MESSAGE("wrong: " << w);
  if (expect_pairs) BOOST_TEST(t.pairs > 0u, what);
  BOOST_TEST(t.wrong_filter == 0u, what << ": filter verdicts that contradict the exact judge");
  BOOST_TEST(t.wrong_decision == 0u, what << ": interiors_intersect != the exact judge");
}

const std::string kMeshes = std::string(PDD_FIXTURES_DIR) + "/meshes/";

std::vector<std::size_t> all(const Mesh& m) {
  std::vector<std::size_t> e(m.tets.size());
  std::iota(e.begin(), e.end(), std::size_t{0});
  return e;
}

// Every box pair of A x B (B null: of A with itself, vertex-sharing pairs included).
void check_box_pairs(const std::string& a, const std::string& b, Tally& t, bool expect_pairs = true) {
  const Mesh A = read_mesh(kMeshes + a);
  const Mesh B = b.empty() ? Mesh{} : read_mesh(kMeshes + b);
  const auto cand = b.empty() ? box_pairs_self(A, all(A)) : box_pairs(A, all(A), B, all(B));
  const Mesh& BB = b.empty() ? A : B;
  tbb::parallel_for(std::size_t{0}, cand.size(), [&](std::size_t k) {
    const TetVertices x = element(A, cand[k][0]), y = element(BB, cand[k][1]);
    if (!check(x, y, t)) t.wrong.push_back(a + " x " + b + " pair " + std::to_string(cand[k][0]) + ", " + std::to_string(cand[k][1]));
  });
  report(a + " x " + (b.empty() ? "itself" : b), t, expect_pairs);
}

}  // namespace

BOOST_AUTO_TEST_CASE(box_pairs_of_the_shipped_meshes) {
  Tally g, tb, sl, to, c, ts, s, v;
  check_box_pairs("sphere-a.msh", "sphere-b.msh", g);
  // Usefulness: two generic balls, every box pair decided by the filter but a few (the exact
  // path is for touching and parallel-edge pairs; 0.5% would already be 100x the expected).
  BOOST_TEST(g.intersecting > 100u);
  BOOST_TEST(g.unknown * 200 <= g.pairs);
  check_box_pairs("torus.msh", "box.vtk", tb);
  check_box_pairs("slivers.msh", "sphere-a.bin22.msh", sl);
  check_box_pairs("touching-a.msh", "touching-b.msh", to, false);
  BOOST_TEST(to.intersecting == 0u);  // the plane x = 1 between them (half-open boxes: no pair)
  check_box_pairs("conforming-a.msh", "conforming-b.msh", c);
  BOOST_TEST(c.intersecting == 0u);  // shared faces: touching, never intersecting
  BOOST_TEST(c.unknown > 0u);        // ... and the filter left the touching ones to the exact path
  check_box_pairs("two-spheres.msh", "", ts);
  // One conforming mesh with itself: the pairs sharing a face, an edge or a vertex touch.
  check_box_pairs("sphere-a.msh", "", s);
  BOOST_TEST(s.intersecting == 0u);
  check_box_pairs("slivers.msh", "", v);
  BOOST_TEST(v.intersecting == 0u);
}

BOOST_AUTO_TEST_CASE(touching_neighbours_moved_by_a_few_ulps) {
  // Face-, edge- and vertex-neighbours of a conforming mesh touch exactly; translate the second
  // element by d = s · (centroid(A) − centroid(B)) (towards A: s > 0 makes the pair intersect
  // unless rounding undoes the shift; away: s < 0 makes it disjoint), s = ±2^-30 .. ±2^-52.
  for (const char* name : {"sphere-a.msh", "slivers.msh"}) {
    const Mesh M = read_mesh(kMeshes + name);
    auto cand = box_pairs_self(M, all(M));
    std::vector<std::array<std::size_t, 2>> touching;
    for (const auto& p : cand) {
      bool share = false;
      for (auto u : M.tets[p[0]])
        for (auto w : M.tets[p[1]]) share |= u == w;
      if (share) touching.push_back(p);
    }
    if (touching.size() > 1500) touching.resize(1500);  // the exact fallback costs ms on some
    Tally t;
    tbb::parallel_for(std::size_t{0}, touching.size(), [&](std::size_t k) {
      const TetVertices A = element(M, touching[k][0]);
      const TetVertices B0 = element(M, touching[k][1]);
      Vec3d ca{0, 0, 0}, cb{0, 0, 0};
      for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) ca[c] += A[i][c] / 4, cb[c] += B0[i][c] / 4;
      for (int e : {30, 40, 46, 50, 52})
        for (double sign : {1.0, -1.0}) {
          TetVertices B = B0;
          const double s = sign * std::ldexp(1.0, -e);
          for (int i = 0; i < 4; ++i)
            for (int c = 0; c < 3; ++c) B[i][c] = B0[i][c] + s * (ca[c] - cb[c]);
          if (!check(A, B, t))
            t.wrong.push_back(std::string(name) + " pair " + std::to_string(touching[k][0]) + ", " +
                              std::to_string(touching[k][1]) + " shift 2^-" + std::to_string(e));
        }
    });
    report(std::string(name) + " touching neighbours shifted", t);
    BOOST_TEST(t.intersecting > 0u);               // some shifts do make pairs intersect
    BOOST_TEST(t.intersecting < t.pairs);          // and some do not
  }
}

BOOST_AUTO_TEST_CASE(fixture_pairs_both_orders) {
  std::vector<TetPair> pairs;
  for (const std::string& f : test::property_fixture_files())
    for (auto& p : test::load_pairs(f)) pairs.push_back(p);
  for (const auto& fam : compare::fixture_families()) {
    // Generic pairs (paper) and the families whose generator searches long (undecidable-optimum,
    // adversarial, rounding-contacts: tens of seconds for 300 pairs): their shipped files above
    // suffice.
    if (fam.name == "paper" || fam.name == "undecidable-optimum" || fam.name == "adversarial" ||
        fam.name == "rounding-contacts")
      continue;
    for (auto& p : compare::generate_family(fam.name, 20261123, 300)) pairs.push_back(p);
  }
  Tally t;
  tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t k) {
    const TetPair& p = pairs[k];
    if (!check(p.A, p.B, t) || !check(p.B, p.A, t)) t.wrong.push_back(p.name);
  });
  report("fixture and generated family pairs", t);
  BOOST_TEST(t.intersecting > 0u);
  BOOST_TEST(t.unknown > 0u);  // touching and degenerate pairs exist among them
}
