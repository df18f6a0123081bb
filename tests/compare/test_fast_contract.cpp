// definitions §8 on inputs that break naive double arithmetic: the fast engine against the exact
// engine (the judge of compare/pdd/compare/engine_comparison.h), pair by pair. The pairs are
// paper-protocol pairs (reproducible family) put through one transformation each — power-of-two
// scales across the double range, far translations, 1-ulp slivers and needles, a vertex a tiny
// step inside a face, a vertex 1e15 away — plus literal hard pairs (below). Every pair
// must be within the contract, or rejected by the fast engine as not representable where the
// exact values confirm it.
#include <boost/test/unit_test.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "pdd/compare/engine_comparison.h"
#include "pdd/compare/generate.h"
#include "pdd/pdd.h"
#include "pdd/reference/solve_exact.h"
#include "shallow_contact.h"
#include "structured_cells.h"

using namespace pdd;

namespace {

Vec3d lerp(const Vec3d& a, const Vec3d& b, double t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

TetPair transformed(TetPair p, int kind) {
  auto scale = [&](int e) {
    for (auto* t : {&p.A, &p.B})
      for (auto& v : *t)
        for (double& x : v) x = std::ldexp(x, e);
  };
  auto translate = [&](double d) {
    for (auto* t : {&p.A, &p.B})
      for (auto& v : *t) v = {v[0] + d, v[1] - d, v[2] + 0.5 * d};
  };
  switch (kind) {
    case 0: scale(-500); break;
    case 1: scale(400); break;
    case 2: scale(-137); break;
    case 3: translate(1e6); break;
    case 4: translate(1e12); break;
    case 5:  // 1-ulp sliver: s3 one ulp from s2 in x
      p.A[3] = p.A[2];
      p.A[3][0] = std::nextafter(p.A[2][0], 1e300);
      break;
    case 6:  // needle: s1 a 2^-40 step from s0
      p.A[1] = lerp(p.A[0], p.A[1], 0x1p-40);
      break;
    case 7: {  // r0 a 2^-60 step from the centroid of A's face opposite s0 towards s0
      const Vec3d c = {(p.A[1][0] + p.A[2][0] + p.A[3][0]) / 3, (p.A[1][1] + p.A[2][1] + p.A[3][1]) / 3,
                       (p.A[1][2] + p.A[2][2] + p.A[3][2]) / 3};
      p.B[0] = lerp(c, p.A[0], 0x1p-60);
      break;
    }
    case 8: p.B[3][0] += 1e15; break;  // one vertex 1e15 away
    case 9: scale(-1010); break;       // values below the normal range: rejected, exactly
  }
  p.name += "/t" + std::to_string(kind);
  return p;
}

TetPair literal(const std::string& name, TetVertices A, TetVertices B) {
  TetPair p;
  p.name = name;
  p.A = A;
  p.B = B;
  return p;
}

}  // namespace

BOOST_AUTO_TEST_CASE(fast_engine_within_contract_on_adversarial_pairs) {
  std::vector<TetPair> pairs;
  const auto base = compare::generate_family("paper", 2026, 50);
  for (std::size_t k = 0; k < base.size(); ++k) pairs.push_back(transformed(base[k], int(k % 10)));
  // a needle and a sliver 1 ulp from flat, and a tetrahedron 1e18 wide
  pairs.push_back(literal("needle", {{{0, 0, 0}, {9, 0, 9}, {1.0000000000000002, 1, 1}, {1, 1, 1}}},
                          {{{0, -10, 0}, {0, 0, 0}, {0, 0, 0.3}, {0.01, 1, 0}}}));
  pairs.push_back(literal("sliver", {{{9, 5, 9}, {0, 9, 0}, {1, 1, 1}, {1.0000000000000002, 1, 1}}},
                          {{{2.333, 4, 2.333}, {5.333, 4, 2.333}, {2.333, 7, 2.333}, {2.333, 4, 5.333}}}));
  pairs.push_back(literal("wide", {{{1, 0, 0}, {1e18, 0, 0}, {0, 1e18, 0}, {0, 0, 1e18}}},
                          {{{2, 2, 2}, {7, 2, 2}, {2, 7, 2}, {2, 2, 7}}}));
  // the fuzzer's finds (fuzz/corpus/fast_engine/regress-subnormal-*): a subnormal coordinate
  // beside ordinary ones; every value is normal, q1 has subnormal coordinates — computed, not
  // "not representable"
  pairs.push_back(literal("subnormal-vertex",
                          {{{1.2648080533535912e-319, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}}},
                          {{{3, 1, -1}, {1, 1, 0}, {1, 3, -1}, {1.5, 1.5, 0.5}}}));
  pairs.push_back(literal("needle-subnormal",
                          {{{1.9663812704481612e-321, -10, 0}, {0, 0, 0}, {0, 0, 0.30000000000000498}, {0.01, 1, 0}}},
                          {{{1.1798287622688967e-320, 0, 0}, {9, 6.6698862188568283e-322, 9},
                            {1.0000000000000002, 1, 1}, {1, 1, 1}}}));
  // definitions §9 where the depth is ~1e-36 of the size squared (a vertex ~1e18 away): the double
  // normal of pdd2_relaxed has no accurate digit where it matters, and pdd2_global started from
  // it lands above the exact witness on these two (global_depth.h: the exact start, rounded
  // componentwise).
  const auto far = compare::generate_family("adversarial", 78, 40);
  pairs.push_back(far[29]);
  pairs.push_back(far[39]);
  // a vertex of A 1e18 away: on the rescaled pair the faces of A through it have a normal of 0
  // (their differences absorb the near vertices' coordinates), so their double values are not
  // finite; the exact minimum of case 1 is one of them (FV:2, 0.158), and the sweep, hinted
  // at it by rigid_pd2's choice, once certified EE:4:3 (1.12) without it
  const auto far4 = compare::generate_family("adversarial", 4, 120);
  BOOST_TEST(far4[119].name == "adversarial-4-119");
  pairs.push_back(far4[119]);
  // the fuzzer's pair spanning 1e-302..1e308 (fuzz/corpus/fast_engine/regress-global-span-1e308):
  // the seven values are normal doubles; pdd2_global is rejected as not representable (below)
  pairs.push_back(literal("span-1e308",
                          {{{-1.0439190266794049e+308, -1.6699141076786345e+71, -8.2689907683260735e-273},
                            {-9.0229300059495633e+281, -5.6416252970077373e+182, -2.9723526587278523e+67},
                            {3.1097388496567073e+231, -4.3453923822790139e-72, 6.1863313510113515e-53},
                            {1.4410116083510851e+48, 1.0859609912968175e-182, -2.5955854277891067e+266}}},
                          {{{6.051450253959454e+256, -1.1663002744834767e+223, -6.3117898324690887e+203},
                            {-2.0676582014446153e-230, -1.6314770617200834e+206, -9.9784784730759232e+145},
                            {-4.5011173095793752e+102, 1.9378519314214893e+112, 5.6970126625825217e+73},
                            {1.1681938447588521e-302, 3.0614408184858201e+54, 1.7935001692194402e-307}}}));
  // the fuzzer's (fuzz/corpus/fast_engine/regress-global-far-vertex-1e192-a): a vertex 1e192
  // away, a depth of 1e-37; pdd2_global computed in rationals on the rescaled pair is 1e-422
  // there and was reported 0 (then rejected as not representable before that)
  pairs.push_back(literal("far-vertex-1e192",
                          {{{6.1869652345266624e-64, 3.4721511805082962e-15, 1.256142812420757e-19},
                            {2.9024137781856264e-18, -1.7829949767912386e+179, -9.8540028720327217e+192},
                            {1.4979184045187882e-18, 2.0013308293968663e-19, 8.4313681814522292e-18},
                            {2.4769325036142077e-18, 3.8394191780818924e-18, 3.3042097304216101e-18}}},
                          {{{5.1471184288869538e-18, 1.7968774262075965e-19, 2.9010090630874396e-18},
                            {1.5495325739710195e-18, 6.9469722445301342e-18, 7.0795386101003494e-18},
                            {3.2834170918216976e-18, 3.7745084273024319e-19, 2.0425652625649374e-18},
                            {0, 0, 0}}}));
  // one vertex 1e100 to 1e300 away: a naive fast pdd2_global comes out 5%, 3.8%, 61% and 24%
  // above exact witnesses (wall offers lost to underflow, H of the near pieces rounded to 0,
  // the start's normal unevaluable in doubles)
  pairs.push_back(literal("review-F1", {{{7.337351763128489, 5.638439545927295, 1.0313324489907016}, {5.877587699635476, 0.049012785669239056, 1.4351836022712494}, {7.743040203204269, 0.4431286101942056, 0.9179887596012393}, {-5.992997299781062e+160, 6.761152187848012e+160, 6.63367779215839e+159}}},
                          {{{0.23487369280188686, 8.41535574587439, 1.2128347177406729}, {8.4394325401706, 6.735347694301687, 8.361819512870102}, {9.52411318454853, 5.790764190210559, 7.987472496091215}, {0.3626926985565859, 7.674185377630392, 5.11325743265501}}}));
  pairs.push_back(literal("review-F2", {{{5.585272464959346, 6.277671085211685, 6.2622645893278595}, {6.806641760808205, 4.892943148597545, 0.0331432712784796}, {7.976975520708526, 7.482653702237058, 5.029710523624537}, {-1.4376317731943154e+100, 3.75238914361403e+99, -3.114535899188773e+100}}},
                          {{{7.367883285422505, 2.5219353146269006, 0.7444999997417345}, {2.6555822219539893, 7.293350380393967, 2.0521752708208654}, {7.398285914207419, 9.757350941027704, 4.939487788493278}, {3.8256047723248496, 4.79010164070626, 6.836965627023515}}}));
  pairs.push_back(literal("review-F3", {{{8.437926222446576, 0.30534474937409795, 8.993933116527742}, {6.224520608976366, 3.1652915424106745, 4.317656228924082}, {7.615929935010261, 7.854119559309741, 1.8990086818143226}, {-1.167260535431268e+300, -2.1186233420099274e+300, 4.660298969928058e+300}}},
                          {{{4.435765563058341, 9.13145005203284, 7.282478447867935}, {6.062599043956083, 2.6198403134488704, 5.265923229048832}, {1.3861974163698576, 1.3809799323879335, 7.157497662356597}, {3.6108976833344886, 7.513763114866316, 2.404936039137613}}}));
  pairs.push_back(literal("review-F4", {{{1.8527280720823103e-21, 2.4538570014774315e-20, 7.513081811127259e-20}, {2.0548842125944053e-20, 9.492424899080275e-20, 8.194391520150944e-21}, {2.706284155045202e-20, 8.787173255722638e-20, 6.433379820663967e-20}, {1e+300, -1.3400951527526401e+299, -7.190496849657287e+299}}},
                          {{{1.4919707667216176e-20, 4.149598103211293e-20, 1.2999399660886023e-20}, {7.091693335729348e-20, 8.130771338908327e-21, 3.6430839221002095e-20}, {2.59813460488989e-22, 8.805419173267027e-20, 1.5578144418112328e-20}, {4.119209733173353e-20, 2.1505588177096534e-20, 2.981184682562333e-20}}}));
  // nearly collinear edges in shallow contact, the optimal piece's two smallest eigenvalues
  // 1.5e-9 (first), ~1e-15 (second) or untuned apart: Eigen's closed-form solver merges them
  // and gives vectors anywhere in their plane, so a fast pdd2_global from it comes out 4.1e-2,
  // 2.5e-9, 1.3e-3 and 8e-4 above the exact interval (what handles them, piece_visit.h:
  // the iterative solver near a double eigenvalue, the exact pieces where its estimate is
  // too wide, and there the Ritz vectors of the plane)
  const TetVertices collinear_A = {{{-1.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.1, 0.6882917236212551, -0.9829824531467902},
                                    {-0.05, -0.6882917236212551, -0.9829824531467902}}};
  auto collinear_B = [](std::array<double, 3> b0, std::array<double, 3> b1) {
    return TetVertices{{b0, b1, {0.2, 0.6882917236212552, 0.9829824531467901}, {-0.1, 1.159110991546882, -0.310582854123025}}};
  };
  pairs.push_back(literal("review-ee-gap-1.5e-9", collinear_A,
                          collinear_B({-0.87, 3.472963553338607e-05, -0.0001969615506024416},
                                      {0.93, -0.000266424173400347, 7.948194462963113e-05})));
  pairs.push_back(literal("review-ee-gap-1e-15", collinear_A,
                          collinear_B({-0.87, 5.20944533000791e-05, -0.0002954423259036624},
                                      {0.93, -0.000305299367005842, 8.918689588804436e-06})));
  pairs.push_back(literal("review-ee-untuned-1", collinear_A,
                          collinear_B({-1.0202035740845048, -4.3759670805620414e-05, -0.00022839930758007185},
                                      {1.060637189089105, -0.00025750459658994734, 0.0001293565076350626})));
  pairs.push_back(literal("review-ee-untuned-2", collinear_A,
                          collinear_B({-1.0927037033402687, -0.00012862182936045253, -0.0015175529619056876},
                                      {0.814369731757143, -0.001334792991424085, 0.0004421242974513408})));
  int computed = 0, rejected = 0;
  std::vector<std::string> declined;  // pdd2_global alone
  for (const auto& p : pairs) {
    const auto exact = reference::solve_exact(p, {QpFormulation::Reduced});
    const auto fast = fast::solve_pair(p);
    const auto c = compare::compare_pair(p, exact, fast);
    BOOST_TEST(!c.over_tolerance(), p.name << (fast.error ? " fast: " + *fast.error : std::string())
                                           << (exact.error ? " exact: " + *exact.error : std::string()));
    for (int v = 0; v < 7; ++v)
      BOOST_TEST(c.rel_error[v] <= c.tolerance[v], p.name << " " << pdd::kValueKeys[v] << " "
                                                          << c.fast_value[v] << " vs " << c.exact_value[v]);
    (fast.error ? rejected : computed) += 1;
    if (fast.error) BOOST_TEST_MESSAGE("rejected " << p.name << ": " << *fast.error);
    if (!fast.error && fast.pdd2_global_error) declined.push_back(p.name);
  }
  // every kind is computed except the scale 2^-1010 (values ~2^-2000: not representable) and
  // span-1e308, whose pdd2_global (5.03e224 in doubles, inside the exact engine's interval
  // [3.46e224, 9.23e224], which is not closed there) has an eigenvalue of a piece in the window
  // no double normal reaches (suspect_proof.h's unrepresented()): that value alone declined,
  // in the class pdd compare allows, every other value computed
  BOOST_TEST(rejected == 5);
  BOOST_TEST(computed == int(pairs.size()) - 5);
  BOOST_TEST((declined == std::vector<std::string>{"span-1e308"}));
}

// Aligned pairs (elements of structured meshes against shifted copies, `pdd generate --family
// aligned`): every value within definitions §8 of the exact engine, and decided and certified
// almost always without rationals. Record statistics (pdd.h): slow_path = the exact path, or
// pdd2_global's value computed in rationals (at most 2% here: one pair of the 150 has the
// latter; exact parallelism and coplanarity are decided by expansions, nearly parallel edge
// pairs certified with their own bounds); refined = a few candidates evaluated in rationals
// (at most 4% here: 5 of 150; pdd2_accel's contenders are ordered exactly by expansions and its
// value certified in doubles, so rationals remain where those cannot decide).
// The pair through both engines, judged by definitions §8 (compare_pair: every value, label and
// the positions); the comparison, and the fast record in *fast.
static compare::PairComparison judged(const TetPair& p, PairResult<double>* fast_out = nullptr) {
  const auto exact = reference::solve_exact(p, {QpFormulation::Reduced});
  const auto fast = fast::solve_pair(p);
  const auto c = compare::compare_pair(p, exact, fast);
  BOOST_TEST(!c.over_tolerance(), p.name);
  for (int v = 0; v < 7; ++v)
    BOOST_TEST(c.rel_error[v] <= c.tolerance[v], p.name << " " << pdd::kValueKeys[v] << " "
                                                        << c.fast_value[v] << " vs " << c.exact_value[v]);
  if (fast_out) *fast_out = fast;
  return c;
}

// A pdd2_global the fast engine declines is reported as declined, beside the exact values it is
// judged against (not as 0 = 0): two blocks overlapping by 1e-12 in x whose faces y = 0.3 meet
// only by the rounding of 0.1 + 0.2 (pdd2 ~1e-34, pdd2_relaxed below 1e-14 of the extent
// squared: the class definitions §8 allows to decline).
BOOST_AUTO_TEST_CASE(declined_pdd2_global_reported_with_the_exact_values) {
  const TetPair p = literal("blocks-1e-12-by-rounding", {{{1.0, 0.25, 0.0}, {1.0, 0.5, 0.0}, {1.0, 0.5, 0.25}, {0.75, 0.5, 0.25}}},
                            {{{1.199999999999, 0.1 + 0.2, 0.05}, {0.999999999999, 0.1 + 0.2, 0.05},
                              {0.999999999999, 0.1, 0.25}, {1.199999999999, 0.1 + 0.2, 0.25}}});
  PairResult<double> fast;
  const compare::PairComparison c = judged(p, &fast);
  BOOST_REQUIRE(fast.pdd2_global_error);  // (the engine declines this pair; the harness is tested)
  BOOST_TEST(c.global_declined);
  BOOST_TEST(c.global_decline == *fast.pdd2_global_error);
  BOOST_TEST(!c.allowed_because.empty());
  BOOST_TEST(std::isnan(c.global_fast));
  const auto exact = reference::solve_exact(p, {QpFormulation::Reduced});
  BOOST_TEST(c.global_exact == CGAL::to_double(exact.pdd2_global));
  BOOST_TEST(c.global_exact > 0);
  BOOST_TEST(c.global_lower <= c.global_exact);
}

BOOST_AUTO_TEST_CASE(aligned_pairs_within_contract_without_the_exact_path) {
  const auto pairs = compare::generate_family("aligned", 2, 150);
  int slow = 0, refined = 0;
  for (const auto& p : pairs) {
    PairResult<double> fast;
    judged(p, &fast);
    slow += fast.stats.slow_path;
    refined += fast.stats.refined;
  }
  BOOST_TEST_MESSAGE(slow << " of " << pairs.size() << " on the slow path, " << refined << " refined");
  BOOST_TEST(slow <= int(pairs.size()) / 50, slow << " of " << pairs.size() << " on the slow path");
  BOOST_TEST(refined <= int(pairs.size()) / 25, refined << " of " << pairs.size() << " refined");
}

// The values a mesh's contacts can ask for (`pdd mesh`, mesh_contacts' variants) without
// pdd2_global: every one but eq11_pd2, the paper's value, which takes the exact path where
// several of a pair's overlaps are exactly 0 (a contact made by rounding, a resting contact of
// aligned blocks: rigid_depth.cpp's eq11_pd2).
static fast::SolveOptions mesh_variants_only() {
  fast::SolveOptions o;
  o.with_global = false;
  for (std::size_t k = 0; k < kValueCount; ++k)
    if (std::string(kValueKeys[k]) == "eq11_pd2") o.values &= ~(1u << k);
  return o;
}

// Contacts made by rounding (structured_cells.h: a Kuhn grid against its copy shifted a tenth of
// a cell along (1, 1, 1); faces that coincide in exact arithmetic overlap by ~1e-17 once the
// shifted coordinates are rounded): no double value has a correct digit. Every value, label and
// the deformed positions within definitions §8 of the exact engine, and none of these pairs on
// the exact path for the mesh variants (mesh_variants_only): the rigid contenders certify on
// compensated heights or expansions, the case-1 and case-2 values on compensated heights (with
// the rationals only for contenders neither certifies), the positions on compensated heights
// (compensated_positions). (pdd2_global of such a pair, ~1e-33 of the size squared, is searched
// on exact pieces: the slow path with the default options.)
BOOST_AUTO_TEST_CASE(contacts_made_by_rounding_within_contract_without_the_exact_path) {
  const std::vector<TetPair> pairs = pdd::test::rounding_contact_pairs(2, 24);
  BOOST_REQUIRE(pairs.size() == 24u);
  int slow = 0;
  for (const auto& p : pairs) {
    const auto c = judged(p);
    BOOST_TEST(c.position_error <= c.position_tolerance, p.name);
    slow += fast::solve_pair(p, mesh_variants_only()).stats.slow_path;
  }
  BOOST_TEST(slow == 0, slow << " of " << pairs.size() << " on the slow path");
}

// Cells that coincide up to rounding (structured_cells.h: a Kuhn grid of decimal cells against
// its copy one cell up): deep overlaps tied along several directions, so that pdd2 is refined
// while its displacements are of the cell's size, far above the rounding of the coordinates.
// solve_pair keeps the double solver's positions for the refined label where their cost is
// the reported value's (positions_attain), and takes compensated or exact ones only where not.
// Every value and the positions (their cost and their separation by the label's exact plane)
// within definitions §8 of the exact engine, none on the exact path.
BOOST_AUTO_TEST_CASE(refined_pairs_positions_within_contract) {
  int refined_deep = 0, pairs = 0, slow = 0;
  for (const TetPair& p : pdd::test::coincident_cell_pairs(2, 36)) {
    PairResult<double> fast;
    const auto c = judged(p, &fast);
    BOOST_TEST(c.position_error <= c.position_tolerance, p.name);
    refined_deep += fast.stats.refined && fast.pdd2 > 1e-4;
    slow += fast::solve_pair(p, mesh_variants_only()).stats.slow_path;
    ++pairs;
  }
  BOOST_TEST_MESSAGE("coincident cells: " << pairs << " pairs, " << refined_deep << " refined and deep");
  BOOST_TEST(pairs == 36);
  BOOST_TEST(refined_deep >= 8);
  BOOST_TEST(slow == 0, slow << " of " << pairs << " on the slow path");
}

// The hot functions as a mesh's contacts call them (rigid_pd2, then pdd2_accel(·, 1) on the same
// pair, which takes the rigid choice the first call left: rigid_depth.h's rigid_pd2_reusing)
// on contacts made by rounding and resting contacts, where that choice is the exact tie order:
// pdd2_accel1 the same bits as computed alone (another pair asked in between), and both values
// and the rigid label within definitions §8 of the exact engine (compare_pair on solve_pair's
// record with the hot functions' values put in).
BOOST_AUTO_TEST_CASE(hot_functions_in_a_mesh_order_within_contract) {
  std::vector<TetPair> pairs = pdd::test::rounding_contact_pairs(2, 16);
  for (const TetPair& p : pdd::test::resting_contact_pairs(2, 1e-10 * 0.125, 8)) pairs.push_back(p);
  BOOST_REQUIRE(pairs.size() == 24u);
  const TetPair& other = pairs.back();
  for (const TetPair& p : pairs) {
    (void)fast::rigid_pd2(other.A, other.B);
    const fast::Depth alone = fast::pdd2_accel(p.A, p.B, 1);
    const fast::Depth rigid = fast::rigid_pd2(p.A, p.B);
    const fast::Depth accel = fast::pdd2_accel(p.A, p.B, 1);
    BOOST_REQUIRE(rigid.status == fast::DepthStatus::Ok && accel.status == fast::DepthStatus::Ok);
    BOOST_TEST(std::memcmp(&alone.pd2, &accel.pd2, sizeof(double)) == 0, p.name);
    PairResult<double> fast = fast::solve_pair(p);
    fast.rigid_pd2 = rigid.pd2, fast.rigid_dir = rigid.dir, fast.pdd2_accel1 = accel.pd2;
    const auto c = compare::compare_pair(p, reference::solve_exact(p, {QpFormulation::Reduced}), fast);
    BOOST_TEST(!c.over_tolerance(), p.name);
  }
}

// A resting contact of stacked blocks (structured_cells.h), 1e-7 and 1e-10 of the cell deep:
// every value within definitions §8 of the exact engine and each label the exact engine's
// (the contact's candidates tie exactly: a face and the edge pairs of its plane), none on the
// exact path for the mesh variants (mesh_variants_only). The case-1 and case-2 contenders
// certify on compensated heights, which keep the exact ties together: the first of them in
// canonical order, the exact engine's label, is named without rationals (deformable_depth.cpp's
// sweep).
BOOST_AUTO_TEST_CASE(resting_contacts_within_contract_without_the_exact_path) {
  int slow = 0, pairs = 0;
  for (double depth : {1e-7 * 0.125, 1e-10 * 0.125})
    for (const TetPair& p : pdd::test::resting_contact_pairs(2, depth, 16)) {
      const auto c = judged(p);
      for (std::size_t k = 0; k < c.labels.size(); ++k)
        BOOST_TEST(c.exact_label[k] == c.fast_label[k], p.name << " label " << k);
      slow += fast::solve_pair(p, mesh_variants_only()).stats.slow_path;
      ++pairs;
    }
  BOOST_TEST(pairs == 32);
  BOOST_TEST(slow == 0, slow << " of " << pairs << " on the slow path");
}

// Shallow contacts, as a simulator's resting contacts are: a vertex of B (tip) or a face of B
// (face) 1e-4 to 1e-7 of the pair's size (~2) through a face of A, in general position (random
// tetrahedra, the contact along A's face normal). The double heights and pieces carry errors ~u
// of the size, far above such a value's 1e-9; the rigid contenders are certified on compensated
// heights (refine.h's refine_tight), each piece whose double H is too coarse is built again to
// its own rounding (accurate_piece_matrix.h) and pdd2_global's value is certified on compensated
// heights along its normal (relaxed_compensated), so that no rationals are needed (the slow
// path: exact pieces, ~5-30 ms a pair): at most one pair in 50 on the slow path (a small
// eigenvalue beside a piece's structural zero, piece_visit.h), every value within definitions
// §8 of the exact engine's, pdd2_global inside its exact interval.
BOOST_AUTO_TEST_CASE(shallow_contacts_within_contract_without_the_exact_path) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> U(-1, 1);
  int slow = 0, pairs = 0;
  for (double depth : {1e-4, 1e-5, 1e-6, 1e-7})
    for (int trial = 0; trial < 16; ++trial) {
      const TetPair p = pdd::test::shallow_contact_pair(
          depth, trial % 2, [&] { return U(rng); },
          "shallow " + std::to_string(depth) + (trial % 2 ? " face " : " tip ") + std::to_string(trial));
      const auto exact = reference::solve_exact(p, {QpFormulation::Reduced});
      if (!exact.intersecting) continue;
      const auto fast = fast::solve_pair(p);
      const auto cmp = compare::compare_pair(p, exact, fast);
      BOOST_TEST(!cmp.over_tolerance(), p.name);
      slow += fast.stats.slow_path;
      ++pairs;
    }
  BOOST_TEST_MESSAGE("shallow contacts: " << pairs << " pairs, " << slow << " on the slow path");
  BOOST_TEST(pairs >= 48);
  BOOST_TEST(slow * 50 <= pairs, slow << " of " << pairs << " on the slow path");
}
