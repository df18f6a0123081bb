"""Every key the program and the module print is defined in docs/definitions.md.

The keys are collected by running things on small fixtures, not by reading the source:
  - `pdd solve` (both engines; default, --gradient, --no-global, a rejected pair) as JSON Lines,
    and the header rows of --format csv and table;
  - `pdd mesh` records (--variants all, both engines), the value rows and columns of --summary,
    `pdd mesh --energy`, the VTK fields of `pdd mesh --vtk`;
  - `pdd compare --json`, `pdd theorem --json`, `pdd audit-ee --json`;
  - `pdd resolve --report` (JSON, nested keys too), the rounds table of --summary, the VTK fields
    of `pdd resolve --vtk`;
  - the dicts of pdd.solve, pdd.solve_batch, pdd.read_fixtures, pdd.mesh_contacts, pdd.resolve,
    pdd.contact_energy.
A key is defined when definitions.md writes it as a code span (`key`, or inside an object's span
`{key, other}`); a VTK field `max_<key>` when `max_<key>` is written there and <key> is defined.
  - `pdd bench --json` (both families), `pdd bench mesh --json` (with an aligned case), `pdd bench
    resolve --json` and `pdd bench energy --json` (with the stacked blocks) on small inputs.
Nested JSON keys are checked by name."""
import json
import re
import subprocess

import numpy as np
import pytest

import pdd
from conftest import FIXTURES, SOURCE_DIR

MESHES = FIXTURES / "meshes"
TINY = ["--a", str(MESHES / "tiny-a.msh"), "--b", str(MESHES / "tiny-b.msh")]


def defined_words():
    text = (SOURCE_DIR / "docs" / "definitions.md").read_text()
    spans = set(re.findall(r"`([^`\n]+)`", text))
    for s in list(spans):
        if s.startswith("{") and s.endswith("}"):  # an object's keys: `{mesh, index, reason}`
            spans.update(k.strip() for k in s[1:-1].split(","))
    return spans


def is_defined(key, words):
    if key in words:
        return True
    m = re.fullmatch(r"max_(\w+)", key)
    return bool(m) and "max_<key>" in words and m.group(1) in words


def json_keys(value, out):
    """Every key of every object inside `value` (lists and nested objects included)."""
    if isinstance(value, dict):
        for k, v in value.items():
            out.add(k)
            json_keys(v, out)
    elif isinstance(value, (list, tuple)):
        for v in value:
            json_keys(v, out)
    return out


def run(cli, *args, ok=(0,), cwd=None):
    r = subprocess.run([cli, *map(str, args)], capture_output=True, text=True, timeout=900, cwd=cwd)
    assert r.returncode in ok, (args, r.returncode, r.stderr[-2000:])
    return r


def jsonl_keys(text, out):
    for line in text.splitlines():
        if line.strip():
            json_keys(json.loads(line), out)
    return out


def vtk_fields(path):
    """Names of the SCALARS / VECTORS / FIELD arrays of a legacy VTK file."""
    names = set()
    lines = path.read_text().splitlines()
    for i, line in enumerate(lines):
        w = line.split()
        if len(w) >= 2 and w[0] in ("SCALARS", "VECTORS", "NORMALS", "TENSORS"):
            names.add(w[1])
        if len(w) >= 3 and w[0] == "FIELD":
            for k in range(1, int(w[2]) + 1):  # array headers follow (data lines start with digits)
                pass
            names.update(re.findall(r"^([A-Za-z_]\w*) \d+ \d+ \w+$", "\n".join(lines[i + 1:]), re.M))
    return names


def summary_value_rows(text):
    """`pdd mesh --summary`: the column names of the value table and the key of each row."""
    lines = text.splitlines()
    head = next(i for i, l in enumerate(lines) if l.split()[:1] == ["value"])
    columns = re.split(r"\s{2,}", lines[head].strip())[1:]  # "sum", "max", "at (a, b)"
    rows = [l.split()[0] for l in lines[head + 1:] if l.strip()]
    return columns, rows


def rounds_columns(text):
    """`pdd resolve --summary`: the rounds table's column names, written as keys (max pd2 -> max_pd2)."""
    line = next(l for l in text.splitlines() if l.split()[:2] == ["round", "pairs"])
    return [c.replace(" ", "_") for c in re.split(r"\s{2,}", line.strip())]


@pytest.fixture(scope="module")
def cli_keys(pdd_cli, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("keys")
    keys = {}  # key -> where it was printed (first place)

    def add(found, where):
        for k in found:
            keys.setdefault(k, where)

    smoke = FIXTURES / "smoke.json"
    bad = tmp / "bad.json"
    bad.write_text('{"pairs": [{"name": "flat", "A": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]],'
                   ' "B": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]]}]}')
    for engine in ("fast", "reference"):
        for extra in ([], ["--gradient"], ["--no-global"]):
            r = run(pdd_cli, "solve", "--quiet", "--engine", engine, "--input", smoke, *extra)
            add(jsonl_keys(r.stdout, set()), f"pdd solve --engine {engine} {' '.join(extra)}")
        r = run(pdd_cli, "solve", "--quiet", "--engine", engine, "--input", bad, ok=(1,))
        add(jsonl_keys(r.stdout, set()), f"pdd solve --engine {engine} (rejected pair)")
        r = run(pdd_cli, "solve", "--quiet", "--engine", engine, "--format", "csv", "--input", smoke)
        add(r.stdout.splitlines()[0].split(","), f"pdd solve --format csv --engine {engine}")
        r = run(pdd_cli, "solve", "--quiet", "--engine", engine, "--format", "table", "--input", smoke)
        add(r.stdout.splitlines()[0].split(), f"pdd solve --format table --engine {engine}")

    for engine in ("fast", "reference"):
        out = tmp / f"mesh-{engine}.jsonl"
        vtk = tmp / f"mesh-{engine}.vtk"
        r = run(pdd_cli, "mesh", "--quiet", *TINY, "--engine", engine, "--variants", "all",
                "--output", out, "--vtk", vtk, "--summary")
        add(jsonl_keys(out.read_text(), set()), f"pdd mesh --engine {engine} --variants all")
        add(vtk_fields(vtk), f"pdd mesh --vtk --engine {engine}")
        columns, rows = summary_value_rows(r.stdout)
        add(columns + rows, f"pdd mesh --summary --engine {engine}")
    r = run(pdd_cli, "mesh", "--quiet", *TINY, "--energy")
    add(json_keys(json.loads(r.stdout), set()), "pdd mesh --energy")
    r = run(pdd_cli, "mesh", "--quiet", "--a", MESHES / "slivers.msh", "--self", "--variants", "all",
            "--vtk", tmp / "self.vtk", ok=(0, 1))
    add(jsonl_keys(r.stdout, set()), "pdd mesh --self")
    add(vtk_fields(tmp / "self.vtk"), "pdd mesh --self --vtk")

    for command in ("compare", "theorem", "audit-ee"):
        extra = ["--nef", "0"] if command == "theorem" else []
        for fixture in (smoke, bad):
            r = run(pdd_cli, command, "--input", fixture, "--json", *extra, ok=(0, 1))
            add(jsonl_keys(r.stdout, set()), f"pdd {command} --json")

    bench = [["bench", "--count", "20", "--repeats", "1", "--exact-sample", "2"],
             ["bench", "mesh", *TINY, "--repeats", "1", "--aligned-cells", "1"],
             ["bench", "resolve", "--cases", "self", "--size", "200", "--repeats", "1", "--max-rounds", "3",
              "--meshes", MESHES],
             ["bench", "energy", "--cases", "balls", "--size", "2000", "--repeats", "1"],
             ["bench", "--family", "aligned", "--count", "12", "--repeats", "1"],
             ["bench", "resolve", "--cases", "stacked", "--stacked-cells", "2", "--repeats", "1", "--max-rounds", "3"],
             ["bench", "energy", "--cases", "stacked", "--stacked-cells", "3", "--repeats", "1"]]
    for k, args in enumerate(bench):
        out = tmp / f"bench-{k}.json"
        run(pdd_cli, *args, "--json", out)
        add(json_keys(json.loads(out.read_text()), set()), "pdd " + " ".join(map(str, args[:2])) + " --json")

    for variant in ("global", "rigid"):
        rep, vtk = tmp / f"report-{variant}.json", tmp / f"resolve-{variant}.vtk"
        r = run(pdd_cli, "resolve", "--quiet", *TINY, "--variant", variant, "--out-a", tmp / "a1.msh",
                "--out-b", tmp / "b1.vtk", "--report", rep, "--vtk", vtk, "--summary", ok=(0, 1))
        add(json_keys(json.loads(rep.read_text()), set()), f"pdd resolve --report --variant {variant}")
        add(vtk_fields(vtk), "pdd resolve --vtk")
        add(rounds_columns(r.stdout), "pdd resolve --summary (rounds table)")
    rep = tmp / "report-self.json"
    run(pdd_cli, "resolve", "--quiet", "--a", MESHES / "two-spheres.msh", "--self", "--max-rounds", "2",
        "--out-a", tmp / "s1.msh", "--report", rep, ok=(0, 1))
    add(json_keys(json.loads(rep.read_text()), set()), "pdd resolve --self --report")
    return keys


@pytest.fixture(scope="module")
def module_keys():
    keys = {}

    def add(found, where):
        for k in found:
            keys.setdefault(k, where)

    A = [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]]
    B = [[2, 2, 2], [2.5, 2, 2], [2, 2.5, 2], [2, 2, 2.5]]
    flat = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]
    for engine in ("fast", "reference"):
        for kw in ({}, {"gradient": True}, {"with_global": False}):
            add(json_keys(pdd.solve(A, B, engine=engine, **kw), set()), f"pdd.solve(engine={engine!r}, {kw})")
        add(json_keys(pdd.solve(flat, B, engine=engine), set()), "pdd.solve (rejected pair)")
    for kw in ({}, {"gradient": True}, {"with_global": False}):
        add(pdd.solve_batch(np.array([A, flat]), np.array([B, B]), **kw).keys(), f"pdd.solve_batch({kw})")
    add(json_keys(pdd.read_fixtures(FIXTURES / "smoke.json"), set()), "pdd.read_fixtures")
    add(pdd.KEYS, "pdd.KEYS")

    VA, TA = pdd.read_mesh(MESHES / "tiny-a.msh")
    VB, TB = pdd.read_mesh(MESHES / "tiny-b.msh")
    for engine in ("fast", "reference"):
        add(pdd.mesh_contacts(VA, TA, VB, TB, variants="all", engine=engine).keys(),
            f"pdd.mesh_contacts(engine={engine!r})")
    add(pdd.mesh_contacts(VA, TA).keys(), "pdd.mesh_contacts (self)")
    for variant in ("global", "rigid"):
        _, _, report = pdd.resolve(VA, TA, VB, TB, variant=variant)
        add(json_keys(report, set()), f"pdd.resolve(variant={variant!r})")
    add(json_keys(pdd.contact_energy(VA, TA, VB, TB, per_pair=True, hessian=True), set()),
        "pdd.contact_energy")
    return keys


def undefined(keys):
    words = defined_words()
    return sorted(f"{k!r} (printed by {where})" for k, where in keys.items() if not is_defined(k, words))


def test_collected_enough(cli_keys, module_keys):
    # A collector that silently finds nothing would pass the tests below.
    for k in ("pdd2_global_grad", "pdd2_global_lower", "pdd2_global_error", "max_pdd2_global",
              "displacement", "partners", "remaining_pairs", "seconds_total", "max_force", "sum",
              "pairs_dev_over_1e-6", "decision_ratio", "rounds_log", "verdict", "nef_equal"):
        assert k in cli_keys, k
    for k in ("pdd2_global_grad", "slow_paths", "skipped", "hessian", "volume_ratio_a"):
        assert k in module_keys, k


def test_every_printed_key_is_defined(cli_keys):
    assert not undefined(cli_keys), "\n".join(undefined(cli_keys))


def test_every_module_key_is_defined(module_keys):
    assert not undefined(module_keys), "\n".join(undefined(module_keys))


def test_an_undefined_key_is_reported():
    words = defined_words()
    assert undefined({"pdd2": "x", "max_pdd2": "y", "no_such_key": "z", "max_no_such": "w"}) == [
        "'max_no_such' (printed by w)", "'no_such_key' (printed by z)"]
    assert is_defined("rigid_pd2", words) and not is_defined("rigid_pd", words)
    assert is_defined("reason", words)  # from `{mesh, index, reason}`


def test_module_keys_tuple_lists_every_record_key():
    """pdd.KEYS holds every key a record of pdd.solve can have, in the order of the records."""
    A = [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]]
    B = [[2, 2, 2], [2.5, 2, 2], [2, 2.5, 2], [2, 2, 2.5]]
    for engine in ("fast", "reference"):
        for kw in ({}, {"gradient": True}, {"with_global": False}):
            keys = list(pdd.solve(A, B, engine=engine, **kw))
            assert set(keys) <= set(pdd.KEYS), (engine, kw)
            assert keys == sorted(keys, key=pdd.KEYS.index), (engine, kw)
