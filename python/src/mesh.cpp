// mesh.cpp — pdd.read_mesh, pdd.mesh_contacts and pdd.resolve: tetrahedral meshes through
// <pdd/mesh.h> (pdd::mesh; definitions §10 and §11).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "common.h"
#include "long_call.h"
#include "pdd/io/resolve_report.h"
#include "pdd/mesh.h"
#include "record_columns.h"

namespace pdd_python {
namespace {

// pdd.read_mesh, pdd.mesh_contacts (definitions §10; the library include/pdd/mesh.h)

py::tuple read_mesh(py::handle path_like) {
  const std::string path = path_arg(path_like);
  pdd::mesh::Mesh m;
  std::optional<std::string> error;
  {
    py::gil_scoped_release release;
    try {
      m = pdd::mesh::read_mesh(path);
    } catch (const pdd::mesh::ReadError& e) {
      error = e.what();
    }
  }
  if (error) value_error(*error);
  const auto nv = static_cast<py::ssize_t>(m.vertices.size());
  const auto nt = static_cast<py::ssize_t>(m.tets.size());
  py::array_t<double> V({nv, py::ssize_t{3}});
  py::array_t<std::int64_t> T({nt, py::ssize_t{4}});
  double* v = V.mutable_data();
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) v[i * 3 + k] = m.vertices[i][k];
  std::int64_t* t = T.mutable_data();
  for (std::size_t i = 0; i < m.tets.size(); ++i)
    for (int k = 0; k < 4; ++k) t[i * 4 + k] = static_cast<std::int64_t>(m.tets[i][k]);
  return py::make_tuple(V, T);
}

// Meshes A and (unless self) B from the caller's arrays, checked as mesh_vertices and
// mesh_tets check them; B is empty for self-contact.
std::pair<pdd::mesh::Mesh, pdd::mesh::Mesh> meshes_from_arrays(py::handle VA, py::handle TA,
                                                               py::handle VB, py::handle TB,
                                                               bool self) {
  // A mesh without tetrahedra is an error, as `pdd mesh` and `pdd resolve` reject a file
  // without them (read_mesh): an empty result would look like "no contact" or "resolved".
  auto no_tets = [](const char* which) {
    value_error(std::string(which) + " has no tetrahedra (shape (0, 4)): a mesh needs at least one");
  };
  pdd::mesh::Mesh A, B;
  A.vertices = mesh_vertices(VA, "VA");
  A.vertex_sources = vertex_sources(A.vertices, "VA");
  A.tets = mesh_tets(TA, "TA", 'A', A.vertices.size());
  if (A.tets.empty()) no_tets("TA");
  if (!self) {
    B.vertices = mesh_vertices(VB, "VB");
    B.vertex_sources = vertex_sources(B.vertices, "VB");
    B.tets = mesh_tets(TB, "TB", 'B', B.vertices.size());
    if (B.tets.empty()) no_tets("TB");
  }
  return {std::move(A), std::move(B)};
}

template <class R>
py::dict contacts_dict(const pdd::mesh::Contacts<R>& c, unsigned variants, bool exact) {
  const std::size_t n = c.pairs.size();
  const auto N = static_cast<py::ssize_t>(n);
  py::array_t<std::int64_t> a(N), b(N);
  RecordColumns columns(n, exact, variants & ((1u << pdd::kValueCount) - 1),
                        (variants & pdd::mesh::kPdd2) != 0, (variants & pdd::mesh::kGlobal) != 0);
  for (std::size_t j = 0; j < n; ++j) {
    a.mutable_data()[j] = static_cast<std::int64_t>(c.pairs[j].a);
    b.mutable_data()[j] = static_cast<std::int64_t>(c.pairs[j].b);
    columns.put(j, c.pairs[j].result);
  }
  py::dict d;
  d["a"] = a;
  d["b"] = b;
  columns.add_to(d);
  py::list skipped;
  for (const auto& s : c.skipped)
    skipped.append(py::make_tuple(py::str(std::string(1, s.mesh)), s.index, py::str(s.reason)));
  d["skipped"] = skipped;
  d["elements_a"] = c.elements_a;
  d["elements_b"] = c.elements_b;
  d["box_pairs"] = c.box_pairs;
  d["seconds_boxes"] = c.seconds_boxes;
  d["seconds_broadphase"] = c.seconds_broadphase;
  d["seconds_decision"] = c.seconds_decision;
  d["seconds_depth"] = c.seconds_depth;
  return d;
}

py::dict mesh_contacts(py::handle VA, py::handle TA, py::handle VB, py::handle TB,
                       py::handle variants_in, py::handle engine_in, py::handle threads_in,
                       py::handle progress_arg) {
  const std::string engine = text_arg(engine_in, "engine");
  if (engine != "fast" && engine != "reference")
    value_error("engine must be 'fast' or 'reference'; got '" + engine + "'");
  unsigned variants = 0;
  try {
    variants = pdd::mesh::parse_variants(text_arg(variants_in, "variants"));
  } catch (const std::invalid_argument& e) {
    value_error(std::string("variants: ") + e.what());
  }
  const std::optional<int> threads = threads_arg(threads_in);
  Progress progress(progress_arg, "pdd.mesh_contacts");
  if (VB.is_none() != TB.is_none())
    value_error("give both VB and TB (contacts of A with B), or neither (self-contact of A)");
  const bool self = VB.is_none();

  const auto meshes = meshes_from_arrays(VA, TA, VB, TB, self);
  const pdd::mesh::Mesh &A = meshes.first, &B = meshes.second;

  pdd::mesh::ContactOptions options;
  options.variants = variants;
  std::optional<pdd::mesh::Contacts<double>> fast;
  std::optional<pdd::mesh::Contacts<pdd::Rational>> exact;
  std::optional<std::string> bad_input;
  LongCall call(progress);
  options.cancel = &call.cancel;
  options.progress = [&call](std::size_t n, std::size_t total) {
    call.total.store(total, std::memory_order_relaxed);
    call.add_done(n);
  };
  call.run(true, [&] {
    with_threads(threads, [&] {
      try {
        if (engine == "fast")
          fast = self ? pdd::mesh::contacts_self(A, options) : pdd::mesh::contacts(A, B, options);
        else
          exact = self ? pdd::mesh::contacts_exact_self(A, options)
                       : pdd::mesh::contacts_exact(A, B, options);
      } catch (const std::invalid_argument& e) {  // an index past the end of the vertices
        bad_input = e.what();
      } catch (const pdd::mesh::Cancelled&) {  // call.run raises why
      }
    });
  });
  if (bad_input) value_error(*bad_input);
  return fast ? contacts_dict(*fast, variants, false) : contacts_dict(*exact, variants, true);
}

// ---------------------------------------------------------------------------------------------
// pdd.resolve (the library's pdd::mesh::resolve / resolve_self; `pdd resolve`)

// A boolean vertex mask of `vertices` entries (fixed_a, fixed_b) -> the library's flags.
std::vector<char> vertex_mask(py::handle obj, const char* which, std::size_t vertices) {
  if (obj.is_none()) return {};
  py::array a = cached->asarray(obj);
  if (a.dtype().kind() != 'b' || a.ndim() != 1 || static_cast<std::size_t>(a.shape(0)) != vertices)
    value_error(std::string(which) + " must be a boolean array of shape (" + std::to_string(vertices) +
                ",), one entry per vertex (True: kept bit for bit); got dtype " +
                py::str(a.dtype()).cast<std::string>() + ", shape " + shape_str(a));
  const auto d = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!d) throw py::error_already_set();
  std::vector<char> out(vertices);
  for (std::size_t i = 0; i < vertices; ++i) out[i] = d.data()[i] ? 1 : 0;
  return out;
}

py::array_t<double> vertices_array(const std::vector<pdd::Vec3d>& v) {
  py::array_t<double> out({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  double* o = out.mutable_data();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < 3; ++k) o[i * 3 + k] = v[i][k];
  return out;
}

py::tuple resolve(py::handle VA, py::handle TA, py::handle VB, py::handle TB, py::handle fix_in,
                  py::handle variant_in, py::handle max_rounds_in, py::handle threads_in,
                  py::handle progress_arg, py::handle fixed_a_in, py::handle fixed_b_in,
                  py::handle min_volume_ratio_in, py::handle min_shape_ratio_in) {
  pdd::mesh::ResolveOptions options;
  // R4's limits: None keeps ResolveOptions' default; a real number in (0, 1] otherwise.
  for (auto [name, in, value] : {std::tuple{"min_volume_ratio", min_volume_ratio_in, &options.min_volume_ratio},
                                 std::tuple{"min_shape_ratio", min_shape_ratio_in, &options.min_shape_ratio}}) {
    if (in.is_none()) continue;
    const PyObject* p = in.ptr();
    const double x = !PyBool_Check(p) && (PyFloat_Check(p) || PyLong_Check(p)) ? PyFloat_AsDouble(in.ptr()) : -1.0;
    if (PyErr_Occurred()) PyErr_Clear();
    if (!(x > 0 && x <= 1)) value_error(std::string(name) + " must be a real number in (0, 1]; got " + short_repr(in));
    *value = x;
  }
  try {
    options.variant = pdd::mesh::parse_resolve_variant(text_arg(variant_in, "variant"));
  } catch (const std::invalid_argument& e) {
    value_error(std::string("variant: ") + e.what());
  }
  if (VB.is_none() != TB.is_none())
    value_error("give both VB and TB (A against B), or neither (self-contact of A)");
  const bool self = VB.is_none();
  std::string fix;
  if (!fix_in.is_none()) {
    fix = PyUnicode_Check(fix_in.ptr()) ? fix_in.cast<std::string>() : std::string("?");
    if (fix != "a" && fix != "b")
      value_error("fix must be None, 'a' or 'b' (the mesh kept bit for bit); got " + short_repr(fix_in));
    if (self && fix == "b") value_error("fix='b': with self-contact (VB, TB None) there is no mesh B");
  }
  if (self && !fixed_b_in.is_none())
    value_error("fixed_b: with self-contact (VB, TB None) there is no mesh B");
  const PyObject* mr = max_rounds_in.ptr();
  if (PyBool_Check(mr) || !PyLong_Check(mr))
    value_error("max_rounds must be an int >= 1; got " + short_repr(max_rounds_in));
  int overflow = 0;
  const long long rounds = PyLong_AsLongLongAndOverflow(max_rounds_in.ptr(), &overflow);
  if (overflow > 0 || rounds < 1 || rounds > 1000000)
    value_error("max_rounds must be an int from 1 to 1000000; got " + short_repr(max_rounds_in));
  options.max_rounds = static_cast<std::size_t>(rounds);
  const std::optional<int> threads = threads_arg(threads_in);
  Progress progress(progress_arg, "pdd.resolve", "round", /*open_ended=*/true);

  const auto meshes = meshes_from_arrays(VA, TA, VB, TB, self);
  const pdd::mesh::Mesh &A = meshes.first, &B = meshes.second;
  options.fix_a = fix == "a";
  options.fix_b = fix == "b";
  options.fixed_vertices_a = vertex_mask(fixed_a_in, "fixed_a", A.vertices.size());
  if (!self) options.fixed_vertices_b = vertex_mask(fixed_b_in, "fixed_b", B.vertices.size());

  std::optional<pdd::mesh::Resolution> result;
  std::optional<std::string> bad_input;
  LongCall call(progress);
  options.cancel = &call.cancel;
  call.total.store(options.max_rounds);
  options.progress = [&call](const pdd::mesh::ResolveRound& r) {
    call.pairs.store(r.pairs, std::memory_order_relaxed);
    call.done.store(r.round, std::memory_order_relaxed);
  };
  call.run(true, [&] {
    with_threads(threads, [&] {
      try {
        result = self ? pdd::mesh::resolve_self(A, options) : pdd::mesh::resolve(A, B, options);
        call.total.store(result->report.rounds.size());  // the last report: rounds run of rounds run
        call.done.store(result->report.rounds.size());
        call.pairs.store(result->report.remaining_pairs.size());  // what intersects at the end
      } catch (const std::invalid_argument& e) {
        bad_input = e.what();
      } catch (const pdd::mesh::Cancelled&) {  // call.run raises why
      }
    });
  });
  if (bad_input) value_error(*bad_input);
  if (!result) throw std::runtime_error("pdd.resolve: stopped without a result");

  auto count = [](const std::vector<char>& f) {
    return static_cast<std::size_t>(std::count(f.begin(), f.end(), 1));
  };
  pdd::io::ResolveInputs in;
  in.files = false;
  in.self = self;
  in.fix = fix.empty() ? 0 : fix[0];
  in.max_rounds = options.max_rounds;
  in.elements_a = A.tets.size(), in.vertices_a = A.vertices.size();
  in.elements_b = B.tets.size(), in.vertices_b = B.vertices.size();
  in.fixed_vertices_a = options.fix_a ? A.vertices.size() : count(options.fixed_vertices_a);
  in.fixed_vertices_b = options.fix_b ? B.vertices.size() : count(options.fixed_vertices_b);
  const std::string report = pdd::io::resolve_report_json(result->report, in).dump();
  py::object report_dict = py::module_::import("json").attr("loads")(report);
  // Per element ratios as numpy arrays (NaN: element skipped, or non-finite at the result).
  auto array = [](const std::vector<double>& v) {
    py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
    std::copy(v.begin(), v.end(), out.mutable_data());
    return out;
  };
  report_dict["volume_ratio_a"] = array(result->report.volume_ratio_a);
  report_dict["shape_ratio_a"] = array(result->report.shape_ratio_a);
  report_dict["volume_ratio_b"] = self ? py::object(py::none()) : py::object(array(result->report.volume_ratio_b));
  report_dict["shape_ratio_b"] = self ? py::object(py::none()) : py::object(array(result->report.shape_ratio_b));
  return py::make_tuple(vertices_array(result->a),
                        self ? py::object(py::none()) : py::object(vertices_array(result->b)),
                        report_dict);
}

// ---------------------------------------------------------------------------------------------
// Docstrings: help(pdd.mesh_contacts) reads like the README.

// The defaults in these texts ({variants}, {max_rounds}, ...) are filled in from the library's
// options structs by with_defaults() below, as the keyword defaults are: typed nowhere else.
constexpr const char* kMeshContactsDoc = R"doc(mesh_contacts(VA, TA, VB=None, TB=None, variants='{variants}', engine='fast', threads=None, progress=None)
--

Two tetrahedral meshes (or one, with itself) -> every intersecting element pair and its
depths, as numpy arrays: `pdd mesh` (docs/definitions.md §10) from Python, on the C++
library include/pdd/mesh.h, on all cores with the GIL released.

VA, TA   mesh A: VA its vertices, shape (n, 3), real numbers (read as float64); TA its
         tetrahedra, shape (m, 4), integers: four indices into VA each, any orientation.
         Element i is TA[i]. pdd.read_mesh(path) gives (V, T) from a .msh or .vtk file;
         meshio's points and cells_dict["tetra"] are the same arrays.
VB, TB   mesh B, the same way; both None (the default): self-contact of A, the pairs a < b
         of A's elements that share no vertex index.
variants comma-separated, which values to compute: rigid (rigid_pd2), eq11 (eq11_pd2),
         static (pdd2_static), pdd2, relaxed (pdd2_relaxed), accel1, accel6 (pdd2_accel1/6),
         global (pdd2_global, PD_d² over every separating plane: tens of microseconds
         a pair with the fast engine), or all. Default: "{variants}" (the C++
         ContactOptions::variants), as `pdd mesh`.
engine   "fast" (doubles, certified to the accuracy contract of docs/definitions.md §8)
         or "reference" (exact rationals, fractions.Fraction; about 0.1 s a pair on one
         core: for small meshes).
threads  None or 0: all cores; k from 1 to 4096: at most k threads (a TBB arena for this
         call only), as `pdd mesh --threads`. Anything else raises ValueError.
progress None (the default) or False: silent; a callable progress(done, total) or True (a
         tqdm bar), as in solve_batch(). Over stage 4 below: `done` counts the intersecting
         pairs computed, `total` is their number (no call comes before stage 3 is done).

Stages (pdd/mesh/contacts.h): 1. a box per element (an element with a non-finite coordinate or zero
volume, decided exactly, is skipped and listed); 2. the pairs whose boxes overlap (CGAL's
box_intersection_d); 3. the exact decision: the interiors intersect iff rigid_pd2 > 0
(touching is not intersecting); 4. the requested values per intersecting pair.

Returns a dict; its first entries are columns with one row per intersecting pair, sorted
by (a, b) as `pdd mesh` writes its records:
  a, b          (k,) int64: element of A, element of B (of A, for self-contact)
  intersecting  (k,) bool: True (False only on a rejected row)
  the requested values, among rigid_pd2, eq11_pd2, pdd2_static, pdd2, pdd2_relaxed,
                pdd2_accel1, pdd2_accel6: fast: (k,) float64; reference: a list of k
                fractions.Fraction
  their labels, among rigid_dir, pdd2_static_dir, pdd2_dir, pdd2_relaxed_dir:
                (k,) numpy str arrays ('<U8'), as solve() gives them
  q1_A, q1_B    when pdd2 is requested: the deformed positions attaining pdd2; fast
                (k, 4, 3) float64, reference k nested 4 x 3 lists of Fractions
  pdd2_global, pdd2_global_normal, q1_A_global, q1_B_global   when global is requested
                (docs/definitions.md §9), as solve_batch gives them: fast (k,), (k, 3),
                (k, 4, 3) float64;
                reference lists of Fractions, of [x, y, z] Fractions, of nested lists, and
                then pdd2_global_lower, the proved lower bound (a list of Fractions)
  error         list of k entries: None, or why the pair was rejected (fast engine: a
                value outside the normal double range); that row's values are NaN (None),
                its labels "" and intersecting False
then what happened:
  skipped       list of (mesh, index, reason): mesh "A" or "B", the element's index, and
                why, e.g. ("A", 12, "element 12 of mesh A is flat: its four vertices are
                coplanar (volume 0)"); the rest is computed
  elements_a, elements_b   tetrahedra in A and B (elements_b 0 for self-contact)
  box_pairs     pairs whose boxes overlap (self-contact: sharing no vertex)
  seconds_boxes, seconds_broadphase, seconds_decision, seconds_depth   time per stage
Row j's values are those of solve(VA[TA[a]], VB[TB[b]], engine=engine) for (a, b) = (a[j],
b[j]): fast ones bit for bit, reference ones exactly.

Ctrl-C stops a call from the main thread (where Python handles signals): KeyboardInterrupt
(or whatever a signal handler raises), the pairs already computed dropped; within about
0.1 s with the fast engine, once the pairs being computed are done with the reference engine
(one per thread, about 0.1 s each on small meshes). Stage 2 runs to its end first (under a
second for 10^5 elements).

A flat or non-finite element is skipped and listed, never an exception. Malformed
arguments raise ValueError: a wrong shape or dtype, a vertex index out of range ("element
3 of mesh A refers to vertex 99, but the mesh has 20 vertices"), an unknown variant
("variants: unknown variant 'pd' (rigid, eq11, ...)"), an unknown engine, VB without TB, a
mesh without tetrahedra ("TA has no tetrahedra"; `pdd mesh` refuses such a file too), an integer
coordinate that is not exactly a double.

Example (pair (0, 8) has candidates within 1e-9 of each other: the exact engine names EE:2:1,
the fast one FV:1; docs/definitions.md §8 allows either):
  >>> VA, TA = pdd.read_mesh("fixtures/meshes/tiny-a.msh")
  >>> VB, TB = pdd.read_mesh("fixtures/meshes/tiny-b.msh")
  >>> c = pdd.mesh_contacts(VA, TA, VB, TB)
  >>> len(c["a"]), int(c["a"][0]), int(c["b"][0]), float(c["pdd2"][0]), c["pdd2_dir"][0], c["skipped"]
  (51, 0, 8, 0.003461538461538461, 'FV:1', [])
  >>> s = pdd.mesh_contacts(VA, TA)       # self-contact of A
)doc";

constexpr const char* kReadMeshDoc = R"doc(read_mesh(path)
--

A tetrahedral mesh file -> (V, T), numpy arrays for mesh_contacts(): V the vertices,
(n, 3) float64, T the tetrahedra, (m, 4) int64 indices into V.

Read by the library's reader (pdd::mesh::read_mesh, the one `pdd mesh` uses): Gmsh .msh
versions 2.2 and 4.1 (ASCII and binary) and legacy VTK unstructured grids (.vtk, ASCII or
BINARY, cell type 10), chosen by content. Tetrahedra are numbered in file order among the
file's tetrahedral elements; other elements (points, lines, triangles, ...) are ignored.
Gmsh node tags become indices 0, 1, ... in the file's node order. Coordinates are read as
written, non-finite ones too (mesh_contacts() then skips the element that uses them, naming
the array and row, "VA[3]"; `pdd mesh` names the file's node tag and line).

A file that cannot be read (missing, truncated, malformed, an element referring to a node
that is not in the file, an unknown element type) raises ValueError with the message
`pdd mesh` prints, naming the file and the line or byte, e.g. "a.msh:42: element 17
refers to node 999, which is not in the file".

  >>> import pdd
  >>> V, T = pdd.read_mesh("fixtures/meshes/tiny-a.msh")
  >>> V.shape, V.dtype, T.shape, T.dtype
  ((14, 3), dtype('float64'), (24, 4), dtype('int64'))
)doc";

constexpr const char* kResolveDoc = R"doc(resolve(VA, TA, VB=None, TB=None, fix=None, variant='{variant}', max_rounds={max_rounds}, threads=None, progress=None, fixed_a=None, fixed_b=None, min_volume_ratio=None, min_shape_ratio=None)
--

Two tetrahedral meshes that interpenetrate (or one that intersects itself) -> new vertex
positions after which, each decided exactly on the returned doubles:
  R1  no element pair intersects (A against B; self-contact: the pairs of A that share no
      vertex; touching is not intersecting),
  R2  every element keeps the sign of its volume and a non-zero volume (none inverted or
      flattened),
  R3  fixed vertices are bit-for-bit unchanged,
  R4  every element stays usable by a simulator: V1/V0 in [rho, 1/rho] and its mean-ratio
      shape quality eta = 12 (3|V|)^(2/3) / (sum of squared edge lengths) keeps
      eta1/eta0 >= kappa.
`pdd resolve` from Python, on the C++ library include/pdd/mesh.h (pdd::mesh::resolve), on all
cores with the GIL released. The connectivity is unchanged: element i is still TA[i].

VA, TA   mesh A: VA its vertices, shape (n, 3), real numbers (read as float64); TA its
         tetrahedra, shape (m, 4), integers (indices into VA, any orientation), as for
         mesh_contacts(). pdd.read_mesh(path) or meshio give them from a file.
VB, TB   mesh B, the same way; both None (the default): self-contact of A.
fix      None (the default): every vertex may move; "a" or "b": that whole mesh is kept bit
         for bit and only the other one moves ("b" needs B).
fixed_a, fixed_b   boundary conditions: None, or a numpy bool array of shape (n,) per mesh,
         True where the vertex is kept bit for bit (with fix, the union is fixed).
variant  which per-pair solution drives the vertices: "global" (the deformable
         penetration depth over every separating plane, its deformed positions), "pdd2" (the
         deformable depth over the candidate directions) or "rigid" (the baseline: each pair
         pushed apart by its rigid translation, split between the two elements). Default:
         "{variant}" (the C++ ResolveOptions::variant).
max_rounds   rounds of contact solving before giving up, an int from 1 to 1000000 (default
         {max_rounds}: the C++ ResolveOptions::max_rounds). A run
         that reaches it without R1-R4 returns normally with report["resolved"] False.
min_volume_ratio, min_shape_ratio   R4's rho and kappa, real numbers in (0, 1]; None: the
         library's defaults ({min_volume_ratio} and {min_shape_ratio}: QualityLimits), as `pdd resolve --min-volume-ratio/--min-shape-ratio`.
threads  None or 0: all cores; k from 1 to 4096: at most k threads (a TBB arena for this
         call only), as `pdd resolve --threads`. Anything else raises ValueError.
progress None (the default) or False: silent. A callable progress(done, total): called from
         the calling thread with the GIL held, about every 0.05 s while the rounds run when
         `done` (rounds finished) has grown, total being max_rounds; once at the end with
         done == total == the rounds run. An exception it raises stops the call (as Ctrl-C
         does) and propagates. True: a tqdm counter of rounds on standard error (Debian
         python3-tqdm; max_rounds is a limit, not a length), with "pairs=" after it: the
         intersecting pairs at the start of the latest round, and at the end the pairs that
         still intersect (0 when resolved).

Cost: the mesh object norm, the volume-weighted mean squared displacement
  sigma_mesh = sum_e V_e sigma_e / sum_e V_e    (V_e rest volume, sigma_e the per-tetrahedron
                                                 object norm of docs/definitions.md)
so that a translation by t costs |t|^2; reported per mesh and summed.

Returns (VA1, VB1, report):
  VA1       (n, 3) float64: A's new vertices (equal to VA where fixed, bit for bit)
  VB1       (n_B, 3) float64, or None for self-contact
  report    dict, the keys of `pdd resolve --report` (JSON), in that order:
    variant               "global", "pdd2" or "rigid"
    method                "rounds", "translation", "bodies", "pdd2 rounds", "rigid rounds" or "none": what
                          produced it
    stopped_because       why the run stopped at once without resolving (every vertex fixed,
                          no finite per-pair solution), or None
    inputs                {self, fix, max_rounds, min_volume_ratio, min_shape_ratio,
                           elements_a, vertices_a, elements_b,
                           vertices_b, fixed_vertices_a, fixed_vertices_b} (the CLI adds the
                           file names a and b)
    resolved              r1 and r2 and r3 and r4: the exact verdict on VA1, VB1 over every pair (a
                          fresh broadphase, not only the pairs of the last round)
    r1, r2, r3, r4        each condition above
    rounds                list of {round, pairs, max_pd2, cost, seconds}: per round the
                          intersecting pairs at its start, the largest per-pair squared depth
                          of the variant, the cost after it, its wall time
    cost, cost_a, cost_b  sigma_mesh of A plus B, of A, of B
    max_displacement      largest |p1 - p0| over every vertex
    min_volume_ratio      smallest V1 / V0 over every element (signed: < 0 is inverted)
    max_volume_ratio      largest V1 / V0
    min_shape_ratio       smallest eta1 / eta0
    volume_ratio_histogram, shape_ratio_histogram   {edges, counts} of the ratios
    worst_elements        [{mesh, index, volume_ratio, shape_ratio}, ...]: the ten elements
                          closest to (or furthest past) R4's bounds
    remaining_pairs       [[a, b], ...]: element pairs still intersecting ([] when r1)
    bad_elements          [["A" or "B", i], ...]: elements inverted or flat ([] when r2)
    poor_elements         [["A" or "B", i], ...]: elements short of R4 ([] when r4)
    moved_fixed_vertices  [["A" or "B", i], ...]: fixed vertices that moved ([] when r3)
    skipped               [{mesh, index, reason}, ...]: input elements that cannot be
                          computed (flat, non-finite), e.g. "element 12 of mesh A is flat: ...";
                          they are in no pair and no check (`pdd resolve` exits 1 then)
    seconds_contacts, seconds_solve, seconds_move, seconds_verify, seconds_total
                          wall time per stage over the run
    volume_ratio_a, shape_ratio_a, volume_ratio_b, shape_ratio_b   (not in the JSON): numpy
                          float64 arrays, one entry per element (NaN: skipped), V1/V0 and
                          eta1/eta0; the B ones None for self-contact
Write the result with meshio (meshio.Mesh(VA1, [("tetra", TA)]).write("a1.msh")) or with
`pdd resolve`, which writes .msh / .vtk files whose coordinates read back bit for bit.

Ctrl-C stops a call from the main thread: KeyboardInterrupt (or whatever a signal handler
raises) once the stage being computed ends (a round has a few stages: contacts, per-pair
solutions, the move, the exact check); nothing is returned.

Malformed arguments raise ValueError: a wrong shape or dtype, a vertex index out of range,
an unknown variant or fix, fix="b" or fixed_b without B, a mask of the wrong length,
max_rounds < 1, VB without TB, a mesh without tetrahedra (TA or TB of shape (0, 4)), as
`pdd resolve` refuses one.

Example:
  >>> VA, TA = pdd.read_mesh("fixtures/meshes/tiny-a.msh")
  >>> VB, TB = pdd.read_mesh("fixtures/meshes/tiny-b.msh")
  >>> VA1, VB1, r = pdd.resolve(VA, TA, VB, TB, fix="a")
  >>> r["resolved"], len(r["rounds"]), bool((VA1 == VA).all())
  (True, 10, True)
  >>> V1, _, r = pdd.resolve(VA, TA)                # self-contact of one mesh
)doc";

// `doc` with every {name} replaced by the library's default of that option.
std::string with_defaults(std::string doc) {
  const pdd::mesh::ResolveOptions r;
  const std::pair<std::string, std::string> values[] = {
      {"{variants}", pdd::mesh::variant_names(pdd::mesh::ContactOptions{}.variants)},
      {"{variant}", pdd::mesh::resolve_variant_name(r.variant)},
      {"{max_rounds}", std::to_string(r.max_rounds)},
      {"{min_volume_ratio}", py::repr(py::float_(r.min_volume_ratio)).cast<std::string>()},
      {"{min_shape_ratio}", py::repr(py::float_(r.min_shape_ratio)).cast<std::string>()}};
  for (const auto& [key, value] : values)
    for (std::size_t at; (at = doc.find(key)) != std::string::npos;) doc.replace(at, key.size(), value);
  return doc;
}

}  // namespace

void bind_mesh(py::module_& m) {
  // Kept for the module's lifetime (pybind11 keeps the pointer).
  static const std::string contacts_doc = with_defaults(kMeshContactsDoc), resolve_doc = with_defaults(kResolveDoc);
  const pdd::mesh::ResolveOptions defaults;
  m.def("mesh_contacts", &mesh_contacts, contacts_doc.c_str(), py::arg("VA"), py::arg("TA"),
        py::arg("VB") = py::none(), py::arg("TB") = py::none(),
        py::arg("variants") = pdd::mesh::variant_names(pdd::mesh::ContactOptions{}.variants), py::arg("engine") = "fast",
        py::arg("threads") = py::none(), py::arg("progress") = py::none());
  m.def("read_mesh", &read_mesh, kReadMeshDoc, py::arg("path"));
  m.def("resolve", &resolve, resolve_doc.c_str(), py::arg("VA"), py::arg("TA"), py::arg("VB") = py::none(),
        py::arg("TB") = py::none(), py::arg("fix") = py::none(),
        py::arg("variant") = pdd::mesh::resolve_variant_name(defaults.variant),
        py::arg("max_rounds") = defaults.max_rounds, py::arg("threads") = py::none(),
        py::arg("progress") = py::none(), py::arg("fixed_a") = py::none(),
        py::arg("fixed_b") = py::none(), py::arg("min_volume_ratio") = py::none(),
        py::arg("min_shape_ratio") = py::none());
}

}  // namespace pdd_python
