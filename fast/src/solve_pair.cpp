// solve_pair.cpp — SPEC §6 record of one pair, and the parallel batch. See the header.
#include "pdd/fast/solve_pair.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <memory>
#include <string>

#include "pdd/fast/candidate_directions.h"
#include "pdd/fast/deformable_depth.h"
#include "pdd/fast/rigid_depth.h"

namespace pdd::fast {
namespace {

std::string non_finite_message(const char* which, const TetVertices& T) {
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(T[i][k]))
        return std::string("tetrahedron ") + which + ": vertex " + std::to_string(i) +
               " has a non-finite coordinate";
  return std::string("tetrahedron ") + which + ": non-finite coordinate";
}

std::string degenerate_message(const char* which) {
  return std::string("tetrahedron ") + which +
         ": zero volume (its four vertices are coplanar, decided exactly)";
}

std::optional<std::string> status_message(BuildStatus st, const TetPair& p) {
  switch (st) {
    case BuildStatus::Ok: return std::nullopt;
    case BuildStatus::NonFiniteA: return non_finite_message("A", p.A);
    case BuildStatus::NonFiniteB: return non_finite_message("B", p.B);
    case BuildStatus::DegenerateA: return degenerate_message("A");
    case BuildStatus::DegenerateB: return degenerate_message("B");
  }
  return std::string("invalid input");
}

std::optional<DirectionLabel> label_of(const CandidateSet& s, int index) {
  if (index < 0) return std::nullopt;
  return label(s, index);
}

void fill_intersecting(const TetPair& pair, const CandidateSet& set, PairResult<double>& r) {
  const Choice rigid = rigid_pd2(set);
  r.rigid_pd2 = rigid.value;
  r.rigid_dir = label_of(set, rigid.index);
  r.eq11_pd2 = eq11_pd2(set);
  const Choice st = pdd2_static(set, rigid.index);
  r.pdd2_static = st.value;
  r.pdd2_static_dir = label_of(set, st.index);
  const Choice accel6 = pdd2_accel(set, 6);
  r.pdd2_accel6 = accel6.value;
  r.pdd2_accel1 = pdd2_accel(set, 1).value;
  const Choice def = pdd2(set, accel6.index);
  r.pdd2 = def.value;
  r.pdd2_dir = label_of(set, def.index);
  const Choice rel = pdd2_relaxed(set, def.index);
  r.pdd2_relaxed = rel.value;
  r.pdd2_relaxed_dir = label_of(set, rel.index);
  deformed_positions(pair.A, pair.B, candidate(set, def.index), r.q1_A, r.q1_B);
}

}  // namespace

PairResult<double> solve_pair(const TetPair& pair) {
  PairResult<double> r;
  r.name = pair.name;
  // ~20 KB: on the heap to keep TBB worker stacks small; default-initialised (no zeroing).
  std::unique_ptr<CandidateSet> set(new CandidateSet);
  r.error = status_message(build_candidates(pair.A, pair.B, *set), pair);
  if (r.error) return r;
  r.q1_A = pair.A;
  r.q1_B = pair.B;
  r.intersecting = set->intersecting;
  if (r.intersecting) fill_intersecting(pair, *set, r);
  return r;
}

std::vector<PairResult<double>> solve_batch(const std::vector<TetPair>& pairs) {
  std::vector<PairResult<double>> out(pairs.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pairs.size()),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t i = range.begin(); i != range.end(); ++i)
                        out[i] = solve_pair(pairs[i]);
                    });
  return out;
}

}  // namespace pdd::fast
