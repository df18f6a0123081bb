"""examples/soft_body.py on a tiny mesh: a few implicit Euler steps with pdd's contact energy.
Every step converges (the residual force below 1e-5 of the weight), each iterate lowers the
incremental potential Phi (Armijo line search on Phi along L-BFGS directions started from the
positive definite matrix M/dt^2 + K + k H_E, H_E positive semi-definite; below Phi's rounding,
Armijo's condition on the slope, Phi within that rounding), and the
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
        for before, after, allowance in zip(phis, phis[1:], s.allowances):
            assert after <= before + allowance  # Armijo, or within Phi's rounding (Scene.step)
        assert e["max_pdd2_global"] <= 1e-6
    # the floor stayed put
    floor = s.rest[s.nA:, 2] == 0
    assert np.array_equal(s.x[s.nA:][floor], s.rest[s.nA:][floor])


def test_readme_scene_converges_through_resting_contact():
    """The README's scene (default Scene) up to step 35, where the ball, fallen back onto the
    block at step 31, presses on it:
    the residual force reaches 1e-5 of the weight only after Phi's own decrease has fallen
    below its rounding (~1e-15 of Phi), where the line search takes Armijo's condition on the
    slope; on Phi's values alone that step stalls at 1.08e-5 of the weight."""
    s = soft_body.Scene()
    for n in range(36):
        phis, e, converged = s.step()
        assert converged, f"step {n}: {len(phis) - 1} iterations"


def test_resolved_rest_shape_starts_without_strain():
    """Scene(rest="resolved"): the resolved start is the rest shape, so the first step starts
    from zero elastic energy (x = rest exactly) and still converges, the penetration as small;
    Scene(rest="original") stores the resolve's deformation (x != rest on the moved vertices)."""
    s = soft_body.Scene(n_ball=2, n_block=(3, 3, 2), rest="resolved")
    assert np.array_equal(s.x, s.rest)
    phis, e, converged = s.step()
    assert converged and e["max_pdd2_global"] <= 1e-6
    o = soft_body.Scene(n_ball=2, n_block=(3, 3, 2))
    assert not np.array_equal(o.x, o.rest)
    with pytest.raises(ValueError, match="rest must be"):
        soft_body.Scene(n_ball=2, n_block=(3, 3, 2), rest="deformed")
