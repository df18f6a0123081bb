"""scripts/check-resolution.py, the independent exact judge of `pdd resolve` (SPEC §10, §11).

Hand-made cases whose verdicts follow from a derivation given next to each, and agreement with the
C++ program (PDD: its path) where both decide the same thing: R1's pairs against `pdd mesh`, and
R1-R3, the cost and the smallest volume ratio against `pdd resolve --report`.
Run: PDD=build/bin/pdd /usr/bin/python3 -m pytest tests/compare/test_check_resolution.py"""
import json
import os
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import meshio
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
CHECK = ROOT / "scripts" / "check-resolution.py"
FIX = ROOT / "fixtures" / "meshes"
PDD = os.environ.get("PDD", str(ROOT / "build" / "bin" / "pdd"))

CORNER = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]  # 6V = 1, sum of squared edges = 9


def write(path, V, T):
    meshio.write(str(path), meshio.Mesh(np.asarray(V, dtype=np.float64), [("tetra", np.asarray(T))]),
                 file_format="gmsh22", binary=False)
    return str(path)


def check(*args):
    r = subprocess.run([sys.executable, str(CHECK), *map(str, args)], capture_output=True, text=True)
    assert r.returncode in (0, 1), r.stderr
    out = json.loads(r.stdout)
    assert r.returncode == (0 if out["resolved"] else 1)
    return out


def one_tet(tmp_path, name, P):
    return write(tmp_path / name, P, [[0, 1, 2, 3]])


def judge(tmp_path, A0, A1, B0=None, B1=None, *extra):
    a0, a1 = one_tet(tmp_path, "a0.msh", A0), one_tet(tmp_path, "a1.msh", A1)
    if B0 is None:
        B0 = B1 = [[5, 5, 5], [6, 5, 5], [5, 6, 5], [5, 5, 6]]  # far away: no pair
    b0, b1 = one_tet(tmp_path, "b0.msh", B0), one_tet(tmp_path, "b1.msh", B1)
    return check("--a", a0, "--a-out", a1, "--b", b0, "--b-out", b1, *extra)


def test_unchanged_meshes_pass_with_zero_cost(tmp_path):
    out = judge(tmp_path, CORNER, CORNER)
    assert out["resolved"] and out["cost"] == 0
    assert out["min_volume_ratio"] == 1 and out["min_shape_ratio"] == 1


def test_inverted_element_fails_r2_and_r4(tmp_path):
    inv = [CORNER[0], CORNER[1], CORNER[2], [0, 0, -1]]  # vertex 3 through the opposite face: 6V = -1
    out = judge(tmp_path, CORNER, inv)
    assert not out["r2"] and out["inverted_or_flat"] == [{"mesh": "a", "element": 0}]
    assert not out["r4"] and out["min_volume_ratio"] == -1
    assert out["r1"] and out["r3"]


def test_flattened_element_fails_r2(tmp_path):
    flat = [CORNER[0], CORNER[1], CORNER[2], [0.3, 0.3, 0]]  # all four in z = 0
    out = judge(tmp_path, CORNER, flat)
    assert not out["r2"] and out["inverted_or_flat_count"] == 1


def test_fixed_vertex_moved_by_one_ulp_fails_r3(tmp_path):
    moved = [list(p) for p in CORNER]
    moved[2][1] = np.nextafter(1.0, 2.0)  # the smallest change a double allows
    out = judge(tmp_path, CORNER, moved, None, None, "--fix", "a")
    assert not out["r3"] and out["moved_fixed_vertices"] == [{"mesh": "a", "vertex": 2}]
    out = judge(tmp_path, CORNER, moved)  # nothing fixed: moving is allowed
    assert out["r3"]


def test_fixed_vertex_file(tmp_path):
    moved = [list(p) for p in CORNER]
    moved[1][0] = 1.5
    (tmp_path / "fixed.txt").write_text("0 2\n3\n")
    assert judge(tmp_path, CORNER, moved, None, None, "--fixed-a", tmp_path / "fixed.txt")["r3"]
    (tmp_path / "fixed.txt").write_text("1\n")
    out = judge(tmp_path, CORNER, moved, None, None, "--fixed-a", tmp_path / "fixed.txt")
    assert out["moved_fixed_vertices"] == [{"mesh": "a", "vertex": 1}]


def squashed(z):
    return [CORNER[0], CORNER[1], CORNER[2], [0, 0, z]]  # V1/V0 = z exactly


def test_volume_ratio_exactly_rho_passes_and_just_below_fails(tmp_path):
    # --kappa 1/100 so that only the volume bound decides: the shape ratio of squashed(z) is
    # (27 z^2 / (2 + z^2)^3)^(1/3) (6V = z, sum of squared edges 6 + 3 z^2), 0.57 at z = 1/4, 0.36
    # at z = 4, far above 1/100.
    ok = judge(tmp_path, CORNER, squashed(0.25), None, None, "--kappa", "1/100")
    assert ok["r4"] and ok["min_volume_ratio"] == 0.25
    below = judge(tmp_path, CORNER, squashed(np.nextafter(0.25, 0)), None, None, "--kappa", "1/100")
    assert not below["r4"]
    assert below["r4_failing"][0]["volume_ok"] is False and below["r4_failing"][0]["shape_ok"] is True
    ok = judge(tmp_path, CORNER, squashed(4.0), None, None, "--kappa", "1/100")  # V1/V0 = 1/rho
    assert ok["r4"]
    assert not judge(tmp_path, CORNER, squashed(np.nextafter(4.0, 5)), None, None, "--kappa", "1/100")["r4"]
    # rho given as a decimal is the same rational
    assert judge(tmp_path, CORNER, squashed(0.25), None, None, "--rho", "0.25", "--kappa", "0.01")["r4"]


def test_shape_ratio_exactly_kappa_passes_and_just_below_fails(tmp_path):
    # A similar copy (scaled by 2) has eta1/eta0 = 1 exactly and V1/V0 = 8: with --kappa 1 and
    # --rho 1/8 both bounds hold with equality. squashed(z) has (eta1/eta0)^3 = 27 z^2 / (2 + z^2)^3,
    # whose only maximum is 1 at z = 1, so z one ulp above 1 falls below kappa = 1 while its volume
    # ratio stays inside [1/8, 8].
    big = [[2 * c for c in p] for p in CORNER]
    ok = judge(tmp_path, CORNER, big, None, None, "--rho", "1/8", "--kappa", "1")
    assert ok["r4"] and ok["min_shape_ratio"] == 1 and ok["max_volume_ratio"] == 8
    out = judge(tmp_path, CORNER, squashed(np.nextafter(1.0, 2)), None, None, "--rho", "1/8", "--kappa", "1")
    assert not out["r4"] and out["r4_failing"][0]["shape_ok"] is False
    assert out["r4_failing"][0]["volume_ok"] is True
    # and the default kappa 1/2 at z = 1/4: 27/16 / (33/16)^3 = 6912/35937 > 1/8, passes
    assert Fraction(27, 16) / Fraction(33, 16) ** 3 > Fraction(1, 8)
    assert judge(tmp_path, CORNER, squashed(0.25))["r4"]


def wedge(d, up):
    """An edge of length 2 along x (up = False: at z = d, the other two vertices below it) or along
    y (up = True: at z = d, the other two above): two such wedges at the same d touch in one point
    (the crossing of their edges); only the axis edge x edge = z separates them."""
    if up:
        return [[0, -1, d], [0, 1, d], [-1, 0, d + 2], [1, 0, d + 2]]
    return [[-1, 0, d], [1, 0, d], [0, -1, d - 2], [0, 1, d - 2]]


@pytest.mark.parametrize("d,hit", [(2.0 ** -40, False), (0.0, False), (-(2.0 ** -40), True), (-0.5, True)])
def test_edge_edge_separation_and_touching(tmp_path, d, hit):
    # B's edge at height d over A's edge at height 0: above, separated by z = d/2; at d = 0 the
    # closed tetrahedra share exactly the crossing point (touching, not intersecting); below, the
    # edges cross through each other's interiors.
    A = wedge(0.0, False)
    out = judge(tmp_path, A, A, wedge(d, True), wedge(d, True))
    assert out["r1"] == (not hit)
    if hit:
        assert out["intersecting"] == [{"a": 0, "b": 0}]


def test_shared_face_touching_is_not_intersecting(tmp_path):
    mirror = [CORNER[1], CORNER[2], CORNER[3], [1, 1, 1]]  # across the face x + y + z = 1
    assert judge(tmp_path, CORNER, CORNER, mirror, mirror)["r1"]
    inside = [[0.1, 0.1, 0.1], [0.2, 0.1, 0.1], [0.1, 0.2, 0.1], [0.1, 0.1, 0.2]]  # nested
    out = judge(tmp_path, CORNER, CORNER, inside, inside)
    assert not out["r1"] and out["intersecting_pairs"] == 1


def test_self_contact_skips_pairs_sharing_a_vertex_and_names_bodies(tmp_path):
    # elements 0 and 1 share three vertices and overlap (not a pair); element 2 (its own vertices)
    # lies inside element 0 (x + y + z <= 0.7 < 1) above element 1 (whose apex is at z = 0.3 and
    # element 2 starts at z = 0.5): the one pair (0, 2), of bodies 0 and 1; `pdd mesh` agrees.
    V = CORNER + [[0.3, 0.3, 0.3]] + [[0.05, 0.05, 0.5], [0.1, 0.05, 0.5], [0.05, 0.1, 0.5], [0.05, 0.05, 0.6]]
    T = [[0, 1, 2, 3], [0, 1, 2, 4], [5, 6, 7, 8]]
    m = write(tmp_path / "s.msh", V, T)
    out = check("--a", m, "--a-out", m, "--self")
    assert out["intersecting"] == [{"a": 0, "b": 2, "bodies": [0, 1]}]
    assert out["bodies"] == {"a": 2}
    assert pdd_pairs(["--a", m, "--self"]) == [(0, 2)]


def test_cost_of_a_translation_is_its_squared_length(tmp_path):
    # SPEC §2: a translation by t costs |t|^2; both meshes move: the costs add.
    t = np.array([0.5, -0.25, 1.0])
    out = judge(tmp_path, CORNER, (np.array(CORNER) + t).tolist(),
                [[5, 5, 5], [6, 5, 5], [5, 6, 5], [5, 5, 6]], [[5, 5, 5.5], [6, 5, 5.5], [5, 6, 5.5], [5, 5, 6.5]])
    assert out["cost"] == pytest.approx(t @ t + 0.25, rel=1e-15)


def test_rigid_separation_of_nested_tetrahedra(tmp_path):
    # A = the corner, B = its copy shifted by 1/2 along x: translated by t along x, B meets A in
    # interiors while t < 1/2 (x-extent of A is 1, B starts at 1/2 + t... B = A + (1/2 + t) e_x is
    # separated iff 1/2 + t >= 1), so t = 1/2 and, A fixed, the cost is t^2 = 1/4 (bisection: 1e-3).
    B = (np.array(CORNER) + [0.5, 0, 0]).tolist()
    out = judge(tmp_path, CORNER, CORNER, B, B, "--fix", "a", "--rigid-dir", "1,0,0", "--rigid-hi", "2")
    assert out["rigid"]["t"] == pytest.approx(0.5, rel=2e-3)
    assert out["rigid"]["cost"] == pytest.approx(0.25, rel=4e-3)


def test_bad_input_exits_2(tmp_path):
    a = one_tet(tmp_path, "a.msh", CORNER)
    two = write(tmp_path / "two.msh", CORNER + [[1, 1, 1]], [[0, 1, 2, 3], [1, 2, 3, 4]])
    for args in (["--a", a, "--a-out", two, "--self"],         # other connectivity
                 ["--a", a, "--a-out", a],                      # neither --b nor --self
                 ["--a", a, "--a-out", a, "--self", "--rho", "2"]):
        r = subprocess.run([sys.executable, str(CHECK), *args], capture_output=True, text=True)
        assert r.returncode == 2 and "check-resolution:" in r.stderr


def pdd_pairs(args):
    r = subprocess.run([PDD, "mesh", *args, "--variants", "rigid", "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return sorted((j["a"], j["b"]) for j in map(json.loads, r.stdout.split("\n")[:-1]) if "a" in j)


@pytest.mark.parametrize("a,b", [("sphere-a.msh", "sphere-b.msh"), ("torus.msh", "box.vtk"),
                                 ("touching-a.msh", "touching-b.msh"), ("two-spheres.msh", None)])
def test_r1_pairs_equal_pdd_mesh(a, b):
    if b:
        out = check("--a", FIX / a, "--a-out", FIX / a, "--b", FIX / b, "--b-out", FIX / b, "--max-list", "100000")
        theirs = pdd_pairs(["--a", FIX / a, "--b", FIX / b])
    else:
        out = check("--a", FIX / a, "--a-out", FIX / a, "--self", "--max-list", "100000")
        theirs = pdd_pairs(["--a", FIX / a, "--self"])
    assert [(p["a"], p["b"]) for p in out["intersecting"]] == theirs
    assert out["intersecting_pairs"] == len(theirs)


@pytest.mark.parametrize("fix", [None, "a"])
def test_agrees_with_pdd_resolve_report(tmp_path, fix):
    a, b = FIX / "tiny-a.msh", FIX / "tiny-b.msh"
    oa, ob, rep = tmp_path / "a.msh", tmp_path / "b.msh", tmp_path / "r.json"
    f = ["--fix", fix] if fix else []
    r = subprocess.run([PDD, "resolve", "--a", a, "--b", b, "--out-a", oa, "--out-b", ob, "--report", rep,
                        "--quiet", *f], capture_output=True, text=True)
    assert r.returncode in (0, 1), r.stderr
    report = json.loads(rep.read_text())
    out = check("--a", a, "--a-out", oa, "--b", b, "--b-out", ob, *f)
    for k in ("r1", "r2", "r3"):
        assert out[k] == report[k]
    assert out["intersecting_pairs"] == len(report["remaining_pairs"])
    assert out["cost"] == pytest.approx(report["cost"], rel=1e-12)
    assert out["min_volume_ratio"] == pytest.approx(report["min_volume_ratio"], rel=1e-12)
    if fix:
        assert out["per_mesh"]["a"]["cost"] == 0


@pytest.mark.parametrize("a,b", [("sphere-a.msh", "sphere-b.msh"), ("sphere-a.msh", "slivers.msh")])
def test_double_filters_change_no_verdict(tmp_path, a, b):
    # The doubles decide only under proved error bounds; --all-exact decides everything with the
    # integers. Same verdicts, pairs and failing elements (squashing B by 0.3 in z makes R4 fail
    # on all of B and lets the filters meet both outcomes).
    V, T = meshio.read(FIX / b).points, [c.data for c in meshio.read(FIX / b).cells if c.type == "tetra"]
    V1 = V.copy()
    V1[:, 2] *= 0.3
    b1 = write(tmp_path / "b1.msh", V1, np.concatenate(T))
    b0 = write(tmp_path / "b0.msh", V, np.concatenate(T))
    args = ["--a", FIX / a, "--a-out", FIX / a, "--b", b0, "--b-out", b1, "--max-list", "100000"]
    fast, exact = check(*args), check(*args, "--all-exact")
    assert exact["exact_pair_tests"] == exact["pairs_sharing_no_vertex"] > fast["exact_pair_tests"]
    for k in ("r1", "r2", "r3", "r4", "intersecting", "inverted_or_flat", "r4_failing", "min_volume_ratio",
              "min_shape_ratio", "cost"):
        assert fast[k] == exact[k], k
    assert not fast["r1"] and not fast["r4"]


def test_check_arrays_judges_pdd_resolve_in_python(tmp_path):
    # pdd.resolve's arrays judged without files (check_arrays), equal to its own r1-r3.
    import importlib.util
    spec = importlib.util.spec_from_file_location("check_resolution", CHECK)
    cr = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(cr)
    build = os.environ.get("PDD_PYTHON")
    if not build:
        pytest.skip("PDD_PYTHON (the build's python/ directory) not set")
    sys.path.insert(0, build)
    import pdd
    a, b = meshio.read(FIX / "tiny-a.msh"), meshio.read(FIX / "tiny-b.msh")
    VA, TA = a.points, np.concatenate([c.data for c in a.cells if c.type == "tetra"])
    VB, TB = b.points, np.concatenate([c.data for c in b.cells if c.type == "tetra"])
    for fix in (None, "a"):
        VA1, VB1, rep = pdd.resolve(VA, TA, VB, TB, fix=fix)
        out = cr.check_arrays(VA, TA, VA1, VB, TB, VB1, fixed_a=range(len(VA)) if fix else ())
        for k in ("r1", "r2", "r3"):
            assert out[k] == rep[k]
        assert out["cost"] == pytest.approx(rep["cost"], rel=1e-12)
        assert out["intersecting_pairs"] == len(rep["remaining_pairs"])


@pytest.mark.parametrize("scale", [2.0 ** -1000, 2.0 ** 900])
def test_extreme_scales_keep_the_verdicts(scale):
    # The wedges of test_edge_edge_separation_and_touching times a power of two (exact): the same
    # verdicts, where the doubles underflow (2^-1000: products of coordinates are subnormal or
    # zero) or overflow (2^900), so the exact path decides.
    import importlib.util
    spec = importlib.util.spec_from_file_location("check_resolution", CHECK)
    cr = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(cr)
    T = np.array([[0, 1, 2, 3]])
    A = np.array(wedge(0.0, False)) * scale
    for d, hit in ((2.0 ** -40, False), (0.0, False), (-(2.0 ** -40), True)):
        B = np.array(wedge(d, True)) * scale
        out = cr.check_arrays(A, T, A, B, T, B)
        assert out["r1"] == (not hit) and out["r2"] and out["r4"]
