"""passivity and margins: Colgate's condition against its closed forms, the numbers of the
command line (`hapstab passivity --json`, `hapstab check --json`) on seeded loops, and the
margins' meaning (the wall scaled by its gain margin crosses the stability boundary)."""

import json
import math
import subprocess

import numpy as np
import pytest

import hapstab as hs

# Closed forms: the library evaluates the condition without cancellation and finds its
# maximum exactly, so only rounding separates it from the formula.
CLOSED_REL = 1e-12
# The gain margin's factor is exact to rounding; 1e-6 either side is far outside that and far
# inside any change of the verdict's neighbourhood.
CROSS = 1e-6
SEED = 13_2008


def rel_close(got, want, rel=CLOSED_REL):
    assert abs(got - want) <= rel * abs(want), (got, want, (got - want) / want)


# --- Colgate's condition: closed forms ------------------------------------------------------


def test_backward_difference_without_delay_is_eq_28():
    """b_required = KT/2 + |B| (eq. 28), binding at ωT = π for B > 0 and at ω = 0 for B < 0."""
    rng = np.random.default_rng(SEED)
    for _ in range(40):
        m, b, k = rng.uniform(0.05, 3.0), rng.uniform(0.0, 20.0), rng.uniform(0.0, 1e3)
        period = 10 ** rng.uniform(-4.5, -2.0)
        lp = hs.Loop(hs.MassSpringDamper(m, b, k), period=period)
        wk, wb = rng.uniform(0.0, 5e4), rng.uniform(-50.0, 50.0)
        p = hs.passivity(lp, wk, wb)
        rel_close(p.b_required, wk * period / 2 + abs(wb))
        assert p.binding_theta == (math.pi if wb > 0 else 0.0), (wk, wb, p.binding_theta)
        assert p.device_damping == b
        assert p.verdict == ("passive" if b > p.b_required else "not_passive")
        assert p.meets == (p.verdict == "passive")


def test_normalized_loop_is_delta_above_alpha_half_plus_abs_beta():
    """Eq. (28) in Table I's units: δ > α/2 + |β|."""
    rng = np.random.default_rng(SEED + 1)
    for _ in range(20):
        delta = rng.uniform(0.0, 0.5)
        lp = hs.Loop.normalized(gamma=rng.uniform(0, 0.01), delta=delta)
        a, b = rng.uniform(0.0, 2.0), rng.uniform(-1.0, 1.0)
        p = hs.passivity(lp, alpha=a, beta=b)
        rel_close(p.b_required, a / 2 + abs(b))
        assert p.device_damping == delta
        assert p.verdict == ("passive" if delta > a / 2 + abs(b) else "not_passive")


def test_first_order_low_pass_with_nonnegative_damping():
    """v_k = a·v_{k−1} + (1 − a)(y_k − y_{k−1})/T, a = exp(−2π f_c T) (the library's
    definition, model.rs): b_required = KT/2 + B(1 − a)/(1 + a) for B ≥ 0, at ωT = π."""
    rng = np.random.default_rng(SEED + 2)
    for _ in range(40):
        period = 10 ** rng.uniform(-4.0, -2.5)
        fc = float(10 ** rng.uniform(0.5, math.log10(0.45 / period)))
        lp = hs.Loop(hs.MassSpringDamper(1.1, 7.5, 350.0), period=period, velocity=f"lowpass:{fc!r}")
        wk, wb = rng.uniform(0.0, 5e4), rng.uniform(0.0, 50.0)
        a = math.exp(-2 * math.pi * fc * period)
        p = hs.passivity(lp, wk, wb)
        rel_close(p.b_required, wk * period / 2 + wb * (1 - a) / (1 + a))


def test_whole_sample_delay_without_damping():
    """d samples of delay and B = 0: b_required = K(T/2 + dT), binding at ω = 0."""
    rng = np.random.default_rng(SEED + 3)
    for _ in range(40):
        period = 10 ** rng.uniform(-4.0, -2.0)
        d = int(rng.integers(0, 30))
        lp = hs.Loop(hs.MassSpringDamper(1.1, 7.5, 350.0), period=period, delay_samples=d)
        wk = rng.uniform(1.0, 5e4)
        p = hs.passivity(lp, wk, 0.0)
        rel_close(p.b_required, wk * (period / 2 + d * period))
        assert p.binding_theta == 0.0


def test_device_damping_replaces_the_plants_and_scales_the_passive_region():
    lp = hs.Loop.paper(period=1e-3, delay=1e-3)
    own = hs.passivity(lp, 2e3, 1.0)
    assert own.device_damping == 1.5  # the device's own b_L, not b = b_L + b_H of eq. (1)
    assert own.effective_damping == 7.5
    more = hs.passivity(lp, 2e3, 1.0, device_damping=15.0)
    assert more.b_required == own.b_required and more.stable == own.stable
    assert more.device_damping == 15.0 and more.effective_damping is None
    assert more.verdict == ("passive" if 15.0 > own.b_required else "not_passive")
    # the passive region is homogeneous in b: ten times the damping, ten times the K_max
    rel_close(more.passive_region.k_max, 10 * own.passive_region.k_max, 1e-9)
    v = own.passive_region.vertices
    assert v.dtype == np.float64 and v.ndim == 2 and v.shape[1] == 2 and len(v) > 3


def test_passivity_counts_the_devices_own_damping_not_the_arms():
    # 0.25 kg, 2 Ns/m device held by the default arm (b_H = 6 Ns/m), T = 1 ms, t_d = 0.4 ms,
    # K = 5 kN/m, B = 5 Ns/m: the requirement lies between b_L = 2 and b_L + b_H = 8, so the
    # device alone is not passive and eq. (28) with the arm counted is
    lp = hs.Loop.paper(device_mass=0.25, device_damping=2.0, period=1e-3, delay=4e-4)
    p = hs.passivity(lp, 5000.0, 5.0)
    assert p.device_damping == 2.0 and p.verdict == "not_passive"
    assert p.effective_damping == 8.0
    assert 2.0 < p.b_required < 8.0 and p.effective_verdict == "passive"
    bare = hs.passivity(hs.Loop.paper(device_mass=0.25, device_damping=2.0, arm_mass=0.0,
                                      arm_damping=0.0, arm_stiffness=0.0,
                                      period=1e-3, delay=4e-4), 5000.0, 5.0)
    assert bare.b_required == p.b_required and bare.effective_damping is None
    assert hs.MassSpringDamper.from_device_and_arm(device_damping=2.0).device_damping == 2.0


def test_actuator_lag_is_not_applicable_even_with_a_device_damping():
    lp = hs.Loop(hs.MassSpringDamper(1.1, 7.5, 350.0), force_lag=2e-4)
    p = hs.passivity(lp, 2e3, 1.0, device_damping=10.0)
    assert p.verdict == "not_applicable" and p.meets is None and p.device_damping is None
    assert "lag" in p.note and p.passive_region is None


# --- the command line's numbers ---------------------------------------------------------------


def cli_loops(rng):
    """Seeded loops with the command-line flags that describe the same loop (floats passed by
    repr, which both sides parse to the same double)."""
    r = lambda lo, hi: float(rng.uniform(lo, hi))  # noqa: E731
    out = []
    dm, db, am, ab, ak, t = r(0.05, 0.3), r(0.5, 3), r(0.5, 2), r(2, 10), r(100, 600), 1e-3
    td = int(rng.integers(0, 4)) * t
    out.append((
        hs.Loop.paper(device_mass=dm, device_damping=db, arm_mass=am, arm_damping=ab,
                      arm_stiffness=ak, period=t, delay=td),
        ["--device-mass", dm, "--device-damping", db, "--arm-mass", am, "--arm-damping", ab,
         "--arm-stiffness", ak, "--period", t, "--delay-time", td],
    ))
    m, b, k, t, fc = r(0.5, 2), r(2, 10), r(0, 500), r(2e-4, 1e-3), r(50, 300)
    td = r(0, 3) * t  # fractional delay
    out.append((
        hs.Loop(hs.MassSpringDamper(m, b, k), period=t, delay=td, velocity=f"lowpass:{fc!r}"),
        ["--mass", m, "--damping", b, "--stiffness", k, "--period", t, "--delay-time", td,
         "--velocity", f"lowpass:{fc!r}"],
    ))
    m, b, k, n = r(0.5, 2), r(2, 10), r(0, 500), int(rng.integers(2, 6))
    out.append((
        hs.Loop(hs.MassSpringDamper(m, b, k), period=1e-3, delay=1e-3, velocity=f"average:{n}"),
        ["--mass", m, "--damping", b, "--stiffness", k, "--period", 1e-3, "--delay-time", 1e-3,
         "--velocity", f"average:{n}"],
    ))
    c, m, b, k, td = r(0.5, 2), r(0.5, 2), r(2, 10), r(0, 500), r(0, 2.5e-3)
    out.append((
        hs.Loop(hs.TransferFunction([c], [m, b, k]), period=1e-3, delay=td),
        ["--plant-num", c, "--plant-den", f"{m!r},{b!r},{k!r}", "--period", 1e-3,
         "--delay-time", td],
    ))
    jm, kt, bm, hm = r(0.05, 0.2), r(2e4, 1e5), r(1, 5), r(0.02, 0.1)
    out.append((
        hs.Loop(hs.TwoMass(jm, kt, motor_damping=bm, handle_mass=hm), period=1e-3),
        ["--motor-mass", jm, "--transmission-stiffness", kt, "--motor-damping", bm,
         "--handle-mass", hm, "--period", 1e-3],
    ))
    return out


def run_cli(exe, command, flags, wall):
    args = [str(exe), command, *map(str, flags)]
    args += ["--wall-stiffness", repr(wall[0]), "--wall-damping", repr(wall[1]), "--json"]
    done = subprocess.run(args, check=True, capture_output=True, text=True)
    return json.loads(done.stdout)


def walls(lp, rng):
    """A stable wall (K a seeded fraction of K_max at a seeded B) and one beyond K_max."""
    b = float(rng.uniform(0.5, 5.0))
    k_max = hs.kmax(lp, wall_damping=b).k_max
    assert k_max is not None and k_max > 0
    return [(float(rng.uniform(0.2, 0.8)) * k_max, b), (1.3 * k_max, b)]


@pytest.fixture(scope="module")
def cases(hapstab_cli):
    rng = np.random.default_rng(SEED + 4)
    return [(lp, flags, w) for lp, flags in cli_loops(rng) for w in walls(lp, rng)]


def test_passivity_equals_the_command_line(hapstab_cli, cases):
    for lp, flags, wall in cases:
        want = run_cli(hapstab_cli, "passivity", flags, wall)
        got = hs.passivity(lp, *wall)
        for key in ("b_required", "binding_frequency_hz", "binding_theta", "dc_stiffness",
                    "device_damping", "meets", "verdict", "stable"):
            assert getattr(got, key) == want[key], (flags, wall, key, getattr(got, key), want[key])
        assert got.note == want.get("note")
        gr, wr = got.passive_region, want["passive_region"]
        for key in ("k_max", "b_at_k_max", "area", "bounded"):
            assert getattr(gr, key) == wr[key], (flags, key)
        np.testing.assert_array_equal(gr.vertices, np.array(wr["vertices"]))
    assert {c[0].velocity.split(":")[0] for c in cases} >= {"backward", "lowpass", "average"}


def test_margins_equal_the_command_line(hapstab_cli, cases):
    seen_stable = seen_unstable = 0
    for lp, flags, wall in cases:
        want = run_cli(hapstab_cli, "check", flags, wall)
        got = hs.margins(lp, *wall)
        checked = hs.check(lp, *wall)
        assert got.stable == want["stable"] == checked.stable == checked.margins.stable
        for key in ("gain_margin", "gain_margin_lower", "phase_crossover_hz",
                    "stiffness_margin", "stiffness_margin_lower", "stiffness_crossover_hz",
                    "phase_margin_deg", "gain_crossover_hz", "delay_margin",
                    "delay_margin_frequency_hz", "delay_margin_pm_over_wc",
                    "delay_margin_at_least", "stability_margin", "stability_margin_hz",
                    "peak_gain", "peak_gain_hz"):
            assert getattr(got, key) == want.get(key), (flags, wall, key)
            # check's margins are the same report
            assert getattr(checked.margins, key) == want.get(key), (flags, wall, key)
        want_crossings = [(c["kind"], c["frequency_hz"], c["value"]) for c in want["crossings"]]
        assert got.crossings == want_crossings == checked.margins.crossings
        assert got.notes == want["margin_notes"] == checked.margins.notes
        if got.stable:
            seen_stable += 1
            assert got.gain_margin > 1
        else:
            seen_unstable += 1
            assert got.gain_margin is None and got.delay_margin is None and got.notes
    assert seen_stable >= 5 and seen_unstable >= 3


# --- the margins' meaning -----------------------------------------------------------------


def margin_loops():
    yield hs.Loop.paper(period=1e-3, delay=1e-3), [(2e3, 1.0), (6e3, 4.0), (1e3, 0.0)]
    yield hs.Loop.paper(period=5e-4, delay=0.0), [(1e4, 2.0), (3e4, 10.0)]
    lp = hs.Loop(hs.MassSpringDamper(1.1, 7.5, 350.0), period=1e-3, delay=1.4e-3)
    yield lp, [(2e3, 1.5), (5e3, 3.0)]


def test_k_times_the_gain_margin_crosses_the_boundary():
    n = 0
    for lp, ws in margin_loops():
        for k, b in ws:
            m = hs.margins(lp, k, b)
            assert m.stable and m.stiffness_margin is not None, (k, b, m.notes)
            g = m.stiffness_margin
            assert hs.check(lp, k * g * (1 - CROSS), b).stable, (k, b, g)
            assert not hs.check(lp, k * g * (1 + CROSS), b).stable, (k, b, g)
            gkb = m.gain_margin
            assert hs.check(lp, k * gkb * (1 - CROSS), b * gkb * (1 - CROSS)).stable
            assert not hs.check(lp, k * gkb * (1 + CROSS), b * gkb * (1 + CROSS)).stable
            n += 1
    assert n == 7


def test_the_stiffness_crossover_is_the_angle_of_the_boundary_root_pair():
    for lp, ws in margin_loops():
        for k, b in ws:
            m = hs.margins(lp, k, b)
            roots = hs.check(lp, k * m.stiffness_margin, b).roots
            top = roots[np.argmax(np.abs(roots))]
            assert abs(abs(top) - 1) < 1e-6, (k, b, top)
            f = abs(np.angle(top)) / (2 * math.pi * lp.period)
            assert abs(f - m.stiffness_crossover_hz) <= 1e-6 * max(f, 1.0), (f, m)


def test_adding_the_delay_margin_crosses_the_boundary():
    plant = hs.MassSpringDamper(1.1, 7.5, 350.0)
    for td, (k, b) in [(0.0, (5e3, 3.0)), (1.4e-3, (2e3, 1.5)), (1e-3, (1e3, 0.5))]:
        m = hs.margins(hs.Loop(plant, period=1e-3, delay=td), k, b)
        dm = m.delay_margin
        assert dm is not None and dm > 0, m.notes
        before = hs.Loop(plant, period=1e-3, delay=td + dm * (1 - CROSS))
        after = hs.Loop(plant, period=1e-3, delay=td + dm * (1 + CROSS))
        assert hs.check(before, k, b).stable and not hs.check(after, k, b).stable, (td, k, b, dm)


def test_margins_of_a_wall_that_is_not_stable_are_withheld():
    lp = hs.Loop.paper(period=1e-3, delay=1e-3)
    k = hs.kmax(lp, wall_damping=1.0).k_max
    m = hs.margins(lp, 1.5 * k, 1.0)
    assert not m.stable
    assert m.gain_margin is None and m.phase_margin_deg is None and m.delay_margin is None
    assert m.notes == ["the wall is not stable: margins are defined for stable walls"]


def test_alpha_beta_give_the_same_margins_as_k_b():
    lp = hs.Loop.paper(period=1e-3, delay=1e-3)
    a, b = 0.01, 0.02
    kpa, bpb = lp.wall_scale
    by_units = hs.margins(lp, alpha=a, beta=b)
    by_si = hs.margins(lp, a * kpa, b * bpb)
    assert by_units.gain_margin == by_si.gain_margin
    assert by_units.delay_margin == by_si.delay_margin


# --- bad arguments -----------------------------------------------------------------------------

LOOP = hs.Loop.paper()
BAD = [
    ("wall_stiffness", lambda: hs.passivity(LOOP, float("nan"), 1.0)),
    ("wall_damping", lambda: hs.passivity(LOOP, 1e3, float("inf"))),
    ("wall_stiffness, wall_damping", lambda: hs.passivity(LOOP, 1e3)),
    ("alpha, beta", lambda: hs.passivity(LOOP, alpha=0.1)),
    ("alpha", lambda: hs.passivity(LOOP, alpha=float("nan"), beta=0.1)),
    ("device_damping", lambda: hs.passivity(LOOP, 1e3, 1.0, device_damping=-1.0)),
    ("device_damping", lambda: hs.passivity(LOOP, 1e3, 1.0, device_damping=float("nan"))),
    ("velocity", lambda: hs.passivity(hs.Loop(hs.MassSpringDamper(1.0, 5.0), velocity="iir:1,-1/1,-1.5"), 1e3, 1.0)),
    ("wall_stiffness", lambda: hs.margins(LOOP, float("nan"), 1.0)),
    ("wall_damping", lambda: hs.margins(LOOP, 1e3, float("-inf"))),
    ("wall_stiffness, wall_damping", lambda: hs.margins(LOOP, wall_damping=1.0)),
    ("beta", lambda: hs.margins(LOOP, alpha=0.1, beta=float("nan"))),
    ("wall_stiffness, wall_damping, alpha, beta", lambda: hs.margins(LOOP, 1e3, 1.0, alpha=0.1, beta=0.1)),
    ("alpha, beta", lambda: hs.margins(hs.Loop(hs.TwoMass(0.1, 1e4)), alpha=0.1, beta=0.1)),
]


@pytest.mark.parametrize("name, call", BAD, ids=[f"{i}-{n}" for i, (n, _) in enumerate(BAD)])
def test_bad_argument_names_the_keyword(name, call):
    with pytest.raises(ValueError) as e:
        call()
    msg = str(e.value)
    assert msg.startswith(name + ": "), msg
    assert "\n" not in msg
