"""Every example a user is shown runs as written:
  - each command's `--help` (every subcommand of `pdd --help` and of `pdd bench --help`) ends with
    examples; each runs from a copy of the source tree's layout (fixtures/ linked, outputs in a
    fresh folder) and exits 0;
  - every `sh` block of README.md and docs/*.md that runs `build/bin/pdd` runs the same way, its
    lines in order, and exits 0 (but the measurement protocols, LONG below); the Quick start's
    table is the one the README shows (its first five columns), and `pdd theorem`'s counts are
    those docs/paper-findings.md gives.
`bash scripts/...` and `ctest` lines are not run here (they build or run the whole suite)."""
import os
import re
import shlex
import subprocess

import pytest

from conftest import SOURCE_DIR


def help_text(cli, *command):
    r = subprocess.run([cli, *command, "--help"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, (command, r.stderr)
    return r.stdout


def subcommands(text):
    section = text.split("\nSubcommands:\n", 1)[1] if "\nSubcommands:\n" in text else ""
    return re.findall(r"^  (\S+)\s", section.split("\n\n", 1)[0], re.M)


def commands(cli):
    out = [(c,) for c in subcommands(help_text(cli))]
    out += [("bench", c) for c in subcommands(help_text(cli, "bench"))]
    return out


def help_examples(text):
    """The command lines after "Examples", backslash continuations joined."""
    if "\nExamples" not in text:
        return []
    body = text.split("\nExamples", 1)[1].split("\n", 1)[1]
    return [l.strip() for l in re.sub(r"\\\n\s*", "", body).splitlines() if l.strip().startswith("pdd ")]


def run_example(cli, line, cwd):
    """`line` (starting with `pdd` or `build/bin/pdd`) with this build's program, from `cwd`."""
    argv = shlex.split(line)
    assert argv[0] in ("pdd", "build/bin/pdd"), line
    return subprocess.run([cli, *argv[1:]], cwd=cwd, capture_output=True, text=True, timeout=900)


@pytest.fixture
def tree(tmp_path):
    """A folder laid out as the source tree for the examples: fixtures/ linked, outputs here."""
    (tmp_path / "fixtures").symlink_to(SOURCE_DIR / "fixtures")
    return tmp_path


def test_every_command_has_examples(pdd_cli):
    found = commands(pdd_cli)
    assert ("solve",) in found and ("mesh",) in found and ("bench", "resolve") in found
    missing = [" ".join(c) for c in found if not help_examples(help_text(pdd_cli, *c))]
    assert not missing, f"--help without examples: {missing}"


@pytest.mark.parametrize("command", ["solve", "generate", "golden", "theorem", "audit-ee", "compare", "paper",
                                     "bench", "bench mesh", "bench resolve", "mesh", "resolve"])
def test_help_examples_run(pdd_cli, tree, command):
    examples = help_examples(help_text(pdd_cli, *command.split()))
    assert examples, command
    for line in examples:
        assert line.startswith("pdd " + command + " "), line
        r = run_example(pdd_cli, line, tree)
        assert r.returncode == 0, (line, r.stderr[-3000:])


# Documented commands that are measurement protocols, minutes to hours on two cores (the
# paper's full experiment, the benchmarks behind docs/performance.md): not run here; their shorter
# forms are the --help examples above.
LONG = ("build/bin/pdd paper --seed 1 --count 10000 ", "build/bin/pdd bench")


def doc_shell_blocks():
    """(page, [command lines]) of every sh block of README.md and docs/*.md that runs build/bin/pdd,
    backslash continuations joined, comments dropped; the lines of a block run in order (a later
    one may read what an earlier one wrote)."""
    out = []
    for page in [SOURCE_DIR / "README.md", *sorted((SOURCE_DIR / "docs").glob("*.md"))]:
        for block in re.findall(r"```sh\n(.*?)```", page.read_text(), re.S):
            lines = [l.strip() for l in re.sub(r"\\\n\s*", "", block).splitlines()]
            lines = [l for l in lines if l.startswith("build/bin/pdd ")]
            if lines:
                out.append((page.name, lines))
    return out


def test_documented_commands_found():
    lines = [l for _, block in doc_shell_blocks() for l in block]
    assert any(" solve " in l for l in lines) and any(" mesh " in l for l in lines) and any(" resolve " in l for l in lines)
    assert any(l.startswith(LONG) for l in lines)  # the rule below skips something that exists


@pytest.mark.parametrize("page,lines", doc_shell_blocks(),
                         ids=[f"{p}:{b[0][14:34]}" for p, b in doc_shell_blocks()])
def test_documented_commands_run(pdd_cli, tree, page, lines):
    ran = 0
    for line in lines:
        if line.startswith(LONG):
            continue
        argv = shlex.split(line, comments=True)
        r = subprocess.run([pdd_cli, *argv[1:]], cwd=tree, capture_output=True, text=True, timeout=900)
        assert r.returncode == 0, (page, line, r.stderr[-3000:])
        ran += 1
    if not ran:
        pytest.skip(f"{page}: measurement protocols only ({lines[0]} ...)")


def test_theorem_counts_are_what_the_findings_say(pdd_cli, tree):
    """docs/paper-findings.md §1: the counts its comment lines give for 300 pairs of seed 1."""
    run_example(pdd_cli, "pdd generate --family paper --seed 1 --count 300 --output paper300.json --quiet", tree)
    r = run_example(pdd_cli, "pdd theorem --input paper300.json --nef 0", tree)
    assert r.returncode in (0, 1), r.stderr
    assert re.search(r"eq\. 11 < PD \(theorem fails\): +167\n", r.stdout)
    assert re.search(r"nested on the minimising axis: +167 of 167\n", r.stdout)
    assert "leaves the interiors intersecting: 167 of 167\n" in r.stdout
    assert re.search(r"PD = min oriented depth \(corrected\): 300 of 300\n", r.stdout)
    text = (SOURCE_DIR / "docs" / "paper-findings.md").read_text()
    assert "eq. 11 < PD (theorem fails): 167 of 300" in text and "(corrected): 300 of 300" in text


def test_quick_start_table_is_what_the_readme_shows(pdd_cli, tree):
    text = (SOURCE_DIR / "README.md").read_text()
    section = text.split("## Quick start", 1)[1]
    line = re.search(r"```sh\n(.*?)\n```", section, re.S).group(1).strip()
    shown = re.search(r"```text\n(.*?)```", section, re.S).group(1).splitlines()
    r = run_example(pdd_cli, line, tree)
    assert r.returncode == 0, r.stderr
    printed = r.stdout.splitlines()
    assert len(printed) == len(shown)
    for got, want in zip(printed, shown):
        assert got.split()[:5] == want.split()[:5]
