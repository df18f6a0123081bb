"""`pdd bench resolve --cases-dir` (compare/bench/pdd/compare/resolve_bench.h) against the
independent exact judge scripts/check-resolution.py: a small case list in the format
scripts/make-resolve-cases.sh writes (both meshes free, one mesh fixed, one file with two bodies),
run with --write, each row's written meshes judged by the checker, and the bench's columns (R1-R4,
resolved, volume and shape ratios, the rigid separation) compared with the checker's. No timing.
Run: PDD=build/bin/pdd /usr/bin/python3 -m pytest tests/compare/test_bench_resolve.py"""
import json
import os
import subprocess
import sys
from pathlib import Path

import meshio
import numpy as np

ROOT = Path(__file__).resolve().parents[2]
CHECK = ROOT / "scripts" / "check-resolution.py"
FIX = ROOT / "fixtures" / "meshes"
PDD = os.environ.get("PDD", str(ROOT / "build" / "bin" / "pdd"))


def shifted(src, dst, dx):
    m = meshio.read(str(src))
    tets = np.vstack([c.data for c in m.cells if c.type == "tetra"])
    meshio.write(str(dst), meshio.Mesh(m.points + np.array([dx, 0.0, 0.0]), [("tetra", tets)]),
                 file_format="gmsh22", binary=False)
    return dst


def check(*args):
    r = subprocess.run([sys.executable, str(CHECK), *map(str, args)], capture_output=True, text=True)
    assert r.returncode in (0, 1), r.stderr
    return json.loads(r.stdout)


def test_bench_columns_agree_with_the_exact_checker(tmp_path):
    # The boxes of fixtures/meshes/touching-*.msh touch along x = 0.5 (the shipped bench case
    # "boxes 0.1"); B moved by -0.1 in x overlaps A in a slab of depth 0.1.
    a = FIX / "touching-a.msh"
    b = shifted(FIX / "touching-b.msh", tmp_path / "b.msh", -0.1)
    cases = [
        ("boxes", f"--a {a} --b {b}", "--rigid-dir 1,0,0 --rigid-hi 0.5"),
        ("boxes-fixed", f"--a {a} --b {b} --fix a", "--fix a --rigid-dir 1,0,0 --rigid-hi 0.5"),
        ("two-spheres", f"--a {FIX / 'two-spheres.msh'} --self", ""),
    ]
    (tmp_path / "cases.tsv").write_text("".join("\t".join(c) + "\n" for c in cases))
    out = tmp_path / "out"
    r = subprocess.run([PDD, "bench", "resolve", "--cases", "", "--cases-dir", str(tmp_path),
                        "--variants", "global,pdd2", "--repeats", "1", "--write", str(out), "--json"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    rep = json.loads(r.stdout)
    assert [c["name"] for c in rep["cases"]] == [c[0] for c in cases]
    for (name, resolve_opts, check_opts), c in zip(cases, rep["cases"]):
        self_contact = "--self" in resolve_opts
        fixed = "--fix a" in resolve_opts
        assert c["fixed"] == ("a" if fixed else None)
        assert [w["variant"] for w in c["variants"]] == ["global", "pdd2"]
        for w in c["variants"]:
            stem = out / f"{name}-{w['variant']}"
            args = ["--a", resolve_opts.split()[1], "--a-out", f"{stem}-a.vtk"]
            args += ["--self"] if self_contact else ["--b", str(b), "--b-out", f"{stem}-b.vtk"]
            args += check_opts.split()
            judged = check(*args)
            for key in ("resolved", "r1", "r2", "r3", "r4"):
                assert w[key] == judged[key], (name, w["variant"], key)
            # Both sides compute the ratios in doubles from the same written coordinates (the
            # library on its positions, which the VTK writer round-trips with 17 digits; the
            # checker on the file): per element a 3x3 determinant and six squared edges, each to
            # a few ulps relative for elements of bounded shape (R4 keeps eta1 >= eta0 / 2 on
            # these well-shaped meshes), so 1e-9 relative holds with a wide margin.
            for key in ("min_volume_ratio", "max_volume_ratio", "min_shape_ratio"):
                assert abs(w[key] - judged[key]) <= 1e-9 * abs(judged[key]), (name, w["variant"], key)
            if c["rigid_separation_cost"] is not None:
                t_check = judged["rigid"]["t"]
                # Both bisect the same exact R1 from above: the bench to 1e-4 relative of its
                # bracket, the checker to 1e-3, so the two upper ends differ by at most
                # (1e-3 + 1e-4) t.
                assert abs(c["rigid_separation_t"] - t_check) <= 1.1e-3 * t_check
                assert w["cost_over_rigid"] == w["cost"] / c["rigid_separation_cost"]
                # One mesh fixed: the other moves by all of t; both free: half each.
                t = c["rigid_separation_t"]
                assert c["rigid_separation_cost"] == (t * t if fixed else t * t / 2)
        if self_contact:
            assert c["rigid_separation_cost"] is None
