// pdd_module.cpp — the Python module `pdd` (pybind11): both engines from Python.
//
//   pdd.solve(A, B, engine="fast", formulation="reduced", name="", with_global=True,
//             gradient=False) -> dict
//   pdd.solve_batch(A, B, threads=None, with_global=True, gradient=False, progress=None)
//             -> dict of arrays
//   pdd.read_fixtures(path)                                        -> list of dicts
//   pdd.mesh_contacts(VA, TA, VB=None, TB=None, variants, engine, threads, progress) -> dict
//   pdd.read_mesh(path)                                            -> (V, T) numpy arrays
//   pdd.resolve(VA, TA, VB=None, TB=None, fix, variant, max_rounds, threads, progress,
//               fixed_a, fixed_b)                                   -> (VA1, VB1, report dict)
//
// Built only on the public C++ interface (<pdd/pdd.h>: pdd::fast, pdd::reference; <pdd/mesh.h>:
// pdd::mesh) and on compare/'s fixture reader (the one `pdd solve` uses, so messages are the
// CLI's). Many records become columns in one place (RecordColumns). Numbers:
// the fast engine's are Python floats, the reference engine's fractions.Fraction, built from
// GMP's integers exactly (never through a float). Every engine call runs with the GIL released;
// the long ones (solve_batch, mesh_contacts, resolve) stop on Ctrl-C (LongCall).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <pthread.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <type_traits>
#include <vector>

#include "pdd/io/fixture_io.h"
#include "pdd/io/resolve_report.h"
#include "pdd/mesh.h"
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

// An array's shape as Python writes it: "(4,)", "(2, 3)".
std::string shape_str(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

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
// a double (the engines read IEEE doubles, definitions §1; rounding it silently would solve another
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
                " is not exactly a double: pdd reads coordinates as IEEE doubles "
                "(docs/definitions.md §1); "
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

// ---------------------------------------------------------------------------------------------
// Output: one definitions §6 record as a dict, keys in the order of `pdd solve`'s JSON records.

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

// `global` false: without definitions §9's keys (the result was computed without it). The key
// pdd2_global_grad is there when the result has the gradient (gradient=True).
template <class R>
py::dict record(const pdd::PairResult<R>& r, bool global) {
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
  if (!global) return d;
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
// pdd.solve

// A str argument; ValueError naming it otherwise.
std::string text_arg(py::handle o, const char* what) {
  if (!PyUnicode_Check(o.ptr()))
    value_error(std::string(what) + " must be a str; got " + short_repr(o));
  return o.cast<std::string>();
}

// A bool argument (True or False only); ValueError naming it otherwise.
bool bool_arg(py::handle o, const char* what) {
  if (!PyBool_Check(o.ptr())) value_error(std::string(what) + " must be True or False; got " + short_repr(o));
  return o.ptr() == Py_True;
}

// with_global=False with gradient=True: the gradient is that of pdd2_global, which is not computed.
void check_gradient_needs_global(bool global, bool gradient) {
  if (gradient && !global)
    value_error("gradient=True needs with_global=True (it is the gradient of pdd2_global)");
}

py::dict solve(py::handle A, py::handle B, py::handle engine_arg, py::handle formulation_arg,
               py::handle name_arg, py::handle global_arg, py::handle gradient_arg) {
  const bool global = bool_arg(global_arg, "with_global");
  const bool gradient = bool_arg(gradient_arg, "gradient");
  check_gradient_needs_global(global, gradient);
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
      r = pdd::fast::solve_pair(pair, pdd::fast::SolveOptions{global, gradient});
    }
    r.name = name;
    return record(r, global);
  }
  pdd::reference::SolveOptions options;
  options.formulation = formulation == "full" ? pdd::QpFormulation::Full : pdd::QpFormulation::Reduced;
  options.with_global = global;
  options.gradient = gradient;
  pdd::PairResult<pdd::Rational> r;
  {
    py::gil_scoped_release release;
    try {
      r = pdd::reference::solve_pair(pair, options);
    } catch (const std::exception& ex) {  // an engine invariant failed: reported as `pdd solve` does
      r = {};
      r.error = std::string("internal error in the reference engine: ") + ex.what();
    }
  }
  r.name = name;
  return record(r, global);
}

// ---------------------------------------------------------------------------------------------
// Records as columns: the one conversion of many PairResult records into numpy arrays (and
// lists of Fractions), shared by solve_batch and mesh_contacts.

constexpr int kLabelChars = 8;  // the longest label, "EE:a:b:+"

// `threads`, as the CLI's --threads: None or 0 all cores, 1..4096 at most that many (numpy
// integers too; not float, not bool). nullopt stands for all cores.
constexpr long kMaxThreads = 4096;
std::optional<int> threads_arg(py::handle threads_in) {
  if (threads_in.is_none()) return std::nullopt;
  const std::string msg = "threads must be 0 (all cores) or an int from 1 to " +
                          std::to_string(kMaxThreads) + ", or None; got ";
  const bool is_bool = PyBool_Check(threads_in.ptr()) || is_numpy_bool(threads_in);
  PyObject* index = is_bool ? nullptr : PyNumber_Index(threads_in.ptr());
  if (!index) {
    PyErr_Clear();
    Py_XDECREF(index);
    value_error(msg + short_repr(threads_in));
  }
  int overflow = 0;
  const long t = PyLong_AsLongAndOverflow(index, &overflow);
  Py_DECREF(index);
  if (t == -1 && PyErr_Occurred()) PyErr_Clear();
  if (overflow || t < 0 || t > kMaxThreads) value_error(msg + short_repr(threads_in));
  if (t == 0) return std::nullopt;
  return static_cast<int>(t);
}

// Runs f on all cores, or in a TBB arena of `threads` threads for this call only.
template <class F>
void with_threads(std::optional<int> threads, F&& f) {
  if (threads) {
    tbb::task_arena arena(*threads);
    arena.execute(f);
  } else {
    f();
  }
}

// ---------------------------------------------------------------------------------------------
// Threads that compute the long calls (LongCall below), kept for the next call: a new thread's
// first TBB loop costs 0.1 to 0.3 ms (it registers with TBB), handing a job to a waiting one
// about 7 us. A call takes an idle one or starts one, so there are as many as calls ever ran
// at once. Used with the GIL held (the GIL orders them); after fork() the child has none.
class Workers {
 public:
  static Workers& get() {
    if (!instance) instance = new Workers;  // never destroyed: idle threads wait in it
    return *instance;
  }
  static void forget_after_fork() { instance = nullptr; }  // the threads did not come along

  // Runs work() then done() on an idle thread (a new one if none is idle) and returns at once;
  // neither may throw. The thread is idle again before done() is called, so that a call that
  // follows this one finds it.
  void start(std::function<void()> work, std::function<void()> done) {
    Worker* w = nullptr;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!idle_.empty()) {
        w = idle_.back();
        idle_.pop_back();
      }
    }
    if (!w) {
      auto fresh = std::make_unique<Worker>();
      std::thread(&Workers::loop, this, fresh.get()).detach();
      w = fresh.release();
    }
    {
      std::lock_guard<std::mutex> lock(w->mutex);
      w->work = std::move(work);
      w->done = std::move(done);
    }
    w->cv.notify_one();
  }

 private:
  struct Worker {
    std::mutex mutex;
    std::condition_variable cv;
    std::function<void()> work, done;
  };

  void loop(Worker* w) {
    for (;;) {
      std::function<void()> work, done;
      {
        std::unique_lock<std::mutex> lock(w->mutex);
        w->cv.wait(lock, [&] { return bool(w->work); });
        work = std::move(w->work);
        done = std::move(w->done);
        w->work = w->done = nullptr;
      }
      work();
      work = nullptr;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        idle_.push_back(w);
      }
      done();
    }
  }

  static inline Workers* instance = nullptr;
  std::mutex mutex_;
  std::vector<Worker*> idle_;
};

// ---------------------------------------------------------------------------------------------
// Long calls (solve_batch, mesh_contacts): Ctrl-C and progress.

// The `progress` argument: None or False (silent), a callable progress(done, total), or True
// (a tqdm bar on standard error; tqdm is imported when the call starts, so that a missing one
// fails before any work). Used with the GIL held.
class Progress {
 public:
  // `unit`: what done and total count, for the bar ("pair", "round").
  Progress(py::handle arg, const char* what, const char* unit = "pair") : what_(what), unit_(unit) {
    if (arg.is_none() || arg.ptr() == Py_False) return;
    if (arg.ptr() == Py_True) {
      try {
        tqdm_ = py::module_::import("tqdm").attr("tqdm");
      } catch (py::error_already_set& e) {
        if (!e.matches(PyExc_ImportError)) throw;
        py::raise_from(e, PyExc_ImportError,
                       "progress=True draws a tqdm bar, but tqdm cannot be imported (Debian: "
                       "apt install python3-tqdm; pip: pip install tqdm); pass a callable "
                       "progress(done, total) instead, or None");
        throw py::error_already_set();
      }
      return;
    }
    if (!PyCallable_Check(arg.ptr()))
      value_error("progress must be None, True or a callable progress(done, total); got " + short_repr(arg));
    callable_ = py::reinterpret_borrow<py::object>(arg);
  }

  bool active() const { return bool(callable_) || bool(tqdm_); }

  // `done` of `total` pairs (rounds) are computed: calls progress(done, total) or moves the
  // bar, unless that is what it last said. `postfix`, if not empty, is shown after the bar
  // ("pairs=120"; not passed to a callable). Throws py::error_already_set when the callable
  // raises.
  void report(std::size_t done, std::size_t total, const std::string& postfix = {}) {
    if (!active() || (said_ && done == done_ && total == total_)) return;
    if (tqdm_) {
      if (!bar_) bar_ = tqdm_(py::arg("total") = total, py::arg("desc") = what_, py::arg("unit") = unit_);
      if (total != total_ && said_) bar_.attr("total") = total;  // a run that stopped early
      if (!postfix.empty()) bar_.attr("set_postfix_str")(postfix, py::arg("refresh") = false);
      bar_.attr("update")(done - done_);
    } else {
      callable_(done, total);
    }
    said_ = true, done_ = done, total_ = total;
  }

  // The call ended: closes the bar.
  void close() {
    if (!bar_) return;
    const py::object bar = std::move(bar_);
    bar.attr("close")();
  }

 private:
  const char* what_;
  const char* unit_;
  py::object callable_, tqdm_, bar_;
  bool said_ = false;
  std::size_t done_ = 0, total_ = 0;
};

// The pairs are computed on a thread of Workers (TBB's loops inside, in the call's arena)
// while the calling thread waits with the GIL released; every kPoll it takes the GIL, runs
// Python's signal handlers (PyErr_CheckSignals: in the main thread Ctrl-C raises
// KeyboardInterrupt there) and reports progress. On an exception (from a signal handler or
// the progress callable) it sets `cancel`, which the pair loops check before each pair, waits
// for the pairs already started (one per thread: microseconds with the fast engine, up to
// seconds for an exact pair) and raises it; the results are dropped. Python code on other
// threads runs meanwhile, as with any call that releases the GIL.
class LongCall {
 public:
  static constexpr auto kPoll = std::chrono::milliseconds(50);
  static constexpr std::size_t kUnknown = std::size_t(-1);

  explicit LongCall(Progress& progress) : progress_(progress) {}

  // Set by the calling thread; the computation starts no more pairs once it is.
  std::atomic<bool> cancel{false};
  // Set by the computation: pairs computed, of `total` (kUnknown until it is known); `pairs`
  // (resolve: intersecting pairs at the last round's start) is shown after a tqdm bar.
  std::atomic<std::size_t> done{0}, total{kUnknown}, pairs{kUnknown};

  bool cancelled() const { return cancel.load(std::memory_order_relaxed); }
  void add_done(std::size_t n) { done.fetch_add(n, std::memory_order_relaxed); }

  // Runs compute() (no Python inside) as described above, or, when `watch` is false (short
  // calls), on the calling thread with the GIL released; then reports progress(total, total).
  // Called with the GIL held; throws the Python exception that stopped it, or what compute()
  // threw.
  template <class Compute>
  void run(bool watch, Compute&& compute) {
    try {
      if (watch) {
        watched(compute);
      } else {
        py::gil_scoped_release release;
        compute();
      }
      const std::size_t t = total.load();
      if (t != kUnknown) progress_.report(t, t);
    } catch (...) {
      try {
        progress_.close();
      } catch (py::error_already_set&) {  // the exception that stopped the call goes on
      }
      throw;
    }
    progress_.close();
  }

 private:
  template <class Compute>
  void watched(Compute& compute) {
    std::mutex mutex;
    std::condition_variable finished_cv;
    bool finished = false;
    std::exception_ptr failure;        // compute()'s exception
    std::exception_ptr watch_failure;  // a C++ exception in the watch itself
    bool python_error = false;         // set in this thread's state; raised once compute() ended
    Workers& workers = Workers::get();
    {
      py::gil_scoped_release release;
      workers.start(
          [&] {
            try {
              compute();
            } catch (...) {
              failure = std::current_exception();
            }
          },
          [&] {
            std::lock_guard<std::mutex> lock(mutex);
            finished = true;
            finished_cv.notify_one();
          });
      for (;;) {
        {
          std::unique_lock<std::mutex> lock(mutex);
          if (finished_cv.wait_for(lock, kPoll, [&] { return finished; })) break;
        }
        py::gil_scoped_acquire gil;
        try {  // nothing may leave this scope while the worker runs
          python_error = PyErr_CheckSignals() != 0;
          const std::size_t t = total.load();
          const std::size_t p = pairs.load();
          if (!python_error && t != kUnknown)
            progress_.report(done.load(), t, p == kUnknown ? std::string() : "pairs=" + std::to_string(p));
        } catch (py::error_already_set& e) {
          e.restore();
          python_error = true;
        } catch (...) {
          watch_failure = std::current_exception();
        }
        if (python_error || watch_failure) {
          cancel.store(true, std::memory_order_relaxed);
          break;
        }
      }
      std::unique_lock<std::mutex> lock(mutex);
      finished_cv.wait(lock, [&] { return finished; });
    }
    if (python_error) throw py::error_already_set();
    if (watch_failure) std::rethrow_exception(watch_failure);
    if (failure) std::rethrow_exception(failure);
  }

  Progress& progress_;
};

// n records as columns, keyed as definitions §6 (pair_result.h's kValueKeys / kLabelKeys):
//   intersecting                (n,) bool
//   the values of `values`      bit k of `values` selects kValueKeys[k] (the bits of
//                               pdd::mesh::Variant); fast: (n,) float64, exact: a list of n
//                               fractions.Fraction
//   their labels                (n,) numpy str arrays ('<U8'), "" for no label
//   q1_A, q1_B (if `positions`) fast: (n, 4, 3) float64; exact: n nested lists of Fractions
//   definitions §9 (if `global`)       pdd2_global, pdd2_global_normal, q1_A_global, q1_B_global:
//                               fast (n,), (n, 3) (NaN where no normal), (n, 4, 3) float64;
//                               exact lists of n Fractions, [x, y, z] Fractions or None,
//                               nested lists of Fractions, and pdd2_global_lower (Fractions);
//                               fast: pdd2_global_error, a list of n entries, None or why the
//                               engine declined pdd2_global alone (then its row is NaN)
//   pdd2_global_grad            (if `gradient`, fast only) (n, 8, 3) float64, A's vertices first;
//                               NaN where pdd2_global is
//   error                       a list of n entries, None or why record j was rejected
// A rejected record's row: values and positions NaN (exact: None), labels "", intersecting
// False. Construct and add_to() with the GIL held; put() of a double record touches only the
// arrays' memory and may run without the GIL; put() of an exact record needs the GIL. Rows are
// put by one thread at a time.
class RecordColumns {
 public:
  RecordColumns(std::size_t n, bool exact, unsigned values, bool positions, bool global = false,
                bool gradient = false)
      : n_(static_cast<py::ssize_t>(n)), exact_(exact), values_(values), positions_(positions),
        intersecting_(n_) {
    if (gradient && !exact_) {
      global_grad_ = py::array_t<double>({n_, py::ssize_t{8}, py::ssize_t{3}});
      out_global_grad_ = global_grad_->mutable_data();
    }
    if (global && exact_) {
      for (auto* l : {&exact_global_, &exact_global_normal_, &exact_global_q1_[0], &exact_global_q1_[1],
                       &exact_global_lower_})
        *l = py::list(n_);
    }
    if (global && !exact_) {  // definitions §9: value (n,), normal (n, 3), positions (n, 4, 3)
      global_value_ = py::array_t<double>(n_);
      global_normal_ = py::array_t<double>({n_, py::ssize_t{3}});
      global_q1_[0] = py::array_t<double>({n_, py::ssize_t{4}, py::ssize_t{3}});
      global_q1_[1] = py::array_t<double>({n_, py::ssize_t{4}, py::ssize_t{3}});
      out_global_ = global_value_->mutable_data();
      out_global_normal_ = global_normal_->mutable_data();
      out_global_q1_[0] = global_q1_[0]->mutable_data();
      out_global_q1_[1] = global_q1_[1]->mutable_data();
    }
    for (std::size_t k = 0; k < pdd::kValueCount; ++k) {
      if (!has_value(k)) continue;
      if (exact_)
        exact_values_[k] = py::list(n_);
      else
        values_out_[k] = py::array_t<double>(n_);
      if (pdd::kLabelOfValue[k] >= 0) {
        auto& l = labels_[pdd::kLabelOfValue[k]];
        l = py::array(py::dtype("<U" + std::to_string(kLabelChars)), std::vector<py::ssize_t>{n_});
        std::memset(l->mutable_data(), 0, n * kLabelChars * sizeof(std::uint32_t));
      }
    }
    if (positions_) {
      if (exact_) {
        exact_q1_[0] = py::list(n_), exact_q1_[1] = py::list(n_);
      } else {
        q1_[0] = py::array_t<double>({n_, py::ssize_t{4}, py::ssize_t{3}});
        q1_[1] = py::array_t<double>({n_, py::ssize_t{4}, py::ssize_t{3}});
      }
    }
    // Raw pointers, so that put() of a double record calls nothing of Python's.
    out_intersecting_ = intersecting_.mutable_data();
    for (std::size_t k = 0; k < pdd::kValueCount; ++k)
      out_values_[k] = values_out_[k] ? values_out_[k]->mutable_data() : nullptr;
    for (std::size_t l = 0; l < pdd::kLabelCount; ++l)
      out_labels_[l] = labels_[l] ? static_cast<std::uint32_t*>(labels_[l]->mutable_data()) : nullptr;
    for (int s = 0; s < 2; ++s) out_q1_[s] = q1_[s] ? q1_[s]->mutable_data() : nullptr;
  }

  void put(std::size_t j, const pdd::PairResult<double>& r) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    put_common(j, r);
    for (std::size_t k = 0; k < pdd::kValueCount; ++k)
      if (out_values_[k]) out_values_[k][j] = r.error ? nan : pdd::record_value(r, k);
    const pdd::Positions<double>* q[2] = {&r.q1_A, &r.q1_B};
    for (int s = 0; s < 2; ++s)
      if (out_q1_[s])
        for (int i = 0; i < 4; ++i)
          for (int c = 0; c < 3; ++c) out_q1_[s][(j * 4 + i) * 3 + c] = r.error ? nan : (*q[s])[i][c];
    if (out_global_) {
      out_global_[j] = r.error ? nan : r.pdd2_global;
      for (int c = 0; c < 3; ++c)
        out_global_normal_[j * 3 + c] = (r.error || !r.pdd2_global_normal) ? nan : (*r.pdd2_global_normal)[c];
      const pdd::Positions<double>* g[2] = {&r.q1_A_global, &r.q1_B_global};
      for (int s = 0; s < 2; ++s)
        for (int i = 0; i < 4; ++i)
          for (int c = 0; c < 3; ++c) out_global_q1_[s][(j * 4 + i) * 3 + c] = r.error ? nan : (*g[s])[i][c];
      if (!r.error && r.pdd2_global_error) global_errors_.emplace_back(j, *r.pdd2_global_error);
    }
    if (out_global_grad_)
      for (int i = 0; i < 8; ++i)
        for (int c = 0; c < 3; ++c)
          out_global_grad_[(j * 8 + i) * 3 + c] = (r.error || !r.pdd2_global_grad) ? nan : (*r.pdd2_global_grad)[i][c];
  }

  void put(std::size_t j, const pdd::PairResult<pdd::Rational>& r) {  // GIL held
    put_common(j, r);
    const auto J = static_cast<py::ssize_t>(j);
    for (std::size_t k = 0; k < pdd::kValueCount; ++k)
      if (exact_values_[k])
        (*exact_values_[k])[J] = r.error ? py::object(py::none()) : number(pdd::record_value(r, k));
    const pdd::Positions<pdd::Rational>* q[2] = {&r.q1_A, &r.q1_B};
    for (int s = 0; s < 2; ++s)
      if (exact_q1_[s]) (*exact_q1_[s])[J] = r.error ? py::object(py::none()) : py::object(positions(*q[s]));
    if (exact_global_) {
      const py::object none = py::none();
      (*exact_global_)[J] = r.error ? none : number(r.pdd2_global);
      py::object normal = none;
      if (!r.error && r.pdd2_global_normal) {
        py::list n;
        for (const auto& c : *r.pdd2_global_normal) n.append(number(c));
        normal = n;
      }
      (*exact_global_normal_)[J] = normal;
      const pdd::Positions<pdd::Rational>* g[2] = {&r.q1_A_global, &r.q1_B_global};
      for (int s = 0; s < 2; ++s) (*exact_global_q1_[s])[J] = r.error ? none : py::object(positions(*g[s]));
      (*exact_global_lower_)[J] = (r.error || !r.pdd2_global_lower) ? none : number(*r.pdd2_global_lower);
    }
  }

  void add_to(py::dict& d) const {
    d["intersecting"] = intersecting_;
    for (std::size_t k = 0; k < pdd::kValueCount; ++k) {
      if (values_out_[k]) d[pdd::kValueKeys[k]] = *values_out_[k];
      if (exact_values_[k]) d[pdd::kValueKeys[k]] = *exact_values_[k];
    }
    for (std::size_t l = 0; l < pdd::kLabelCount; ++l)
      if (labels_[l]) d[pdd::kLabelKeys[l]] = *labels_[l];
    const char* q1_keys[2] = {"q1_A", "q1_B"};
    for (int s = 0; s < 2; ++s) {
      if (q1_[s]) d[q1_keys[s]] = *q1_[s];
      if (exact_q1_[s]) d[q1_keys[s]] = *exact_q1_[s];
    }
    if (global_value_) {
      d["pdd2_global"] = *global_value_;
      d["pdd2_global_normal"] = *global_normal_;
      d["q1_A_global"] = *global_q1_[0];
      d["q1_B_global"] = *global_q1_[1];
      d["pdd2_global_error"] = error_column(global_errors_);
    }
    if (global_grad_) d["pdd2_global_grad"] = *global_grad_;
    if (exact_global_) {  // in the order `pdd solve` writes them
      d["pdd2_global"] = *exact_global_;
      d["pdd2_global_normal"] = *exact_global_normal_;
      d["q1_A_global"] = *exact_global_q1_[0];
      d["q1_B_global"] = *exact_global_q1_[1];
      d["pdd2_global_lower"] = *exact_global_lower_;
    }
    d["error"] = error_column(errors_);
  }

 private:
  // n entries: None, or the message of row j
  py::list error_column(const std::vector<std::pair<std::size_t, std::string>>& messages) const {
    py::list out(n_);
    for (py::ssize_t j = 0; j < n_; ++j) out[j] = py::none();
    for (const auto& [j, msg] : messages) out[static_cast<py::ssize_t>(j)] = py::str(msg);
    return out;
  }

  bool has_value(std::size_t k) const { return values_ & (1u << k); }

  template <class R>
  void put_common(std::size_t j, const pdd::PairResult<R>& r) {
    if (r.error) errors_.emplace_back(j, *r.error);
    out_intersecting_[j] = !r.error && r.intersecting;
    for (std::size_t l = 0; l < pdd::kLabelCount; ++l) {
      const auto& label = pdd::record_label(r, l);
      if (!out_labels_[l] || r.error || !label) continue;
      const std::string s = label->str();
      for (std::size_t c = 0; c < s.size() && c < std::size_t(kLabelChars); ++c)
        out_labels_[l][j * kLabelChars + c] = static_cast<unsigned char>(s[c]);
    }
  }

  py::ssize_t n_;
  bool exact_;
  unsigned values_;
  bool positions_;
  py::array_t<bool> intersecting_;
  // Empty where not a column (a default pybind11 array or list is not a null handle).
  std::array<std::optional<py::array_t<double>>, pdd::kValueCount> values_out_;
  std::array<std::optional<py::list>, pdd::kValueCount> exact_values_;
  std::array<std::optional<py::array>, pdd::kLabelCount> labels_;
  std::array<std::optional<py::array_t<double>>, 2> q1_;
  std::array<std::optional<py::list>, 2> exact_q1_;
  bool* out_intersecting_ = nullptr;
  std::array<double*, pdd::kValueCount> out_values_{};
  std::array<std::uint32_t*, pdd::kLabelCount> out_labels_{};
  std::array<double*, 2> out_q1_{};
  std::vector<std::pair<std::size_t, std::string>> errors_, global_errors_;
  std::optional<py::array_t<double>> global_value_, global_normal_;
  std::array<std::optional<py::array_t<double>>, 2> global_q1_;
  double* out_global_ = nullptr;
  double* out_global_normal_ = nullptr;
  std::array<double*, 2> out_global_q1_{};
  std::optional<py::array_t<double>> global_grad_;
  double* out_global_grad_ = nullptr;
  std::optional<py::list> exact_global_, exact_global_normal_, exact_global_lower_;
  std::array<std::optional<py::list>, 2> exact_global_q1_;
};

// ---------------------------------------------------------------------------------------------
// pdd.solve_batch

// (N, 4, 3) float64, C order; ValueError naming the problem otherwise.
py::array_t<double, py::array::c_style> batch_input(py::handle obj, const char* which) {
  py::array a = cached->asarray(obj);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    value_error(std::string(which) + " must be an array of real numbers of shape (N, 4, 3); got dtype " +
                py::str(a.dtype()).cast<std::string>());
  if (a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 3)
    value_error(std::string(which) + " must have shape (N, 4, 3); got " + shape_str(a));
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
}

// Pairs a chunk of solve_batch's loop holds (its records' memory: about 700 bytes a pair).
constexpr std::size_t kChunk = 1 << 15;
// Batches of more pairs than this are watched for Ctrl-C (LongCall); smaller ones take about a
// millisecond a core (a few when some take the exact path) and run on the calling thread.
constexpr std::size_t kWatchedPairs = 256;

py::dict solve_batch(py::handle A_in, py::handle B_in, py::handle threads_in, py::handle global_arg,
                     py::handle gradient_arg, py::handle progress_arg) {
  const bool global = bool_arg(global_arg, "with_global");
  const bool gradient = bool_arg(gradient_arg, "gradient");
  check_gradient_needs_global(global, gradient);
  const std::optional<int> threads = threads_arg(threads_in);
  Progress progress(progress_arg, "pdd.solve_batch");
  const auto A = batch_input(A_in, "A");
  const auto B = batch_input(B_in, "B");
  if (!A || !B) throw py::error_already_set();
  if (A.shape(0) != B.shape(0))
    value_error("A and B must hold the same number of pairs; got " + std::to_string(A.shape(0)) +
                " and " + std::to_string(B.shape(0)));
  const std::size_t n = static_cast<std::size_t>(A.shape(0));

  // Outputs, allocated with the GIL held, filled without it.
  RecordColumns out(n, /*exact=*/false, (1u << pdd::kValueCount) - 1, /*positions=*/true, global, gradient);
  const pdd::fast::SolveOptions options{global, gradient};
  const double* a = A.data();
  const double* b = B.data();
  std::size_t slow_paths = 0;
  LongCall call(progress);
  call.total = n;
  // Chunks bound the memory of the engine's records; every chunk uses all cores (or the arena's
  // `threads`). Each record is solve_pair's on that pair, as fast::solve_batch gives it (bit for
  // bit the same as one pair at a time), by a loop that stops before the next pair once
  // `cancel` is set.
  call.run(n > kWatchedPairs, [&] {
    with_threads(threads, [&] {
      std::vector<pdd::TetPair> chunk;
      std::vector<pdd::PairResult<double>> res;
      for (std::size_t first = 0; first < n; first += kChunk) {
        const std::size_t m = std::min(kChunk, n - first);
        chunk.resize(m);
        for (std::size_t k = 0; k < m; ++k)
          for (int i = 0; i < 4; ++i)
            for (int c = 0; c < 3; ++c) {
              chunk[k].A[i][c] = a[((first + k) * 4 + i) * 3 + c];
              chunk[k].B[i][c] = b[((first + k) * 4 + i) * 3 + c];
            }
        res.resize(m);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m), [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t k = r.begin(); k != r.end(); ++k) {
            if (call.cancelled()) return;
            res[k] = pdd::fast::solve_pair(chunk[k], options);
          }
          call.add_done(r.size());
        });
        if (call.cancelled()) return;
        for (std::size_t k = 0; k < m; ++k) {
          slow_paths += res[k].stats.slow_path;
          out.put(first + k, res[k]);
        }
      }
    });
  });

  py::dict d;
  out.add_to(d);
  d["slow_paths"] = slow_paths;
  return d;
}

// ---------------------------------------------------------------------------------------------
// pdd.read_fixtures

// A path argument (str, bytes, os.PathLike) as the C++ readers take it.
std::string path_arg(py::handle path_like) {
  try {
    return cached->fsdecode(path_like).cast<std::string>();
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_TypeError)) throw;
    value_error("path must be a str, bytes or os.PathLike; got " + short_repr(path_like));
  }
}

py::list read_fixtures(py::handle path_like) {
  const std::string path = path_arg(path_like);
  pdd::io::FixtureFile file;
  {
    py::gil_scoped_release release;
    file = pdd::io::read_fixture_file(path);
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

// Vertices: (n, 3) real numbers -> the mesh's vertices (float64, as numpy.asarray would convert).
std::vector<pdd::Vec3d> mesh_vertices(py::handle obj, const char* which) {
  py::array a = cached->asarray(obj);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    value_error(std::string(which) + " must be an array of real numbers of shape (n, 3); got dtype " +
                py::str(a.dtype()).cast<std::string>());
  if (a.ndim() != 2 || a.shape(1) != 3)
    value_error(std::string(which) + " must have shape (n, 3); got " + shape_str(a));
  const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!d) throw py::error_already_set();
  std::vector<pdd::Vec3d> out(static_cast<std::size_t>(a.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int k = 0; k < 3; ++k) out[i][k] = d.data()[i * 3 + k];
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

  pdd::mesh::Mesh A, B;
  A.vertices = mesh_vertices(VA, "VA");
  A.tets = mesh_tets(TA, "TA", 'A', A.vertices.size());
  if (!self) {
    B.vertices = mesh_vertices(VB, "VB");
    B.tets = mesh_tets(TB, "TB", 'B', B.vertices.size());
  }

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
          fast = self ? pdd::mesh::self_contacts(A, options) : pdd::mesh::contacts(A, B, options);
        else
          exact = self ? pdd::mesh::self_contacts_exact(A, options)
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
                  py::handle progress_arg, py::handle fixed_a_in, py::handle fixed_b_in) {
  pdd::mesh::ResolveOptions options;
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
  Progress progress(progress_arg, "pdd.resolve", "round");

  pdd::mesh::Mesh A, B;
  A.vertices = mesh_vertices(VA, "VA");
  A.tets = mesh_tets(TA, "TA", 'A', A.vertices.size());
  if (!self) {
    B.vertices = mesh_vertices(VB, "VB");
    B.tets = mesh_tets(TB, "TB", 'B', B.vertices.size());
  }
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
  return py::make_tuple(vertices_array(result->a),
                        self ? py::object(py::none()) : py::object(vertices_array(result->b)),
                        report_dict);
}

// ---------------------------------------------------------------------------------------------
// Docstrings: help(pdd), help(pdd.solve) read like the README.

constexpr const char* kModuleDoc = R"doc(Penetration depth between two tetrahedra (pdd), from Python.

Two senses of depth (Kim & Kim, "A Penetration Metric for Deforming Tetrahedra using
Object Norm", arXiv:1911.06144; every quantity is defined in docs/definitions.md):
  PD    the rigid penetration depth: the shortest translation of B that leaves the
        interiors of A and B disjoint;
  PD_d  the deformable penetration depth: the smallest object-norm cost (mean squared
        displacement) of deforming both tetrahedra until a plane separates them.
Every value is SQUARED (rigid_pd2 = PD², pdd2 = PD_d², ...), which keeps it rational.

Two engines:
  "fast"       doubles, certified: every value within 1e-9 relative of the exact one
               (0 exactly when it is 0), labels within that of the exact minimum
               (the fast engine's accuracy contract, docs/definitions.md §8);
  "reference"  exact: every value a fractions.Fraction (CGAL, GMP); about 0.1 s a pair.

Functions:
  solve(A, B, engine="fast", formulation="reduced", name="", with_global=True, gradient=False)
                                       one pair -> dict
  solve_batch(A, B, threads=None, with_global=True, gradient=False, progress=None)
                                       (N, 4, 3) numpy arrays, fast engine, all cores
  read_fixtures(path)                  a fixture file (fixtures/*.json) -> list of dicts
  mesh_contacts(VA, TA, VB=None, TB=None, variants=..., engine="fast", threads=None,
                progress=None)
                                       every intersecting element pair of two tetrahedral
                                       meshes (numpy arrays; docs/definitions.md §10)
                                       and its depths
  read_mesh(path)                      a .msh or .vtk file -> (V, T) numpy arrays
  resolve(VA, TA, VB=None, TB=None, fix=None, variant="global", max_rounds=200, ...)
                                       move the meshes' vertices until no element pair
                                       intersects, checked exactly -> (VA1, VB1, report)

Example:
  >>> import pdd
  >>> A = [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]]
  >>> B = [[2, 2, 2], [2.5, 2, 2], [2, 2.5, 2], [2, 2, 2.5]]
  >>> r = pdd.solve(A, B, engine="reference")
  >>> r["rigid_pd2"], r["eq11_pd2"], r["pdd2"], r["pdd2_dir"]
  (Fraction(16, 3), Fraction(1, 12), Fraction(4, 5), 'VF:0')

KEYS is the tuple of a record's keys, in the order `pdd solve` writes them.
)doc";

constexpr const char* kSolveDoc = R"doc(solve(A, B, engine='fast', formulation='reduced', name='', with_global=True, gradient=False)
--

One pair -> dict: every quantity of the output record (docs/definitions.md §6), as
`pdd solve` writes it (one JSON record).

A, B     the tetrahedra: 4 vertices x 3 coordinates, anything array-like (nested lists,
         tuples, a numpy array of shape (4, 3)). A is the paper's T1 (static in case 1), B is
         T2. Coordinates are IEEE doubles (docs/definitions.md §1): floats, ints, or any number (Fraction,
         Decimal, numpy scalar) whose value is exactly a double; anything else raises
         ValueError naming the coordinate. Vertex order and orientation are free.
engine   "fast" (doubles, certified to the accuracy contract of
         docs/definitions.md §8) or "reference" (exact rationals).
formulation  the reference engine's per-direction QP: "reduced" (the default: the
         displacement along the separating direction only, about 7x faster) or "full" (the
         paper's 27 variables); both give the same exact result. Ignored by the fast engine.
         The same option as `pdd solve --formulation` and pdd.h's SolveOptions::formulation.
name     copied to the record's "name".
with_global  False: skip pdd2_global, PD_d² over every separating plane
         (docs/definitions.md §9): the record has no pdd2_global, pdd2_global_normal,
         q1_A_global, q1_B_global, pdd2_global_lower keys. Faster (fast engine: about 6 of
         15 us a pair; reference: its branch and bound of 5 to 50 ms). `pdd solve --no-global`.
gradient True: add "pdd2_global_grad", the gradient of pdd2_global with respect to the
         eight rest vertices, 8 x [x, y, z] (A's s0..s3, then B's r0..r3): minus the object
         norm's derivative at the displacement to q1_A_global, q1_B_global (pdd.h says why and
         how exact). None where pdd2_global is None; 0 when not intersecting. Needs
         with_global=True (ValueError otherwise). `pdd solve --gradient`.

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
  pdd2_global, pdd2_global_normal, q1_A_global, q1_B_global (with_global)   PD_d² over every
                separating plane, the normal attaining it (pointing from A to B) and the
                deformed positions; pdd2_global_lower (reference engine) its proved lower bound.
                The normal is a direction: from the fast engine the exact triple of doubles
                along which the value was certified, scaled by a power of two so that its
                largest |component| is in [1, 2) (not rescaled to unit length: rounding n/|n|
                can move the value of a very shallow contact by more than 1e-9); from the
                reference engine the exact rational witness, of no fixed length
  pdd2_global_error (fast engine, with_global)   None, or why pdd2_global alone could not be
                certified in doubles (a depth below the resolution of the pair's extent): then
                the four keys above are None and every other value is still reported
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

constexpr const char* kSolveBatchDoc = R"doc(solve_batch(A, B, threads=None, with_global=True, gradient=False, progress=None)
--

N pairs -> dict of numpy arrays: the fast engine on all cores, with the GIL released; the
same values, bit for bit, as solve(A[k], B[k]) one pair at a time.

A, B     arrays of shape (N, 4, 3) of real numbers (converted to float64 as
         numpy.asarray(A, dtype=numpy.float64) would); pair k is (A[k], B[k]). A wrong shape,
         a different N, or a non-numeric dtype raises ValueError.
threads  None or 0: all cores; k from 1 to 4096: at most k threads (a TBB arena for this
         call only), as `pdd solve --threads`. Anything else raises ValueError.
with_global  False: skip pdd2_global (PD_d² over every separating plane), as in solve()
         (no pdd2_global* / q1_*_global arrays).
gradient True: add "pdd2_global_grad", (N, 8, 3) float64, as in solve() (NaN where solve()
         gives None).
progress None (the default) or False: silent. A callable progress(done, total): called
         from the calling thread with the GIL held, about every 0.05 s while pairs are
         computed when `done` (pairs computed so far) has grown, and once at the end with
         done == total == N; an exception it raises stops the call (as Ctrl-C does, below)
         and propagates. True: a tqdm progress bar on standard error (Debian python3-tqdm;
         without tqdm, ImportError before any work).

Returns a dict:
  intersecting               (N,) bool
  rigid_pd2, eq11_pd2, pdd2_static, pdd2, pdd2_relaxed, pdd2_accel1, pdd2_accel6
                             (N,) float64, as in solve()
  rigid_dir, pdd2_static_dir, pdd2_dir, pdd2_relaxed_dir
                             (N,) numpy str arrays ('<U8'); "" where solve() gives None
  q1_A, q1_B                 (N, 4, 3) float64
  pdd2_global, pdd2_global_normal, q1_A_global, q1_B_global
                             PD_d² over every separating plane (docs/definitions.md §9):
                             (N,), (N, 3) (NaN where solve() gives None), (N, 4, 3)
                             float64
  pdd2_global_error          list of N entries (with_global only): None, or why the engine
                             declined pdd2_global alone for pair k (its pdd2_global row is
                             NaN, the other values are reported)
  error                      list of N entries: None, or why pair k was rejected
  slow_paths                 int: how many pairs took the engine's exact path (to keep
                             its accuracy contract)
A rejected pair never stops the batch: its error is set, its values and positions are NaN,
its labels "" and intersecting False.

Ctrl-C stops a call from the main thread (where Python handles signals): KeyboardInterrupt
(or whatever a signal handler raises) within about 0.1 s, the pairs already computed
dropped. Batches of more than 256 pairs are computed on a thread of their own while the
calling thread watches for signals.

Example:
  >>> rng = numpy.random.default_rng(1)
  >>> A, B = rng.uniform(0, 10, (2, 100000, 4, 3))
  >>> r = pdd.solve_batch(A, B)
  >>> r["pdd2"][r["intersecting"]].mean()
)doc";

constexpr const char* kReadFixturesDoc = R"doc(read_fixtures(path)
--

A fixture file -> list of dicts: the pairs of a fixture file (docs/definitions.md §1;
fixtures/*.json), read by the same reader as `pdd solve`:
   {"pairs": [{"name": ..., "tags": [...], "A": [[x,y,z] x 4], "B": ...}, ...]}.

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

constexpr const char* kMeshContactsDoc = R"doc(mesh_contacts(VA, TA, VB=None, TB=None, variants='rigid,static,pdd2,accel1', engine='fast', threads=None, progress=None)
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
         a pair with the fast engine), or all. Default: "rigid,static,pdd2,accel1", as
         `pdd mesh`.
engine   "fast" (doubles, certified to the accuracy contract of docs/definitions.md §8)
         or "reference" (exact rationals, fractions.Fraction; about 0.1 s a pair on one
         core: for small meshes).
threads  None or 0: all cores; k from 1 to 4096: at most k threads (a TBB arena for this
         call only), as `pdd mesh --threads`. Anything else raises ValueError.
progress None (the default) or False: silent; a callable progress(done, total) or True (a
         tqdm bar), as in solve_batch(). Over stage 4 below: `done` counts the intersecting
         pairs computed, `total` is their number (no call comes before stage 3 is done).

Stages (mesh.h): 1. a box per element (an element with a non-finite coordinate or zero
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
("variants: unknown variant 'pd' (rigid, eq11, ...)"), an unknown engine, VB without TB.

Example:
  >>> VA, TA = pdd.read_mesh("fixtures/meshes/tiny-a.msh")
  >>> VB, TB = pdd.read_mesh("fixtures/meshes/tiny-b.msh")
  >>> c = pdd.mesh_contacts(VA, TA, VB, TB)
  >>> len(c["a"]), c["a"][0], c["b"][0], c["pdd2"][0], c["pdd2_dir"][0], c["skipped"]
  (51, 0, 8, 0.0034615384615384608, 'EE:2:1', [])
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
written, non-finite ones too (mesh_contacts() then skips the element that uses them).

A file that cannot be read (missing, truncated, malformed, an element referring to a node
that is not in the file, an unknown element type) raises ValueError with the message
`pdd mesh` prints, naming the file and the line or byte, e.g. "a.msh:42: element 17
refers to node 999, which is not in the file".
)doc";

constexpr const char* kResolveDoc = R"doc(resolve(VA, TA, VB=None, TB=None, fix=None, variant='global', max_rounds=200, threads=None, progress=None, fixed_a=None, fixed_b=None)
--

Two tetrahedral meshes that interpenetrate (or one that intersects itself) -> new vertex
positions after which, each decided exactly on the returned doubles:
  R1  no element pair intersects (A against B; self-contact: the pairs of A that share no
      vertex; touching is not intersecting),
  R2  every element keeps the sign of its volume and a non-zero volume (none inverted or
      flattened),
  R3  fixed vertices are bit-for-bit unchanged.
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
variant  which per-pair solution drives the vertices: "global" (the default: the deformable
         penetration depth over every separating plane, its deformed positions), "pdd2" (the
         deformable depth over the candidate directions) or "rigid" (the baseline: each pair
         pushed apart by its rigid translation, split between the two elements).
max_rounds   rounds of contact solving before giving up, an int from 1 to 1000000. A run
         that reaches it without R1-R3 returns normally with report["resolved"] False.
threads  None or 0: all cores; k from 1 to 4096: at most k threads (a TBB arena for this
         call only), as `pdd resolve --threads`. Anything else raises ValueError.
progress None (the default) or False: silent. A callable progress(done, total): called from
         the calling thread with the GIL held, about every 0.05 s while the rounds run when
         `done` (rounds finished) has grown, total being max_rounds; once at the end with
         done == total == the rounds run. An exception it raises stops the call (as Ctrl-C
         does) and propagates. True: a tqdm bar on standard error (Debian python3-tqdm), in
         rounds, with the intersecting pairs of the last round after it.

Cost: the mesh object norm, the volume-weighted mean squared displacement
  sigma_mesh = sum_e V_e sigma_e / sum_e V_e    (V_e rest volume, sigma_e the per-tetrahedron
                                                 object norm of docs/definitions.md)
so that a translation by t costs |t|^2; reported per mesh and summed.

Returns (VA1, VB1, report):
  VA1       (n, 3) float64: A's new vertices (equal to VA where fixed, bit for bit)
  VB1       (n_B, 3) float64, or None for self-contact
  report    dict, the keys of `pdd resolve --report` (JSON), in that order:
    variant               "global", "pdd2" or "rigid"
    inputs                {self, fix, max_rounds, elements_a, vertices_a, elements_b,
                           vertices_b, fixed_vertices_a, fixed_vertices_b} (the CLI adds the
                           file names a and b)
    resolved              r1 and r2 and r3: the exact verdict on VA1, VB1 over every pair (a
                          fresh broadphase, not only the pairs of the last round)
    r1, r2, r3            each condition above
    rounds                list of {round, pairs, max_pd2, cost, seconds}: per round the
                          intersecting pairs at its start, the largest per-pair squared depth
                          of the variant, the cost after it, its wall time
    cost, cost_a, cost_b  sigma_mesh of A plus B, of A, of B
    max_displacement      largest |p1 - p0| over every vertex
    min_volume_ratio      smallest V1 / V0 over every element (signed: < 0 is inverted)
    remaining_pairs       [[a, b], ...]: element pairs still intersecting ([] when r1)
    bad_elements          [["A" or "B", i], ...]: elements inverted or flat ([] when r2)
    moved_fixed_vertices  [["A" or "B", i], ...]: fixed vertices that moved ([] when r3)
    skipped               [{mesh, index, reason}, ...]: input elements that cannot be
                          computed (flat, non-finite), e.g. "element 12 of mesh A is flat: ...";
                          they are in no pair and no check (`pdd resolve` exits 1 then)
    seconds_contacts, seconds_solve, seconds_move, seconds_verify, seconds_total
                          wall time per stage over the run
Write the result with meshio (meshio.Mesh(VA1, [("tetra", TA)]).write("a1.msh")) or with
`pdd resolve`, which writes .msh / .vtk files whose coordinates read back bit for bit.

Ctrl-C stops a call from the main thread: KeyboardInterrupt (or whatever a signal handler
raises) once the stage being computed ends (a round has a few stages: contacts, per-pair
solutions, the move, the exact check); nothing is returned.

Malformed arguments raise ValueError: a wrong shape or dtype, a vertex index out of range,
an unknown variant or fix, fix="b" or fixed_b without B, a mask of the wrong length,
max_rounds < 1, VB without TB.

Example:
  >>> VA, TA = pdd.read_mesh("fixtures/meshes/tiny-a.msh")
  >>> VB, TB = pdd.read_mesh("fixtures/meshes/tiny-b.msh")
  >>> VA1, VB1, r = pdd.resolve(VA, TA, VB, TB, fix="a")
  >>> r["resolved"], len(r["rounds"]), (VA1 == VA).all()
  (True, 11, True)
  >>> V1, _, r = pdd.resolve(V, T)                  # self-contact of one mesh (V, T)
)doc";

}  // namespace

PYBIND11_MODULE(pdd, m) {
  py::options options;
  options.disable_function_signatures();  // each docstring starts with its text signature
  m.doc() = kModuleDoc;
  pthread_atfork(nullptr, nullptr, &Workers::forget_after_fork);
  cached = new Cached{py::module_::import("fractions").attr("Fraction"),
                      py::module_::import("numpy").attr("bool_"),
                      py::module_::import("numpy").attr("asarray"),
                      py::module_::import("os").attr("fsdecode")};
  m.attr("__version__") = PDD_VERSION;
  m.attr("KEYS") = py::make_tuple("name", "intersecting", "rigid_pd2", "eq11_pd2", "pdd2_static",
                                  "pdd2", "pdd2_relaxed", "pdd2_accel1", "pdd2_accel6",
                                  "rigid_dir", "pdd2_static_dir", "pdd2_dir", "pdd2_relaxed_dir",
                                  "q1_A", "q1_B", "error", "pdd2_global", "pdd2_global_normal",
                                  "q1_A_global", "q1_B_global", "pdd2_global_lower",
                                  "pdd2_global_error");
  // The defaults of pdd.h's SolveOptions (the CLI's too)
  const pdd::reference::SolveOptions defaults;
  m.def("solve", &solve, kSolveDoc, py::arg("A"), py::arg("B"), py::arg("engine") = "fast",
        py::arg("formulation") = pdd::to_string(defaults.formulation), py::arg("name") = "",
        py::arg("with_global") = defaults.with_global, py::arg("gradient") = defaults.gradient);
  m.def("solve_batch", &solve_batch, kSolveBatchDoc, py::arg("A"), py::arg("B"),
        py::arg("threads") = py::none(), py::arg("with_global") = defaults.with_global,
        py::arg("gradient") = defaults.gradient, py::arg("progress") = py::none());
  m.def("read_fixtures", &read_fixtures, kReadFixturesDoc, py::arg("path"));
  m.def("mesh_contacts", &mesh_contacts, kMeshContactsDoc, py::arg("VA"), py::arg("TA"),
        py::arg("VB") = py::none(), py::arg("TB") = py::none(),
        py::arg("variants") = "rigid,static,pdd2,accel1", py::arg("engine") = "fast",
        py::arg("threads") = py::none(), py::arg("progress") = py::none());
  m.def("read_mesh", &read_mesh, kReadMeshDoc, py::arg("path"));
  m.def("resolve", &resolve, kResolveDoc, py::arg("VA"), py::arg("TA"), py::arg("VB") = py::none(),
        py::arg("TB") = py::none(), py::arg("fix") = py::none(), py::arg("variant") = "global",
        py::arg("max_rounds") = 200, py::arg("threads") = py::none(),
        py::arg("progress") = py::none(), py::arg("fixed_a") = py::none(),
        py::arg("fixed_b") = py::none());
}
