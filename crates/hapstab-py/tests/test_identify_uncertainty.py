"""identify's uncertainty against the truth of an independent simulator
(benches/baseline/identify_data.py, numpy/scipy only): K_max's intervals over 20 seeded
recordings of a two-mass device, the truth being the library's exact K_max of the *true*
parameters; several runs fitted together; a quantized position without noise; and the
coverage of the frequency fit's intervals over seeded noise realisations.

A calibrated 95 % interval misses the truth in about one recording of twenty (all twenty
inside: 0.95^20 = 36 %), so the delta-method intervals are asked for at least 17 of 20
(fewer has probability 1.6 % for a calibrated interval), and only the range over the
parameters' 95 % box — conservative by construction
(Σ|∂K/∂θ_i|·1.96σ_i ≥ 1.96·√(gᵀΣg)) — for all 20."""

import os
import sys
from pathlib import Path

import numpy as np
import pytest

import hapstab as hs

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "benches" / "baseline"))
import identify_data  # noqa: E402

PERIOD = 1e-3
Q = 1e-5


def recording(model, params, n, seed, snr=40.0, quantization=Q, **force):
    """t, F, x from the independent simulator: exact ZOH of the plant, noise at `snr` dB,
    position rounded to `quantization`."""
    num, den = identify_data.plant_tf(model, params)
    phi, gamma, c = identify_data.sampled(num, den, PERIOD)
    kind = force.pop("kind", "chirp")
    f = identify_data.force_signal(kind, n, PERIOD, force.pop("amplitude", 1.0), seed,
                                   force.pop("f0", 0.5), force.pop("f1", 50.0),
                                   force.pop("hold", 10))
    y = identify_data.simulate(phi, gamma, c, f, 0)
    return np.arange(n) * PERIOD, f, identify_data.measured(y, snr, quantization, seed)


TWO_MASS = {"J": 0.3, "b_m": 2.0, "m_h": 0.1, "k_t": 2300.0, "b_t": 1.0}


def true_two_mass_kmax():
    """K_max at B = 0 and over the renderable band (Δ = Q) of the true two-mass loop."""
    plant = hs.TwoMass(0.3, 2300.0, motor_damping=2.0, handle_mass=0.1,
                       transmission_damping=1.0, arm_mass=0.0, arm_damping=0.0,
                       arm_stiffness=0.0)
    lp = hs.Loop(plant, period=PERIOD)
    at_zero = hs.kmax(lp, wall_damping=0.0).k_max
    band = hs.kmax(lp, position_resolution=Q).renderable.k_max
    return at_zero, band


def test_true_k_max_inside_its_intervals_on_20_seeded_recordings():
    k_true, band_true = true_two_mass_kmax()
    inside = {"delta": 0, "box": 0, "band": 0}
    for seed in range(1, 21):
        t, f, x = recording("two-mass", TWO_MASS, 8000, seed, f0=5.0, f1=80.0, amplitude=2.0)
        r = hs.identify(t, f, x, model="two-mass", quantization=Q, draws=1, seed=seed)
        lo, hi = r.k_max_interval
        inside["delta"] += lo <= k_true <= hi
        lo, hi = r.k_max_box_range
        inside["box"] += lo <= k_true <= hi
        lo, hi = r.k_max_band_interval
        inside["band"] += lo <= band_true <= hi
        assert r.k_max_interval[0] < r.k_max < r.k_max_interval[1]
    print(f"true K_max {k_true:.6g} N/m, over the band {band_true:.6g} N/m: inside {inside}")
    assert inside["box"] == 20, inside
    assert inside["delta"] >= 17 and inside["band"] >= 17, inside


def test_several_runs_are_fitted_together():
    truth = {"mass": 0.6, "damping": 7.5, "stiffness": 350.0}
    p = {"m": 0.6, "b": 7.5, "k": 350.0}
    runs = [recording("mass-spring-damper", p, 4000, s, f1=40.0) for s in (11, 12)]
    # the second run rests 2 mm further out
    runs[1] = (runs[1][0], runs[1][1], runs[1][2] + 2e-3)
    t, f, x = (list(c) for c in zip(*runs))
    both = hs.identify(t, f, x, quantization=Q, draws=1)
    one = hs.identify(*runs[0], quantization=Q, draws=1)
    assert len(both.position_offsets) == 2
    assert both.position_offsets[1] - both.position_offsets[0] == pytest.approx(2e-3, abs=5e-5)
    for name, v, se, se1, lo, hi in zip(both.names, both.values, both.standard_errors,
                                        one.standard_errors, both.ci_low, both.ci_high):
        assert abs(v / truth[name] - 1) < 0.02 and lo <= truth[name] <= hi, name
        # twice the data: standard errors about 1/√2 of one run's (0.707)
        assert 0.6 < se / se1 < 0.8, (name, se / se1)
    with pytest.raises(ValueError) as e:
        hs.identify(t, f[:1], x, draws=1)
    assert str(e.value).startswith("force: 1 runs, t has 2"), str(e.value)


def test_a_quantized_position_without_noise():
    """Q = 10 µm and no noise: the residuals are the rounding, of variance Q²/12."""
    truth = {"mass": 0.6, "damping": 7.5, "stiffness": 350.0}
    t, f, x = recording("mass-spring-damper", {"m": 0.6, "b": 7.5, "k": 350.0}, 4000, 3,
                        snr=None, f1=40.0)
    r = hs.identify(t, f, x, quantization=Q, draws=1)
    for name, v, lo, hi in zip(r.names, r.values, r.ci_low, r.ci_high):
        assert abs(v / truth[name] - 1) < 0.02 and lo <= truth[name] <= hi, name
    assert r.residual_rms == pytest.approx(Q / np.sqrt(12), rel=0.05)
    with pytest.raises(ValueError) as e:
        hs.identify(t, f, x, quantization=-1.0)
    assert str(e.value).startswith("quantization:"), str(e.value)


def tf3_response():
    """f (Hz), the exact sampled response of 2000/(s³ + 60s² + 4000s + 20000) at T = 1 ms
    (identify_data.py's), and the truth."""
    num, den = [2000.0], [1.0, 60.0, 4000.0, 20000.0]
    phi, gamma, c = identify_data.sampled(np.array(num), np.array(den), PERIOD)
    f = np.geomspace(0.5, 200.0, 60)
    z = np.exp(2j * np.pi * f * PERIOD)
    h = np.array([c @ np.linalg.solve(zi * np.eye(3) - phi, gamma) for zi in z])
    return f, h, {"b0": 2000.0, "a0": 20000.0, "a1": 4000.0, "a2": 60.0}


def noisy(h, seed, db, deg):
    rng = np.random.default_rng(seed + 104729)
    return h * 10 ** (rng.normal(0.0, db, h.size) / 20) \
        * np.exp(1j * np.radians(rng.normal(0.0, deg, h.size)))


def test_frequency_fit_starts_close_enough_at_half_a_db():
    """0.5 dB and 0.5° errors: every one of 300 realisations is fitted (Levy's start alone,
    without Sanathanan–Koerner's reweighting, left 113 of 500 such responses refused) and
    recovers the coefficients within 10 %."""
    f, h, truth = tf3_response()
    worst = 0.0
    for seed in range(1, 301):
        r = hs.identify_frequency(f, noisy(h, seed, 0.5, 0.5), period=PERIOD, model="tf:0/3",
                                  draws=1)
        worst = max(worst, max(abs(v / truth[n] - 1) for n, v in zip(r.names, r.values)))
    print(f"largest relative error {worst:.3g}")
    assert worst < 0.1


def test_frequency_fit_intervals_cover_the_truth():
    """1000 realisations of a measured response of 2000/(s³ + 60s² + 4000s + 20000) with
    0.1 dB and 1° errors (as identify_data.py --frequency-response draws them): each
    coefficient's 95 % interval holds the truth 93-97 % of the time (±2.9 binomial sd)."""
    f, h, truth = tf3_response()
    inside = dict.fromkeys(truth, 0)
    n = 1000
    for seed in range(1, n + 1):
        r = hs.identify_frequency(f, noisy(h, seed, 0.1, 1.0), period=PERIOD, model="tf:0/3",
                                  draws=1)
        for name, lo, hi in zip(r.names, r.ci_low, r.ci_high):
            inside[name] += lo <= truth[name] <= hi
    print({k: v / n for k, v in inside.items()})
    assert all(0.93 <= v / n <= 0.97 for v in inside.values()), inside


# the cases of benches/baseline/identify_coverage.py: simulator model and parameters, force,
# samples, identify's model and held parameters, the truth, the true loop
COVERAGE_CASES = {
    "msd": ("mass-spring-damper", {"m": 0.6, "b": 7.5, "k": 350.0}, {"f1": 40.0}, 4000,
            {}, {"mass": 0.6, "damping": 7.5, "stiffness": 350.0},
            lambda: hs.Loop(hs.MassSpringDamper(0.6, 7.5, 350.0), period=PERIOD)),
    "held": ("held-device", {"m_L": 0.1, "b_L": 1.5, "m_H": 1.0, "b_H": 6.0, "k_H": 350.0},
             {"kind": "prbs", "hold": 20, "amplitude": 2.0}, 4000,
             {"model": "held-device", "fixed": {"device-mass": 0.1, "device-damping": 1.5}},
             {"arm-mass": 1.0, "arm-damping": 6.0, "arm-stiffness": 350.0},
             lambda: hs.Loop.paper()),
    "two-mass": ("two-mass", TWO_MASS, {"f0": 5.0, "f1": 80.0, "amplitude": 2.0}, 8000,
                 {"model": "two-mass"},
                 {"motor-mass": 0.3, "motor-damping": 2.0, "handle-mass": 0.1,
                  "transmission-stiffness": 2300.0, "transmission-damping": 1.0}, None),
}


@pytest.mark.parametrize("case", sorted(COVERAGE_CASES))
def test_time_fit_intervals_cover_the_truth(case):
    """Per parameter and for K_max at B = 0, how often the 95 % interval holds the truth
    over seeded 40 dB realisations (10 µm quantization). 40 realisations here (the two-mass
    case, slower, only in the full run): at least
    34 of 40 (fewer has probability 0.3 % for a calibrated interval); with
    HAPSTAB_FULL_COVERAGE=1, 200 realisations and 182-197 of 200 (the binomial 99 % band
    around 95 %; 93-97 % is ±1.3 binomial sd at 200 and fails a calibrated interval one
    time in five)."""
    full = os.environ.get("HAPSTAB_FULL_COVERAGE") == "1"
    if case == "two-mass" and not full:
        pytest.skip("8000-sample recordings: with HAPSTAB_FULL_COVERAGE=1 only")
    n = 200 if full else 40
    sim, params, force, samples, kw, truth, true_loop = COVERAGE_CASES[case]
    if true_loop is None:
        k_true = true_two_mass_kmax()[0]
    else:
        k_true = hs.kmax(true_loop(), wall_damping=0.0).k_max
    inside = dict.fromkeys([*truth, "K_max"], 0)
    for seed in range(1, n + 1):
        t, f, x = recording(sim, params, samples, seed, **dict(force))
        r = hs.identify(t, f, x, quantization=Q, draws=1, **kw)
        for name, lo, hi in zip(r.names, r.ci_low, r.ci_high):
            if name in truth:
                inside[name] += lo <= truth[name] <= hi
        inside["K_max"] += r.k_max_interval[0] <= k_true <= r.k_max_interval[1]
    print(case, n, {k: f"{100 * v / n:.1f} %" for k, v in inside.items()})
    low, high = (182, 197) if full else (34, 40)
    assert all(low <= v <= high for v in inside.values()), inside
