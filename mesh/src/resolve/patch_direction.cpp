// patch_direction.cpp — one separating direction per disagreeing contact patch (patch_direction.h).
#include "patch_direction.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "geometry.h"

namespace pdd::mesh::detail {
namespace {

// Below this agreement the pairs' planes are replaced. Measured: blocks of 3^3 cubes stacked a
// third of a cell deep (Kuhn, mirrored Kuhn, five and 24 tetrahedra a cube; five offsets; A
// fixed or both free) agree to 0.02-0.32 in their first round, their pairs' planes pointing
// sideways, opposite ways; the shipped balls 0.73 deep (about 2.4 layers) likewise. The Gmsh
// cases of scripts/make-resolve-cases.sh --small: plate-ball and deep run bit for bit as
// without the rule; ball-box, whose patch falls below it in a few rounds, ends at cost
// 1.9e-4 for 1.6e-4, min V1/V0 0.65 for 0.50, 28 rounds for 29.
constexpr double kAgree = 0.5;
// The deepest pairs' normals tried (each costs one pass over the patch's pairs).
constexpr std::size_t kCandidates = 32;

// Union-find over the pairs (path halving).
struct Patches {
  std::vector<std::size_t> parent;
  explicit Patches(std::size_t n) : parent(n) {
    for (std::size_t k = 0; k < n; ++k) parent[k] = k;
  }
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(std::size_t x, std::size_t y) { parent[find(x)] = find(y); }
};

// Pairs joined through a shared vertex of A or of B; each patch's pairs, listed at its root.
std::vector<std::vector<std::size_t>> patches(const Run& run, const std::vector<std::array<std::size_t, 2>>& pairs) {
  Patches p(pairs.size());
  std::unordered_map<std::size_t, std::size_t> seen_a, seen_b;  // vertex -> a pair holding it
  for (std::size_t k = 0; k < pairs.size(); ++k)
    for (int i = 0; i < 4; ++i) {
      if (const auto [it, fresh] = seen_a.emplace(run.sa.rest->tets[pairs[k][0]][i], k); !fresh) p.join(k, it->second);
      if (const auto [it, fresh] = seen_b.emplace(run.sb.rest->tets[pairs[k][1]][i], k); !fresh) p.join(k, it->second);
    }
  std::vector<std::vector<std::size_t>> members(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) members[p.find(k)].push_back(k);
  return members;
}

// |sum w_k u_k| >= kAgree sum w_k over the patch's solved pairs (w_k = sqrt(v_k)).
bool agrees(const std::vector<std::size_t>& patch, const std::vector<PairMove>& moves) {
  Vec3d sum = {0, 0, 0};
  double weight = 0;
  for (std::size_t k : patch)
    if (moves[k].ok && moves[k].value > 0) {
      const double w = std::sqrt(moves[k].value);
      add_to(sum, scaled(moves[k].u, w));
      weight += w;
    }
  return !(weight > 0) || std::sqrt(dot(sum, sum)) >= kAgree * weight;
}

// The normals of the patch's deepest pairs, then both signs of its vertices' principal axes.
std::vector<Vec3d> candidates(const Run& run, const std::vector<std::array<std::size_t, 2>>& pairs,
                              std::vector<std::size_t> patch, const std::vector<PairMove>& moves) {
  std::vector<Vec3d> out;
  std::stable_sort(patch.begin(), patch.end(), [&](std::size_t x, std::size_t y) { return moves[x].value > moves[y].value; });
  for (std::size_t k : patch)
    if (moves[k].ok && out.size() < kCandidates) out.push_back(moves[k].u);
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  double n = 0;
  for (std::size_t k : patch)
    for (const TetVertices& t : {element(run.sa.cur, pairs[k][0]), element(run.sb.cur, pairs[k][1])})
      for (const Vec3d& v : t) {
        const Eigen::Vector3d x(v[0], v[1], v[2]);
        c += x, second += x * x.transpose(), n += 1;
      }
  c /= n;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(second / n - c * c.transpose());
  if (eig.info() != Eigen::Success) return out;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d e = eig.eigenvectors().col(a);
    if (const auto u = unit(Vec3d{e[0], e[1], e[2]})) out.push_back(*u), out.push_back(scaled(*u, -1));
  }
  return out;
}

// sum_k c_k(u)^2 over the patch.
double squared_clearances(const Run& run, const std::vector<std::array<std::size_t, 2>>& pairs,
                          const std::vector<std::size_t>& patch, const Vec3d& u) {
  double total = 0;
  for (std::size_t k : patch) {
    const double d = std::max(0.0, clearance(u, element(run.sa.cur, pairs[k][0]), element(run.sb.cur, pairs[k][1])));
    total += d * d;
  }
  return total;
}

// The direction most of the patch's vertices were pushed along last round (an index into
// memory.along), or -1.
int last_direction(const Run& run, const Run::PatchMemory& memory, const std::vector<std::array<std::size_t, 2>>& pairs,
                   const std::vector<std::size_t>& patch) {
  if (memory.along.empty()) return -1;
  std::vector<std::size_t> votes(memory.along.size(), 0);
  for (std::size_t k : patch)
    for (int i = 0; i < 4; ++i) {
      if (const int d = memory.of_a[run.sa.rest->tets[pairs[k][0]][i]]; d >= 0) ++votes[std::size_t(d)];
      if (const int d = memory.of_b[run.sb.rest->tets[pairs[k][1]][i]]; d >= 0) ++votes[std::size_t(d)];
    }
  const auto most = std::max_element(votes.begin(), votes.end());
  return *most > 0 ? int(most - votes.begin()) : -1;
}

// A patch's direction turns by at most 45 degrees from one round to the next (the cosine):
// within 90 degrees, blocks of 10^3 Kuhn cubes half a cell apart in x and y still turned their
// push around in two rounds, (-0.71, 0.71, 0) -> (-0.78, 0.14, 0.62) -> (0.20, -0.80, 0.57),
// and ended in the translation; within 60 degrees that case too; within 45 degrees they resolve
// by the rounds (34 rounds), and every `pdd bench resolve` case keeps its rounds and cost.
constexpr double kTurn = 0.70710678118654752;

// The patch's direction: the candidate of least squared clearances; where the patch was pushed
// along `last` in the previous round, of the candidates within 45 degrees of it (kTurn), or
// `last` itself where none is.
std::optional<Vec3d> direction(const Run& run, const std::vector<std::array<std::size_t, 2>>& pairs,
                               const std::vector<std::size_t>& patch, const std::vector<PairMove>& moves,
                               const Vec3d* last) {
  std::optional<Vec3d> best;
  double least = HUGE_VAL;
  for (const Vec3d& u : candidates(run, pairs, patch, moves))
    if (!last || dot(u, *last) >= kTurn)
      if (const double s = squared_clearances(run, pairs, patch, u); s < least) least = s, best = u;
  if (!best && last) best = *last;  // (no candidate within the cone: the way it went)
  return best;
}

}  // namespace

std::vector<std::optional<Vec3d>> patch_directions(Run& run, const std::vector<std::array<std::size_t, 2>>& pairs,
                                                   const std::vector<PairMove>& moves) {
  std::vector<std::optional<Vec3d>> along(pairs.size());
  if (!run.B) return along;
  const Run::PatchMemory last = std::move(run.patch_memory);
  Run::PatchMemory& now = run.patch_memory;
  now.clear();
  now.of_a.assign(run.sa.cur.vertices.size(), -1), now.of_b.assign(run.sb.cur.vertices.size(), -1);
  for (const std::vector<std::size_t>& patch : patches(run, pairs)) {
    if (patch.empty() || agrees(patch, moves)) continue;
    const int d = last_direction(run, last, pairs, patch);
    const std::optional<Vec3d> u = direction(run, pairs, patch, moves, d >= 0 ? &last.along[std::size_t(d)] : nullptr);
    if (!u) continue;
    const int index = int(now.along.size());
    now.along.push_back(*u);
    for (std::size_t k : patch) {
      along[k] = u;
      for (int i = 0; i < 4; ++i)
        now.of_a[run.sa.rest->tets[pairs[k][0]][i]] = now.of_b[run.sb.rest->tets[pairs[k][1]][i]] = index;
    }
  }
  return along;
}

}  // namespace pdd::mesh::detail
