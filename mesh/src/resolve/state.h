// state.h — the state of one resolve run: each mesh's current positions and its rest data
// (Side), and the run itself (Run: the meshes, the options, the report, cancellation).
//
// Inputs:  the rest meshes A (and B; none for self-contact), the options.
// Outputs: nothing by itself; the phases (contacts, local step, global step, step limit,
//          fallbacks; resolve.h) read and move Side::cur and append to Run::rep.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "../elastic_step.h"
#include "contact_list.h"
#include "pdd/mesh.h"
#include "pdd/sign.h"

namespace pdd::mesh::detail {

// One mesh's state during the rounds.
struct Side {
  const Mesh* rest = nullptr;
  char which = 'A';
  Mesh cur;
  std::vector<char> fixed;          // per vertex, as ResolveOptions' flags: 1 fixed (R3), 0 free
  std::vector<std::size_t> elems;   // valid at rest
  QualityLimits limits;             // R4's bounds, kept by the step limit
  std::vector<Sign> sign;           // rest orientation per element (Zero: not valid)
  std::vector<double> d0, s0;       // per element: rest 6V (signed) and sum of squared edge lengths,
                                    // of the element scaled by factor[e] (edge_scale)
  std::vector<double> factor;
  std::vector<double> volume;       // |rest volume| per element, of the side scaled by a power of two
  std::vector<Vec3d> acc;           // per vertex: the step proposed this round (step_limit.h)
  std::vector<double> weight;       // per vertex: sum of the weights in acc (0: no step)
  ElasticStep::Anchor anchor = ElasticStep::Anchor::Pulled;  // the global step's anchors
  // The valid elements of each vertex (CSR: vertex_elems[vertex_start[v] .. vertex_start[v+1])).
  std::vector<std::size_t> vertex_start, vertex_elems;

  bool is_fixed(std::size_t v) const { return fixed[v] != 0; }
  bool any_fixed() const;
  bool all_fixed() const;
};

// Throws std::invalid_argument when flags are neither empty nor one per vertex of m.
void check_fixed_flags(const std::vector<char>& flags, const Mesh& m, char which);

// The side of mesh m at rest: fix_all fixes every vertex, else flags (possibly empty) do.
void init_side(Side& s, const Mesh& m, char which, bool fix_all, const std::vector<char>& flags,
               std::vector<SkippedElement>& skipped);

// sigma_mesh of the side's current positions against its rest mesh.
double side_cost(const Side& s);

// One run of resolve / resolve_self (B == nullptr: self-contact).
struct Run {
  Run(const Mesh& a, const Mesh* b, const ResolveOptions& options, ResolveReport& report)
      : A(a), B(b), o(options), rep(report) {}
  const Mesh& A;
  const Mesh* B;
  const ResolveOptions& o;
  ResolveReport& rep;
  Side sa, sb;
  ResolveVariant pd_variant = o.variant;  // the per-pair solution of the projective-dynamics rounds
  std::optional<ElasticStep> elastic_a, elastic_b;  // the global step, assembled on first use
  ContactList contact_list;                         // the contact stage's candidates (rounds.h)
  // The directions of last round's replaced patches (patch_direction.h) and, per vertex of A
  // and of B, the one it was pushed along (an index into them; -1: none). Cleared where the
  // rounds start again.
  struct PatchMemory {
    std::vector<Vec3d> along;
    std::vector<int> of_a, of_b;
    void clear() { along.clear(), of_a.clear(), of_b.clear(); }
  } patch_memory;
  // The largest overlap of a pair along its plane's normal that the rounds have met (never
  // lowered): the plane gap's cap (local_step.h), so that a contact far shallower than the
  // elements is not pushed apart by more than its own depth.
  double depth_scale = 0;

  Side& second() { return B ? sb : sa; }  // the side of a pair's second element
  double cost() const { return side_cost(sa) + (B ? side_cost(sb) : 0); }
  bool cancelled() const { return o.cancel && o.cancel->load(std::memory_order_relaxed); }
  void stop_if_cancelled() const {
    if (cancelled()) throw Cancelled();
  }
  // Both sides back to given positions (b ignored for self-contact).
  void place(const std::vector<Vec3d>& a, const std::vector<Vec3d>& b) {
    patch_memory.clear();
    sa.cur.vertices = a;
    if (B) sb.cur.vertices = b;
  }
  // Appends a round to the report and tells the caller's progress callback.
  void record(const ResolveRound& r) {
    rep.rounds.push_back(r);
    if (o.progress) o.progress(r);
  }
};

}  // namespace pdd::mesh::detail
