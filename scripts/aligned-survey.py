#!/usr/bin/python3
"""Structured grids against shifted copies through pdd.mesh_contacts, beside rotated twins.

What a user of a structured mesh meets (docs/performance.md, "Where structured grids stand"):
a block of n^3 cubes cut into tetrahedra one of four ways (Kuhn: six around the cube's
diagonal; mirror: Kuhn cubes mirrored in alternate cells, conforming; five: five a cube,
alternating; bc24: 24 around the cube's centre and its faces' centres), against the same block
shifted by a few fractions of a cell h, with pdd.mesh_contacts on one thread (its default
variants, or --variants as pdd.mesh_contacts takes them, e.g. global).
With --energy, pdd.contact_energy with its Hessian instead (one thread; the pairs taken at a
certified bound, docs/definitions.md "Contact energy", counted in the column "bounded").
With --resolve, pdd.resolve on one thread instead (its default variant, global): per case the
rounds, the pair solves (the intersecting pairs summed over the rounds) and the time, beside the
turned twin's, the ratio of the times and of the time per pair solve. A twin turned about its
centroid overlaps A in another shape, so its rounds and pair solves differ; the time per pair
solve tells what the alignment itself costs, the time how long a user waits.
Beside each, the same call with the shifted copy turned 0.3 rad about (1, 2, 3) through its
centroid (no face or edge parallel). Per case: intersecting pairs and the time per
intersecting pair (the best of --repeats calls) of both, their ratio, and the ratio of the
whole calls (box pairs, decision and depths; an aligned copy has fewer intersecting pairs).

The grids are built here with numpy (nothing to read: the shifts are exact multiples of h in
the coordinates as a user would type them, 0.1 * i rounded once, then + s rounded once).

    PYTHONPATH=build/python /usr/bin/python3 scripts/aligned-survey.py [--kinds kuhn,five]
        [--cells 0.1,1/6,0.125] [--shifts off,half-xy,q111,diag] [--n 6] [--repeats 3]
        [--variants global | --energy | --resolve]
"""
import argparse
import os
import sys
import time
from fractions import Fraction

import numpy as np

import pdd

# The cube's corners: bit 0 x, bit 1 y, bit 2 z.
KUHN = [(0, 1, 3, 7), (0, 1, 5, 7), (0, 2, 3, 7), (0, 2, 6, 7), (0, 4, 5, 7), (0, 4, 6, 7)]
FIVE_EVEN = [(1, 2, 4, 7), (0, 1, 2, 4), (3, 1, 2, 7), (5, 1, 4, 7), (6, 2, 4, 7)]
FIVE_ODD = [(0, 3, 5, 6), (1, 0, 3, 5), (2, 0, 3, 6), (4, 0, 5, 6), (7, 3, 5, 6)]
FACES = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
# B's shift in cells (the last coordinate of `diag` puts B on A's top, a third of a cell deep).
SHIFTS = {"off": lambda n: (0.37, 0.21, 0.13), "half-xy": lambda n: (0.5, 0.5, 0.0),
          "q111": lambda n: (0.25, 0.25, 0.25), "diag": lambda n: (0.1, 0.1, n - 1 / 3)}
KINDS = ("kuhn", "mirror", "five", "bc24")  # grid()'s cuts


def corner(i, j, k, b):
    """Corner b of cube (i, j, k) in half-cell integer units."""
    return (2 * (i + (b & 1)), 2 * (j + (b >> 1 & 1)), 2 * (k + (b >> 2 & 1)))


def grid(kind, n, h):
    """n^3 cubes of side h cut as `kind`; vertices keyed by their half-cell integer position."""
    index, V, T = {}, [], []

    def vertex(key):
        if key not in index:
            index[key] = len(V)
            V.append([h * c / 2 for c in key])
        return index[key]

    for i in range(n):
        for j in range(n):
            for k in range(n):
                c = [vertex(corner(i, j, k, b)) for b in range(8)]
                if kind == "kuhn":
                    T += [[c[q] for q in t] for t in KUHN]
                elif kind == "mirror":
                    m = i % 2 | (j % 2) << 1 | (k % 2) << 2
                    T += [[c[q ^ m] for q in t] for t in KUHN]
                elif kind == "five":
                    T += [[c[q] for q in t] for t in (FIVE_EVEN if (i + j + k) % 2 == 0 else FIVE_ODD)]
                elif kind == "bc24":
                    centre = vertex((2 * i + 1, 2 * j + 1, 2 * k + 1))
                    for f in FACES:
                        mid = vertex(tuple(sum(x) // 4 for x in zip(*(corner(i, j, k, b) for b in f))))
                        T += [[c[f[q]], c[f[(q + 1) % 4]], mid, centre] for q in range(4)]
                else:
                    raise SystemExit(f"unknown kind {kind!r}")
    V, T = np.array(V), np.array(T, dtype=np.int64)
    e = V[T[:, 1:]] - V[T[:, :1]]
    flip = np.linalg.det(e) < 0
    T[flip, 1], T[flip, 2] = T[flip, 2].copy(), T[flip, 1].copy()
    return V, T


def turned(V, angle=0.3, axis=(1, 2, 3)):
    a = np.array(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    R = np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K
    c = V.mean(0)
    return (V - c) @ R.T + c


def best_call(repeats, variants, energy, *args):
    """The best time of `repeats` calls, the intersecting pairs and the pairs taken at a bound."""
    best, pairs, bounded = float("inf"), 0, 0
    for _ in range(repeats):
        t = time.perf_counter()
        if energy:
            c = pdd.contact_energy(*args, hessian=True, threads=1)
            best, pairs, bounded = min(best, time.perf_counter() - t), c["pairs"], c["bounded_pairs"]
        else:
            options = {"variants": variants} if variants else {}
            c = pdd.mesh_contacts(*args, threads=1, **options)
            best, pairs = min(best, time.perf_counter() - t), len(c["a"])
    return best, pairs, bounded


def resolve_call(repeats, *args):
    """pdd.resolve: the best time of `repeats` calls, its rounds, pair solves, verdict and method."""
    best = float("inf")
    for _ in range(repeats):
        t = time.perf_counter()
        *_, report = pdd.resolve(*args, threads=1)
        best = min(best, time.perf_counter() - t)
    rounds = report["rounds"]
    return best, len(rounds), sum(r["pairs"] for r in rounds), report["resolved"], report["method"]


def resolve_columns(repeats, VA, T, VB, methods=False):
    """pdd.resolve of VA against VB and against VB turned: each one's rounds, pair solves, time
    (and, with `methods`, what produced the result), the ratio of the times and of the times per
    pair solve, and which did not end resolved; None when either has no intersecting pair."""
    ta, ra, sa, oka, ma = resolve_call(repeats, VA, T, VB, T)
    tb, rb, sb, okb, mb = resolve_call(repeats, VA, T, turned(VB), T)
    if sa == 0 or sb == 0:
        return None
    verdict = "" if oka and okb else f" not resolved:{' aligned' if not oka else ''}{' turned' if not okb else ''}"
    a, b = f"{ra:6d} {sa:7d} {ta:8.3f}", f"{rb:6d} {sb:7d} {tb:8.3f}"
    if methods:  # (one column: "rigid rounds" as rigid-rounds)
        a, b = f"{a} {ma.replace(' ', '-'):12s}", f"{b} {mb.replace(' ', '-'):12s}"
    return f"{a} {b} {ta / tb:5.2f}x {ta / sa / (tb / sb):8.2f}x" + verdict


def resolve_row(kind, cell, name, repeats, VA, T, VB):
    columns = resolve_columns(repeats, VA, T, VB)
    return f"{kind:8s} {cell:>6s} {name:8s} " + (columns or "no intersecting pairs")


def check_arguments(p, a):
    """Every argument checked before any grid is built: p.error (exit 2) naming the one at fault.
    The variants by the call itself (one tetrahedron against itself moved), so that they mean
    what they mean to pdd.mesh_contacts."""
    for kind in a.kinds.split(","):
        if kind not in KINDS:
            p.error(f"--kinds: unknown kind {kind!r} ({', '.join(KINDS)})")
    for cell in a.cells.split(","):
        try:
            if not Fraction(cell) > 0:
                raise ValueError
        except (ValueError, ZeroDivisionError):
            p.error(f"--cells: {cell!r} is not a positive number or fraction")
    for name in a.shifts.split(","):
        if name not in SHIFTS:
            p.error(f"--shifts: unknown shift {name!r} ({', '.join(SHIFTS)})")
    if a.energy and a.variants is not None:
        p.error("--energy: not with --variants (the energy takes pdd2_global alone)")
    if a.resolve and (a.energy or a.variants is not None):
        p.error("--resolve: not with --energy or --variants (it times pdd.resolve alone)")
    if a.n < 1 or a.repeats < 1:
        p.error("--n and --repeats: at least 1")
    if a.variants is not None:
        V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
        T = np.array([[0, 1, 2, 3]], dtype=np.int64)
        try:
            pdd.mesh_contacts(V, T, V + 0.1, T, variants=a.variants, threads=1)
        except ValueError as e:
            p.error(f"--variants: {e}")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--kinds", default=",".join(KINDS))
    p.add_argument("--cells", default="0.1,1/6,0.125", help="cell sizes (fractions allowed)")
    p.add_argument("--shifts", default=",".join(SHIFTS))
    p.add_argument("--n", type=int, default=6, help="cubes a side (bc24: two thirds of it)")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--variants", help="as pdd.mesh_contacts takes them (default: its own)")
    p.add_argument("--energy", action="store_true", help="time pdd.contact_energy (with its Hessian)")
    p.add_argument("--resolve", action="store_true", help="time pdd.resolve (rounds, pair solves)")
    a = p.parse_args()
    check_arguments(p, a)
    if a.resolve:
        print(f"{'grid':8s} {'cell':>6s} {'shift':8s} {'rounds':>6s} {'solves':>7s} {'seconds':>8s} {'rounds':>6s} "
              f"{'solves':>7s} {'turned':>8s} {'ratio':>6s} {'per-solve':>9s}")
    else:
        print(f"{'grid':8s} {'cell':>6s} {'shift':8s} {'pairs':>7s} {'us/pair':>8s} {'turned':>7s} "
              f"{'us/pair':>8s} {'ratio':>6s} {'whole':>6s}" + (f" {'bounded':>7s}" if a.energy else ""))
    for kind in a.kinds.split(","):
        n = max(2, 2 * a.n // 3) if kind == "bc24" else a.n
        for cell in a.cells.split(","):
            h = float(Fraction(cell))
            VA, T = grid(kind, n, h)
            for name in a.shifts.split(","):
                VB = VA + np.array(SHIFTS[name](n)) * h
                if a.resolve:
                    print(resolve_row(kind, cell, name, a.repeats, VA, T, VB), flush=True)
                    continue
                ta, na, ba = best_call(a.repeats, a.variants, a.energy, VA, T, VB, T)
                tb, nb, _ = best_call(a.repeats, a.variants, a.energy, VA, T, turned(VB), T)
                if na == 0 or nb == 0:
                    print(f"{kind:8s} {cell:>6s} {name:8s} no intersecting pairs")
                    continue
                print(f"{kind:8s} {cell:>6s} {name:8s} {na:7d} {ta / na * 1e6:8.2f} {nb:7d} {tb / nb * 1e6:8.2f} "
                      f"{ta / na / (tb / nb):5.2f}x {ta / tb:5.2f}x" + (f" {ba:7d}" if a.energy else ""), flush=True)


if __name__ == "__main__":
    try:
        main()
    except KeyboardInterrupt:  # (the rows printed so far stand: each is flushed whole)
        sys.stderr.write("aligned-survey.py: interrupted\n")
        raise SystemExit(130)
    except BrokenPipeError:  # (a reader that stopped early, `| head`: the rows it took stand)
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        raise SystemExit(1)
