#!/usr/bin/python3
"""Resolution study of pdd.contact_energy (include/pdd/mesh/contact_energy.h, "Weights").

The same shallow contact meshed at h, h/2, h/4 with Gmsh: box A = [0,1] x [0,1] x [0,0.5], box
B = 0.6 x 0.6 x 0.4 turned by 0.37 rad about z, centred over A, its bottom face `depth` below
A's top face. For each weight applied to the per-pair pdd2_global (area = (V_a V_b)^(1/3), the
default; unit = 1; volume = (V_a + V_b)/2) prints E and its ratio to E at h. A
resolution-independent weight gives ratios near 1. With a third argument N > 1, the area weight's
ratios for N placements of B (turned by 0.37 rad plus up to 0.5 rad, its centre moved by up to
0.05 in x and y, seed 1; B's bottom face stays within A's top face): their spread at one h
beside the trend over h, and E over the integral of depth^2 (the contact area times depth^2).
A fourth argument sets B's height (default 0.4; 0.3 or 0.2: a body one or two elements thick
at the coarsest h).

    PYTHONPATH=build/python /usr/bin/python3 scripts/contact-energy-resolution.py [h] [depth] [N] [height]
"""
import os
import subprocess
import sys
import tempfile

import numpy as np

import pdd


def box(path, x0, x1, y0, y1, z0, z1, h):
    geo = path + ".geo"
    with open(geo, "w") as f:
        f.write(f'SetFactory("OpenCASCADE");\nBox(1) = {{{x0}, {y0}, {z0}, {x1 - x0}, {y1 - y0}, {z1 - z0}}};\n'
                f"Mesh.CharacteristicLengthMax = {h};\nMesh.CharacteristicLengthMin = {h};\n")
    subprocess.run(["gmsh", "-3", "-format", "msh41", "-o", path, geo], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return pdd.read_mesh(path)


def volumes(V, T):
    e = V[T[:, 1:]] - V[T[:, :1]]
    return np.abs(np.linalg.det(e)) / 6


def rotation(axis, angle):
    x, y, z = np.asarray(axis, float) / np.linalg.norm(axis)
    c, s = np.cos(angle), np.sin(angle)
    K = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + s * K + (1 - c) * K @ K


def placements(h, depth, n, height):
    """The area weight's E at h, h/2, h/4 for n placements of B (module docstring)."""
    rng = np.random.default_rng(1)
    poses = [(0.37 + rng.uniform(0, 0.5), rng.uniform(-0.05, 0.05, 2)) for _ in range(n)]
    E = np.zeros((n, 3))
    with tempfile.TemporaryDirectory() as d:
        for k, hk in enumerate([h, h / 2, h / 4]):
            VA, TA = box(os.path.join(d, f"a{k}.msh"), 0, 1, 0, 1, 0, 0.5, hk)
            VB0, TB = box(os.path.join(d, f"b{k}.msh"), -0.3, 0.3, -0.3, 0.3, 0, height, hk)
            for j, (th, c) in enumerate(poses):
                VB = VB0 @ rotation([0, 0, 1], th).T + np.array([0.5 + c[0], 0.5 + c[1], 0.5 - depth])
                E[j, k] = pdd.contact_energy(VA, TA, VB, TB)["energy"]
    print(f"contact: depth {depth}, area 0.36, B {height} high; area weight, {n} placements, h = {h}, {h / 2}, "
          f"{h / 4}")
    for j in range(n):
        print(f"  placement {j}: E {E[j, 0]:.4e} {E[j, 1]:.4e} {E[j, 2]:.4e}  ratios {E[j, 1] / E[j, 0]:.3f} "
              f"{E[j, 2] / E[j, 0]:.3f}")
    m = E.mean(axis=0)
    print(f"  mean: ratios {m[1] / m[0]:.3f} {m[2] / m[0]:.3f}; spread over placements at each h (max/min): "
          + " ".join(f"{E[:, k].max() / E[:, k].min():.3f}" for k in range(3)))
    print("  E over the integral of depth^2 (0.36 depth^2), mean at each h: "
          + " ".join(f"{m[k] / (0.36 * depth**2):.3f}" for k in range(3)))


def main():
    h = float(sys.argv[1]) if len(sys.argv) > 1 else 0.2
    depth = float(sys.argv[2]) if len(sys.argv) > 2 else 0.01
    height = float(sys.argv[4]) if len(sys.argv) > 4 else 0.4
    if len(sys.argv) > 3 and int(sys.argv[3]) > 1:
        return placements(h, depth, int(sys.argv[3]), height)
    th = 0.37
    R = np.array([[np.cos(th), -np.sin(th), 0], [np.sin(th), np.cos(th), 0], [0, 0, 1]])
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for k, hk in enumerate([h, h / 2, h / 4]):
            VA, TA = box(os.path.join(d, f"a{k}.msh"), 0, 1, 0, 1, 0, 0.5, hk)
            VB, TB = box(os.path.join(d, f"b{k}.msh"), -0.3, 0.3, -0.3, 0.3, 0, height, hk)
            VB = VB @ R.T + np.array([0.5, 0.5, 0.5 - depth])
            e = pdd.contact_energy(VA, TA, VB, TB, per_pair=True, weight="unit")
            va, vb = volumes(VA, TA)[e["a"]], volumes(VB, TB)[e["b"]]
            p = e["pdd2_global"]
            rows.append((hk, len(TA) + len(TB), e["pairs"], np.sum(np.cbrt(va * vb) * p), np.sum(p),
                         np.sum((va + vb) / 2 * p), np.max(p)))
    print(f"contact: depth {depth}, area 0.36; E per weight and its ratio to E at h = {h}")
    print(f"{'h':>8} {'elements':>9} {'pairs':>6} {'area':>11} {'ratio':>6} {'unit':>11} {'ratio':>6} "
          f"{'volume':>11} {'ratio':>6} {'max pdd2':>10}")
    for r in rows:
        print(f"{r[0]:8.4f} {r[1]:9d} {r[2]:6d} {r[3]:11.4e} {r[3] / rows[0][3]:6.3f} {r[4]:11.4e} "
              f"{r[4] / rows[0][4]:6.3f} {r[5]:11.4e} {r[5] / rows[0][5]:6.3f} {r[6]:10.3e}")
    print(f"integral of depth^2 over the contact area: {0.36 * depth**2:.4e}")


if __name__ == "__main__":
    main()
