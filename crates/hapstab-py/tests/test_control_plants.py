"""python-control plants: a `control.tf` or `control.ss` system is the plant of a Loop, with
the same results as the equivalent `TransferFunction(num, den)`; discrete or MIMO systems
are refused naming the keyword."""

import control
import numpy as np
import pytest

import hapstab as hs

NUM, DEN = [0.5, 120.0, 35000.0], [0.44, 113.0, 11000.0, 715000.0, 35000000.0]


def answers(lp):
    k = hs.kmax(lp, wall_damping=2.0).k_max
    c = hs.check(lp, 0.4 * k, 2.0)
    return k, c.spectral_radius, hs.margins(lp, 0.4 * k, 2.0).delay_margin


def test_a_control_tf_is_the_transfer_function():
    ours = hs.Loop(hs.TransferFunction(NUM, DEN), delay=3.7e-4, velocity="lowpass:100")
    theirs = hs.Loop(control.tf(NUM, DEN), delay=3.7e-4, velocity="lowpass:100")
    assert answers(theirs) == answers(ours)
    assert theirs.plant.num.tolist() == NUM and theirs.plant.den.tolist() == DEN


def test_a_control_ss_is_its_transfer_function():
    sys = control.ss(control.tf(NUM, DEN))
    theirs = hs.Loop(sys, delay=1e-3)
    # exactly the loop of python-control's own ss2tf of the system
    tf = control.ss2tf(sys)
    same = hs.Loop(hs.TransferFunction(tf.num[0][0], tf.den[0][0]), delay=1e-3)
    assert answers(theirs) == answers(same)
    # and the original transfer function up to the realization's rounding (tf → ss → tf
    # moves the coefficients by ~1e-14 relative, which K_max amplifies to ~3e-12)
    ours = hs.Loop(hs.TransferFunction(NUM, DEN), delay=1e-3)
    for x, y in zip(answers(theirs), answers(ours)):
        assert (x is None and y is None) or abs(x - y) <= 1e-10 * abs(y), (x, y)


def test_discrete_and_mimo_systems_are_refused():
    with pytest.raises(ValueError, match="^plant: .*continuous-time"):
        hs.Loop(control.tf([1.0], [1.0, -0.5], 0.001))
    mimo = control.ss([[-1.0]], [[1.0, 1.0]], [[1.0]], [[0.0, 0.0]])
    with pytest.raises(ValueError, match="^plant: .*one input and one output"):
        hs.Loop(mimo)


@pytest.mark.parametrize("lp, wall", [
    (hs.Loop.paper(delay=1e-3), dict(wall_stiffness=2000.0, wall_damping=3.0)),
    (hs.Loop(control.tf(NUM, DEN), delay=3.7e-4, velocity="butterworth:2:150"),
     dict(wall_stiffness=300.0, wall_damping=0.5)),
    (hs.Loop.normalized(gamma=0.001, delta=0.015, d=2), dict(alpha=0.05, beta=0.1)),
])
def test_to_control_closes_to_the_roots_of_p(lp, wall):
    L = lp.to_control(**wall)
    assert L.dt == lp.period
    poles = list(control.poles(control.feedback(L, 1)))
    roots = hs.check(lp, **wall).roots
    assert len(poles) == len(roots)
    for r in roots:  # each root matched to its nearest pole, once
        i = int(np.argmin([abs(p - r) for p in poles]))
        assert abs(poles.pop(i) - r) <= 1e-9, (r, poles)
