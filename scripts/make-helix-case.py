#!/usr/bin/env python3
"""make-helix-case.py — a self-contact case for `pdd resolve --self` (SPEC §11, one body folded
into itself): a bar of Kuhn cubes (each cube cut into the six tetrahedra around its diagonal)
wound into a helix whose turns overlap by a fraction of a cell.

    make-helix-case.py OUT.msh [--cells N] [--section S] [--h H] [--radius R] [--overlap F]

The bar is N cells long and S x S cells in section, cell size H. Its axis is wound on a helix of
radius R: the point (x, y, z) of the straight bar (x along it, y radial inwards, z axial, y
and z centred) goes to angle theta = x / R, radius R - y, height z + pitch * theta / (2 pi), with
pitch = (S - F) H: consecutive turns overlap by F cells axially. Every element keeps its
orientation (the map is orientation preserving for R > S H / 2). Written as Gmsh 2.2.
Defaults: N 154, S 2 (3696 elements), H 0.1, R 0.8 (about 3 turns), F 0.3.
"""
import argparse

import meshio
import numpy as np


def kuhn_bar(n, s, h):
    """Vertices and positively oriented tetrahedra of an n x s x s bar of Kuhn cubes, size h."""
    idx = lambda i, j, k: (i * (s + 1) + j) * (s + 1) + k
    V = np.array([[i, j, k] for i in range(n + 1) for j in range(s + 1) for k in range(s + 1)], float) * h
    perms = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    T = []
    for i in range(n):
        for j in range(s):
            for k in range(s):
                for p in perms:
                    c = [i, j, k]
                    t = [idx(*c)]
                    for ax in p:
                        c[ax] += 1
                        t.append(idx(*c))
                    T.append(t)
    T = np.array(T)
    d = V[T]
    vol = np.einsum("ij,ij->i", np.cross(d[:, 1] - d[:, 0], d[:, 2] - d[:, 0]), d[:, 3] - d[:, 0])
    T[vol < 0] = T[vol < 0][:, [0, 2, 1, 3]]
    return V, T


def wind(V, s, h, radius, overlap):
    """The straight bar wound on the helix (module docstring)."""
    x, y, z = V[:, 0], V[:, 1] - s * h / 2, V[:, 2] - s * h / 2
    theta = x / radius
    pitch = (s - overlap) * h
    r = radius - y  # y outwards would reverse the orientation (x, y, z) -> (theta, r, height)
    return np.column_stack([r * np.cos(theta), r * np.sin(theta), z + pitch * theta / (2 * np.pi)])


def main():
    ap = argparse.ArgumentParser(
        description="A bar of Kuhn cubes wound into a helix whose turns overlap: a self-contact "
        "case for `pdd resolve --self` (one body folded into itself).")
    ap.add_argument("out", help="the Gmsh 2.2 file to write")
    ap.add_argument("--cells", type=int, default=154, help="cells along the bar (default 154)")
    ap.add_argument("--section", type=int, default=2, help="cells across the bar's square section (default 2)")
    ap.add_argument("--h", type=float, default=0.1, help="cell size (default 0.1)")
    ap.add_argument("--radius", type=float, default=0.8, help="radius of the helix (default 0.8)")
    ap.add_argument("--overlap", type=float, default=0.3,
                    help="axial overlap of consecutive turns, in cells (default 0.3)")
    a = ap.parse_args()
    if a.cells < 1 or a.section < 1 or not a.h > 0:
        raise SystemExit("make-helix-case: --cells and --section must be >= 1 and --h > 0")
    V, T = kuhn_bar(a.cells, a.section, a.h)
    W = wind(V, a.section, a.h, a.radius, a.overlap)
    d = W[T]
    vol = np.einsum("ij,ij->i", np.cross(d[:, 1] - d[:, 0], d[:, 2] - d[:, 0]), d[:, 3] - d[:, 0])
    if not (vol > 0).all():
        raise SystemExit("make-helix-case: the winding inverts elements (radius too small)")
    try:
        meshio.write(a.out, meshio.Mesh(W, [("tetra", T)]), file_format="gmsh22", binary=False)
    except OSError as e:
        raise SystemExit(f"make-helix-case: cannot write {a.out}: {e.strerror}")


if __name__ == "__main__":
    main()
