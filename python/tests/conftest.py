"""Shared helpers of the pytest suite of the Python module `pdd` (python/tests).

Run by CTest (`ctest -R python`) with PYTHONPATH set to the build's python/ folder, or by hand:
    PYTHONPATH=build/python /usr/bin/python3 -m pytest python/tests
PDD_CLI (the `pdd` tool of the same build) and PDD_BUILD_DIR are set by CTest; tests that need
them are skipped, with the reason, when they are not set.
"""
import json
import os
import pathlib
from fractions import Fraction

import pytest

# Subprocesses of the tests run elsewhere: make a relative PYTHONPATH (build/python) absolute.
if os.environ.get("PYTHONPATH"):
    os.environ["PYTHONPATH"] = os.pathsep.join(
        os.path.abspath(p) for p in os.environ["PYTHONPATH"].split(os.pathsep) if p)

SOURCE_DIR = pathlib.Path(os.environ.get("PDD_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
FIXTURES = SOURCE_DIR / "fixtures"

VALUE_KEYS = ("rigid_pd2", "eq11_pd2", "pdd2_static", "pdd2", "pdd2_relaxed", "pdd2_accel1",
              "pdd2_accel6")
LABEL_KEYS = ("rigid_dir", "pdd2_static_dir", "pdd2_dir", "pdd2_relaxed_dir")
GLOBAL_VALUE_KEYS = ("pdd2_global", "pdd2_global_lower")  # definitions §9 (lower: exact engine only)
CONTRACT = Fraction(1, 10**9)  # definitions §8: 1e-9 relative


def load_script(name):
    """scripts/<name> (a file name with hyphens: no import statement reaches it) as a module; its
    main() is not run."""
    import importlib.util
    spec = importlib.util.spec_from_file_location(name.replace("-", "_").removesuffix(".py"),
                                                  SOURCE_DIR / "scripts" / name)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def golden_fixture_files():
    """Every shipped fixture with a golden file: all fixtures/**/*.json but bad/ and golden/
    (the set `pdd golden` checks), as paths relative to fixtures/."""
    out = []
    for p in sorted(FIXTURES.rglob("*.json")):
        rel = p.relative_to(FIXTURES).as_posix()
        if not rel.startswith(("bad/", "golden/")):
            out.append(rel)
    return out


def exact(s):
    """A golden number: the exact rational string "p/q" or "p"."""
    return Fraction(s)


def golden_records(rel):
    """The golden JSON records of fixture `rel`, numbers as Fractions."""
    path = (FIXTURES / "golden" / rel).with_suffix(".jsonl")
    out = []
    for line in path.read_text().splitlines():
        r = json.loads(line)
        for k in VALUE_KEYS:
            if k in r:
                r[k] = exact(r[k])
        for k in ("q1_A", "q1_B", "q1_A_global", "q1_B_global"):
            if k in r:
                r[k] = [[exact(c) for c in v] for v in r[k]]
        for k in GLOBAL_VALUE_KEYS:
            if k in r:
                r[k] = exact(r[k])
        if r.get("pdd2_global_normal") is not None:
            r["pdd2_global_normal"] = [exact(c) for c in r["pdd2_global_normal"]]
        out.append(r)
    return out


def golden_cases():
    """(file, pair, golden record) for every golden pair."""
    import pdd
    cases = []
    for rel in golden_fixture_files():
        pairs = pdd.read_fixtures(FIXTURES / rel)
        gold = golden_records(rel)
        assert len(pairs) == len(gold), rel
        cases.extend((rel, p, g) for p, g in zip(pairs, gold))
    return cases


def object_norm(rest, moved):
    """The object norm (definitions §2) of one tetrahedron moved from `rest` to `moved`, exactly."""
    sq = Fraction(0)
    total = [Fraction(0)] * 3
    for r, m in zip(rest, moved):
        for k in range(3):
            d = Fraction(m[k]) - Fraction(r[k])
            sq += d * d
            total[k] += d
    return (sq + sum(t * t for t in total)) / 20


@pytest.fixture(scope="session")
def pdd_cli():
    cli = os.environ.get("PDD_CLI")
    if not cli or not os.path.exists(cli):
        pytest.skip("PDD_CLI (the pdd tool of this build) not set; CTest sets it")
    return cli
