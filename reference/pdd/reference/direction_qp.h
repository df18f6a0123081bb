// direction_qp.h — PD_d^2 along one candidate direction: the QP of paper Secs. IV-B and V
// (objective eq. 3, constraints eq. 10), solved exactly by CGAL's QP solver (definitions §5).
//
// Input : an exact pair, one oriented candidate n with its constrained/free vertex sets, the
//         case and the formulation.
// Output: nullopt when the QP is infeasible (case 1 only); otherwise the exact optimum
//         sigma_A + sigma_B and the deformed positions q1_A, q1_B attaining it.
//
// Constraints (p_s a point of the separating plane, x the deformed vertex):
//   n.(x - p_s) = 0   for x in C_A and C_B        (Relaxed: <= 0 for C_A, >= 0 for C_B)
//   n.(x - p_s) <= 0  for x in F_A,   n.(x - p_s) >= 0 for x in F_B
// Cases: Static    q1_A = q0_A (paper case 1), B deforms;
//        Deformable both deform (paper case 2);
//        Relaxed   case 2 with every constraint an inequality.
// Formulations:
//   Full     the paper's variables: q1_A (12, not in Static), q1_B (12), p_s (3); minimise
//            20 (sigma_A + sigma_B) as a quadratic in q1 (definitions §2 closed form).
//   Reduced  definitions §5: orthogonal displacement components never help, so with mu_i = n.d_i
//            (the displacement along n, scaled by |n|^2's unit) and C = n.p_s the problem is
//            minimise sum_T mu_T^T (I + J) mu_T / (20 n.n)  s.t.  n.x_i + mu_i - C {=,<=,>=} 0.
//            Deformed positions are x_i + (mu_i / n.n) n. The two formulations agree exactly
//            (tested on every fixture family).
#pragma once

#include <optional>

#include "pdd/qp_formulation.h"
#include "pdd/reference/candidate_directions.h"

namespace pdd::reference {

enum class PddCase { Static, Deformable, Relaxed };

struct DirectionOptimum {
  Rational value;    // sigma_A + sigma_B at the optimum (PD_d^2 along this direction)
  ExactTet q1_A;     // deformed A (the rest pose in Static)
  ExactTet q1_B;     // deformed B
};

// Full is solved axis-aligned (the paper's coordinates) unless some component of n has a
// mantissa wider than 256 bits (only pairs mixing magnitudes far beyond a double's 53 bits,
// e.g. 1e20 with 1e-20, or 1e308 with 5e-324; no shipped fixture); then in the orthogonal frame (n, n x e, n x (n x e)), an exact
// change of the same 27 variables under which the solver's matrix entries stay small
// (direction_qp.cpp explains the cost). Exposed for the tests.
bool full_qp_uses_frame(const Vector& n);

std::optional<DirectionOptimum> direction_qp(const ExactPair& pair, const CandidateDirection& dir,
                                             PddCase pdd_case, QpFormulation formulation);

// definitions §9, a lower bound for a whole cone of normals. With G(n) = (the Reduced Relaxed QP's
// optimum for the unnormalised n) · n.n = the minimum of sum_T mu_T^T (I + J) mu_T / 20 subject
// to n.x_i + mu_i <= C (A), >= C (B), returns
//     min { G(n) : n in conv(normals) },
// solved as ONE convex QP in (lambda, mu, C) with n = sum_k lambda_k normals_k, lambda >= 0,
// sum lambda = 1: the constraints are linear in (lambda, mu, C) jointly, so the joint minimum is
// the minimum of G over the hull (no convexity of G needed; it is convex all the same).
// Use (global_pdd.cpp): if every normal has |n_k| <= 1, every unit u in the cone they span is
// p/|p| for a p in the hull with |p| <= 1, and relaxed(u) = G(p)/|p|² >= G(p) >= the returned
// value. `normals`: 1 to 8 vectors with dyadic components (CGAL's QP solver takes Gmpzf).
// `lambda` (optional): the minimiser's weights (n* = sum_k lambda_k normals_k).
Rational relaxed_hull_minimum(const ExactPair& pair, const std::vector<Vector>& normals,
                              std::vector<Rational>* lambda = nullptr);

}  // namespace pdd::reference
