"""Interrupting long `pdd` runs with real signals: whatever was written is a valid prefix of the
output (whole JSON lines, in input order), and the exit status is 128 + the signal (130 for
SIGINT, 143 for SIGTERM)."""
import json
import pathlib
import signal
import subprocess
import time

import numpy as np
import pytest


def write_pairs(path, n, seed=1):
    """n random pairs of the paper's protocol (vertices uniform in a cube of side 10), named p<k>;
    about half of them intersect."""
    rng = np.random.default_rng(seed)
    pts = rng.uniform(0, 10, (n, 2, 4, 3))
    pairs = [{"name": f"p{k}", "A": pts[k, 0].tolist(), "B": pts[k, 1].tolist()} for k in range(n)]
    path.write_text(json.dumps({"pairs": pairs}))
    return [p["name"] for p in pairs]


def interrupt_when_written(cmd, out, sig, min_lines=1, timeout=120):
    """Runs cmd, sends `sig` once `out` holds at least min_lines lines; returns the exit status."""
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    start = time.monotonic()
    try:
        while time.monotonic() - start < timeout:
            if proc.poll() is not None:
                pytest.fail("the run ended before it could be interrupted: " + proc.stderr.read())
            if out.exists() and out.read_bytes().count(b"\n") >= min_lines:
                break
            time.sleep(0.02)
        proc.send_signal(sig)
        code = proc.wait(timeout=30)  # promptly: not after the pairs still being computed
        return code, proc.stderr.read()
    finally:
        if proc.poll() is None:
            proc.kill()


def assert_valid_prefix(out, names):
    text = out.read_text()
    assert text.endswith("\n"), "the output ends in a partial line"
    records = [json.loads(line) for line in text.splitlines()]
    assert [r["name"] for r in records] == names[:len(records)]
    return records


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_reference_solve_keeps_each_finished_record(pdd_cli, tmp_path, sig, code):
    names = write_pairs(tmp_path / "in.json", 24)
    out = tmp_path / "out.jsonl"
    status, err = interrupt_when_written([pdd_cli, "solve", "--input", str(tmp_path / "in.json"),
                                          "--output", str(out), "--threads", "1"], out, sig)
    assert status == code, err
    records = assert_valid_prefix(out, names)
    assert 1 <= len(records) < len(names)
    assert f"{len(records)} records written" in err


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_fast_solve_never_writes_a_partial_line(pdd_cli, tmp_path, sig, code):
    names = write_pairs(tmp_path / "in.json", 300000)
    out = tmp_path / "out.jsonl"
    status, err = interrupt_when_written([pdd_cli, "solve", "--engine", "fast", "--quiet", "--input",
                                          str(tmp_path / "in.json"), "--output", str(out)], out, sig,
                                         min_lines=1000)
    assert status == code, err
    records = assert_valid_prefix(out, names)
    assert 1000 <= len(records) < len(names)


def test_solve_to_standard_output_keeps_a_valid_prefix(pdd_cli, tmp_path):
    names = write_pairs(tmp_path / "in.json", 24)
    out = tmp_path / "out.jsonl"
    with open(out, "wb") as sink:
        proc = subprocess.Popen([pdd_cli, "solve", "--quiet", "--threads", "1", "--input",
                                 str(tmp_path / "in.json")], stdout=sink, stderr=subprocess.PIPE)
        deadline = time.monotonic() + 120
        while out.stat().st_size == 0 and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.02)
        proc.send_signal(signal.SIGINT)
        assert proc.wait(timeout=30) == 130
    assert 1 <= len(assert_valid_prefix(out, names)) < len(names)


def test_generate_closes_a_valid_fixture_file(pdd_cli, tmp_path):
    """pdd generate writes pairs as it makes them; interrupted, the file it leaves is a complete
    fixture file holding the pairs made so far (the same bytes as a run with that --count)."""
    out = tmp_path / "big.json"
    proc = subprocess.Popen([pdd_cli, "generate", "--family", "paper", "--count", "100000000", "--quiet",
                             "--output", str(out)], stderr=subprocess.PIPE, text=True)
    time.sleep(1.5)
    proc.send_signal(signal.SIGINT)
    assert proc.wait(timeout=30) == 130
    assert "pairs written, as a complete fixture file" in proc.stderr.read()
    pairs = json.loads(out.read_text())["pairs"]
    assert 100 <= len(pairs) < 100000000
    assert [p["name"] for p in pairs] == [f"paper-1-{k}" for k in range(len(pairs))]
    again = tmp_path / "again.json"
    subprocess.run([pdd_cli, "generate", "--family", "paper", "--count", str(len(pairs)), "--quiet",
                    "--output", str(again)], check=True)
    assert again.read_bytes() == out.read_bytes()
    assert not list(tmp_path.glob("*.partial-*"))


def test_generate_over_an_existing_file_leaves_it_as_it_was(pdd_cli, tmp_path):
    """An existing --output is replaced whole or not at all: interrupted, the old bytes stay and
    no temporary file is left, also after two quick signals."""
    out = tmp_path / "old.json"
    old = b'{"pairs": []}\n'
    for signals in ([signal.SIGINT], [signal.SIGTERM, signal.SIGINT]):
        out.write_bytes(old)
        proc = subprocess.Popen([pdd_cli, "generate", "--family", "paper", "--count", "100000000", "--quiet",
                                 "--output", str(out)], stderr=subprocess.PIPE, text=True)
        deadline = time.monotonic() + 60
        while not list(tmp_path.glob("old.json.partial-*")) and time.monotonic() < deadline:
            time.sleep(0.02)
        time.sleep(0.5)
        for s in signals:
            proc.send_signal(s)
        code = proc.wait(timeout=30)
        err = proc.stderr.read()
        # one signal: the command answers (130); two: the first delivered is answered (128 + it)
        # or the second ends the process at once (killed by it). Both may be pending when the
        # process next runs, and Linux delivers pending signals lowest number first: SIGINT
        # before SIGTERM, whichever was sent first.
        two = (130, 143, -signal.SIGINT, -signal.SIGTERM)
        assert code in ((130,) if len(signals) == 1 else two), err
        if len(signals) == 1:
            assert "left as it was" in err
        assert out.read_bytes() == old
        assert not list(tmp_path.glob("*.partial-*"))


def interrupt_when_stdout_written(cmd, out, sig, min_lines=1, timeout=300):
    """Runs cmd with standard output to the file `out`; sends `sig` once it holds min_lines lines."""
    with open(out, "wb") as sink:
        proc = subprocess.Popen(cmd, stdout=sink, stderr=subprocess.PIPE, text=True)
        try:
            deadline = time.monotonic() + timeout
            while out.read_bytes().count(b"\n") < min_lines:
                if proc.poll() is not None:
                    pytest.fail("the run ended before it could be interrupted: " + proc.stderr.read())
                assert time.monotonic() < deadline, "nothing written in time"
                time.sleep(0.02)
            proc.send_signal(sig)
            return proc.wait(timeout=30), proc.stderr.read()
        finally:
            if proc.poll() is None:
                proc.kill()


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_mesh_keeps_each_finished_record(pdd_cli, tmp_path, sig, code):
    """pdd mesh writes each contact as soon as it and every one before it are computed (the
    exact engine: milliseconds a pair on the shipped spheres, hundreds of pairs); interrupted,
    the file holds whole records in (a, b) order and standard error says how many."""
    meshes = pathlib.Path(__file__).resolve().parents[2] / "fixtures" / "meshes"
    out = tmp_path / "pairs.jsonl"
    status, err = interrupt_when_written([pdd_cli, "mesh", "--engine", "reference", "--quiet", "--threads", "1",
                                          "--a", str(meshes / "sphere-a.msh"), "--b", str(meshes / "sphere-b.msh"),
                                          "--output", str(out)], out, sig, min_lines=2)
    assert status == code, err
    text = out.read_text()
    assert text.endswith("\n")
    records = [json.loads(line) for line in text.splitlines()]
    keys = [(r["a"], r["b"]) for r in records]
    assert len(records) >= 2 and keys == sorted(keys) and len(set(keys)) == len(keys)
    assert all(r["intersecting"] is True for r in records)
    assert f"pdd mesh: interrupted (signal {int(sig)}): {len(records)} records written" in err


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_compare_json_keeps_each_finished_object(pdd_cli, tmp_path, sig, code):
    names = write_pairs(tmp_path / "in.json", 200)
    out = tmp_path / "out.jsonl"
    status, err = interrupt_when_stdout_written([pdd_cli, "compare", "--json", "--input", str(tmp_path / "in.json")],
                                                out, sig)
    assert status == code, err
    records = assert_valid_prefix(out, names)
    assert 1 <= len(records) < len(names)
    assert f"{len(records)} records written" in err


def test_solve_interrupted_while_checking_its_input(pdd_cli, tmp_path):
    """A big input is checked whole before anything is computed; a signal then ends the run at
    once, saying nothing was written, and leaves no output file."""
    write_pairs(tmp_path / "in.json", 400000)
    assert (tmp_path / "in.json").stat().st_size > 16 << 20  # the size at which solve says "checking"
    out = tmp_path / "out.jsonl"
    proc = subprocess.Popen([pdd_cli, "solve", "--engine", "fast", "--input", str(tmp_path / "in.json"),
                             "--output", str(out)], stderr=subprocess.PIPE, text=True)
    try:
        assert "checking" in proc.stderr.readline()
        proc.send_signal(signal.SIGINT)
        assert proc.wait(timeout=30) == 130
        err = proc.stderr.read()
    finally:
        if proc.poll() is None:
            proc.kill()
    if "pairs, fast engine" in err:  # the check ended before the signal arrived: nothing to see
        pytest.skip("the check finished before the signal")
    assert "pdd solve: interrupted (signal 2): nothing written: the input was still being checked" in err
    assert not out.exists()


@pytest.mark.parametrize("args", [
    ["golden", "--check", "--quiet", "--formulation", "full"],
    ["paper", "--count", "100000", "--exact-sample", "20000"],
    ["bench", "--count", "100000", "--exact-sample", "20000"],
])
def test_commands_that_print_at_the_end_say_so_when_stopped(pdd_cli, tmp_path, args):
    if args[0] == "golden":
        args += ["--fixtures", str(pathlib.Path(__file__).resolve().parents[2] / "fixtures")]
    if args[0] == "paper":
        args += ["--out", str(tmp_path / "paper")]
    proc = subprocess.Popen([pdd_cli] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            cwd=tmp_path)
    try:
        time.sleep(1.0)
        assert proc.poll() is None, "the run ended before it could be interrupted"
        proc.send_signal(signal.SIGTERM)
        assert proc.wait(timeout=30) == 143
        err = proc.stderr.read()
    finally:
        if proc.poll() is None:
            proc.kill()
    assert f"pdd {args[0]}: interrupted (signal 15): nothing was kept" in err
    assert not list(tmp_path.rglob("*.partial-*"))
