// common.cpp — the shared helpers of common.h.
#include "common.h"

#include <pybind11/numpy.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>

namespace pdd_python {

std::string short_repr(py::handle o) {
  std::string s = py::repr(o).cast<std::string>();
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

[[noreturn]] void value_error(const std::string& msg) { throw py::value_error(msg); }

std::string shape_str(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

bool is_numpy_bool(py::handle x) { return py::isinstance(x, cached->numpy_bool); }

std::string where(const char* which, std::size_t i, std::size_t k) {
  return std::string(which) + "[" + std::to_string(i) + "][" + std::to_string(k) + "]";
}

double coordinate(py::handle x, const char* which, std::size_t i, std::size_t k) {
  if (PyFloat_CheckExact(x.ptr())) return PyFloat_AS_DOUBLE(x.ptr());
  if (PyBool_Check(x.ptr()) || PyUnicode_Check(x.ptr()) || PyBytes_Check(x.ptr()) ||
      PyComplex_Check(x.ptr()) || x.is_none() || is_numpy_bool(x))
    value_error(where(which, i, k) + " is not a real number: " + short_repr(x));
  // An integer of any kind (int, numpy.int64, numpy.uint64, anything with __index__) is read
  // through its exact Python int: numpy compares its own integers with a float after rounding
  // them to a double, so np.int64(2**53 + 1) == 2.0**53 would pass the check below.
  py::object as_int;
  if (!PyLong_Check(x.ptr()) && PyIndex_Check(x.ptr())) {
    PyObject* i = PyNumber_Index(x.ptr());
    if (!i) throw py::error_already_set();
    as_int = py::reinterpret_steal<py::object>(i);
    x = as_int;
  }
  PyObject* f = PyNumber_Float(x.ptr());
  if (!f) {
    if (PyErr_ExceptionMatches(PyExc_OverflowError)) {  // e.g. 10**400: beyond the double range
      PyErr_Clear();
      const int negative = PyObject_RichCompareBool(x.ptr(), py::int_(0).ptr(), Py_LT);
      if (negative < 0) throw py::error_already_set();
      return negative ? -std::numeric_limits<double>::infinity()
                      : std::numeric_limits<double>::infinity();
    }
    PyErr_Clear();
    value_error(where(which, i, k) + " is not a real number: " + short_repr(x));
  }
  py::object fo = py::reinterpret_steal<py::object>(f);
  const double v = PyFloat_AS_DOUBLE(f);
  if (PyFloat_Check(x.ptr()) || std::isnan(v)) return v;  // float subclasses; NaN-valued input
  const int same = PyObject_RichCompareBool(x.ptr(), f, Py_EQ);
  if (same < 0) throw py::error_already_set();
  if (!same)
    value_error(where(which, i, k) + " = " + short_repr(x) +
                " is not exactly a double: pdd reads coordinates as IEEE doubles "
                "(docs/definitions.md §1); "
                "round it yourself with float() if that is what you mean");
  return v;
}

namespace {
// "[i][j]..." of the flat C-order index `flat` in an array of `shape`.
std::string index_str(std::size_t flat, const py::array& a) {
  std::string s;
  for (py::ssize_t d = a.ndim() - 1; d >= 0; --d) {
    const auto n = static_cast<std::size_t>(a.shape(d));
    s = "[" + std::to_string(flat % n) + "]" + s;
    flat /= n;
  }
  return s;
}

template <class I>
void check_exact(const py::array& a, const char* which) {
  const auto d = py::array_t<I, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!d) throw py::error_already_set();
  // 2^63 and 2^64 as doubles: a value that rounds to one of them is out of I's range, hence
  // not the double it would become.
  const double top = std::is_signed_v<I> ? 9223372036854775808.0 : 18446744073709551616.0;
  for (py::ssize_t k = 0; k < d.size(); ++k) {
    const I v = d.data()[k];
    const double x = static_cast<double>(v);
    if (x < top && (x >= -top || !std::is_signed_v<I>) && static_cast<I>(x) == v) continue;
    value_error(std::string(which) + index_str(static_cast<std::size_t>(k), a) + " = " + std::to_string(v) +
                " is not exactly a double: pdd reads coordinates as IEEE doubles "
                "(docs/definitions.md §1); round it yourself with float() if that is what you mean");
  }
}
}  // namespace

void check_integers_exact(const py::array& a, const char* which) {
  const char kind = a.dtype().kind();
  if (kind == 'i') check_exact<std::int64_t>(a, which);
  if (kind == 'u') check_exact<std::uint64_t>(a, which);
}

bool is_sequence(py::handle o) {
  return PySequence_Check(o.ptr()) && !PyUnicode_Check(o.ptr()) && !PyBytes_Check(o.ptr()) &&
         !PyByteArray_Check(o.ptr());
}

pdd::TetVertices tetrahedron(py::handle obj, const char* which) {
  const char* w = which;
  auto shape_msg = [&] { return std::string(w) + " must be 4 vertices of 3 coordinates (shape (4, 3))"; };
  py::object o = py::reinterpret_borrow<py::object>(obj);
  if (py::isinstance<py::array>(o)) {
    py::array a = o.cast<py::array>();
    if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 3)
      value_error(shape_msg() + "; got an array of shape " + shape_str(a));
    if (a.dtype().is(py::dtype::of<double>())) {  // float64: read as it is
      const auto d = a.cast<py::array_t<double>>().unchecked<2>();
      pdd::TetVertices t{};
      for (py::ssize_t i = 0; i < 4; ++i)
        for (py::ssize_t k = 0; k < 3; ++k) t[i][k] = d(i, k);
      return t;
    }
    o = a.attr("tolist")();  // numpy scalars become Python numbers of the same value
  }
  if (!is_sequence(o)) value_error(shape_msg() + "; got " + short_repr(o));
  py::sequence rows = o.cast<py::sequence>();
  if (rows.size() != 4)
    value_error(shape_msg() + "; got " + std::to_string(rows.size()) + " vertices");
  pdd::TetVertices t{};
  for (std::size_t i = 0; i < 4; ++i) {
    py::object row = rows[i];
    auto wi = [&] { return std::string(w) + "[" + std::to_string(i) + "]"; };
    if (!is_sequence(row)) value_error(wi() + " must be 3 coordinates; got " + short_repr(row));
    py::sequence r = row.cast<py::sequence>();
    if (r.size() != 3)
      value_error(wi() + " must be 3 coordinates; got " + std::to_string(r.size()));
    for (std::size_t k = 0; k < 3; ++k) t[i][k] = coordinate(r[k], which, i, k);
  }
  return t;
}

py::object exact_integer(const mpz_class& z) {
  const std::string hex = z.get_str(16);
  PyObject* v = PyLong_FromString(hex.c_str(), nullptr, 16);
  if (!v) throw py::error_already_set();
  return py::reinterpret_steal<py::object>(v);
}

py::object fraction(const pdd::Rational& q) {
  return cached->Fraction(exact_integer(q.get_num()), exact_integer(q.get_den()));
}

py::object number(double x) { return py::float_(x); }
py::object number(const pdd::Rational& q) { return fraction(q); }

py::object label(const std::optional<pdd::DirectionLabel>& l) {
  return l ? py::object(py::str(l->str())) : py::object(py::none());
}

std::string text_arg(py::handle o, const char* what) {
  if (!PyUnicode_Check(o.ptr()))
    value_error(std::string(what) + " must be a str; got " + short_repr(o));
  return o.cast<std::string>();
}

bool bool_arg(py::handle o, const char* what) {
  if (PyBool_Check(o.ptr())) return o.ptr() == Py_True;
  // numpy's scalar bool (its type is named numpy.bool_, or numpy.bool from numpy 2): exactly two values
  const std::string type = Py_TYPE(o.ptr())->tp_name;
  if (type == "numpy.bool_" || type == "numpy.bool") return PyObject_IsTrue(o.ptr()) == 1;
  value_error(std::string(what) + " must be True or False; got " + short_repr(o));
}

void check_gradient_needs_global(bool global, bool gradient) {
  if (gradient && !global)
    value_error("gradient=True needs with_global=True (it is the gradient of pdd2_global)");
}

std::string path_arg(py::handle path_like) {
  try {
    return cached->fsdecode(path_like).cast<std::string>();
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_TypeError)) throw;
    value_error("path must be a str, bytes or os.PathLike; got " + short_repr(path_like));
  }
}

// Vertices: (n, 3) real numbers -> the mesh's vertices (float64, as numpy.asarray would convert).
std::vector<pdd::Vec3d> mesh_vertices(py::handle obj, const char* which) {
  py::array a = cached->asarray(obj);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    value_error(std::string(which) + " must be an array of real numbers of shape (n, 3); got dtype " +
                py::str(a.dtype()).cast<std::string>());
  if (a.ndim() != 2 || a.shape(1) != 3)
    value_error(std::string(which) + " must have shape (n, 3); got " + shape_str(a));
  check_integers_exact(a, which);
  const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!d) throw py::error_already_set();
  std::vector<pdd::Vec3d> out(static_cast<std::size_t>(a.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int k = 0; k < 3; ++k) out[i][k] = d.data()[i * 3 + k];
  return out;
}

std::map<std::size_t, std::string> vertex_sources(const std::vector<pdd::Vec3d>& vertices, const char* which) {
  std::map<std::size_t, std::string> out;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    if (!(std::isfinite(vertices[i][0]) && std::isfinite(vertices[i][1]) && std::isfinite(vertices[i][2])))
      out.emplace_hint(out.end(), i, std::string(which) + "[" + std::to_string(i) + "]");
  return out;
}

// Tetrahedra: (m, 4) integers -> vertex indices. Indices past the end are left to the library
// (its message); a negative one has no size_t, so it is reported here in the same words.
std::vector<std::array<std::size_t, 4>> mesh_tets(py::handle obj, const char* which, char mesh,
                                                  std::size_t vertices) {
  py::array a = cached->asarray(obj);
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u')
    value_error(std::string(which) + " must be an array of integers (vertex indices) of shape (m, 4); got dtype " +
                py::str(a.dtype()).cast<std::string>());
  if (a.ndim() != 2 || a.shape(1) != 4)
    value_error(std::string(which) + " must have shape (m, 4); got " + shape_str(a));
  std::vector<std::array<std::size_t, 4>> out(static_cast<std::size_t>(a.shape(0)));
  if (kind == 'u') {
    const auto d = py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!d) throw py::error_already_set();
    for (std::size_t i = 0; i < out.size(); ++i)
      for (int k = 0; k < 4; ++k) out[i][k] = static_cast<std::size_t>(d.data()[i * 4 + k]);
    return out;
  }
  const auto d = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!d) throw py::error_already_set();
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int k = 0; k < 4; ++k) {
      const std::int64_t v = d.data()[i * 4 + k];
      if (v < 0)
        value_error("element " + std::to_string(i) + " of mesh " + mesh + " refers to vertex " +
                    std::to_string(v) + ", but the mesh has " + std::to_string(vertices) + " vertices");
      out[i][k] = static_cast<std::size_t>(v);
    }
  return out;
}

}  // namespace pdd_python
