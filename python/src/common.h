// common.h — internal to python/src: what every file of the module `pdd` shares: reading
// arguments (a tetrahedron, coordinates, str/bool/path arguments; ValueError naming the
// argument otherwise), numbers out (fast: float, reference: fractions.Fraction, exactly), one
// record as a dict, and the bind_* functions each file registers its functions with.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <type_traits>

#include "pdd/pdd.h"

namespace pdd_python {

namespace py = pybind11;

// The functions of each file, registered on the module by PYBIND11_MODULE (module.cpp).
void bind_pdd(py::module_& m);   // pdd.cpp:  solve, solve_batch (<pdd/pdd.h>)
void bind_io(py::module_& m);    // io.cpp:   read_fixtures (pdd::io's fixture reader)
void bind_mesh(py::module_& m);  // mesh.cpp: mesh_contacts, read_mesh, resolve (<pdd/mesh.h>)
void bind_energy(py::module_& m);  // energy.cpp: contact_energy (<pdd/mesh.h>)

// ---------------------------------------------------------------------------------------------
// Input: one tetrahedron from anything array-like 4 x 3.

// Python's repr of `o`, shortened for a message.
std::string short_repr(py::handle o);

[[noreturn]] void value_error(const std::string& msg);

// An array's shape as Python writes it: "(4,)", "(2, 3)".
std::string shape_str(const py::array& a);

// Python objects the module uses on every call, looked up once when the module is imported.
// Not function-local statics: their first use can happen in two threads at once, and a C++
// static's initialisation guard, held across an import that lets the GIL go, deadlocks against
// a thread that holds the GIL and waits for the guard. Leaked on purpose: released after the
// interpreter is gone otherwise.
struct Cached {
  py::object Fraction;     // fractions.Fraction
  py::object numpy_bool;   // numpy.bool_
  py::object asarray;      // numpy.asarray
  py::object fsdecode;     // os.fsdecode
};
inline const Cached* cached = nullptr;  // set by PYBIND11_MODULE (module.cpp)

bool is_numpy_bool(py::handle x);

// One coordinate. Accepted: float, int, and any real number type whose value is exactly a
// double (fractions.Fraction, decimal.Decimal, numpy scalars). Refused with ValueError: str,
// bytes, bool, complex, None, anything that is not a number, and a number that is not exactly
// a double (the engines read IEEE doubles, definitions §1; rounding it silently would solve another
// pair). A number beyond the double range becomes +-inf, which the engines reject as
// non-finite, as `pdd solve` does with 1e999 in a file.
double coordinate(py::handle x, const char* which, std::size_t i, std::size_t k);
// The same rule for a numpy array of coordinates: an integer array (dtype kind 'i' or 'u') whose
// element is not exactly a double raises ValueError naming it ("VA[3][0] = 9007199254740993 is
// not exactly a double: ..."); any other array passes.
void check_integers_exact(const py::array& a, const char* which);
// A mesh's arrays, the rule of every mesh call (mesh_contacts, resolve, contact_energy):
// vertices (n, 3) real numbers -> float64, an integer array checked by check_integers_exact;
// tetrahedra (m, 4) integers -> vertex indices, a negative one raising ValueError in the
// library's words ("element i of mesh A refers to vertex -1, ..."), those past the end left to
// the library.
std::vector<pdd::Vec3d> mesh_vertices(py::handle obj, const char* which);
// pdd::mesh::Mesh::vertex_sources of an array's rows, for the message that skips an element
// with a non-finite vertex: "VA[4]" for each row of `vertices` (read from the argument `which`)
// with a non-finite coordinate.
std::map<std::size_t, std::string> vertex_sources(const std::vector<pdd::Vec3d>& vertices, const char* which);
std::vector<std::array<std::size_t, 4>> mesh_tets(py::handle obj, const char* which, char mesh,
                                                  std::size_t vertices);
// The name of a coordinate in messages, "A[i][k]" (built only for a message).
std::string where(const char* which, std::size_t i, std::size_t k);

// A sequence that is not a string: list, tuple, numpy array, any other sequence.
bool is_sequence(py::handle o);

pdd::TetVertices tetrahedron(py::handle obj, const char* which);

// ---------------------------------------------------------------------------------------------
// Output: one definitions §6 record as a dict, keys in the order of `pdd solve`'s JSON records.

py::object exact_integer(const mpz_class& z);

// GMP's rational (lowest terms, positive denominator) as fractions.Fraction, exactly.
py::object fraction(const pdd::Rational& q);

py::object number(double x);
py::object number(const pdd::Rational& q);

py::object label(const std::optional<pdd::DirectionLabel>& l);

template <class R>
py::list positions(const pdd::Positions<R>& q) {
  py::list out;
  for (const auto& v : q) {
    py::list p;
    for (const auto& c : v) p.append(number(c));
    out.append(p);
  }
  return out;
}

// pdd2_global_grad: 8 x [x, y, z], A's vertices first.
template <class R>
py::list gradient_list(const pdd::PairGradient<R>& g) {
  py::list out;
  for (const auto& v : g) {
    py::list p;
    for (const auto& c : v) p.append(number(c));
    out.append(p);
  }
  return out;
}

// The keys of the values in `variants` (the bits of pdd::mesh::Variant: bit k < kValueCount the
// value kValueKeys[k] with its label, q1_A and q1_B with pdd2; bit kValueCount definitions §9's
// keys), as `pdd solve --variants` writes them (io::asked_keys). The key pdd2_global_grad is
// there when the result has the gradient (gradient=True).
template <class R>
py::dict record(const pdd::PairResult<R>& r, unsigned variants) {
  py::dict d;
  d["name"] = r.name;
  if (r.error) {  // as `pdd solve` writes it: the name and the reason, no values
    d["error"] = *r.error;
    return d;
  }
  d["intersecting"] = r.intersecting;
  for (std::size_t k = 0; k < pdd::kValueCount; ++k)
    if (variants >> k & 1u) d[pdd::kValueKeys[k]] = number(pdd::record_value(r, k));
  for (std::size_t k = 0; k < pdd::kValueCount; ++k)
    if ((variants >> k & 1u) && pdd::kLabelOfValue[k] >= 0)
      d[pdd::kLabelKeys[pdd::kLabelOfValue[k]]] = label(pdd::record_label(r, pdd::kLabelOfValue[k]));
  if (variants >> 3 & 1u) {  // pdd2 (kValueKeys[3])
    d["q1_A"] = positions(r.q1_A);
    d["q1_B"] = positions(r.q1_B);
  }
  d["error"] = py::none();
  if (!(variants >> pdd::kValueCount & 1u)) return d;
  // definitions §9, in the order `pdd solve` writes them; None where the fast engine declined it
  if (r.pdd2_global_error) {
    for (const char* key : {"pdd2_global", "pdd2_global_normal", "q1_A_global", "q1_B_global"}) d[key] = py::none();
    d["pdd2_global_error"] = *r.pdd2_global_error;
    if (r.pdd2_global_grad) d["pdd2_global_grad"] = py::none();
    return d;
  }
  d["pdd2_global"] = number(r.pdd2_global);
  if (r.pdd2_global_normal) {
    const auto& n = *r.pdd2_global_normal;
    py::list normal;
    for (int c = 0; c < 3; ++c) normal.append(number(n[c]));
    d["pdd2_global_normal"] = normal;
  } else {
    d["pdd2_global_normal"] = py::none();
  }
  d["q1_A_global"] = positions(r.q1_A_global);
  d["q1_B_global"] = positions(r.q1_B_global);
  if (r.pdd2_global_lower) d["pdd2_global_lower"] = number(*r.pdd2_global_lower);
  if constexpr (std::is_same_v<R, double>) d["pdd2_global_error"] = py::none();
  if (r.pdd2_global_grad) d["pdd2_global_grad"] = gradient_list(*r.pdd2_global_grad);
  return d;
}

// ---------------------------------------------------------------------------------------------
// Arguments

// A str argument; ValueError naming it otherwise.
std::string text_arg(py::handle o, const char* what);

// A bool argument (True or False, or a numpy.bool_ as an array gives one); ValueError naming it otherwise.
bool bool_arg(py::handle o, const char* what);

// with_global=False with gradient=True: the gradient is that of pdd2_global, which is not computed.
void check_gradient_needs_global(bool global, bool gradient);

// A path argument (str, bytes, os.PathLike) as the C++ readers take it.
std::string path_arg(py::handle path_like);

}  // namespace pdd_python
