"""`cmake --install` puts the module where Debian's python3 finds it under the prefix: the
python component installed into a temporary prefix lands in one of the directories that
site.py adds for that prefix, and imports from there."""
import os
import pathlib
import site
import subprocess
import sys

import pytest


def install(component, tmp_path):
    """`cmake --install` of one component of this build into a fresh prefix; the prefix."""
    build = os.environ.get("PDD_BUILD_DIR")
    cmake = os.environ.get("CMAKE_COMMAND", "cmake")
    if not build:
        pytest.skip("PDD_BUILD_DIR (the build tree) not set; CTest sets it")
    prefix = tmp_path / "prefix"
    out = subprocess.run([cmake, "--install", build, "--component", component, "--prefix", str(prefix)],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr
    return prefix


def test_install_where_python_finds_it(tmp_path):
    prefix = install("python", tmp_path)
    installed = [p for p in prefix.rglob("pdd*.so")]
    assert len(installed) == 1, installed
    where = installed[0].parent
    # the directories site.py puts on sys.path for this prefix (Debian: lib/python3.X/dist-packages
    # under /usr and /usr/local alike; lib/python3/dist-packages under /usr only)
    assert str(where) in site.getsitepackages([str(prefix)])
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    probe = ("import site, sys; site.addsitedir(sys.argv[1]); import pdd; "
             "assert pdd.__file__.startswith(sys.argv[1]), pdd.__file__; "
             "print(pdd.solve([[0,0,0],[1,0,0],[0,1,0],[0,0,1]], [[0,0,0],[1,0,0],[0,1,0],[0,0,1]])['intersecting'])")
    run = subprocess.run([sys.executable, "-c", probe, str(where)], env=env, cwd=tmp_path,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "True"


def test_install_puts_the_program_in_bin(tmp_path):
    """The `tools` component installs the `pdd` program into <prefix>/bin; it runs from there
    (no library of the build tree needed) and names the project's version."""
    prefix = install("tools", tmp_path)
    program = prefix / "bin" / "pdd"
    assert program.is_file() and os.access(program, os.X_OK)
    run = subprocess.run([str(program), "--version"], capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0 and run.stdout.strip() == "pdd " + pdd_version(), run.stdout + run.stderr


def pdd_version():
    """The version of the build's module, which CMake sets from project(pdd VERSION ...)."""
    import pdd
    return pdd.__version__
