"""Interrupting long `pdd` runs with real signals: whatever was written is a valid prefix of the
output (whole JSON lines, in input order), and the exit status is 128 + the signal (130 for
SIGINT, 143 for SIGTERM)."""
import json
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
