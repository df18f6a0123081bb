"""pdd.solve_batch: bit for bit the single calls, on all cores with the GIL released; rejected
pairs are error entries, malformed arrays raise ValueError."""
import json
import math
import re
import subprocess
import threading
import time

import numpy as np
import pytest

import pdd
from conftest import LABEL_KEYS, VALUE_KEYS, golden_cases

BATCH_KEYS = ("intersecting",) + VALUE_KEYS + LABEL_KEYS + ("q1_A", "q1_B", "error", "slow_paths",
             "pdd2_global", "pdd2_global_normal", "q1_A_global", "q1_B_global", "pdd2_global_error")


def random_pairs(n, seed=3):
    A, B = np.random.default_rng(seed).uniform(0, 10, (2, n, 4, 3))
    return A, B


def bits(x):
    return np.asarray(x, dtype=np.float64).view(np.int64)


def assert_batch_equals_single(A, B, res):
    n = len(A)
    assert set(res) == set(BATCH_KEYS)
    for k in VALUE_KEYS:
        assert res[k].shape == (n,) and res[k].dtype == np.float64
    for k in LABEL_KEYS:
        assert res[k].shape == (n,) and res[k].dtype.kind == "U"
    assert res["intersecting"].dtype == np.bool_
    assert res["q1_A"].shape == (n, 4, 3) and res["q1_B"].shape == (n, 4, 3)
    assert isinstance(res["error"], list) and len(res["error"]) == n
    for j in range(n):
        r = pdd.solve(A[j], B[j])
        assert res["error"][j] == r["error"], j
        if r["error"] is not None:
            assert not res["intersecting"][j]
            assert all(math.isnan(res[k][j]) for k in VALUE_KEYS)
            assert all(res[k][j] == "" for k in LABEL_KEYS)
            assert np.isnan(res["q1_A"][j]).all() and np.isnan(res["q1_B"][j]).all()
            continue
        assert res["intersecting"][j] == r["intersecting"], j
        for k in VALUE_KEYS:  # bit for bit, including the sign of zero
            assert bits(res[k][j]) == bits(r[k]), (j, k)
        for k in LABEL_KEYS:
            assert res[k][j] == (r[k] or ""), (j, k)
        assert (bits(res["q1_A"][j]) == bits(r["q1_A"])).all(), j
        assert (bits(res["q1_B"][j]) == bits(r["q1_B"])).all(), j
        # definitions §9 columns
        assert bits(res["pdd2_global"][j]) == bits(r["pdd2_global"]), j
        if r["pdd2_global_normal"] is None:
            assert np.isnan(res["pdd2_global_normal"][j]).all(), j
        else:
            assert (bits(res["pdd2_global_normal"][j]) == bits(r["pdd2_global_normal"])).all(), j
        for k in ("q1_A_global", "q1_B_global"):
            assert (bits(res[k][j]) == bits(r[k])).all(), (j, k)


def test_batch_equals_single_calls_on_random_pairs():
    A, B = random_pairs(3000)
    res = pdd.solve_batch(A, B)
    assert 0 < res["intersecting"].sum() < 3000
    assert isinstance(res["slow_paths"], int) and 0 <= res["slow_paths"] <= 3000
    assert_batch_equals_single(A, B, res)


def test_batch_equals_single_calls_on_golden_pairs():
    cases = golden_cases()
    A = np.array([p["A"] for _, p, _ in cases])
    B = np.array([p["B"] for _, p, _ in cases])
    assert_batch_equals_single(A, B, pdd.solve_batch(A, B))


def test_threads_do_not_change_results():
    A, B = random_pairs(2000, seed=5)
    ref = pdd.solve_batch(A, B)
    for threads in (1, 2, np.int64(3)):
        res = pdd.solve_batch(A, B, threads=threads)
        for k in VALUE_KEYS + ("q1_A", "q1_B"):
            assert (bits(res[k]) == bits(ref[k])).all(), (threads, k)
        for k in LABEL_KEYS + ("intersecting",):
            assert (res[k] == ref[k]).all(), (threads, k)
        assert res["error"] == ref["error"] and res["slow_paths"] == ref["slow_paths"]


def test_rejected_pairs_are_error_entries():
    A, B = random_pairs(50, seed=11)
    flat = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], dtype=float)
    A[3] = flat
    B[7, 2, 1] = np.inf
    A[9, 0, 0] = np.nan
    B[9] = flat
    res = pdd.solve_batch(A, B)
    assert res["error"][3] == "tetrahedron A is flat: its four vertices are coplanar (volume 0)"
    assert res["error"][7] == "tetrahedron B: vertex 2 coordinate y is not finite (inf)"
    assert res["error"][9] == ("tetrahedron A: vertex 0 coordinate x is not finite (nan); "
                               "tetrahedron B is flat: its four vertices are coplanar (volume 0)")
    assert sum(e is not None for e in res["error"]) == 3
    assert_batch_equals_single(A, B, res)


def test_inputs_converted_to_float64():
    A, B = random_pairs(20, seed=2)
    ref = pdd.solve_batch(A, B)
    for a, b in ((A.tolist(), B.tolist()), (np.asfortranarray(A), B[::1]),
                 (A.astype(np.float32).astype(np.float64), B)):
        res = pdd.solve_batch(a, b)
        exp = pdd.solve_batch(np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64))
        assert (bits(res["pdd2"]) == bits(exp["pdd2"])).all()
    Ai = np.round(A).astype(np.int64)
    Bi = np.round(B).astype(np.int32)
    res = pdd.solve_batch(Ai, Bi)
    exp = pdd.solve_batch(Ai.astype(float), Bi.astype(float))
    assert (bits(res["rigid_pd2"]) == bits(exp["rigid_pd2"])).all()
    # a strided view (every other pair) is the same as its copy
    res = pdd.solve_batch(A[::2], B[::2])
    assert (bits(res["pdd2"]) == bits(ref["pdd2"][::2])).all()


def test_empty_batch():
    res = pdd.solve_batch(np.zeros((0, 4, 3)), np.zeros((0, 4, 3)))
    assert res["pdd2"].shape == (0,) and res["q1_A"].shape == (0, 4, 3)
    assert res["error"] == [] and res["slow_paths"] == 0


@pytest.mark.parametrize("A, B, message", [
    (np.zeros((5, 4, 2)), np.zeros((5, 4, 3)), r"A must have shape \(N, 4, 3\); got \(5, 4, 2\)"),
    (np.zeros((4, 3)), np.zeros((4, 3)), r"A must have shape \(N, 4, 3\); got \(4, 3\)"),
    (np.zeros((5, 4, 3)), np.zeros((6, 4, 3)), "A and B must hold the same number of pairs; got 5 and 6"),
    (np.zeros((5, 4, 3)), np.full((5, 4, 3), "1"), "B must be an array of real numbers"),
    (np.zeros((5, 4, 3)), np.zeros((5, 4, 3), dtype=bool), "B must be an array of real numbers"),
    (np.zeros((5, 4, 3)), np.zeros((5, 4, 3), dtype=complex), "B must be an array of real numbers"),
    (np.zeros((5, 4, 3)), np.zeros((5, 4, 3), dtype=object), "B must be an array of real numbers"),
    ([[[0, 0, 0]] * 4] * 2, [[[0, 0, 0]] * 4, [[0, 0, 0]] * 3], None),  # ragged
])
def test_malformed_batches_raise_value_error(A, B, message):
    with pytest.raises(ValueError, match=message):
        pdd.solve_batch(A, B)


THREADS_MESSAGE = r"^threads must be 0 \(all cores\) or an int from 1 to 4096, or None; got "


@pytest.mark.parametrize("threads", [-1, 4097, 10**6, 2**80, 1.5, 2.0, "2", True, False, np.bool_(True)])
def test_bad_threads_raise_value_error(threads):
    with pytest.raises(ValueError, match=THREADS_MESSAGE + re.escape(repr(threads)) + "$"):
        pdd.solve_batch(np.zeros((1, 4, 3)), np.zeros((1, 4, 3)), threads=threads)


@pytest.mark.parametrize("threads", [None, 0, np.int64(0), 1, 4096, np.uint16(4096)])
def test_threads_as_the_cli_reads_them(threads):
    """None and 0 are all cores, 1..4096 at most that many (4096: all of this machine's)."""
    A, B = random_pairs(50, seed=5)
    res = pdd.solve_batch(A, B, threads=threads)
    ref = pdd.solve_batch(A, B)
    assert (bits(res["pdd2"]) == bits(ref["pdd2"])).all()


def test_threads_rule_is_the_clis(pdd_cli, tmp_path):
    """The same numbers are accepted by `pdd solve --threads` and solve_batch(threads=...)."""
    path = tmp_path / "one.json"
    path.write_text(json.dumps({"pairs": [{"name": "p", "A": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                                           "B": [[2, 2, 2], [3, 2, 2], [2, 3, 2], [2, 2, 3]]}]}))
    for threads in (-1, 0, 1, 2, 4096, 4097):
        cli = subprocess.run([pdd_cli, "solve", "--engine", "fast", "--quiet", "--input", str(path),
                              "--threads", str(threads)], capture_output=True, text=True)
        try:
            pdd.solve_batch(np.zeros((1, 4, 3)), np.zeros((1, 4, 3)), threads=threads)
            python_ok = True
        except ValueError:
            python_ok = False
        assert (cli.returncode == 0) == python_ok, (threads, cli.returncode, cli.stderr)


def python_work_during(call):
    """How many Python loop iterations the main thread makes while `call` runs in another
    thread: none if `call` holds the GIL throughout. `call` must be ONE call into the module:
    between two calls the calling thread runs bytecode and hands the GIL over for a switch
    interval (5 ms, hundreds of thousands of iterations) even if each call holds it (measured:
    sum(range(3 * 10**7)) gives 0, three sum(range(10**7)) in a row about 2e5)."""
    done = threading.Event()
    started = threading.Event()

    def worker():
        started.set()
        call()
        done.set()

    t = threading.Thread(target=worker)
    t.start()
    started.wait()
    time.sleep(0.05)  # let the call enter the engine
    # A call that ended during that wait says nothing either way (count 0 whether or not it
    # released the GIL): the workload must last well beyond 50 ms on every machine.
    assert not done.is_set(), "the call ended within the 50 ms start-up wait: give it more work"
    count = 0
    while not done.is_set():
        count += 1
    t.join()
    return count


def test_batch_releases_the_gil():
    A, B = random_pairs(60000, seed=13)  # ~0.4 s on two cores of an EPYC (13 us per pair)
    assert python_work_during(lambda: pdd.solve_batch(A, B)) > 1000


def test_reference_solve_releases_the_gil():
    A = [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]]
    B = [[2, 2, 2], [2.5, 2, 2], [2, 2.5, 2], [2, 2, 2.5]]
    # one call (see python_work_during): about 0.9 s with the full formulation
    assert python_work_during(lambda: pdd.solve(A, B, engine="reference", formulation="full")) > 1000


def test_concurrent_first_calls_in_a_fresh_interpreter(tmp_path):
    """Threads calling into a freshly imported module at once (every entry point, both engines)
    finish: nothing in the module waits for a lock while holding the GIL (a C++ function-local
    static built on first use did, and hung the golden test once)."""
    import subprocess
    import sys
    from conftest import FIXTURES
    code = f"""
import threading, numpy as np, pdd
A = [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]]
B = [[2, 2, 2], [2.5, 2, 2], [2, 2.5, 2], [2, 2, 2.5]]
calls = [lambda: pdd.solve(A, B, engine="reference"), lambda: pdd.solve(A, B, engine="reference"),
         lambda: pdd.solve(A, B), lambda: pdd.solve_batch(np.array([A] * 500), np.array([B] * 500)),
         lambda: pdd.read_fixtures({str(FIXTURES / 'smoke.json')!r}), lambda: pdd.solve(A, B, engine="reference"),
         lambda: pdd.mesh_contacts(*pdd.read_mesh({str(FIXTURES / 'meshes' / 'tiny-a.msh')!r}), variants="all")]
go = threading.Barrier(len(calls))
def run(f):
    go.wait()
    f()
ts = [threading.Thread(target=run, args=(f,)) for f in calls]
[t.start() for t in ts]
[t.join() for t in ts]
print("done")
"""
    for _ in range(3):
        out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                             text=True, timeout=120)
        assert out.returncode == 0 and out.stdout.strip() == "done", out.stderr


def test_fast_normals_have_one_scale():
    """The fast engine's pdd2_global_normal, from solve() and solve_batch() alike (the same bits),
    is scaled by a power of two so that its largest |component| is in [1, 2): checked on every
    intersecting pair of the shipped fixtures and on random paper-protocol pairs."""
    pairs = [(p["A"], p["B"]) for _, p, _ in golden_cases()]
    rng = np.random.default_rng(5)
    pairs += [(a.tolist(), b.tolist()) for a, b in rng.uniform(0, 10, (200, 2, 4, 3))]
    A = np.array([a for a, _ in pairs], dtype=float)
    B = np.array([b for _, b in pairs], dtype=float)
    batch = pdd.solve_batch(A, B)
    seen = 0
    for k, (a, b) in enumerate(pairs):
        r = pdd.solve(a, b)
        if r.get("error") or not r["intersecting"] or r["pdd2_global_normal"] is None:
            continue
        n = np.array(r["pdd2_global_normal"])
        assert 1 <= np.abs(n).max() < 2, (k, n)
        assert (batch["pdd2_global_normal"][k] == n).all(), k
        seen += 1
    assert seen > 100
