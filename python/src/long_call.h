// long_call.h — internal to python/src: the calls that run long (solve_batch, mesh_contacts,
// resolve): their `threads` argument, the threads that compute them, their `progress`
// argument, and LongCall, which keeps them stoppable by Ctrl-C with the GIL released.
#pragma once

#include <pybind11/pybind11.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "common.h"

namespace pdd_python {

// `threads`, as the CLI's --threads: None or 0 all cores, 1..4096 at most that many (numpy
// integers too; not float, not bool). nullopt stands for all cores.
constexpr long kMaxThreads = 4096;
inline std::optional<int> threads_arg(py::handle threads_in) {
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
  // `unit`: what done and total count, for the bar ("pair", "round"). `open_ended`: `total` is
  // only a limit the call usually stops well before (resolve's max_rounds): the tqdm bar is
  // then a counter ("7 round [00:02, pairs=0]") rather than a bar whose length jumps from the
  // limit to the rounds run; a callable gets (done, total) all the same.
  Progress(py::handle arg, const char* what, const char* unit = "pair", bool open_ended = false)
      : what_(what), unit_(unit), open_ended_(open_ended) {
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
    if (!active() || (said_ && done == done_ && total == total_ && postfix == postfix_)) return;
    if (tqdm_) {
      if (!bar_)
        bar_ = tqdm_(py::arg("total") = open_ended_ ? py::object(py::none()) : py::object(py::int_(total)),
                     py::arg("desc") = what_, py::arg("unit") = unit_);
      if (!open_ended_ && total != total_ && said_) bar_.attr("total") = total;  // a run that stopped early
      if (!postfix.empty()) bar_.attr("set_postfix_str")(postfix, py::arg("refresh") = false);
      bar_.attr("update")(done - done_);
      if (done == done_) bar_.attr("refresh")();  // only the postfix changed
    } else {
      callable_(done, total);
    }
    said_ = true, done_ = done, total_ = total, postfix_ = postfix;
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
  bool open_ended_ = false;
  py::object callable_, tqdm_, bar_;
  bool said_ = false;
  std::size_t done_ = 0, total_ = 0;
  std::string postfix_;
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
      // The last word: every pair (round) done, and `pairs` as the computation left it (resolve:
      // the pairs that still intersect), not as the last round found it.
      const std::size_t t = total.load();
      const std::size_t p = pairs.load();
      if (t != kUnknown) progress_.report(t, t, p == kUnknown ? std::string() : "pairs=" + std::to_string(p));
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

}  // namespace pdd_python
