#!/usr/bin/python3
"""check-resolution.py — an independent exact judge of `pdd resolve`'s output (SPEC §10, §11).

Reads the rest meshes (A, and B or --self) and the written meshes (.msh / .vtk, through meshio)
and decides, exactly on the doubles as written:
  R1  no pair intersects: A x B, or with --self the element pairs i < j that share no vertex.
      Two tetrahedra's interiors intersect iff no separating axis exists among the 4 + 4 face
      normals and the 36 edge x edge cross products (non-zero ones) of the pair: for convex
      polytopes with non-empty interiors, disjoint interiors <=> a plane weakly separates them
      <=> 0 is not inside the Minkowski difference A - B, whose facet normals are exactly those
      axes. Touching (max_A n.x == min_B n.x) is separated, so touching is not intersecting.
      Flat elements (zero volume) have no interior and take part in no pair (they fail R2).
  R2  every element keeps the sign of its volume, and a non-zero volume.
  R3  fixed vertices (--fix a|b, --fixed-a/--fixed-b index files) are bit-for-bit unchanged.
  R4  V1/V0 in [rho, 1/rho]:  q V1 V0 >= p V0^2  and  p V1 V0 <= q V0^2   (rho = p/q), and
      eta1/eta0 >= kappa:     q^3 V1^2 (sum l0^2)^3 >= p^3 V0^2 (sum l1^2)^3 (kappa = p/q),
      eta = 12 (3|V|)^(2/3) / sum of the six squared edge lengths (SPEC §11).
Number type: every double is a dyadic rational m 2^e; all coordinates of all meshes are scaled by
one power of two 2^-emin (emin: the smallest exponent among them) to Python integers, exactly. The
predicates above are homogeneous polynomials in the coordinate differences, so their signs are the
signs over the rationals; rho and kappa are Fractions. Nothing is rounded. numpy (doubles) only
finds candidate pairs: axis-aligned boxes whose interiors overlap (a tetrahedron's interior lies in
its box's interior, and the boxes of doubles are exact, so no intersecting pair is missed).

Also reported (doubles, not verdicts): the cost, SPEC §11's mesh object norm summed over the meshes
(per element sigma = (sum |d_i|^2 + |sum d_i|^2) / 20, weighted by |rest volume|), the largest
vertex displacement, the smallest V1/V0 and eta1/eta0, the bodies (vertex-connected components);
with --rigid-dir, the smallest translation t along that direction of B (with --self: of the body
named by --rigid-body, against the other bodies) that separates, by bisection with the exact R1,
and the cost of that motion split the cheapest way between the two sides (rigid()).

Usage:
  check-resolution.py --a A0 --a-out A1 [--b B0 --b-out B1 | --self] [--fix a|b]
                      [--fixed-a FILE] [--fixed-b FILE] [--rho 1/4] [--kappa 1/2]
                      [--rigid-dir x,y,z [--rigid-hi H] [--rigid-body K]] [--max-list N]
                      [--all-exact]   (every element and candidate pair exactly: audits the
                                       double-precision filters, same verdicts, slower)
Prints JSON; exit 0 when R1-R4 hold, 1 when one fails, 2 on bad input.
"""
import argparse
import json
import sys
import time
from fractions import Fraction

import numpy as np


def fail_input(msg):
    print(f"check-resolution: {msg}", file=sys.stderr)
    sys.exit(2)


# ---------------------------------------------------------------- reading
def read_mesh(path):
    """Vertices (n x 3 doubles) and tetrahedra (m x 4 indices, file order among tetra blocks)."""
    import contextlib
    import meshio
    try:
        with contextlib.redirect_stdout(sys.stderr):  # meshio may print warnings; stdout is JSON
            m = meshio.read(path)
    except Exception as e:  # meshio raises many kinds
        fail_input(f"{path}: cannot read: {e}")
    tets = [c.data for c in m.cells if c.type == "tetra"]
    if not tets:
        fail_input(f"{path}: no tetrahedra")
    T = np.concatenate(tets).astype(np.int64)
    V = np.ascontiguousarray(m.points[:, :3], dtype=np.float64)
    if not np.all(np.isfinite(V)):
        fail_input(f"{path}: a coordinate is not finite")
    if T.min() < 0 or T.max() >= len(V):
        fail_input(f"{path}: a vertex index is out of range")
    return V, T


def read_indices(path):
    with open(path) as f:
        return sorted({int(w) for w in f.read().split()})


# ---------------------------------------------------------------- exact numbers
def min_exponent(arrays):
    """Smallest e such that every double of `arrays` is an integer multiple of 2^e."""
    e = 0
    for X in arrays:
        x = X[X != 0]
        if x.size:
            _, ex = np.frexp(x)  # x = m 2^ex, 0.5 <= |m| < 1: m has 53 bits -> lsb 2^(ex - 53)
            e = min(e, int(ex.min()) - 53)
    return e


def exact_point(row, emin):
    t = []
    for x in row:
        n, d = x.as_integer_ratio()  # exact; d a power of two
        t.append(n * ((1 << -emin) // d))  # d <= 2^-emin by the choice of emin
    return tuple(t)


class ExactPoints:
    """The integer coordinates of the vertices of V, converted when first asked for."""

    def __init__(self, V, emin):
        self.V, self.emin, self.cache = V, emin, {}

    def __getitem__(self, k):
        p = self.cache.get(k)
        if p is None:
            p = self.cache[k] = exact_point(self.V[k].tolist(), self.emin)
        return p


U = 2.0 ** -53  # the unit roundoff of doubles
ALL_EXACT = False  # --all-exact: no decision in doubles (to audit the filters; slow)


def float_volumes(V, T):
    """6V of each element in doubles and a bound on its error: Shewchuk's orient3d bound
    (7 + 56u) u * permanent, which covers the rounded differences too; taken as 8u * permanent,
    the permanent computed in doubles (its own rounding is inside the slack)."""
    X = V[T]
    d1, d2, d3 = X[:, 1] - X[:, 0], X[:, 2] - X[:, 0], X[:, 3] - X[:, 0]
    det = np.einsum("mj,mj->m", d1, np.cross(d2, d3))
    a1, a2, a3 = np.abs(d1), np.abs(d2), np.abs(d3)
    perm = (a1[:, 0] * (a2[:, 1] * a3[:, 2] + a2[:, 2] * a3[:, 1])
            + a1[:, 1] * (a2[:, 2] * a3[:, 0] + a2[:, 0] * a3[:, 2])
            + a1[:, 2] * (a2[:, 0] * a3[:, 1] + a2[:, 1] * a3[:, 0]))
    return det, 8 * U * perm


def float_sum_sq_edges(V, T):
    """Sum of the six squared edge lengths in doubles; relative error <= 32u (a rounded difference
    u, its square 3u, a sum of 18 non-negative terms 17u: 21u, with slack)."""
    X = V[T]
    s = np.zeros(len(T))
    for i, j in EDGES:
        d = X[:, i] - X[:, j]
        s += np.einsum("mj,mj->m", d, d)
    return s


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def vol6(p):
    """6 x signed volume of the tetrahedron p[0..3] (exact)."""
    return dot(sub(p[1], p[0]), cross(sub(p[2], p[0]), sub(p[3], p[0])))


def sum_sq_edges(p):
    s = 0
    for i in range(4):
        for j in range(i + 1, 4):
            d = sub(p[i], p[j])
            s += dot(d, d)
    return s


EDGES = ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))
FACES = ((1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2))


def separated_on(n, P, Q):
    a = [dot(n, x) for x in P]
    b = [dot(n, x) for x in Q]
    return max(a) <= min(b) or max(b) <= min(a)


def interiors_intersect(P, Q):
    """Exact: do the interiors of the non-flat tetrahedra P and Q (4 integer points each) meet?"""
    for T in (P, Q):
        for f in FACES:
            n = cross(sub(T[f[1]], T[f[0]]), sub(T[f[2]], T[f[0]]))
            if separated_on(n, P, Q):
                return False
    ep = [sub(P[j], P[i]) for i, j in EDGES]
    eq = [sub(Q[j], Q[i]) for i, j in EDGES]
    for u in ep:
        for v in eq:
            n = cross(u, v)
            if n == (0, 0, 0):
                continue  # parallel edges: no axis (the face normals cover that case)
            if separated_on(n, P, Q):
                return False
    return True


# ---------------------------------------------------------------- broadphase (doubles, exact boxes)
def boxes(V, T, keep):
    X = V[T[keep]]  # k x 4 x 3
    return X.min(axis=1), X.max(axis=1)


def candidate_pairs(loA, hiA, loB, hiB, same):
    """Index pairs (i, j) into the two box lists whose open boxes overlap; same: i < j of one list.
    Grouped by size class (log2 of the largest extent), so a few large boxes do not widen the
    search radius of all the small ones; within two classes, a k-d tree over box centres in the
    max-norm with the classes' largest half extents, then the exact per-axis overlap test."""
    from scipy.spatial import cKDTree
    cA, hA = (loA + hiA) / 2, (hiA - loA) / 2
    cB, hB = (loB + hiB) / 2, (hiB - loB) / 2
    kA = np.ceil(np.log2(np.maximum(hA.max(axis=1), 1e-300))).astype(int)
    kB = np.ceil(np.log2(np.maximum(hB.max(axis=1), 1e-300))).astype(int)
    out = []
    for ka in np.unique(kA):
        ia = np.nonzero(kA == ka)[0]
        ta = cKDTree(cA[ia])
        for kb in np.unique(kB):
            if same and kb < ka:
                continue
            ib = np.nonzero(kB == kb)[0]
            r = hA[ia].max() + hB[ib].max()
            r = r * (1 + 1e-12) + 1e-300  # the tree's distance is rounded: widen, then test exactly
            if same and kb == ka:
                pr = ta.query_pairs(r, p=np.inf, output_type="ndarray")
                if len(pr) == 0:
                    continue
                i, j = ia[pr[:, 0]], ia[pr[:, 1]]
            else:
                tb = cKDTree(cB[ib])
                sm = ta.sparse_distance_matrix(tb, r, p=np.inf, output_type="ndarray")
                if len(sm) == 0:
                    continue
                i, j = ia[sm["i"]], ib[sm["j"]]
            ok = np.all((loA[i] < hiB[j]) & (loB[j] < hiA[i]), axis=1)
            out.append(np.stack([i[ok], j[ok]], axis=1))
    if not out:
        return np.zeros((0, 2), dtype=np.int64)
    P = np.concatenate(out)
    if same:
        P = np.sort(P, axis=1)
    # each (class, class) query yields each pair once: sorting by (i, j) is all that is left
    key = np.sort(P[:, 0] * np.int64(len(loB)) + P[:, 1])
    return np.stack([key // len(loB), key % len(loB)], axis=1)


# ---------------------------------------------------------------- the checks
class Side:
    """One mesh: rest and written positions (doubles), their exact integers when asked for."""

    def __init__(self, name, V0, T, V1, fixed):
        self.name, self.V0, self.T, self.V1, self.fixed = name, V0, T, V1, fixed

    def exact(self, emin):
        self.I0, self.I1 = ExactPoints(self.V0, emin), ExactPoints(self.V1, emin)


def certain_volumes(V, T, I):
    """6V in doubles, its relative error bound (inf where the sign is not certain), and the exact
    signs: from the doubles where |6V| > 2 bound, else from the exact integers I."""
    det, bound = float_volumes(V, T)
    with np.errstate(all="ignore"):
        sure = np.isfinite(det) & np.isfinite(bound) & (np.abs(det) > 2 * bound) & (bound > 1e-250)
        rel = np.where(sure, bound / (np.abs(det) - bound), np.inf)
    sign = np.sign(det).astype(np.int64)
    exact = {}
    for e in np.nonzero(~sure)[0].tolist():
        v = vol6([I[k] for k in T[e].tolist()])
        exact[e] = v
        sign[e] = (v > 0) - (v < 0)
    return det, rel, sign, exact


def elements_checks(s, rho, kappa, max_list):
    """R2 and R4 of one side; the smallest ratios (doubles) and the worst elements.
    Each element is decided in doubles where the forward error bounds (float_volumes,
    float_sum_sq_edges) put the float ratio on one side of the bound with room to spare, and
    exactly (integers: the polynomial forms of the module's header) otherwise."""
    det0, rel0, sg0, ex0 = certain_volumes(s.V0, s.T, s.I0)
    det1, rel1, sg1, ex1 = certain_volumes(s.V1, s.T, s.I1)
    flat_rest = np.nonzero(sg0 == 0)[0]
    r2_bad = np.nonzero((sg0 != 0) & (sg1 != sg0))[0]
    S0, S1 = float_sum_sq_edges(s.V0, s.T), float_sum_sq_edges(s.V1, s.T)
    with np.errstate(all="ignore"):
        x = det1 / det0
        ex = 1.01 * (rel0 + rel1) + 2 * U
        y = x * x * (S0 / S1) ** 3
        ey = 2.05 * ex + 250 * U
        rl, rh = float(rho) * (1 - 2 * U), float(rho) * (1 + 2 * U)
        il, ih = float(1 / rho) * (1 - 2 * U), float(1 / rho) * (1 + 2 * U)
        kl, kh = float(kappa ** 3) * (1 - 2 * U), float(kappa ** 3) * (1 + 2 * U)
        xl, xh, yl, yh = x * (1 - ex), x * (1 + ex), y * (1 - ey), y * (1 + ey)
        v_pass, v_fail = (xl > rh) & (xh < il), (xh < rl) | (xl > ih)
        s_pass, s_fail = yl > kh, yh < kl
    fin = np.isfinite(ex) & np.isfinite(ey) & np.isfinite(y) & np.isfinite(x)
    decided = fin & (v_pass | v_fail) & (s_pass | s_fail) & (not ALL_EXACT)
    ok_v, ok_s = v_pass.copy(), s_pass.copy()
    vr, sr = x.copy(), np.cbrt(y)
    rp, rq = rho.numerator, rho.denominator
    kp3, kq3 = kappa.numerator ** 3, kappa.denominator ** 3
    undecided = np.nonzero(~decided & (sg0 != 0))[0]
    for e in undecided.tolist():
        t = s.T[e].tolist()
        p0, p1 = [s.I0[k] for k in t], [s.I1[k] for k in t]
        a = ex0[e] if e in ex0 else vol6(p0)
        b = ex1[e] if e in ex1 else vol6(p1)
        ok_v[e] = rq * b * a >= rp * a * a and rp * b * a <= rq * a * a
        A0, A1 = sum_sq_edges(p0), sum_sq_edges(p1)
        lhs, rhs = b * b * A0 ** 3, a * a * A1 ** 3  # (eta1/eta0)^3 = lhs / rhs
        ok_s[e] = kq3 * lhs >= kp3 * rhs
        vr[e] = b / a  # Python's int / int: correctly rounded
        sr[e] = (lhs / rhs) ** (1 / 3) if rhs else 0.0
    live = sg0 != 0
    bad = np.nonzero(live & ~(ok_v & ok_s))[0]
    # The printed ratios of the failing and the worst elements: correctly rounded from the exact
    # integers (the doubles of a crushed element lose digits to cancellation).
    idx = np.nonzero(live)[0]
    worst = set(bad.tolist()) | set(idx[np.argsort(vr[idx])[:max_list]].tolist()) \
        | set(idx[np.argsort(sr[idx])[:max_list]].tolist())
    for e in worst - set(undecided.tolist()):
        t = s.T[e].tolist()
        p0, p1 = [s.I0[k] for k in t], [s.I1[k] for k in t]
        a, b = vol6(p0), vol6(p1)
        lhs, rhs = b * b * sum_sq_edges(p0) ** 3, a * a * sum_sq_edges(p1) ** 3
        vr[e] = b / a
        sr[e] = (lhs / rhs) ** (1 / 3) if rhs else 0.0
    r4_bad = [{"mesh": s.name, "element": int(e), "volume_ratio": float(vr[e]),
               "shape_ratio": float(sr[e]), "volume_ok": bool(ok_v[e]), "shape_ok": bool(ok_s[e])}
              for e in bad.tolist()]
    ov, os_ = idx[np.argsort(vr[idx], kind="stable")], idx[np.argsort(sr[idx], kind="stable")]
    return {
        "r2_bad": r2_bad.tolist(), "r4_bad": r4_bad, "flat_rest": flat_rest.tolist(),
        "volume_signs": sg1, "rest_signs": sg0, "exact_elements": len(undecided),
        "min_volume_ratio": float(vr[ov[0]]) if len(ov) else None,
        "max_volume_ratio": float(vr[ov[-1]]) if len(ov) else None,
        "min_shape_ratio": float(sr[os_[0]]) if len(os_) else None,
        "worst_volume": [{"element": int(e), "volume_ratio": float(vr[e])} for e in ov[:max_list]],
        "worst_shape": [{"element": int(e), "shape_ratio": float(sr[e])} for e in os_[:max_list]],
    }


def cost_of(s):
    """SPEC §11: sum_e |V_e| sigma_e / sum_e |V_e|, doubles (a reported number, not a verdict)."""
    D = (s.V1 - s.V0)[s.T]  # m x 4 x 3
    sig = (np.einsum("mij,mij->m", D, D) + np.einsum("mj,mj->m", D.sum(1), D.sum(1))) / 20
    X = s.V0[s.T]
    w = np.abs(np.einsum("mj,mj->m", X[:, 1] - X[:, 0], np.cross(X[:, 2] - X[:, 0], X[:, 3] - X[:, 0])))
    disp = np.sqrt(((s.V1 - s.V0) ** 2).sum(axis=1))
    return float((w * sig).sum() / w.sum()), float(disp.max())


def components(T, n):
    """Bodies: connected components of the elements by shared vertices; label per element."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    m = len(T)
    rows = np.repeat(np.arange(m), 4)
    g = coo_matrix((np.ones(4 * m), (rows, T.ravel() + m)), shape=(m + n, m + n))
    k, lab = connected_components(g, directed=False)
    el = lab[:m]
    _, el = np.unique(el, return_inverse=True)
    return int(el.max()) + 1, el


def certainly_separated(PA, PB):
    """For k pairs of tetrahedra (k x 4 x 3 doubles each): True where one of the 8 face normals,
    taken as computed in doubles (any vector is a valid axis), separates them with a margin above
    the rounding of the projections: |fl(n.x) - n.x| <= 4u sum_i |n_i| |x_i| (gamma_3 with slack),
    so fl(min_B) - fl(max_A) > 2 (errA + errB) proves min_B n.x > max_A n.x exactly (the factor
    2 covers the rounded subtraction; an absolute 1e-300 covers products in the subnormal range,
    whose error is absolute, at most 2^-1074 an operation). False means: not proved here, decide
    exactly."""
    out = np.zeros(len(PA), dtype=bool)
    if not len(PA):
        return out
    for T in (PA, PB):
        for f in FACES:
            n = np.cross(T[:, f[1]] - T[:, f[0]], T[:, f[2]] - T[:, f[0]])
            pa, pb = np.einsum("kij,kj->ki", PA, n), np.einsum("kij,kj->ki", PB, n)
            an = np.abs(n)
            ea = 4 * U * np.einsum("kij,kj->ki", np.abs(PA), an).max(axis=1)
            eb = 4 * U * np.einsum("kij,kj->ki", np.abs(PB), an).max(axis=1)
            m = 2 * (ea + eb) + 1e-300  # + an absolute term: gradual underflow's errors
            with np.errstate(invalid="ignore"):
                out |= (pb.min(axis=1) - pa.max(axis=1) > m) | (pa.min(axis=1) - pb.max(axis=1) > m)
    return out


def intersecting(VA, TA, IA, liveA, VB, TB, IB, liveB, same, first_only=False):
    """Exact R1: the pairs (i, j) of non-flat elements (live) whose interiors intersect; with same,
    the pairs i < j of one mesh that share no vertex. Candidates from the boxes, then those the
    doubles prove separated (certainly_separated) are dropped, the rest decided exactly."""
    ka = np.nonzero(liveA)[0]
    kb = ka if same else np.nonzero(liveB)[0]
    loA, hiA = boxes(VA, TA, ka)
    loB, hiB = (loA, hiA) if same else boxes(VB, TB, kb)
    C = candidate_pairs(loA, hiA, loB, hiB, same)
    i, j = ka[C[:, 0]], kb[C[:, 1]]
    ncand = len(i)
    if same:
        shared = (TA[i][:, :, None] == TA[j][:, None, :]).any(axis=(1, 2))
        i, j = i[~shared], j[~shared]
    nonadjacent = len(i)
    hits = []
    step = 1 << 16
    exact_tests = 0
    for s0 in range(0, len(i), step):
        ii, jj = i[s0:s0 + step], j[s0:s0 + step]
        sep = np.zeros(len(ii), bool) if ALL_EXACT else certainly_separated(VA[TA[ii]], VB[TB[jj]])
        for a, b in zip(ii[~sep].tolist(), jj[~sep].tolist()):
            exact_tests += 1
            if interiors_intersect([IA[k] for k in TA[a].tolist()], [IB[k] for k in TB[b].tolist()]):
                hits.append((a, b))
                if first_only:
                    return hits, (ncand, nonadjacent, exact_tests)
    hits.sort()
    return hits, (ncand, nonadjacent, exact_tests)


def judge(sides, self_contact, rho, kappa, max_list=20):
    """R1-R4, cost and ratios of the Sides (A, and B unless self_contact): the verdict dict printed
    by main (without inputs and rigid), the body label of each element of A, and the seconds."""
    # The double-precision filters treat overflow and NaN as "not decided" (exact path): quiet.
    with np.errstate(all="ignore"):
        return judge_(sides, self_contact, rho, kappa, max_list)


def judge_(sides, self_contact, rho, kappa, max_list):
    t_read = time.perf_counter()
    emin = min_exponent([a for s in sides for a in (s.V0, s.V1)])
    for s in sides:
        s.exact(emin)
    t_exact = time.perf_counter()

    out = {}
    # R3
    moved = []
    for s in sides:
        for k in s.fixed:
            if s.V0[k].tobytes() != s.V1[k].tobytes():  # bit for bit (the doubles as written)
                moved.append({"mesh": s.name, "vertex": k})
    # R2, R4
    el = {s.name: elements_checks(s, rho, kappa, max_list) for s in sides}
    t_el = time.perf_counter()
    # R1
    A = sides[0]
    B = A if self_contact else sides[1]
    hits, counts = intersecting(A.V1, A.T, A.I1, el["a"]["volume_signs"] != 0, B.V1, B.T, B.I1,
                                el[B.name]["volume_signs"] != 0, self_contact)
    t_r1 = time.perf_counter()
    # bodies
    nb, lab = components(A.T, len(A.V0))
    bodies = {"a": nb}
    if not self_contact:
        bodies["b"] = components(B.T, len(B.V0))[0]

    r1 = not hits
    r2 = all(not el[s.name]["r2_bad"] for s in sides)
    r3 = not moved
    r4 = all(not el[s.name]["r4_bad"] for s in sides)
    flat_rest = [{"mesh": s.name, "element": e} for s in sides for e in el[s.name]["flat_rest"]]
    costs = {s.name: cost_of(s) for s in sides}
    pairs = [{"a": i, "b": j} for i, j in hits]
    if self_contact:
        for p in pairs:
            p["bodies"] = [int(lab[p["a"]]), int(lab[p["b"]])]
    out.update({
        "resolved": r1 and r2 and r3 and r4 and not flat_rest,
        "r1": r1, "r2": r2, "r3": r3, "r4": r4,
        "intersecting_pairs": len(hits), "intersecting": pairs[:max_list],
        "inverted_or_flat": [{"mesh": s.name, "element": e} for s in sides for e in el[s.name]["r2_bad"]][:max_list],
        "inverted_or_flat_count": sum(len(el[s.name]["r2_bad"]) for s in sides),
        "moved_fixed_vertices": moved[:max_list], "moved_fixed_count": len(moved),
        "r4_failing_count": sum(len(el[s.name]["r4_bad"]) for s in sides),
        "r4_failing": [x for s in sides for x in el[s.name]["r4_bad"]][:max_list],
        "flat_at_rest": flat_rest[:max_list],
        "min_volume_ratio": min(el[s.name]["min_volume_ratio"] for s in sides),
        "max_volume_ratio": max(el[s.name]["max_volume_ratio"] for s in sides),
        "min_shape_ratio": min(el[s.name]["min_shape_ratio"] for s in sides),
        "per_mesh": {s.name: {"elements": len(s.T), "vertices": len(s.V0), "fixed": len(s.fixed),
                              "cost": costs[s.name][0], "max_displacement": costs[s.name][1],
                              "min_volume_ratio": el[s.name]["min_volume_ratio"],
                              "min_shape_ratio": el[s.name]["min_shape_ratio"],
                              "worst_volume": el[s.name]["worst_volume"][:5],
                              "worst_shape": el[s.name]["worst_shape"][:5]} for s in sides},
        "cost": sum(c[0] for c in costs.values()),
        "bodies": bodies,
        "candidate_pairs": counts[0], "pairs_sharing_no_vertex": counts[1],
        "exact_pair_tests": counts[2],
        "exact_element_checks": sum(el[s.name]["exact_elements"] for s in sides),
    })
    return out, lab, {"exact_coordinates": t_exact - t_read, "r2_r4": t_el - t_exact, "r1": t_r1 - t_el}


def check_arrays(VA0, TA, VA1, VB0=None, TB=None, VB1=None, self_contact=False, fixed_a=(),
                 fixed_b=(), rho=Fraction(1, 4), kappa=Fraction(1, 2), max_list=20):
    """The same verdict on arrays (e.g. pdd.resolve's outputs): vertices n x 3 doubles,
    tetrahedra m x 4 indices, rest and new positions; fixed_*: vertex indices or bool masks. Import with
    importlib (the file name has a dash); see tests/compare/test_check_resolution.py."""
    def ids(f):  # indices, or a bool mask as pdd.resolve's fixed_a
        f = np.asarray(list(f) if not hasattr(f, "dtype") else f)
        return sorted(np.nonzero(f)[0].tolist() if f.dtype == bool else f.astype(np.int64).tolist())

    sides = [Side("a", np.asarray(VA0, np.float64), np.asarray(TA, np.int64),
                  np.asarray(VA1, np.float64), ids(fixed_a))]
    if not self_contact:
        sides.append(Side("b", np.asarray(VB0, np.float64), np.asarray(TB, np.int64),
                          np.asarray(VB1, np.float64), ids(fixed_b)))
    return judge(sides, self_contact, Fraction(rho), Fraction(kappa), max_list)[0]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--a", required=True)
    ap.add_argument("--a-out", required=True)
    ap.add_argument("--b")
    ap.add_argument("--b-out")
    ap.add_argument("--self", action="store_true")
    ap.add_argument("--fix", choices=["a", "b"])
    ap.add_argument("--fixed-a")
    ap.add_argument("--fixed-b")
    ap.add_argument("--rho", default="1/4")
    ap.add_argument("--kappa", default="1/2")
    ap.add_argument("--rigid-dir")
    ap.add_argument("--rigid-hi", type=float, default=1.0)
    ap.add_argument("--rigid-body", type=int, default=1)
    ap.add_argument("--max-list", type=int, default=20)
    ap.add_argument("--all-exact", action="store_true")
    o = ap.parse_args(argv)
    if o.self == bool(o.b) or bool(o.b) != bool(o.b_out):
        fail_input("give --b and --b-out, or --self")
    try:
        rho, kappa = Fraction(o.rho), Fraction(o.kappa)
    except (ValueError, ZeroDivisionError):
        fail_input("--rho and --kappa are rationals such as 1/4 or 0.5")
    if not (0 < rho <= 1 and 0 < kappa <= 1):
        fail_input("--rho and --kappa lie in (0, 1]")
    global ALL_EXACT
    ALL_EXACT = o.all_exact
    t_start = time.perf_counter()

    sides = []
    for name, p0, p1, fx, ff in (("a", o.a, o.a_out, o.fix == "a", o.fixed_a),
                                 ("b", o.b, o.b_out, o.fix == "b", o.fixed_b)):
        if p0 is None:
            continue
        V0, T0 = read_mesh(p0)
        V1, T1 = read_mesh(p1)
        if T0.shape != T1.shape or not np.array_equal(T0, T1) or V0.shape != V1.shape:
            fail_input(f"mesh {name}: {p1} does not have the connectivity of {p0}")
        fixed = list(range(len(V0))) if fx else (read_indices(ff) if ff else [])
        if fixed and (fixed[0] < 0 or fixed[-1] >= len(V0)):
            fail_input(f"mesh {name}: a fixed vertex index is out of range")
        sides.append(Side(name, V0, T0, V1, fixed))
    t_read = time.perf_counter()

    out = {"inputs": {"a": o.a, "a_out": o.a_out, "b": o.b, "b_out": o.b_out, "self": o.self,
                      "fix": o.fix, "rho": str(rho), "kappa": str(kappa)}}
    verdict, lab, sec = judge(sides, o.self, rho, kappa, o.max_list)
    out.update(verdict)
    t_end = time.perf_counter()
    if o.rigid_dir:
        out["rigid"] = rigid(o, sides, lab)
    out["seconds"] = {"read": t_read - t_start, **sec, "total": t_end - t_start}
    if o.rigid_dir:
        out["seconds"]["rigid"] = time.perf_counter() - t_end
    print(json.dumps(out, indent=1))
    return 0 if out["resolved"] else 1


def abs_volume(V, T):
    X = V[T]
    return float(np.abs(np.einsum("mj,mj->m", X[:, 1] - X[:, 0],
                                  np.cross(X[:, 2] - X[:, 0], X[:, 3] - X[:, 0]))).sum() / 6)


def submesh(V, T):
    """The vertices used by the elements T, renumbered."""
    used, inv = np.unique(T, return_inverse=True)
    return V[used], inv.reshape(T.shape)


def rigid(o, sides, lab):
    """Smallest t (bisection to 1e-3 relative) such that moving B (--self: body --rigid-body of A)
    by t * dir at rest leaves no intersecting pair, each step decided with the exact R1."""
    u = np.array([float(x) for x in o.rigid_dir.split(",")])
    u = u / np.linalg.norm(u)
    A = sides[0]

    # The pairs a translation can change: with --self, those of the moving body with the others
    # (as two meshes: bodies share no vertex); pairs inside one body stay as they are.
    if o.self:
        mv = lab == o.rigid_body
        if not mv.any():
            fail_input(f"--rigid-body {o.rigid_body}: there are {lab.max() + 1} bodies")
        VA, TA = submesh(A.V0, A.T[~mv])
        VB, TB = submesh(A.V0, A.T[mv])
    else:
        VA, TA, VB, TB = A.V0, A.T, sides[1].V0, sides[1].T

    liveA = certain_volumes(VA, TA, ExactPoints(VA, min_exponent([VA])))[2] != 0

    def separated(t):
        VBt = VB + t * u  # the doubles a program would write for the translated body
        e = min_exponent([VA, VBt])
        IB = ExactPoints(VBt, e)
        liveB = certain_volumes(VBt, TB, IB)[2] != 0
        h, _ = intersecting(VA, TA, ExactPoints(VA, e), liveA, VBt, TB, IB, liveB, False, first_only=True)
        return not h

    hi, lo = o.rigid_hi, 0.0
    if not separated(hi):
        return {"dir": u.tolist(), "t": None, "note": "--rigid-hi does not separate"}
    while hi - lo > 1e-3 * hi:
        mid = (lo + hi) / 2
        if separated(mid):
            hi = mid
        else:
            lo = mid
    # The cheapest split of t between the two sides: A by -s, B by t - s costs, in the mesh object
    # norm, s^2 + (t - s)^2 for two meshes (s = t/2: t^2/2; A fixed: t^2), and for two bodies of
    # one mesh (volumes wa, wb; the norm is over the whole mesh) (wa s^2 + wb (t - s)^2) / (wa + wb),
    # least at s = wb t / (wa + wb): t^2 wa wb / (wa + wb)^2.
    if o.self:
        wa, wb = abs_volume(VA, TA), abs_volume(VB, TB)
        cost = hi * hi * wa * wb / (wa + wb) ** 2
    else:
        cost = hi * hi if o.fix is not None else hi * hi / 2
    return {"dir": u.tolist(), "t": hi, "cost": cost}


if __name__ == "__main__":
    sys.exit(main())
