// pdd.cpp — pdd.solve and pdd.solve_batch: one pair, or N pairs on all cores, with either
// engine of <pdd/pdd.h> (pdd::fast, pdd::reference).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "common.h"
#include "long_call.h"
#include "pdd/mesh/variants.h"
#include "pdd/pdd.h"
#include "record_columns.h"

namespace pdd_python {
namespace {

// The fast engine's options for the values asked (pdd::mesh::Variant bits).
pdd::fast::SolveOptions fast_options(unsigned variants, bool gradient) {
  pdd::fast::SolveOptions o;
  o.with_global = (variants & pdd::mesh::kGlobal) != 0;
  o.gradient = gradient;
  o.values = variants & ((1u << pdd::kValueCount) - 1);
  return o;
}

// The values asked: variants= parsed as `pdd solve --variants` parses it, less definitions §9
// when with_global=False; ValueError when nothing is left.
unsigned asked_variants(py::handle variants_arg, bool global) {
  unsigned v = 0;
  try {
    v = pdd::mesh::parse_variants(text_arg(variants_arg, "variants"));
  } catch (const std::invalid_argument& e) {
    value_error(std::string("variants: ") + e.what());
  }
  if (!global) v &= ~unsigned(pdd::mesh::kGlobal);
  if (!v) value_error("with_global=False leaves nothing of variants='global'");
  return v;
}

py::dict solve(py::handle A, py::handle B, py::handle engine_arg, py::handle formulation_arg,
               py::handle name_arg, py::handle global_arg, py::handle gradient_arg, py::handle variants_arg) {
  const unsigned variants = asked_variants(variants_arg, bool_arg(global_arg, "with_global"));
  const bool global = (variants & pdd::mesh::kGlobal) != 0;
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
      r = pdd::fast::solve_pair(pair, fast_options(variants, gradient));
    }
    r.name = name;
    return record(r, variants);
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
  return record(r, variants);
}

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
  check_integers_exact(a, which);
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
}

// Pairs a chunk of solve_batch's loop holds (its records' memory: about 700 bytes a pair).
constexpr std::size_t kChunk = 1 << 15;
// Batches of more pairs than this are watched for Ctrl-C (LongCall); smaller ones take about a
// millisecond a core (a few when some take the exact path) and run on the calling thread.
constexpr std::size_t kWatchedPairs = 256;

py::dict solve_batch(py::handle A_in, py::handle B_in, py::handle threads_in, py::handle global_arg,
                     py::handle gradient_arg, py::handle progress_arg, py::handle variants_arg) {
  const unsigned variants = asked_variants(variants_arg, bool_arg(global_arg, "with_global"));
  const bool global = (variants & pdd::mesh::kGlobal) != 0;
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
  RecordColumns out(n, /*exact=*/false, variants & ((1u << pdd::kValueCount) - 1),
                    /*positions=*/(variants & pdd::mesh::kPdd2) != 0, global, gradient);
  const pdd::fast::SolveOptions options = fast_options(variants, gradient);
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
// Docstrings: help(pdd.solve) reads like the README.

constexpr const char* kSolveDoc = R"doc(solve(A, B, engine='fast', formulation='reduced', name='', with_global=True, gradient=False, variants='all')
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
         eight vertices at their current positions (A, B as given), 8 x [x, y, z] (A's s0..s3, then B's r0..r3): minus the object
         norm's derivative at the displacement to q1_A_global, q1_B_global (docs/definitions.md §9 says why;
         how exact: §8). None where pdd2_global is None; 0 when not intersecting. Needs
         with_global=True (ValueError otherwise). `pdd solve --gradient`.
variants comma-separated, which values to compute and return, as `pdd solve --variants`
         and mesh_contacts name them: rigid (rigid_pd2), eq11 (eq11_pd2), static
         (pdd2_static), pdd2 (pdd2, q1_A, q1_B), relaxed (pdd2_relaxed), accel1
         (pdd2_accel1), accel6 (pdd2_accel6), global (pdd2_global and its keys), or "all"
         (the default). A value comes with its label; the other values' keys are left out.
         From the fast engine each value asked is the same double as with "all", and only
         it and what it is kept against (docs/definitions.md §5's relations) is computed:
         variants="rigid,pdd2" takes less than half the time of "all". with_global=False
         removes "global" (nothing left: ValueError).

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

constexpr const char* kSolveBatchDoc = R"doc(solve_batch(A, B, threads=None, with_global=True, gradient=False, progress=None, variants='all')
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
variants which values to compute and return, as in solve(): the other values' arrays are
         left out (q1_A, q1_B come with pdd2).
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
  >>> A, B = rng.uniform(0, 10, (2, 10000, 4, 3))
  >>> r = pdd.solve_batch(A, B)
  >>> print(f'{r["pdd2"][r["intersecting"]].mean():.6g}')
  0.181549
)doc";

}  // namespace

void bind_pdd(py::module_& m) {
  // The defaults of pdd.h's SolveOptions (the CLI's too)
  const pdd::reference::SolveOptions defaults;
  m.def("solve", &solve, kSolveDoc, py::arg("A"), py::arg("B"), py::arg("engine") = "fast",
        py::arg("formulation") = pdd::to_string(defaults.formulation), py::arg("name") = "",
        py::arg("with_global") = defaults.with_global, py::arg("gradient") = defaults.gradient,
        py::arg("variants") = "all");
  m.def("solve_batch", &solve_batch, kSolveBatchDoc, py::arg("A"), py::arg("B"),
        py::arg("threads") = py::none(), py::arg("with_global") = defaults.with_global,
        py::arg("gradient") = defaults.gradient, py::arg("progress") = py::none(),
        py::arg("variants") = "all");
}

}  // namespace pdd_python
