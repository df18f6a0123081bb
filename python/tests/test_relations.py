"""Relations that hold exactly between a pair's values (definitions §5 and §9) hold between the
doubles the fast engine prints:

    pdd2 <= pdd2_static <= rigid_pd2,   pdd2 <= rigid_pd2 / 2,
    pdd2_global <= pdd2_relaxed <= pdd2 <= pdd2_accel6 <= pdd2_accel1.

Each value alone is within 1e-9 of its exact value (definitions §8), so at an exact tie (pdd2 =
pdd2_accel1 when the shallowest candidate is optimal, computed along two paths) the two roundings
could land on either side; the engine keeps the relation (fast/src/solve_pair.cpp,
keep_exact_relations). Checked with no tolerance, as parsed from `pdd solve --engine fast`
output (a JSON number reads back to the printed double), from `pdd mesh`, and from
`pdd.solve_batch`, on random pairs of every `pdd generate` family (the degenerate ones included:
shared faces and edges, identical, coplanar, near-coplanar, slivers, adversarial scales) and on
every shipped fixture."""
import json
import subprocess

import numpy as np
import pytest

from conftest import FIXTURES

RELATIONS = (("pdd2", "pdd2_static"), ("pdd2_static", "rigid_pd2"), ("pdd2_relaxed", "pdd2"),
             ("pdd2", "pdd2_accel6"), ("pdd2_accel6", "pdd2_accel1"))


def violations(r):
    """The relations record r breaks (a dict of the fast engine's printed values)."""
    if r.get("error") or not r.get("intersecting"):
        return []
    out = [f"{a} {r[a]!r} > {b} {r[b]!r}" for a, b in RELATIONS if a in r and b in r and r[a] > r[b]]
    if "pdd2" in r and "rigid_pd2" in r and r["pdd2"] > r["rigid_pd2"] / 2:
        out.append(f"pdd2 {r['pdd2']!r} > rigid_pd2 / 2 {r['rigid_pd2'] / 2!r}")
    g = r.get("pdd2_global")
    if g is not None and "pdd2_relaxed" in r and g > r["pdd2_relaxed"]:
        out.append(f"pdd2_global {g!r} > pdd2_relaxed {r['pdd2_relaxed']!r}")
    return out


def families(pdd_cli):
    out = subprocess.run([pdd_cli, "generate", "--list"], capture_output=True, text=True, check=True)
    return [line.split()[0] for line in out.stdout.splitlines() if line.strip()]


def solve_fast(pdd_cli, path, tmp_path):
    out = tmp_path / (path.stem + ".jsonl")
    run = subprocess.run([pdd_cli, "solve", "--engine", "fast", "--input", str(path), "--output", str(out)],
                         capture_output=True, text=True, timeout=1200)
    assert run.returncode in (0, 1), run.stderr  # 1: a rejected pair of a bad-input family
    return [json.loads(line) for line in out.read_text().splitlines()]


def assert_relations(records, where):
    bad = [f"{where} {r.get('name', (r.get('a'), r.get('b')))}: {v}" for r in records for v in violations(r)]
    assert not bad, f"{len(bad)} violations, first: " + "; ".join(bad[:5])


def test_every_family(pdd_cli, tmp_path):
    names = families(pdd_cli)
    assert "paper" in names and "near-coplanar" in names and "adversarial" in names
    for seed in (1,):
        for family in names:
            path = tmp_path / f"{family}-{seed}.json"
            subprocess.run([pdd_cli, "generate", "--family", family, "--seed", str(seed), "--count", "60",
                            "--output", str(path)], check=True, capture_output=True)
            assert_relations(solve_fast(pdd_cli, path, tmp_path), f"{family} seed {seed}")


@pytest.mark.parametrize("name", ["smoke.json", "degenerate.json", "adversarial.json"])
def test_shipped_fixtures(pdd_cli, tmp_path, name):
    assert_relations(solve_fast(pdd_cli, FIXTURES / name, tmp_path), name)


def test_family_files(pdd_cli, tmp_path):
    files = sorted((FIXTURES / "families").glob("*.json"))
    assert files
    for path in files:
        assert_relations(solve_fast(pdd_cli, path, tmp_path), path.name)


def test_mesh_records(pdd_cli, tmp_path):
    """`pdd mesh --variants all`: the same relations between the columns of each record."""
    out = tmp_path / "pairs.jsonl"
    subprocess.run([pdd_cli, "mesh", "--a", str(FIXTURES / "meshes" / "sphere-a.msh"), "--b",
                    str(FIXTURES / "meshes" / "sphere-b.msh"), "--variants", "all", "--output", str(out)],
                   check=True, capture_output=True, timeout=1200)
    records = [json.loads(line) for line in out.read_text().splitlines()]
    assert len(records) > 1000
    assert_relations(records, "sphere-a x sphere-b")


def test_solve_batch():
    """The module's batch (numpy columns) on the paper protocol and on shared-face pairs."""
    import pdd
    rng = np.random.default_rng(11)
    A, B = rng.uniform(0, 10, (2, 3000, 4, 3))
    B[1500:, :3] = A[1500:, :3]  # B shares A's face (s0, s1, s2): many exact ties
    res = pdd.solve_batch(A, B)
    records = [{k: (float(v[i]) if v.dtype.kind == "f" else v[i]) for k, v in res.items()
                if isinstance(v, np.ndarray) and v.ndim == 1 and v.dtype.kind in "fb"}
               for i in range(len(A))]
    for r in records:
        r["error"] = None
    assert sum(r["intersecting"] for r in records) > 1000
    assert_relations(records, "solve_batch")
