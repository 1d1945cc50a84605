"""Named low-pass velocity estimators against scipy: `butterworth:N:FC`, `bessel:N:FC` and
`critically-damped:N:FC` are the `iir:` filter a user would build by hand — scipy's design
convolved with the backward difference (1 − z⁻¹)/T — to 1e-12 in the discrete loop, and equal
to it in K_max and in the passivity figure (1e-12 alike), for every order 1–4 and a few cut-offs and
periods. The references: scipy's `butter(N, FC, fs=1/T)` and `bessel(N, FC, fs=1/T)`
(norm='phase'), and for the critically damped filter an independent construction of N equal
analog poles at −ω_a/√(2^{1/N} − 1), ω_a = (2/T)·tan(π·FC·T), through scipy's `bilinear_zpk`
at the true sampling rate and `zpk2tf`."""

import numpy as np
import pytest
from scipy import signal

import hapstab as hs

REL = 1e-12
FAMILIES = ("butterworth", "bessel", "critically-damped")
# (FC in Hz, T in s): mid-band, a low cut-off at a fast rate, and close to Nyquist/2
PAIRS = [(150.0, 1e-3), (40.0, 5e-4), (300.0, 1e-3)]


def critically_damped(order, fc, period):
    """N equal real analog poles with the cascade's −3 dB point at the pre-warped cut-off,
    mapped by scipy's bilinear_zpk at fs = 1/T (not the fs = 2 normalization hapstab uses)."""
    fs = 1.0 / period
    warped = 2.0 * fs * np.tan(np.pi * fc / fs)
    alpha = warped / np.sqrt(2.0 ** (1.0 / order) - 1.0)
    z, p, k = signal.bilinear_zpk([], [-alpha] * order, alpha ** order, fs=fs)
    return signal.zpk2tf(z, p, k)


def design(family, order, fc, period):
    """The reference low-pass (b, a) in powers of z⁻¹."""
    if family == "butterworth":
        return signal.butter(order, fc, fs=1.0 / period)
    if family == "bessel":
        return signal.bessel(order, fc, fs=1.0 / period)
    return critically_damped(order, fc, period)


def hand_made(family, order, fc, period):
    """The `iir:` spec of the reference design applied to the backward difference."""
    b, a = design(family, order, fc, period)
    num = np.convolve(b, [1.0, -1.0]) / period
    return "iir:" + ",".join(repr(float(x)) for x in num) + "/" + ",".join(
        repr(float(x)) for x in a)


def close(x, y, rel=REL):
    x, y = np.asarray(x, float), np.asarray(y, float)
    scale = max(np.max(np.abs(y)), 1e-300)
    assert np.max(np.abs(x - y)) <= rel * scale, (x, y)


def loops(family, order, fc, period):
    plant = hs.MassSpringDamper.from_device_and_arm()
    named = hs.Loop(plant, period=period, velocity=f"{family}:{order}:{fc!r}")
    iir = hs.Loop(plant, period=period, velocity=hand_made(family, order, fc, period))
    return named, iir


def assert_same_discrete_loop(named, iir):
    dn, di = hs.discretize(named, 1000.0, 2.0), hs.discretize(iir, 1000.0, 2.0)
    for key in ("velocity_num", "velocity_den", "p0", "pk", "pb"):
        close(getattr(dn, key), getattr(di, key))


@pytest.mark.parametrize("family", FAMILIES)
@pytest.mark.parametrize("order", [1, 2, 3, 4])
@pytest.mark.parametrize("fc, period", PAIRS)
def test_named_filter_equals_the_hand_made_iir(family, order, fc, period):
    named, iir = loops(family, order, fc, period)
    assert_same_discrete_loop(named, iir)
    kn, ki = hs.kmax(named, wall_damping=2.0).k_max, hs.kmax(iir, wall_damping=2.0).k_max
    assert abs(kn - ki) <= REL * ki, (kn, ki)
    pn, pi = hs.passivity(named, 0.3 * kn, 2.0), hs.passivity(iir, 0.3 * kn, 2.0)
    assert abs(pn.b_required - pi.b_required) <= REL * pi.b_required


@pytest.mark.parametrize("family", FAMILIES)
@pytest.mark.parametrize("order", [5, 6, 7, 8])
def test_high_orders_discretize_as_the_reference(family, order):
    """Orders 5–8 (the Bessel poles of every order the spec accepts): the discrete loop only."""
    assert_same_discrete_loop(*loops(family, order, 60.0, 1e-3))


@pytest.mark.parametrize("family", FAMILIES)
def test_the_spec_round_trips_and_refuses(family):
    title = {"butterworth": "Butterworth", "bessel": "Bessel",
             "critically-damped": "critically damped"}[family]
    plant = hs.MassSpringDamper(1.0, 1.0)
    lp = hs.Loop(plant, velocity=f"{family}:2:150")
    assert lp.velocity == f"{family}:2:150"
    assert hs.Loop(plant, velocity=lp.velocity).velocity == lp.velocity
    for spec, needle in [(f"{family}:2:600", "Nyquist"), (f"{family}:2:500", "Nyquist"),
                         (f"{family}:9:60", f"{title} order N"),
                         (f"{family}:0:60", f"{title} order N"),
                         (f"{family}:2:-60", f"{title} cut-off f_c"),
                         (f"{family}:60", f"{family}:ORDER:FC"),
                         (f"{family}:two:60", "'two'")]:
        with pytest.raises(ValueError, match=needle):
            hs.Loop(plant, velocity=spec)


@pytest.mark.parametrize("family", ["bessel", "critically-damped"])
def test_sweeping_the_cutoff_is_the_loop_at_each_cutoff(family):
    """`sweep(loop, 'cutoff', …)` keeps the family and the order and varies FC: each point's
    K_max is that of the loop built with that cut-off."""
    plant = hs.MassSpringDamper.from_device_and_arm()
    lp = hs.Loop(plant, period=1e-3, velocity=f"{family}:3:100")
    values = [40.0, 120.0, 300.0]
    s = hs.sweep(lp, "cutoff", values, wall_damping=2.0)
    for v, k in zip(values, s.k_max):
        one = hs.Loop(plant, period=1e-3, velocity=f"{family}:3:{v!r}")
        want = hs.kmax(one, wall_damping=2.0).k_max
        assert abs(k - want) <= 1e-9 * want, (v, k, want)
