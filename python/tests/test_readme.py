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


def test_readme_defaults_are_the_programs(pdd_cli):
    """Every "`--flag` (default X" of the README is the default `pdd mesh --help` or `pdd resolve
    --help` prints for that flag, which the CLI takes from the library's options structs
    (ContactOptions, ResolveOptions): the README cannot drift from them."""
    text = (SOURCE_DIR / "README.md").read_text()
    stated = re.findall(r"`(--[\w-]+)`\*?\*?\s+\(default `?([^`;)]+)`?[;)]", text)
    assert {f for f, _ in stated} >= {"--variants", "--max-rounds", "--min-volume-ratio", "--min-shape-ratio"}
    helps = "".join(subprocess.run([pdd_cli, cmd, "--help"], capture_output=True, text=True, check=True).stdout
                    for cmd in ("mesh", "resolve"))
    for flag, value in stated:
        printed = re.findall(rf"^\s*{re.escape(flag)} [^\n=]*=(\S+)", helps, re.M)
        assert printed, f"{flag}: no default in the --help of pdd mesh / pdd resolve"
        assert value.strip() in printed, f"README says {flag} defaults to {value}; --help says {printed}"


def test_python_defaults_are_the_programs(pdd_cli):
    """pdd.resolve and pdd.mesh_contacts take their keyword defaults from the same structs as the
    CLI: each equals the default `pdd resolve --help` / `pdd mesh --help` prints."""
    import inspect
    import pdd
    helps = {cmd: subprocess.run([pdd_cli, cmd, "--help"], capture_output=True, text=True, check=True).stdout
             for cmd in ("mesh", "resolve")}
    def cli_default(cmd, flag):
        return re.search(rf"^\s*{flag} [^\n=]*=(\S+)", helps[cmd], re.M).group(1)
    r = inspect.signature(pdd.resolve).parameters
    assert str(r["max_rounds"].default) == cli_default("resolve", "--max-rounds")
    assert r["variant"].default == cli_default("resolve", "--variant")
    assert inspect.signature(pdd.mesh_contacts).parameters["variants"].default == cli_default("mesh", "--variants")
    doc = pdd.resolve.__doc__
    for flag in ("--min-volume-ratio", "--min-shape-ratio"):
        assert cli_default("resolve", flag) in doc, flag  # "library's defaults (0.25 and 0.5 ..."
