"""pdd.contact_energy (docs/definitions.md "Contact energy"): the dict, the gradient against
central differences of E, the Hessian symmetric and positive semi-definite, the per-pair terms
against pdd.mesh_contacts, the exact engine against the fast one, self-contact, bad input."""
import json
import os
import re

import numpy as np
import pytest

import pdd

scipy_sparse = pytest.importorskip("scipy.sparse")

HERE = os.path.dirname(os.path.abspath(__file__))
MESHES = os.path.join(HERE, "..", "..", "fixtures", "meshes")


def scene():
    """tiny-a / tiny-b with B turned and moved into general position (73 intersecting pairs;
    the axis-aligned original sends most pairs to the engine's exact path)."""
    VA, TA = pdd.read_mesh(os.path.join(MESHES, "tiny-a.msh"))
    VB, TB = pdd.read_mesh(os.path.join(MESHES, "tiny-b.msh"))
    cz, sz, cx, sx = np.cos(0.3), np.sin(0.3), np.cos(0.2), np.sin(0.2)
    R = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]) @ np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    return VA, TA, VB @ R.T + np.array([0.013, 0.021, 0.007]), TB


def test_dict_and_pairs():
    VA, TA, VB, TB = scene()
    e = pdd.contact_energy(VA, TA, VB, TB, per_pair=True)
    assert isinstance(e["energy"], float)
    assert e["gradient"].shape == (len(VA) + len(VB), 3)
    assert e["hessian"] is None
    c = pdd.mesh_contacts(VA, TA, VB, TB, variants="global")
    assert e["pairs"] == len(c["a"]) > 0
    assert np.array_equal(e["a"], c["a"]) and np.array_equal(e["b"], c["b"])
    assert np.array_equal(e["pdd2_global"], np.asarray(c["pdd2_global"]))
    # w = (V_a V_b)^(1/3), rest volumes |det| / 6 (rest = the positions here)
    vol = lambda V, T: np.abs(np.linalg.det(V[T[:, 1:]] - V[T[:, :1]])) / 6
    w = np.cbrt(vol(VA, TA)[e["a"]] * vol(VB, TB)[e["b"]])
    np.testing.assert_allclose(e["weight"], w, rtol=1e-12)
    np.testing.assert_array_equal(e["pair_energy"], e["weight"] * e["pdd2_global"])
    assert e["energy"] == pytest.approx(e["pair_energy"].sum(), rel=1e-12)
    assert e["max_pdd2_global"] == e["pdd2_global"].max()


def test_gradient_central_differences():
    # The weights come from rest_A / rest_B (held), so E is a function of the positions alone.
    # Away from kinks (one-sided quotients agreeing) the central quotient matches to O(h^2)
    # plus the engine's 1e-9 relative error over h (test_contact_energy.cpp argues 1e-5).
    VA, TA, VB, TB = scene()
    e = pdd.contact_energy(VA, TA, VB, TB, rest_A=VA, rest_B=VB)
    g = e["gradient"]
    gmax = np.abs(g).max()
    h = 1e-6
    n_a = len(VA)
    smooth = 0
    for v in np.flatnonzero(np.abs(g).sum(axis=1) > 0)[::3]:
        for k in range(3):
            def E(d):
                A, B = VA.copy(), VB.copy()
                (A if v < n_a else B)[v if v < n_a else v - n_a, k] += d
                return pdd.contact_energy(A, TA, B, TB, rest_A=VA, rest_B=VB)["energy"]
            ep, em = E(h), E(-h)
            fwd, bwd = (ep - e["energy"]) / h, (e["energy"] - em) / h
            if abs(fwd - bwd) <= 1e-6 * gmax:
                smooth += 1
                assert abs((ep - em) / (2 * h) - g[v, k]) <= 1e-5 * gmax
    assert smooth > 0


def test_gradient_without_rest_moves_the_weights():
    """Without rest_A / rest_B the weights are the current volumes, E(P) = sum w(P) pdd2_global(P),
    and the gradient is that function's (the weights' derivative dw/dx = w / 3 (dV_a/dx / V_a +
    dV_b/dx / V_b) included): central differences of the default call agree with it as the
    fixed-rest ones agree with the fixed-rest gradient, which it differs from by those terms. With
    one rest given only the other side's weights move."""
    VA, TA, VB, TB = scene()
    fixed = pdd.contact_energy(VA, TA, VB, TB, rest_A=VA, rest_B=VB)
    e = pdd.contact_energy(VA, TA, VB, TB)
    assert e["energy"] == fixed["energy"]
    g, gmax = e["gradient"], np.abs(e["gradient"]).max()
    assert np.abs(g - fixed["gradient"]).max() > 1e-3 * gmax  # the weights' share is not small
    h, n_a, smooth = 1e-6, len(VA), 0
    half = pdd.contact_energy(VA, TA, VB, TB, rest_A=VA)["gradient"]  # B's weights move, A's held
    for v in np.flatnonzero(np.abs(g).sum(axis=1) > 0)[::3]:
        for k in range(3):
            def E(d, **rest):
                A, B = VA.copy(), VB.copy()
                (A if v < n_a else B)[v if v < n_a else v - n_a, k] += d
                return pdd.contact_energy(A, TA, B, TB, **rest)["energy"]
            ep, em = E(h), E(-h)
            if abs((ep - e["energy"]) / h - (e["energy"] - em) / h) <= 1e-6 * gmax:
                smooth += 1
                assert abs((ep - em) / (2 * h) - g[v, k]) <= 1e-5 * gmax
                hp, hm = E(h, rest_A=VA), E(-h, rest_A=VA)
                assert abs((hp - hm) / (2 * h) - half[v, k]) <= 1e-5 * gmax
    assert smooth > 0


def test_hessian_symmetric_psd():
    VA, TA, VB, TB = scene()
    e = pdd.contact_energy(VA, TA, VB, TB, hessian=True)
    H = e["hessian"]
    n = 3 * (len(VA) + len(VB))
    assert scipy_sparse.issparse(H) and H.shape == (n, n)
    D = H.toarray()
    assert np.array_equal(D, D.T)
    ev = np.linalg.eigvalsh(D)
    assert ev.min() >= -1e-12 * np.abs(ev).max()  # rounding of w Qs (x) u u^T (contact_energy.h)


def test_exact_engine_agrees():
    VA, TA, VB, TB = scene()
    f = pdd.contact_energy(VA, TA, VB, TB)
    x = pdd.contact_energy(VA, TA, VB, TB, engine="reference")
    assert f["pairs"] == x["pairs"]
    assert f["energy"] == pytest.approx(x["energy"], rel=1e-8)
    assert np.abs(f["gradient"] - x["gradient"]).max() <= 1e-4 * np.abs(x["gradient"]).max()


def test_a_pair_intersecting_by_rounding_takes_the_exact_engines_normal():
    """A Kuhn cell and one of its copy shifted by 0.01 along (1, 1, 1): their diagonal faces are
    coplanar but for the rounding of x + 0.01 and y + 0.01, so the pair intersects by ~1e-19.
    The fast engine cannot certify pdd2_global there (its record says so); the energy takes the
    exact engine's, whose witness normal has components outside the double range (numerators of
    ~800 bits): it is scaled by a power of two before rounding, and E is that value weighted."""
    VA = np.array([[0.0, 0.0, 0.5], [0.25, 0.0, 0.5], [0.25, 0.25, 0.5], [0.25, 0.25, 0.75]])
    VB = np.array([[0.01, 0.01, 0.26], [0.26, 0.01, 0.51], [0.26, 0.01, 0.26], [0.26, 0.26, 0.51]])
    T = np.array([[0, 1, 2, 3]])
    assert pdd.solve(VA, VB)["pdd2_global_error"] is not None
    exact = pdd.solve(VA, VB, engine="reference")["pdd2_global"]
    assert 0 < exact < 1e-37
    e = pdd.contact_energy(VA, T, VB, T, hessian=True, per_pair=True)
    assert e["pairs"] == 1
    assert e["pdd2_global"][0] == pytest.approx(float(exact), rel=1e-15)
    assert e["energy"] == pytest.approx(e["weight"][0] * float(exact), rel=1e-15)
    assert np.isfinite(e["gradient"]).all() and np.isfinite(e["hessian"].toarray()).all()


def test_self_contact_and_errors():
    V, T = pdd.read_mesh(os.path.join(MESHES, "two-spheres.msh"))
    e = pdd.contact_energy(V, T)
    assert e["gradient"].shape == (len(V), 3)
    assert e["pairs"] == len(pdd.mesh_contacts(V, T, variants="global")["a"])
    VA, TA, VB, TB = scene()
    # one name per engine across the module and the CLI (mesh_contacts, solve, pdd mesh --engine)
    for name in ("slow", "exact"):
        with pytest.raises(ValueError, match=f"^engine must be 'fast' or 'reference'; got '{name}'$"):
            pdd.contact_energy(VA, TA, VB, TB, engine=name)
        with pytest.raises(ValueError, match=f"^engine must be 'fast' or 'reference'; got '{name}'$"):
            pdd.mesh_contacts(VA, TA, VB, TB, engine=name)
    with pytest.raises(ValueError, match="rest_A"):
        pdd.contact_energy(VA, TA, VB, TB, rest_A=VA[:-1])
    with pytest.raises(ValueError, match="both VB and TB"):
        pdd.contact_energy(VA, TA, VB)
    # flags as solve's: True or False (a numpy bool too), a clear ValueError otherwise
    for name in ("hessian", "per_pair"):
        for bad in ("yes", 1, None):
            with pytest.raises(ValueError, match=f"^{name} must be True or False; got {bad!r}$"):
                pdd.contact_energy(VA, TA, VB, TB, **{name: bad})
    e = pdd.contact_energy(VA, TA, VB, TB, hessian=np.bool_(True), per_pair=np.array([False])[0])
    assert e["hessian"] is not None and "a" not in e


def test_elements_without_a_rest_weight_are_skipped_and_named():
    """An element whose rest shape has no finite volume (a non-finite rest coordinate, or one
    whose edge vectors overflow) gets no weight, as a flat one: skipped with the reason, its
    pairs left out, the energy finite. B's element 1 uses vertex 4; element 0 does not."""
    V = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4], [1, 1, 1]], dtype=float)
    T = np.array([[0, 1, 2, 3], [0, 1, 2, 4]])
    P = V + 0.5
    whole = pdd.contact_energy(V, T, P, T, per_pair=True)
    assert whole["pairs"] == 4 and whole["skipped"] == []
    rest = P.copy()
    rest[4] = [np.nan, 0, 0]
    e = pdd.contact_energy(V, T, P, T, rest_B=rest, per_pair=True)
    assert e["skipped"] == [("B", 1, "element 1 of mesh B: vertex 3 (mesh vertex 4: rest_B[4]) coordinate x "
                                     "is not finite (nan) at rest: it has no contact weight")]
    assert list(e["b"]) == [0, 0] and np.isfinite(e["energy"])
    # the same pairs of element 0, with the same weights: the same energy, term by term
    keep = whole["b"] == 0
    assert list(e["pair_energy"]) == list(whole["pair_energy"][keep])
    # rest volumes ~1e900 (not doubles) whose cube roots are: the weights (V_a V_b)^(1/3) ~1e300
    # and the energy are ordinary doubles, the same pairs as at rest
    big = pdd.contact_energy(V, T, P, T, rest_B=P * 1e300, per_pair=True)
    assert big["skipped"] == [] and list(big["b"]) == list(whole["b"])
    assert np.allclose(big["weight"], whole["weight"] * 1e300, rtol=1e-14)
    assert np.isfinite(big["energy"]) and big["energy"] == pytest.approx(whole["energy"] * 1e300, rel=1e-14)
    huge = pdd.contact_energy(V, T, P, T, rest_B=(P - 2.5) * 8e307)  # coordinates within +-1.6e308, edges not
    assert huge["pairs"] == 0 and huge["energy"] == 0
    assert [s[2] for s in huge["skipped"]] == [
        f"element {i} of mesh B: an edge at rest exceeds the double range: it has no contact weight" for i in (0, 1)]
    # the non-finite rest vertex first in both elements: every edge vector NaN, still "not
    # finite", not "flat"
    rest0 = P.copy()
    rest0[0] = np.nan
    e0 = pdd.contact_energy(V, T, P, T, rest_B=rest0)
    assert [(m, i) for m, i, _ in e0["skipped"]] == [("B", 0), ("B", 1)]
    assert all("rest_B[0]) coordinate x is not finite (nan) at rest" in why for _, _, why in e0["skipped"])
    assert e0["pairs"] == 0 and e0["energy"] == 0
    # a non-finite rest coordinate is bad input wherever it lies: listed though its element (B's
    # element 2, far from A) is in no pair, first, and the energy that of the rest
    V2 = np.vstack([V, [[10, 10, 10], [11, 10, 10], [10, 11, 10], [10, 10, 11]]])
    T2 = np.vstack([T, [[5, 6, 7, 8]]])
    P2 = V2 + 0.5
    rest2 = P2.copy()
    rest2[6] = [0, np.inf, 0]
    e2 = pdd.contact_energy(V, T, P2, T2, rest_B=rest2, per_pair=True)
    assert e2["skipped"] == [("B", 2, "element 2 of mesh B: vertex 1 (mesh vertex 6: rest_B[6]) coordinate y "
                                      "is not finite (inf) at rest: it has no contact weight")]
    assert list(e2["pair_energy"]) == list(whole["pair_energy"])
    # self-contact: one list for the mesh, each element once (element 1 of the chain below,
    # flat at rest, is b of the pair (0, 1) and a of the pair (1, 2))
    es = pdd.contact_energy(V2, T2, rest_A=rest2)
    assert [(m, i) for m, i, _ in es["skipped"]] == [("A", 2)]
    tet = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    chain = np.vstack([tet, tet + [0.3, 0.1, 0.1], tet + [0.6, 0.2, 0.2]])
    flat = chain.copy()
    flat[7] = flat[4]
    ec = pdd.contact_energy(chain, np.arange(12).reshape(3, 4), rest_A=flat)
    assert ec["skipped"] == [("A", 1, "element 1 of mesh A is flat at rest (volume 0): it has no contact weight")]


def test_energy_outside_the_double_range_raises():
    """E ~ L^4: at 2^-260 of the size a pair's term w_ab * pdd2_global is ~1e-313 (no normal
    double: E would read ~0 with pairs intersecting), at 2^260 E ~ 1e313; both raise, naming it."""
    V = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4]], dtype=float)
    T = np.array([[0, 1, 2, 3]])
    P = V + 0.5
    assert pdd.contact_energy(V, T, P, T)["energy"] > 0
    with pytest.raises(ValueError, match=r"below the double range \(pair \(0, 0\)"):
        pdd.contact_energy(np.ldexp(V, -260), T, np.ldexp(P, -260), T)
    with pytest.raises(OverflowError, match="exceeds the double range") as e:
        pdd.contact_energy(np.ldexp(V, 260), T, np.ldexp(P, 260), T)
    # the largest value as the shortest decimal that reads back as it (not ~300 digits)
    largest = re.search(r"largest pdd2_global (\S+)\)", str(e.value))
    assert largest and len(largest.group(1)) <= 24 and float(largest.group(1)) > 1e150


# ---- `pdd mesh --energy` (docs/definitions.md "Contact energy": its keys) ------------------

ENERGY_KEYS = {"energy", "pairs", "max_pdd2_global", "max_force", "max_force_vertex", "skipped", "seconds"}


def write_vtk(path, V, T):
    """Legacy VTK with every coordinate in its shortest round-trip form (repr), so that the
    tool reads the same doubles as the module gets."""
    with open(path, "w") as f:
        f.write("# vtk DataFile Version 3.0\nscene\nASCII\nDATASET UNSTRUCTURED_GRID\n")
        f.write(f"POINTS {len(V)} double\n")
        for v in V:
            f.write(" ".join(repr(float(x)) for x in v) + "\n")
        f.write(f"CELLS {len(T)} {5 * len(T)}\n")
        for t in T:
            f.write("4 " + " ".join(str(int(i)) for i in t) + "\n")
        f.write(f"CELL_TYPES {len(T)}\n" + "10\n" * len(T))


def run_cli(*args):
    import subprocess
    cli = os.environ.get("PDD_CLI")
    if not cli:
        pytest.skip("PDD_CLI (the pdd tool of this build) not set")
    return subprocess.run([cli, "mesh", *args], capture_output=True, text=True)


def check_cli_energy(out, e):
    import json
    lines = out.strip().splitlines()
    assert len(lines) == 1
    j = json.loads(lines[0])
    assert set(j) == ENERGY_KEYS
    # the same library call on the same doubles: equal, not close
    assert j["energy"] == e["energy"]
    assert j["pairs"] == e["pairs"]
    assert j["max_pdd2_global"] == e["max_pdd2_global"]
    forces = np.sqrt((e["gradient"] ** 2).sum(axis=1))
    assert j["max_force"] == pytest.approx(forces.max(), rel=1e-15)
    assert j["max_force_vertex"] == int(np.argmax(forces))
    # (the tool names a vertex by its line in the file, the module by its row)
    assert [(k["mesh"], k["index"]) for k in j["skipped"]] == [(m, i) for m, i, _ in e["skipped"]]
    assert j["seconds"] >= 0


def test_cli_energy_two_meshes(tmp_path):
    VA, TA, VB, TB = scene()
    a, b = str(tmp_path / "a.vtk"), str(tmp_path / "b.vtk")
    write_vtk(a, VA, TA)
    write_vtk(b, VB, TB)
    r = run_cli("--a", a, "--b", b, "--energy", "--quiet")
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""  # --quiet: nothing but errors and skipped elements
    e = pdd.contact_energy(VA, TA, VB, TB)
    assert e["pairs"] > 0
    check_cli_energy(r.stdout, e)
    # --output: the same object in the file, nothing on standard output
    out = str(tmp_path / "energy.json")
    r = run_cli("--a", a, "--b", b, "--energy", "--quiet", "--output", out)
    assert r.returncode == 0 and r.stdout == ""
    with open(out) as f:
        check_cli_energy(f.read(), e)


def test_cli_energy_rest_shapes(tmp_path):
    """--rest-a / --rest-b: the weights from the rest shapes, held constant, as the module's
    rest_A / rest_B (the same library call on the same doubles: equal); a rest file that is not
    the same mesh (vertex count, tetrahedra) is refused, exit 2, and so are a rest shape without
    --energy, --rest-b with --self and an output over a rest file."""
    VA, TA, VB, TB = scene()
    RA, RB = VA * 1.01, VB + np.array([0.0, 0.0, 0.02])  # rest shapes other than the positions
    a, b, ra, rb = (str(tmp_path / f"{n}.vtk") for n in ("a", "b", "ra", "rb"))
    for path, V, T in ((a, VA, TA), (b, VB, TB), (ra, RA, TA), (rb, RB, TB)):
        write_vtk(path, V, T)
    e = pdd.contact_energy(VA, TA, VB, TB, rest_A=RA, rest_B=RB)
    r = run_cli("--a", a, "--b", b, "--energy", "--quiet", "--rest-a", ra, "--rest-b", rb)
    assert r.returncode == 0, r.stderr
    check_cli_energy(r.stdout, e)
    # one side's rest shape: the other's weights follow its positions, as rest_B=None
    e = pdd.contact_energy(VA, TA, VB, TB, rest_A=RA)
    r = run_cli("--a", a, "--b", b, "--energy", "--quiet", "--rest-a", ra)
    assert r.returncode == 0, r.stderr
    check_cli_energy(r.stdout, e)
    assert e["energy"] != pdd.contact_energy(VA, TA, VB, TB)["energy"]  # the rest shape mattered
    # a rest vertex that is not finite, used only by elements in no pair: named and exit 1, as
    # the module lists it, the energy that of the other elements
    in_pairs = set(pdd.contact_energy(VA, TA, VB, TB, rest_B=RB, per_pair=True)["b"])
    v = next(v for v in range(len(VB)) if not any(v in TB[i] for i in in_pairs))
    RBn = RB.copy()
    RBn[v] = [np.nan, 0.0, 0.0]
    rbn = str(tmp_path / "rbn.vtk")
    write_vtk(rbn, RBn, TB)
    e = pdd.contact_energy(VA, TA, VB, TB, rest_B=RBn)
    named = sorted(i for i in range(len(TB)) if v in TB[i])
    assert [(m, i) for m, i, _ in e["skipped"]] == [("B", i) for i in named]
    assert e["energy"] == pdd.contact_energy(VA, TA, VB, TB, rest_B=RB)["energy"]
    r = run_cli("--a", a, "--b", b, "--energy", "--quiet", "--rest-b", rbn)
    assert r.returncode == 1, r.stderr
    check_cli_energy(r.stdout, e)
    assert all(f"pdd mesh: skipped element {i} of mesh B" in r.stderr for i in named)
    for args, why in (((("--rest-a", rb)), "not the same mesh"), ((("--rest-b", ra)), "not the same mesh")):
        r = run_cli("--a", a, "--b", b, "--energy", "--quiet", *args)
        assert r.returncode == 2 and r.stdout == "" and why in r.stderr
    r = run_cli("--a", a, "--b", b, "--rest-a", ra)
    assert r.returncode == 2 and "give them with --energy" in r.stderr
    # an output over a rest file is refused before anything is written (the rest file kept)
    with open(rb) as f:
        kept = f.read()
    r = run_cli("--a", a, "--b", b, "--energy", "--rest-b", rb, "--output", rb)
    assert r.returncode == 2 and "--rest-b" in r.stderr and "same file" in r.stderr
    with open(rb) as f:
        assert f.read() == kept
    r = run_cli("--a", a, "--self", "--energy", "--rest-b", rb)
    assert r.returncode != 0 and r.stdout == ""


def test_cli_energy_self_contact(tmp_path):
    VA, TA, VB, TB = scene()
    V = np.vstack([VA, VB])
    T = np.vstack([TA, TB + len(VA)])
    p = str(tmp_path / "both.vtk")
    write_vtk(p, V, T)
    r = run_cli("--a", p, "--self", "--energy", "--quiet")
    assert r.returncode == 0, r.stderr
    e = pdd.contact_energy(V, T)
    assert e["pairs"] > 0
    check_cli_energy(r.stdout, e)


def test_cli_energy_no_contact(tmp_path):
    VA, TA, VB, TB = scene()
    a, b = str(tmp_path / "a.vtk"), str(tmp_path / "b.vtk")
    write_vtk(a, VA, TA)
    write_vtk(b, VB + np.array([10.0, 0, 0]), TB)
    r = run_cli("--a", a, "--b", b, "--energy", "--quiet")
    assert r.returncode == 0, r.stderr
    import json
    j = json.loads(r.stdout)
    assert set(j) == ENERGY_KEYS
    assert j["energy"] == 0 and j["pairs"] == 0 and j["max_force"] == 0
    assert j["max_force_vertex"] is None


def test_cli_energy_exit_codes(tmp_path):
    VA, TA, VB, TB = scene()
    a = str(tmp_path / "a.vtk")
    write_vtk(a, VA, TA)
    # a missing mesh: exit 2 (file error), a message naming it, nothing on standard output
    r = run_cli("--a", a, "--b", str(tmp_path / "missing.vtk"), "--energy", "--quiet")
    assert r.returncode == 2 and r.stdout == "" and "missing.vtk" in r.stderr
    # neither --b nor --self: exit 2 (usage)
    r = run_cli("--a", a, "--energy", "--quiet")
    assert r.returncode == 2 and r.stdout == "" and "--self" in r.stderr
    # what the energy does not make (per-pair variants, a VTK file of the pairs, their summary):
    # refused, exit 2 (usage), nothing computed or written
    for extra in (["--vtk", str(tmp_path / "e.vtk")], ["--summary"], ["--variants", "global"]):
        r = run_cli("--a", a, "--self", "--energy", *extra)
        assert r.returncode == 2 and r.stdout == "" and extra[0] + " excludes --energy" in r.stderr, extra
    assert not (tmp_path / "e.vtk").exists()
    # an unwritable --output: exit 2
    r = run_cli("--a", a, "--self", "--energy", "--quiet", "--output", str(tmp_path / "no" / "dir" / "e.json"))
    assert r.returncode == 2 and "cannot write" in r.stderr
    # a vertex that is not finite: its elements skipped and named (standard error and the
    # object's `skipped`), the energy of the rest, exit 1 (as `pdd mesh` without --energy)
    b = str(tmp_path / "b.vtk")
    VBn = VB.copy()
    VBn[0] = [np.nan, 0.0, 0.0]
    write_vtk(b, VBn, TB)
    r = run_cli("--a", a, "--b", b, "--energy", "--quiet")
    assert r.returncode == 1, r.stderr
    e = pdd.contact_energy(VA, TA, VBn, TB)
    assert e["skipped"] and all(s[0] == "B" for s in e["skipped"])
    check_cli_energy(r.stdout, e)
    assert all(("pdd mesh: skipped " + k["reason"]) in r.stderr for k in json.loads(r.stdout)["skipped"])


def test_contacts_made_by_rounding_taken_at_a_bound():
    # A Kuhn grid of cell 0.1 (0.1 * i rounded once) against its copy moved by 0.01 along
    # (1, 1, 1): faces x = y meet by rounding (~1e-34 of a cell squared) beside deep pairs. By
    # default those pairs are taken at a certified bound (docs/definitions.md "Contact energy",
    # Accuracy): E within 1e-12 of the per_pair call's (every pair certified; the certified
    # terms are the same bits, the bounded ones' bounds sum to <= 1e-12 of E), the same pairs and
    # max_pdd2_global, gradients within 1e-12 of the largest entry.
    corners = [(0, 1, 3, 7), (0, 1, 5, 7), (0, 2, 3, 7), (0, 2, 6, 7), (0, 4, 5, 7), (0, 4, 6, 7)]
    n = 2
    index = {}
    V, T = [], []
    for i in range(n):
        for j in range(n):
            for k in range(n):
                c = []
                for b in range(8):
                    key = (i + (b & 1), j + (b >> 1 & 1), k + (b >> 2 & 1))
                    if key not in index:
                        index[key] = len(V)
                        V.append([0.1 * x for x in key])
                    c.append(index[key])
                T += [[c[q] for q in t] for t in corners]
    V, T = np.array(V), np.array(T)
    e = pdd.contact_energy(V, T, V + 0.01, T)
    f = pdd.contact_energy(V, T, V + 0.01, T, per_pair=True)
    assert e["pairs"] == f["pairs"] > 50
    assert e["bounded_pairs"] > 0 and f["bounded_pairs"] == 0
    assert abs(e["energy"] - f["energy"]) <= 1e-12 * f["energy"] + 2e-16 * f["pairs"] * f["energy"]
    assert e["max_pdd2_global"] == f["max_pdd2_global"]
    assert np.abs(e["gradient"] - f["gradient"]).max() <= 1e-12 * np.abs(f["gradient"]).max()
    assert (f["pdd2_global"] < 1e-30).sum() >= e["bounded_pairs"]
