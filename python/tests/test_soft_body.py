"""examples/soft_body.py on a tiny mesh: a few implicit Euler steps with pdd's contact energy.
Every step converges (the residual force below 1e-5 of the weight), each iterate lowers the
incremental potential Phi (Armijo line search on Phi along L-BFGS directions started from the
positive definite matrix M/dt^2 + K + k H_E, H_E positive semi-definite), and the
penetration stays small: the largest pdd2_global (a squared depth) below 1e-6, a depth of 1e-3
= 0.25% of the ball's radius, the tolerance the example's stiffness k = 1e7 is chosen for."""
import os
import sys

import numpy as np
import pytest

pytest.importorskip("scipy.sparse")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples"))
import soft_body  # noqa: E402


def test_soft_body_steps():
    s = soft_body.Scene(n_ball=2, n_block=(3, 3, 2))
    for _ in range(4):
        phis, e, converged = s.step()
        assert converged  # the residual force below 1e-5 of the weight (Scene.step)
        assert len(phis) >= 2
        for before, after in zip(phis, phis[1:]):
            assert after <= before + 1e-12 * abs(before)
        assert e["max_pdd2_global"] <= 1e-6
    # the floor stayed put
    floor = s.rest[s.nA:, 2] == 0
    assert np.array_equal(s.x[s.nA:][floor], s.rest[s.nA:][floor])
