"""The long calls of the module (solve_batch, mesh_contacts) stop on Ctrl-C: a real SIGINT to a
child interpreter raises KeyboardInterrupt within a fraction of a second, not when the call would
have ended."""
import signal
import subprocess
import sys
import textwrap
import time

import pytest

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


@pytest.mark.parametrize("with_global", [True, False])
def test_solve_batch_stops_on_sigint(with_global):
    # 10^6 random pairs on two threads: 5 to 10 s of work (13 us a pair a core)
    delay, status, err = interrupt(
        "A, B = np.random.default_rng(1).uniform(0, 10, (2, 10**6, 4, 3))",
        f"pdd.solve_batch(A, B, threads=2, with_global={with_global})")
    assert_keyboard_interrupt(delay, status, err)


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
