// contact_energy.cpp — pdd::mesh::contact_energy (definitions §12; include/pdd/mesh/contact_energy.h
// derives every formula used here).
#include "pdd/mesh/contact_energy.h"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "pdd/mesh.h"

namespace pdd::mesh {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// |det| / 6 of tetrahedron i of m at its `vertices` (the rest volume).
double rest_volume(const Mesh& m, std::size_t i) {
  const TetVertices t = element(m, i);
  double e[3][3];
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) e[k][c] = t[k + 1][c] - t[0][c];
  const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                     e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                     e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  return std::abs(det) / 6;
}

// The KKT solve of the header's "Hessian" for the active set `active` (not empty): the 8 x 8
// matrix Qs = S^T X^T H X S.
Eigen::Matrix<double, 8, 8> piece_matrix(const std::array<bool, 8>& active) {
  int m = 0;
  for (bool a : active) m += a;
  const int n = 9 + m;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (int blk = 0; blk < 2; ++blk)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) K(4 * blk + i, 4 * blk + j) = (i == j ? 2.0 : 1.0) / 10;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, m);
  for (int k = 0, r = 0; k < 8; ++k) {
    if (!active[k]) continue;
    K(9 + r, k) = K(k, 9 + r) = 1;
    K(9 + r, 8) = K(8, 9 + r) = -1;
    rhs(9 + r, r) = 1;
    ++r;
  }
  const Eigen::MatrixXd Z = K.partialPivLu().solve(rhs);
  const Eigen::MatrixXd X = Z.topRows(9);
  const Eigen::MatrixXd W = X.transpose() * K.topLeftCorner(9, 9) * X;  // X^T H X (m x m)
  Eigen::Matrix<double, 8, 8> Qs = Eigen::Matrix<double, 8, 8>::Zero();
  for (int i = 0, ri = 0; i < 8; ++i) {
    if (!active[i]) continue;
    for (int j = 0, rj = 0; j < 8; ++j) {
      if (!active[j]) continue;
      Qs(i, j) = 0.5 * (W(ri, rj) + W(rj, ri));
      ++rj;
    }
    ++ri;
  }
  return Qs;
}

std::array<double, 8> projections(const TetVertices& A, const TetVertices& B, const Vec3d& u) {
  std::array<double, 8> s{};
  for (int i = 0; i < 4; ++i) {
    s[i] = dot(u, A[i]);
    s[4 + i] = dot(u, B[i]);
  }
  return s;
}

Vec3d unit(const Vec3d& n) {
  const double l = std::sqrt(dot(n, n));
  if (!(l > 0) || !std::isfinite(l)) throw std::invalid_argument("contact_energy: null or non-finite normal");
  return {n[0] / l, n[1] / l, n[2] / l};
}

// pdd2_global gradient -d sigma / d d at d = q - p, per tetrahedron (header, "Gradient").
void object_norm_gradient(const TetVertices& p, const TetVertices& q, Vec3d* g) {
  Vec3d sum{0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) sum[k] += q[i][k] - p[i][k];
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) g[i][k] = -((q[i][k] - p[i][k]) + sum[k]) / 10;
}

// One intersecting pair as the energy needs it: the positions attaining pdd2_global and the
// normal, from either engine (rounded to double for the exact one).
struct PairSolution {
  std::size_t a = 0, b = 0;
  double value = 0;
  TetVertices qA{}, qB{};
  Vec3d normal{};
};

template <class R>
double to_double(const R& x) {
  if constexpr (std::is_same_v<R, double>) return x;
  else return x.get_d();
}

template <class R>
PairSolution solution_of(std::size_t a, std::size_t b, const PairResult<R>& r) {
  PairSolution s;
  s.a = a;
  s.b = b;
  s.value = to_double(r.pdd2_global);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      s.qA[i][k] = to_double(r.q1_A_global[i][k]);
      s.qB[i][k] = to_double(r.q1_B_global[i][k]);
    }
  for (int k = 0; k < 3; ++k) s.normal[k] = to_double((*r.pdd2_global_normal)[k]);
  return s;
}

Mesh at_positions(const Mesh& m, const std::vector<Vec3d>& p, const char* which) {
  if (p.size() != m.vertices.size())
    throw std::invalid_argument(std::string("contact_energy: positions of mesh ") + which + " have " +
                                std::to_string(p.size()) + " entries, the mesh has " +
                                std::to_string(m.vertices.size()) + " vertices");
  Mesh out;
  out.vertices = p;
  out.tets = m.tets;
  out.source_ids = m.source_ids;
  out.vertex_sources = m.vertex_sources;  // messages name a non-finite vertex where it was read
  return out;
}

// The intersecting pairs at the current positions, each with its global minimiser.
std::vector<PairSolution> solutions(const Mesh& A, const Mesh* B, const ContactEnergyOptions& o,
                                    std::vector<SkippedElement>& skipped) {
  ContactOptions co;
  co.variants = kGlobal;
  co.cancel = o.cancel;
  std::vector<PairSolution> out;
  const Mesh& Bm = B ? *B : A;
  if (o.engine == EnergyEngine::Exact) {
    const Contacts<Rational> c = B ? contacts_exact(A, *B, co) : self_contacts_exact(A, co);
    skipped = c.skipped;
    for (const auto& k : c.pairs) out.push_back(solution_of(k.a, k.b, k.result));
    return out;
  }
  const Contacts<double> c = B ? contacts(A, *B, co) : self_contacts(A, co);
  skipped = c.skipped;
  out.resize(c.pairs.size());
  tbb::parallel_for(std::size_t(0), c.pairs.size(), [&](std::size_t j) {
    const auto& k = c.pairs[j];
    if (!k.result.pdd2_global_error && !k.result.error) {
      out[j] = solution_of(k.a, k.b, k.result);
      return;
    }
    // Declined by the fast engine (no certified normal in doubles): the exact engine's witness.
    reference::SolveOptions so;
    const auto r = reference::solve_pair(TetPair{"", {}, element(A, k.a), element(Bm, k.b)}, so);
    out[j] = solution_of(k.a, k.b, r);
  });
  return out;
}

// Symmetric 3x3 blocks (vi, vj) of the Hessian, summed over pairs, then expanded to CSR.
struct Block {
  std::size_t i, j;
  std::array<double, 9> v;
};

Eigen::SparseMatrix<double> assemble(std::vector<Block>& blocks, std::size_t n) {
  std::stable_sort(blocks.begin(), blocks.end(),  // stable: (i,j) and (j,i) summed in one order
            [](const Block& x, const Block& y) { return x.i != y.i ? x.i < y.i : x.j < y.j; });
  std::vector<Block> merged;
  merged.reserve(blocks.size());
  for (const Block& b : blocks) {
    if (!merged.empty() && merged.back().i == b.i && merged.back().j == b.j) {
      for (int k = 0; k < 9; ++k) merged.back().v[k] += b.v[k];
    } else {
      merged.push_back(b);
    }
  }
  // Row-major by vertex rows: CSR rows 3i+a hold, for each block (i, j) in j order, 3 entries.
  Eigen::SparseMatrix<double, Eigen::RowMajor> H(3 * n, 3 * n);
  std::vector<int> per_row(3 * n, 0);
  for (const Block& b : merged)
    for (int a = 0; a < 3; ++a) per_row[3 * b.i + a] += 3;
  H.reserve(per_row);
  for (const Block& b : merged)
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c)
        H.insert(static_cast<Eigen::Index>(3 * b.i + a), static_cast<Eigen::Index>(3 * b.j + c)) =
            b.v[3 * a + c];
  H.makeCompressed();
  return Eigen::SparseMatrix<double>(H);
}

ContactEnergy run(const Mesh& A, const Mesh* B, const std::vector<Vec3d>& pa,
                  const std::vector<Vec3d>* pb, const ContactEnergyOptions& o) {
  const auto t0 = Clock::now();
  const Mesh Ap = at_positions(A, pa, "A");
  std::optional<Mesh> Bp;
  if (B) Bp = at_positions(*B, *pb, "B");
  ContactEnergy e;
  std::vector<PairSolution> sol = solutions(Ap, B ? &*Bp : nullptr, o, e.skipped);
  e.seconds_contacts = seconds_since(t0);
  const auto t1 = Clock::now();

  const Mesh& Bm = B ? *B : A;
  const Mesh& Bpm = B ? *Bp : Ap;
  const std::size_t nA = A.vertices.size();
  const std::size_t n = nA + (B ? B->vertices.size() : 0);
  const std::size_t offset_b = B ? nA : 0;

  // Weights from the rest volumes; an element flat at rest has no weight: listed, its pairs
  // left out.
  std::vector<double> wa(A.tets.size(), -1), wb(Bm.tets.size(), -1);
  for (const auto& s : sol) {
    if (wa[s.a] < 0) wa[s.a] = rest_volume(A, s.a);
    if (wb[s.b] < 0) wb[s.b] = rest_volume(Bm, s.b);
  }
  auto weight = [&](const PairSolution& s) {
    return o.weight == EnergyWeight::Unit ? 1.0 : std::cbrt(wa[s.a] * wb[s.b]);
  };
  // No weight: flat at rest, or a rest volume that is not finite (a non-finite rest coordinate,
  // or one whose products overflow); -2 marks an element already listed.
  const auto unweighted = [](double w) { return w == 0 || w == -2 || !std::isfinite(w); };
  auto list_unweighted = [&](std::vector<double>& w, const Mesh& rest, std::size_t i, char which) {
    if (w[i] == -2 || !unweighted(w[i])) return;
    const std::string element_i = "element " + std::to_string(i) + " of mesh " + which;
    std::string why = element_i + " is flat at rest (volume 0): it has no contact weight";
    if (!std::isfinite(w[i])) {
      const auto problem = element_problem(rest, i, which);
      why = (problem ? *problem + " at rest" : element_i + ": its rest volume is not finite") +
            ": it has no contact weight";
    }
    w[i] = -2;
    e.skipped.push_back({which, i, why});
  };
  std::vector<PairSolution> kept;
  kept.reserve(sol.size());
  for (auto& s : sol) {
    const bool fa = unweighted(wa[s.a]), fb = unweighted(wb[s.b]);
    list_unweighted(wa, A, s.a, 'A');
    list_unweighted(wb, Bm, s.b, B ? 'B' : 'A');
    if (!fa && !fb) kept.push_back(s);
  }
  sol.swap(kept);

  std::vector<PairTerms> terms(sol.size());
  tbb::parallel_for(std::size_t(0), sol.size(), [&](std::size_t j) {
    if (o.cancel && o.cancel->load(std::memory_order_relaxed)) return;
    const auto& s = sol[j];
    terms[j] = pair_terms(element(Ap, s.a), element(Bpm, s.b), s.qA, s.qB, s.normal);
  });
  if (o.cancel && o.cancel->load()) throw Cancelled();

  e.gradient.assign(n, Vec3d{0, 0, 0});
  e.pair_count = sol.size();
  std::vector<Block> blocks;
  if (o.hessian) blocks.reserve(64 * sol.size());
  for (std::size_t j = 0; j < sol.size(); ++j) {
    const auto& s = sol[j];
    const double w = weight(s);
    e.energy += w * s.value;
    e.max_pdd2_global = std::max(e.max_pdd2_global, s.value);
    if (o.per_pair) e.pairs.push_back({s.a, s.b, w, s.value, w * s.value});
    std::array<std::size_t, 8> v{};
    for (int k = 0; k < 4; ++k) {
      v[k] = A.tets[s.a][k];
      v[4 + k] = offset_b + Bm.tets[s.b][k];
    }
    for (int k = 0; k < 8; ++k)
      for (int c = 0; c < 3; ++c) e.gradient[v[k]][c] += w * terms[j].gradient[k][c];
    if (!o.hessian) continue;
    const Vec3d& u = terms[j].unit_normal;
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 8; ++k) {
        const double q = w * terms[j].qs[i][k];
        if (q == 0) continue;
        Block b{v[i], v[k], {}};
        for (int x = 0; x < 3; ++x)
          for (int y = 0; y < 3; ++y) b.v[3 * x + y] = q * (u[x] * u[y]);  // u_x u_y = u_y u_x: blocks (i,k), (k,i) transposes bit for bit
        blocks.push_back(b);
      }
  }
  if (o.hessian) e.hessian = assemble(blocks, n);
  e.seconds_assembly = seconds_since(t1);
  return e;
}

}  // namespace

PairTerms pair_terms(const TetVertices& A, const TetVertices& B, const TetVertices& qA,
                     const TetVertices& qB, const Vec3d& normal) {
  PairTerms t;
  object_norm_gradient(A, qA, t.gradient.data());
  object_norm_gradient(B, qB, t.gradient.data() + 4);
  const Vec3d u = unit(normal);
  t.unit_normal = u;
  const std::array<double, 8> s = projections(A, B, u);
  const std::array<double, 8> q = projections(qA, qB, u);
  double cA = -std::numeric_limits<double>::infinity(), cB = std::numeric_limits<double>::infinity();
  double lo = s[0], hi = s[0];
  for (int i = 0; i < 8; ++i) {
    lo = std::min(lo, s[i]);
    hi = std::max(hi, s[i]);
    if (i < 4) cA = std::max(cA, q[i]);
    else cB = std::min(cB, q[i]);
  }
  const double c = (cA + cB) / 2;
  const double tol = kActiveTolerance * (hi - lo);
  bool any = false;
  for (int i = 0; i < 8; ++i) {
    t.active[i] = i < 4 ? q[i] >= c - tol : q[i] <= c + tol;
    any = any || t.active[i];
  }
  if (!any) return t;  // not reached for an intersecting pair (both sides touch the plane)
  const Eigen::Matrix<double, 8, 8> Qs = piece_matrix(t.active);
  Eigen::Matrix<double, 8, 1> sv;
  for (int i = 0; i < 8; ++i) sv[i] = s[i];
  t.piece_value = 0.5 * sv.dot(Qs * sv);
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 8; ++k) t.qs[i][k] = Qs(i, k);
  return t;
}

FixedPlane fixed_plane(const TetVertices& A, const TetVertices& B, const Vec3d& normal) {
  const Vec3d u = unit(normal);
  const std::array<double, 8> s = projections(A, B, u);
  FixedPlane best;
  double maxA = std::max({s[0], s[1], s[2], s[3]}), minB = std::min({s[4], s[5], s[6], s[7]});
  if (maxA <= minB) return best;  // t = 0 is feasible: value 0
  best.value = std::numeric_limits<double>::infinity();
  Eigen::Matrix<double, 8, 1> sv;
  for (int i = 0; i < 8; ++i) sv[i] = s[i];
  for (unsigned mask = 1; mask < 256; ++mask) {
    std::array<bool, 8> active{};
    for (int k = 0; k < 8; ++k) active[k] = (mask >> k) & 1u;
    // The equality QP's solution x = (t, c) for this set: solve the KKT system directly.
    int m = 0;
    for (bool a : active) m += a;
    const int n = 9 + m;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
    for (int blk = 0; blk < 2; ++blk)
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) K(4 * blk + i, 4 * blk + j) = (i == j ? 2.0 : 1.0) / 10;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    for (int k = 0, r = 0; k < 8; ++k) {
      if (!active[k]) continue;
      K(9 + r, k) = K(k, 9 + r) = 1;
      K(9 + r, 8) = K(8, 9 + r) = -1;
      rhs(9 + r) = -s[k];
      ++r;
    }
    const Eigen::VectorXd x = K.partialPivLu().solve(rhs);
    // Feasible: every constraint holds (to rounding relative to the pair's spread).
    const double spread = std::max(std::abs(maxA), std::abs(minB)) + (maxA - minB);
    bool feasible = true;
    for (int k = 0; k < 8 && feasible; ++k) {
      const double slack = k < 4 ? x[8] - (s[k] + x[k]) : (s[k] + x[k]) - x[8];
      feasible = slack >= -1e-12 * spread;
    }
    if (!feasible) continue;
    const double value = 0.5 * x.head(8).dot(K.topLeftCorner(8, 8) * x.head(8));
    if (value < best.value) {
      best.value = value;
      const Eigen::Matrix<double, 8, 8> Qs = piece_matrix(active);
      const Eigen::Matrix<double, 8, 1> g = Qs * sv;
      for (int k = 0; k < 8; ++k)
        for (int c = 0; c < 3; ++c) best.gradient[k][c] = g[k] * u[c];
    }
  }
  return best;
}

ContactEnergy contact_energy(const Mesh& A, const Mesh& B, const std::vector<Vec3d>& pa,
                             const std::vector<Vec3d>& pb, const ContactEnergyOptions& options) {
  return run(A, &B, pa, &pb, options);
}

ContactEnergy self_contact_energy(const Mesh& A, const std::vector<Vec3d>& pa,
                                  const ContactEnergyOptions& options) {
  return run(A, nullptr, pa, nullptr, options);
}

}  // namespace pdd::mesh
