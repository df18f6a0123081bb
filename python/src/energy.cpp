// energy.cpp — pdd.contact_energy: the contact energy of two tetrahedral meshes (or of one,
// self-contact), its gradient and Hessian, through <pdd/mesh.h> (pdd::mesh::contact_energy;
// definitions §12 and docs/definitions.md "Contact energy").
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common.h"
#include "long_call.h"
#include "pdd/mesh.h"

namespace pdd_python {
namespace {

// Mesh `which` at rest (rest given, or the positions) with the positions given.
pdd::mesh::Mesh mesh_arg(py::handle V, py::handle T, py::handle rest, char which,
                         std::vector<pdd::Vec3d>& positions) {
  const std::string v = std::string("V") + which, t = std::string("T") + which,
                    r = std::string("rest_") + which;
  positions = mesh_vertices(V, v.c_str());
  pdd::mesh::Mesh m;
  m.vertices = rest.is_none() ? positions : mesh_vertices(rest, r.c_str());
  // The energy is taken at the positions: their rows first, then the rest rows (a non-finite
  // rest coordinate is named where the rest shape is used).
  m.vertex_sources = vertex_sources(positions, v.c_str());
  if (!rest.is_none()) m.vertex_sources.merge(vertex_sources(m.vertices, r.c_str()));
  if (m.vertices.size() != positions.size())
    value_error(r + " must have the shape of " + v + " (one rest position per vertex); got " +
                std::to_string(m.vertices.size()) + " rows for " + std::to_string(positions.size()));
  m.tets = mesh_tets(T, t.c_str(), which, positions.size());
  return m;
}

py::object hessian_csr(const Eigen::SparseMatrix<double>& H) {
  // Eigen's default storage is column-major (CSC); H is symmetric, so its CSC arrays read as CSR
  // are H^T = H.
  const auto nnz = static_cast<py::ssize_t>(H.nonZeros());
  py::array_t<double> data(nnz);
  py::array_t<std::int64_t> indices(nnz), indptr(H.outerSize() + 1);
  double* dp = data.mutable_data();
  std::int64_t* ip = indices.mutable_data();
  std::int64_t* op = indptr.mutable_data();
  for (py::ssize_t k = 0; k < nnz; ++k) {
    dp[k] = H.valuePtr()[k];
    ip[k] = H.innerIndexPtr()[k];
  }
  for (Eigen::Index k = 0; k <= H.outerSize(); ++k) op[k] = H.outerIndexPtr()[k];
  py::module_ sparse;
  try {
    sparse = py::module_::import("scipy.sparse");
  } catch (py::error_already_set& e) {
    if (!e.matches(PyExc_ImportError)) throw;
    py::raise_from(e, PyExc_ImportError,
                   "hessian=True returns a scipy.sparse matrix, but scipy cannot be imported "
                   "(Debian: apt install python3-scipy; pip: pip install scipy)");
    throw py::error_already_set();
  }
  return sparse.attr("csr_matrix")(py::make_tuple(data, indices, indptr),
                                   py::arg("shape") = py::make_tuple(H.rows(), H.cols()));
}

py::dict contact_energy(py::handle VA, py::handle TA, py::handle VB, py::handle TB, py::handle hessian_in,
                        py::handle per_pair_in, py::handle engine_in, py::handle weight_in,
                        py::handle threads_in, py::handle rest_A, py::handle rest_B) {
  const bool hessian = bool_arg(hessian_in, "hessian"), per_pair = bool_arg(per_pair_in, "per_pair");
  const std::string engine = text_arg(engine_in, "engine");
  if (engine != "fast" && engine != "reference")  // (the names of mesh_contacts, solve and pdd mesh --engine)
    value_error("engine must be 'fast' or 'reference'; got '" + engine + "'");
  const std::string weight = text_arg(weight_in, "weight");
  if (weight != "area" && weight != "unit")
    value_error("weight must be 'area' or 'unit'; got '" + weight + "'");
  const std::optional<int> threads = threads_arg(threads_in);
  if (VB.is_none() != TB.is_none())
    value_error("give both VB and TB (contact of A with B), or neither (self-contact of A)");
  const bool self = VB.is_none();
  if (self && !rest_B.is_none()) value_error("rest_B is for two meshes; self-contact has rest_A only");
  if (hessian) py::module_::import("scipy.sparse");  // fail before the work when scipy is missing

  std::vector<pdd::Vec3d> pa, pb;
  const pdd::mesh::Mesh A = mesh_arg(VA, TA, rest_A, 'A', pa);
  pdd::mesh::Mesh B;
  if (!self) B = mesh_arg(VB, TB, rest_B, 'B', pb);

  pdd::mesh::ContactEnergyOptions o;
  o.engine = engine == "fast" ? pdd::mesh::EnergyEngine::Fast : pdd::mesh::EnergyEngine::Exact;
  o.weight = weight == "area" ? pdd::mesh::EnergyWeight::Area : pdd::mesh::EnergyWeight::Unit;
  o.hessian = hessian;
  o.per_pair = per_pair;
  // no rest given: that mesh's weights are its current volumes, and E's gradient their function's
  o.weights_follow_a = rest_A.is_none();
  o.weights_follow_b = rest_B.is_none();
  Progress progress(py::none(), "pdd.contact_energy");
  LongCall call(progress);
  o.cancel = &call.cancel;
  std::optional<pdd::mesh::ContactEnergy> e;
  std::optional<std::string> bad_input;
  call.run(true, [&] {
    with_threads(threads, [&] {
      try {
        e = self ? pdd::mesh::contact_energy_self(A, pa, o) : pdd::mesh::contact_energy(A, B, pa, pb, o);
      } catch (const std::invalid_argument& x) {
        bad_input = x.what();
      } catch (const std::underflow_error& x) {  // positions too small for the energy's doubles
        bad_input = x.what();
      } catch (const pdd::mesh::Cancelled&) {  // call.run raises why
      }
    });
  });
  if (bad_input) value_error(*bad_input);

  py::dict d;
  d["energy"] = e->energy;
  const auto n = static_cast<py::ssize_t>(e->gradient.size());
  py::array_t<double> g({n, py::ssize_t{3}});
  double* gp = g.mutable_data();
  for (std::size_t i = 0; i < e->gradient.size(); ++i)
    for (int k = 0; k < 3; ++k) gp[i * 3 + k] = e->gradient[i][k];
  d["gradient"] = g;
  d["hessian"] = hessian ? hessian_csr(e->hessian) : py::object(py::none());
  d["pairs"] = e->pair_count;
  d["max_pdd2_global"] = e->max_pdd2_global;
  d["bounded_pairs"] = e->bounded_pairs;
  if (per_pair) {
    const auto m = static_cast<py::ssize_t>(e->pairs.size());
    py::array_t<std::int64_t> a(m), b(m);
    py::array_t<double> w(m), v(m), en(m);
    for (py::ssize_t j = 0; j < m; ++j) {
      const auto& p = e->pairs[static_cast<std::size_t>(j)];
      a.mutable_data()[j] = static_cast<std::int64_t>(p.a);
      b.mutable_data()[j] = static_cast<std::int64_t>(p.b);
      w.mutable_data()[j] = p.weight;
      v.mutable_data()[j] = p.pdd2_global;
      en.mutable_data()[j] = p.energy;
    }
    d["a"] = a;
    d["b"] = b;
    d["weight"] = w;
    d["pdd2_global"] = v;
    d["pair_energy"] = en;
  }
  py::list skipped;
  for (const auto& s : e->skipped)
    skipped.append(py::make_tuple(py::str(std::string(1, s.mesh)), s.index, py::str(s.reason)));
  d["skipped"] = skipped;
  d["seconds_contacts"] = e->seconds_contacts;
  d["seconds_assembly"] = e->seconds_assembly;
  return d;
}

// Python's names of the library's enums (the keyword values below).
const char* engine_name(pdd::mesh::EnergyEngine e) { return e == pdd::mesh::EnergyEngine::Fast ? "fast" : "reference"; }
const char* weight_name(pdd::mesh::EnergyWeight w) { return w == pdd::mesh::EnergyWeight::Area ? "area" : "unit"; }

// {hessian}, {per_pair}, {engine}, {weight}: ContactEnergyOptions' defaults, filled in by bind_energy.
constexpr const char* kDoc = R"doc(contact_energy(VA, TA, VB=None, TB=None, hessian={hessian}, per_pair={per_pair}, engine='{engine}', weight='{weight}', threads=None, rest_A=None, rest_B=None)

The contact energy of two tetrahedral meshes at their current positions (docs/definitions.md
"Contact energy"; SPEC §12):  E = sum over intersecting element pairs of w_ab * pdd2_global.
Without VB and TB: self-contact of A (element pairs sharing no vertex).

VA, VB     (n, 3) current vertex positions; TA, TB (m, 4) vertex indices.
rest_A/B   (n, 3) rest positions, for the weights w_ab = (V_a V_b)^(1/3) (rest volumes, held
           constant: a simulator passes its rest shape). Default: the positions given, the
           weights of this configuration, which then move with it: the gradient is that E's
           whole gradient (the weights' derivative included; finite differences of E without
           rest_A/B agree with it), the hessian still the Gauss-Newton one at fixed weights.
hessian    also the Gauss-Newton Hessian (positive semi-definite, symmetric).
per_pair   also each pair's a, b, weight, pdd2_global and pair_energy (each certified: no pair
           is then taken at a bound, so where contacts made by rounding were, the gradient and
           hessian are those of their certified planes, a little different).
engine     'fast' (certified doubles) or 'reference' (the exact engine, as for mesh_contacts
           and solve; slow: small meshes).
weight     'area' ((V_a V_b)^(1/3), resolution-independent) or 'unit' (w = 1).
threads    None or 0: all cores; k from 1 to 4096: at most k threads.

Returns a dict: energy (float), gradient ((nA + nB, 3), A's vertices first), hessian
(scipy.sparse.csr_matrix of size 3(nA + nB), row 3v + k for coordinate k of vertex v; None
unless asked), pairs (int), max_pdd2_global (float), bounded_pairs (int: of the pairs, contacts
made by rounding taken at a certified upper bound; 0 with per_pair), skipped (list of (mesh,
index, reason): elements with a non-finite coordinate, at the positions or anywhere in a rest
shape given, or flat), seconds_contacts, seconds_assembly, and with per_pair: a, b, weight,
pdd2_global, pair_energy.
The GIL is released; Ctrl-C stops the call (KeyboardInterrupt). Raises ValueError on bad input
(shapes, indices, options) and where a pair's term w_ab * pdd2_global falls below the double
range (coordinates below ~1e-67: scale them up); OverflowError where E exceeds it (beyond ~1e77).

  >>> import pdd
  >>> VA, TA = pdd.read_mesh("fixtures/meshes/tiny-a.msh")
  >>> VB, TB = pdd.read_mesh("fixtures/meshes/tiny-b.msh")
  >>> e = pdd.contact_energy(VA, TA, VB, TB)
  >>> e["pairs"], f"{e['energy']:.6g}", e["gradient"].shape, e["skipped"], e["hessian"]
  (51, '0.0137533', (28, 3), [], None)
)doc";

}  // namespace

void bind_energy(py::module_& m) {
  // Every default from pdd::mesh::ContactEnergyOptions, in the signature and in the docstring.
  const pdd::mesh::ContactEnergyOptions d;
  static const std::string doc = [&] {
    std::string s = kDoc;
    const std::pair<std::string, std::string> values[] = {
        {"{hessian}", d.hessian ? "True" : "False"}, {"{per_pair}", d.per_pair ? "True" : "False"},
        {"{engine}", engine_name(d.engine)}, {"{weight}", weight_name(d.weight)}};
    for (const auto& [key, value] : values)
      for (std::size_t at; (at = s.find(key)) != std::string::npos;) s.replace(at, key.size(), value);
    return s;
  }();
  m.def("contact_energy", &contact_energy, doc.c_str(), py::arg("VA"), py::arg("TA"), py::arg("VB") = py::none(),
        py::arg("TB") = py::none(), py::arg("hessian") = d.hessian, py::arg("per_pair") = d.per_pair,
        py::arg("engine") = engine_name(d.engine), py::arg("weight") = weight_name(d.weight), py::arg("threads") = py::none(),
        py::arg("rest_A") = py::none(), py::arg("rest_B") = py::none());
}

}  // namespace pdd_python
