// mesh/contacts.h — every intersecting element pair of two tetrahedral meshes (or of one mesh
// with itself) and its penetration depths (definitions §10).
//
//   #include <pdd/mesh.h>             // CMake: target_link_libraries(app PRIVATE pdd::mesh)
//   pdd::mesh::Mesh A = pdd::mesh::read_mesh("a.msh"), B = pdd::mesh::read_mesh("b.vtk");
//   pdd::mesh::Contacts<double> c = pdd::mesh::contacts(A, B);     // default variants
//   for (const auto& k : c.pairs) k.a, k.b, k.result.pdd2, k.result.q1_B ...;
//   c.skipped: flat or non-finite elements, by mesh and index, with the reason
//
// Inputs   meshes A and B (or A alone: self-contact), ContactOptions (defaults in the struct).
// Outputs  Contacts: the intersecting pairs (a, b) sorted by (a, b), each with its PairResult,
//          the skipped elements, and the time per stage.
//
// Stages of contacts():
//   1. boxes        the axis-aligned bounding box of every valid element (an element with a
//                   non-finite coordinate or zero volume — exact test — is skipped and listed);
//   2. broadphase   every pair (a, b) whose boxes overlap: CGAL's box_intersection_d, half-open
//                   boxes (interiors that intersect have overlapping half-open boxes, so no pair
//                   whose interiors intersect is lost; boxes that only touch are not reported),
//                   after dropping the boxes that miss the other mesh's bounding box; CGAL's
//                   parallel version (TBB) for two meshes, the sequential one for self-contact
//                   (faster there);
//   3. decision     the exact decision of definitions §4 per box pair, on all cores:
//                   pdd::fast::interiors_intersect (a certified separating-axis filter in
//                   doubles, then rigid_pd2's exact decision for the pairs it cannot decide:
//                   touching or nearly touching, parallel edges); touching is not intersecting;
//   4. depth        the requested variants per intersecting pair, on all cores (TBB), through the
//                   public engine calls of <pdd/pdd.h> only.
// Stage 4 computes once the pairs that are equal up to an exact translation (pdd.h,
// "Translation": a structured mesh of dyadic or integer coordinates against a shifted copy has
// few kinds of pairs) and moves the record to each, the same bits as computing each; on meshes
// where fewer than a quarter of the first 4096 pairs repeat this stops by itself.
// Results are sorted by (a, b), independent of the number of threads.
//
// Self-contact (contacts_self, contacts_exact_self): pairs a < b of one mesh whose elements share no vertex index.
//
// Values: a record is pdd.h's PairResult with `name` empty; only the requested variants are
// computed, the others are 0 with no label; q1_A / q1_B (the deformed positions attaining pdd2)
// are set when kPdd2 is requested and are the rest pose otherwise. With the fast engine each
// value equals the field of the same name of pdd::fast::solve_pair on the pair
// (A = element a, B = element b), bit for bit, whichever variants are asked (those without
// pdd2, eq11, global, relaxed and accel6 come from pdd.h's hot functions, which name the
// record's side of every near tie);
// contacts_exact gives pdd::reference::solve_pair's exact record
// (every value; definitions §9's search only with kGlobal).
//
// kGlobal (definitions §9, "global"; not a default): pdd2_global, PD_d² over every separating plane
// (the paper's eq. 5 as defined: the minimum over unit normals of the relaxed QP, so
// pdd2_global <= pdd2_relaxed), with pdd2_global_normal (the normal attaining it, A -> B, not
// necessarily of unit length) and q1_A_global / q1_B_global (the deformed positions attaining
// it, every vertex moved along that normal). Fast engine: the fields of one
// pdd::fast::solve_pair (bit for bit), not the hot path pdd::fast::pdd2_global, which gives no
// positions and, starting without the relaxed candidate's normal, is slower on mesh pairs. The
// search is most of solve_pair's time, and solve_pair runs it only when asked (its `global`
// argument, set from kGlobal): kGlobal costs the search even with kPdd2 or kEq11, which take one
// solve_pair anyway. Reference engine: the exact witness value, normal and positions and
// pdd2_global_lower, the proved lower bound (pdd2_global − pdd2_global_lower <= 1e-12 ·
// pdd2_global); the search runs only with kGlobal. Without kGlobal these fields are 0, no
// normal, the rest pose and (reference) no lower bound.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <vector>

#include "pdd/mesh/mesh.h"
#include "pdd/mesh/variants.h"
#include "pdd/pdd.h"

namespace pdd::mesh {

template <class R>
struct Contact {
  std::size_t a = 0, b = 0;  // element of A (of the mesh, for self-contact), element of B
  PairResult<R> result;      // error set only when a value is not representable (fast engine)
};

struct ContactOptions {
  unsigned variants = kDefaultVariants;
  // Stage 4 progress: progress(n, total) says n more of the `total` intersecting pairs are
  // done; called once with n = 0 when stage 4 starts (`total` known), then from worker threads
  // (must be thread-safe). May be empty.
  std::function<void(std::size_t n, std::size_t total)> progress;
  // Cancellation, for interactive callers: when not null and *cancel becomes true (from any
  // thread), the call starts no more work and throws Cancelled. Checked between stages, per
  // block of box pairs in stage 3 and before each pair in stage 4; stage 2 (CGAL's
  // broadphase) and the pairs already being computed run to their end.
  const std::atomic<bool>* cancel = nullptr;
  // Stage 4's pairs as they are computed, for callers that stream them: pair(h, c) says that
  // `c` is pairs[h] of the result (h in its sorted (a, b) order, 0 <= h < the `total` given to
  // `progress`); called from worker threads (must be thread-safe), in any order. The fast
  // engine calls fast_pair, the reference one exact_pair. May be empty.
  std::function<void(std::size_t h, const Contact<double>& c)> fast_pair;
  std::function<void(std::size_t h, const Contact<Rational>& c)> exact_pair;
};

template <class R>
struct Contacts {
  std::vector<Contact<R>> pairs;  // intersecting pairs, sorted by (a, b)
  std::vector<SkippedElement> skipped;
  std::size_t elements_a = 0, elements_b = 0;  // tetrahedra in each mesh (B: 0 for self-contact)
  std::size_t box_pairs = 0;  // stage 2's pairs (self-contact: after dropping vertex-sharing ones)
  double seconds_boxes = 0, seconds_broadphase = 0, seconds_decision = 0, seconds_depth = 0;
};

// Throws std::invalid_argument when a tetrahedron refers to a vertex that does not exist.
Contacts<double> contacts(const Mesh& A, const Mesh& B, const ContactOptions& options = {});
Contacts<double> contacts_self(const Mesh& A, const ContactOptions& options = {});
// The same pairs (stages 1–3 as above), each pair's record from the exact engine
// (pdd::reference::solve_pair, reduced formulation; every value of the record is computed).
Contacts<Rational> contacts_exact(const Mesh& A, const Mesh& B,
                                  const ContactOptions& options = {});
Contacts<Rational> contacts_exact_self(const Mesh& A, const ContactOptions& options = {});

}  // namespace pdd::mesh
