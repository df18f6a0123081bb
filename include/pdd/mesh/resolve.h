// mesh/resolve.h — resolving interpenetration (definitions §11): new positions for the free
// vertices of A and B (or of one mesh with itself) after which no element pair intersects.
//
//   pdd::mesh::ResolveOptions o;  o.fix_a = true;          // defaults in the struct
//   pdd::mesh::Resolution r = pdd::mesh::resolve(A, B, o);
//   r.a, r.b (new positions), r.report.resolved, r.report.cost ...
//
// Inputs   meshes A and B (or A alone: self-contact), ResolveOptions.
// Outputs  Resolution: the new vertex positions and the ResolveReport (verdict, rounds, cost,
//          ratios, what remains).
//
// After resolve(), decided exactly on the doubles:
//   (R1) no element pair intersects (A x B; self-contact: pairs that share no vertex);
//   (R2) every element keeps the sign of its rest volume and a non-zero volume;
//   (R3) fixed vertices are bit-for-bit unchanged;
//   (R4) every element stays usable by a simulator: its volume ratio V1/V0 lies in
//        [rho, 1/rho] and its mean-ratio shape quality eta = 12 (3|V|)^(2/3) / (sum of its six
//        squared edge lengths) keeps eta1/eta0 >= kappa (QualityLimits below), decided exactly
//        by the polynomial forms V1 >= rho V0, V1 <= V0/rho and
//        |V1|^2 (sum l0^2)^3 >= kappa^3 |V0|^2 (sum l1^2)^3 (rho, kappa read as exact rationals).
// Cost: the mesh object norm, sigma_mesh = sum_e V_e sigma_e(P0, P1) / sum_e V_e (V_e the rest
// volume of element e, sigma_e the per-tetrahedron object norm), the volume-weighted mean
// squared displacement; a translation by t costs |t|^2. Reported per mesh and summed.
// The method, its stopping argument and how it keeps elements from inverting: mesh/src/resolve.h.
// The verdict alone on given positions: check_resolution.h.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "pdd/mesh/mesh.h"
#include "pdd/pdd.h"

namespace pdd::mesh {

// Which per-pair solution drives the vertices.
enum class ResolveVariant {
  Global,  // pdd2_global: PD_d over every separating plane (q1_*_global); the default (a pair
           // whose pdd2_global is declined, or shallower than 1e-12 of its extent: pdd2's)
  Pdd2,    // pdd2: PD_d over the candidate directions (q1_A, q1_B)
  Rigid,   // baseline: each pair pushed apart by its rigid translation (rigid_pd2's direction),
           // split between the two elements as PD_d would split it
};
// "global" | "pdd2" | "rigid" <-> ResolveVariant; parse throws std::invalid_argument naming
// the word.
ResolveVariant parse_resolve_variant(const std::string& name);
const char* resolve_variant_name(ResolveVariant v);

struct ResolveRound {
  std::size_t round = 0;       // 1, 2, ...
  std::size_t pairs = 0;       // intersecting pairs found at the start of the round
  double max_pd2 = 0;          // largest per-pair value of the variant (squared length)
  double cost = 0;             // sigma_mesh of A plus B after the round
  double seconds = 0;          // wall time of the round
};

// R4's bounds (definitions §11): rho = min_volume_ratio, kappa = min_shape_ratio, each in (0, 1].
struct QualityLimits {
  double min_volume_ratio = 0.25;  // rho: every element keeps V1/V0 in [rho, 1/rho]
  double min_shape_ratio = 0.5;    // kappa: every element keeps eta1/eta0 >= kappa
};

// How the result was produced (ResolveReport::method).
enum class ResolveMethod {
  Rounds,       // the rounds alone cleared every contact
  Translation,  // the deep-overlap fallback: the cheapest separating translation of a body
                // pair over a few directions (centroids' line, mean pdd2 normal, principal
                // axes of the contact region), then walked back towards the rest pose
  Bodies,       // self-contact of several bodies: each contacting pair of bodies resolved as
                // two meshes (any of the above per pair); larger groups of contacting bodies
                // spread apart from their cluster's centre by the smallest separating factor,
                // then walked back towards the rest pose
  Pdd2Rounds,   // self-contact fallback: the rounds again from the rest pose with pdd2's
                // per-pair planes (under the global variant)
  RigidRounds,  // rounds of the rigid variant from the rest pose: self-contact's last fallback,
                // and two meshes' (global or pdd2 variant) before the translation
  None,         // nothing cleared the contacts (the report says what remains)
};
// "rounds" | "translation" | "bodies" | "pdd2 rounds" | "rigid rounds" | "none"
const char* resolve_method_name(ResolveMethod m);

struct ResolveOptions : QualityLimits {
  ResolveVariant variant = ResolveVariant::Global;
  // Whole meshes kept bit for bit (the paper's case 1 at mesh level). fix_b is ignored for
  // self-contact. At most one of the two may be set (both: std::invalid_argument).
  bool fix_a = false, fix_b = false;
  // Boundary conditions: per-vertex flags (1 = fixed), empty or of the mesh's vertex count.
  std::vector<char> fixed_vertices_a, fixed_vertices_b;
  std::size_t max_rounds = 200;  // rounds of contact solving before giving up (>= 1)
  // Called after every round (thread-safe need not be: called from the calling thread).
  std::function<void(const ResolveRound&)> progress;
  // As ContactOptions::cancel: checked between rounds and stages; throws Cancelled.
  const std::atomic<bool>* cancel = nullptr;
};

struct ResolveReport {
  ResolveVariant variant = ResolveVariant::Global;
  ResolveMethod method = ResolveMethod::None;
  // Why the run stopped before its round limit without resolving (empty otherwise): every
  // vertex fixed, or no intersecting pair with a finite per-pair solution (coordinates beyond
  // what doubles can square).
  std::string stopped_because;
  QualityLimits limits;        // the R4 bounds the verdict used
  bool resolved = false;       // r1 && r2 && r3 && r4, decided exactly on the final positions
  bool r1 = false, r2 = false, r3 = false, r4 = false;
  std::vector<ResolveRound> rounds;
  double cost = 0, cost_a = 0, cost_b = 0;  // sigma_mesh (sum, A, B)
  double max_displacement = 0;               // largest |p1 - p0| over all vertices
  double min_volume_ratio = 0;               // smallest V1 / V0 over all elements (signed)
  double max_volume_ratio = 0;               // largest V1 / V0 over all elements
  double min_shape_ratio = 0;                // smallest eta1 / eta0 over all elements
  // Per element of A and of B (doubles, for display; the verdict is exact): V1 / V0 (signed)
  // and eta1 / eta0; NaN for an element skipped at rest or non-finite at P1.
  std::vector<double> volume_ratio_a, volume_ratio_b, shape_ratio_a, shape_ratio_b;
  // What remains when not resolved: intersecting element pairs (a, b) of the final positions
  // (complete, from a fresh broadphase and the exact decision), elements flattened or
  // inverted ('A'/'B', index), fixed vertices that moved ('A'/'B', index).
  std::vector<std::array<std::size_t, 2>> remaining_pairs;
  std::vector<std::pair<char, std::size_t>> bad_elements;
  // Elements that fall short of R4 ('A'/'B', index; inverted and flat ones included), in order.
  std::vector<std::pair<char, std::size_t>> poor_elements;
  std::vector<std::pair<char, std::size_t>> moved_fixed_vertices;
  std::vector<SkippedElement> skipped;  // elements of the input that cannot be computed
  // Wall time per stage over the whole run (seconds).
  double seconds_contacts = 0, seconds_solve = 0, seconds_move = 0, seconds_verify = 0,
         seconds_total = 0;
};

struct Resolution {
  std::vector<Vec3d> a, b;  // new vertex positions of A and B (b empty for self-contact)
  ResolveReport report;
};

// Throws std::invalid_argument for inconsistent options (limits outside (0, 1] included) or a
// tetrahedron referring to a vertex that does not exist; Cancelled when cancelled. A run that
// does not reach R1-R4 in max_rounds
// returns normally with report.resolved == false.
Resolution resolve(const Mesh& A, const Mesh& B, const ResolveOptions& options = {});
Resolution resolve_self(const Mesh& A, const ResolveOptions& options = {});

// The mesh object norm sigma_mesh(P0, P1) of one mesh (see above), at any scale of the
// coordinates: +inf above the double range, NaN where it is positive but below the normal range.
double mesh_cost(const Mesh& m, const std::vector<Vec3d>& p1);

}  // namespace pdd::mesh
