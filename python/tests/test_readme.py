"""The README's "Use it from Python" section, run as it is written: each python block is saved
as a script and run by /usr/bin/python3 (the interpreter of this test) from the source tree, with
the module of this build on PYTHONPATH. The printed values are the ones the README shows."""
import os
import re
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR


def readme_python_blocks():
    text = (SOURCE_DIR / "README.md").read_text()
    section = text.split("## Use it from Python", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```python\n(.*?)```", section, re.S)


def run_block(code, tmp_path, name):
    script = tmp_path / name
    script.write_text(code)
    return subprocess.run([sys.executable, str(script)], cwd=SOURCE_DIR, env=os.environ.copy(),
                          capture_output=True, text=True, timeout=600)


def test_readme_has_the_section():
    blocks = readme_python_blocks()
    assert len(blocks) == 3  # pairs, dask, meshes
    assert len(blocks[0].strip().splitlines()) <= 12  # "about ten lines"
    assert len(blocks[2].strip().splitlines()) <= 12


def assert_prints_what_it_shows(code, out):
    """Every `print(...)  # shown` line of the block prints `shown`, in order."""
    assert out.returncode == 0, out.stderr
    shown = re.findall(r"^print\(.*\)\s+# (.*)$", code, re.M)  # the output the README promises
    assert shown
    assert out.stdout.splitlines()[:len(shown)] == shown


def test_readme_first_block(tmp_path):
    code = readme_python_blocks()[0]
    assert_prints_what_it_shows(code, run_block(code, tmp_path, "readme_use.py"))


def test_readme_mesh_block(tmp_path):
    code = readme_python_blocks()[2]
    assert_prints_what_it_shows(code, run_block(code, tmp_path, "readme_mesh.py"))


def test_readme_dask_block(tmp_path):
    pytest.importorskip("distributed", reason="dask.distributed not importable (Debian python3-distributed)")
    out = run_block(readme_python_blocks()[1], tmp_path, "readme_dask.py")
    assert out.returncode == 0, out.stderr
