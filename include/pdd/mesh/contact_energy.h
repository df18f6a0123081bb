// mesh/contact_energy.h — a contact energy for simulators (definitions §12): at the current positions
// P of two tetrahedral meshes (or of one, self-contact),
//
//     E(P) = sum over intersecting element pairs (a, b) of  w_ab * pdd2_global(a, b; P)
//
// with its gradient per vertex and, on request, a sparse positive semi-definite Hessian.
//
//   #include <pdd/mesh.h>     // includes this header; CMake: pdd::mesh
//   pdd::mesh::ContactEnergyOptions o;  o.hessian = true;
//   pdd::mesh::ContactEnergy e = pdd::mesh::contact_energy(A, B, pa, pb, o);
//   e.energy, e.gradient[v] (A's vertices, then B's), e.hessian (3n x 3n, row 3v + k)
//
// Inputs
//   A, B     meshes at REST (their `vertices` give the weights, below); the tetrahedra.
//   pa, pb   current positions, one per vertex of A / of B (same counts).
//   options  ContactEnergyOptions (defaults in the struct).
// Outputs (ContactEnergy)
//   energy    E(P), squared length times the weight's units (length^4 with the default weight).
//   gradient  dE/dP per vertex, A's vertices first (n = nA + nB rows; nA for self-contact).
//   hessian   (options.hessian) 3n x 3n, symmetric, positive semi-definite (Gauss–Newton, below).
//   pairs     (options.per_pair) each intersecting pair: a, b, weight, pdd2_global, w * pdd2_global.
//
// Pairs. Those of definitions §10 at P: every (a, b) of A x B whose interiors intersect (exact
// decision), or for self-contact every a < b sharing no vertex index (so two bodies of one file,
// and a body folded onto itself, both count, as definitions §11 asks). A flat element (zero
// volume at P, or at rest for the weight) or one with a non-finite coordinate is skipped and
// listed in `skipped`, as contacts() does; an element whose REST vertex (the mesh's `vertices`,
// where they give the weights) has a non-finite coordinate is listed whether or not it is in a
// pair (bad input wherever it lies).
//
// Weights. w_ab = (V_a V_b)^(1/3), V the REST volumes (|det| / 6 of A's / B's `vertices`; with
// options.weights_follow_a / _b that side's current volumes, and the gradient then includes the
// weights' derivative: the options' comment), held
// constant: E is a function of P alone, and the gradient and Hessian below are exactly its
// derivatives (weights from the current volumes would add a non-convex term per pair). Why this
// weight: for a shallow contact (depth delta << element size h) across an area S, each
// intersecting pair costs pdd2_global ~ delta^2 (a few vertices moved by about delta: the
// object norm is a MEAN squared displacement, independent of the element's size), and there
// are ~ S / h^2 such pairs; so the unweighted sum grows like S delta^2 / h^2 when the mesh is
// refined. (V_a V_b)^(1/3) ~ h^2 is an area, making E ~ c S delta^2 = c times the integral of
// the squared depth over the contact area, a penalty independent of the resolution; measured
// c = 0.62-0.69 (0.71 on the coarsest mesh of a body 1.5 elements thick). Measured (two Gmsh
// boxes overlapping by a fixed depth, meshed at h, h/2, h/4; scripts/contact-energy-resolution.py):
// E(h/4)/E(h/2) within ~2% on average over placements; E(h/2)/E(h) and E(h/4)/E(h) within ~3% on
// average (~10% for one placement) where the body is several elements thick at h, 7-12% on average
// (up to ~20% for one placement) where it is one or two (docs/definitions.md "Contact energy"),
// beside ~4x per halving for w = 1 and ~1/2 for w = (V_a + V_b)/2. Weight::Unit gives w = 1. Formed as
// the product of the two volumes' cube roots, each from an exactly rescaled determinant (no
// overflow or underflow where the weight is a double).
//
// Gradient (definitions §11/§12). Per pair, with Q* = (q1_A_global, q1_B_global) the separated
// positions attaining pdd2_global and d = Q* - P per tetrahedron,
//     grad_p pdd2_global = -d sigma / d d = -(d_i + sum_k d_k) / 10   (vertex i of that element)
// where the minimiser is unique; at a tie, the gradient of the returned minimiser's branch (one
// element of the Clarke generalized gradient, pdd.h "Ties"). Scattered with weight w_ab onto the
// pair's eight vertices. Not intersecting: 0.
//
// Hessian (Gauss–Newton of the fixed-plane QP). Hold the unit normal u of the pair's minimiser.
// Definitions §9: the cheapest separation across a plane of normal u moves every vertex along u
// only, so with s = (u.p_0, ..., u.p_7) (A's four vertices, then B's) and displacements t along u
//     V_u(s) = min over t in R^8, c in R of  t_A^T M t_A + t_B^T M t_B,   M = (I + J) / 20,
//              subject to s_i + t_i <= c (i in A),  s_j + t_j >= c (j in B),
// a convex QP whose right-hand side is linear in s; pdd2_global(P) = V_u(s(P)) at the held u.
// On the current active set S (the vertices on the plane at the minimiser: A's with
// u.q_i = c, B's with u.q_j = c) the constraints are equalities t_k - c = -s_k (k in S). With
// x = (t, c), H = 2 blockdiag(M, M, 0) and C the |S| x 9 matrix of rows e_k - e_c, the KKT system
//     [H C^T; C 0] [x; lambda] = [0; -S s]           (S: the |S| x 8 selection)
// has x = X (-S s) (X: the first 9 rows of the inverse's last |S| columns), so the value is
//     V_S(s) = 1/2 x^T H x = 1/2 s^T (S^T X^T H X S) s =: 1/2 s^T Qs s,
// a quadratic in s (Qs = S^T X^T H X S is 8 x 8, positive semi-definite as X^T H X is, and
// Qs 1 = 0: shifting all eight along u shifts c). The KKT matrix is invertible when S is not
// empty: C has full row rank (each row has its own t_k) and H is positive definite on the null
// space of C (t = 0 there forces c = t_k = 0). With N the 8 x 24 matrix of rows u^T (s = N p),
//     Hessian_p = N^T Qs N = Qs (x) u u^T            (24 x 24, entry (3i+a, 3j+b) = Qs_ij u_a u_b)
// positive semi-definite, and its gradient Qs s (x) u equals the gradient above on the piece.
// Summed with the weights over all pairs into one sparse 3n x 3n matrix (row 3v + k). It omits
// the curvature of the normal's motion (pdd2_global is semiconcave: that part is concave), so it
// is the Hessian of a majorizer: V_u(s(P')) >= pdd2_global(P') for every P' (pdd2_global is the
// minimum over normals), with equality at P. Per pair only: M(P') = sum over the pairs
// intersecting at P of w V_u(s(P')) majorizes those pairs' share of E, not E itself, whose sum
// also takes the pairs that begin to intersect at P' (a ball sliding 0.03 of its radius on a
// block: M(P') = 2.69e-9 below E(P) = 3.38e-9, while E(P') = 3.63e-9). A step that lowers M
// lowers E when it creates no new intersecting pair; a line search on E itself (as
// examples/soft_body.py does) makes no such assumption. The active set S is V_u's at s(P),
// from the heights alone (fixed_plane_active_set in contact_energy.cpp: the piece whose KKT
// conditions hold, with no tolerance); where s(P) lies within rounding of a kink of V_u, either
// piece is a one-sided Hessian.
//
// Engine. Fast (default): the intersecting pairs of mesh contacts (no variant), then per pair
// pdd::fast::global_minimiser (pdd/global_minimiser.h: solve_pair's definitions §9 value,
// normal and positions bit for bit, without the rest of the record), or where it declines the
// whole pdd::fast::solve_pair; a pair whose fast pdd2_global is declined (pdd2_global_error) is
// recomputed by the exact engine. A contact made by rounding (faces meant to coincide that
// rounding made cross, ~1e-17 of the element deep: blocks stacked face to face, a grid against
// its shifted copy) has pdd2_global certified along a rational normal that no double normal
// attains; global_minimiser returns it (`witness`) with that normal and its positions rounded, as
// the exact engine's witness is rounded below, and the energy takes it (tens of microseconds a
// pair where the shallow certificate answers it, else milliseconds on the exact pieces; the
// exact engine takes tens to hundreds). Its gradient there is the rounded positions' (their
// displacement, ~1e-17 of the element, is below their rounding: accurate in absolute terms
// only, as for the exact engine's). Such a pair's term is ~1e-30 of a real overlap's, so unless
// options.per_pair asks for every value, it is first taken bounded (MinimiserOptions::
// bound_shallow: the doubles' estimate along a face normal or the search's start, with a
// certified upper bound below 1e-20 of the pair's size squared, in a few microseconds) and kept
// so while the bounded pairs' weighted bounds together stay below 1e-12 of the certified terms'
// sum and none reaches the largest certified pdd2_global; the rest are certified as above (all
// of them where no pair is certified: blocks resting by rounding alone; their time counts in
// seconds_contacts). E is then within definitions §8's 1e-9 plus 1e-12 of the exact terms' sum,
// max_pdd2_global certified, a bounded pair's gradient its plane's positions' (displacements of
// object norm below sqrt(bound), as the minimiser's: within ~1e-9 of the pair's size of its
// gradient, in absolute terms) and its Hessian its plane's (V_u of "Hessian" for that normal: a
// majorizer touching its term at P to within the bound); bounded_pairs counts them. Measured on
// a decimal Kuhn grid against its copy moved a quarter cell along (1, 1, 1) (7,884 of 11,910
// pairs made by rounding): 8.4 us a pair against 259 us with every pair certified, 6.9 us for
// the copy turned. The bound is about the value itself (its relaxed value along the normal on
// compensated heights), so the bounded share stays within 1e-12 of E even beside resting
// contacts ~1e-9 deep: Kuhn blocks resting on each other, the whole scene turned (4,649 such
// pairs beside 1,728 resting ones), ~0.16 s a call with the Hessian, 2.2 s with them certified.
// Pairs run in parallel (TBB); the gradient and the Hessian are summed per vertex over its pairs
// in pair order (the same doubles on any number of threads), the Hessian written row by row
// straight into its compressed storage.
// Exact: contacts_exact (pdd::reference::solve_pair; exact witness positions, rounded to double
// here), milliseconds a pair: the judge for small meshes.
//
// Errors: std::invalid_argument when positions do not have one entry per vertex or a
// tetrahedron refers to a missing vertex; Cancelled when options.cancel is set;
// std::length_error when the Hessian would have more than 2^31 - 1 entries (Eigen's int index);
// std::overflow_error when E itself exceeds the double range (E ~ L^4: coordinates beyond
// ~1e77; weights and values are formed without overflow wherever they are doubles);
// std::underflow_error when a pair's term w_ab pdd2_global falls below it (coordinates below
// ~1e-67), naming the pair: E would lose its accuracy, or read 0 with pairs intersecting.
#pragma once

#include <Eigen/Sparse>

#include <array>
#include <atomic>
#include <cstddef>
#include <vector>

#include "pdd/mesh/mesh.h"
#include "pdd/pdd.h"

namespace pdd::mesh {

enum class EnergyEngine { Fast, Exact };
enum class EnergyWeight {
  Area,  // w_ab = (V_a V_b)^(1/3), rest volumes (the default; see "Weights")
  Unit,  // w_ab = 1 (for comparison: grows with refinement)
};

struct ContactEnergyOptions {
  EnergyEngine engine = EnergyEngine::Fast;
  EnergyWeight weight = EnergyWeight::Area;
  bool hessian = false;   // fill ContactEnergy::hessian
  bool per_pair = false;  // fill ContactEnergy::pairs (every pair certified: none bounded, "Engine")
  // A's (B's) weights from its current volumes instead of its rest vertices (Python's default,
  // rest_A=None; pdd mesh --energy without --rest-a): E(P) = sum w_ab(P) pdd2_global(P), and the
  // gradient is that function's, each weight's derivative included (w_ab = (V_a V_b)^(1/3):
  // dw/dx = w / 3 (dV_a/dx / V_a + dV_b/dx / V_b), over the side that follows), so that finite
  // differences of E agree with it; that term grows like V^(-2/3) as an element flattens (a
  // simulator holds rest weights). The Hessian stays the Gauss–Newton one at fixed weights
  // (positive semi-definite). Self-contact: follow_a alone.
  bool weights_follow_a = false, weights_follow_b = false;
  // As ContactOptions::cancel (checked between stages and per pair); throws Cancelled.
  const std::atomic<bool>* cancel = nullptr;
};

struct EnergyPair {
  std::size_t a = 0, b = 0;  // element of A (of the mesh, self-contact), element of B
  double weight = 0;         // w_ab
  double pdd2_global = 0;    // definitions §9 at the current positions
  double energy = 0;         // weight * pdd2_global
};

struct ContactEnergy {
  double energy = 0;
  std::vector<Vec3d> gradient;         // one row per vertex, A's first
  Eigen::SparseMatrix<double> hessian;  // 3n x 3n when asked, else 0 x 0
  std::vector<EnergyPair> pairs;        // when asked, sorted by (a, b)
  std::size_t pair_count = 0;           // intersecting pairs
  double max_pdd2_global = 0;           // largest pdd2_global over them (0 if none)
  std::size_t bounded_pairs = 0;        // of them, taken at a bound ("Engine" above; 0 with per_pair)
  std::vector<SkippedElement> skipped;
  double seconds_contacts = 0, seconds_assembly = 0;
  double seconds_found = 0;  // the part of seconds_contacts spent finding the pairs (boxes,
                             // broadphase, exact decision); the rest: their minimisers
};

// Two meshes: pa / pb the current positions of A's / B's vertices.
ContactEnergy contact_energy(const Mesh& A, const Mesh& B, const std::vector<Vec3d>& pa,
                             const std::vector<Vec3d>& pb, const ContactEnergyOptions& options = {});
// Self-contact of one mesh (definitions §10's pairs: a < b sharing no vertex).
ContactEnergy contact_energy_self(const Mesh& A, const std::vector<Vec3d>& pa,
                                  const ContactEnergyOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Building blocks (one pair; for tests and for callers with their own pair lists).

// One pair's terms at positions P = (A's s0..s3, B's r0..r3), from its global minimiser
// Q = (q1_A_global, q1_B_global) and normal (any length, A -> B).
struct PairTerms {
  std::array<Vec3d, 8> gradient{};             // grad_P pdd2_global
  std::array<std::array<double, 8>, 8> qs{};   // Qs of "Hessian" (Hessian_P = Qs (x) u u^T)
  Vec3d unit_normal{};                         // u
  std::array<bool, 8> active{};                // the active set S
  double piece_value = 0;                      // V_S(s(P)) = 1/2 s^T Qs s (= pdd2_global)
};
PairTerms pair_terms(const TetVertices& A, const TetVertices& B, const TetVertices& qA,
                     const TetVertices& qB, const Vec3d& normal);

// Qs of "Hessian" for an active set S (true: on the plane; A's four vertices, then B's; S_A
// and S_B not empty), 8 x 8, zero off S. piece_matrix: the closed form
//     Qs_km = ( [k = m] + alpha_g [m in S_g] - 5 alpha_g alpha_g(m) / W ) / 10   (k in S_g, m in S)
// with alpha_g = 1 / (5 - |S_g|), W = alpha_A |S_A| + alpha_B |S_B| (derived in
// contact_energy.cpp), which the energy uses; piece_matrix_kkt: by solving the KKT system
// above (for tests: the two agree to rounding).
std::array<std::array<double, 8>, 8> piece_matrix(const std::array<bool, 8>& active);
std::array<std::array<double, 8>, 8> piece_matrix_kkt(const std::array<bool, 8>& active);

// V_u of "Hessian" with the normal u held (any length, A -> B), solved exactly as a QP by
// enumerating the 255 non-empty active sets (the feasible one of least value): for tests.
// gradient: its gradient with respect to the eight positions on the optimal piece.
struct FixedPlane {
  double value = 0;
  std::array<Vec3d, 8> gradient{};
};
FixedPlane fixed_plane(const TetVertices& A, const TetVertices& B, const Vec3d& normal);

}  // namespace pdd::mesh
