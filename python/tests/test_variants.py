"""variants=: pdd.solve and pdd.solve_batch compute and return only the values asked, as
`pdd solve --variants` writes them; each value asked has the bits (fast engine) or the exact
value (reference engine) it has in the full record."""
import json
import subprocess

import numpy as np
import pytest

import pdd
from conftest import FIXTURES, LABEL_KEYS, VALUE_KEYS

NAMES = ("rigid", "eq11", "static", "pdd2", "relaxed", "accel1", "accel6")  # VALUE_KEYS' order
LABEL_OF = {"rigid_pd2": "rigid_dir", "pdd2_static": "pdd2_static_dir", "pdd2": "pdd2_dir",
            "pdd2_relaxed": "pdd2_relaxed_dir"}
GLOBAL_KEYS = ("pdd2_global", "pdd2_global_normal", "q1_A_global", "q1_B_global")
# The default of `pdd mesh`, each value alone, pdd2 with global, global alone.
ASKED = ("rigid,static,pdd2,accel1", "rigid", "eq11", "static", "pdd2", "relaxed", "accel1",
         "accel6", "pdd2,global", "global")


def expected_keys(variants, engine):
    """The keys of a record of `variants` (definitions §6's order)."""
    names = variants.split(",")
    values = [k for k, n in zip(VALUE_KEYS, NAMES) if n in names]
    keys = ["name", "intersecting"] + values + [LABEL_OF[k] for k in values if k in LABEL_OF]
    if "pdd2" in names:
        keys += ["q1_A", "q1_B"]
    keys.append("error")
    if "global" in names:
        keys += list(GLOBAL_KEYS) + (["pdd2_global_error"] if engine == "fast" else ["pdd2_global_lower"])
    return keys


def pairs(n=40, seed=11):
    """Random pairs of the paper's protocol and the shipped smoke pairs."""
    A, B = np.random.default_rng(seed).uniform(0, 10, (2, n, 4, 3))
    smoke = pdd.read_fixtures(FIXTURES / "smoke.json")
    return [(a, b) for a, b in zip(A, B)] + [(np.array(p["A"]), np.array(p["B"])) for p in smoke]


def same(x, y):
    """Bit for bit (floats, nested lists of floats), or equal (str, None, Fraction, bool)."""
    if isinstance(x, float) and isinstance(y, float):
        return np.float64(x).view(np.int64) == np.float64(y).view(np.int64)
    if isinstance(x, list) and isinstance(y, list):
        return len(x) == len(y) and all(same(a, b) for a, b in zip(x, y))
    return x == y


@pytest.mark.parametrize("variants", ASKED)
def test_solve_returns_the_asked_values_with_the_full_records_bits(variants):
    for k, (a, b) in enumerate(pairs()):
        full = pdd.solve(a, b)
        part = pdd.solve(a, b, variants=variants)
        if full["error"] is not None:
            assert part == full, k
            continue
        assert list(part) == expected_keys(variants, "fast"), k
        for key, value in part.items():
            assert same(value, full[key]), (k, key, value, full[key])


@pytest.mark.parametrize("variants", ("rigid,static,pdd2,accel1", "eq11,relaxed", "global"))
def test_reference_engine_returns_the_asked_values(variants):
    smoke = pdd.read_fixtures(FIXTURES / "smoke.json")[:3]
    for p in smoke:
        full = pdd.solve(p["A"], p["B"], engine="reference")
        part = pdd.solve(p["A"], p["B"], engine="reference", variants=variants)
        assert list(part) == expected_keys(variants, "reference")
        for key, value in part.items():
            if key != "name":
                assert value == full[key], (key, value, full[key])


@pytest.mark.parametrize("variants", ("rigid,static,pdd2,accel1", "static", "relaxed,global"))
def test_solve_batch_returns_the_asked_arrays_with_the_full_batchs_bits(variants):
    A, B = (np.array(x) for x in zip(*pairs()))
    full = pdd.solve_batch(A, B)
    part = pdd.solve_batch(A, B, variants=variants)
    keys = set(expected_keys(variants, "fast")) - {"name"} | {"slow_paths"}
    assert set(part) == keys
    for key in keys - {"error", "pdd2_global_error", "slow_paths"}:
        x, y = np.asarray(part[key]), np.asarray(full[key])
        if x.dtype == np.float64:
            x, y = x.view(np.int64), y.view(np.int64)
        assert (x == y).all(), key
    assert part["error"] == full["error"]


def test_cli_writes_the_same_keys(pdd_cli, tmp_path):
    """`pdd solve --variants` and solve(variants=) name and fill the same keys."""
    path = tmp_path / "pairs.json"
    ps = pairs(6)
    path.write_text(json.dumps({"pairs": [{"name": f"p{k}", "A": a.tolist(), "B": b.tolist()}
                                          for k, (a, b) in enumerate(ps)]}))
    for variants in ("rigid,pdd2", "static,global"):
        out = subprocess.run([pdd_cli, "solve", "--engine", "fast", "--quiet", "--input", str(path),
                              "--variants", variants], capture_output=True, text=True, check=True).stdout
        for k, line in enumerate(out.splitlines()):
            record = json.loads(line)
            mine = pdd.solve(ps[k][0], ps[k][1], name=f"p{k}", variants=variants)
            assert list(record) == list(mine), variants
            assert all(same(record[key], mine[key]) for key in record), (variants, k)


@pytest.mark.parametrize("kwargs, message", [
    ({"variants": "rigd"}, "variants: unknown variant 'rigd'"),
    ({"variants": ""}, "variants: no variant named"),
    ({"variants": 3}, "variants"),
    ({"variants": "global", "with_global": False}, "leaves nothing"),
    ({"variants": "rigid,pdd2", "gradient": True}, "gradient=True needs"),
])
def test_bad_variants_raise_value_error(kwargs, message):
    a = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
    for call in (lambda: pdd.solve(a, a, **kwargs),
                 lambda: pdd.solve_batch(np.array([a], float), np.array([a], float), **kwargs)):
        with pytest.raises(ValueError, match=message):
            call()


def test_with_global_false_removes_global():
    a = [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]]
    b = [[2, 2, 2], [2.5, 2, 2], [2, 2.5, 2], [2, 2, 2.5]]
    r = pdd.solve(a, b, variants="pdd2,global", with_global=False)
    assert list(r) == expected_keys("pdd2", "fast")
