"""pdd.solve and pdd.read_fixtures on every kind of input: array-likes, exact numbers, malformed
arguments (ValueError naming the problem), rejected pairs (an error record with the CLI's words,
never an exception), fixture files (the same messages and records as `pdd solve`)."""
import inspect
import json
import os
import pathlib
import pydoc
import subprocess
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest

import pdd
from conftest import FIXTURES, LABEL_KEYS, VALUE_KEYS, golden_records

A = [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]]
B = [[2, 2, 2], [2.5, 2, 2], [2, 2.5, 2], [2, 2, 2.5]]  # nested-1 of fixtures/smoke.json
FLAT = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]
ENGINES = ("fast", "reference")


def test_module_surface():
    assert pdd.KEYS == ("name", "intersecting") + VALUE_KEYS + LABEL_KEYS + (
        "q1_A", "q1_B", "error", "pdd2_global", "pdd2_global_normal", "q1_A_global", "q1_B_global",
        "pdd2_global_lower", "pdd2_global_error", "pdd2_global_grad")
    # the keys of `pdd solve`'s records: the exact engine's (golden) end with pdd2_global_lower, the
    # fast engine's with pdd2_global_error instead; pdd2_global_grad only with gradient=True
    assert pdd.KEYS[:-2] == tuple(golden_records("smoke.json")[0])
    first = pdd.read_fixtures(str(FIXTURES / "smoke.json"))[0]
    assert tuple(pdd.solve(first["A"], first["B"])) == tuple(
        k for k in pdd.KEYS if k not in ("pdd2_global_lower", "pdd2_global_grad"))
    assert tuple(pdd.solve(first["A"], first["B"], gradient=True)) == tuple(
        k for k in pdd.KEYS if k != "pdd2_global_lower")
    assert isinstance(pdd.__version__, str)
    for f in (pdd, pdd.solve, pdd.solve_batch, pdd.read_fixtures):
        assert f.__doc__ and len(f.__doc__) > 400, f
    single = inspect.signature(pdd.solve).parameters
    assert list(single) == ["A", "B", "engine", "formulation", "name", "with_global", "gradient", "variants"]
    # pdd.h's SolveOptions defaults, as `pdd solve` has them
    assert (single["formulation"].default, single["with_global"].default, single["gradient"].default,
            single["variants"].default) == ("reduced", True, False, "all")
    batch = inspect.signature(pdd.solve_batch).parameters
    assert list(batch) == ["A", "B", "threads", "with_global", "gradient", "progress", "variants"]
    assert batch["threads"].default is None and batch["progress"].default is None
    assert batch["with_global"].default is True and batch["gradient"].default is False
    text = pydoc.render_doc(pdd.solve_batch, renderer=pydoc.plaintext)
    for words in ("solve_batch(A, B, threads=None, with_global=True, gradient=False, progress=None, variants='all')", "None or 0: all cores",
                  "progress(done, total)", "tqdm", "Ctrl-C", "KeyboardInterrupt", "bit for bit"):
        assert words in text, words
    text = pydoc.render_doc(pdd.solve, renderer=pydoc.plaintext)
    for words in ("solve(A, B, engine='fast', formulation='reduced', name='', with_global=True, gradient=False, variants='all')",
                  "fractions.Fraction",
                  "rigid_pd2", "pdd2_relaxed_dir", "q1_A", "ValueError", "definitions.md §8", "GIL"):
        assert words in text, words


@pytest.mark.parametrize("engine", ENGINES)
def test_array_likes_and_exact_numbers_are_the_same_pair(engine):
    ref = pdd.solve(A, B, engine=engine)
    assert ref["pdd2"] == (Fraction(4, 5) if engine == "reference" else 0.8)
    same = [
        (tuple(map(tuple, A)), tuple(map(tuple, B))),
        (np.array(A), np.array(B, dtype=np.float64)),
        (np.array(A, dtype=np.int32), np.array(B, dtype=np.float32)),
        (np.array(A, dtype=np.float64).T.copy().T, np.asfortranarray(B)),
        ([[Fraction(c) for c in v] for v in A], [[Fraction(c) for c in v] for v in B]),
        ([[Decimal(c) for c in v] for v in A], [[Decimal(str(c)) for c in v] for v in B]),
        ([[np.float32(c) for c in v] for v in A], [[np.int64(c * 2) / 2 for c in v] for v in B]),
        (list(map(list, np.array(A))), B),  # rows that are numpy arrays
    ]
    for a, b in same:
        assert pdd.solve(a, b, engine=engine) == ref


@pytest.mark.parametrize("bad, message", [
    (A[:3], r"A must be 4 vertices of 3 coordinates \(shape \(4, 3\)\); got 3 vertices"),
    (A + [[1, 1, 1]], "got 5 vertices"),
    ([[0, 0, 0], [10, 0], [0, 10, 0], [0, 0, 10]], r"A\[1\] must be 3 coordinates; got 2"),
    ([[0, 0, 0], 10, [0, 10, 0], [0, 0, 10]], r"A\[1\] must be 3 coordinates; got 10"),
    (np.zeros(12), r"got an array of shape \(12,\)"),
    (np.zeros((4, 3, 1)), r"got an array of shape \(4, 3, 1\)"),
    (np.zeros((3, 4)), r"got an array of shape \(3, 4\)"),
    (5, "got 5"),
    (None, "got None"),
    ("abcd", "got 'abcd'"),
    ([[0, 0, "1"], [10, 0, 0], [0, 10, 0], [0, 0, 10]], r"A\[0\]\[2\] is not a real number: '1'"),
    ([[0, 0, None], [10, 0, 0], [0, 10, 0], [0, 0, 10]], r"A\[0\]\[2\] is not a real number: None"),
    ([[0, 0, True], [10, 0, 0], [0, 10, 0], [0, 0, 10]], r"A\[0\]\[2\] is not a real number: True"),
    ([[0, 0, 1j], [10, 0, 0], [0, 10, 0], [0, 0, 10]], r"A\[0\]\[2\] is not a real number: 1j"),
    ([[0, 0, object()], [10, 0, 0], [0, 10, 0], [0, 0, 10]], r"A\[0\]\[2\] is not a real number"),
    (np.array([["0", "0", "0"]] * 4), r"A\[0\]\[0\] is not a real number: '0'"),
    (np.zeros((4, 3), dtype=bool), r"A\[0\]\[0\] is not a real number: False"),
    ([[Fraction(1, 3), 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]],
     r"A\[0\]\[0\] = Fraction\(1, 3\) is not exactly a double"),
    ([[Decimal("0.1"), 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]],
     r"A\[0\]\[0\] = Decimal\('0.1'\) is not exactly a double"),
    ([[2**53 + 1, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]], r"A\[0\]\[0\] = 9007199254740993 is not exactly a double"),
    # numpy integers: compared with a float, numpy rounds them first (np.int64(2**53 + 1) ==
    # 2.0**53 is True), so they are read through their exact Python int
    ([[np.int64(2**53 + 1), 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]], r"A\[0\]\[0\] = 9007199254740993 is not exactly a double"),
    ([[0, np.uint64(2**64 - 1), 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]], r"A\[0\]\[1\] = 18446744073709551615 is not exactly a double"),
    (np.array([[0, 0, -(2**53 + 1)], [10, 0, 0], [0, 10, 0], [0, 0, 10]], dtype=np.int64),
     r"A\[0\]\[2\] = -9007199254740993 is not exactly a double"),
    (np.array([[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 2**63 + 1]], dtype=np.uint64),
     r"A\[3\]\[2\] = 9223372036854775809 is not exactly a double"),
])
@pytest.mark.parametrize("engine", ENGINES)
def test_malformed_tetrahedra_raise_value_error(bad, message, engine):
    with pytest.raises(ValueError, match=message):
        pdd.solve(bad, B, engine=engine)
    with pytest.raises(ValueError, match=message.replace("A", "B", 1)):
        pdd.solve(A, bad, engine=engine)


@pytest.mark.parametrize("kwargs, message", [
    ({"engine": "gpu"}, "engine must be 'fast' or 'reference'; got 'gpu'"),
    ({"engine": None}, "engine must be a str; got None"),
    ({"formulation": "partial"}, "formulation must be 'reduced' or 'full'; got 'partial'"),
    ({"name": 3}, "name must be a str; got 3"),
    ({"gradient": 1}, "gradient must be True or False; got 1"),
    ({"with_global": False, "gradient": True}, r"gradient=True needs with_global=True"),
])
def test_bad_arguments_raise_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        pdd.solve(A, B, **kwargs)


@pytest.mark.parametrize("b, error", [
    (FLAT, "tetrahedron B is flat: its four vertices are coplanar (volume 0)"),
    ([[0, 0, 0], [1, 1, 1], [2, 2, 2], [3, 3, 3]], "tetrahedron B is flat: its four vertices are coplanar (volume 0)"),
    ([[0, 0, 0], [1, 0, 0], [0, float("inf"), 0], [0, 0, 1]], "tetrahedron B: vertex 2 coordinate y is not finite (inf)"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, float("nan")]], "tetrahedron B: vertex 3 coordinate z is not finite (nan)"),
    ([[0, 0, 0], [10**400, 0, 0], [0, 1, 0], [0, 0, 1]], "tetrahedron B: vertex 1 coordinate x is not finite (inf)"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, -Fraction(10**400)]], "tetrahedron B: vertex 3 coordinate z is not finite (-inf)"),
])
def test_rejected_pairs_are_error_records_with_the_same_words(b, error):
    for engine in ENGINES:
        assert pdd.solve(A, b, engine=engine, name="p") == {"name": "p", "error": error}
    both = pdd.solve(FLAT, b, engine="reference")["error"]
    assert both == "tetrahedron A is flat: its four vertices are coplanar (volume 0); " + error


def test_fractions_are_exact_beyond_the_double_range():
    # nested-1 scaled by 2^-600 and 2^600: every squared value scales by 2^-1200 / 2^1200,
    # far outside the double range, so only exact integers can carry it.
    for e in (-600, 600):
        s = Fraction(2) ** e
        a = [[c * 2.0**e for c in v] for v in A]
        b = [[c * 2.0**e for c in v] for v in B]
        r = pdd.solve(a, b, engine="reference", name="scaled")
        assert r["rigid_pd2"] == Fraction(16, 3) * s * s
        assert r["eq11_pd2"] == Fraction(1, 12) * s * s
        assert r["pdd2"] == Fraction(4, 5) * s * s
        assert r["q1_B"][1] == [Fraction(7, 3) * s, Fraction(11, 6) * s, Fraction(11, 6) * s]
        assert all(type(r[k]) is Fraction for k in VALUE_KEYS)
        fast = pdd.solve(a, b)  # definitions §8: not a normal double, so rejected with a message
        assert fast["error"].startswith("not representable")


@pytest.mark.parametrize("rel", ["smoke.json", "degenerate.json"])
def test_fractions_print_as_the_golden_strings(rel):
    lines = (FIXTURES / "golden" / rel).with_suffix(".jsonl").read_text().splitlines()
    for p, line in zip(pdd.read_fixtures(FIXTURES / rel), lines):
        g = json.loads(line)
        r = pdd.solve(p["A"], p["B"], engine="reference", name=p["name"])
        for k in VALUE_KEYS:
            assert str(r[k]) == g[k]
        assert [[str(c) for c in v] for v in r["q1_A"]] == g["q1_A"]


def test_read_fixtures():
    pairs = pdd.read_fixtures(str(FIXTURES / "smoke.json"))
    assert [p["name"] for p in pairs][0] == "nested-1"
    p = pairs[0]
    assert set(p) == {"name", "tags", "A", "B", "error"}
    assert p["A"] == A and p["B"] == B and p["error"] is None
    assert all(type(c) is float for v in p["A"] + p["B"] for c in v)
    assert all(isinstance(t, str) for q in pairs for t in q["tags"])
    assert pdd.read_fixtures(FIXTURES / "smoke.json") == pairs                 # os.PathLike
    assert pdd.read_fixtures(os.fsencode(FIXTURES / "smoke.json")) == pairs    # bytes
    with pytest.raises(ValueError, match="path must be a str, bytes or os.PathLike; got 3"):
        pdd.read_fixtures(3)


def cli(pdd_cli, *args):
    return subprocess.run([pdd_cli, *args], capture_output=True, text=True)


BAD_FILES = sorted(p.name for p in (FIXTURES / "bad").glob("*.json"))


@pytest.mark.parametrize("path", [str(FIXTURES / "bad" / f) for f in BAD_FILES]
                         + [str(FIXTURES / "bad" / "does-not-exist.json"), str(FIXTURES / "bad")])
def test_read_fixtures_raises_the_cli_message(path, pdd_cli):
    out = cli(pdd_cli, "solve", "--engine", "fast", "--quiet", "--input", path)
    if out.returncode != 2:  # the file itself is readable: read_fixtures reads it too
        assert out.returncode in (0, 1), out.stderr
        pdd.read_fixtures(path)
        return
    with pytest.raises(ValueError) as e:
        pdd.read_fixtures(path)
    assert "pdd solve: " + str(e.value) in out.stderr.splitlines()


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("name", ["mixed.json", "overflow.json", "mistyped.json"])
def test_fixture_pairs_solve_to_the_cli_records(engine, name, pdd_cli):
    """Every entry of a fixture file, read by read_fixtures and solved by solve (an error entry
    becomes {"name", "error"}), gives exactly the records of `pdd solve` on the file."""
    path = FIXTURES / "bad" / name
    out = cli(pdd_cli, "solve", "--engine", engine, "--formulation", "reduced", "--quiet", "--input", str(path))
    assert out.returncode == 1, out.stderr  # some pairs rejected, the others computed
    want = []
    for line in out.stdout.splitlines():
        r = json.loads(line)
        if engine == "reference":
            for k in VALUE_KEYS + ("pdd2_global", "pdd2_global_lower"):
                if k in r:
                    r[k] = Fraction(r[k])
            for k in ("q1_A", "q1_B", "q1_A_global", "q1_B_global"):
                if k in r:
                    r[k] = [[Fraction(c) for c in v] for v in r[k]]
            if r.get("pdd2_global_normal") is not None:
                r["pdd2_global_normal"] = [Fraction(c) for c in r["pdd2_global_normal"]]
        want.append(r)
    got = []
    for p in pdd.read_fixtures(path):
        if p["error"] is not None:
            assert p["A"] is None and p["B"] is None
            got.append({"name": p["name"], "error": p["error"]})
        else:
            got.append(pdd.solve(p["A"], p["B"], engine=engine, name=p["name"]))
    assert got == want
    assert any(r["error"] for r in got) and any(not r["error"] for r in got)


# adversarial-1-3 of fixtures/families (a vertex of B 1e-18 inside a face of A): its exact
# pdd2_relaxed is below 1e-14 of its extent squared, where no double normal need attain
# pdd2_global, and the fast engine declines that value alone: its keys are None,
# pdd2_global_error says why, and every other value is reported. with_global=False skips
# definitions §9: the pair's values come back, within definitions §8 of the exact engine's, and no
# record carries §9's keys.
NEAR_A = [[1.484375, 0.0390625, -2.0625], [-2.390625, -0.8359375, 1.3125], [-2.640625, 1.4765625, 7.6875], [-4.765625, 1.7890625, 7.125]]
NEAR_B = [[3.125, -0.875, -4.59375], [1.1875, -1.3125, -2.90625], [1.0625, -0.15625, 0.28125], [-4.133520782600986e-18, 1.5517643593698782e-18, 6.179952383167375e-18]]
GLOBAL_KEYS = {"pdd2_global", "pdd2_global_normal", "q1_A_global", "q1_B_global", "pdd2_global_lower",
               "pdd2_global_error"}


def test_with_global_false():
    declined = pdd.solve(NEAR_A, NEAR_B)
    assert declined["error"] is None and "no normal in doubles" in declined["pdd2_global_error"]
    assert all(declined[k] is None for k in ("pdd2_global", "pdd2_global_normal", "q1_A_global", "q1_B_global"))
    fast = pdd.solve(NEAR_A, NEAR_B, with_global=False)
    assert {k: v for k, v in declined.items() if k not in GLOBAL_KEYS} == fast
    exact = pdd.solve(NEAR_A, NEAR_B, engine="reference", with_global=False)
    assert fast["error"] is None and exact["error"] is None and fast["intersecting"]
    assert not GLOBAL_KEYS & set(fast) and not GLOBAL_KEYS & set(exact)
    for k in VALUE_KEYS:
        assert exact[k] > 0 and abs(Fraction(fast[k]) - exact[k]) <= Fraction(1, 10**9) * exact[k], k
    # elsewhere it changes nothing but the keys
    full = pdd.solve(A, B)
    assert {k: v for k, v in full.items() if k not in GLOBAL_KEYS} == pdd.solve(A, B, with_global=False)
    batch = pdd.solve_batch(np.array([A, NEAR_A]), np.array([B, NEAR_B]), with_global=False)
    assert not GLOBAL_KEYS & set(batch) and batch["error"] == [None, None]
    assert batch["pdd2"][0] == full["pdd2"] and batch["pdd2"][1] == fast["pdd2"]
    # the batch declines the same value of the same pair, with the same words, and keeps the rest
    both = pdd.solve_batch(np.array([A, NEAR_A]), np.array([B, NEAR_B]))
    assert both["error"] == [None, None] and both["pdd2_global_error"] == [None, declined["pdd2_global_error"]]
    assert np.isnan(both["pdd2_global"][1]) and np.isnan(both["pdd2_global_normal"][1]).all()
    assert np.isnan(both["q1_B_global"][1]).all() and both["pdd2"][1] == fast["pdd2"]
    assert both["pdd2_global"][0] == full["pdd2_global"]
    for bad in (1, None, "no"):
        with pytest.raises(ValueError, match="with_global must be True or False"):
            pdd.solve(A, B, with_global=bad)


# The same rule for the array readers: solve_batch's (N, 4, 3) arrays, mesh_contacts',
# resolve's and contact_energy's vertex arrays (the index names the element); integers that are
# doubles pass.
@pytest.mark.parametrize("dtype, value, shown", [(np.int64, 2**53 + 1, "9007199254740993"),
                                                 (np.int64, -(2**62 + 1), "-4611686018427387905"),
                                                 (np.uint64, 2**64 - 1, "18446744073709551615")])
def test_integer_arrays_that_are_not_doubles_raise_value_error(dtype, value, shown):
    a = np.array([A, A], dtype=dtype)
    a[1, 2, 0] = value
    b = np.array([B, B])
    with pytest.raises(ValueError, match=rf"A\[1\]\[2\]\[0\] = {shown} is not exactly a double"):
        pdd.solve_batch(a, b)
    V = np.array(A + [[1, 1, 1]], dtype=dtype)
    V[4, 1] = value
    with pytest.raises(ValueError, match=rf"VA\[4\]\[1\] = {shown} is not exactly a double"):
        pdd.mesh_contacts(V, [[0, 1, 2, 3]], np.array(B), [[0, 1, 2, 3]])
    with pytest.raises(ValueError, match=rf"VA\[4\]\[1\] = {shown} is not exactly a double"):
        pdd.resolve(V, [[0, 1, 2, 3]], np.array(B), [[0, 1, 2, 3]])
    with pytest.raises(ValueError, match=rf"VA\[4\]\[1\] = {shown} is not exactly a double"):
        pdd.contact_energy(V, [[0, 1, 2, 3]], np.array(B), [[0, 1, 2, 3]])
    exact = np.array([A, A], dtype=dtype)
    exact[1, 2, 0] = 2**53  # a double: read as it is
    r = pdd.solve_batch(exact, b)
    assert r["pdd2"][0] == pdd.solve(A, B, engine="fast")["pdd2"]
