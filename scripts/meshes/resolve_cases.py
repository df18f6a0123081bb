#!/usr/bin/python3
"""resolve_cases.py — mesh operations for scripts/make-resolve-cases.sh (meshio, numpy):
  tetgen IN.1.ele OUT.msh        a TetGen mesh (.node/.ele) as Gmsh 2.2 ASCII
  merge A.msh B.msh OUT.msh      the tetrahedra of A then of B in one file (two bodies, one mesh)
  bend BAR.msh OUT.msh R PITCH   the bar [0, L] x [-w/2, w/2] x [-w/2, w/2] wound about the z axis:
                                 (x, y, z) -> ((R + y) cos f, (R + y) sin f, z + PITCH f / 2 pi),
                                 f = x / R. Orientation preserving while R + y > 0 (its Jacobian
                                 determinant is (R + y) / R), so no element inverts; past one turn
                                 (L > 2 pi R) the end lies PITCH above the start and overlaps it by
                                 w - PITCH: a body pressed into itself.
  count MESH                     the number of tetrahedra
Only tetrahedra are written (other elements are dropped)."""
import contextlib
import sys

import meshio
import numpy as np


def read(path):
    with contextlib.redirect_stdout(sys.stderr):
        m = meshio.read(path)
    T = np.concatenate([c.data for c in m.cells if c.type == "tetra"])
    return np.asarray(m.points[:, :3], dtype=np.float64), T


def write(path, V, T):
    with contextlib.redirect_stdout(sys.stderr):
        meshio.write(path, meshio.Mesh(V, [("tetra", T)]), file_format="gmsh22", binary=False)


def main(a):
    if a[0] == "tetgen":
        write(a[2], *read(a[1]))
    elif a[0] == "merge":
        VA, TA = read(a[1])
        VB, TB = read(a[2])
        write(a[3], np.vstack([VA, VB]), np.vstack([TA, TB + len(VA)]))
    elif a[0] == "bend":
        V, T = read(a[1])
        R, pitch = float(a[3]), float(a[4])
        f = V[:, 0] / R
        W = np.stack([(R + V[:, 1]) * np.cos(f), (R + V[:, 1]) * np.sin(f),
                      V[:, 2] + pitch * f / (2 * np.pi)], axis=1)
        write(a[2], W, T)
    elif a[0] == "count":
        print(len(read(a[1])[1]))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
