// mesh.h — pdd on tetrahedral meshes (definitions §10): every intersecting element pair of two
// meshes (or of one mesh with itself) and its penetration depths.
//
//   #include <pdd/mesh.h>             // CMake: target_link_libraries(app PRIVATE pdd::mesh)
//   pdd::mesh::Mesh A = pdd::mesh::read_mesh("a.msh"), B = pdd::mesh::read_mesh("b.vtk");
//   pdd::mesh::Contacts<double> c = pdd::mesh::contacts(A, B);     // default variants
//   for (const auto& k : c.pairs) k.a, k.b, k.result.pdd2, k.result.q1_B ...;
//   c.skipped: flat or non-finite elements, by mesh and index, with the reason
//
// Meshes: vertices (doubles) and tetrahedra (four vertex indices each, any orientation).
// Tetrahedra are numbered 0, 1, ... in file order among the file's tetrahedral elements; other
// element types (points, lines, triangles, hexahedra, ...) are ignored.
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
// Results are sorted by (a, b), independent of the number of threads.
//
// Self-contact (self_contacts): pairs a < b of one mesh whose elements share no vertex index.
//
// Values: a record is pdd.h's PairResult with `name` empty; only the requested variants are
// computed, the others are 0 with no label; q1_A / q1_B (the deformed positions attaining pdd2)
// are set when kPdd2 is requested and are the rest pose otherwise. With the fast engine each
// value equals the field of the same name of pdd::fast::solve_pair on the pair
// (A = element a, B = element b); contacts_exact gives pdd::reference::solve_pair's exact record
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

#include <array>
#include <atomic>
#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pdd/pdd.h"

namespace pdd::mesh {

struct Mesh {
  std::vector<Vec3d> vertices;
  std::vector<std::array<std::size_t, 4>> tets;  // vertex indices into `vertices`
  // Where each tetrahedron came from, for messages: the element tag of a Gmsh file, the cell
  // index of a VTK file (same length as `tets`; may be empty for meshes built in code).
  std::vector<long long> source_ids;
  // Where each vertex with a non-finite coordinate came from, by vertex index, for the message
  // that skips its elements (element_problem): "node 5 at a.msh:12" (a Gmsh file's own node
  // tag and line), "point 4 at b.vtk:30" (a VTK file's point number), "VA[4]" (Python's array
  // and row). Empty for meshes built in code (the message then names the vertex index alone).
  std::map<std::size_t, std::string> vertex_sources;
};

// A mesh file that cannot be read: missing, truncated, malformed, an element referring to a
// node that is not in the file, an unknown element type. what() names the file and the line
// (text) or the byte offset (binary data): "a.msh:42: element 17 refers to node 999, which
// is not in the file".
struct ReadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads a Gmsh .msh file (versions 2.2 and 4.1, ASCII and binary) or a legacy VTK unstructured
// grid (.vtk, ASCII or BINARY, cell type 10), chosen by content ("$MeshFormat" or
// "# vtk DataFile"). Coordinates are read as written (non-finite ones too: the element that
// uses them is skipped by contacts(), with its index and the vertex's node tag, file and line
// from vertex_sources). Throws ReadError.
Mesh read_mesh(const std::string& path);

// Variants, one bit per definitions §6 value; bit k < kValueCount is the value kValueKeys[k] of
// pair_result.h, bit kValueCount (kGlobal) definitions §9's pdd2_global and its keys.
enum Variant : unsigned {
  kRigid = 1u << 0,    // rigid_pd2 (+ rigid_dir)
  kEq11 = 1u << 1,     // eq11_pd2
  kStatic = 1u << 2,   // pdd2_static (+ pdd2_static_dir)
  kPdd2 = 1u << 3,     // pdd2 (+ pdd2_dir, q1_A, q1_B)
  kRelaxed = 1u << 4,  // pdd2_relaxed (+ pdd2_relaxed_dir)
  kAccel1 = 1u << 5,   // pdd2_accel1
  kAccel6 = 1u << 6,   // pdd2_accel6
  kGlobal = 1u << 7,   // pdd2_global (+ pdd2_global_normal, q1_A_global, q1_B_global and,
                       // reference engine, pdd2_global_lower); see "kGlobal" above
};
inline constexpr std::size_t kVariantCount = kValueCount + 1;
inline constexpr unsigned kAllVariants = (1u << kVariantCount) - 1;
inline constexpr unsigned kDefaultVariants = kRigid | kStatic | kPdd2 | kAccel1;
static_assert(kGlobal == 1u << kValueCount, "bit k of a variant set is the value kVariantKeys[k]");
// Variant k's name (--variants) and the key of its value in the record.
inline constexpr std::array<const char*, kVariantCount> kVariantNames = {
    "rigid", "eq11", "static", "pdd2", "relaxed", "accel1", "accel6", "global"};
inline constexpr std::array<const char*, kVariantCount> kVariantKeys = {
    kValueKeys[0], kValueKeys[1], kValueKeys[2], kValueKeys[3],
    kValueKeys[4], kValueKeys[5], kValueKeys[6], "pdd2_global"};
// The value of variant k (kVariantKeys[k]) in a record.
template <class R>
const R& variant_value(const PairResult<R>& r, std::size_t k) {
  return k < kValueCount ? record_value(r, k) : r.pdd2_global;
}
// "rigid,static,pdd2,accel1" (names: rigid eq11 static pdd2 relaxed accel1 accel6 global, or
// "all": every one) -> bits; throws std::invalid_argument naming the unknown word.
unsigned parse_variants(const std::string& list);
std::string variant_names(unsigned variants);  // the inverse, comma-separated

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

// What contacts() throws when ContactOptions::cancel stopped it.
struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("pdd::mesh: cancelled") {}
};

// An element that was not computed (definitions §10): `mesh` is 'A' or 'B', `index` its number.
struct SkippedElement {
  char mesh = 'A';
  std::size_t index = 0;
  std::string reason;  // "element 12 of mesh A is flat: its four vertices are coplanar (volume 0)"
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
Contacts<double> self_contacts(const Mesh& A, const ContactOptions& options = {});
// The same pairs (stages 1–3 as above), each pair's record from the exact engine
// (pdd::reference::solve_pair, reduced formulation; every value of the record is computed).
Contacts<Rational> contacts_exact(const Mesh& A, const Mesh& B,
                                  const ContactOptions& options = {});
Contacts<Rational> self_contacts_exact(const Mesh& A, const ContactOptions& options = {});

// Building blocks, for tests and benchmarks.
TetVertices element(const Mesh& m, std::size_t i);  // the vertices of tetrahedron i
// Why element i cannot be computed (non-finite coordinate, flat: exact), or nullopt.
std::optional<std::string> element_problem(const Mesh& m, std::size_t i, char which);
// Stage 2 alone over the given elements (indices into A and B; B == nullptr: self, a < b,
// vertex-sharing pairs kept unless options.drop_shared_vertex): the box pairs, sorted by (a, b).
//   prune     (two meshes) first drop the boxes that miss the other mesh's bounding box;
//   parallel  CGAL's parallel box_intersection_d (Parallel_tag, on TBB's threads);
//   drop_shared_vertex  (self) leave out the pairs whose elements share a vertex index.
// The pair set does not depend on `prune` and `parallel`.
struct BroadphaseOptions {
  bool prune = true;
  bool parallel = true;
  bool drop_shared_vertex = false;
};
std::vector<std::array<std::size_t, 2>> box_pairs(const Mesh& A, const std::vector<std::size_t>& ea,
                                                  const Mesh* B, const std::vector<std::size_t>& eb,
                                                  const BroadphaseOptions& options = {});

// Writes A (and B unless null: self-contact) as one legacy VTK unstructured grid (ASCII) for
// ParaView: points of A then of B, cells of A then of B, with cell data `mesh` (0 A, 1 B),
// `element` (its number in its mesh), `partners` (number of intersecting pairs it is in),
// `skipped` (1: the element was skipped, flat or with a non-finite vertex) and `max_<value>`
// (largest value of each requested variant over its pairs, 0 if none; `max_pdd2_global` for
// kGlobal); point data `non_finite` (1: a vertex with a non-finite coordinate, written at the
// origin since VTK readers reject nan) and, when kPdd2 was requested, `displacement`: for each mesh vertex, among the
// displacements q1 − rest that the pairs' pdd2 solutions give that vertex, the one of largest
// length (first in (a, b) order among equals); 0 where no pair moves it. Throws
// std::runtime_error when the file cannot be written.
template <class R>
void write_vtk(const std::string& path, const Mesh& A, const Mesh* B, const Contacts<R>& contacts,
               unsigned variants);

// ---------------------------------------------------------------------------------------------
// Resolving interpenetration: new positions for the free vertices of A and B (or of one mesh
// with itself) after which, decided exactly on the doubles:
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

// Which per-pair solution drives the vertices.
enum class ResolveVariant {
  Global,  // pdd2_global: PD_d over every separating plane (q1_*_global); the default
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
  Bodies,       // self-contact of several bodies: each contacting group of bodies, split in
                // two colours, resolved as two meshes (any of the above per group)
  RigidRounds,  // self-contact fallback: rounds of the rigid variant from the rest pose
  None,         // nothing cleared the contacts (the report says what remains)
};
// "rounds" | "translation" | "bodies" | "rigid rounds" | "none"
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

// The exact verdict on given positions (the building block of report.resolved, for tests and
// independent checks): R1 over every pair (fresh broadphase, exact decision), R2 per element
// against its rest orientation (exact sign of the determinant), R3 for the fixed flags given,
// R4 per element for `limits` (exact). B0 == nullptr: self-contact. Fills r1 to r4, resolved,
// limits, remaining_pairs, bad_elements, poor_elements, moved_fixed_vertices, skipped and the
// volume and shape ratios. Throws std::invalid_argument for limits outside (0, 1].
ResolveReport check_resolution(const Mesh& A0, const std::vector<Vec3d>& a1, const Mesh* B0,
                               const std::vector<Vec3d>& b1,
                               const std::vector<char>& fixed_a = {},
                               const std::vector<char>& fixed_b = {},
                               const QualityLimits& limits = {});

// The mesh object norm sigma_mesh(P0, P1) of one mesh (see above).
double mesh_cost(const Mesh& m, const std::vector<Vec3d>& p1);

// Writes m with its vertices replaced by `positions` (same count) as Gmsh 4.1 ASCII (.msh) or
// legacy VTK ASCII (.vtk), chosen by the path's extension, tetrahedra in m's order, every
// coordinate printed so that it reads back as the same double. Throws std::runtime_error when
// the extension is neither or the file cannot be written (nothing partial is left: a new or
// regular file is written under a temporary name beside it and renamed; a device is written
// in place), std::invalid_argument when `positions` does not have one entry per vertex.
void write_mesh(const std::string& path, const Mesh& m, const std::vector<Vec3d>& positions);

// Writes a resolution for ParaView: A at positions a1 and B at b1 (B == nullptr: self-contact)
// as one legacy VTK ASCII file, points of A then of B, cells of A then of B, with point data
// `displacement` (p1 - p0) and cell data `mesh` (0 A, 1 B), `element` (its number in its mesh),
// `volume_ratio` (V1 / V0, signed; doubles, for display), `shape_ratio` (eta1 / eta0 from
// the report; 0 where it has none), `remaining` (how many of report.remaining_pairs it is
// in), `bad` (1: in report.bad_elements) and `poor` (1: in report.poor_elements). A vertex with a
// non-finite coordinate is written at the origin (VTK readers reject nan). Written whole or
// not at all, as write_mesh; throws std::runtime_error when the file cannot be written.
void write_resolution_vtk(const std::string& path, const Mesh& A, const std::vector<Vec3d>& a1,
                          const Mesh* B, const std::vector<Vec3d>& b1, const ResolveReport& report);

}  // namespace pdd::mesh

#include "pdd/mesh/contact_energy.h"  // contact_energy: E, its gradient and Hessian (definitions §12)
