// module.cpp — the Python module `pdd` (pybind11): both engines from Python.
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
// pdd::mesh) and on pdd::io's fixture reader (the one `pdd solve` uses, so messages are the
// CLI's). Many records become columns in one place (RecordColumns). Numbers:
// the fast engine's are Python floats, the reference engine's fractions.Fraction, built from
// GMP's integers exactly (never through a float). Every engine call runs with the GIL released;
// the long ones (solve_batch, mesh_contacts, resolve) stop on Ctrl-C (LongCall).
//
// This file: the module itself (its docstring, __version__, KEYS) and the registration of the
// functions, one file per library they bind: pdd.cpp (<pdd/pdd.h>), io.cpp (pdd::io's fixture
// reader), mesh.cpp (<pdd/mesh.h>); shared helpers in common.h, long_call.h (threads, Ctrl-C,
// progress) and record_columns.h.
#include <pybind11/pybind11.h>

#include <pthread.h>

#include <new>

#include <oneapi/tbb/global_control.h>

#include "common.h"
#include "long_call.h"

namespace pdd_python {
namespace {

// ---------------------------------------------------------------------------------------------
// Docstrings: help(pdd) reads like the README.

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
  resolve(VA, TA, VB=None, TB=None, fix=None, variant=..., max_rounds=..., ...)
                                       move the meshes' vertices until no element pair
                                       intersects, checked exactly -> (VA1, VB1, report)

Example:
  >>> import pdd
  >>> A = [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]]
  >>> B = [[2, 2, 2], [2.5, 2, 2], [2, 2.5, 2], [2, 2, 2.5]]
  >>> r = pdd.solve(A, B, engine="reference")
  >>> r["rigid_pd2"], r["eq11_pd2"], r["pdd2"], r["pdd2_dir"]
  (Fraction(16, 3), Fraction(1, 12), Fraction(4, 5), 'VF:0')

KEYS is the tuple of every key a record can have, in the order `pdd solve` writes them
(pdd2_global_lower: exact engine only; pdd2_global_error: fast engine only; pdd2_global_grad:
with gradient=True).
)doc";

// Fork (os.fork; multiprocessing's default start method on Linux): the child has only the
// forking thread. Workers forgets the parent's long-call threads, and TBB's worker threads are
// joined before the fork (tbb::finalize on a handle attached at import, as numba's TBB backend
// does): a child that inherits a scheduler whose workers held its slots or locks at the fork can
// wait forever in its first parallel_for. When they cannot be joined (another thread is inside a
// TBB call at that moment), finalize says so and the fork goes on as without it.
oneapi::tbb::task_scheduler_handle* scheduler = nullptr;  // never destroyed (outlives every call)
void attach_scheduler() { *scheduler = oneapi::tbb::task_scheduler_handle{oneapi::tbb::attach{}}; }
void before_fork() {
  if (*scheduler) oneapi::tbb::finalize(*scheduler, std::nothrow);  // releases the handle either way
}
void after_fork_in_parent() { attach_scheduler(); }
void after_fork_in_child() {
  Workers::forget_after_fork();
  attach_scheduler();
}

}  // namespace
}  // namespace pdd_python

PYBIND11_MODULE(pdd, m) {
  using namespace pdd_python;
  py::options options;
  options.disable_function_signatures();  // each docstring starts with its text signature
  m.doc() = kModuleDoc;
  scheduler = new oneapi::tbb::task_scheduler_handle;
  attach_scheduler();
  pthread_atfork(&before_fork, &after_fork_in_parent, &after_fork_in_child);
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
                                  "pdd2_global_error", "pdd2_global_grad");
  bind_pdd(m);
  bind_io(m);
  bind_mesh(m);
  bind_energy(m);
}
