// Candidate directions (definitions §3): count, canonical order, orientation, degenerate edges.
#include <boost/test/unit_test.hpp>

#include "fixtures.h"
#include "pdd/reference/candidate_directions.h"

using namespace pdd;
using namespace pdd::reference;

namespace {
std::size_t count_undecidable(const std::vector<CandidateDirection>& c) {
  std::size_t k = 0;
  for (const auto& d : c) k += d.label.orientation == EdgeOrientation::Plus;
  return k;
}
const CandidateDirection* find(const std::vector<CandidateDirection>& c, const std::string& l) {
  for (const auto& d : c)
    if (d.label.str() == l) return &d;
  return nullptr;
}
}  // namespace

BOOST_AUTO_TEST_CASE(canonical_order_and_count) {
  for (const auto& file : test::property_fixture_files())
    for (const TetPair& pair : test::load_pairs(file)) {
      const ExactPair p = to_exact(pair);
      const auto c = candidate_directions(p);
      // 44, plus one per undecidable edge pair, minus one per colinear edge pair.
      BOOST_TEST(c.size() == 44 + count_undecidable(c) - colinear_edge_pairs(p).size(),
                 pair.name);
      for (std::size_t k = 1; k < c.size(); ++k) BOOST_TEST((c[k - 1].label < c[k].label));
    }
}

BOOST_AUTO_TEST_CASE(orientation_rules) {
  for (const auto& file : test::property_fixture_files())
    for (const TetPair& pair : test::load_pairs(file)) {
      const ExactPair p = to_exact(pair);
      for (const auto& d : candidate_directions(p)) {
        BOOST_TEST((d.n != CGAL::NULL_VECTOR));
        const auto& lab = d.label;
        if (lab.kind == ContactKind::FV) {  // out of A: s_i strictly behind the face
          BOOST_TEST(d.n * (p.A[lab.a] - p.A[(lab.a + 1) % 4]) < 0, pair.name << lab.str());
        } else if (lab.kind == ContactKind::VF) {  // into B: r_j strictly in front
          BOOST_TEST(d.n * (p.B[lab.a] - p.B[(lab.a + 1) % 4]) > 0, pair.name << lab.str());
        } else {
          const int u = kEdges[lab.a][0], v = kEdges[lab.a][1];
          BOOST_TEST(d.n * (p.A[v] - p.A[u]) == 0);  // n is orthogonal to both edges
          BOOST_TEST(d.n * (p.B[kEdges[lab.b][1]] - p.B[kEdges[lab.b][0]]) == 0);
          int pos = 0, neg = 0;
          for (int k = 0; k < 4; ++k) {
            if (k == u || k == v) continue;
            const auto s = CGAL::sign(d.n * (p.A[k] - p.A[u]));
            pos += s == CGAL::POSITIVE, neg += s == CGAL::NEGATIVE;
          }
          const bool undecidable = pos > 0 && neg > 0;
          BOOST_TEST(undecidable == (lab.orientation != EdgeOrientation::Decided));
          if (!undecidable) BOOST_TEST(pos == 0, "decided EE keeps A's others on n <= 0");
        }
      }
    }
}

BOOST_AUTO_TEST_CASE(undecidable_pairs_come_as_plus_then_minus) {
  const auto c = candidate_directions(to_exact(test::load_pair("smoke.json", "random-1")));
  BOOST_TEST(count_undecidable(c) > 0u);  // random-1 has undecidable edge pairs
  for (std::size_t k = 0; k < c.size(); ++k)
    if (c[k].label.orientation == EdgeOrientation::Plus) {
      BOOST_REQUIRE(k + 1 < c.size());
      BOOST_TEST((c[k + 1].label.orientation == EdgeOrientation::Minus));
      BOOST_TEST((c[k + 1].n == -c[k].n));
    }
}

BOOST_AUTO_TEST_CASE(parallel_edges_use_shortest_vector) {
  // A edge 0 = (0,0,0)-(4,0,0), B edge 0 = (1,.5,.5)-(3,.5,.5): parallel. w = (1,.5,.5),
  // e = (4,0,0): w - (w.e/e.e) e = (0,.5,.5). A's others s2 = (0,4,0), s3 = (0,0,4) give
  // g = 2, 2 >= 0, so the direction is -(0,.5,.5), i.e. a positive multiple of (0,-1,-1).
  const auto c = candidate_directions(to_exact(test::load_pair("smoke.json", "parallel-edges-1")));
  const CandidateDirection* d = find(c, "EE:0:0");
  BOOST_REQUIRE(d);
  BOOST_TEST((d->edge_kind == EdgePairKind::Parallel));
  BOOST_TEST(d->n.x() == 0);
  BOOST_TEST(d->n.y() < 0);
  BOOST_TEST(d->n.y() == d->n.z());
}

BOOST_AUTO_TEST_CASE(colinear_edges_give_no_direction) {
  // A edge 0 = (0,0,0)-(4,0,0) and B edge 0 = (1,0,0)-(3,0,0) lie on one line.
  const ExactPair p = to_exact(test::load_pair("degenerate.json", "colinear-edges-1"));
  const auto c = candidate_directions(p);
  BOOST_TEST(find(c, "EE:0:0") == nullptr);
  BOOST_TEST(find(c, "EE:0:0:+") == nullptr);
  const auto col = colinear_edge_pairs(p);
  BOOST_REQUIRE(col.size() == 1u);
  BOOST_TEST(col[0][0] == 0);
  BOOST_TEST(col[0][1] == 0);
}

BOOST_AUTO_TEST_CASE(labels_round_trip) {
  for (const std::string s : {"FV:0", "VF:3", "EE:0:5", "EE:5:0:+", "EE:2:3:-"}) {
    const auto l = DirectionLabel::parse(s);
    BOOST_REQUIRE(l.has_value());
    BOOST_TEST(l->str() == s);
  }
  for (const std::string s : {"FV:4", "EE:6:0", "EE:1:1:x", "VF:", "FV:0 ", "EE:1:2:+-"})
    BOOST_TEST(!DirectionLabel::parse(s).has_value(), s);
}
