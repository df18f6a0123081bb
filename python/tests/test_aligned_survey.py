"""scripts/aligned-survey.py: its grids are valid conforming meshes, it runs, and blocks of them
stacked a third of a cell deep resolve by rounds.

The survey's numbers (docs/performance.md, "Where structured grids stand") are only worth what
its meshes are: each decomposition must fill the block exactly with positively oriented
tetrahedra that meet face to face, as a mesh generator's would. Checked here exactly, in the
grid's integer half-cell units (every vertex is h/2 times an integer vector)."""
import os
import subprocess
import sys
from collections import Counter

import numpy as np
import pytest

import pdd
from conftest import SOURCE_DIR, load_script

SCRIPT = SOURCE_DIR / "scripts" / "aligned-survey.py"


@pytest.fixture(scope="module")
def survey():
    return load_script("aligned-survey.py")


# Triangles on the block's boundary: each boundary square of a cube is cut into 2 triangles by
# the Kuhn, mirrored Kuhn and 5-tetrahedra cuts, into 4 (around its centre) by the 24-cut; the
# block of n^3 cubes has 6 n^2 boundary squares.
BOUNDARY_TRIANGLES_PER_SQUARE = {"kuhn": 2, "mirror": 2, "five": 2, "bc24": 4}


@pytest.mark.parametrize("kind", ["kuhn", "mirror", "five", "bc24"])
@pytest.mark.parametrize("n", [2, 3])
def test_grid_fills_the_block_face_to_face(survey, kind, n):
    h = 0.125  # dyadic: V / (h / 2) recovers the integer positions exactly
    V, T = survey.grid(kind, n, h)
    P = [tuple(int(round(c / (h / 2))) for c in v) for v in V]
    assert all(tuple(x * h / 2 for x in P[i]) == tuple(V[i]) for i in range(len(P)))

    def six_volume(t):  # det[b - a, c - a, d - a] over integers: 6 V in half-cell units
        a, b, c, d = (P[i] for i in t)
        u, v, w = ([q[k] - a[k] for k in range(3)] for q in (b, c, d))
        return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                u[2] * (v[0] * w[1] - v[1] * w[0]))

    volumes = [six_volume(t) for t in T]
    assert min(volumes) > 0  # positively oriented, none flat
    assert sum(volumes) == 6 * (2 * n) ** 3  # fills the block (side 2n half-cells) exactly
    faces = Counter(tuple(sorted((t[i], t[j], t[k]))) for t in T for i, j, k in
                    ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)))
    assert max(faces.values()) == 2  # no face shared by three
    once = [f for f, m in faces.items() if m == 1]

    def on_boundary(f):  # all three vertices on one side of the block
        return any(len({P[i][k] for i in f}) == 1 and P[f[0]][k] in (0, 2 * n) for k in range(3))

    assert all(on_boundary(f) for f in once)  # inside, every face is shared: conforming
    assert len(once) == 6 * n * n * BOUNDARY_TRIANGLES_PER_SQUARE[kind]


def test_survey_prints_a_row_per_case():
    env = dict(os.environ)
    r = subprocess.run([sys.executable, str(SCRIPT), "--kinds", "kuhn,bc24", "--cells", "0.125,1/6",
                        "--shifts", "off,diag", "--n", "2", "--repeats", "1"],
                       capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr
    rows = r.stdout.strip().splitlines()[1:]
    assert len(rows) == 2 * 2 * 2
    for row in rows:
        words = row.split()
        assert words[-1].endswith("x") and words[-2].endswith("x"), row
        assert int(words[3]) > 0 and int(words[5]) > 0, row  # intersecting pairs on both sides


@pytest.mark.parametrize("argument, message", [
    (["--variants", "bogus"], "--variants: variants: unknown variant 'bogus'"),
    (["--kinds", "kuhn,hex"], "--kinds: unknown kind 'hex'"),
    (["--cells", "0.1,-1/6"], "--cells: '-1/6' is not a positive number or fraction"),
    (["--shifts", "off,up"], "--shifts: unknown shift 'up'"),
    (["--repeats", "0"], "--n and --repeats: at least 1"),
    (["--energy", "--variants", "rigid"], "--energy: not with --variants"),
    (["--resolve", "--energy"], "--resolve: not with --energy or --variants"),
    (["--resolve", "--variants", "global"], "--resolve: not with --energy or --variants"),
])
def test_survey_names_a_bad_argument_before_any_work(argument, message):
    r = subprocess.run([sys.executable, str(SCRIPT), *argument], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stderr
    assert message in r.stderr and "Traceback" not in r.stderr, r.stderr
    assert r.stdout == ""  # (no header: nothing measured)


def test_survey_passes_its_variants_to_the_call(survey, monkeypatch):
    # --variants reaches pdd.mesh_contacts as given; without it the call keeps its own default
    # (no variants keyword at all)
    seen = []

    def recorder(*args, **kwargs):
        seen.append(kwargs)
        return {"a": [0]}

    monkeypatch.setattr(survey.pdd, "mesh_contacts", recorder)
    survey.best_call(1, "global", False, None, None, None, None)
    survey.best_call(1, None, False, None, None, None, None)
    assert seen == [{"threads": 1, "variants": "global"}, {"threads": 1}]


def run_survey(*arguments):
    """The survey's header line and rows, its exit status 0."""
    r = subprocess.run([sys.executable, str(SCRIPT), *arguments], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    header, *rows = r.stdout.strip().splitlines()
    return header, rows


def test_survey_times_the_energy():
    # --energy: pdd.contact_energy in place of pdd.mesh_contacts, a column of the pairs taken at
    # a bound; the Kuhn grid of cell 0.1 a quarter cell along (1, 1, 1) has contacts made by
    # rounding (faces x = y meeting by rounding), the same on the dyadic cell 1/8 none
    header, rows = run_survey("--energy", "--kinds", "kuhn", "--cells", "0.1,0.125", "--shifts", "q111", "--n", "2",
                              "--repeats", "1")
    assert header.split()[-1] == "bounded" and len(rows) == 2
    bounded = {row.split()[1]: int(row.split()[-1]) for row in rows}
    assert bounded["0.1"] > 0 and bounded["0.125"] == 0, rows


def test_survey_times_resolve():
    # --resolve: pdd.resolve on both sides; a row per case with the rounds, the pair solves (at
    # least the first round's intersecting pairs) and two ratios, nothing left unresolved (a row
    # that is not resolved carries more words)
    header, rows = run_survey("--resolve", "--kinds", "kuhn,five", "--cells", "0.125", "--shifts", "diag", "--n", "2",
                              "--repeats", "1")
    assert header.split()[3:] == ["rounds", "solves", "seconds", "rounds", "solves", "turned", "ratio", "per-solve"]
    assert len(rows) == 2, rows
    for row in rows:
        words = row.split()
        assert len(words) == 11 and words[-1].endswith("x") and words[-2].endswith("x"), row
        rounds_a, solves_a, rounds_t, solves_t = int(words[3]), int(words[4]), int(words[6]), int(words[7])
        assert 1 <= rounds_a <= solves_a and 1 <= rounds_t <= solves_t, row


# Blocks of 3^3 cubes of each cut, B on A's top a third of a cell deep and moved across as a user
# types offsets (the README's limits: 40 runs, 1-32 rounds, none through a fallback). In the
# first round each element pair's cheapest plane points sideways, neighbours opposite ways; the
# rounds push each such contact patch one way (mesh/src/resolve/patch_direction.h); with the
# pairs' own planes alone, 2 of these runs stall and take the translation (168-189 rounds).
@pytest.mark.parametrize("kind", ["kuhn", "mirror", "five", "bc24"])
@pytest.mark.parametrize("fix", ["a", None])
def test_stacked_blocks_resolve_by_rounds(survey, kind, fix):
    VA, T = survey.grid(kind, 3, 1.0)
    for shift in [(0.25, 0.25), (0.5, 0.5), (0.1, 0.1), (0.37, 0.21), (0.0, 0.0)]:
        VB = VA + np.array([shift[0], shift[1], 3 - 1 / 3])
        A1, B1, report = pdd.resolve(VA, T, VB, T, fix=fix)
        where = f"{kind} moved {shift}, fix={fix}"
        assert report["resolved"], where  # the library's exact R1-R4 verdict
        assert report["method"] == "rounds", (where, report["method"], len(report["rounds"]))
        if fix == "a":
            assert (A1 == VA).all(), where
