"""Named Butterworth velocity estimators against scipy: `butterworth:N:FC` is the `iir:` filter
a user would build by hand — scipy's `butter(N, FC, fs=1/T)` convolved with the backward
difference (1 − z⁻¹)/T — to 1e-12 in the discrete loop, in K_max and in the passivity figure,
for every order 1–4 and a few cut-offs and periods."""

import numpy as np
import pytest
from scipy import signal

import hapstab as hs

REL = 1e-12


def hand_made(order, fc, period):
    """The `iir:` spec of the scipy design applied to the backward difference."""
    b, a = signal.butter(order, fc, fs=1.0 / period)
    num = np.convolve(b, [1.0, -1.0]) / period
    return "iir:" + ",".join(repr(float(x)) for x in num) + "/" + ",".join(
        repr(float(x)) for x in a)


def close(x, y, rel=REL):
    x, y = np.asarray(x, float), np.asarray(y, float)
    scale = max(np.max(np.abs(y)), 1e-300)
    assert np.max(np.abs(x - y)) <= rel * scale, (x, y)


@pytest.mark.parametrize("order", [1, 2, 3, 4])
@pytest.mark.parametrize("fc, period", [(150.0, 1e-3), (40.0, 5e-4), (300.0, 1e-3)])
def test_named_filter_equals_the_hand_made_iir(order, fc, period):
    named = hs.Loop(hs.MassSpringDamper.from_device_and_arm(), period=period,
                    velocity=f"butterworth:{order}:{fc!r}")
    iir = hs.Loop(hs.MassSpringDamper.from_device_and_arm(), period=period,
                  velocity=hand_made(order, fc, period))
    dn, di = hs.discretize(named, 1000.0, 2.0), hs.discretize(iir, 1000.0, 2.0)
    for key in ("velocity_num", "velocity_den", "p0", "pk", "pb"):
        close(getattr(dn, key), getattr(di, key))
    kn, ki = hs.kmax(named, wall_damping=2.0).k_max, hs.kmax(iir, wall_damping=2.0).k_max
    assert abs(kn - ki) <= 1e-9 * ki, (kn, ki)
    pn, pi = hs.passivity(named, 0.3 * kn, 2.0), hs.passivity(iir, 0.3 * kn, 2.0)
    assert abs(pn.b_required - pi.b_required) <= 1e-9 * pi.b_required


def test_the_spec_round_trips_and_refuses():
    lp = hs.Loop(hs.MassSpringDamper(1.0, 1.0), velocity="butterworth:2:150")
    assert lp.velocity == "butterworth:2:150"
    with pytest.raises(ValueError, match="Nyquist"):
        hs.Loop(hs.MassSpringDamper(1.0, 1.0), velocity="butterworth:2:600")
    with pytest.raises(ValueError, match="order"):
        hs.Loop(hs.MassSpringDamper(1.0, 1.0), velocity="butterworth:9:60")
