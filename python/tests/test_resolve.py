"""pdd.resolve and `pdd resolve` (the C++ library's pdd::mesh::resolve, include/pdd/mesh.h) on the
shipped meshes (fixtures/meshes): the two tiny cubes (51 intersecting pairs), ball B moved into a
shallow overlap with ball A (0.08 deep), the cubes as one mesh (self-contact), and the shipped
balls (0.73 deep, about 2.4 element layers), which one round cannot resolve:
  - a resolved result satisfies R1-R3, checked again here independently: pdd.mesh_contacts on
    the new positions finds no intersecting pair, every element keeps the sign of its volume,
    fixed vertices (fix="a", or boolean masks) are bit-for-bit unchanged;
  - the report has the keys of the CLI's JSON report, in its order, and Python and the CLI give
    the same positions bit for bit (one thread on both sides);
  - the CLI's .msh and .vtk outputs are read by Debian's python3-meshio (and by pdd.read_mesh)
    as the same arrays, bit for bit, with the input's connectivity;
  - progress, bad arguments (ValueError naming them), SIGINT / SIGTERM on the CLI (130 / 143,
    nothing written)."""
import json
import signal
import subprocess
import time
import warnings

import numpy as np
import pytest

import pdd
from conftest import FIXTURES

MESHES = FIXTURES / "meshes"
REPORT_KEYS = ["variant", "method", "stopped_because", "inputs", "resolved", "r1", "r2", "r3", "r4", "rounds", "cost",
               "cost_a", "cost_b", "max_displacement", "min_volume_ratio", "max_volume_ratio",
               "min_shape_ratio", "volume_ratio_histogram", "shape_ratio_histogram", "worst_elements",
               "remaining_pairs", "bad_elements", "poor_elements", "moved_fixed_vertices", "skipped",
               "seconds_contacts", "seconds_solve", "seconds_move", "seconds_verify", "seconds_total"]
# Added by the module to the JSON report's keys: per-element ratios as numpy arrays.
ARRAY_KEYS = ["volume_ratio_a", "shape_ratio_a", "volume_ratio_b", "shape_ratio_b"]
ROUND_KEYS = ["round", "pairs", "max_pd2", "cost", "seconds"]


def bits(x):
    return np.asarray(x, dtype=np.float64).view(np.int64)


def load(name):
    return pdd.read_mesh(MESHES / name)


def signed_volumes(V, T):
    """6 x the signed volume of every tetrahedron (floats: only their signs are used, on
    elements far from flat: the check of R2 proper is the library's exact one)."""
    p = V[T]
    return np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]))


def assert_resolved(V0, T, V1, W0=None, TB=None, W1=None):
    """R1 again through the contacts pipeline, R2 by float volume signs."""
    c = pdd.mesh_contacts(V1, T, variants="rigid") if W1 is None else \
        pdd.mesh_contacts(V1, T, W1, TB, variants="rigid")
    assert len(c["a"]) == 0, list(zip(c["a"][:5], c["b"][:5]))
    assert (np.sign(signed_volumes(V1, T)) == np.sign(signed_volumes(V0, T))).all()
    if W1 is not None:
        assert (np.sign(signed_volumes(W1, TB)) == np.sign(signed_volumes(W0, TB))).all()


def shallow_balls():
    """Ball B (radius 0.9, centre (1.1, 0.35, 0.2)) moved along the centres' line until the
    centres are 1.82 apart: 0.08 deep into ball A (radius 1, at the origin)."""
    VA, TA = load("sphere-a.msh")
    VB, TB = load("sphere-b.msh")
    c = np.array([1.1, 0.35, 0.2])
    return VA, TA, VB + c * (1.82 / np.linalg.norm(c) - 1), TB


def tiny_as_one_mesh():
    """The two tiny cubes as one mesh of two components (A's vertices, then B's)."""
    VA, TA = load("tiny-a.msh")
    VB, TB = load("tiny-b.msh")
    return np.vstack([VA, VB]), np.vstack([TA, TB + len(VA)])


def test_pair_with_a_fixed():
    VA, TA, VB, TB = shallow_balls()
    VA1, VB1, r = pdd.resolve(VA, TA, VB, TB, fix="a")
    assert list(r) == REPORT_KEYS + ARRAY_KEYS
    assert r["resolved"] and r["r1"] and r["r2"] and r["r3"] and r["r4"]
    assert r["poor_elements"] == []
    for m, T in (("a", TA), ("b", TB)):  # R4 per element: V1/V0 in [1/4, 4], eta1/eta0 >= 1/2
        vr, sr = r["volume_ratio_" + m], r["shape_ratio_" + m]
        assert vr.dtype == np.float64 and vr.shape == (len(T),) and sr.shape == (len(T),)
        assert (vr >= 0.25).all() and (vr <= 4).all() and (sr >= 0.5).all()
    assert r["min_volume_ratio"] == min(r["volume_ratio_a"].min(), r["volume_ratio_b"].min())
    assert r["remaining_pairs"] == [] and r["bad_elements"] == [] and r["moved_fixed_vertices"] == []
    assert (bits(VA1) == bits(VA)).all()  # R3: A bit for bit
    assert not (bits(VB1) == bits(VB)).all()
    assert_resolved(VA, TA, VA1, VB, TB, VB1)
    assert r["inputs"] == {"self": False, "fix": "a", "max_rounds": 200, "min_volume_ratio": 0.25,
                           "min_shape_ratio": 0.5, "elements_a": len(TA),
                           "vertices_a": len(VA), "elements_b": len(TB), "vertices_b": len(VB),
                           "fixed_vertices_a": len(VA), "fixed_vertices_b": 0}
    assert r["variant"] == "global" and r["cost_a"] == 0 and r["cost"] == r["cost_b"] > 0
    assert len(r["rounds"]) >= 1 and all(list(k) == ROUND_KEYS for k in r["rounds"])
    assert [k["round"] for k in r["rounds"]] == list(range(1, len(r["rounds"]) + 1))
    assert r["rounds"][0]["pairs"] > 0 and r["max_displacement"] > 0
    assert 0 < r["min_volume_ratio"]


@pytest.mark.parametrize("exponent", [-400, -300, 300, 400])
def test_a_mesh_scaled_by_a_power_of_two_resolves_as_at_its_own_scale(exponent):
    """Resolving is covariant under scaling by 2^e: every value it computes on coordinates
    scaled by a power of two (per-pair depths, the elastic step's solve, the step limit's ratios,
    the cost) is the unscaled one's scaled, bit for bit, while nothing leaves the double range
    (the library scales its sums so that nothing does: at 2^-300 the elastic step's squared norms,
    ~L^4, and the cost's V sigma, ~L^5, would underflow; at 2^300 overflow). So the run takes the
    same rounds and writes the same positions times 2^e, the cost times 2^(2e); at 2^+-400 the
    elements' volumes (~L^3) themselves would leave the range, which the step limit's ratios and
    the volume weights (variant rigid) are scaled for."""
    VA, TA, VB, TB = shallow_balls()
    s = 2.0 ** exponent
    VA1, VB1, r = pdd.resolve(VA, TA, VB, TB, fix="a", threads=1)
    WA1, WB1, q = pdd.resolve(VA * s, TA, VB * s, TB, fix="a", threads=1)
    for variant in ("rigid", "pdd2"):
        _, XB1, _ = pdd.resolve(VA, TA, VB, TB, fix="a", variant=variant, threads=1)
        _, YB1, _ = pdd.resolve(VA * s, TA, VB * s, TB, fix="a", variant=variant, threads=1)
        assert (bits(YB1) == bits(XB1 * s)).all(), variant
    assert r["resolved"] and q["resolved"] and q["method"] == r["method"] == "rounds"
    assert [k["pairs"] for k in q["rounds"]] == [k["pairs"] for k in r["rounds"]]
    assert [k["max_pd2"] for k in q["rounds"]] == [k["max_pd2"] * s * s for k in r["rounds"]]
    assert (bits(WA1) == bits(VA1 * s)).all() and (bits(WB1) == bits(VB1 * s)).all()
    assert q["cost"] == r["cost"] * s * s > 0 and q["max_displacement"] == r["max_displacement"] * s
    assert q["min_volume_ratio"] == r["min_volume_ratio"]


def test_self_contact():
    V, T = tiny_as_one_mesh()
    assert len(pdd.mesh_contacts(V, T, variants="rigid")["a"]) > 0
    V1, none, r = pdd.resolve(V, T)
    assert none is None and r["resolved"] and r["inputs"]["self"] and r["cost_b"] == 0
    assert_resolved(V, T, V1)


def test_fixed_vertex_masks_are_kept_bit_for_bit():
    VA, TA = load("tiny-a.msh")
    VB, TB = load("tiny-b.msh")
    fixed_a = np.zeros(len(VA), dtype=bool)
    fixed_a[::2] = True
    fixed_b = np.zeros(len(VB), dtype=bool)
    fixed_b[1::3] = True
    VA1, VB1, r = pdd.resolve(VA, TA, VB, TB, fixed_a=fixed_a, fixed_b=fixed_b)
    assert r["r3"] and r["inputs"]["fixed_vertices_a"] == fixed_a.sum()
    assert r["inputs"]["fixed_vertices_b"] == fixed_b.sum()
    assert (bits(VA1[fixed_a]) == bits(VA[fixed_a])).all()
    assert (bits(VB1[fixed_b]) == bits(VB[fixed_b])).all()
    if r["resolved"]:
        assert_resolved(VA, TA, VA1, VB, TB, VB1)


def test_separated_meshes_do_not_move():
    VA, TA = load("conforming-a.msh")
    VB, TB = load("conforming-b.msh")
    VA1, VB1, r = pdd.resolve(VA, TA, VB, TB)
    assert r["resolved"] and r["rounds"] == [] and r["cost"] == 0
    assert (bits(VA1) == bits(VA)).all() and (bits(VB1) == bits(VB)).all()


def test_unresolved_run_says_what_remains():
    VA, TA = load("sphere-a.msh")
    VB, TB = load("sphere-b.msh")
    VA1, VB1, r = pdd.resolve(VA, TA, VB, TB, max_rounds=1)
    assert not r["resolved"] and len(r["rounds"]) == 1
    assert r["remaining_pairs"] or r["bad_elements"]
    assert not r["r1"] or not r["r2"]


def test_progress_callable():
    VA, TA = load("tiny-a.msh")
    VB, TB = load("tiny-b.msh")
    calls = []
    _, _, r = pdd.resolve(VA, TA, VB, TB, fix="a", progress=lambda done, total: calls.append((done, total)))
    n = len(r["rounds"])
    assert calls and calls[-1] == (n, n)
    assert all(t == 200 for _, t in calls[:-1]) and [d for d, _ in calls] == sorted(d for d, _ in calls)


def test_progress_bar_counts_rounds_and_ends_with_what_remains(capsys):
    """progress=True: a tqdm counter of rounds (max_rounds is only a limit: no bar of length 200
    that jumps to the rounds run), whose last postfix is the pairs that still intersect at the
    end (0 when resolved), not those the last round started from."""
    pytest.importorskip("tqdm")
    VA, TA = load("tiny-a.msh")
    VB, TB = load("tiny-b.msh")
    _, _, r = pdd.resolve(VA, TA, VB, TB, fix="a", progress=True)
    assert r["resolved"]
    err = capsys.readouterr().err
    last = err.replace("\r", "\n").strip().splitlines()[-1]
    n = len(r["rounds"])
    assert last.startswith(f"pdd.resolve: {n}round [") and "/200" not in err, err
    assert last.endswith("pairs=0]"), err


def test_cli_and_python_give_the_same_positions(pdd_cli, tmp_path):
    """One thread on both sides; the CLI's files read back bit for bit, its report has the same
    keys plus the file names."""
    a, b = MESHES / "tiny-a.msh", MESHES / "tiny-b.msh"
    out = subprocess.run([pdd_cli, "resolve", "--a", str(a), "--b", str(b), "--threads", "1",
                          "--out-a", str(tmp_path / "a1.msh"), "--out-b", str(tmp_path / "b1.vtk"),
                          "--report", str(tmp_path / "r.json"), "--quiet"],
                         capture_output=True, text=True, timeout=1200)
    VA, TA = load("tiny-a.msh")
    VB, TB = load("tiny-b.msh")
    VA1, VB1, r = pdd.resolve(VA, TA, VB, TB, threads=1)
    assert out.returncode == (0 if r["resolved"] else 1), out.stderr
    cli = json.loads((tmp_path / "r.json").read_text())
    assert list(cli) == REPORT_KEYS
    assert list(r) == REPORT_KEYS + ARRAY_KEYS
    assert cli["inputs"].pop("a") == str(a) and cli["inputs"].pop("b") == str(b)
    assert cli["inputs"] == r["inputs"]
    for k in ("method", "resolved", "r1", "r2", "r3", "r4", "cost", "cost_a", "cost_b", "max_displacement",
              "min_volume_ratio", "max_volume_ratio", "min_shape_ratio", "volume_ratio_histogram",
              "shape_ratio_histogram", "worst_elements", "remaining_pairs", "bad_elements",
              "poor_elements", "moved_fixed_vertices"):
        assert cli[k] == r[k], k
    assert [{k: v for k, v in x.items() if k != "seconds"} for x in cli["rounds"]] == \
           [{k: v for k, v in x.items() if k != "seconds"} for x in r["rounds"]]
    for path, V1, T in ((tmp_path / "a1.msh", VA1, TA), (tmp_path / "b1.vtk", VB1, TB)):
        V, TT = pdd.read_mesh(path)
        assert (bits(V) == bits(V1)).all() and (TT == T).all()


def meshio_read(path):
    meshio = pytest.importorskip("meshio", reason="meshio not importable (Debian python3-meshio)")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = meshio.read(path)
    return m.points, m.cells_dict["tetra"]


@pytest.mark.parametrize("ext_a, ext_b", [(".msh", ".vtk"), (".vtk", ".msh")])
def test_meshio_reads_the_written_meshes(pdd_cli, tmp_path, ext_a, ext_b):
    out_a, out_b, both = tmp_path / ("a1" + ext_a), tmp_path / ("b1" + ext_b), tmp_path / "both.vtk"
    run = subprocess.run([pdd_cli, "resolve", "--a", str(MESHES / "tiny-a.msh"), "--b",
                          str(MESHES / "tiny-b.msh"), "--fix", "a", "--out-a", str(out_a), "--out-b", str(out_b),
                          "--vtk", str(both), "--quiet"], capture_output=True, text=True, timeout=1200)
    assert run.returncode == 0, run.stderr
    for path, name in ((out_a, "tiny-a.msh"), (out_b, "tiny-b.msh")):
        P, C = meshio_read(path)
        V, T = pdd.read_mesh(path)
        V0, T0 = load(name)
        assert (bits(P) == bits(V)).all() and (C == T0).all() and (T == T0).all()
        assert len(V) == len(V0)
        if name == "tiny-a.msh":  # fixed: A bit for bit
            assert (bits(P) == bits(V0)).all()
    P, C = meshio_read(both)
    VA1, _ = pdd.read_mesh(out_a)
    VB1, _ = pdd.read_mesh(out_b)
    assert (bits(P) == bits(np.vstack([VA1, VB1]))).all()
    meshio = pytest.importorskip("meshio")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = meshio.read(both)
    VA0, _ = load("tiny-a.msh")
    VB0, _ = load("tiny-b.msh")
    assert np.array_equal(m.point_data["displacement"], np.vstack([VA1 - VA0, VB1 - VB0]))


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_cli_interrupted_writes_nothing(pdd_cli, tmp_path, sig, code):
    """The shipped balls with a large round limit run long (they stall: see
    test_unresolved_run_says_what_remains); a signal after the first round stops the run after
    its current stage: exit 128 + signal, no output, no temporary file."""
    proc = subprocess.Popen([pdd_cli, "resolve", "--a", str(MESHES / "sphere-a.msh"), "--b",
                             str(MESHES / "sphere-b.msh"), "--max-rounds", "100000",
                             "--out-a", str(tmp_path / "a1.msh"), "--out-b", str(tmp_path / "b1.msh"),
                             "--report", str(tmp_path / "r.json")],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        err = ""
        start = time.monotonic()
        while "round 1:" not in err and time.monotonic() - start < 300:
            line = proc.stderr.readline()
            if not line:
                pytest.fail("the run ended before its first round: " + err)
            err += line
        proc.send_signal(sig)
        assert proc.wait(timeout=120) == code
        err += proc.stderr.read()
        assert "nothing written" in err
        assert list(tmp_path.iterdir()) == []
    finally:
        if proc.poll() is None:
            proc.kill()


@pytest.mark.parametrize("kwargs, message", [
    ({"fix": "c"}, "fix must be None, 'a' or 'b'"),
    ({"fix": "b", "self": True}, "fix='b': with self-contact"),
    ({"fixed_b": np.zeros(3, dtype=bool), "self": True}, "fixed_b: with self-contact"),
    ({"fixed_a": np.zeros(3, dtype=bool)}, r"fixed_a must be a boolean array of shape \(\d+,\)"),
    ({"fixed_a": "all"}, "fixed_a must be a boolean array"),
    ({"variant": "bogus"}, "variant: .*bogus"),
    ({"max_rounds": 0}, "max_rounds must be an int from 1"),
    ({"max_rounds": True}, "max_rounds must be an int"),
    ({"threads": -1}, "threads must be"),
    ({"progress": 3}, "progress must be"),
    ({"min_volume_ratio": 0}, r"min_volume_ratio must be a real number in \(0, 1\]; got 0"),
    ({"min_volume_ratio": True}, "min_volume_ratio must be a real number"),
    ({"min_shape_ratio": 1.5}, r"min_shape_ratio must be a real number in \(0, 1\]; got 1.5"),
    ({"min_shape_ratio": float("nan")}, "min_shape_ratio must be a real number"),
    ({"min_shape_ratio": "half"}, "min_shape_ratio must be a real number"),
])
def test_bad_arguments(kwargs, message):
    VA, TA = load("tiny-a.msh")
    VB, TB = load("tiny-b.msh")
    if kwargs.pop("self", False):
        VB = TB = None
    with pytest.raises(ValueError, match=message):
        pdd.resolve(VA, TA, VB, TB, **kwargs)
    with pytest.raises(ValueError, match="give both VB and TB"):
        pdd.resolve(VA, TA, VB=VA)


def test_docstring():
    import inspect
    import pydoc
    sig = inspect.signature(pdd.resolve).parameters
    assert list(sig) == ["VA", "TA", "VB", "TB", "fix", "variant", "max_rounds", "threads", "progress",
                         "fixed_a", "fixed_b", "min_volume_ratio", "min_shape_ratio"]
    assert sig["variant"].default == "global" and sig["max_rounds"].default == 200
    text = pydoc.render_doc(pdd.resolve, renderer=pydoc.plaintext)
    for words in ("R1", "R2", "R3", "R4", "min_volume_ratio", "min_shape_ratio", "bit for bit", "fix", "fixed_a", "variant", "max_rounds",
                  "progress(done, total)", "tqdm", "Ctrl-C", "KeyboardInterrupt", "ValueError",
                  "GIL", "report", "remaining_pairs", "pdd resolve", "meshio"):
        assert words in text, words
    assert "resolve(" in pdd.__doc__


def test_ctrl_c_stops_resolve():
    """A real SIGINT to a child interpreter one second into a long run: KeyboardInterrupt out of
    the call within test_long_calls.PROMPT seconds (the solver checks the cancel flag between
    rounds and between their stages). The run: three copies of the shipped ball (radius 1) in ONE
    mesh, centred at the corners of a triangle of side 1.4 (every two overlap by 0.6), one vertex
    of each fixed: the rounds do not resolve it, the three bodies cannot be split into two meshes
    and their spread declines (a cluster with fixed vertices in two bodies), so max_rounds=100000
    keeps the self-contact rounds going far past the signal (measured: 300 rounds in 2.8 s, none
    resolved)."""
    from test_long_calls import assert_keyboard_interrupt, interrupt
    delay, status, err = interrupt(f"""
        VA, TA = pdd.read_mesh({str(MESHES / "sphere-a.msh")!r})
        corners = [(0, 0, 0), (1.4, 0, 0), (0.7, 0.7 * 3 ** 0.5, 0)]
        V = np.vstack([VA + np.array(c) for c in corners])
        T = np.vstack([TA + k * len(VA) for k in range(3)])
        fixed = np.zeros(len(V), dtype=bool)
        fixed[[TA[0, 0] + k * len(VA) for k in range(3)]] = True
        """,
        "pdd.resolve(V, T, max_rounds=100000, threads=2, fixed_a=fixed)")
    assert_keyboard_interrupt(delay, status, err)


def test_an_exception_from_progress_stops_resolve():
    VA, TA = load("sphere-a.msh")
    VB, TB = load("sphere-b.msh")
    calls = []

    def progress(done, total):
        calls.append((done, total))
        if done >= 1:
            raise KeyError("stop")
    # A fixed: the deep balls take the translation fallback, ~190 rounds (~0.3 s), so the
    # progress callback is called while the rounds run, not only at the end.
    with pytest.raises(KeyError, match="stop"):
        pdd.resolve(VA, TA, VB, TB, fix="a", max_rounds=100000, progress=progress)
    assert calls[-1][0] >= 1 and all(t == 100000 for _, t in calls)
