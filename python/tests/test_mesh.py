"""pdd.mesh_contacts and pdd.read_mesh (definitions §10; the C++ library include/pdd/mesh.h):
the same pairs and values as the `pdd mesh` tool on the shipped meshes (fixtures/meshes),
each pair's values those of pdd.solve on that element pair (fast: bit for bit; reference:
equal Fractions), definitions §9's global variant (its four columns, and the exact engine's lower
bound), self-contact, skipped elements, bad input raising ValueError with the
library's words, and meshes read by Debian's python3-meshio giving the same arrays and
contacts (on our files, and on formats only meshio reads)."""
import json
import re
import math
import subprocess
import warnings
from fractions import Fraction

import numpy as np
import pytest

import pdd
from conftest import CONTRACT, FIXTURES, LABEL_KEYS, VALUE_KEYS

MESHES = FIXTURES / "meshes"
VARIANT_OF_KEY = dict(zip(VALUE_KEYS, ("rigid", "eq11", "static", "pdd2", "relaxed", "accel1", "accel6")))
LABEL_OF_KEY = {"rigid_pd2": "rigid_dir", "pdd2_static": "pdd2_static_dir", "pdd2": "pdd2_dir",
                "pdd2_relaxed": "pdd2_relaxed_dir"}
DEFAULT = ("rigid_pd2", "pdd2_static", "pdd2", "pdd2_accel1")  # "rigid,static,pdd2,accel1"
# definitions §9's columns with variant "global" (as solve_batch gives them); reference: and the
# bound.
GLOBAL_COLUMNS = ("pdd2_global", "pdd2_global_normal", "q1_A_global", "q1_B_global")
STATS = ("skipped", "elements_a", "elements_b", "box_pairs", "seconds_boxes", "seconds_broadphase",
         "seconds_decision", "seconds_depth")

# (A, B) of the CLI comparisons; B None: self-contact. Intersecting pairs (from `pdd mesh
# --summary`): spheres 2639, torus/box 2712, tiny 51, two-spheres (self) 616; conforming,
# touching and slivers (self) have none, and must have none here too.
CASES = [("sphere-a.msh", "sphere-b.msh"), ("torus.msh", "box.vtk"), ("tiny-a.msh", "tiny-b.msh"),
         ("conforming-a.msh", "conforming-b.msh"), ("touching-a.msh", "touching-b.msh"),
         ("two-spheres.msh", None), ("slivers.msh", None)]


def bits(x):
    return np.asarray(x, dtype=np.float64).view(np.int64)


def value_keys(variants):
    names = variants.split(",")
    return tuple(k for k in VALUE_KEYS if VARIANT_OF_KEY[k] in names or "all" in names)


def wants_global(variants):
    names = variants.split(",")
    return "global" in names or "all" in names


def global_keys(glob, exact):
    """The keys of definitions §9: the exact engine adds its lower bound, the fast one pdd2_global_error."""
    return (GLOBAL_COLUMNS + (("pdd2_global_lower",) if exact else ("pdd2_global_error",))) if glob else ()


def column_keys(keys, glob=False, exact=False):
    """The row columns mesh_contacts returns for value keys `keys` (in definitions §6 order) and, with
    `glob`, definitions §9's (before "error", as solve_batch places them)."""
    out = ("a", "b", "intersecting") + keys + tuple(LABEL_OF_KEY[k] for k in keys if k in LABEL_OF_KEY)
    return out + (("q1_A", "q1_B") if "pdd2" in keys else ()) + global_keys(glob, exact) + ("error",)


def record_keys(keys, glob=False, exact=False):
    """The keys of the CLI's records: `pdd solve`'s order, definitions §9's after "error"."""
    out = column_keys(keys)
    return out + global_keys(glob, exact)


_meshes = {}


def mesh(name):
    if name not in _meshes:
        _meshes[name] = pdd.read_mesh(MESHES / name)
    return _meshes[name]


def contacts_of(a, b, **kw):
    VA, TA = mesh(a)
    if b is None:
        return pdd.mesh_contacts(VA, TA, **kw)
    VB, TB = mesh(b)
    return pdd.mesh_contacts(VA, TA, VB, TB, **kw)


def cli_records(cli, tmp_path, a, b, *extra):
    out = tmp_path / "pairs.jsonl"
    cmd = [cli, "mesh", "--a", str(MESHES / a)] + (["--self"] if b is None else ["--b", str(MESHES / b)])
    run = subprocess.run(cmd + ["--output", str(out), "--quiet", *extra], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return [json.loads(line) for line in out.read_text().splitlines()]


def assert_same_as_cli(res, records, keys, exact, glob=False):
    """mesh_contacts' columns == the CLI's JSON Lines records, row for row."""
    cols = column_keys(keys, glob, exact)
    assert list(res)[:len(cols)] == list(cols)
    assert list(res)[len(cols):] == list(STATS)
    n = len(records)
    assert res["a"].dtype == np.int64 and res["b"].dtype == np.int64
    assert res["a"].tolist() == [r["a"] for r in records]
    assert res["b"].tolist() == [r["b"] for r in records]
    for j, r in enumerate(records):  # the CLI writes the same keys, `a` and `b` in place of name
        assert tuple(r) == record_keys(keys, glob, exact), r
        if glob:
            assert_global_row(res, j, r, exact)
        assert res["intersecting"][j] == r["intersecting"] and res["error"][j] == r["error"]
        for k in keys:
            if exact:
                assert res[k][j] == Fraction(r[k]), (j, k)
            else:  # the CLI's JSON numbers read back as the same doubles (round trip)
                assert bits(res[k][j]) == bits(r[k]), (j, k)
        for k in keys:
            if k in LABEL_OF_KEY:
                assert res[LABEL_OF_KEY[k]][j] == (r[LABEL_OF_KEY[k]] or ""), (j, k)
        if "pdd2" in keys:
            for q in ("q1_A", "q1_B"):
                if exact:
                    assert res[q][j] == [[Fraction(c) for c in v] for v in r[q]], (j, q)
                else:
                    assert (bits(res[q][j]) == bits(r[q])).all(), (j, q)
    for k in keys:
        if exact:
            assert isinstance(res[k], list) and len(res[k]) == n
        else:
            assert res[k].dtype == np.float64 and res[k].shape == (n,)
    if "pdd2" in keys and not exact:
        assert res["q1_A"].shape == (n, 4, 3) and res["q1_B"].shape == (n, 4, 3)


def assert_global_row(res, j, r, exact):
    """Row j's definitions §9 columns == the record r (a CLI record or a pdd.solve dict): the same
    doubles bit for bit (fast), equal Fractions (reference; the CLI's "p/q" strings read)."""
    if exact:
        F = Fraction
        assert res["pdd2_global"][j] == F(r["pdd2_global"]), j
        assert res["pdd2_global_lower"][j] == F(r["pdd2_global_lower"]), j
        assert res["pdd2_global_normal"][j] == [F(c) for c in r["pdd2_global_normal"]], j
        for q in ("q1_A_global", "q1_B_global"):
            assert res[q][j] == [[F(c) for c in v] for v in r[q]], (j, q)
    else:
        assert bits(res["pdd2_global"][j]) == bits(r["pdd2_global"]), j
        assert (bits(res["pdd2_global_normal"][j]) == bits(r["pdd2_global_normal"])).all(), j
        for q in ("q1_A_global", "q1_B_global"):
            assert (bits(res[q][j]) == bits(r[q])).all(), (j, q)


def pair_of(res, j, a, b):
    VA, TA = mesh(a)
    VB, TB = (VA, TA) if b is None else mesh(b)
    return VA[TA[res["a"][j]]], VB[TB[res["b"][j]]]


def assert_rows_are_single_solves(res, a, b, keys, engine="fast", rows=None, glob=False):
    """Row j == pdd.solve(element a[j], element b[j]) on the requested keys: bit for bit (fast),
    equal Fractions (reference)."""
    for j in (range(len(res["a"])) if rows is None else rows):
        A, B = pair_of(res, j, a, b)
        r = pdd.solve(A, B, engine=engine)
        assert r["error"] is None and r["intersecting"] and res["error"][j] is None, j
        if glob:
            assert_global_row(res, j, r, exact=engine == "reference")
        for k in keys:
            if engine == "fast":
                assert bits(res[k][j]) == bits(r[k]), (j, k)
            else:
                assert res[k][j] == r[k], (j, k)
            if k in LABEL_OF_KEY:
                assert res[LABEL_OF_KEY[k]][j] == r[LABEL_OF_KEY[k]], (j, k)
        if "pdd2" in keys:
            for q in ("q1_A", "q1_B"):
                if engine == "fast":
                    assert (bits(res[q][j]) == bits(r[q])).all(), (j, q)
                else:
                    assert res[q][j] == r[q], (j, q)


@pytest.mark.parametrize("a, b", CASES)
def test_fast_contacts_are_the_cli_records(pdd_cli, tmp_path, a, b):
    res = contacts_of(a, b)
    records = cli_records(pdd_cli, tmp_path, a, b)
    assert_same_as_cli(res, records, DEFAULT, exact=False)
    assert res["skipped"] == []
    assert res["elements_a"] == len(mesh(a)[1])
    assert res["elements_b"] == (0 if b is None else len(mesh(b)[1]))
    assert res["box_pairs"] >= len(res["a"])
    assert all(res[k] >= 0 for k in STATS[4:])
    expected = {"sphere-a.msh": 2639, "torus.msh": 2712, "tiny-a.msh": 51, "two-spheres.msh": 616}
    assert len(res["a"]) == expected.get(a, 0)


def test_fast_all_variants_are_the_cli_records(pdd_cli, tmp_path):
    res = contacts_of("sphere-a.msh", "sphere-b.msh", variants="all")
    assert_same_as_cli(res, cli_records(pdd_cli, tmp_path, "sphere-a.msh", "sphere-b.msh",
                                        "--variants", "all"), VALUE_KEYS, exact=False, glob=True)


def test_fast_global_columns():
    """Variant "global" (definitions §9): pdd2_global, its normal and positions as columns of
    solve_batch's shapes, each row pdd.solve's on that pair bit for bit (the library takes them
    from the same solve_pair), strictly positive and at most the pair's pdd2_relaxed (a minimum
    over every separating plane, the candidates' included); NaN-free. Without it, no such column."""
    res = contacts_of("sphere-a.msh", "sphere-b.msh", variants="rigid,global")
    n = len(res["a"])
    assert n == 2639
    assert list(res)[:len(column_keys(("rigid_pd2",), True))] == list(column_keys(("rigid_pd2",), True))
    assert res["pdd2_global"].dtype == np.float64 and res["pdd2_global"].shape == (n,)
    assert res["pdd2_global_normal"].dtype == np.float64 and res["pdd2_global_normal"].shape == (n, 3)
    assert res["q1_A_global"].shape == (n, 4, 3) and res["q1_B_global"].shape == (n, 4, 3)
    assert not any(np.isnan(res[k]).any() for k in GLOBAL_COLUMNS)
    assert_rows_are_single_solves(res, "sphere-a.msh", "sphere-b.msh", ("rigid_pd2",), glob=True)
    for j in range(n):
        r = pdd.solve(*pair_of(res, j, "sphere-a.msh", "sphere-b.msh"))
        assert 0 < res["pdd2_global"][j] <= r["pdd2_relaxed"], j
    assert (res["pdd2_global"] <= contacts_of("sphere-a.msh", "sphere-b.msh", variants="relaxed")["pdd2_relaxed"]).all()
    assert not set(GLOBAL_COLUMNS) & set(contacts_of("sphere-a.msh", "sphere-b.msh"))


def test_reference_global_is_the_cli_records_and_single_solves(pdd_cli, tmp_path):
    """The exact engine with "rigid,global" on the tiny cubes (51 pairs): definitions §9's witness,
    normal, positions and proved lower bound as Fractions, equal to the CLI's records and to
    pdd.solve(engine="reference"); the fast pdd2_global lies in [lower, witness] up to definitions §8."""
    res = contacts_of("tiny-a.msh", "tiny-b.msh", engine="reference", variants="rigid,global")
    keys = ("rigid_pd2",)
    records = cli_records(pdd_cli, tmp_path, "tiny-a.msh", "tiny-b.msh", "--engine", "reference",
                          "--variants", "rigid,global")
    assert len(records) == 51
    assert_same_as_cli(res, records, keys, exact=True, glob=True)
    assert all(isinstance(x, Fraction) for k in ("pdd2_global", "pdd2_global_lower") for x in res[k])
    assert_rows_are_single_solves(res, "tiny-a.msh", "tiny-b.msh", keys, engine="reference", glob=True)
    fast = contacts_of("tiny-a.msh", "tiny-b.msh", variants="global")
    assert fast["a"].tolist() == res["a"].tolist() and fast["b"].tolist() == res["b"].tolist()
    for x, lower, upper in zip(fast["pdd2_global"], res["pdd2_global_lower"], res["pdd2_global"]):
        assert 0 < lower <= upper
        assert lower * (1 - CONTRACT) <= Fraction(float(x)) <= upper * (1 + CONTRACT)


@pytest.mark.parametrize("b", ["tiny-b.msh", None])
def test_reference_contacts_are_the_cli_records_and_single_solves(pdd_cli, tmp_path, b):
    """The exact engine on the tiny cubes (51 pairs) and on the self-contact of one (no pair):
    the CLI's "p/q" strings as Fractions, and pdd.solve(engine="reference") per pair."""
    res = contacts_of("tiny-a.msh", b, engine="reference", variants="rigid,pdd2,relaxed")
    keys = ("rigid_pd2", "pdd2", "pdd2_relaxed")
    records = cli_records(pdd_cli, tmp_path, "tiny-a.msh", b, "--engine", "reference",
                          "--variants", "rigid,pdd2,relaxed")
    assert_same_as_cli(res, records, keys, exact=True)
    assert len(records) == (51 if b else 0)
    assert all(isinstance(res[k][j], Fraction) for k in keys for j in range(len(records)))
    assert_rows_are_single_solves(res, "tiny-a.msh", b, keys, engine="reference")
    # the fast engine on the same pairs is within definitions §8 (1e-9 relative) of these values
    fast = contacts_of("tiny-a.msh", b, variants="rigid,pdd2,relaxed")
    assert fast["a"].tolist() == res["a"].tolist() and fast["b"].tolist() == res["b"].tolist()
    for k in keys:
        for x, q in zip(fast[k], res[k]):
            assert abs(Fraction(float(x)) - q) <= Fraction(1, 10**9) * q


@pytest.mark.parametrize("variants", ["rigid,static,pdd2,accel1", "rigid", "eq11", "static", "pdd2",
                                      "relaxed", "accel1", "accel6", "rigid,static", "static,accel6",
                                      "global", "accel1,global", "all"])
def test_fast_rows_are_single_solves(variants):
    """Every variant set, including those the library computes by separate engine calls
    instead of one solve_pair (one variant, or rigid and one other): the same bits."""
    res = contacts_of("sphere-a.msh", "sphere-b.msh", variants=variants)
    keys = value_keys(variants)
    glob = wants_global(variants)
    assert tuple(k for k in res if k in VALUE_KEYS) == keys
    assert list(res)[:len(column_keys(keys, glob))] == list(column_keys(keys, glob))
    assert len(res["a"]) == 2639
    assert_rows_are_single_solves(res, "sphere-a.msh", "sphere-b.msh", keys, glob=glob)


def test_self_contact_is_brute_force_and_contacts_of_the_parts():
    """Self-contact of one mesh made of tiny-a and tiny-b (B's indices shifted by 14): every pair
    a < b sharing no vertex whose interiors intersect, by brute force over all 1128 pairs
    (solve_batch, rigid_pd2 > 0 — definitions §4); they are A–B pairs only (each part is a valid mesh)
    and equal mesh_contacts(A, B) shifted, value for value."""
    VA, TA = mesh("tiny-a.msh")
    VB, TB = mesh("tiny-b.msh")
    V = np.concatenate([VA, VB])
    T = np.concatenate([TA, TB + len(VA)])
    res = pdd.mesh_contacts(V, T, variants="all")
    assert res["elements_a"] == 48 and res["elements_b"] == 0
    i, j = np.triu_indices(len(T), k=1)
    disjoint = np.array([not set(T[x]) & set(T[y]) for x, y in zip(i, j)])
    i, j = i[disjoint], j[disjoint]
    brute = pdd.solve_batch(V[T[i]], V[T[j]])
    hit = brute["rigid_pd2"] > 0
    assert res["a"].tolist() == i[hit].tolist() and res["b"].tolist() == j[hit].tolist()
    assert (res["a"] < 24).all() and (res["b"] >= 24).all()
    two = pdd.mesh_contacts(VA, TA, VB, TB, variants="all")
    assert two["a"].tolist() == res["a"].tolist() and (two["b"] + 24).tolist() == res["b"].tolist()
    for k in VALUE_KEYS + ("q1_A", "q1_B"):
        assert (bits(two[k]) == bits(res[k])).all(), k
        assert (bits(brute[k][hit]) == bits(res[k])).all(), k
    for k in LABEL_KEYS:
        assert (two[k] == res[k]).all() and (brute[k][hit] == res[k]).all(), k


def test_self_contact_drops_pairs_sharing_a_vertex():
    """Two copies of one tetrahedron overlap completely; sharing a vertex index (only the
    index counts) they are not a self-contact pair, with their own vertices they are."""
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    shared = pdd.mesh_contacts(np.concatenate([V, V[1:]]), np.array([[0, 1, 2, 3], [0, 4, 5, 6]]))
    assert len(shared["a"]) == 0 and shared["box_pairs"] == 0
    own = pdd.mesh_contacts(np.concatenate([V, V]), np.array([[0, 1, 2, 3], [4, 5, 6, 7]]))
    assert own["a"].tolist() == [0] and own["b"].tolist() == [1]
    r = pdd.solve(V, V)
    assert bits(own["pdd2"][0]) == bits(r["pdd2"]) and own["pdd2_dir"][0] == r["pdd2_dir"]


def write_legacy_vtk(path, V, T):
    """A legacy ASCII VTK file of tetrahedra; repr() writes every double so that it reads back
    as the same double."""
    with open(path, "w") as f:
        f.write(f"# vtk DataFile Version 2.0\ntest\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS {len(V)} double\n")
        f.writelines(" ".join(repr(float(x)) for x in p) + "\n" for p in V)
        f.write(f"CELLS {len(T)} {5 * len(T)}\n")
        f.writelines("4 " + " ".join(map(str, t)) + "\n" for t in T)
        f.write(f"CELL_TYPES {len(T)}\n" + "10\n" * len(T))


def test_rejected_pairs_are_error_rows(pdd_cli, tmp_path):
    """A pair whose values leave the normal double range (definitions §8: the tiny cubes scaled by
    1e-160 have squared depths near 1e-323) is an error row — NaN values and positions, ""
    labels, intersecting False, the engine's message — never an exception; the other rows are
    computed. Each mesh is the tiny cube twice, as it is and scaled, so both kinds of row occur.
    Rows and messages are those of `pdd mesh` (which writes {"a", "b", "error"} for them and
    exits 1) and of pdd.solve on the pair."""
    meshes = []
    for name in ("tiny-a.msh", "tiny-b.msh"):
        V, T = mesh(name)
        meshes.append((np.concatenate([V, V * 1e-160]), np.concatenate([T, T + len(V)])))
    (VA, TA), (VB, TB) = meshes
    res = pdd.mesh_contacts(VA, TA, VB, TB)
    write_legacy_vtk(tmp_path / "a.vtk", VA, TA)
    write_legacy_vtk(tmp_path / "b.vtk", VB, TB)
    assert (pdd.read_mesh(tmp_path / "a.vtk")[0] == VA).all()
    run = subprocess.run([pdd_cli, "mesh", "--a", str(tmp_path / "a.vtk"), "--b", str(tmp_path / "b.vtk"),
                          "--quiet", "--output", str(tmp_path / "o.jsonl")], capture_output=True, text=True)
    assert run.returncode == 1, run.stderr
    records = [json.loads(line) for line in (tmp_path / "o.jsonl").read_text().splitlines()]
    assert res["a"].tolist() == [r["a"] for r in records] and res["b"].tolist() == [r["b"] for r in records]
    rejected = [j for j, e in enumerate(res["error"]) if e is not None]
    assert 0 < len(rejected) < len(records)
    for j, r in enumerate(records):
        A, B = VA[TA[res["a"][j]]], VB[TB[res["b"][j]]]
        single = pdd.solve(A, B)
        assert res["error"][j] == r["error"] == single["error"], j
        if j in rejected:
            assert tuple(r) == ("a", "b", "error") and "not representable" in r["error"]
            assert not res["intersecting"][j] and res["pdd2_dir"][j] == "" and res["rigid_dir"][j] == ""
            assert all(math.isnan(res[k][j]) for k in DEFAULT)
            assert np.isnan(res["q1_A"][j]).all() and np.isnan(res["q1_B"][j]).all()
        else:
            assert res["intersecting"][j]
            assert all(bits(res[k][j]) == bits(single[k]) for k in DEFAULT), j
            assert (bits(res["q1_B"][j]) == bits(single["q1_B"])).all(), j


def test_threads_do_not_change_results():
    ref = contacts_of("torus.msh", "box.vtk", variants="all")
    for threads in (1, np.int32(2), 0, 4096):
        res = contacts_of("torus.msh", "box.vtk", variants="all", threads=threads)
        for k in ("a", "b") + VALUE_KEYS + ("q1_A", "q1_B"):
            assert (bits(res[k]) == bits(ref[k])).all(), k
        for k in LABEL_KEYS:
            assert (res[k] == ref[k]).all(), k


def test_inputs_converted_like_numpy():
    """Lists, int32 and unsigned indices, Fortran order, strided views, int coordinates: the
    same mesh as float64 and int64 arrays."""
    VA, TA = mesh("tiny-a.msh")
    VB, TB = mesh("tiny-b.msh")
    ref = pdd.mesh_contacts(VA, TA, VB, TB)
    for args in ((VA.tolist(), TA.tolist(), VB.tolist(), TB.tolist()),
                 (np.asfortranarray(VA), TA.astype(np.int32), VB, TB.astype(np.uint16)),
                 (VA, np.asfortranarray(TA), np.concatenate([VB, VB], axis=1)[:, :3], TB)):  # a strided view
        res = pdd.mesh_contacts(*args)
        assert (res["a"] == ref["a"]).all() and (bits(res["pdd2"]) == bits(ref["pdd2"])).all()
    Vi = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4], [1, 1, 1], [5, 1, 1], [1, 5, 1], [1, 1, 5]])
    res = pdd.mesh_contacts(Vi, [[0, 1, 2, 3]], Vi, [[4, 5, 6, 7]])
    r = pdd.solve(Vi[:4], Vi[4:])
    assert res["a"].tolist() == [0] and bits(res["pdd2"][0]) == bits(r["pdd2"])


def test_meshes_without_tetrahedra_are_errors():
    """As `pdd mesh` and `pdd resolve` refuse a mesh file without tetrahedra (exit 2), the module
    refuses an empty tetrahedron array: an empty result would read as "no contact" or
    "resolved"."""
    VA, TA = mesh("tiny-a.msh")
    empty_v, empty_t = np.zeros((0, 3)), np.zeros((0, 4), dtype=np.int64)
    for call in (pdd.mesh_contacts, pdd.resolve):
        with pytest.raises(ValueError, match=r"TA has no tetrahedra \(shape \(0, 4\)\)"):
            call(empty_v, empty_t)
        with pytest.raises(ValueError, match=r"TA has no tetrahedra"):
            call(VA, empty_t)
        with pytest.raises(ValueError, match=r"TB has no tetrahedra"):
            call(VA, TA, empty_v, empty_t)


@pytest.mark.parametrize("engine", ["fast", "reference"])
def test_flat_and_non_finite_elements_are_skipped(engine):
    """definitions §10: a flat element (zero volume, decided exactly) or one with a non-finite
    coordinate is listed with the library's reason and skipped; the other pairs are computed."""
    V = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4], [1, 1, 0]], dtype=float)
    W = V + 0.5
    W[4] = [np.inf, 0, 0]
    T = np.array([[0, 1, 2, 3], [0, 1, 2, 4]])  # element 1: four points in z = 0
    U = np.array([[0, 1, 2, 3], [0, 1, 2, 4]])
    res = pdd.mesh_contacts(V, T, W, U, engine=engine)
    assert res["skipped"] == [
        ("A", 1, "element 1 of mesh A is flat: its four vertices are coplanar (volume 0)"),
        ("B", 1, "element 1 of mesh B: vertex 3 (mesh vertex 4: VB[4]) coordinate x is not finite (inf)")]
    assert res["a"].tolist() == [0] and res["b"].tolist() == [0]
    assert res["pdd2"][0] == pdd.solve(V[:4], W[:4], engine=engine)["pdd2"]


def test_non_finite_vertex_named_by_array_and_row():
    """Every mesh call names a non-finite vertex by the argument and row it came from (the files
    read by `pdd mesh` name the node tag and line instead): mesh_contacts, resolve,
    contact_energy."""
    V = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4], [1, 1, 1]], dtype=float)
    T = np.array([[0, 1, 2, 3], [0, 1, 2, 4]])
    W = V + 0.5
    W[4] = [np.nan, 0, 0]
    reason = "element 1 of mesh B: vertex 3 (mesh vertex 4: {}) coordinate x is not finite (nan)"
    assert pdd.mesh_contacts(V, T, W, T)["skipped"] == [("B", 1, reason.format("VB[4]"))]
    assert pdd.mesh_contacts(W, T)["skipped"] == [("A", 1, reason.format("VA[4]").replace("mesh B", "mesh A"))]
    _, _, report = pdd.resolve(V, T, W, T, max_rounds=1)
    assert report["skipped"] == [{"mesh": "B", "index": 1, "reason": reason.format("VB[4]")}]
    assert pdd.contact_energy(V, T, W, T)["skipped"] == [("B", 1, reason.format("VB[4]"))]
    U = V.copy()
    U[0, 2] = np.inf  # row 0 of A, used by both elements
    skipped = pdd.mesh_contacts(U, T, W, T)["skipped"]
    assert skipped[0] == ("A", 0, "element 0 of mesh A: vertex 0 (mesh vertex 0: VA[0]) coordinate z is not finite (inf)")


def test_skipped_elements_are_the_cli_messages(pdd_cli, tmp_path):
    """fixtures/meshes/bad/flat.msh and nan.msh: the reasons `pdd mesh` prints after
    "pdd mesh: skipped " (it exits 1 for them), in the same order; a non-finite vertex is named
    where each caller sees it: the file's node tag and line by `pdd mesh`, the array and row by
    the module."""
    def vertex_source(reason):
        m = re.search(r"\(mesh vertex \d+: ([^)]*)\)", reason)
        return m and m.group(1)

    def without_source(reason):
        return re.sub(r"\(mesh vertex (\d+): [^)]*\)", r"(mesh vertex \1)", reason)

    for name in ("flat.msh", "nan.msh"):
        V, T = pdd.read_mesh(MESHES / "bad" / name)
        res = pdd.mesh_contacts(V, T, V, T)
        run = subprocess.run([pdd_cli, "mesh", "--a", str(MESHES / "bad" / name), "--b",
                              str(MESHES / "bad" / name), "--quiet", "--output", str(tmp_path / "o")],
                             capture_output=True, text=True)
        assert run.returncode == 1
        said = [l[len("pdd mesh: skipped "):] for l in run.stderr.splitlines()
                if l.startswith("pdd mesh: skipped ")]
        assert said and [without_source(s[2]) for s in res["skipped"]] == [without_source(w) for w in said], name
        if name == "nan.msh":  # node 4 (line 9) is mesh vertex 3, the NaN row of the arrays
            path = str(MESHES / "bad" / name)
            assert [vertex_source(w) for w in said] == [f"node 4 at {path}:9", None, f"node 4 at {path}:9", None]
            assert [vertex_source(s[2]) for s in res["skipped"]] == ["VA[3]", None, "VB[3]", None]
        assert [s[:2] for s in res["skipped"]] == [(w[w.index("mesh ") + 5], int(w.split()[1])) for w in said]


@pytest.mark.parametrize("args, kw, message", [
    (("V", "T"), dict(variants="pd"),
     r"^variants: unknown variant 'pd' \(rigid, eq11, static, pdd2, relaxed, accel1, accel6, global, all\)$"),
    (("V", "T"), dict(variants=""), "^variants: no variant named$"),
    (("V", "T"), dict(variants=3), "^variants must be a str; got 3$"),
    (("V", "T"), dict(engine="exact"), "^engine must be 'fast' or 'reference'; got 'exact'$"),
    (("V", "T"), dict(threads=-1),
     r"^threads must be 0 \(all cores\) or an int from 1 to 4096, or None; got -1$"),
    (("V", "T"), dict(threads=4097), "^threads must be 0 .all cores. or an int from 1 to 4096, or None; got 4097$"),
    (("V", "T"), dict(threads=1.5), "^threads must be 0 .all cores. or an int from 1 to 4096, or None; got 1.5$"),
    (("V", "T", "V"), {}, r"^give both VB and TB \(contacts of A with B\), or neither"),
    (("V", "T", None, "T"), {}, r"^give both VB and TB"),
    (("V2", "T"), {}, r"^VA must have shape \(n, 3\); got \(14, 2\)$"),
    (("Vflat", "T"), {}, r"^VA must have shape \(n, 3\); got \(42,\)$"),
    (("V", "T3"), {}, r"^TA must have shape \(m, 4\); got \(24, 3\)$"),
    (("V", "T", "V", "T.T"), {}, r"^TB must have shape \(m, 4\); got \(4, 24\)$"),
    (("V", "Tf"), {}, r"^TA must be an array of integers \(vertex indices\) of shape \(m, 4\); got dtype float64$"),
    (("Vs", "T"), {}, r"^VA must be an array of real numbers of shape \(n, 3\); got dtype <U3$"),
    (("Vc", "T"), {}, r"^VA must be an array of real numbers of shape \(n, 3\); got dtype complex128$"),
    # out of range: the library's message (mesh.h, contacts.cpp check_indices); negative: the same words
    (("V", "Tbig"), {}, r"^element 5 of mesh A refers to vertex 14, but the mesh has 14 vertices$"),
    (("V", "T", "V", "Tneg"), {}, r"^element 23 of mesh B refers to vertex -1, but the mesh has 14 vertices$"),
])
def test_bad_input_raises_value_error(args, kw, message):
    V, T = mesh("tiny-a.msh")
    Tbig = T.copy()
    Tbig[5, 2] = 14
    Tneg = T.copy()
    Tneg[23, 3] = -1
    env = {"V": V, "T": T, "V2": V[:, :2], "Vflat": V.ravel(), "T3": T[:, :3], "T.T": T.T,
           "Tf": T.astype(float), "Vs": V.astype(str).astype("<U3"), "Vc": V.astype(complex),
           "Tbig": Tbig, "Tneg": Tneg, None: None}
    with pytest.raises(ValueError, match=message):
        pdd.mesh_contacts(*[env[x] for x in args], **kw)


def test_read_mesh_gives_the_library_mesh():
    """The six encodings of ball A: the same tetrahedra; coordinates equal within each group
    (Gmsh writes ASCII ones with 16 significant digits, which do not round-trip every double,
    binary ones exactly — as tests/mesh/test_mesh.cpp says) and within 1e-15 (coordinates
    of size <= 1, one unit in the 16th digit) across groups."""
    V, T = pdd.read_mesh(MESHES / "sphere-a.msh")
    assert V.dtype == np.float64 and V.shape == (258, 3) and T.dtype == np.int64 and T.shape == (898, 4)
    assert T.min() == 0 and T.max() == len(V) - 1  # other elements (triangles, lines) ignored
    Vb, Tb = pdd.read_mesh(MESHES / "sphere-a.bin41.msh")
    assert (Tb == T).all() and np.abs(Vb - V).max() <= 1e-15 and (Vb != V).any()
    for other, (X, Y) in (("sphere-a.v22.msh", (V, T)), ("sphere-a.vtk", (V, T)),
                          ("sphere-a.bin22.msh", (Vb, Tb)), ("sphere-a.bin.vtk", (Vb, Tb))):
        W, U = pdd.read_mesh(str(MESHES / other))  # str or PathLike
        assert (bits(W) == bits(X)).all() and (U == Y).all(), other


def test_read_mesh_errors_are_the_cli_messages(pdd_cli, tmp_path):
    """Every file of fixtures/meshes/bad that cannot be read: ValueError with the message
    `pdd mesh` prints after "pdd mesh: " (exit 2)."""
    unreadable = 0
    for path in sorted((MESHES / "bad").iterdir()):
        if path.suffix not in (".msh", ".vtk"):
            continue
        run = subprocess.run([pdd_cli, "mesh", "--a", str(path), "--self", "--quiet",
                              "--output", str(tmp_path / "o")], capture_output=True, text=True)
        if run.returncode != 2:  # flat.msh, nan.msh: read, elements skipped
            pdd.read_mesh(path)
            continue
        unreadable += 1
        with pytest.raises(ValueError) as e:
            pdd.read_mesh(path)
        assert "pdd mesh: " + str(e.value) == run.stderr.splitlines()[-1], path.name
    assert unreadable == 7
    with pytest.raises(ValueError, match="cannot open|No such file"):
        pdd.read_mesh(tmp_path / "missing.msh")
    with pytest.raises(ValueError, match="^path must be a str, bytes or os.PathLike; got 3$"):
        pdd.read_mesh(3)


@pytest.mark.parametrize("engine", ["fast", "reference"])
def test_mesh_contacts_releases_the_gil(engine):
    """One call (see test_batch.python_work_during: between calls a thread that holds the GIL
    in C++ lets others run, so only a single call tells)."""
    from test_batch import python_work_during
    if engine == "fast":
        # torus against ten coincident copies of the box: 27120 pairs, every value, about 0.45 s
        # on two cores of an EPYC (one copy, 2712 pairs, took about 50 ms: as long as
        # python_work_during's start-up wait, so the test failed at random)
        V, T = mesh("box.vtk")
        VB = np.vstack([V] * 10)
        TB = np.vstack([T + k * len(V) for k in range(10)])
        args = mesh("torus.msh") + (VB, TB)
    else:  # 6 exact pairs, about 0.1 s each
        V, T = mesh("tiny-a.msh")
        args = (V, T[:3]) + mesh("tiny-b.msh")
    assert python_work_during(lambda: pdd.mesh_contacts(*args, variants="all", engine=engine)) > 1000


def test_docstrings_read_like_the_readme():
    import inspect
    import pydoc
    sig = inspect.signature(pdd.mesh_contacts).parameters
    assert list(sig) == ["VA", "TA", "VB", "TB", "variants", "engine", "threads", "progress"]
    assert sig["VB"].default is None and sig["variants"].default == "rigid,static,pdd2,accel1"
    assert sig["engine"].default == "fast" and sig["threads"].default is None
    assert sig["progress"].default is None
    text = pydoc.render_doc(pdd.mesh_contacts, renderer=pydoc.plaintext)
    for words in ("mesh_contacts(VA, TA, VB=None, TB=None, variants='rigid,static,pdd2,accel1', "
                  "engine='fast', threads=None, progress=None)", "self-contact", "skipped",
                  "fractions.Fraction", "sorted", "q1_A", "ValueError", "GIL", "definitions.md §10", "read_mesh",
                  "meshio", "progress(done, total)", "tqdm", "Ctrl-C", "KeyboardInterrupt"):
        assert words in text, words
    text = pydoc.render_doc(pdd.read_mesh, renderer=pydoc.plaintext)
    for words in ("read_mesh(path)", "(n, 3) float64", "(m, 4) int64", "ValueError", ".msh", ".vtk"):
        assert words in text, words
    assert "mesh_contacts" in pdd.__doc__ and "read_mesh" in pdd.__doc__


# --- Debian's python3-meshio: the same arrays, the same contacts --------------------------------

def meshio_arrays(path):
    meshio = pytest.importorskip("meshio", reason="meshio not importable (Debian python3-meshio)")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # meshio warns about Gmsh physical tags it does not map
        m = meshio.read(path)
    return m.points, m.cells_dict["tetra"]


# Every shipped mesh: meshio 7.0 (Debian 12) reads all of them (Gmsh 2.2 and 4.1, ASCII and
# binary; legacy VTK, ASCII and BINARY) and gives our arrays: vertices in file order, bit for
# bit, and tetrahedra in file order with the same 0-based indices.
@pytest.mark.parametrize("name", sorted(p.name for p in MESHES.iterdir() if p.suffix in (".msh", ".vtk")))
def test_meshio_reads_the_same_mesh(name):
    P, C = meshio_arrays(MESHES / name)
    V, T = pdd.read_mesh(MESHES / name)
    assert P.shape == V.shape and (bits(P) == bits(V)).all()
    assert C.shape == T.shape and (C == T).all()


@pytest.mark.parametrize("a, b", [("sphere-a.msh", "sphere-b.msh"), ("sphere-a.bin.vtk", "sphere-b.msh"),
                                  ("sphere-a.bin41.msh", "sphere-b.msh"), ("torus.msh", "box.vtk"),
                                  ("two-spheres.msh", None)])
def test_meshio_arrays_give_the_same_contacts(a, b):
    P, C = meshio_arrays(MESHES / a)
    args = (P, C) if b is None else (P, C) + meshio_arrays(MESHES / b)
    res = pdd.mesh_contacts(*args, variants="all")
    ref = contacts_of(a, b, variants="all")
    assert len(res["a"]) > 0
    for k in ("a", "b") + VALUE_KEYS + ("q1_A", "q1_B"):
        assert (bits(res[k]) == bits(ref[k])).all(), k
    for k in LABEL_KEYS:
        assert (res[k] == ref[k]).all(), k


def test_meshio_does_not_check_indices_mesh_contacts_does():
    """meshio reads fixtures/meshes/bad/bad-index.vtk (cell 1 refers to point 9 of 4) without a
    word; pdd.read_mesh refuses it, and mesh_contacts refuses meshio's arrays with the
    library's message. (meshio fails on the other unreadable files with numpy errors —
    reshape, index — rather than a message naming the line: use pdd.read_mesh for those.)"""
    P, C = meshio_arrays(MESHES / "bad" / "bad-index.vtk")
    assert C.max() == 9 and len(P) == 4
    with pytest.raises(ValueError, match="bad-index.vtk"):
        pdd.read_mesh(MESHES / "bad" / "bad-index.vtk")
    with pytest.raises(ValueError, match="^element 1 of mesh A refers to vertex 9, but the mesh has 4 vertices$"):
        pdd.mesh_contacts(P, C)


@pytest.mark.parametrize("ext", ["vtu", "inp", "mesh", "node"])
def test_meshio_serves_formats_read_mesh_does_not(tmp_path, ext):
    """VTK XML (.vtu), Abaqus (.inp), Medit (.mesh), TetGen (.node/.ele): pdd.read_mesh refuses
    them (it reads .msh and legacy .vtk only); meshio writes and reads them, and its arrays give
    the contacts of the original mesh, bit for bit (these writers keep every double: ball A's
    binary file holds coordinates that 16 significant digits do not round-trip)."""
    meshio = pytest.importorskip("meshio", reason="meshio not importable (Debian python3-meshio)")
    V, T = mesh("sphere-a.bin41.msh")
    path = tmp_path / f"sphere-a.{ext}"
    meshio.write(path, meshio.Mesh(V, [("tetra", T)]))
    with pytest.raises(ValueError, match="neither a Gmsh mesh"):
        pdd.read_mesh(path)
    P, C = meshio_arrays(path)
    assert (bits(P) == bits(V)).all() and (C == T).all()
    res = pdd.mesh_contacts(P, C, *mesh("sphere-b.msh"), variants="all")
    ref = contacts_of("sphere-a.bin41.msh", "sphere-b.msh", variants="all")
    assert len(ref["a"]) > 0
    for k in ("a", "b") + VALUE_KEYS + ("q1_A", "q1_B"):
        assert (bits(res[k]) == bits(ref[k])).all(), k
