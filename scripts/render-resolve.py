#!/usr/bin/python3
"""render-resolve.py — before/after pictures of a resolved mesh pair: a planar cut through the
contact region, the input meshes overlapping on the left, the resolved meshes on the right
coloured by how far each point moved.

    scripts/render-resolve.py                          # runs `pdd resolve` on the shipped balls,
                                                       # B moved 0.08 deep into A (see --move-b)
    scripts/render-resolve.py --a A.msh --b B.msh --a1 A1.msh --b1 B1.msh   # existing results
    scripts/render-resolve.py --a M.msh --self --a1 M1.msh                  # self-contact
    # the README's picture: the plate-ball case of scripts/make-resolve-cases.sh DIR, resolved
    # by `pdd bench resolve --cases '' --cases-dir DIR --variants global --write OUT`
    scripts/render-resolve.py --a DIR/plate-ball-a.msh --b DIR/plate-ball-b.msh \
        --a1 OUT/plate-ball-global-a.vtk --b1 OUT/plate-ball-global-b.vtk --rigid-cost 0.0004

Writes <out>/resolve-before.png, <out>/resolve-after.png and <out>/resolve.png (both side by
side with a third panel, the distribution over all elements of the volume ratio V1/V0 and the
shape ratio eta1/eta0 with R4's bounds --rho and --kappa, and the cost in its title: the README's
picture). Needs Debian's python3-matplotlib and python3-meshio (both in
scripts/setup.sh). Without --a1, runs `pdd resolve` (--pdd, default build/bin/pdd) into
a temporary folder with --fix and --variant as given, on B translated by --move-b first (by
default, for the shipped balls: along the line of their centres until they are 1.82 apart, a
contact 0.08 deep; as shipped they overlap by 0.73, more than the solver resolves).

The cut: the plane through the contact region (the centroid of the vertices that moved,
weighted by how far) whose normal is the coordinate axis least aligned with the mean
displacement, so that the push lies in the picture. Each tetrahedron the plane crosses gives
a triangle or a quadrilateral: its vertices are where the plane meets the tetrahedron's
edges, the displacement there interpolated linearly along the edge, the polygon coloured by
the mean length of those displacements.
"""
import argparse
import os
import pathlib
import subprocess
import sys
import tempfile
import warnings

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]


def read(path):
    import meshio
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # meshio's notes on Gmsh tags it does not map
        m = meshio.read(path)
    return np.asarray(m.points, dtype=float), np.asarray(m.cells_dict["tetra"])


def cut(V, T, origin, normal, values):
    """The polygons where the plane (origin, normal) meets the tetrahedra: a list of (k, 3)
    point arrays and, per polygon, the mean of `values` (per vertex) interpolated at its points."""
    s = (V - origin) @ normal
    polys, vals = [], []
    ts = s[T]
    crossing = (ts.min(axis=1) < 0) & (ts.max(axis=1) > 0)
    for t in T[crossing]:
        pts, vs = [], []
        for i in range(4):
            for j in range(i + 1, 4):
                si, sj = s[t[i]], s[t[j]]
                if (si < 0) != (sj < 0) and si != sj:
                    w = si / (si - sj)
                    pts.append(V[t[i]] + w * (V[t[j]] - V[t[i]]))
                    vs.append(values[t[i]] + w * (values[t[j]] - values[t[i]]))
        if len(pts) >= 3:
            polys.append(np.array(pts))
            vals.append(float(np.mean(vs)))
    return polys, np.array(vals)


def quality(V0, V1, T):
    """Per element: V1/V0 and eta1/eta0, eta = 12 (3|V|)^(2/3) / (sum of the six squared edge
    lengths) (SPEC §11), in doubles (a picture; check-resolution.py decides R4 exactly)."""
    def vol_edges(V):
        P = V[T]
        D = P[:, 1:] - P[:, :1]
        vol = np.linalg.det(D) / 6
        l2 = sum(((P[:, i] - P[:, j]) ** 2).sum(axis=1) for i in range(4) for j in range(i + 1, 4))
        return vol, l2
    v0, l0 = vol_edges(V0)
    v1, l1 = vol_edges(V1)
    eta = lambda v, l: 12 * np.cbrt(3 * np.abs(v)) ** 2 / l
    return v1 / v0, eta(v1, l1) / eta(v0, l0), np.abs(v0)


def cost(V0, V1, T):
    """SPEC §11's mesh object norm of one mesh: sum_e V_e sigma_e / sum_e V_e, sigma_e =
    (sum_i |d_i|^2 + |sum_i d_i|^2) / 20 over the element's four displacements d_i."""
    d = (V1 - V0)[T]
    sigma = ((d ** 2).sum(axis=(1, 2)) + (d.sum(axis=1) ** 2).sum(axis=1)) / 20
    w = np.abs(np.linalg.det(V0[T][:, 1:] - V0[T][:, :1]))
    return float((w * sigma).sum() / w.sum())


def in_plane(polys, u, w):
    """3-D polygons -> their coordinates along the in-plane axes u, w (unit coordinate axes),
    vertices ordered around their centre."""
    out = []
    for p in polys:
        q = np.stack([p @ u, p @ w], axis=1)
        c = q.mean(axis=0)
        out.append(q[np.argsort(np.arctan2(q[:, 1] - c[1], q[:, 0] - c[0]))])
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--a", default=str(ROOT / "fixtures/meshes/sphere-a.msh"))
    ap.add_argument("--b", default=str(ROOT / "fixtures/meshes/sphere-b.msh"))
    ap.add_argument("--self", action="store_true", help="self-contact of A (no B)")
    ap.add_argument("--a1", help="resolved A (default: run pdd resolve)")
    ap.add_argument("--b1", help="resolved B")
    ap.add_argument("--fix", choices=["a", "b"], help="passed to pdd resolve")
    ap.add_argument("--variant", default="global", help="passed to pdd resolve")
    ap.add_argument("--move-b", nargs=3, type=float, metavar=("X", "Y", "Z"),
                    help="translate B by this vector before resolving (default: see above)")
    ap.add_argument("--pdd", default=str(ROOT / "build/bin/pdd"))
    ap.add_argument("--out", default=str(ROOT / "docs/images"))
    ap.add_argument("--rho", type=float, default=0.25, help="R4's volume-ratio bound (drawn)")
    ap.add_argument("--kappa", type=float, default=0.5, help="R4's shape-ratio bound (drawn)")
    ap.add_argument("--rigid-cost", type=float, help="cost of the rigid separation, for the title")
    args = ap.parse_args()

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    tmp = tempfile.TemporaryDirectory()
    shipped = args.b == ap.get_default("b") and args.a == ap.get_default("a")
    if args.move_b is None and shipped and not args.a1 and not args.self:
        c = np.array([1.1, 0.35, 0.2])  # ball B's centre (scripts/meshes); ball A's is the origin
        args.move_b = list(c * (1.82 / np.linalg.norm(c) - 1))
    if args.move_b is not None and not args.self:
        import meshio
        V, T = read(args.b)
        args.b = os.path.join(tmp.name, "b-moved.vtk")
        meshio.write(args.b, meshio.Mesh(V + np.array(args.move_b), [("tetra", T)]), binary=False)
    if not args.a1:
        args.a1 = os.path.join(tmp.name, "a1.msh")
        cmd = [args.pdd, "resolve", "--a", args.a, "--out-a", args.a1, "--variant", args.variant]
        if args.self:
            cmd.append("--self")
        else:
            args.b1 = os.path.join(tmp.name, "b1.msh")
            cmd += ["--b", args.b, "--out-b", args.b1]
        if args.fix:
            cmd += ["--fix", args.fix]
        print(" ".join(cmd), file=sys.stderr)
        code = subprocess.run(cmd).returncode
        if code not in (0, 1):
            sys.exit(f"render-resolve: pdd resolve failed (exit {code})")
        if code == 1:
            print("render-resolve: not resolved; drawing the result anyway", file=sys.stderr)

    meshes = [("A", read(args.a), read(args.a1))]
    if not args.self:
        meshes.append(("B", read(args.b), read(args.b1)))
    disp = [np.linalg.norm(V1 - V0, axis=1) for _, (V0, _), (V1, _) in meshes]
    vec = np.vstack([V1 - V0 for _, (V0, _), (V1, _) in meshes])
    rest = np.vstack([V0 for _, (V0, _), _ in meshes])
    weight = np.concatenate(disp)
    if weight.sum() > 0:
        origin = (rest * weight[:, None]).sum(axis=0) / weight.sum()
        mean = (vec * weight[:, None]).sum(axis=0)
    else:
        origin, mean = rest.mean(axis=0), np.array([1.0, 0, 0])
    k = int(np.argmin(np.abs(mean) / (np.linalg.norm(mean) or 1)))
    normal = np.eye(3)[k]
    u, w = np.eye(3)[[i for i in range(3) if i != k]]
    axes = "xyz"
    vmax = max(float(d.max()) for d in disp) or 1.0

    def draw(ax, after):
        for (name, (V0, T), (V1, _)), d in zip(meshes, disp):
            V = V1 if after else V0
            polys, vals = cut(V, T, origin, normal, d)
            coll = PolyCollection(in_plane(polys, u, w), linewidths=0.3)
            if after:
                coll.set_array(vals)
                coll.set_cmap("viridis")
                coll.set_clim(0, vmax)
                coll.set_edgecolor((1, 0.6, 0.55, 0.6) if name == "A" else (0.6, 0.75, 1, 0.6))
            else:
                coll.set_facecolor((0.85, 0.25, 0.2, 0.45) if name == "A" else (0.2, 0.35, 0.85, 0.45))
                coll.set_edgecolor((0, 0, 0, 0.25))
            ax.add_collection(coll)
        ax.set_xlim(*window[0])
        ax.set_ylim(*window[1])
        ax.set_aspect("equal")
        ax.set_xlabel(axes[[i for i in range(3) if i != k][0]])
        ax.set_ylabel(axes[[i for i in range(3) if i != k][1]])
        return ax.collections[-1]

    # The window: the moved vertices' extent in the plane, doubled, at least a third of the meshes'.
    moved = rest[weight > 1e-3 * vmax] if weight.max() > 0 else rest
    window = []
    for a in (u, w):
        lo, hi = float((moved @ a).min()), float((moved @ a).max())
        whole = float((rest @ a).max() - (rest @ a).min())
        half = max(hi - lo, whole / 3)
        window.append(((lo + hi) / 2 - half, (lo + hi) / 2 + half))
    title = f"{axes[k]} = {origin[k]:.3g}"
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for after, name, label in ((False, "resolve-before.png", "input: A (red) and B (blue) overlap"),
                               (True, "resolve-after.png", "resolved: |displacement|")):
        fig, ax = plt.subplots(figsize=(4.5, 4))
        coll = draw(ax, after)
        ax.set_title(f"{label}\n{title}", fontsize=9)
        if after:
            fig.colorbar(coll, ax=ax, shrink=0.8)
        fig.tight_layout()
        fig.savefig(out / name, dpi=90)
        plt.close(fig)
    q = [quality(V0, V1, T) for _, (V0, T), (V1, _) in meshes]
    vr = np.concatenate([x[0] for x in q])
    sr = np.concatenate([x[1] for x in q])
    total = sum(cost(V0, V1, T) for _, (V0, T), (V1, _) in meshes)
    fig, (ax0, ax1, ax2) = plt.subplots(1, 3, figsize=(12, 3.6))
    draw(ax0, False)
    ax0.set_title("before: A (red) and B (blue) overlap", fontsize=9)
    coll = draw(ax1, True)
    ax1.set_title("after pdd resolve: |displacement|", fontsize=9)
    fig.colorbar(coll, ax=ax1, shrink=0.85)
    lo = min(args.rho, args.kappa, float(vr.min()), float(sr.min())) * 0.9
    hi = max(1 / args.rho, float(vr.max()), float(sr.max())) * 1.1
    bins = np.geomspace(lo, hi, 60)
    ax2.hist(vr, bins=bins, histtype="step", color="tab:blue", label=f"V1/V0 (min {vr.min():.3f})")
    ax2.hist(sr, bins=bins, histtype="step", color="tab:orange", label=f"eta1/eta0 (min {sr.min():.3f})")
    for x, c in ((args.rho, "tab:blue"), (1 / args.rho, "tab:blue"), (args.kappa, "tab:orange")):
        ax2.axvline(x, color=c, linestyle=":", linewidth=1)
    ax2.set_xscale("log")
    ticks = [x for x in (0.125, 0.25, 0.5, 1, 2, 4, 8) if lo <= x <= hi]
    ax2.set_xticks(ticks, [f"{x:g}" for x in ticks])
    ax2.minorticks_off()
    ax2.set_yscale("log")
    ax2.set_xlabel("ratio, final over rest (dotted: R4 bounds)")
    ax2.set_ylabel("elements")
    ax2.legend(fontsize=7, loc="upper left")
    rigid = f" ({total / args.rigid_cost:.2g} of the rigid separation)" if args.rigid_cost else ""
    ax2.set_title(f"quality of all {len(vr):,} elements\ncost {total:.2g}{rigid}", fontsize=9)
    fig.suptitle(f"planar cut {title} through the contact region (zoomed)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out / "resolve.png", dpi=80)
    plt.close(fig)
    for name in ("resolve-before.png", "resolve-after.png", "resolve.png"):
        print(f"render-resolve: wrote {out / name} ({(out / name).stat().st_size // 1024} KB)", file=sys.stderr)


if __name__ == "__main__":
    main()
