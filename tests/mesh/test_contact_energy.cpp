// test_contact_energy.cpp — pdd::mesh::contact_energy (include/pdd/mesh/contact_energy.h;
// definitions §12) on the shipped meshes: the gradient against central differences of E, the
// Hessian symmetric, positive semi-definite and equal to finite differences of the fixed-plane
// gradient, the majorizer property, and the exact engine against the fast one.
#define BOOST_TEST_MODULE contact_energy
#include <boost/test/unit_test.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <gmpxx.h>
#include <tbb/task_arena.h>

#include "pdd/global_minimiser.h"
#include "pdd/mesh.h"
#include "pdd/reference/relaxed_pieces.h"
#include "kuhn_grid_mesh.h"
#include "structured_cells.h"

using namespace pdd;
using namespace pdd::mesh;

namespace {

const std::string kDir = std::string(PDD_FIXTURES_DIR) + "/meshes/";
Mesh load(const std::string& name) { return read_mesh(kDir + name); }

struct Scene {
  Mesh A, B;
};
// tiny-a / tiny-b (24 elements each, unit cubes, B shifted by (0.6, 0.3, 0.2)) with B turned
// by 0.3 about z after 0.2 about x and moved by (0.013, 0.021, 0.007): 73 intersecting pairs
// in general position (the axis-aligned original has coplanar faces, which send most pairs to
// the engine's exact path, tens of milliseconds each).
Scene tiny() {
  Scene s{load("tiny-a.msh"), load("tiny-b.msh")};
  const double cz = std::cos(0.3), sz = std::sin(0.3), cx = std::cos(0.2), sx = std::sin(0.2);
  const double R[3][3] = {{cz, -sz * cx, sz * sx}, {sz, cz * cx, -cz * sx}, {0, sx, cx}};
  const Vec3d t{0.013, 0.021, 0.007};
  for (Vec3d& v : s.B.vertices) {
    Vec3d w{};
    for (int i = 0; i < 3; ++i) w[i] = R[i][0] * v[0] + R[i][1] * v[1] + R[i][2] * v[2] + t[i];
    v = w;
  }
  return s;
}

double energy_at(const Scene& s, const std::vector<Vec3d>& pa, const std::vector<Vec3d>& pb,
                 EnergyEngine engine = EnergyEngine::Fast) {
  ContactEnergyOptions o;
  o.engine = engine;
  return contact_energy(s.A, s.B, pa, pb, o).energy;
}

double max_abs(const std::vector<Vec3d>& g) {
  double m = 0;
  for (const auto& v : g)
    for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// Central differences (step h) of fixed_plane's gradient, with the normal n held, against the
// pair's Hessian Qs (x) u u^T, entry by entry within tol.
void check_hessian_by_differences(const TetVertices& A, const TetVertices& B, const Vec3d& n, const PairTerms& t,
                                  double h, double tol) {
  for (int j = 0; j < 8; ++j)
    for (int b = 0; b < 3; ++b) {
      TetVertices Ap = A, Am = A, Bp = B, Bm = B;
      (j < 4 ? Ap[j] : Bp[j - 4])[b] += h;
      (j < 4 ? Am[j] : Bm[j - 4])[b] -= h;
      const FixedPlane fp = fixed_plane(Ap, Bp, n), fm = fixed_plane(Am, Bm, n);
      for (int i = 0; i < 8; ++i)
        for (int a = 0; a < 3; ++a) {
          const double fd = (fp.gradient[i][a] - fm.gradient[i][a]) / (2 * h);
          const double hess = t.qs[i][j] * t.unit_normal[a] * t.unit_normal[b];
          BOOST_TEST(std::abs(fd - hess) <= tol, "entry " << 3 * i + a << "," << 3 * j + b);
        }
    }
}

}  // namespace

BOOST_AUTO_TEST_CASE(energy_is_the_weighted_sum_of_the_pairs) {
  const Scene s = tiny();
  ContactEnergyOptions o;
  o.per_pair = true;
  const ContactEnergy e = contact_energy(s.A, s.B, s.A.vertices, s.B.vertices, o);
  BOOST_REQUIRE_GT(e.pair_count, 0u);
  BOOST_TEST(e.pairs.size() == e.pair_count);
  ContactOptions co;
  co.variants = kGlobal;
  const auto c = contacts(s.A, s.B, co);
  BOOST_REQUIRE_EQUAL(c.pairs.size(), e.pairs.size());
  double sum = 0;
  for (std::size_t j = 0; j < c.pairs.size(); ++j) {
    const auto& p = e.pairs[j];
    BOOST_TEST(p.a == c.pairs[j].a);
    BOOST_TEST(p.b == c.pairs[j].b);
    BOOST_TEST(p.pdd2_global == c.pairs[j].result.pdd2_global);
    // w = (V_a V_b)^(1/3) from the rest volumes (|det| / 6).
    auto vol = [](const TetVertices& t) {
      Eigen::Matrix3d m;
      for (int k = 0; k < 3; ++k)
        for (int c2 = 0; c2 < 3; ++c2) m(k, c2) = t[k + 1][c2] - t[0][c2];
      return std::abs(m.determinant()) / 6;
    };
    const double w = std::cbrt(vol(element(s.A, p.a)) * vol(element(s.B, p.b)));
    BOOST_TEST(p.weight == w, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(p.energy == p.weight * p.pdd2_global);
    sum += p.energy;
  }
  BOOST_TEST(e.energy == sum, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(e.gradient.size() == s.A.vertices.size() + s.B.vertices.size());
}

// Central differences of E along every coordinate of every vertex in contact. Where the
// one-sided quotients agree (no tie, no pair appearing or vanishing inside [-h, h]) the
// central quotient matches the gradient to O(h^2) plus the engine's error: values within 1e-9
// relative (definitions §8), so the quotient is off by at most 1e-9 E / h; with h = 1e-6 of the
// mesh's extent and E ~ w depth^2 that is far below 1e-5 of the largest gradient entry, the
// tolerance used. Elsewhere, pdd.h's bracket: forward <= g + h C and backward >= g - h C, with C
// = sigma(e_k) summed over the pairs with weights (0.1 per tetrahedron containing the vertex),
// bounded here by 0.2 times the sum of all weights.
BOOST_AUTO_TEST_CASE(gradient_matches_central_differences) {
  const Scene s = tiny();
  ContactEnergyOptions o;
  o.per_pair = true;
  const ContactEnergy e = contact_energy(s.A, s.B, s.A.vertices, s.B.vertices, o);
  const double g_max = max_abs(e.gradient);
  BOOST_REQUIRE_GT(g_max, 0);
  double wsum = 0;
  for (const auto& p : e.pairs) wsum += p.weight;
  const std::size_t nA = s.A.vertices.size();
  const double h = 1e-6;  // the meshes span about 1
  int smooth = 0, kinks = 0;
  for (std::size_t v = 0; v < e.gradient.size(); ++v) {
    if (e.gradient[v] == Vec3d{0, 0, 0}) continue;
    for (int k = 0; k < 3; ++k) {
      auto E = [&](double d) {
        std::vector<Vec3d> pa = s.A.vertices, pb = s.B.vertices;
        (v < nA ? pa[v] : pb[v - nA])[k] += d;
        return energy_at(s, pa, pb);
      };
      const double ep = E(h), em = E(-h), e0 = e.energy;
      const double fwd = (ep - e0) / h, bwd = (e0 - em) / h, g = e.gradient[v][k];
      if (std::abs(fwd - bwd) <= 1e-6 * g_max) {
        ++smooth;
        BOOST_TEST(std::abs((ep - em) / (2 * h) - g) <= 1e-5 * g_max, "vertex " << v << " coord " << k);
      } else {
        ++kinks;
        BOOST_TEST(fwd <= g + 0.2 * h * wsum + 1e-5 * g_max);
        BOOST_TEST(bwd >= g - 0.2 * h * wsum - 1e-5 * g_max);
      }
    }
  }
  BOOST_TEST_MESSAGE("smooth coordinates " << smooth << ", kinks " << kinks);
  BOOST_TEST(smooth > 0);
}

// Symmetric by construction (blocks w Qs_ij u u^T with Qs symmetrised); positive semi-definite:
// each block is w (Qs (x) u u^T), Qs = X^T H X in doubles, so its negative eigenvalues are
// rounding, below 1e-12 of the largest in size.
BOOST_AUTO_TEST_CASE(hessian_symmetric_psd) {
  const Scene s = tiny();
  ContactEnergyOptions o;
  o.hessian = true;
  const ContactEnergy e = contact_energy(s.A, s.B, s.A.vertices, s.B.vertices, o);
  const auto n = static_cast<Eigen::Index>(3 * e.gradient.size());
  BOOST_REQUIRE_EQUAL(e.hessian.rows(), n);
  BOOST_REQUIRE_EQUAL(e.hessian.cols(), n);
  const Eigen::MatrixXd H(e.hessian);
  BOOST_TEST((H - H.transpose()).cwiseAbs().maxCoeff() == 0);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(H);
  const double top = es.eigenvalues().cwiseAbs().maxCoeff();
  BOOST_REQUIRE_GT(top, 0);
  BOOST_TEST(es.eigenvalues().minCoeff() >= -1e-12 * top);
}

// Per pair, with the normal held: the piece's value equals pdd2_global (the engine's positions
// attain it to 2e-9 relative; the tolerance 1e-7 covers the rounding of Qs), the fixed-plane QP
// (solved independently by enumeration) gives the same value, its gradient equals the pair's
// gradient, and its finite differences (h = 1e-7: inside the piece unless a vertex is within h
// of the plane, which the piece test excludes) equal Qs (x) u u^T.
BOOST_AUTO_TEST_CASE(hessian_is_the_fixed_plane_second_derivative) {
  const Scene s = tiny();
  ContactOptions co;
  co.variants = kGlobal;
  const auto c = contacts(s.A, s.B, co);
  BOOST_REQUIRE(!c.pairs.empty());
  int checked = 0;
  for (const auto& k : c.pairs) {
    const auto& r = k.result;
    const TetVertices A = element(s.A, k.a), B = element(s.B, k.b);
    TetVertices qA, qB;
    for (int i = 0; i < 4; ++i) qA[i] = r.q1_A_global[i], qB[i] = r.q1_B_global[i];
    const Vec3d n = *r.pdd2_global_normal;
    const PairTerms t = pair_terms(A, B, qA, qB, n);
    BOOST_TEST(t.piece_value == r.pdd2_global, boost::test_tools::tolerance(1e-7));
    const FixedPlane f = fixed_plane(A, B, n);
    BOOST_TEST(f.value == r.pdd2_global, boost::test_tools::tolerance(1e-7));
    double gscale = 0;
    for (const auto& g : t.gradient)
      for (double x : g) gscale = std::max(gscale, std::abs(x));
    for (int i = 0; i < 8; ++i)
      for (int a = 0; a < 3; ++a)
        BOOST_TEST(std::abs(f.gradient[i][a] - t.gradient[i][a]) <= 1e-6 * gscale);
    BOOST_TEST_CONTEXT("pair " << k.a << "," << k.b) { check_hessian_by_differences(A, B, n, t, 1e-7, 1e-6); }
    ++checked;
  }
  BOOST_TEST(checked > 0);
}

// A shallow pair (a block resting on a slab, 1e-6 of its size deep, Gmsh meshes at h = 0.1;
// pdd2_global 7.1e-14): at its minimiser B's third vertex lies 1.23e-8 off the plane, 5% of the
// depth and 6e-8 of the pair's extent along u. The Hessian is that of the piece at P: finite
// differences of the fixed-plane gradient with h = 1e-10 (each vertex stays on its side of the
// plane) equal Qs (x) u u^T. Tolerance: the gradients (~1e-8) carry rounding below 1e-16 x 0.4
// (heights relative to A's first vertex: the extent, 0.4) times a few terms, so each quotient
// is within ~1e-6 of its value; a neighbouring piece's entries differ by O(0.1).
BOOST_AUTO_TEST_CASE(shallow_pair_hessian_is_the_piece_at_p) {
  const TetVertices A = {{{0.04999999999999738, -0.27942286340599543, 0},
                          {0.099999999999997952, -0.2505533082886211, -0.09999999999999945},
                          {0.099999999999998868, -0.34641016151377613, 0},
                          {0.099999999999999978, -0.39856406460551058, -0.1000000000000001}}};
  const TetVertices B = {{{0.03019569671339031, -0.3044114612382397, -9.9999999999999995e-07},
                          {0.10897367174764531, -0.29059056530802801, -9.9999999999999995e-07},
                          {0.071645231802398998, -0.22338983520924044, -9.9999999999999995e-07},
                          {0.045288219671967098, -0.26101927036160327, 0.099999000000000005}}};
  const auto m = fast::global_minimiser(A, B);
  BOOST_REQUIRE(m.has_value());
  const Vec3d n = m->normal;
  const PairTerms t = pair_terms(A, B, m->q1_A, m->q1_B, n);
  BOOST_TEST(!t.active[6]);  // B's third vertex: off the plane
  check_hessian_by_differences(A, B, n, t, 1e-10, 1e-4);
}

// The Hessian's active set is the fixed-plane QP's optimum: on random pairs and normals, with
// overlaps along u from 1e-1 to 1e-9 of the extent, Qs s (x) u (pair_terms, the sixteen pieces'
// KKT test) equals the gradient of fixed_plane (every one of the 255 active sets solved and the
// feasible one of least value kept). Tolerance: each gradient is a sum of eight products of
// entries of Qs (|Qs_ik| <= 1/5) and heights (|s_k| <= smax) that cancels down to ~ depth / 10,
// rounded in both routes (fixed_plane's through an LU solve of a well-conditioned 9 + |S|
// system): within 1e-13 smax of each other, while a neighbouring piece's differs by ~ depth /
// 10 >= 1e-10 smax here (random heights lie within rounding of a kink only by chance: none
// does in these draws).
BOOST_AUTO_TEST_CASE(active_set_is_the_fixed_plane_optimum) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    TetVertices A, B;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) A[i][k] = U(rng), B[i][k] = U(rng);
    Vec3d u{U(rng), U(rng), U(rng)};
    const double l = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (double& x : u) x /= l;
    // B moved along u so that A's top and B's bottom overlap by `depth` along u
    double topA = -1e300, botB = 1e300;
    for (int i = 0; i < 4; ++i) {
      topA = std::max(topA, u[0] * A[i][0] + u[1] * A[i][1] + u[2] * A[i][2]);
      botB = std::min(botB, u[0] * B[i][0] + u[1] * B[i][1] + u[2] * B[i][2]);
    }
    const double depth = std::pow(10.0, -1 - trial % 9);
    const double shift = topA - depth - botB;
    for (auto& p : B)
      for (int k = 0; k < 3; ++k) p[k] += shift * u[k];
    const PairTerms t = pair_terms(A, B, A, B, u);
    const FixedPlane f = fixed_plane(A, B, u);
    std::array<double, 8> s{};
    for (int i = 0; i < 8; ++i) {
      const Vec3d& p = i < 4 ? A[i] : B[i - 4];
      s[i] = u[0] * (p[0] - A[0][0]) + u[1] * (p[1] - A[0][1]) + u[2] * (p[2] - A[0][2]);
    }
    double smax = 0, scale = 0, diff = 0;
    for (double x : s) smax = std::max(smax, std::abs(x));
    for (int i = 0; i < 8; ++i) {
      double g = 0;
      for (int k = 0; k < 8; ++k) g += t.qs[i][k] * s[k];
      for (int a = 0; a < 3; ++a) {
        scale = std::max(scale, std::abs(f.gradient[i][a]));
        diff = std::max(diff, std::abs(g * u[a] - f.gradient[i][a]));
      }
    }
    BOOST_TEST(diff <= 1e-13 * smax, "trial " << trial << " depth " << depth);
    BOOST_TEST(scale >= 1e-3 * depth);  // (the gradient, ~ depth / 10: far above the tolerance)
    ++checked;
  }
  BOOST_TEST(checked == 400);
}

// The majorizer: with the normal held at P's minimiser, V_u(P + W) >= pdd2_global(P + W) for
// random W (pdd2_global is the minimum over normals; tolerance: both values to 1e-9 relative),
// and equal at P (previous test).
BOOST_AUTO_TEST_CASE(fixed_plane_majorizes) {
  const Scene s = tiny();
  ContactOptions co;
  co.variants = kGlobal;
  const auto c = contacts(s.A, s.B, co);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss(0, 1);
  int checked = 0;
  for (const auto& k : c.pairs) {
    const TetVertices A = element(s.A, k.a), B = element(s.B, k.b);
    const Vec3d n = *k.result.pdd2_global_normal;
    const double scale = std::sqrt(k.result.pdd2_global);
    for (int trial = 0; trial < 20; ++trial) {
      TetVertices Ap = A, Bp = B;
      for (int i = 0; i < 4; ++i)
        for (int a = 0; a < 3; ++a) {
          Ap[i][a] += 0.5 * scale * gauss(rng);
          Bp[i][a] += 0.5 * scale * gauss(rng);
        }
      const auto r = fast::solve_pair(TetPair{"", {}, Ap, Bp});
      if (r.error || r.pdd2_global_error) continue;
      const double V = fixed_plane(Ap, Bp, n).value;
      BOOST_TEST(V >= r.pdd2_global * (1 - 2e-9) - 1e-300);
      ++checked;
    }
  }
  BOOST_TEST(checked > 0);
}

// The exact engine against the fast one: the energies within 1e-8 (values within 1e-9
// relative, definitions §8) and the gradients within 1e-4 of the largest entry (the fast
// gradient's bound, pdd/solve_options.h: 4.5e-5 of its size where the separated set is
// locally convex).
BOOST_AUTO_TEST_CASE(exact_engine_agrees) {
  const Scene s = tiny();
  ContactEnergyOptions o;
  o.hessian = true;
  const ContactEnergy f = contact_energy(s.A, s.B, s.A.vertices, s.B.vertices, o);
  o.engine = EnergyEngine::Exact;
  const ContactEnergy x = contact_energy(s.A, s.B, s.A.vertices, s.B.vertices, o);
  BOOST_TEST(f.pair_count == x.pair_count);
  BOOST_TEST(f.energy == x.energy, boost::test_tools::tolerance(1e-8));
  const double g = max_abs(x.gradient);
  for (std::size_t v = 0; v < f.gradient.size(); ++v)
    for (int k = 0; k < 3; ++k) BOOST_TEST(std::abs(f.gradient[v][k] - x.gradient[v][k]) <= 1e-4 * g);
}

BOOST_AUTO_TEST_CASE(self_contact_of_two_bodies_equals_two_meshes) {
  // two-spheres.msh: two bodies in one file; its self-contact energy counts the pairs between
  // the bodies (and a body's own non-adjacent pairs, none here when it does not fold).
  const Mesh m = load("two-spheres.msh");
  const ContactEnergy e = contact_energy_self(m, m.vertices);
  BOOST_TEST(e.gradient.size() == m.vertices.size());
  ContactOptions co;
  co.variants = kGlobal;
  BOOST_TEST(e.pair_count == contacts_self(m, co).pairs.size());
}

// Scale: E ~ L^4 (pdd2_global ~ L^2, the weight ~ L^2), so scaling every coordinate by a power
// of two 2^k multiplies E by exactly 2^4k up to the engine's own accuracy (definitions §8: 1e-9
// per value). At 2^180 (~1.5e54) and 2^-180 the rest volumes themselves (~L^3: 1e163 x 1e163 as
// a product, 1e-163 x 1e-163) leave the double range, the weights and E do not; at 2^260
// (~1.9e78) E ~ 1e313 does not either: std::overflow_error, no inf; at 2^-260 E ~ 1e-313 (a
// subnormal, or 0 for a smaller scene): std::underflow_error, never an energy that reads 0.
BOOST_AUTO_TEST_CASE(energy_at_extreme_scales) {
  const Scene s = tiny();
  const double E0 = contact_energy(s.A, s.B, s.A.vertices, s.B.vertices).energy;
  BOOST_REQUIRE(E0 > 0);
  auto scaled = [&](int k) {
    Scene t = s;
    for (Mesh* m : {&t.A, &t.B})
      for (Vec3d& v : m->vertices)
        for (double& x : v) x = std::ldexp(x, k);
    return t;
  };
  for (int k : {180, -180}) {
    const Scene t = scaled(k);
    const ContactEnergy e = contact_energy(t.A, t.B, t.A.vertices, t.B.vertices);
    BOOST_TEST(e.skipped.empty());
    BOOST_TEST(std::ldexp(e.energy, -4 * k) == E0, boost::test_tools::tolerance(1e-9));
    for (const Vec3d& g : e.gradient)
      for (double x : g) BOOST_TEST(std::isfinite(x));
  }
  const Scene t = scaled(260);
  BOOST_CHECK_THROW(contact_energy(t.A, t.B, t.A.vertices, t.B.vertices), std::overflow_error);
  const Scene u = scaled(-260);
  BOOST_CHECK_THROW(contact_energy(u.A, u.B, u.A.vertices, u.B.vertices), std::underflow_error);
}

BOOST_AUTO_TEST_CASE(positions_must_match_the_mesh) {
  const Scene s = tiny();
  std::vector<Vec3d> pa = s.A.vertices;
  pa.pop_back();
  BOOST_CHECK_THROW(contact_energy(s.A, s.B, pa, s.B.vertices), std::invalid_argument);
}

// The closed form of Qs (piece_matrix, the energy's) against the KKT solve (piece_matrix_kkt)
// on every active set with both sides touching (15 x 15): equal to the KKT solve's rounding
// (entries are O(1/10), the 9 + |S| system is well conditioned: 1e-14 absolute), symmetric
// bit for bit, and Qs 1 = 0 (shifting all eight heights moves the plane along).
BOOST_AUTO_TEST_CASE(piece_matrix_closed_form_equals_the_kkt_solve) {
  int sets = 0;
  for (unsigned ma = 1; ma < 16; ++ma)
    for (unsigned mb = 1; mb < 16; ++mb) {
      std::array<bool, 8> active{};
      for (int k = 0; k < 4; ++k) active[k] = (ma >> k) & 1u, active[4 + k] = (mb >> k) & 1u;
      const auto Q = piece_matrix(active), K = piece_matrix_kkt(active);
      for (int i = 0; i < 8; ++i) {
        double row = 0;
        for (int k = 0; k < 8; ++k) {
          BOOST_TEST(std::abs(Q[i][k] - K[i][k]) <= 1e-14, "set " << ma << "," << mb << " (" << i << "," << k << ")");
          BOOST_TEST(Q[i][k] == Q[k][i]);
          if (!active[i] || !active[k]) BOOST_TEST(Q[i][k] == 0);
          row += Q[i][k];
        }
        BOOST_TEST(std::abs(row) <= 1e-15);
      }
      ++sets;
    }
  BOOST_TEST(sets == 225);
}

// A piece's value grows with its active set: with S within S' (S' = S and one more vertex, so
// every S within S' by steps), Qs(S') - Qs(S) is positive semi-definite, exactly. V_S(s) =
// s^T Qs s / 2 is the least object norm putting S's heights on one plane (the equality QP of the
// set, the other constraints dropped), so a further vertex adds a constraint and V cannot drop.
// The double enumeration of pdd2_global relies on it (piece_enumeration.cpp, pieces above the
// window): H_S = X^T Qs X / 2 for the pair's positions X, so H_S' - H_S is semi-definite too.
// Qs in rationals from the header's closed form (above: equal to the KKT solve); semi-definite
// by exact symmetric elimination (a zero pivot must have a zero row).
BOOST_AUTO_TEST_CASE(piece_matrix_grows_with_the_active_set) {
  auto exact_qs = [](unsigned set) {  // bits 0..3: A's vertices, 4..7: B's
    int n[2] = {0, 0};
    for (int k = 0; k < 8; ++k) n[k / 4] += (set >> k) & 1u;
    const mpq_class alpha[2] = {mpq_class(1, 5 - n[0]), mpq_class(1, 5 - n[1])};
    const mpq_class W = alpha[0] * n[0] + alpha[1] * n[1];
    std::array<std::array<mpq_class, 8>, 8> Q;
    for (int k = 0; k < 8; ++k)
      for (int m = 0; m < 8; ++m) {
        Q[k][m] = 0;
        if (!((set >> k) & 1u) || !((set >> m) & 1u)) continue;
        Q[k][m] = (mpq_class(k == m ? 1 : 0) + (k / 4 == m / 4 ? alpha[k / 4] : 0) -
                   5 * alpha[k / 4] * alpha[m / 4] / W) / 10;
      }
    return Q;
  };
  auto semi_definite = [](std::array<std::array<mpq_class, 8>, 8> D) {
    for (int p = 0; p < 8; ++p) {
      int piv = -1;  // the largest remaining diagonal entry
      for (int i = p; i < 8; ++i)
        if (piv < 0 || D[i][i] > D[piv][piv]) piv = i;
      std::swap(D[p], D[piv]);
      for (auto& row : D) std::swap(row[p], row[piv]);
      if (D[p][p] < 0) return false;
      if (D[p][p] == 0) {
        for (int i = p; i < 8; ++i)
          if (D[p][i] != 0) return false;
        continue;
      }
      for (int i = p + 1; i < 8; ++i) {
        const mpq_class f = D[i][p] / D[p][p];
        for (int j = p; j < 8; ++j) D[i][j] -= f * D[p][j];
      }
    }
    return true;
  };
  auto valid = [](unsigned set) { return (set & 15u) != 0 && (set >> 4) != 0; };
  int steps = 0;
  for (unsigned set = 1; set < 256; ++set) {
    if (!valid(set)) continue;
    const auto Q = exact_qs(set);
    for (int k = 0; k < 8; ++k) {
      if ((set >> k) & 1u) continue;
      auto D = exact_qs(set | (1u << k));
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) D[i][j] -= Q[i][j];
      BOOST_TEST(semi_definite(D), "set " << set << " plus vertex " << k);
      ++steps;
    }
  }
  // 225 sets, each with its 8 - |S| missing vertices: sum over a, b = 1..4 of C(4,a) C(4,b) (8 - a - b)
  BOOST_TEST(steps == 840);
  // and the check can fail: the smaller set minus the larger is not semi-definite
  auto D = exact_qs(0x11u);
  const auto Q = exact_qs(0x33u);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) D[i][j] -= Q[i][j];
  BOOST_TEST(!semi_definite(D));
}

// pdd::fast::global_minimiser, the energy's per-pair call, gives solve_pair's definitions §9
// fields bit for bit where it does not decline (pdd/global_minimiser.h), on the tiny scene's
// pairs and on the same pairs moved by random perturbations.
BOOST_AUTO_TEST_CASE(global_minimiser_equals_solve_pair) {
  const Scene s = tiny();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-0.01, 0.01);
  int compared = 0, declined = 0;
  for (int round = 0; round < 4; ++round) {
    Scene m = s;
    if (round > 0)
      for (auto& v : m.B.vertices)
        for (double& x : v) x += U(rng);
    ContactOptions co;
    co.variants = kGlobal;
    for (const auto& k : contacts(m.A, m.B, co).pairs) {
      const auto g = fast::global_minimiser(element(m.A, k.a), element(m.B, k.b));
      if (!g) {
        ++declined;
        continue;
      }
      const auto& r = k.result;
      BOOST_REQUIRE(!r.pdd2_global_error);
      BOOST_TEST(g->pd2 == r.pdd2_global);
      BOOST_TEST((g->normal == *r.pdd2_global_normal));
      for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) {
          BOOST_TEST(g->q1_A[i][c] == r.q1_A_global[i][c]);
          BOOST_TEST(g->q1_B[i][c] == r.q1_B_global[i][c]);
        }
      ++compared;
    }
  }
  BOOST_TEST_MESSAGE("compared " << compared << ", declined " << declined);
  BOOST_TEST(compared > 100);
}

// Shallow tip contacts (a vertex of B 1e-10 inside a face of A, the pair about 2 across, the tip
// ~1e-7 from an edge of the face): the depth is below the double pieces' floor (global_depth.cpp:
// 1e-18 scale^2 for a compact pair), and the contact so near the face's edge that
// shallow_certificate.h's overlap bound cannot hold off its cap (the disc about the contact
// within the face has a radius ~1e-7), so the enumeration builds its pieces exactly and computes
// the value in rationals; solve_pair then takes the value again on the pair as given along the
// same normal, and global_minimiser does the same: its fields equal solve_pair's bit for bit
// there too.
BOOST_AUTO_TEST_CASE(global_minimiser_equals_solve_pair_on_exact_values) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  auto sub = [](const Vec3d& a, const Vec3d& b) { return Vec3d{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
  auto dot3 = [](const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  int slow = 0, compared = 0;
  for (int trial = 0; trial < 60; ++trial) {
    TetVertices A, B;
    for (auto& v : A)
      for (double& x : v) x = U(rng);
    const Vec3d e = sub(A[2], A[1]), f = sub(A[3], A[1]);
    Vec3d n{e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]};
    const double len = std::sqrt(dot3(n, n));
    if (dot3(n, sub(A[0], A[1])) > 0) n = {-n[0], -n[1], -n[2]};
    for (double& x : n) x /= len;  // unit, outward from face 1 2 3
    Vec3d c{};  // on the face, 2e-7 of the way from the edge 1 2 to vertex 3
    for (int k = 0; k < 3; ++k) c[k] = (0.5 - 1e-7) * (A[1][k] + A[2][k]) + 2e-7 * A[3][k];
    for (int k = 0; k < 3; ++k) B[0][k] = c[k] - 1e-10 * n[k];  // the tip, inside A
    for (int j = 1; j < 4; ++j) {
      Vec3d r{U(rng), U(rng), U(rng)};
      const double h = dot3(r, n), up = 0.2 + std::abs(U(rng));
      for (int k = 0; k < 3; ++k) B[j][k] = c[k] + r[k] - h * n[k] + up * n[k];  // above the face
    }
    const auto g = fast::global_minimiser(A, B);
    fast::SolveOptions so;
    so.with_global = true;
    const PairResult<double> r = fast::solve_pair(TetPair{"", {}, A, B}, so);
    if (!g) continue;
    BOOST_REQUIRE(!r.error);
    BOOST_REQUIRE(!r.pdd2_global_error);
    slow += r.stats.slow_path;
    BOOST_TEST(g->pd2 == r.pdd2_global);
    BOOST_TEST((g->normal == *r.pdd2_global_normal));
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        BOOST_TEST(g->q1_A[i][k] == r.q1_A_global[i][k]);
        BOOST_TEST(g->q1_B[i][k] == r.q1_B_global[i][k]);
      }
    ++compared;
  }
  BOOST_TEST_MESSAGE("compared " << compared << ", in rationals " << slow);
  BOOST_TEST(slow > 20);
}

// The sums over pairs run per vertex in pair order: one thread and all threads give the same
// doubles (energy, gradient, every Hessian entry and its position).
BOOST_AUTO_TEST_CASE(results_do_not_depend_on_the_threads) {
  const Scene s = tiny();
  ContactEnergyOptions o;
  o.hessian = true;
  const ContactEnergy all = contact_energy(s.A, s.B, s.A.vertices, s.B.vertices, o);
  tbb::task_arena one(1);
  ContactEnergy single;
  one.execute([&] { single = contact_energy(s.A, s.B, s.A.vertices, s.B.vertices, o); });
  BOOST_TEST(all.energy == single.energy);
  BOOST_TEST((all.gradient == single.gradient));
  BOOST_REQUIRE_EQUAL(all.hessian.nonZeros(), single.hessian.nonZeros());
  const Eigen::SparseMatrix<double> d = all.hessian - single.hessian;
  BOOST_TEST((d.nonZeros() == 0 || d.coeffs().cwiseAbs().maxCoeff() == 0));
}

// Positions that are the mesh's own vertices bit for bit take the mesh itself (no copy);
// positions equal in value but not in bits (a coordinate +0 written as -0) take a copy of the
// mesh at them. The two routes see the same geometry: E, the gradient, the Hessian and the
// pairs compare equal.
BOOST_AUTO_TEST_CASE(positions_at_rest_equal_a_copy_of_the_mesh) {
  const Scene s = tiny();
  auto signed_zeros = [](std::vector<Vec3d> p, std::size_t& flipped) {
    for (Vec3d& v : p)
      for (double& x : v)
        if (x == 0 && !std::signbit(x)) x = -0.0, ++flipped;
    return p;
  };
  std::size_t flipped = 0;
  const std::vector<Vec3d> pa = signed_zeros(s.A.vertices, flipped);
  BOOST_REQUIRE(flipped > 0);  // tiny-a has a corner at the origin
  ContactEnergyOptions o;
  o.hessian = true;
  o.per_pair = true;
  const ContactEnergy rest = contact_energy(s.A, s.B, s.A.vertices, s.B.vertices, o);
  const ContactEnergy copy = contact_energy(s.A, s.B, pa, s.B.vertices, o);
  BOOST_REQUIRE_GT(rest.pair_count, 0u);
  BOOST_TEST(rest.pair_count == copy.pair_count);
  BOOST_TEST(rest.energy == copy.energy);
  BOOST_TEST((rest.gradient == copy.gradient));
  BOOST_REQUIRE_EQUAL(rest.hessian.nonZeros(), copy.hessian.nonZeros());
  const Eigen::SparseMatrix<double> d = rest.hessian - copy.hessian;
  BOOST_TEST((d.nonZeros() == 0 || d.coeffs().cwiseAbs().maxCoeff() == 0));
  BOOST_REQUIRE_EQUAL(rest.pairs.size(), copy.pairs.size());
  for (std::size_t j = 0; j < rest.pairs.size(); ++j) {
    BOOST_TEST(rest.pairs[j].a == copy.pairs[j].a);
    BOOST_TEST(rest.pairs[j].b == copy.pairs[j].b);
    BOOST_TEST(rest.pairs[j].pdd2_global == copy.pairs[j].pdd2_global);
    BOOST_TEST(rest.pairs[j].energy == copy.pairs[j].energy);
  }
}

// Grids of cell 1/4 half a cell apart along (1, 1, 1): most pairs repeat up to an exact
// translation and the energy computes each kind once (mesh/src/translation_memo.h). Every
// pair's pdd2_global is solve_pair's bit for bit, and the gradient is the weighted sum of
// solve_pair's per-pair gradients (pdd.h: computed from the moved positions, so a position
// moved wrongly would show; summed in another order: 1e-12 of the largest row).
BOOST_AUTO_TEST_CASE(repeated_pairs_of_a_grid_equal_solve_pair) {
  const Mesh A = test::kuhn_grid(4, 0.25, {0, 0, 0}), B = test::kuhn_grid(4, 0.25, {0.125, 0.125, 0.125});
  ContactEnergyOptions o;
  o.per_pair = true;
  const ContactEnergy e = contact_energy(A, B, A.vertices, B.vertices, o);
  BOOST_REQUIRE_GT(e.pair_count, 200u);
  fast::SolveOptions so;
  so.with_global = true;
  so.gradient = true;
  const std::size_t na = A.vertices.size();
  std::vector<Vec3d> g(na + B.vertices.size(), Vec3d{0, 0, 0});
  for (const EnergyPair& p : e.pairs) {
    const TetVertices Ta = element(A, p.a), Tb = element(B, p.b);
    const PairResult<double> r = fast::solve_pair(TetPair{"", {}, Ta, Tb}, so);
    BOOST_REQUIRE(!r.error && !r.pdd2_global_error && r.pdd2_global_grad);
    BOOST_REQUIRE_EQUAL(p.pdd2_global, r.pdd2_global);
    for (int i = 0; i < 8; ++i) {
      const std::size_t v = i < 4 ? A.tets[p.a][i] : na + B.tets[p.b][i - 4];
      for (int k = 0; k < 3; ++k) g[v][k] += p.weight * (*r.pdd2_global_grad)[i][k];
    }
  }
  double scale = 0;
  for (const Vec3d& x : g) scale = std::max({scale, std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
  BOOST_REQUIRE_GT(scale, 0.0);
  for (std::size_t v = 0; v < g.size(); ++v)
    for (int k = 0; k < 3; ++k) BOOST_REQUIRE_LE(std::abs(e.gradient[v][k] - g[v][k]), 1e-12 * scale);
}

// Contacts made by rounding: blocks built from k h (h = 0.1) stacked face to face, B = A moved
// up by 0.3 (A's top at 3 h = 0.30000000000000004, B's bottom at 0.3: every pair across the two
// faces crosses ~5e-17 deep, pdd2_global ~1e-34), and a grid against its copy moved by 0.01 along
// (1, 1, 1) (faces x = y coinciding up to rounding, beside deep pairs). The fast engine computes
// every pair's minimiser itself (global_minimiser: a double normal, or a rational witness where
// none attains the value: pdd/global_minimiser.h), none left to the exact engine; on a sample of
// the shallow pairs each value lies within definitions §8 of the exact engine's interval
// [pdd2_global_lower, pdd2_global].
BOOST_AUTO_TEST_CASE(contacts_made_by_rounding_stay_in_the_fast_engine) {
  const Mesh grid = test::kuhn_grid(3, 0.1, {0, 0, 0});
  const Scene scenes[] = {{grid, test::kuhn_grid(3, 0.1, {0, 0, 0.3})},
                          {test::kuhn_grid(2, 0.1, {0, 0, 0}), test::kuhn_grid(2, 0.1, {0.01, 0.01, 0.01})}};
  int sampled = 0, shallow = 0;
  for (const Scene& s : scenes) {
    ContactEnergyOptions o;
    o.per_pair = true;
    const ContactEnergy e = contact_energy(s.A, s.B, s.A.vertices, s.B.vertices, o);
    BOOST_REQUIRE_GT(e.pair_count, 50u);
    reference::SolveOptions ro;
    ro.with_global = true;
    for (std::size_t j = 0; j < e.pairs.size(); ++j) {
      const EnergyPair& p = e.pairs[j];
      const TetVertices Ta = element(s.A, p.a), Tb = element(s.B, p.b);
      const auto g = fast::global_minimiser(Ta, Tb);
      BOOST_REQUIRE(g);
      BOOST_TEST(g->pd2 == p.pdd2_global);
      if (!(p.pdd2_global < 1e-30)) continue;
      if (shallow++ % 16 != 0) continue;
      const PairResult<Rational> x = reference::solve_pair(TetPair{"", {}, Ta, Tb}, ro);
      BOOST_REQUIRE(!x.error);
      BOOST_REQUIRE(x.pdd2_global_lower);
      const mpq_class v(p.pdd2_global), hi = x.pdd2_global, lo = *x.pdd2_global_lower;
      BOOST_TEST(v <= hi * mpq_class(1 + 1e-9));
      BOOST_TEST(v >= lo * mpq_class(1 - 1e-9));
      ++sampled;
    }
  }
  BOOST_TEST(sampled >= 8);
}

namespace {
// The exact relaxed value along the double normal n (definitions §9's G(n) / n.n): the piece of
// relaxed_pieces.h whose KKT conditions hold at n.
reference::Rational exact_relaxed_along(const TetVertices& A, const TetVertices& B, const Vec3d& n) {
  using reference::Rational;
  const reference::ExactPair p = reference::to_exact(TetPair{"", {}, A, B});
  const reference::Vector v{Rational(n[0]), Rational(n[1]), Rational(n[2])};
  for (unsigned a = 1; a < 16; ++a)
    for (unsigned b = 1; b < 16; ++b) {
      const reference::RelaxedPiece piece = reference::relaxed_piece(p, {a, b});
      if (reference::piece_is_optimal_at(piece, v)) return reference::piece_quadratic(piece, v) / v.squared_length();
    }
  return Rational(0);  // no piece optimal: n separates the pair (every KKT set needs an overlap)
}

// fast::global_minimiser with bound_shallow on one pair: bounded, 0 < pd2 <= upper, and upper at
// or above the exact relaxed value along the returned normal, which must be positive (a normal
// along which the pair still overlaps: an upper bound on pdd2_global that a bound of 0 could
// not pass); the exact value along it returned.
reference::Rational check_bound(const TetVertices& A, const TetVertices& B) {
  fast::MinimiserOptions mo;
  mo.bound_shallow = true;
  const auto b = fast::global_minimiser(A, B, mo);
  BOOST_REQUIRE(b);
  BOOST_REQUIRE(b->bounded);
  BOOST_TEST(b->pd2 > 0);
  BOOST_TEST(b->pd2 <= b->upper);
  const reference::Rational exact = exact_relaxed_along(A, B, b->normal);
  BOOST_TEST(reference::Rational(b->upper) >= exact);
  return exact;
}
}  // namespace

// Contacts made by rounding taken at a bound (contact_energy.h, "Engine"): a Kuhn grid of cell
// 0.1 against its copy moved by 0.01 along (1, 1, 1), faces x = y coinciding up to rounding
// beside deep pairs. By default those pairs are bounded: E within 1e-12 of the energy with every
// pair certified (per_pair) beyond the summation's rounding (the certified terms are the same
// bits; each bounded term lies in (0, w upper], the bounds summing to <= 1e-12 of E), the same
// max_pdd2_global, and gradients within 1e-12 of the largest entry (a bounded pair's gradient is
// ~1e-17 of the element: below the deep pairs' by ~1e-14). Each bounded pair's upper bound lies
// at or above the exact relaxed value along its own normal (so above pdd2_global, the minimum
// over normals) and at or above the certified value; its estimate in (0, upper]. A pair that
// is not bounded is global_minimiser's bit for bit with or without the option.
BOOST_AUTO_TEST_CASE(contacts_made_by_rounding_are_bounded_within_the_share) {
  const Mesh A = test::kuhn_grid(2, 0.1, {0, 0, 0}), B = test::kuhn_grid(2, 0.1, {0.01, 0.01, 0.01});
  ContactEnergyOptions o;
  o.hessian = true;
  const ContactEnergy bounded = contact_energy(A, B, A.vertices, B.vertices, o);
  o.per_pair = true;
  const ContactEnergy full = contact_energy(A, B, A.vertices, B.vertices, o);
  BOOST_REQUIRE_GT(full.pair_count, 50u);
  BOOST_TEST(bounded.pair_count == full.pair_count);
  BOOST_TEST(bounded.bounded_pairs > 0u);
  BOOST_TEST(full.bounded_pairs == 0u);
  BOOST_TEST(std::abs(bounded.energy - full.energy) <= 1e-12 * full.energy + 2e-16 * full.pair_count * full.energy);
  BOOST_TEST(bounded.max_pdd2_global == full.max_pdd2_global);
  const double g = max_abs(full.gradient);
  for (std::size_t v = 0; v < full.gradient.size(); ++v)
    for (int k = 0; k < 3; ++k) BOOST_TEST(std::abs(bounded.gradient[v][k] - full.gradient[v][k]) <= 1e-12 * g);
  fast::MinimiserOptions mo;
  mo.bound_shallow = true;
  int checked = 0, same = 0, shallow = 0, positive = 0;
  for (const EnergyPair& p : full.pairs) {
    const TetVertices Ta = element(A, p.a), Tb = element(B, p.b);
    const auto b = fast::global_minimiser(Ta, Tb, mo);
    BOOST_REQUIRE(b);
    if (!b->bounded) {
      const auto c = fast::global_minimiser(Ta, Tb);
      BOOST_REQUIRE(c);
      BOOST_TEST(b->pd2 == c->pd2);
      BOOST_TEST(b->normal == c->normal);
      BOOST_TEST((b->q1_A == c->q1_A && b->q1_B == c->q1_B));
      ++same;
      continue;
    }
    BOOST_TEST(p.pdd2_global < 1e-30);  // only contacts made by rounding are bounded
    BOOST_TEST(b->upper >= p.pdd2_global * (1 - 1e-9));
    if (shallow++ % 4 != 0) continue;
    positive += check_bound(Ta, Tb) > 0;
    ++checked;
  }
  BOOST_TEST(checked >= 8);
  BOOST_TEST(positive * 2 >= checked);  // (most: a face normal across the crossing faces)
  BOOST_TEST(same >= 8);
}

// A resting contact of a turned scene: Kuhn blocks of 3^3 cells of 0.1, B's bottom 1e-9 below
// A's top, both turned by 0.3 rad about (1, 2, 3) through the contact's middle (each coordinate
// rounded once). Beside the resting pairs (pdd2_global ~1e-20) the turn's rounding makes
// contacts between neighbouring columns (~1e-34). Their face normals' bound (the overlap's
// rounding, ~(10 u size)^2 ~ 1e-31 each) summed over them exceeds 1e-12 of E (~1e-20 a resting
// pair): computed in full, they took most of the call. The same normals' relaxed values on
// compensated heights bound them about their values (~1e-34): every such pair is bounded, E
// within the share of the per_pair call's, and each bound at or above the exact relaxed value
// along its normal (sampled).
BOOST_AUTO_TEST_CASE(rounding_contacts_of_a_turned_resting_scene_stay_bounded) {
  Mesh A = test::kuhn_grid(3, 0.1, {0, 0, 0}), B = test::kuhn_grid(3, 0.1, {0, 0, 0.3 - 1e-9});
  for (Mesh* m : {&A, &B})
    for (Vec3d& x : m->vertices) x = test::turned_about_123(x, {0.15, 0.15, 0.3});
  ContactEnergyOptions o;
  const ContactEnergy bounded = contact_energy(A, B, A.vertices, B.vertices, o);
  o.per_pair = true;
  const ContactEnergy full = contact_energy(A, B, A.vertices, B.vertices, o);
  std::size_t rounding = 0;
  for (const EnergyPair& p : full.pairs) rounding += p.pdd2_global < 1e-30;
  BOOST_REQUIRE_GT(rounding, 50u);
  BOOST_REQUIRE_GT(full.pair_count - rounding, 50u);  // the resting pairs, certified
  BOOST_TEST(bounded.bounded_pairs == rounding);
  BOOST_TEST(std::abs(bounded.energy - full.energy) <= 1e-12 * full.energy + 2e-16 * full.pair_count * full.energy);
  BOOST_TEST(bounded.max_pdd2_global == full.max_pdd2_global);
  int checked = 0;
  for (std::size_t j = 0; j < full.pairs.size(); j += 7)
    if (full.pairs[j].pdd2_global < 1e-30) {
      check_bound(element(A, full.pairs[j].a), element(B, full.pairs[j].b));
      ++checked;
    }
  BOOST_TEST(checked >= 8);
}

// The other route to a bound: pairs whose quick lanes hold, so that the search starts and finds
// its start already below the exact pieces' depth (global_depth's bound_shallow, value_upper's
// bound ~1e-26 where the face normals' is ~1e-31). Two pairs of a grid of Kuhn cubes mirrored in
// alternate cells, cell 0.1 (0.1 k rounded once), against its copy moved (0.05, 0.05, 0) (half a
// cell in x and y): faces on the diagonal planes meeting by rounding. Bounds checked as above.
BOOST_AUTO_TEST_CASE(bounds_from_the_search_start) {
  const TetVertices A1{{{0x0p+0, 0x1.999999999999ap-3, 0x0p+0}, {0x1.999999999999ap-4, 0x1.999999999999ap-3, 0x0p+0},
                        {0x1.999999999999ap-4, 0x1.999999999999ap-3, 0x1.999999999999ap-4},
                        {0x1.999999999999ap-4, 0x1.999999999999ap-4, 0x1.999999999999ap-4}}};
  const TetVertices B1{{{0x1.999999999999ap-5, 0x1.999999999999ap-5, 0x0p+0}, {0x1.3333333333334p-3, 0x1.3333333333334p-3, 0x0p+0},
                        {0x1.999999999999ap-5, 0x1.3333333333334p-3, 0x0p+0},
                        {0x1.3333333333334p-3, 0x1.3333333333334p-3, 0x1.999999999999ap-4}}};
  const TetVertices A3{{{0x0p+0, 0x1.999999999999ap-3, 0x1.999999999999ap-3}, {0x1.999999999999ap-4, 0x1.999999999999ap-3, 0x1.999999999999ap-3},
                        {0x1.999999999999ap-4, 0x1.999999999999ap-3, 0x1.3333333333334p-2},
                        {0x1.999999999999ap-4, 0x1.999999999999ap-4, 0x1.3333333333334p-2}}};
  const TetVertices B3{{{0x1.999999999999ap-5, 0x1.999999999999ap-5, 0x1.999999999999ap-3}, {0x1.3333333333334p-3, 0x1.3333333333334p-3, 0x1.999999999999ap-3},
                        {0x1.999999999999ap-5, 0x1.3333333333334p-3, 0x1.999999999999ap-3},
                        {0x1.3333333333334p-3, 0x1.3333333333334p-3, 0x1.3333333333334p-2}}};
  int positive = 0;
  for (const auto& [A, B] : {std::pair{A1, B1}, std::pair{A3, B3}}) positive += check_bound(A, B) > 0;
  BOOST_TEST(positive >= 1);
}

// Self-contact takes the same bounds: one mesh holding the grid and its moved copy as two bodies
// gives the two-mesh energy (the same pairs, the same bounded ones, E and max_pdd2_global).
BOOST_AUTO_TEST_CASE(self_contact_bounds_as_two_meshes) {
  const Mesh A = test::kuhn_grid(2, 0.1, {0, 0, 0}), B = test::kuhn_grid(2, 0.1, {0.01, 0.01, 0.01});
  Mesh both = A;
  const std::size_t na = A.vertices.size();
  both.vertices.insert(both.vertices.end(), B.vertices.begin(), B.vertices.end());
  for (auto t : B.tets) {
    for (auto& v : t) v += na;
    both.tets.push_back(t);
  }
  both.source_ids.clear();
  both.vertex_sources.clear();
  const ContactEnergy two = contact_energy(A, B, A.vertices, B.vertices);
  const ContactEnergy self = contact_energy_self(both, both.vertices);
  BOOST_REQUIRE_GT(two.bounded_pairs, 0u);
  BOOST_TEST(self.pair_count == two.pair_count);
  BOOST_TEST(self.bounded_pairs == two.bounded_pairs);
  BOOST_TEST(self.energy == two.energy, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(self.max_pdd2_global == two.max_pdd2_global);
}

// Where no pair is certified (blocks stacked face to face, every pair across the faces a contact
// made by rounding), no share is left for bounds: every pair is certified, and E is the
// per_pair call's bit for bit.
BOOST_AUTO_TEST_CASE(rounding_alone_is_certified) {
  const Mesh A = test::kuhn_grid(3, 0.1, {0, 0, 0}), B = test::kuhn_grid(3, 0.1, {0, 0, 0.3});
  ContactEnergyOptions o;
  const ContactEnergy e = contact_energy(A, B, A.vertices, B.vertices, o);
  o.per_pair = true;
  const ContactEnergy full = contact_energy(A, B, A.vertices, B.vertices, o);
  BOOST_REQUIRE_GT(e.pair_count, 20u);
  BOOST_TEST(e.bounded_pairs == 0u);
  BOOST_TEST(e.energy == full.energy);
  BOOST_TEST(e.max_pdd2_global == full.max_pdd2_global);
}

// bound_shallow bounds valid intersecting pairs only: a pair touching face to face exactly (no
// interior point in common, overlap 0 along the face normal) and a separated one are declined
// with the option as without it.
BOOST_AUTO_TEST_CASE(bounds_only_for_intersecting_pairs) {
  const TetVertices A{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  const TetVertices touching{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}}};
  const TetVertices apart{{{0, 0, -0.5}, {1, 0, -0.5}, {0, 1, -0.5}, {0, 0, -1}}};
  fast::MinimiserOptions mo;
  mo.bound_shallow = true;
  for (const TetVertices& B : {touching, apart}) {
    BOOST_TEST(!fast::global_minimiser(A, B));
    BOOST_TEST(!fast::global_minimiser(A, B, mo));
  }
}

// Random contacts made by rounding off the axes: A random in [-1, 1]^3; three vertices of B on
// one of A's face planes up to rounding (barycentric combinations of its vertices, weights in
// [-0.3, 1], computed in doubles), B's apex across the plane. Every pair bounded is checked as
// above (the bound at or above the exact relaxed value along its normal); most are bounded
// (measured: 2,179 of 3,000; the others cross by more than rounding or not at all).
BOOST_AUTO_TEST_CASE(bounds_on_random_planes) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coord(-1, 1), weight(-0.3, 1), apex(0.2, 2);
  fast::MinimiserOptions mo;
  mo.bound_shallow = true;
  int bounded = 0, positive = 0;
  const int faces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (int k = 0; k < 60; ++k) {
    TetVertices A, B;
    for (auto& v : A)
      for (double& x : v) x = coord(rng);
    const int* f = faces[k % 4];
    const int o = 6 - f[0] - f[1] - f[2];
    for (int j = 0; j < 3; ++j) {
      double w[3] = {weight(rng), weight(rng), weight(rng)};
      const double s = w[0] + w[1] + w[2];
      for (double& x : w) x /= s;
      for (int c = 0; c < 3; ++c) B[j][c] = w[0] * A[f[0]][c] + w[1] * A[f[1]][c] + w[2] * A[f[2]][c];
    }
    const double t = apex(rng);
    for (int c = 0; c < 3; ++c) {
      const double centre = (A[f[0]][c] + A[f[1]][c] + A[f[2]][c]) / 3;
      B[3][c] = centre - (A[o][c] - centre) * t;
    }
    const auto b = fast::global_minimiser(A, B, mo);
    if (!b || !b->bounded) continue;
    ++bounded;
    positive += check_bound(A, B) > 0;
  }
  BOOST_TEST(bounded >= 20);
  BOOST_TEST(positive * 2 >= bounded);
}
