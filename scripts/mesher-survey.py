#!/usr/bin/python3
"""Meshes as mesh generators make them, against moved copies, through pdd.mesh_contacts.

scripts/aligned-survey.py builds its grids from exact formulas; a user's structured meshes come
from a mesh generator, which places nodes its own way. Here a unit box is meshed by Gmsh as a
transfinite (structured) volume and as an unstructured one, by TetGen (`-pq1.4a`), and cut by
numpy into prisms of three tetrahedra; each meets copies of itself moved off the grid, stacked a
third of a cell deep and moved half a cell along (1, 1, 1), beside the same copy turned 0.3 rad
about (1, 2, 3) through its centroid (no face or edge parallel). `--ball` adds the shipped
fixtures/meshes/sphere-a.msh against its copy moved by 0.01 in x.

Per case: intersecting pairs and the time per intersecting pair (the best of --repeats calls of
pdd.mesh_contacts, default variants, one thread) of both, their ratio, and the ratio of the whole
calls. First, how far the transfinite box's nodes lie from the grid (Gmsh places each node a few
ulps off it, each its own: faces that coincide in exact arithmetic then coincide only up to a
rounding; docs/performance.md, "Grids placed up to a rounding").
With --resolve, pdd.resolve on one thread instead (its default variant, global), as
scripts/aligned-survey.py --resolve times it: per case the rounds, the pair solves (the
intersecting pairs summed over the rounds), the time and what produced the result (the rounds,
or a fallback: docs/definitions.md), beside the turned copy's, the ratio of the times and of the
time per pair solve.

Needs the Debian packages gmsh and tetgen on PATH, and meshio (python3-meshio).

    PYTHONPATH=build/python /usr/bin/python3 scripts/mesher-survey.py [--cells 10] [--repeats 3]
        [--kinds gmsh-transfinite,gmsh,tetgen,prism] [--ball] [--resolve]
"""
import argparse
import contextlib
import importlib.util
import io
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

import meshio
import numpy as np

import pdd

SOURCE_DIR = pathlib.Path(__file__).resolve().parent.parent
KINDS = ("gmsh-transfinite", "gmsh", "tetgen", "prism")


def aligned_survey():
    """scripts/aligned-survey.py as a module (its turned copies: the same twin in both surveys)."""
    spec = importlib.util.spec_from_file_location("aligned_survey", pathlib.Path(__file__).with_name("aligned-survey.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_aligned = aligned_survey()
turned = _aligned.turned  # (the same twin, and resolve_columns below, in both surveys)


def gmsh_box(work, cells, transfinite):
    """The unit box meshed by Gmsh (OpenCASCADE kernel): a transfinite volume of cells^3 hexahedra
    cut into tetrahedra, or an unstructured mesh of size 1/cells."""
    geo, out = work / "box.geo", work / "box.msh"
    lines = ['SetFactory("OpenCASCADE");', "Box(1) = {0, 0, 0, 1, 1, 1};"]
    if transfinite:
        lines += [f"Transfinite Curve{{:}} = {cells + 1};", "Transfinite Surface{:};", "Transfinite Volume{:};"]
    else:
        lines += [f"Mesh.MeshSizeMax = {1 / cells};"]
    geo.write_text("\n".join(lines) + "\n")
    subprocess.run(["gmsh", "-v", "1", "-nt", "1", "-3", "-format", "msh22", "-o", str(out), str(geo)], check=True, capture_output=True)
    with contextlib.redirect_stdout(io.StringIO()):  # (meshio prints an empty line reading .msh 2.2)
        m = meshio.read(out)
    return m.points.astype(float), m.cells_dict["tetra"].astype(np.int64)


def tetgen_box(work, cells):
    """The unit box meshed by TetGen: quality 1.4, volumes below a cell's / 2."""
    poly = work / "box.poly"
    P = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    F = [(1, 2, 3, 4), (5, 6, 7, 8), (1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (4, 1, 5, 8)]
    text = ["8 3 0 0"] + [f"{i + 1} {x} {y} {z}" for i, (x, y, z) in enumerate(P)] + ["6 0"]
    text += [f"1\n4 {a} {b} {c} {d}" for a, b, c, d in F] + ["0", "0"]
    poly.write_text("\n".join(text) + "\n")
    subprocess.run(["tetgen", f"-pq1.4a{0.5 / cells ** 3:g}", "-Q", str(poly)], check=True, capture_output=True)
    nodes = np.loadtxt(work / "box.1.node", skiprows=1, comments="#", ndmin=2)[:, 1:4]
    elements = np.loadtxt(work / "box.1.ele", skiprows=1, comments="#", dtype=np.int64, ndmin=2)[:, 1:5] - 1
    return nodes, elements


def prism_grid(cells):
    """cells^3 cubes of the unit box, each cut into two prisms along its xy diagonal and each
    prism into three tetrahedra, (A, B, C, D), (B, C, D, E), (C, D, E, F) for the bottom triangle
    A, B, C and the top D, E, F: a tiling of the box, whose side faces neighbouring cubes need
    not cut by the same diagonal (the survey needs the tiling, not a conforming mesh)."""
    h = 1.0 / cells
    idx = lambda i, j, k: (i * (cells + 1) + j) * (cells + 1) + k
    r = range(cells + 1)
    V = np.array([(i * h, j * h, k * h) for i in r for j in r for k in r])
    T = []
    for i in range(cells):
        for j in range(cells):
            for k in range(cells):
                c = [idx(i + (b & 1), j + (b >> 1 & 1), k + (b >> 2 & 1)) for b in range(8)]
                for p in ([0, 1, 3, 4, 5, 7], [0, 3, 2, 4, 7, 6]):  # bottom triangle, top triangle
                    a, b, d, e, f, g = (c[q] for q in p)
                    T += [[a, b, d, e], [b, d, e, f], [d, e, f, g]]
    T = np.array(T, dtype=np.int64)
    P = V[T]
    flip = np.einsum("ij,ij->i", np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]), P[:, 3] - P[:, 0]) < 0
    T[flip, 1], T[flip, 2] = T[flip, 2].copy(), T[flip, 1].copy()
    return V, T


def off_grid(V, cells):
    """How many coordinates of V differ from the nearest grid line i/cells (rounded once), and the
    distinct values among the first grid line's (0.1 for 10 cells)."""
    grid = np.round(V * cells) / cells
    first = np.unique(V[np.abs(grid - 1 / cells) < 0.5 / cells])
    return int(np.count_nonzero(V != grid)), first


def best_call(repeats, *args):
    best, pairs = float("inf"), 0
    for _ in range(repeats):
        t = time.perf_counter()
        c = pdd.mesh_contacts(*args, threads=1)
        best, pairs = min(best, time.perf_counter() - t), len(c["a"])
    return best, pairs


def row(name, repeats, V, T, VB):
    ta, na = best_call(repeats, V, T, VB, T)
    tb, nb = best_call(repeats, V, T, turned(VB), T)
    if na == 0 or nb == 0:
        return f"{name:44s} {na:7d} {'-':>8s} {nb:7d} {'-':>8s} {'-':>6s} {ta / tb:5.2f}x"
    pa, pb = ta / na * 1e6, tb / nb * 1e6
    return f"{name:44s} {na:7d} {pa:8.2f} {nb:7d} {pb:8.2f} {pa / pb:5.2f}x {ta / tb:5.2f}x"


def resolve_row(name, repeats, V, T, VB):
    return f"{name:44s} " + (_aligned.resolve_columns(repeats, V, T, VB, methods=True) or "no intersecting pairs")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cells", type=int, default=10, help="cells a side (mesh size 1/cells)")
    p.add_argument("--repeats", type=int, default=3, help="calls per case (the best is kept)")
    p.add_argument("--kinds", default=",".join(KINDS), help="comma-separated: " + ", ".join(KINDS))
    p.add_argument("--ball", action="store_true", help="also the shipped sphere-a.msh against a moved copy")
    p.add_argument("--resolve", action="store_true", help="time pdd.resolve (rounds, pair solves, method)")
    a = p.parse_args()
    kinds = a.kinds.split(",")
    for k in kinds:
        if k not in KINDS:
            p.error(f"unknown kind {k!r} (one of {', '.join(KINDS)})")
    if a.cells < 2 or a.repeats < 1:
        p.error("--cells must be at least 2 and --repeats at least 1")
    for tool, needed in (("gmsh", {"gmsh-transfinite", "gmsh"}), ("tetgen", {"tetgen"})):
        if needed & set(kinds) and not shutil.which(tool):
            p.error(f"{tool} is not on PATH (Debian package {tool}); leave out --kinds {','.join(sorted(needed & set(kinds)))}")
    h = 1.0 / a.cells
    moves = [("off the grid", (0.37 * h, 0.21 * h, 0.13 * h)), ("stacked a third of a cell deep", (0, 0, 1 - h / 3)),
             ("half a cell along (1, 1, 1)", (h / 2, h / 2, h / 2))]
    if a.resolve:
        print(f"{'mesh, B = A moved':44s} {'rounds':>6s} {'solves':>7s} {'seconds':>8s} {'method':12s} {'rounds':>6s} "
              f"{'solves':>7s} {'turned':>8s} {'method':12s} {'ratio':>6s} {'per-solve':>9s}")
    else:
        print(f"{'mesh, B = A moved':44s} {'pairs':>7s} {'us/pair':>8s} {'turned':>7s} {'us/pair':>8s} {'ratio':>6s} whole")
    survey_row = (lambda *x: resolve_row(*x)) if a.resolve else (lambda *x: row(*x))
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(tmp)
        for kind in kinds:
            if kind == "gmsh-transfinite":
                V, T = gmsh_box(work, a.cells, True)
                moved_off, first = off_grid(V, a.cells)
                print(f"# Gmsh transfinite box: {len(T)} tetrahedra; {moved_off} of {V.size} coordinates off the "
                      f"grid; the line x = {h:g} as {', '.join(repr(float(x)) for x in first[:8])}"
                      f"{' ...' if len(first) > 8 else ''}", flush=True)
            elif kind == "gmsh":
                V, T = gmsh_box(work, a.cells, False)
            elif kind == "tetgen":
                V, T = tetgen_box(work, a.cells)
            else:
                V, T = prism_grid(a.cells)
            for what, t in moves:
                print(survey_row(f"{kind} ({len(T)}), {what}", a.repeats, V, T, V + t), flush=True)
    if a.ball:
        with contextlib.redirect_stdout(io.StringIO()):
            m = meshio.read(SOURCE_DIR / "fixtures" / "meshes" / "sphere-a.msh")
        V, T = m.points.astype(float), m.cells_dict["tetra"].astype(np.int64)
        print(survey_row(f"sphere-a.msh ({len(T)}), moved by 0.01 in x", a.repeats, V, T, V + (0.01, 0, 0)))
    if a.resolve:
        print("(rounds: rows of the report's rounds table; solves: intersecting pairs summed over the rounds;\n"
              " seconds: the best call's; method: what produced the result, the report's method with its words\n"
              " joined by '-'; ratio: of the times, aligned / turned; per-solve: of the times per pair solve)")
    else:
        print("(pairs: intersecting element pairs; us/pair: the best call's time per intersecting pair; ratio: of\n"
              " the times per pair, aligned / turned; whole: of the calls' times)")


if __name__ == "__main__":
    try:
        main()
    except KeyboardInterrupt:  # (the rows printed so far stand: each is flushed whole)
        sys.stderr.write("mesher-survey.py: interrupted\n")
        raise SystemExit(130)
    except BrokenPipeError:  # (a reader that stopped early, `| head`: the rows it took stand)
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        raise SystemExit(1)
