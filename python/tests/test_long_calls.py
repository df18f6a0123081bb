"""The long calls of the module (solve_batch, mesh_contacts): they stop on Ctrl-C (a real SIGINT
to a child interpreter raises KeyboardInterrupt within a fraction of a second, not when the call
would have ended) and report progress (a callable, or a tqdm bar)."""
import importlib.util
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import pdd
from conftest import SOURCE_DIR

MESHES = SOURCE_DIR / "fixtures" / "meshes"

# From the signal to KeyboardInterrupt out of the call. Measured on two shared cores: about
# 0.05 s for the fast engine, the rest of one exact pair (a few 0.1 s) for the reference engine;
# every call below would run at least 5 s longer.
PROMPT = 2.0


def interrupt(setup, call, after=1.0, timeout=60):
    """Runs `setup` then `call` in a child /usr/bin/python3, sends SIGINT `after` seconds into
    the call; returns (seconds from the signal to KeyboardInterrupt out of the call, the child's
    exit status, its standard error)."""
    code = "\n".join([
        "import time", "import numpy as np", "import pdd", textwrap.dedent(setup),
        'print("ready", flush=True)',
        "start = time.monotonic()",
        "try:",
        "    " + call,
        "except KeyboardInterrupt:",
        '    print("interrupted", time.monotonic(), flush=True)',
        "    raise",
        'print("finished", time.monotonic() - start, flush=True)'])
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        line = proc.stdout.readline()
        assert line == "ready\n", line + proc.stderr.read()
        time.sleep(after)
        sent = time.monotonic()  # CLOCK_MONOTONIC: the same clock in both processes
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=timeout)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    words = out.split()
    assert words and words[0] != "finished", f"the call ended ({out.strip()}) before the signal: give it more work"
    assert words[0] == "interrupted", out + err
    return float(words[1]) - sent, proc.returncode, err


def assert_keyboard_interrupt(delay, status, err):
    assert err.rstrip().endswith("KeyboardInterrupt"), err
    assert status == -signal.SIGINT, (status, err)  # Python ends by SIGINT after KeyboardInterrupt
    assert 0 <= delay < PROMPT, delay


HAVE_TQDM = importlib.util.find_spec("tqdm") is not None


@pytest.mark.parametrize("with_global, progress", [
    (True, None), (False, None),
    pytest.param(True, True, marks=pytest.mark.skipif(not HAVE_TQDM, reason="no tqdm (python3-tqdm)"))])
def test_solve_batch_stops_on_sigint(with_global, progress):
    # 10^6 random pairs on two threads: 5 to 10 s of work (13 us a pair a core)
    delay, status, err = interrupt(
        "A, B = np.random.default_rng(1).uniform(0, 10, (2, 10**6, 4, 3))",
        f"pdd.solve_batch(A, B, threads=2, with_global={with_global}, progress={progress})")
    assert_keyboard_interrupt(delay, status, err)
    if progress:  # the bar was drawn, then closed, before the exception
        assert "pdd.solve_batch:" in err and "/1000000 [" in err


def test_fast_mesh_contacts_stop_on_sigint():
    # the torus against 200 copies of the box: 542400 pairs, every value, about 10 s on two threads
    delay, status, err = interrupt(f"""
        V, T = pdd.read_mesh({str(MESHES / "box.vtk")!r})
        VB, TB = np.vstack([V] * 200), np.vstack([T + k * len(V) for k in range(200)])
        VA, TA = pdd.read_mesh({str(MESHES / "torus.msh")!r})
        """,
        'pdd.mesh_contacts(VA, TA, VB, TB, variants="all", threads=2)')
    assert_keyboard_interrupt(delay, status, err)


def test_reference_mesh_contacts_stop_on_sigint():
    # 2639 exact pairs of two balls, about 60 ms each: minutes on two threads; the call waits
    # only for the pairs being computed
    delay, status, err = interrupt(f"""
        VA, TA = pdd.read_mesh({str(MESHES / "sphere-a.msh")!r})
        VB, TB = pdd.read_mesh({str(MESHES / "sphere-b.msh")!r})
        """,
        'pdd.mesh_contacts(VA, TA, VB, TB, engine="reference", threads=2)')
    assert_keyboard_interrupt(delay, status, err)


def test_concurrent_calls_and_a_forked_child():
    """Calls from several threads at once each get their own computing thread, and a child
    made by fork() (which has none of the parent's threads) computes too."""
    code = textwrap.dedent("""
        import os, threading
        import numpy as np
        import pdd
        A, B = np.random.default_rng(2).uniform(0, 10, (2, 3000, 4, 3))
        ref = pdd.solve_batch(A, B)["pdd2"].view(np.int64)
        res = [None] * 4
        def run(i):
            res[i] = pdd.solve_batch(A, B)["pdd2"].view(np.int64)
        threads = [threading.Thread(target=run, args=(i,)) for i in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        assert all((r == ref).all() for r in res)
        pid = os.fork()
        if pid == 0:
            os._exit(0 if (pdd.solve_batch(A, B)["pdd2"].view(np.int64) == ref).all() else 3)
        assert os.waitpid(pid, 0)[1] == 0
        print("ok")
        """)
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0 and run.stdout == "ok\n", run.stderr


# ---------------------------------------------------------------------------------------------
# progress

def random_pairs(n, seed=4):
    return np.random.default_rng(seed).uniform(0, 10, (2, n, 4, 3))


def recorder():
    calls = []

    def progress(done, total):
        calls.append((done, total, threading.get_ident()))
    return calls, progress


def assert_monotone_to(calls, total):
    assert calls, "progress was never called"
    done = [c[0] for c in calls]
    assert done == sorted(set(done)), done  # growing, each value once
    assert calls[-1][:2] == (total, total)
    assert {c[1] for c in calls} == {total}
    assert {c[2] for c in calls} == {threading.get_ident()}  # the calling thread


def test_solve_batch_reports_progress():
    A, B = random_pairs(100000)  # one thread: about 1.3 s, progress about every 0.05 s
    calls, progress = recorder()
    res = pdd.solve_batch(A, B, threads=1, progress=progress)
    assert len(calls) >= 3, calls
    assert_monotone_to(calls, 100000)
    ref = pdd.solve_batch(A, B)
    for k in ("pdd2", "rigid_pd2", "pdd2_global", "q1_A"):
        assert (res[k].view(np.int64) == ref[k].view(np.int64)).all(), k


@pytest.mark.parametrize("n", [0, 1, 256, 257])
def test_short_batches_report_the_end(n):
    A, B = random_pairs(n)
    calls, progress = recorder()
    pdd.solve_batch(A, B, progress=progress)
    assert_monotone_to(calls, n)


def test_an_exception_from_progress_stops_solve_batch():
    A, B = random_pairs(100000)
    start = time.monotonic()
    pdd.solve_batch(A, B, threads=1)
    whole = time.monotonic() - start
    calls = []

    def progress(done, total):
        calls.append(done)
        if len(calls) == 2:
            raise RuntimeError("enough")
    start = time.monotonic()
    with pytest.raises(RuntimeError, match="^enough$"):
        pdd.solve_batch(A, B, threads=1, progress=progress)
    stopped = time.monotonic() - start
    assert len(calls) == 2 and calls[1] < 100000
    assert stopped < whole / 3, (stopped, whole)
    # the end of a short call too
    with pytest.raises(ZeroDivisionError):
        pdd.solve_batch(A[:10], B[:10], progress=lambda done, total: 1 / 0)


def mesh(name):
    return pdd.read_mesh(MESHES / name)


@pytest.mark.parametrize("engine", ["fast", "reference"])
def test_mesh_contacts_report_progress(engine):
    if engine == "fast":
        V, T = mesh("box.vtk")
        args = mesh("torus.msh") + (np.vstack([V] * 10), np.vstack([T + k * len(V) for k in range(10)]))
    else:  # 6 exact pairs, about 0.1 s each
        V, T = mesh("tiny-a.msh")
        args = (V, T[:3]) + mesh("tiny-b.msh")
    calls, progress = recorder()
    # one thread: about 0.9 s (fast), 0.6 s (reference)
    res = pdd.mesh_contacts(*args, variants="all", engine=engine, threads=1, progress=progress)
    assert_monotone_to(calls, len(res["a"]))
    assert len(calls) >= 2
    ref = pdd.mesh_contacts(*args, variants="all", engine=engine)
    assert (res["a"] == ref["a"]).all() and (res["b"] == ref["b"]).all()
    assert list(res["pdd2"]) == list(ref["pdd2"])
    # no intersecting pair: (0, 0) once
    calls, progress = recorder()
    far = pdd.mesh_contacts(V, T, V + 100, T, engine=engine, progress=progress)
    assert len(far["a"]) == 0 and [c[:2] for c in calls] == [(0, 0)]


def test_an_exception_from_progress_stops_mesh_contacts():
    # 51 exact pairs on one thread: about 3 s; stopped at the first report, after one pair
    args = mesh("tiny-a.msh") + mesh("tiny-b.msh")
    calls = []

    def progress(done, total):
        calls.append((done, total))
        raise KeyError("stop")
    start = time.monotonic()
    with pytest.raises(KeyError, match="stop"):
        pdd.mesh_contacts(*args, engine="reference", threads=1, progress=progress)
    assert time.monotonic() - start < 1.5
    assert len(calls) == 1 and calls[0][1] == 51


@pytest.mark.skipif(not HAVE_TQDM, reason="no tqdm (Debian python3-tqdm)")
def test_progress_true_draws_a_tqdm_bar(capsys):
    A, B = random_pairs(3000)
    pdd.solve_batch(A, B, progress=True)
    err = capsys.readouterr().err
    assert "pdd.solve_batch: 100%" in err and "3000/3000" in err, err
    res = pdd.mesh_contacts(*mesh("sphere-a.msh"), *mesh("sphere-b.msh"), progress=True)
    k = len(res["a"])
    err = capsys.readouterr().err
    assert "pdd.mesh_contacts: 100%" in err and f"{k}/{k}" in err, err


def test_progress_true_without_tqdm(monkeypatch):
    monkeypatch.setitem(sys.modules, "tqdm", None)  # import tqdm raises ImportError
    A, B = random_pairs(10**5)
    start = time.monotonic()
    with pytest.raises(ImportError, match="tqdm cannot be imported .Debian: apt install python3-tqdm"):
        pdd.solve_batch(A, B, progress=True)
    with pytest.raises(ImportError, match="pass a callable progress.done, total. instead, or None$"):
        pdd.mesh_contacts(*mesh("tiny-a.msh"), progress=True)
    assert time.monotonic() - start < 0.5  # before any work


@pytest.mark.parametrize("progress", [1, "yes", np.True_, [print]])
def test_bad_progress_raises_value_error(progress):
    message = r"^progress must be None, True or a callable progress\(done, total\); got "
    with pytest.raises(ValueError, match=message):
        pdd.solve_batch(np.zeros((1, 4, 3)), np.zeros((1, 4, 3)), progress=progress)
    with pytest.raises(ValueError, match=message):
        pdd.mesh_contacts(*mesh("tiny-a.msh"), progress=progress)
    assert pdd.solve_batch(np.zeros((1, 4, 3)), np.zeros((1, 4, 3)), progress=False)["error"][0]
