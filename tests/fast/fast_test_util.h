// fast_test_util.h — shared helpers of the fast-engine tests: random pairs (paper Sec. VI
// protocol, fixed seeds), the object norm of definitions §2, plain constructors.
#pragma once

#include <cmath>
#include <vector>

#include "kernel/candidate_directions.h"
#include "pdd/compare/random.h"
#include "pdd/tet_pair.h"

namespace pdd::fast::test {

inline TetPair tet_pair(const TetVertices& A, const TetVertices& B, const char* name = "t") {
  TetPair p;
  p.name = name;
  p.A = A;
  p.B = B;
  return p;
}

// Random pairs with vertices uniform in [0, side]^3; `intersecting_only` keeps those with
// intersecting interiors (decided by the engine's exact test).
inline std::vector<TetPair> random_pairs(int count, unsigned seed, bool intersecting_only,
                                         double side = 10.0) {
  pdd::compare::ReproducibleRng rng(seed);  // the same pairs with every standard library
  std::vector<TetPair> out;
  CandidateSet set;
  while (int(out.size()) < count) {
    TetPair p;
    p.name = "random-" + std::to_string(out.size());
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        p.A[i][k] = rng.uniform(0.0, side);
        p.B[i][k] = rng.uniform(0.0, side);
      }
    if (build_candidates(p.A, p.B, set) != BuildStatus::Ok) continue;
    if (intersecting_only && !set.intersecting) continue;
    out.push_back(p);
  }
  return out;
}

// definitions §2: sigma = 1/20 (sum |d_i|² + |sum d_i|²), d_i = q1_i − q0_i.
template <class P>
double sigma(const TetVertices& q0, const P& q1) {
  double sq = 0.0, s[3] = {0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      const double d = q1[i][k] - q0[i][k];
      sq += d * d;
      s[k] += d;
    }
  return (sq + s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / 20.0;
}

inline bool close_rel(double a, double b, double rel, double abs = 0.0) {
  return std::fabs(a - b) <= rel * std::fmax(std::fabs(a), std::fabs(b)) + abs;
}

}  // namespace pdd::fast::test
