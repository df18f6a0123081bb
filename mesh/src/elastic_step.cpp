// elastic_step.cpp — the global step of resolve (elastic_step.h).
#include "elastic_step.h"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "binary_scale.h"

namespace pdd::mesh::detail {
namespace {

// w_v = kAnchor * K_vv: the anchor of a vertex against its own elastic stiffness. The screened
// Poisson kernel of K + W spreads a pull over about 1/sqrt(kAnchor) rings of elements per round
// (each round anchors at the positions the last one reached, so the spread grows over the
// rounds), and a patch of contact vertices pulled together moves most of its pull. Measured on
// two Gmsh balls (h = 0.1, about 2.5e4 elements each) overlapping by one layer, both free /
// A fixed: kAnchor 1 (overshoot 1): 19 rounds, min V1/V0 0.254 (the contact layer squeezed to
// the R4 bound before the interior follows) / stalled at 400 pairs; 0.2 (overshoot 1): 23 / 22
// rounds, min V1/V0 0.35 / 0.29; 0.1 (overshoot 1.5): 22 / 18 rounds, 0.54 / 0.37; 0.05
// (overshoot 1): stalled / 41 rounds.
// Anchor::Free anchors the vertices without a pull by kFreeAnchor * K_vv only: the interior
// follows the contact about three times as far per round (1/sqrt(0.01) rings) while the
// contact vertices keep kAnchor's share of their pull. Used from the first round on every mesh
// it costs about 1.7 times as much on the one-layer cases of scripts/make-resolve-cases.sh, so
// resolve uses it only for the self-contact rounds after the first ones stalled (resolve.cpp);
// on that script's bar wound into itself (coil, 25.8k elements) kAnchor alone leaves 4 pairs
// whose elements are squeezed to the R4 bounds; Anchor::Free from the rest pose resolves it in
// 44 rounds, min V1/V0 0.38 (switched on only after the step limit first cut a step, it still
// left 18 pairs: the squeezed layer does not recover).
constexpr double kAnchor = 0.1;
constexpr double kFreeAnchor = 0.01;
// Conjugate gradients: relative residual 1e-3 (the displacement to about 1e-3 of the pull: the
// step limit and the exact verdict judge the positions reached, not the solve, and the next
// round's pull corrects what this one left), at most 500 iterations (the conditioning argued in
// elastic_step.h needs a few tens).
constexpr double kTolerance = 1e-3;
constexpr int kMaxIterations = 500;

}  // namespace

ElasticStep::ElasticStep(const Mesh& rest, const std::vector<std::size_t>& elements, const std::vector<char>& fixed) {
  const std::size_t nv = rest.vertices.size();
  std::vector<char> used(nv, 0);
  for (std::size_t e : elements)
    for (std::size_t v : rest.tets[e]) used[v] = 1;
  unknown_.assign(nv, -1);
  std::ptrdiff_t n = 0;
  for (std::size_t v = 0; v < nv; ++v)
    if (used[v] && !fixed[v]) unknown_[v] = n++;
  // 2^-scale: the largest |rest edge vector entry| in [1/2, 1) once scaled (header: "Scale").
  double largest = 0;
  for (std::size_t e : elements)
    for (int c = 1; c < 4; ++c)
      for (int r = 0; r < 3; ++r)
        largest = std::max(largest, std::abs(rest.vertices[rest.tets[e][c]][r] - rest.vertices[rest.tets[e][0]][r]));
  const int scale = binary_exponent(largest);
  std::vector<Eigen::Triplet<double>> k;
  k.reserve(elements.size() * 16);
  std::vector<double> diag(std::size_t(n), 0);
  for (std::size_t e : elements) {
    const auto& t = rest.tets[e];
    Eigen::Matrix3d D;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) D(r, c) = std::ldexp(rest.vertices[t[c + 1]][r] - rest.vertices[t[0]][r], -scale);
    const double volume = std::abs(D.determinant()) / 6;
    const Eigen::Matrix3d G = D.inverse();  // row i: grad phi_{i+1}
    Eigen::Matrix<double, 4, 3> grad;
    grad.row(0) = -(G.row(0) + G.row(1) + G.row(2));
    grad.bottomRows<3>() = G;
    for (int i = 0; i < 4; ++i) {
      const std::ptrdiff_t ui = unknown_[t[i]];
      if (ui < 0) continue;
      for (int j = 0; j < 4; ++j) {
        const std::ptrdiff_t uj = unknown_[t[j]];
        if (uj < 0) continue;  // a fixed neighbour: Delta = 0 there, no term on the right
        const double kij = volume * grad.row(i).dot(grad.row(j));
        k.emplace_back(ui, uj, kij);
        if (i == j) diag[std::size_t(ui)] += kij;
      }
    }
  }
  weight_.resize(std::size_t(n));
  for (std::ptrdiff_t u = 0; u < n; ++u) {
    weight_[std::size_t(u)] = kAnchor * diag[std::size_t(u)];
    k.emplace_back(u, u, weight_[std::size_t(u)]);
  }
  matrix_.resize(n, n);
  matrix_.setFromTriplets(k.begin(), k.end());
  matrix_.makeCompressed();
  if (n == 0) return;
  preconditioner_.compute(matrix_);
  ok_ = preconditioner_.info() == Eigen::Success;
}

bool ElasticStep::solve(const std::vector<Vec3d>& pull, std::vector<Vec3d>& delta, Anchor anchor) const {
  delta.assign(pull.size(), {0, 0, 0});
  if (!ok_) return false;
  const std::ptrdiff_t n = std::ptrdiff_t(weight_.size());
  // 2^-scale: the largest |pull| entry in [1/2, 1) once scaled (header: "Scale").
  double largest = 0;
  for (std::size_t v = 0; v < pull.size(); ++v)
    if (unknown_[v] >= 0)
      for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(pull[v][c]));
  const int scale = binary_exponent(largest);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 3);
  for (std::size_t v = 0; v < pull.size(); ++v)
    if (unknown_[v] >= 0)
      for (int c = 0; c < 3; ++c)
        rhs(unknown_[v], c) = weight_[std::size_t(unknown_[v])] * std::ldexp(pull[v][c], -scale);
  // Free anchors: a copy of K + W whose vertices without pull keep kFreeAnchor of their anchor.
  Eigen::SparseMatrix<double> relaxed;
  Eigen::DiagonalPreconditioner<double> relaxed_preconditioner;
  const Eigen::SparseMatrix<double>* m = &matrix_;
  const Eigen::DiagonalPreconditioner<double>* preconditioner = &preconditioner_;
  if (anchor == Anchor::Free) {
    relaxed = matrix_;
    for (std::size_t v = 0; v < pull.size(); ++v) {
      const std::ptrdiff_t i = unknown_[v];
      if (i >= 0 && pull[v] == Vec3d{0, 0, 0}) relaxed.coeffRef(i, i) -= (1 - kFreeAnchor / kAnchor) * weight_[std::size_t(i)];
    }
    relaxed_preconditioner.compute(relaxed);
    if (relaxed_preconditioner.info() != Eigen::Success) return false;
    m = &relaxed;
    preconditioner = &relaxed_preconditioner;
  }
  // Per column, Eigen's ConjugateGradient<SparseMatrix, Lower | Upper>::solve from x = 0: it
  // multiplies by the transpose (a row-major traversal of the symmetric matrix), and an
  // iteration that does not reach kTolerance in kMaxIterations returns its last iterate.
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(n, 3);
  tbb::parallel_for(0, 3, [&](int c) {
    auto xc = x.col(c);
    Eigen::Index iterations = kMaxIterations;
    double error = kTolerance;
    Eigen::internal::conjugate_gradient(m->transpose(), rhs.col(c), xc, *preconditioner, iterations, error);
  });
  if (!x.allFinite()) return false;  // not converged within kMaxIterations: still a descent
  for (std::size_t v = 0; v < pull.size(); ++v)
    if (unknown_[v] >= 0)
      for (int c = 0; c < 3; ++c) delta[v][c] = std::ldexp(x(unknown_[v], c), scale);
  return true;
}

}  // namespace pdd::mesh::detail
