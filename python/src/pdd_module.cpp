// pdd_module.cpp — the Python module `pdd` (pybind11): both engines from Python.
//
//   pdd.solve(A, B, engine="fast", formulation="reduced", name="")  -> dict (SPEC §6 record)
//   pdd.solve_batch(A, B, threads=None)                            -> dict of numpy arrays
//   pdd.read_fixtures(path)                                        -> list of dicts
//
// Built only on the public C++ interface (<pdd/pdd.h>: pdd::fast, pdd::reference) and on
// compare/'s fixture reader (the one `pdd solve` uses, so messages are the CLI's). Numbers:
// the fast engine's are Python floats, the reference engine's fractions.Fraction, built from
// GMP's integers exactly (never through a float). Every engine call runs with the GIL released.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <tbb/task_arena.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pdd/compare/fixture_io.h"
#include "pdd/pdd.h"

namespace py = pybind11;

namespace {

// ---------------------------------------------------------------------------------------------
// Input: one tetrahedron from anything array-like 4 x 3.

// Python's repr of `o`, shortened for a message.
std::string short_repr(py::handle o) {
  std::string s = py::repr(o).cast<std::string>();
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

[[noreturn]] void value_error(const std::string& msg) { throw py::value_error(msg); }

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
const Cached* cached = nullptr;

bool is_numpy_bool(py::handle x) { return py::isinstance(x, cached->numpy_bool); }

// One coordinate. Accepted: float, int, and any real number type whose value is exactly a
// double (fractions.Fraction, decimal.Decimal, numpy scalars). Refused with ValueError: str,
// bytes, bool, complex, None, anything that is not a number, and a number that is not exactly
// a double (the engines read IEEE doubles, SPEC §1; rounding it silently would solve another
// pair). A number beyond the double range becomes +-inf, which the engines reject as
// non-finite, as `pdd solve` does with 1e999 in a file.
// The name of a coordinate in messages, "A[i][k]" (built only for a message).
std::string where(const char* which, std::size_t i, std::size_t k) {
  return std::string(which) + "[" + std::to_string(i) + "][" + std::to_string(k) + "]";
}

double coordinate(py::handle x, const char* which, std::size_t i, std::size_t k) {
  if (PyFloat_CheckExact(x.ptr())) return PyFloat_AS_DOUBLE(x.ptr());
  if (PyBool_Check(x.ptr()) || PyUnicode_Check(x.ptr()) || PyBytes_Check(x.ptr()) ||
      PyComplex_Check(x.ptr()) || x.is_none() || is_numpy_bool(x))
    value_error(where(which, i, k) + " is not a real number: " + short_repr(x));
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
                " is not exactly a double: pdd reads coordinates as IEEE doubles (SPEC §1); "
                "round it yourself with float() if that is what you mean");
  return v;
}

// A sequence that is not a string: list, tuple, numpy array, any other sequence.
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
    if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 3) {
      std::string shape = "(";
      for (py::ssize_t d = 0; d < a.ndim(); ++d)
        shape += (d ? ", " : "") + std::to_string(a.shape(d));
      value_error(shape_msg() + "; got an array of shape " + shape + (a.ndim() == 1 ? ",)" : ")"));
    }
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

// ---------------------------------------------------------------------------------------------
// Output: one SPEC §6 record as a dict, keys in the order of `pdd solve`'s JSON records.

py::object exact_integer(const mpz_class& z) {
  const std::string hex = z.get_str(16);
  PyObject* v = PyLong_FromString(hex.c_str(), nullptr, 16);
  if (!v) throw py::error_already_set();
  return py::reinterpret_steal<py::object>(v);
}

// GMP's rational (lowest terms, positive denominator) as fractions.Fraction, exactly.
py::object fraction(const pdd::Rational& q) {
  return cached->Fraction(exact_integer(q.get_num()), exact_integer(q.get_den()));
}

py::object number(double x) { return py::float_(x); }
py::object number(const pdd::Rational& q) { return fraction(q); }

py::object label(const std::optional<pdd::DirectionLabel>& l) {
  return l ? py::object(py::str(l->str())) : py::object(py::none());
}

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

template <class R>
py::dict record(const pdd::PairResult<R>& r) {
  py::dict d;
  d["name"] = r.name;
  if (r.error) {  // as `pdd solve` writes it: the name and the reason, no values
    d["error"] = *r.error;
    return d;
  }
  d["intersecting"] = r.intersecting;
  for (std::size_t k = 0; k < pdd::kValueCount; ++k) d[pdd::kValueKeys[k]] = number(pdd::record_value(r, k));
  for (std::size_t k = 0; k < pdd::kLabelCount; ++k) d[pdd::kLabelKeys[k]] = label(pdd::record_label(r, k));
  d["q1_A"] = positions(r.q1_A);
  d["q1_B"] = positions(r.q1_B);
  d["error"] = py::none();
  return d;
}

// ---------------------------------------------------------------------------------------------
// pdd.solve

// A str argument; ValueError naming it otherwise.
std::string text_arg(py::handle o, const char* what) {
  if (!PyUnicode_Check(o.ptr()))
    value_error(std::string(what) + " must be a str; got " + short_repr(o));
  return o.cast<std::string>();
}

py::dict solve(py::handle A, py::handle B, py::handle engine_arg, py::handle formulation_arg,
               py::handle name_arg) {
  const std::string engine = text_arg(engine_arg, "engine");
  const std::string formulation = text_arg(formulation_arg, "formulation");
  const std::string name = text_arg(name_arg, "name");
  if (engine != "fast" && engine != "reference")
    value_error("engine must be 'fast' or 'reference'; got '" + engine + "'");
  if (formulation != "reduced" && formulation != "full")
    value_error("formulation must be 'reduced' or 'full'; got '" + formulation + "'");
  pdd::TetPair pair{name, {}, tetrahedron(A, "A"), tetrahedron(B, "B")};
  if (engine == "fast") {
    pdd::PairResult<double> r;
    {
      py::gil_scoped_release release;
      r = pdd::fast::solve_pair(pair);
    }
    r.name = name;
    return record(r);
  }
  const auto f = formulation == "full" ? pdd::QpFormulation::Full : pdd::QpFormulation::Reduced;
  pdd::PairResult<pdd::Rational> r;
  {
    py::gil_scoped_release release;
    try {
      r = pdd::reference::solve_pair(pair, f);
    } catch (const std::exception& ex) {  // an engine invariant failed: reported as `pdd solve` does
      r = {};
      r.error = std::string("internal error in the reference engine: ") + ex.what();
    }
  }
  r.name = name;
  return record(r);
}

// ---------------------------------------------------------------------------------------------
// pdd.solve_batch

constexpr const char* kValueKeys[7] = {"rigid_pd2",   "eq11_pd2",    "pdd2_static", "pdd2",
                                       "pdd2_relaxed", "pdd2_accel1", "pdd2_accel6"};
constexpr const char* kLabelKeys[4] = {"rigid_dir", "pdd2_static_dir", "pdd2_dir",
                                       "pdd2_relaxed_dir"};
constexpr int kLabelChars = 8;  // the longest label, "EE:a:b:+"

// (N, 4, 3) float64, C order; ValueError naming the problem otherwise.
py::array_t<double, py::array::c_style> batch_input(py::handle obj, const char* which) {
  py::array a = cached->asarray(obj);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    value_error(std::string(which) + " must be an array of real numbers of shape (N, 4, 3); got dtype " +
                py::str(a.dtype()).cast<std::string>());
  if (a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 3) {
    std::string shape = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(a.shape(d));
    value_error(std::string(which) + " must have shape (N, 4, 3); got " + shape +
                (a.ndim() == 1 ? ",)" : ")"));
  }
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
}

py::dict solve_batch(py::handle A_in, py::handle B_in, py::handle threads_arg) {
  std::optional<int> threads;
  if (!threads_arg.is_none()) {
    const std::string msg = "threads must be a positive int, or None for all cores; got ";
    PyObject* index = PyNumber_Index(threads_arg.ptr());  // int, numpy integers; not float, bool
    if (!index || PyBool_Check(threads_arg.ptr())) {
      PyErr_Clear();
      Py_XDECREF(index);
      value_error(msg + short_repr(threads_arg));
    }
    const long t = PyLong_AsLong(index);
    Py_DECREF(index);
    if (t == -1 && PyErr_Occurred()) PyErr_Clear();
    if (t < 1 || t > 1 << 16) value_error(msg + short_repr(threads_arg));
    threads = static_cast<int>(t);
  }
  const auto A = batch_input(A_in, "A");
  const auto B = batch_input(B_in, "B");
  if (!A || !B) throw py::error_already_set();
  if (A.shape(0) != B.shape(0))
    value_error("A and B must hold the same number of pairs; got " + std::to_string(A.shape(0)) +
                " and " + std::to_string(B.shape(0)));
  const std::size_t n = static_cast<std::size_t>(A.shape(0));

  // Outputs, allocated with the GIL held, filled without it.
  const py::ssize_t N = static_cast<py::ssize_t>(n);
  py::array_t<bool> intersecting(N);
  std::vector<py::array_t<double>> values;
  for (int v = 0; v < 7; ++v) values.emplace_back(N);
  std::vector<py::array> labels;
  for (int l = 0; l < 4; ++l) {
    labels.emplace_back(py::dtype("<U" + std::to_string(kLabelChars)), std::vector<py::ssize_t>{N});
    std::memset(labels.back().mutable_data(), 0, n * kLabelChars * sizeof(std::uint32_t));
  }
  py::array_t<double> q1_A({N, py::ssize_t{4}, py::ssize_t{3}});
  py::array_t<double> q1_B({N, py::ssize_t{4}, py::ssize_t{3}});

  const double* a = A.data();
  const double* b = B.data();
  bool* out_intersecting = intersecting.mutable_data();
  double* out_values[7];
  for (int v = 0; v < 7; ++v) out_values[v] = values[v].mutable_data();
  std::uint32_t* out_labels[4];
  for (int l = 0; l < 4; ++l) out_labels[l] = static_cast<std::uint32_t*>(labels[l].mutable_data());
  double* out_qa = q1_A.mutable_data();
  double* out_qb = q1_B.mutable_data();

  std::vector<std::pair<std::size_t, std::string>> errors;
  std::size_t slow_paths = 0;
  {
    py::gil_scoped_release release;
    // Chunks bound the memory of the engine's records; every chunk uses all cores (or the
    // arena's `threads`). Results are those of solve_pair one pair at a time, bit for bit.
    constexpr std::size_t kChunk = 1 << 15;
    auto run = [&] {
      std::vector<pdd::TetPair> chunk;
      for (std::size_t first = 0; first < n; first += kChunk) {
        const std::size_t m = std::min(kChunk, n - first);
        chunk.resize(m);
        for (std::size_t k = 0; k < m; ++k)
          for (int i = 0; i < 4; ++i)
            for (int c = 0; c < 3; ++c) {
              chunk[k].A[i][c] = a[((first + k) * 4 + i) * 3 + c];
              chunk[k].B[i][c] = b[((first + k) * 4 + i) * 3 + c];
            }
        std::size_t slow = 0;
        const std::vector<pdd::PairResult<double>> res = pdd::fast::solve_batch(chunk, &slow);
        slow_paths += slow;
        for (std::size_t k = 0; k < m; ++k) {
          const std::size_t j = first + k;
          const pdd::PairResult<double>& r = res[k];
          const double nan = std::numeric_limits<double>::quiet_NaN();
          if (r.error) errors.emplace_back(j, *r.error);
          out_intersecting[j] = !r.error && r.intersecting;
          const double vals[7] = {r.rigid_pd2, r.eq11_pd2,     r.pdd2_static, r.pdd2,
                                  r.pdd2_relaxed, r.pdd2_accel1, r.pdd2_accel6};
          for (int v = 0; v < 7; ++v) out_values[v][j] = r.error ? nan : vals[v];
          const std::optional<pdd::DirectionLabel>* ls[4] = {&r.rigid_dir, &r.pdd2_static_dir,
                                                             &r.pdd2_dir, &r.pdd2_relaxed_dir};
          for (int l = 0; l < 4; ++l)
            if (!r.error && *ls[l]) {
              const std::string s = (*ls[l])->str();
              for (std::size_t c = 0; c < s.size() && c < std::size_t(kLabelChars); ++c)
                out_labels[l][j * kLabelChars + c] = static_cast<unsigned char>(s[c]);
            }
          for (int i = 0; i < 4; ++i)
            for (int c = 0; c < 3; ++c) {
              out_qa[(j * 4 + i) * 3 + c] = r.error ? nan : r.q1_A[i][c];
              out_qb[(j * 4 + i) * 3 + c] = r.error ? nan : r.q1_B[i][c];
            }
        }
      }
    };
    if (threads) {
      tbb::task_arena arena(*threads);
      arena.execute(run);
    } else {
      run();
    }
  }

  py::dict d;
  d["intersecting"] = intersecting;
  for (int v = 0; v < 7; ++v) d[kValueKeys[v]] = values[v];
  for (int l = 0; l < 4; ++l) d[kLabelKeys[l]] = labels[l];
  d["q1_A"] = q1_A;
  d["q1_B"] = q1_B;
  py::list error_list(N);
  for (py::ssize_t j = 0; j < N; ++j) error_list[j] = py::none();
  for (const auto& [j, msg] : errors) error_list[j] = py::str(msg);
  d["error"] = error_list;
  d["slow_paths"] = slow_paths;
  return d;
}

// ---------------------------------------------------------------------------------------------
// pdd.read_fixtures

py::list read_fixtures(py::handle path_like) {
  std::string path;
  try {
    path = cached->fsdecode(path_like).cast<std::string>();
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_TypeError)) throw;
    value_error("path must be a str, bytes or os.PathLike; got " + short_repr(path_like));
  }
  pdd::compare::FixtureFile file;
  {
    py::gil_scoped_release release;
    file = pdd::compare::read_fixture_file(path);
  }
  if (file.error) value_error(*file.error);
  py::list out;
  for (const auto& e : file.entries) {
    py::dict d;
    d["name"] = e.pair.name;
    py::list tags;
    for (const auto& t : e.pair.tags) tags.append(py::str(t));
    d["tags"] = tags;
    auto tet = [&](const pdd::TetVertices& t) -> py::object {
      if (e.error) return py::none();
      py::list rows;
      for (const auto& v : t) {
        py::list row;
        for (double c : v) row.append(py::float_(c));
        rows.append(row);
      }
      return rows;
    };
    d["A"] = tet(e.pair.A);
    d["B"] = tet(e.pair.B);
    d["error"] = e.error ? py::object(py::str(*e.error)) : py::object(py::none());
    out.append(d);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Docstrings: help(pdd), help(pdd.solve) read like the README.

constexpr const char* kModuleDoc = R"doc(Penetration depth between two tetrahedra (pdd), from Python.

Two senses of depth (SPEC.md; Kim & Kim, "A Penetration Metric for Deforming Tetrahedra
using Object Norm"):
  PD    the rigid penetration depth: the shortest translation of B that leaves the
        interiors of A and B disjoint;
  PD_d  the deformable penetration depth: the smallest object-norm cost (mean squared
        displacement) of deforming both tetrahedra until a plane separates them.
Every value is SQUARED (rigid_pd2 = PD², pdd2 = PD_d², ...), which keeps it rational.

Two engines:
  "fast"       doubles, certified: every value within 1e-9 relative of the exact one
               (0 exactly when it is 0), labels within that of the exact minimum (SPEC §8);
  "reference"  exact: every value a fractions.Fraction (CGAL, GMP); about 0.1 s a pair.

Functions:
  solve(A, B, engine="fast", formulation="reduced", name="")  one pair -> dict
  solve_batch(A, B, threads=None)      (N, 4, 3) numpy arrays, fast engine, all cores
  read_fixtures(path)                  a fixture file (fixtures/*.json) -> list of dicts

Example:
  >>> import pdd
  >>> A = [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]]
  >>> B = [[2, 2, 2], [2.5, 2, 2], [2, 2.5, 2], [2, 2, 2.5]]
  >>> r = pdd.solve(A, B, engine="reference")
  >>> r["rigid_pd2"], r["eq11_pd2"], r["pdd2"], r["pdd2_dir"]
  (Fraction(16, 3), Fraction(1, 12), Fraction(4, 5), 'VF:0')

KEYS is the tuple of a record's keys, in the order `pdd solve` writes them.
)doc";

constexpr const char* kSolveDoc = R"doc(solve(A, B, engine='fast', formulation='reduced', name='')
--

One pair -> dict: every SPEC §6 quantity, as `pdd solve` writes it (one JSON record).

A, B     the tetrahedra: 4 vertices x 3 coordinates, anything array-like (nested lists,
         tuples, a numpy array of shape (4, 3)). A is the paper's T1 (static in case 1), B is
         T2. Coordinates are IEEE doubles (SPEC §1): floats, ints, or any number (Fraction,
         Decimal, numpy scalar) whose value is exactly a double; anything else raises
         ValueError naming the coordinate. Vertex order and orientation are free.
engine   "fast" (doubles, certified to SPEC §8) or "reference" (exact rationals).
formulation  the reference engine's per-direction QP: "reduced" (SPEC §5's 9-variable form,
         about 7x faster) or "full" (the paper's 27 variables); both give the same exact
         result. Ignored by the fast engine.
name     copied to the record's "name".

Returns a dict with the keys of `pdd solve`'s JSON records (pdd.KEYS), in that order:
  name          the name given
  intersecting  whether the interiors intersect (touching is not intersecting)
  rigid_pd2     PD², through the Minkowski difference A (+) (-B)
  eq11_pd2      the paper's eq. 11 value squared (its appendix claims it equals PD;
                it does not always)
  pdd2_static   PD_d², A static and B deforming (paper case 1)
  pdd2          PD_d², both deforming (paper case 2)
  pdd2_relaxed  case 2 with every constraint an inequality
  pdd2_accel1, pdd2_accel6   case 2 on the 1 or 6 candidates of smallest rigid depth
                (paper case 3)
  rigid_dir, pdd2_static_dir, pdd2_dir, pdd2_relaxed_dir   the candidate separating
                direction attaining each minimum, a str: "FV:i" (face of A opposite s_i),
                "VF:j" (face of B opposite r_j), "EE:a:b" (edge a of A, edge b of B;
                ":+"/":-" for the two orientations of an undecidable edge pair);
                None when the pair does not intersect
  q1_A, q1_B    the deformed vertex positions attaining pdd2, 4 x [x, y, z] nested lists
  error         None
Values are floats from the fast engine and fractions.Fraction from the reference engine
(exact, in lowest terms); positions are of the same type. A pair that does not intersect
reports 0 everywhere, None labels and its rest pose.

A rejected pair (a non-finite coordinate, a flat tetrahedron; from the fast engine also a
result outside the normal double range) does not raise: the record is
{"name": name, "error": "<why>"} with the CLI's words, e.g. "tetrahedron B is flat: its four
vertices are coplanar (volume 0)". Malformed arguments (wrong shape, not numbers, unknown
engine) raise ValueError.

The GIL is released while the engine runs, so threads can solve pairs in parallel.

Example:
  >>> r = pdd.solve([[0,0,0],[10,0,0],[0,10,0],[0,0,10]],
  ...               [[2,2,2],[2.5,2,2],[2,2.5,2],[2,2,2.5]], engine="reference")
  >>> r["pdd2"], r["pdd2_dir"], r["q1_B"][1]
  (Fraction(4, 5), 'VF:0', [Fraction(7, 3), Fraction(11, 6), Fraction(11, 6)])
)doc";

constexpr const char* kSolveBatchDoc = R"doc(solve_batch(A, B, threads=None)
--

N pairs -> dict of numpy arrays: the fast engine on all cores, with the GIL released; the
same values, bit for bit, as solve(A[k], B[k]) one pair at a time.

A, B     arrays of shape (N, 4, 3) of real numbers (converted to float64 as
         numpy.asarray(A, dtype=numpy.float64) would); pair k is (A[k], B[k]). A wrong shape,
         a different N, or a non-numeric dtype raises ValueError.
threads  None: all cores; k >= 1: at most k threads (a TBB arena for this call only).

Returns a dict:
  intersecting               (N,) bool
  rigid_pd2, eq11_pd2, pdd2_static, pdd2, pdd2_relaxed, pdd2_accel1, pdd2_accel6
                             (N,) float64, as in solve()
  rigid_dir, pdd2_static_dir, pdd2_dir, pdd2_relaxed_dir
                             (N,) numpy str arrays ('<U8'); "" where solve() gives None
  q1_A, q1_B                 (N, 4, 3) float64
  error                      list of N entries: None, or why pair k was rejected
  slow_paths                 int: how many pairs took the engine's exact path (SPEC §8)
A rejected pair never stops the batch: its error is set, its values and positions are NaN,
its labels "" and intersecting False.

Example:
  >>> rng = numpy.random.default_rng(1)
  >>> A, B = rng.uniform(0, 10, (2, 100000, 4, 3))
  >>> r = pdd.solve_batch(A, B)
  >>> r["pdd2"][r["intersecting"]].mean()
)doc";

constexpr const char* kReadFixturesDoc = R"doc(read_fixtures(path)
--

A fixture file -> list of dicts: the pairs of a fixture file (SPEC §1; fixtures/*.json), read by the same reader as
`pdd solve`:  {"pairs": [{"name": ..., "tags": [...], "A": [[x,y,z] x 4], "B": ...}, ...]}.

Returns one dict per entry, in file order:
  {"name": str, "tags": [str, ...], "A": 4 x [x, y, z] floats, "B": ..., "error": None}
so that solve(p["A"], p["B"], name=p["name"]) solves it. A malformed entry (a missing or
mistyped field, a wrong shape) does not stop the file: it has "error" set to the message
`pdd solve` gives for it, A and B None, and name "#<index>" when it has no usable name.
Non-finite coordinates (1e999) are read as +-inf: solve() then reports them.

A file that cannot be read at all (missing, a directory, empty, not JSON, malformed numbers,
a NUL byte, a repeated key, no "pairs" array) raises ValueError with the message `pdd solve`
prints after "pdd solve: ", e.g. "malformed JSON at byte 12: ...".
)doc";

}  // namespace

PYBIND11_MODULE(pdd, m) {
  py::options options;
  options.disable_function_signatures();  // each docstring starts with its text signature
  m.doc() = kModuleDoc;
  cached = new Cached{py::module_::import("fractions").attr("Fraction"),
                      py::module_::import("numpy").attr("bool_"),
                      py::module_::import("numpy").attr("asarray"),
                      py::module_::import("os").attr("fsdecode")};
  m.attr("__version__") = PDD_VERSION;
  m.attr("KEYS") = py::make_tuple("name", "intersecting", "rigid_pd2", "eq11_pd2", "pdd2_static",
                                  "pdd2", "pdd2_relaxed", "pdd2_accel1", "pdd2_accel6",
                                  "rigid_dir", "pdd2_static_dir", "pdd2_dir", "pdd2_relaxed_dir",
                                  "q1_A", "q1_B", "error");
  m.def("solve", &solve, kSolveDoc, py::arg("A"), py::arg("B"), py::arg("engine") = "fast",
        py::arg("formulation") = "reduced", py::arg("name") = "");
  m.def("solve_batch", &solve_batch, kSolveBatchDoc, py::arg("A"), py::arg("B"),
        py::arg("threads") = py::none());
  m.def("read_fixtures", &read_fixtures, kReadFixturesDoc, py::arg("path"));
}
