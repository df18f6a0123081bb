// fast_aligned_global_test — definitions §9 on aligned pairs (parallel faces, parallel and
// colinear edges, coplanar faces: the pairs of structured meshes) stays on the double path.
//
// Pairs: the shipped aligned family (fixtures/families/aligned.json: Kuhn and five-tetrahedra
// cubes shifted by a non-grid offset, stacked cubes with touching faces) and the degenerate
// families of parallel edges, colinear edges and coplanar faces. On all of them the quick
// candidate lanes decline, which used to send the definitions §9 search to work without a start
// (all 225 pieces to the eigensolver, and on shifted five-tetrahedra pairs the exact pieces) and
// made global_minimiser decline every pair (the contact energy then ran the whole solve_pair).
// Pinned without timing, by what each path reports:
//  - global_depth with no start normal (the caller had no candidate: global_depth.h offers the
//    pair's own shallowest directions) neither builds its pieces in rationals (exact_value) nor
//    declines (certified), and its value is solve_pair's pdd2_global within definitions §8
//    twice over (both within 1e-9 of the exact minimum: 2e-9 of each other);
//  - global_minimiser declines none of them and equals solve_pair's definitions §9 fields bit
//    for bit (pdd/global_minimiser.h); so on the near-touching family, whose enumeration is
//    exact (its value taken again in rationals, as solve_pair takes it).
// solve_pair's pdd2_global itself is judged against the exact engine by fast_golden_test and
// tests/compare (golden records of these files).
#define BOOST_TEST_MODULE fast_aligned_global
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "global/facet_bounds.h"
#include "global/global_depth.h"
#include "global/relaxed_value.h"
#include "pdd/global_minimiser.h"
#include "pdd/io/fixture_io.h"
#include "pdd/pdd.h"

using namespace pdd;

namespace {

const std::string kFixtures = PDD_FAST_FIXTURES_DIR;
const char* const kFiles[] = {"families/aligned.json", "families/parallel-edges.json",
                              "families/colinear-edges.json", "families/coplanar-faces.json"};

std::vector<TetPair> read_pairs(const std::string& file) {
  const io::FixtureFile f = io::read_fixture_file(file);
  if (f.error) throw std::runtime_error(file + ": " + *f.error);
  std::vector<TetPair> out;
  for (const auto& e : f.entries) out.push_back(e.pair);
  return out;
}

// The intersecting pairs of every file with their solve_pair records (definitions §9 on).
struct Solved {
  TetPair pair;
  PairResult<double> record;
};
std::vector<Solved> solved_pairs(const std::vector<const char*>& files = {std::begin(kFiles), std::end(kFiles)}) {
  std::vector<Solved> out;
  fast::SolveOptions o;
  o.with_global = true;
  for (const char* f : files)
    for (const TetPair& p : read_pairs(kFixtures + "/" + f)) {
      PairResult<double> r = fast::solve_pair(p, o);
      if (!r.error && r.intersecting) out.push_back({p, r});
    }
  return out;
}

// A pair and its exact pdd2_global (`pdd solve --engine reference`'s, a rational string).
struct ExactCase {
  TetVertices A, B;
  const char* exact;
};

// The pair stays in doubles: the public function (its start from the superset) and solve_pair's
// record within definitions §8 of the exact value, no slow path, and the enumeration itself,
// from solve_pair's bounds, certified and not in rationals.
void check_in_doubles(const ExactCase& c) {
  const double exact = mpq_class(c.exact).get_d();
  const fast::NormalDepth d = fast::pdd2_global(c.A, c.B);
  BOOST_TEST(std::fabs(d.pd2 - exact) <= 1e-9 * exact, d.pd2 << " vs exact " << exact);
  fast::SolveOptions o;
  o.with_global = true;
  const PairResult<double> r = fast::solve_pair(TetPair{"", {}, c.A, c.B}, o);
  BOOST_REQUIRE(!r.pdd2_global_error);
  BOOST_TEST(std::fabs(r.pdd2_global - exact) <= 1e-9 * exact);
  BOOST_TEST(!r.stats.slow_path);  // not in rationals
  const double none[3] = {0, 0, 0};
  const fast::GlobalOptimum g = fast::global_depth(c.A, c.B, none, r.pdd2_relaxed, {}, r.rigid_pd2);
  BOOST_TEST(g.certified);
  BOOST_TEST(!g.exact_value);
}

// Random pairs for the sampled-normal tests: a unit vector (uniform on the sphere, by rejection
// from the cube), and a pair of tetrahedra, A's coordinates in [-1, 1], B's in [-0.5, 1.1].
struct RandomPairs {
  std::mt19937_64 rng;
  std::uniform_real_distribution<double> U{-1, 1};
  explicit RandomPairs(std::uint64_t seed) : rng(seed) {}
  fast::global::V3 unit() {
    for (;;) {
      const fast::global::V3 u{U(rng), U(rng), U(rng)};
      const double n = fast::global::norm(u);
      if (n > 0.1 && n < 1) return fast::global::mul(u, 1 / n);
    }
  }
  void pair(TetVertices& A, TetVertices& B) {
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) A[i][k] = U(rng), B[i][k] = U(rng) * 0.8 + 0.3;
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(global_depth_without_start_stays_in_doubles) {
  const std::vector<Solved> pairs = solved_pairs();
  BOOST_TEST(pairs.size() >= 30u);  // 24 aligned + the degenerate families' intersecting pairs
  const double none[3] = {0, 0, 0};
  int exact = 0;
  for (const Solved& s : pairs) {
    BOOST_TEST_CONTEXT(s.pair.name) {
      const PairResult<double>& r = s.record;
      BOOST_REQUIRE(!r.pdd2_global_error);
      // the pair as given (coordinates of order 1: inside the double pieces' range); the
      // bounds as the pdd2_global fallback passes them: certified rigid_pd2 and pdd2_relaxed
      const fast::GlobalOptimum g = fast::global_depth(s.pair.A, s.pair.B, none, r.pdd2_relaxed, {}, r.rigid_pd2);
      exact += g.exact_value;
      BOOST_TEST(g.certified);
      BOOST_TEST(std::fabs(g.value - r.pdd2_global) <= 2e-9 * r.pdd2_global, g.value << " vs " << r.pdd2_global);
      bool ok = true;  // the normal reproduces the value (definitions §8 on the normal)
      const double along = fast::exact_relaxed_value(s.pair.A, s.pair.B, g.normal, ok);
      BOOST_TEST(ok);
      BOOST_TEST(std::fabs(along - g.value) <= 1e-9 * along, along << " along the normal, reported " << g.value);
    }
  }
  BOOST_TEST(exact == 0);  // none in rationals: the start's offers prune as a caller's start does
}

// global_minimiser against solve_pair's fields on `pairs`: the number declined and compared.
std::pair<int, int> check_against_solve_pair(const std::vector<Solved>& pairs) {
  int declined = 0, compared = 0;
  for (const Solved& s : pairs) {
    BOOST_TEST_CONTEXT(s.pair.name) {
      const auto g = fast::global_minimiser(s.pair.A, s.pair.B);
      if (!g) {
        ++declined;
        continue;
      }
      const PairResult<double>& r = s.record;
      BOOST_REQUIRE(!r.pdd2_global_error);
      BOOST_TEST(g->pd2 == r.pdd2_global);
      BOOST_TEST((g->normal == *r.pdd2_global_normal));
      BOOST_TEST((g->q1_A == r.q1_A_global));
      BOOST_TEST((g->q1_B == r.q1_B_global));
      ++compared;
    }
  }
  return {declined, compared};
}

BOOST_AUTO_TEST_CASE(global_minimiser_takes_aligned_pairs) {
  const auto [declined, compared] = check_against_solve_pair(solved_pairs());
  BOOST_TEST(compared >= 30);
  BOOST_TEST(declined == 0);
}

// Near-touching pairs (depths ~1e-12 of their size): global_depth builds the pieces in
// rationals, and solve_pair takes the value again exactly on the pair as given; global_minimiser
// does the same instead of declining (the caller would redo the exact enumeration in solve_pair).
BOOST_AUTO_TEST_CASE(global_minimiser_takes_exact_enumerations) {
  const auto [declined, compared] = check_against_solve_pair(solved_pairs({"families/near-touching.json"}));
  BOOST_TEST(compared == 4);  // the family's 4 intersecting pairs
  BOOST_TEST(declined == 0);
}

// A double eigenvalue (symmetric aligned pairs: gaps of ~1e-19 beside eigenvalues of ~1e-3)
// is taken as a plane on the double path (piece_visit.h's plane_accurate) instead of sending
// the pair to the exact pieces, which took milliseconds. Pairs `aligned-2-106`,
// `aligned-9-442` and `aligned-10-246` of `pdd generate --family aligned --seed 2 / 9 / 10
// --count 1000`, the pairs of three seeds whose enumeration met such a plane; each exact value is
// `pdd solve --engine reference`'s pdd2_global of the pair (its lower bound within 1e-12).
BOOST_AUTO_TEST_CASE(double_eigenvalues_stay_in_doubles) {
  const ExactCase cases[] = {
      {{{{-3.5062469909220626, -1.737735460655986, 4.685418596745679},
         {-4.064606358716736, -1.1793760928613126, 4.685418596745679},
         {-4.064606358716736, -1.737735460655986, 5.243777964540352},
         {-3.5062469909220626, -1.1793760928613126, 5.243777964540352}}},
       {{{-3.58567839667384, -1.6978706536441206, 4.672583925099658},
         {-4.144037764468513, -1.1395112858494472, 4.672583925099658},
         {-4.144037764468513, -1.6978706536441206, 5.230943292894331},
         {-3.58567839667384, -1.1395112858494472, 5.230943292894331}}},
       "770294648834778934385293017459600739569257032722407631659722963/"
       "47281695449962029579754208688841821549162802136759026501812224000"},
      {{{{-0.7241668273057513, -2.17430759713932, -2.8637481033613055},
         {1.1483039256768024, -2.17430759713932, -2.8637481033613055},
         {-0.7241668273057513, -0.30183684415676626, -2.8637481033613055},
         {-0.7241668273057513, -2.17430759713932, -0.9912773503787518}}},
       {{{0.7997103281263889, -1.8518570277416997, -4.729680841812904},
         {0.7997103281263889, -3.7243277807242534, -4.729680841812904},
         {2.672181081108943, -1.8518570277416997, -4.729680841812904},
         {0.7997103281263889, -1.8518570277416997, -2.8572100888303504}}},
       "49943413496782325213506678317525171593282642340446609624772114693/"
       "30195286851041787482554567775737987435788954763265787557562821189304320"},
      {{{{-3.565390723200219, 0.9018292728370589, -1.599063893992815},
         {-2.2595091485012975, 0.9018292728370589, -1.599063893992815},
         {-2.2595091485012975, 0.9018292728370589, -0.2931823192938934},
         {-2.2595091485012975, 2.2077108475359806, -0.2931823192938934}}},
       {{{-3.8388621023725076, -0.4017962517128042, -0.9947656295455404},
         {-3.8388621023725076, 0.9040853229861174, -0.9947656295455404},
         {-2.532980527673586, 0.9040853229861174, -0.9947656295455404},
         {-2.532980527673586, 0.9040853229861174, 0.31111594515338126}}},
       "4591725926317378701245555944957639217103318787059032607750672507/"
       "11215383268277739161133030883667830058032849160102051611187662783774720"},
  };
  for (const ExactCase& c : cases) check_in_doubles(c);
}

// Minimisers tied at a vertex of A - B: blocks of cubes of 0.1 cut into five (vertex coordinates
// i 0.1, each rounded once, A's top 3 x 0.1 = 0.30000000000000004), B's bottom 1e-9 under it
// (1e-10 for the last pair), on A's columns with the cuts alternating across the contact. The
// overlap is least along two facet normals at once (the first, third and fourth pairs: (1, -1,
// 1) and (-1, -1, 1), d / sqrt(3) each, or an edge on the collinear edge on either side of it)
// or three (the second); one cap of the shallow certificate leaves the other minimisers outside
// the ball, a cap about each covers them (shallow_certificate.h), and on the third pair the walk
// from the pair's own starts finds no multipliers, from the other least-overlap direction it
// does (global_depth.cpp's least_overlap_starts). Each exact value is `pdd solve --engine
// reference`'s pdd2_global of the pair (its lower bound within 1e-12).
BOOST_AUTO_TEST_CASE(minimisers_tied_at_a_vertex_stay_in_doubles) {
  const double t = 0.30000000000000004, b9 = 0.299999999, u9 = 0.39999999900000005;
  const double b10 = 0.29999999990000004, u10 = 0.3999999999;
  const ExactCase cases[] = {
      {{{{0.1, 0.0, 0.2}, {0.1, 0.1, 0.2}, {0.1, 0.1, t}, {0.2, 0.1, 0.2}}},
       {{{0.1, 0.0, b9}, {0.2, 0.0, b9}, {0.1, 0.1, b9}, {0.1, 0.0, u9}}},
       "18170968945527974473497014903549913360719293741163996554947855668687586933194114451123906661796"
       "458511803029323037/"
       "17444129092359044943792171795211013513103976240769830462485691110414445586505631043624972996415"
       "07375915130000546110152982486048571392"},
      {{{{0.1, 0.0, 0.2}, {0.0, 0.1, 0.2}, {0.0, 0.0, t}, {0.1, 0.1, t}}},
       {{{0.0, 0.0, b9}, {0.0, 0.0, u9}, {0.1, 0.0, u9}, {0.0, 0.1, u9}}},
       "89949018136949952562857665503020609849754065232576479893550807619299287729484887293264120338604"
       "00602130699125095706588332682262174172678232304676638215607572112859757753644111/"
       "86351051989336218449022529393349154968688216210410736020574207665747468881755742670285237308592"
       "35463140612052199663108749308772187498610188172184446293048942824657616511593621574312399121793"
       "67936"},
      {{{{0.5, 0.0, 0.2}, {0.4, 0.1, 0.2}, {0.4, 0.0, t}, {0.5, 0.1, t}}},
       {{{0.5, 0.1, b9}, {0.4, 0.0, b9}, {0.5, 0.0, u9}, {0.4, 0.1, u9}}},
       "702081982691335567223148465761053386400093224023/"
       "25274949719620954890162990498165569009348437376801389702160287006720"},
      {{{{0.1, 0.0, 0.2}, {0.0, 0.1, 0.2}, {0.0, 0.0, t}, {0.1, 0.1, t}}},
       {{{0.1, 0.1, b10}, {0.0, 0.0, b10}, {0.1, 0.0, u10}, {0.0, 0.1, u10}}},
       "9522597404218056104161349882228713430025/34281344944191784183045706266634214036936743604805767463436288"},
  };
  for (const ExactCase& c : cases) check_in_doubles(c);
}

// Nearly aligned resting contacts: stacked Kuhn blocks of cell h = 1/8, B's bottom a third of a
// cell into A's top, B tilted 1e-6 rad about (1, 2, 3) (a simulator's blocks a step after
// touching). Pairs across the cells' vertical faces meet ~1e-7 of h deep (pdd2_global ~1e-14),
// where a piece's in-window eigenvalue (~1e-13 |H|) sits beside a near-zero one (three or four
// nearly coplanar active vertices): the accuracy estimate saw a gap of the eigenvalue itself and
// sent about a quarter of these pairs to the exact pieces (milliseconds each); piece_visit.h's
// ritz_pair keeps them in doubles. Pinned without timing:
//  - four such pairs (8 x 8 x 3 blocks, pairs 1, 22, 46 and 70 of their 2552), each against
//    `pdd solve --engine reference --variants global`'s exact pdd2_global, taken in doubles
//    (no slow path, global_depth not in rationals);
//  - 3 x 3 blocks built here: no pair whose pdd2_global exceeds 1e-24 takes the exact path (the
//    ones below, contacts made by the rotation's rounding ~1e-13 of h deep, are exact by
//    design: global_depth.cpp's kCompactTiny), and each value is the relaxed value along its
//    own normal (exact_relaxed_value) within definitions §8.
BOOST_AUTO_TEST_CASE(nearly_aligned_resting_contacts_stay_in_doubles) {
  const ExactCase cases[] = {
      {{{{0, 0, 0.25}, {0.125, 0, 0.25}, {0.125, 0.125, 0.25}, {0.125, 0.125, 0.375}}},
       {{{4.0089205927129612e-07, -4.0089172004265095e-07, 0.33333346696379357},
         {3.0066910250425849e-07, 0.12499959910823538, 0.33333350037147558},
         {0.12500030066904444, 0.12499969933121002, 0.3333334335561785},
         {0.12500036748436832, 0.12499966592358158, 0.45833343355615619}}},
       "14197790448792241464606517212346394298681910440168260031835661/"
       "904621979960145150968308256614330273693888676846142765862118373014280077312"},
      {{{{0, 0, 0.25}, {0, 0, 0.375}, {0.125, 0, 0.375}, {0.125, 0.125, 0.375}}},
       {{{4.0089205927129612e-07, -4.0089172004265095e-07, 0.33333346696379357},
         {3.0066910250425849e-07, 0.12499959910823538, 0.33333350037147558},
         {3.6748442638900869e-07, 0.12499956570060694, 0.45833350037145326},
         {0.12500036748436832, 0.12499966592358158, 0.45833343355615619}}},
       "612085398265998499579449869524855436787691797032300630641974291/"
       "29400244550903814557174647938578586375438628023908184463538736592862283038720"},
      {{{{0, 0.125, 0.25}, {0, 0.25, 0.25}, {0, 0.25, 0.375}, {0.125, 0.25, 0.375}}},
       {{{2.0044614573722086e-07, 0.2499995991081907, 0.33333353377915759},
         {0.12500020044608767, 0.24999969933116534, 0.33333346696386051},
         {0.12500026726141156, 0.2499996659235369, 0.45833346696383814},
         {0.12500016703845473, 0.37499966592349226, 0.45833350037152021}}},
       "29417361084468454020838325937996744342696792692399972256698174347/"
       "1736881338564380281493342187508301124310212337228375677148726259477532786032640"},
      {{{{0, 0.25, 0.25}, {0.125, 0.25, 0.25}, {0.125, 0.25, 0.375}, {0.125, 0.375, 0.375}}},
       {{{2.0044614573722086e-07, 0.2499995991081907, 0.33333353377915759},
         {1.0022318891467208e-07, 0.37499959910814606, 0.3333335671868396},
         {0.12500010022313085, 0.37499969933112071, 0.33333350037154252},
         {0.12500016703845473, 0.37499966592349226, 0.45833350037152021}}},
       "556552349694455469138457973778574983563595166943272220005560529/"
       "72369812793749080090896157345362994709894703832013985312016451765207144857600"},
  };
  for (const ExactCase& c : cases) check_in_doubles(c);

  // 3 x 3 blocks, one layer each (A's top, B's bottom), B tilted as above about its bottom
  // face's centre.
  const int n = 3;
  const double h = 0.125, zb = h - h / 3, t = 1e-6;
  const double ax = 1 / std::sqrt(14.0), ay = 2 / std::sqrt(14.0), az = 3 / std::sqrt(14.0);
  const double co = std::cos(t), si = std::sin(t), C = 1 - co;
  const double R[3][3] = {{co + ax * ax * C, ax * ay * C - az * si, ax * az * C + ay * si},
                          {ay * ax * C + az * si, co + ay * ay * C, ay * az * C - ax * si},
                          {az * ax * C - ay * si, az * ay * C + ax * si, co + az * az * C}};
  const Vec3d centre = {n * h / 2, n * h / 2, zb};
  std::vector<TetVertices> A, B;
  static const int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (const auto& p : kPerm) {
        TetVertices a, b;
        int step[3] = {0, 0, 0};
        for (int v = 0; v < 4; ++v) {
          if (v > 0) step[p[v - 1]] = 1;
          const Vec3d local = {(i + step[0]) * h, (j + step[1]) * h, step[2] * h};
          a[v] = {local[0], local[1], local[2]};
          const Vec3d q = {local[0] - centre[0], local[1] - centre[1], local[2] + zb - centre[2]};
          for (int r = 0; r < 3; ++r) b[v][r] = centre[r] + R[r][0] * q[0] + R[r][1] * q[1] + R[r][2] * q[2];
        }
        A.push_back(a);
        B.push_back(b);
      }
  int pairs = 0, slow = 0, slow_above = 0, shallow = 0;
  for (const TetVertices& a : A)
    for (const TetVertices& b : B) {
      fast::SolveOptions o;
      o.with_global = true;
      const PairResult<double> r = fast::solve_pair(TetPair{"", {}, a, b}, o);
      if (r.error || !r.intersecting) continue;
      BOOST_REQUIRE(!r.pdd2_global_error);
      ++pairs;
      slow += r.stats.slow_path;
      const bool above = r.pdd2_global > 1e-24;
      slow_above += above && r.stats.slow_path;
      shallow += above && r.pdd2_global < 1e-10;
      bool ok = true;
      const double along = fast::exact_relaxed_value(a, b, *r.pdd2_global_normal, ok);
      BOOST_TEST(ok);
      BOOST_TEST(std::fabs(along - r.pdd2_global) <= 1e-9 * along);
    }
  BOOST_TEST_MESSAGE("nearly aligned blocks: " << pairs << " intersecting pairs, " << shallow
                                               << " shallow (1e-24 < pdd2_global < 1e-10), " << slow
                                               << " on the exact path, " << slow_above << " of them above 1e-24");
  BOOST_TEST(shallow >= 20);
  BOOST_TEST(slow_above == 0);
}

// Contacts made by rounding: blocks whose coordinates are k h (h = 0.1, rounded once), A's top
// at 3 h = 0.30000000000000004 and B = A moved up by 0.3 (its bottom at 0.3: stacked face to
// face, as a user builds them), and a Kuhn grid against its copy moved by 0.01 along (1, 1, 1),
// whose faces x = y coincide in exact arithmetic. Rounding makes the faces cross ~1e-17 deep;
// pdd2_global is ~1e-35, ~1e-33 of a cell squared, and is attained along a normal ~1e-17 off
// the face normal. Each case's exact value is `pdd solve --engine reference --variants
// global`'s pdd2_global rounded to 17 digits (its proved lower bound within 2e-15 of it).
//  - Stacked: suspect_proof.h settles the suspects (a zero eigenvalue beside mu: its gap and
//    mu located by exact counts) and a double normal attains the value: solve_pair reports it.
//  - Shifted along (1, 1, 1): no double normal attains it (solve_pair declines, definitions §8
//    and §9: no normal to report), but the value is certified along a rational witness, which
//    global_minimiser returns for the contact energy (`witness`), within definitions §8.
BOOST_AUTO_TEST_CASE(contacts_made_by_rounding) {
  const double h = 0.1, z = 0.3, d = 0.01;
  struct Case {
    TetVertices A, B;
    double exact;
    bool double_normal;  // solve_pair reports it (else only global_minimiser's witness)
  };
  const Case cases[] = {
      {{{{0, 0, 2 * h}, {0, 0, 3 * h}, {h, 0, 3 * h}, {h, h, 3 * h}}},
       {{{0, 0, z}, {h, 0, z}, {h, 0, h + z}, {h, h, h + z}}},
       1.28395329625815738e-34,
       true},
      {{{{0, 3 * h, 2 * h}, {0, 3 * h, 3 * h}, {h, 3 * h, 3 * h}, {h, 4 * h, 3 * h}}},
       {{{0, 3 * h, z}, {h, 3 * h, z}, {h, 4 * h, z}, {h, 4 * h, h + z}}},
       5.77778983316170756e-34,
       true},
      {{{{0, 0, h}, {h, 0, h}, {h, h, h}, {h, h, 2 * h}}},
       {{{d, d, h + d}, {h + d, d, h + d}, {h + d, d, 2 * h + d}, {h + d, h + d, 2 * h + d}}},
       1.30837632091524171e-36,
       false},
      {{{{0, 0, h}, {h, 0, h}, {h, h, h}, {h, h, 2 * h}}},
       {{{d, d, h + d}, {d, d, 2 * h + d}, {h + d, d, 2 * h + d}, {h + d, h + d, 2 * h + d}}},
       4.76820243713829248e-37,
       false},
      {{{{0, 0, h}, {h, 0, h}, {h, 0, 2 * h}, {h, h, 2 * h}}},
       {{{d, d, h + d}, {h + d, d, h + d}, {h + d, h + d, h + d}, {h + d, h + d, 2 * h + d}}},
       2.52237908924615706e-36,
       false},
  };
  for (const Case& c : cases) {
    fast::SolveOptions o;
    o.with_global = true;
    const PairResult<double> r = fast::solve_pair(TetPair{"", {}, c.A, c.B}, o);
    BOOST_REQUIRE(!r.error);
    BOOST_TEST(bool(r.pdd2_global_error) == !c.double_normal);
    const auto g = fast::global_minimiser(c.A, c.B);
    BOOST_REQUIRE(g);
    BOOST_TEST(g->witness == !c.double_normal);
    BOOST_TEST(std::fabs(g->pd2 - c.exact) <= 1e-9 * c.exact, g->pd2 << " vs exact " << c.exact);
    if (c.double_normal) {
      BOOST_TEST(r.pdd2_global == g->pd2);
      BOOST_TEST((*r.pdd2_global_normal == g->normal));
    }
  }
}

// Contacts made by rounding whose minimiser lies where two pieces meet: a Gmsh transfinite box
// (cells of 1/3 and 1/7) against its copy moved one cell, and Kuhn blocks of cell 1/6 placed
// on each other up to a rounding (their coordinates written as computed). The exact minimiser's
// normal, rounded, has a vertex at the plane whose margin is ~0 in compensated heights, so its
// value is certified only by bracketing that vertex on either side (deformable_depth.h's
// relaxed_compensated): the shallow certificate's cap then holds and solve_pair reports the
// value along a double normal. Each exact value is `pdd solve --engine reference --variants
// global`'s pdd2_global rounded to 18 digits (its proved lower bound within 6e-15 of it).
struct RoundingCase {
  TetVertices A, B;
  double exact;
};
const std::vector<RoundingCase>& pieces_meet_cases() {
  static const std::vector<RoundingCase> cases = {
      {{{{0.3333333333333334, 2.0, 0.3333333333333334}, {0.3333333333333334, 1.666666666666666, 0.6666666666666667},
         {0.6666666666666669, 1.666666666666667, 0.6666666666666667}, {0.3333333333333333, 2.0, 0.6666666666666667}}},
       {{{0.3333333333333333, 2.0, 0.3333333333333333}, {0.3333333333333333, 1.666666666666667, 0.6666666666666666},
         {0.6666666666666667, 1.666666666666666, 0.3333333333333334}, {0.6666666666666667, 1.666666666666666, 0.6666666666666667}}},
       9.55261252416068053e-33},
      {{{{1.333333333333333, 1.0, 0.3333333333333334}, {1.333333333333333, 0.666666666666667, 0.6666666666666672},
         {1.666666666666667, 0.6666666666666669, 0.6666666666666666}, {1.333333333333334, 1.0, 0.6666666666666669}}},
       {{{1.3333333333333333, 0.6666666666666666, 1.0}, {1.3333333333333333, 0.6666666666666665, 0.666666666666667},
         {1.3333333333333333, 1.0, 0.6666666666666664}, {1.6666666666666663, 0.666666666666667, 0.6666666666666672}}},
       9.86076131526266043e-33},
      {{{{1.666666666666667, 1.333333333333333, 0.0}, {1.666666666666667, 1.0, 0.3333333333333334},
         {1.666666666666667, 1.333333333333333, 0.3333333333333334}, {1.333333333333333, 1.333333333333334, 0.3333333333333335}}},
       {{{1.6666666666666663, 1.333333333333334, 0.3333333333333335}, {1.3333333333333333, 1.333333333333334, 0.3333333333333332},
         {1.6666666666666672, 1.0, 0.6666666666666669}, {1.3333333333333333, 1.333333333333333, 0.6666666666666664}}},
       1.20370621524201676e-33},
      {{{{0.0, 0.16666666666666669, 0.33333333333333326}, {0.16666666666666666, 0.1666666666666666, 0.33333333333333337},
         {0.16666666666666663, 0.3333333333333334, 0.3333333333333333}, {0.1666666666666666, 0.33333333333333337, 0.49999999999999994}}},
       {{{0.0, 0.3333333333333334, 0.4444444444444444}, {0.16666666666666669, 0.33333333333333326, 0.4444444444444444},
         {0.16666666666666663, 0.5000000000000002, 0.4444444444444444}, {0.1666666666666666, 0.5000000000000001, 0.611111111111111}}},
       7.25927440576727005e-34},
      {{{{0.0, 0.16666666666666669, 0.33333333333333326}, {0.1666666666666666, 0.16666666666666669, 0.49999999999999994},
         {0.16666666666666666, 0.1666666666666666, 0.33333333333333337}, {0.1666666666666666, 0.33333333333333337, 0.49999999999999994}}},
       {{{0.0, 0.0, 0.4444444444444444}, {0.16666666666666663, 0.1666666666666667, 0.4444444444444444},
         {0.0, 0.16666666666666666, 0.4444444444444444}, {0.1666666666666667, 0.16666666666666666, 0.611111111111111}}},
       1.33333611534500940e-34},
      {{{{1.142857142857143, 1.0, 0.2857142857142863}, {1.142857142857143, 0.8571428571428573, 0.4285714285714288},
         {1.285714285714286, 0.8571428571428568, 0.4285714285714289}, {1.142857142857143, 1.0, 0.4285714285714288}}},
       {{{1.2857142857142858, 0.7142857142857142, 0.5714285714285714}, {1.2857142857142858, 0.7142857142857144, 0.4285714285714288},
         {1.1428571428571428, 0.857142857142857, 0.4285714285714289}, {1.2857142857142858, 0.8571428571428573, 0.4285714285714288}}},
       9.62964972193621561e-35},
      {{{{0.2857142857142855, 0.4285714285714284, 0.2857142857142861}, {0.2857142857142857, 0.2857142857142858, 0.428571428571429},
         {0.4285714285714284, 0.2857142857142855, 0.2857142857142861}, {0.4285714285714285, 0.2857142857142855, 0.4285714285714288}}},
       {{{0.42857142857142855, 0.2857142857142858, 0.428571428571429}, {0.28571428571428564, 0.2857142857142858, 0.4285714285714288},
         {0.42857142857142844, 0.1428571428571428, 0.5714285714285714}, {0.28571428571428564, 0.2857142857142856, 0.5714285714285714}}},
       4.33334237487130889e-34},
  };
  return cases;
}

BOOST_AUTO_TEST_CASE(minimisers_where_pieces_meet_by_rounding) {
  for (const RoundingCase& c : pieces_meet_cases()) {
    fast::SolveOptions o;
    o.with_global = true;
    const PairResult<double> r = fast::solve_pair(TetPair{"", {}, c.A, c.B}, o);
    BOOST_REQUIRE(!r.error);
    BOOST_TEST(!r.pdd2_global_error);
    BOOST_TEST(r.pdd2_global_normal.has_value());
    BOOST_TEST(std::fabs(r.pdd2_global - c.exact) <= 1e-9 * c.exact, r.pdd2_global << " vs exact " << c.exact);
  }
}

// The exact pieces skip the pieces with a vertex away from the contact (global_depth.cpp's
// enumerate_exact): along any unit u of relaxed value mu, a vertex at the plane lies within
// sqrt(40 mu) of its tetrahedron's extreme height, and D(u) <= sqrt(32 mu). Checked on the
// recorded contacts made by rounding above, along each one's reported normal v (relaxed value
// mu, exact): with b = mu (1 + 2^-20), every vertex at the plane along v (the exact closed form's
// pattern) is kept by vertices_off_the_contact, which drops some vertex on every pair (the
// test is not empty: the vertices away from the shared face or edge).
BOOST_AUTO_TEST_CASE(vertices_off_the_contact_keep_those_at_the_plane) {
  using fast::detail::Q;
  for (const RoundingCase& c : pieces_meet_cases()) {
    fast::SolveOptions o;
    o.with_global = true;
    const PairResult<double> r = fast::solve_pair(TetPair{"", {}, c.A, c.B}, o);
    BOOST_REQUIRE(r.pdd2_global_normal.has_value());
    const fast::global::V3 v = *r.pdd2_global_normal;
    Q hA[4], hB[4];
    fast::Solution<Q> s;
    const Q mu = fast::global::relaxed_exact(c.A, c.B, v, hA, hB, s);
    const double b = std::nextafter(mu.get_d(), INFINITY) * (1 + 0x1p-20);
    fast::global::FacetBounds bounds(c.A, c.B);
    const unsigned off = fast::global::vertices_off_the_contact(bounds, c.A, c.B, std::sqrt(32 * b) * (1 + 0x1p-50),
                                                                std::sqrt(40 * b) * (1 + 0x1p-50));
    BOOST_TEST(off != 0u);
    for (int i = 0; i < 4; ++i) {
      const bool atA = s.c - hA[i] < -s.sumA, atB = s.c - hB[i] > -s.sumB;  // (direction_qp.h)
      if (atA) BOOST_TEST(!(off >> i & 1u), "A's vertex " << i << " at the plane, shown off the contact");
      if (atB) BOOST_TEST(!(off >> (4 + i) & 1u), "B's vertex " << i << " at the plane, shown off the contact");
    }
  }
}

// vertices_off_the_contact against sampled normals: on random pairs, d0 chosen so that the region
// D(u) <= d0 is a cap about a direction u0 of least overlap among samples (d0 = 1.1 D(u0)).
// For each vertex x, the least gap g_x from its tetrahedron's extreme height over the sampled
// unit u in that region (by a margin: doubles, 1e-9 of the pair's size): with gamma just above
// g_x (1.01 g_x + the margin) some such u has a gap below gamma, so x must be kept; with gamma a
// tenth of the pair's size, some vertex is dropped on some pairs (the test is not empty).
BOOST_AUTO_TEST_CASE(vertices_off_the_contact_against_sampled_normals) {
  namespace g = fast::global;
  RandomPairs random(20261207);
  auto unit = [&] { return random.unit(); };
  int dropped = 0, kept = 0;
  for (int pair = 0; pair < 200; ++pair) {
    TetVertices A, B;
    random.pair(A, B);
    // gap[c]: vertex c's height below A's top (c < 4) or above B's bottom (c >= 4) along u
    auto along = [&](const g::V3& u, double (&gap)[8]) {
      double topA = -INFINITY, botB = INFINITY;
      for (int i = 0; i < 4; ++i) topA = std::max(topA, g::dot(u, A[i])), botB = std::min(botB, g::dot(u, B[i]));
      for (int i = 0; i < 4; ++i) gap[i] = topA - g::dot(u, A[i]), gap[4 + i] = g::dot(u, B[i]) - botB;
      return topA - botB;  // D(u)
    };
    double gap[8];
    g::V3 u0 = unit();
    for (int s = 0; s < 2000; ++s) {  // (about the least overlap: a cap, not the whole sphere)
      const g::V3 u = unit();
      if (along(u, gap) < along(u0, gap)) u0 = u;
    }
    const double D0 = along(u0, gap);
    if (!(D0 > 0.01)) continue;
    const double d0 = 1.1 * D0, margin = 4e-9;
    g::FacetBounds bounds(A, B);
    if (!bounds.get()) continue;  // (not intersecting)
    double least[8];
    std::fill(std::begin(least), std::end(least), INFINITY);
    for (int s = 0; s < 4000; ++s) {
      g::V3 u = g::add(u0, g::mul(unit(), std::ldexp(1.0, -(s % 8))));
      u = g::mul(u, 1 / g::norm(u));
      if (!(along(u, gap) <= d0 - margin)) continue;
      for (int c = 0; c < 8; ++c) least[c] = std::min(least[c], gap[c]);
    }
    for (int c = 0; c < 8; ++c) {
      if (!std::isfinite(least[c]) || !(least[c] > 0)) continue;
      const unsigned off = g::vertices_off_the_contact(bounds, A, B, d0, 1.01 * least[c] + margin);
      BOOST_TEST(!(off >> c & 1u), "pair " << pair << ": vertex " << c << " dropped at a sampled gap " << least[c]);
      ++kept;
    }
    dropped += g::vertices_off_the_contact(bounds, A, B, d0, 0.1) != 0;
  }
  BOOST_TEST(dropped > 0);
  BOOST_TEST(kept > 100);
}

// polytope_inside_ball with several planes against sampled normals: on random pairs, the
// region D(u) <= d0 about a direction u0 of least overlap among samples (d0 = 1.3 D(u0)) cut by
// two to four planes u.w <= c, each w a unit vector near u0 and c = cos of an angle (a cap about
// w removed). Where some sampled unit u satisfies every plane and has D(u) <= d0 by a margin
// (doubles: 1e-9 of the pair's size), the polytope is not inside the ball and the test must say
// false; it says true on some cases (caps wide enough to hold the whole region), so the check is
// not empty. The clips here keep tens to hundreds of crossings, which the thinning
// (drop_inner_cuts, facet_bounds.cpp) reduces: a wrong widening shows as a true where a sampled
// normal lies in the polytope.
BOOST_AUTO_TEST_CASE(polytope_inside_ball_against_sampled_normals) {
  namespace g = fast::global;
  RandomPairs random(20261208);
  auto unit = [&] { return random.unit(); };
  int shown = 0, refused = 0;
  for (int pair = 0; pair < 300; ++pair) {
    TetVertices A, B;
    random.pair(A, B);
    auto overlap = [&](const g::V3& u) {
      double topA = -INFINITY, botB = INFINITY;
      for (int i = 0; i < 4; ++i) topA = std::max(topA, g::dot(u, A[i])), botB = std::min(botB, g::dot(u, B[i]));
      return topA - botB;
    };
    g::V3 u0 = unit();
    for (int s = 0; s < 2000; ++s) {
      const g::V3 u = unit();
      if (overlap(u) < overlap(u0)) u0 = u;
    }
    const double D0 = overlap(u0);
    if (!(D0 > 0.01)) continue;
    const double d0 = 1.3 * D0, margin = 4e-9;
    g::FacetBounds bounds(A, B);
    if (!bounds.get()) continue;  // (not intersecting)
    // the sampled region, and its widest angle from u0
    std::vector<g::V3> region;
    double widest = 0;
    for (int s = 0; s < 20000; ++s) {
      g::V3 u = g::add(u0, g::mul(unit(), std::ldexp(1.0, -(s % 6))));
      u = g::mul(u, 1 / g::norm(u));
      if (overlap(u) <= d0 - margin) region.push_back(u), widest = std::max(widest, std::acos(std::min(1.0, g::dot(u, u0))));
    }
    for (int trial = 0; trial < 4; ++trial) {
      const int k = 2 + trial % 3;
      g::Halfspace planes[4];
      for (int i = 0; i < k; ++i) {
        g::V3 w = g::add(u0, g::mul(unit(), 0.3 * widest));
        w = g::mul(w, 1 / g::norm(w));
        // about half the cases wide enough to hold the sampled region, the others cutting it
        const double angle = widest * (trial < 2 ? 2.0 : 0.4 + 0.5 * i);
        planes[i] = {w, std::cos(angle)};
      }
      const bool inside = g::polytope_inside_ball(bounds, planes, k, d0);
      bool outside_sample = false;
      for (const g::V3& u : region) {
        bool in = true;
        for (int i = 0; i < k; ++i) in = in && g::dot(u, planes[i].d) <= planes[i].c - margin;
        if (in) {
          outside_sample = true;
          break;
        }
      }
      if (outside_sample) BOOST_TEST(!inside, "pair " << pair << ", " << k << " planes: a sampled normal in the polytope");
      shown += inside, refused += outside_sample;
    }
  }
  BOOST_TEST(shown > 20);
  BOOST_TEST(refused > 20);
}
