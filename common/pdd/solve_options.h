// solve_options.h — the options of pdd.h's solve_pair and solve_batch, one struct per engine,
// set once with the recommended defaults (plain data; included by pdd.h). `pdd solve` and the
// Python module use the same names and defaults:
//   with_global  (--no-global, with_global=False)  compute pdd2_global and its keys (default).
//                Not `global`: that is a Python keyword.
//   values       (--variants, variants='all')       fast engine: which definitions §5 values to
//                compute (default: all); the CLI and Python also leave the others' keys out
//                and take definitions §9 (with_global) from the same list, as `pdd mesh` does.
//   gradient     (--gradient, gradient=True)        also pdd2_global's gradient with respect to
//                the eight vertices at their current positions (the pair as given;
//                PairResult::pdd2_global_grad; definitions §9 says what it is).
//                Off by default; it needs with_global (without it the field stays empty; the
//                CLI and Python reject the combination).
//   formulation  (--formulation, formulation=)      reference engine: the per-direction QP.
//                Default Reduced: exactly the values of Full (tested on every shipped pair: the
//                golden files are the same bytes either way), about 7 times faster; Full solves
//                the paper's own 27 variables, for checking.
// How the fast engine computed a pair (exact path, refinement) is part of its record
// (PairResult::stats), not an out-parameter: a batch's counts are a sum over its records, with
// no counter shared between threads.
#pragma once

#include "pdd/pair_result.h"
#include "pdd/qp_formulation.h"

namespace pdd::fast {

struct SolveOptions {
  // false: skip definitions §9 (pdd2_global 0, no normal, q1_*_global the rest pose); it is about
  // 3.5 of the call's 13 us on the paper's protocol.
  bool with_global = true;
  // true (with with_global): fill pdd2_global_grad, from q1_*_global in doubles. Accuracy
  // (derived at global_gradient in fast/src/solve_pair.cpp): the positions attain the value
  // f to eps = 2e-9 and are separated up to tau = 1e-9 R (definitions §8, R the pair's largest
  // coordinate magnitude), which bounds the gradient's error in the dual object norm by
  //     |g_fast - g|_* <= 2 sqrt((1 + K) (eps f + 2 sqrt(f) tau + tau^2))
  // (K = 0 where the separated set is locally convex; K measures how sharply it bends): 4.5e-5
  // of |g|_* = 2 sqrt(f) when tau is negligible, an absolute ~2 sqrt(2 sqrt(f) tau) on contacts
  // far shallower than the pair's extent, where the gradient is not accurate relatively.
  // python/tests/test_gradient.py holds it to this bound against the exact engine on every
  // golden pair. Measured: within 1.4e-14 of the exact engine's on the paper's pairs
  // (both polish the same minimiser), inside its certified intervals; up to 3.2e-8 relative on
  // pairs of a turned block of five-tetrahedra cubes resting 0.01 deep on a Kuhn block
  // (positions within 3e-11 of the exact ones at coordinates ~0.4; the bound above allows
  // 1.2e-3 of |g| there). Where minimisers tie the
  // two engines may return different ones (smoke.json's nested-1, B symmetric in A's corner),
  // hence different gradients: each is valid (definitions §9, "Ties").
  bool gradient = false;
  // Which definitions §5 values to compute: bit k is the value kValueKeys[k] of pair_result.h
  // (the bits of pdd::mesh::Variant; `pdd mesh` and mesh_contacts pass their variants). The
  // others are reported 0 with no label (q1_A, q1_B: the rest pose when pdd2 is not asked).
  // The values an asked one is kept against (definitions §5's relations, in the doubles:
  // fast/src/certification/value_relations.h) are computed too, and left out of the record the
  // same way: rigid_pd2 always; pdd2 needs pdd2_static and pdd2_accel1, pdd2_accel6 and
  // pdd2_relaxed need pdd2, with_global needs pdd2_relaxed. So an asked value has the same bits
  // whatever else is asked (tests/fast/fast_batch_test.cpp) — where the full record is
  // representable: at the edges of the double range a value not asked can make it "not
  // representable" while the asked ones are. `pdd mesh`'s default (rigid,
  // static, pdd2, accel1) skips pdd2_accel6, eq11_pd2 and pdd2_relaxed: about 40% of the
  // record's time on the paper's pairs, 55% on aligned ones (docs/performance.md).
  unsigned values = (1u << kValueCount) - 1;
};

}  // namespace pdd::fast

namespace pdd::reference {

struct SolveOptions {
  // of the per-direction QP (pdd/qp_formulation.h): both give the same result; Reduced is
  // faster, Full solves the paper's own variables.
  QpFormulation formulation = QpFormulation::Reduced;
  // definitions §9 (pdd2_global, its normal, positions and proved lower bound, to the gap 1e-12): a
  // branch and bound of 5 to 50 ms more per pair. false skips it: then pdd2_global =
  // pdd2_global_lower = 0, no normal, q1_*_global = the rest pose.
  bool with_global = true;
  // true (with with_global): fill pdd2_global_grad exactly: -d sigma/d d at the exact witness
  // positions q1_*_global. "Exact" is the slope of the majorant (*) of definitions §9, exactly; the true
  // minimiser is in general irrational (an eigenvector), and the witness pins the value, not
  // the minimiser: its value is within 1e-12 of the minimum, so near a nondegenerate minimum
  // the witness, hence the gradient, is within about sqrt(1e-12) = 1e-6 (relative) of the true
  // one. A certified bound on the true gradient costs more global solves: by (*) applied at
  // P and P -/+ h e_k, each component lies in [(lower(P + h e_k) - value(P)) / h - h sigma(e_k),
  // (value(P) - lower(P - h e_k)) / h + h sigma(e_k)] (tests/reference/test_global_gradient.cpp
  // computes these intervals).
  bool gradient = false;
};

}  // namespace pdd::reference
