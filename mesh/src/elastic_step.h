// elastic_step.h — the global step of resolve's projective-dynamics rounds (resolve.h): the
// displacement of every free vertex of one mesh that pulls its contact vertices towards their
// targets while the rest of the mesh follows elastically.
//
// Inputs:  the rest mesh, its valid elements, the fixed flags; per round the pull y_v - x_v of
//          each vertex (zero for a vertex with no target: it is anchored where it is).
// Outputs: the displacement Delta (per vertex; 0 for fixed vertices and vertices in no valid
//          element) minimising, over the free vertices,
//              E(Delta) = 1/2 sum_e V_e |grad Delta|_e^2  +  1/2 sum_v w_v |Delta_v - pull_v|^2,
//          the Dirichlet energy of the displacement over the rest mesh (linear P1 elements:
//          K_ij = sum_e V_e grad phi_i . grad phi_j, the vector Laplacian form of linear
//          elasticity) plus a weighted anchor to the targets, fixed vertices as Dirichlet
//          conditions (Delta = 0). Normal equations, one per coordinate:
//              (K + W) Delta = W pull,        W = diag(w_v),
//          w_v = kAnchor K_vv (Anchor::Pulled), or with Anchor::Free kFreeAnchor K_vv for a
//          vertex without pull this round (weaker: the interior follows further); a vertex
//          without pull is anchored where it is.
// K + W with kAnchor everywhere is assembled once per run; Anchor::Free lowers the diagonal of
// a copy. It is symmetric positive definite (K positive semi-definite, W positive on every
// unknown) and well conditioned: with w_v >= a K_vv (a = kAnchor, or kFreeAnchor), its
// Jacobi-scaled eigenvalues lie in [a / (1 + a), (2 + a) / (1 + a)] up to the mesh's valence
// spread (Gershgorin), so conjugate gradients with the diagonal preconditioner (Eigen's
// ConjugateGradient) converge in tens of iterations (a few times 1/sqrt(a)) whatever the mesh
// size. A
// sparse Cholesky factorisation (SimplicialLDLT) was measured at 19 s for a 10^5-element ball
// (fill of a 3D mesh), against 0.1 s per round for these iterations. The solution need not be
// exact: the step limit and the exact verdict judge the positions, not the solve.
// Scale: the solution is that of the mesh and pulls scaled by powers of two (rest edge vectors by
// 2^-k, k the exponent of the largest |entry|; the pulls by 2^-j, j that of the largest pull) and
// scaled back. Scaling by a power of two commutes with every rounding while no value leaves the
// normal range, so at ordinary scales the steps are bit for bit those of the unscaled system;
// unscaled, K ~ L, the right side ~ L^2 and the iterations' squared norms ~ L^4 leave the double
// range for meshes of size L beyond about 1e+-77 (Eigen's iteration returns 0 where the right
// side's squared norm underflows: no vertex moved).
// The three coordinates are three independent systems with one matrix: they are solved at once
// on three workers (TBB), each exactly the iteration Eigen's ConjugateGradient runs for that
// column (same matrix traversal, preconditioner and vectors), so the result does not depend on
// the number of threads.
#pragma once

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <cstddef>
#include <vector>

#include "pdd/mesh.h"

namespace pdd::mesh::detail {

class ElasticStep {
 public:
  ElasticStep(const Mesh& rest, const std::vector<std::size_t>& elements, const std::vector<char>& fixed);
  // Delta for the given pulls (both of the mesh's vertex count). False when the iterations
  // did not converge (then Delta is zero).
  enum class Anchor { Pulled, Free };  // every vertex anchored by kAnchor / unpulled ones weaker
  bool solve(const std::vector<Vec3d>& pull, std::vector<Vec3d>& delta, Anchor anchor = Anchor::Pulled) const;
  bool ok() const { return ok_; }

 private:
  std::vector<std::ptrdiff_t> unknown_;  // per vertex: its unknown, -1 when it does not move
  std::vector<double> weight_;           // per unknown: w_v = kAnchor K_vv (scaled: above)
  Eigen::SparseMatrix<double> matrix_;   // K + W over the unknowns
  Eigen::DiagonalPreconditioner<double> preconditioner_;  // Jacobi, of matrix_
  bool ok_ = false;
};

}  // namespace pdd::mesh::detail
