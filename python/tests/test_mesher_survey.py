"""scripts/mesher-survey.py: the premise it measures (Gmsh's transfinite box places its nodes a
few ulps off the grid), its own prism grid tiles the box, and it prints a row per case."""
import shutil
import subprocess
import sys

import numpy as np
import pytest

from conftest import SOURCE_DIR, load_script

SCRIPT = SOURCE_DIR / "scripts" / "mesher-survey.py"
needs_meshers = pytest.mark.skipif(not (shutil.which("gmsh") and shutil.which("tetgen")),
                                   reason="gmsh and tetgen (Debian packages) are not on PATH")


@pytest.fixture(scope="module")
def survey():
    return load_script("mesher-survey.py")


@needs_meshers
def test_transfinite_box_nodes_lie_a_few_ulps_off_the_grid(survey, tmp_path):
    V, T = survey.gmsh_box(tmp_path, 10, True)
    assert len(T) == 6000  # 10^3 hexahedra, six tetrahedra each
    grid = np.round(V * 10) / 10  # the nearest grid line, i/10 rounded once
    ulps = np.abs(V - grid) / np.spacing(np.maximum(np.abs(grid), 0.1))
    assert np.count_nonzero(V != grid) > 100  # off the grid: the survey's premise
    assert ulps.max() <= 16  # but only by a rounding (docs/performance.md: within a few ulps)


def test_prism_grid_tiles_the_box(survey):
    V, T = survey.prism_grid(3)
    P = V[T]
    six = np.einsum("ij,ij->i", np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]), P[:, 3] - P[:, 0])
    assert len(T) == 6 * 27 and six.min() > 0  # positively oriented, none flat
    assert abs(six.sum() / 6 - 1) < 1e-12  # volumes sum to the unit box's


@needs_meshers
def test_survey_prints_a_row_per_case():
    r = subprocess.run([sys.executable, str(SCRIPT), "--cells", "3", "--repeats", "1"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.strip().splitlines()
    rows = [line for line in lines[1:] if not line.startswith(("#", "(", " "))]
    assert len(rows) == 4 * 3, r.stdout  # four meshers, three moves each
    for row in rows:
        words = row.split()
        assert words[-1].endswith("x"), row
    assert any(line.startswith("# Gmsh transfinite box") for line in lines), r.stdout


def test_survey_times_resolve():
    # --resolve: pdd.resolve beside the turned copy, a row per move with the rounds, the pair solves
    # (at least one round's intersecting pairs), what produced the result and two ratios; every
    # case resolved (a row that is not carries "not resolved")
    r = subprocess.run([sys.executable, str(SCRIPT), "--resolve", "--kinds", "prism", "--cells", "3", "--repeats", "1"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.strip().splitlines()
    assert lines[0].split()[-2:] == ["ratio", "per-solve"], lines[0]
    rows = [line for line in lines[1:] if line.startswith("prism (162)")]
    assert len(rows) == 3, r.stdout  # three moves
    for row in rows:
        words = row.split()
        assert "not resolved" not in row and words[-1].endswith("x") and words[-2].endswith("x"), row
        rounds, solves = int(words[-10]), int(words[-9])
        assert 1 <= rounds <= solves, row
        assert words[-7] in ("rounds", "translation"), row


@pytest.mark.parametrize("argument, message", [
    (["--kinds", "gmsh,hex"], "unknown kind 'hex'"),
    (["--cells", "1"], "--cells must be at least 2"),
])
def test_survey_refuses_bad_arguments(argument, message):
    r = subprocess.run([sys.executable, str(SCRIPT), *argument], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stderr
    assert message in r.stderr and "Traceback" not in r.stderr, r.stderr
    assert r.stdout == ""
