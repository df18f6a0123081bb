// edge_audit.h — the degenerate and ambiguous edge-edge cases of paper Sec. IV-A, audited
// exactly on one pair (`pdd audit-ee`).
//
// For a valid intersecting pair, with every QP solved exactly (reduced formulation):
//   parallel / colinear / undecidable   the edge pairs of each kind, as (edge of A, edge of B);
//   orientation rule   for every decided EE direction n, the discarded orientation -n (same
//                      constrained/free sets) is solved too, in every case: how often its
//                      optimum is smaller than the kept one, and whether it would lower the
//                      pair's result (static, deformable, relaxed);
//   colinear pairs     skipped by definitions §3; the paper calls them redundant and suggests the
//                      normals of the faces incident to the two edges. Those directions, with
//                      the edge pair's constrained sets and the EE orientation rule, are
//                      solved: does any lower the pair's result?
//   optimum source     whether the result's direction is a parallel or undecidable EE.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "pdd/tet_pair.h"

namespace pdd::compare {

struct CaseFlags {
  bool static_case = false, deformable = false, relaxed = false;
  bool any() const { return static_case || deformable || relaxed; }
};

struct EdgeAudit {
  std::string name;
  std::optional<std::string> error;
  bool intersecting = false;
  std::vector<std::array<int, 2>> parallel, colinear, undecidable;

  int decided_checked = 0;                 // decided EE directions whose -n was solved
  int discarded_smaller_deformable = 0;    // ... where -n had the smaller case-2 optimum
  int discarded_smaller_relaxed = 0;
  int discarded_feasible_static = 0;       // ... where -n was feasible in case 1 at all
  CaseFlags discarded_changes_result;      // min over {-n} below the pair's result

  int colinear_directions = 0;             // face-normal directions tried for colinear pairs
  CaseFlags colinear_changes_result;

  CaseFlags optimum_parallel, optimum_undecidable;  // the result's direction is of that kind
};

EdgeAudit edge_audit(const TetPair& pair);

}  // namespace pdd::compare
