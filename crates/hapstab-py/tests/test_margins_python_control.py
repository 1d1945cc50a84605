"""hapstab's margins against python-control's `stability_margins` on the same sampled loop,
and python-control's known discrete-time margin failures as hapstab computes them.

**Seeded loops.** Loops of every kind the Python API builds are drawn (a mass-spring-damper
from device + arm, a two-mass device, transfer functions of order 1–6, with or without an
actuator lag; every velocity estimator; whole delays 0–10 samples and fractional delays; T
log-uniform from 1e-5 to 1e-1 s) with a stable wall: B drawn first, K inside the stable K
interval that hapstab's `check` reports at that B (a fraction 0.05–0.7 of the way up it).
The open loop L(z) = (K + B·V(z))·H(z)·z⁻ᵈ is then built *independently of hapstab*
(pc_loops.py): python-control's own sample_system(ss(P), T, 'zoh') for whole delays, the
modified z-transform by scipy's expm for a fractional one, V(z) from the estimator's
definition. hapstab's L = (K·PK + B·PB)/P0 scales with (K, B), so its `gain_margin` (the
factor on K and B together) is python-control's `gm` of this L (its `stiffness_margin`, on K
alone, is not), `phase_margin_deg` its `pm`, `stability_margin` its `sm`, and the crossover
frequencies (Hz in hapstab, rad/s in python-control) its `wpc`, `wgc`.

**Unambiguous.** python-control reads gm at the crossing of the negative real axis whose gm is
nearest 1 (smallest |ln gm|), pm at the gain crossover of smallest |pm|. A loop qualifies when
that choice cannot mean two things and python-control's own numbers are sound:

1. on a dense grid of 2·10⁵ angles (half uniform, half log-spaced down to θ = 1e-9), each
   crossing refined by Brent's method, the runner-up crossing is 1 % farther in ln gm (0.5°
   in |pm|), ln gm is not within 1 % of 0, both chosen crossings lie at 1e-4 ≤ θ ≤ π − 0.01
   (python-control's polynomials in z lose digits near z = ±1), no two crossings lie within
   100 grid steps, and python-control's gm and pm are finite;
2. python-control's two methods, 'poly' (roots of polynomials in z) and 'frd' (its own
   frequency grid, interpolated), agree to 1e-7 on gm, pm, wpc and wgc;
3. python-control's own frequency response of L (its expanded transfer function in z, which
   both methods read) is within 1e-8 of the state-space evaluation at the two crossovers (at
   T ≈ 1e-5 the expanded polynomials lose up to 1e-6 of L, and python-control then reports
   the margins of a slightly different loop).

At least 100 loops must qualify; on each, hapstab's gm, pm, wgc and wpc equal python-control's
to REL = 1e-6 (measured: ≤ 1.1e-7) and the dense evaluation's to 1e-9 (measured: ≤ 2e-10).
sm is compared with python-control's where its two methods agree on it to 1e-7. On every drawn
loop, qualified or not, every gain crossover of the dense evaluation is one of hapstab's
(1e-6) and hapstab's min |1 + L| is not below the dense one by more than SM_ABS = 3e-9
(both evaluations' error at T ≈ 1e-5), nor above it by more (above is a missed global
minimum; the loops are printed).

Measured (python-control 0.10.2, seed below): 478 loops drawn, 127 without a stable wall at
the drawn B, 69 ambiguous, 122 where python-control's two methods disagree, 40 where its
transfer function is off, 120 qualified (every plant kind, estimator and delay kind); hapstab's
min |1 + L| within SM_ABS of the dense one on every drawn loop, within 4.6e-11 on the qualified.

**python-control's known failures** (the c2d of a lightly damped second-order plant and of
2/(s³ + 3s² + 2s)): see the docstrings of the two tests at the end.
"""

import math
import sys
import warnings

import control
import numpy as np
import pytest

import hapstab as hs
from conftest import ROOT, plant_of
from pc_loops import DenseMargins, SampledLoop, dense_grid

sys.path.insert(0, str(ROOT / "benches" / "baseline"))
import control_fixture as fx  # noqa: E402  (python-control and numpy only)

SEED = 2024_0465
QUALIFIED_MIN = 100
MAX_DRAWS = 600
REL = 1e-6
DENSE_REL = 1e-9
SM_REL = 1e-6
THETA_MIN, THETA_MARGIN = 1e-4, 0.01
GM_SEPARATION = 0.01  # in ln gm: the runner-up crossing's gain margin 1 % farther from 1
PM_SEPARATION_DEG = 0.5
GRID_POINTS = 2 * 10**5
METHODS_REL = 1e-7
EVAL_REL = 1e-8
SM_ABS = 3e-9
TWO_PI = 2 * math.pi


def velocity_spec(rng, t):
    """The fixture's estimators; a low-pass's cut-off 0.5 % to 30 % of the sampling rate when
    the fixture's 5 Hz floor lies above that (T > 0.06 s)."""
    if 0.3 / t > 5.0:
        return fx.velocity_spec(rng, t)
    spec = fx.velocity_spec(rng, 0.05)
    if spec.startswith("lowpass"):
        return f"lowpass:{fx.log_uniform(rng, 0.005 / t, 0.3 / t)!r}"
    if spec.startswith("iir"):
        return iir_at(spec, 0.05, t)
    return spec


def iir_at(spec, t_drawn, t):
    """An iir spec drawn at period t_drawn rescaled to t (its numerator is g/T·(…))."""
    b_txt, a_txt = spec[4:].split("/")
    b = [float(x) * t_drawn / t for x in b_txt.split(",")]
    return "iir:" + ",".join(repr(x) for x in b) + "/" + a_txt


def draw(rng, i):
    """One loop: (hapstab loop, SampledLoop, description)."""
    t = float(10 ** rng.uniform(-5, -1))
    category = ["mass_spring_damper", "two_mass", "transfer_function"][i % 3]
    lag = fx.log_uniform(rng, 0.05 * t, 3 * t) if rng.random() < 0.3 else 0.0
    if category == "mass_spring_damper":
        plant = fx.mass_spring_damper(rng)
    elif category == "two_mass":
        plant = fx.two_mass(rng)
    else:
        plant = fx.transfer_function(rng, int(rng.integers(1, 6 if lag > 0 else 7)), t)
    d = int(rng.integers(0, 11))
    lam = float(rng.uniform(0.05, 0.95)) if rng.random() < 0.4 else 0.0
    velocity = velocity_spec(rng, t)
    lp = hs.Loop(plant_of(plant), period=t, delay=(d + lam) * t, velocity=velocity, force_lag=lag)
    p = fx.continuous_plant(plant)
    if lag > 0:
        p = p * control.tf([1.0], [lag, 1.0])
    sl = SampledLoop(p, t, d, lam, fx.velocity_tf(velocity, t))
    desc = dict(category=category, plant=plant, period=t, d=d, lam=lam, velocity=velocity, lag=lag)
    return lp, sl, desc


def stable_wall(rng, lp):
    """B drawn on the loop's scale, K inside the stable K interval at B; None if none."""
    k_unit, b_unit = lp.wall_scale
    for _ in range(4):
        b = float(rng.uniform(0.0, 0.3)) * b_unit
        iv = hs.check(lp, 0.0, b).k_interval
        if iv is not None and iv[1] > max(iv[0], 0.0) and math.isfinite(iv[1]):
            lo = max(iv[0], 0.0)
            return lo + float(rng.uniform(0.05, 0.7)) * (iv[1] - lo), b
    return None


def python_control(loop, method="best"):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return [float(x) for x in control.stability_margins(loop, method=method)]


def methods_agree(poly, frd, rel_tol):
    """python-control's 'poly' (roots of polynomials in z) and 'frd' (a frequency response
    interpolated on its own grid) methods give the same gm, pm, wpc, wgc (indices 0, 1, 3,
    4) to rel_tol."""
    return all(
        math.isfinite(poly[j]) and math.isfinite(frd[j]) and abs(poly[j] - frd[j]) <= rel_tol * abs(poly[j])
        for j in (0, 1, 3, 4)
    )


def selected(values, score, separation):
    """The index python-control picks (the smallest score), or None when the runner-up is
    within `separation` of it."""
    if not values:
        return None
    order = sorted(range(len(values)), key=lambda j: score(values[j]))
    if len(order) > 1 and score(values[order[1]]) < score(values[order[0]]) + separation:
        return None
    return order[0]


def in_range(theta):
    return THETA_MIN <= theta <= math.pi - THETA_MARGIN


def unambiguous(dense, pc):
    """(θ of the phase crossover python-control reads gm at, θ of the gain crossover it reads
    pm at), or None when python-control's choice is ambiguous (module doc)."""
    if not all(math.isfinite(x) for x in (pc[0], pc[1])):
        return None
    # every crossing of the negative real axis, z = ±1 included, as python-control lists them
    ends = [t for t, v in ((0.0, dense.at_zero), (math.pi, dense.at_pi)) if math.isfinite(abs(v)) and v.real < 0]
    phases = dense.phase + ends
    gms = [dense.gm(t) if 0 < t < math.pi else -1 / (dense.at_zero if t == 0 else dense.at_pi).real for t in phases]
    ip = selected(gms, lambda g: abs(math.log(g)), GM_SEPARATION)
    pms = [dense.pm(t) for t in dense.gain]
    ig = selected(pms, abs, PM_SEPARATION_DEG)
    if ip is None or ig is None or abs(math.log(gms[ip])) < GM_SEPARATION:
        return None
    tp, tg = phases[ip], dense.gain[ig]
    if not (in_range(tp) and in_range(tg)):
        return None
    crossings = sorted(dense.phase + dense.gain)
    gaps = np.diff(crossings) if len(crossings) > 1 else np.array([math.inf])
    if np.min(gaps) < 100 * dense.grid_gap:
        return None
    return tp, tg


def rel(a, b):
    return abs(a - b) / abs(b)


def test_margins_agree_with_python_control_on_seeded_loops():
    rng = np.random.default_rng(SEED)
    grid = dense_grid(GRID_POINTS)
    stats = {"drawn": 0, "no_stable_wall": 0, "ambiguous": 0, "methods_disagree": 0, "tf_evaluation_off": 0, "qualified": 0, "sm_compared": 0}
    dense_failures, missed = [], []
    worst = {k: 0.0 for k in ("gm", "pm", "wgc", "wpc", "sm_pc", "gm_dense", "pm_dense", "wgc_dense", "wpc_dense", "sm_dense")}
    kinds = {}
    failures = []
    i = 0
    while stats["qualified"] < QUALIFIED_MIN + 20 and i < MAX_DRAWS:
        lp, sl, desc = draw(rng, i)
        i += 1
        stats["drawn"] += 1
        wall = stable_wall(rng, lp)
        if wall is None:
            stats["no_stable_wall"] += 1
            continue
        k, b = wall
        m = hs.margins(lp, k, b)
        assert m.stable, (desc, k, b)
        loop = sl.control_loop(k, b)
        pc, poly, frd = (python_control(loop, meth) for meth in ("best", "poly", "frd"))
        dense = DenseMargins(lambda th: sl.value(k, b, th), grid)
        dense_failures += dense_check(m, dense, desc, k, b)
        if sm_missed(m, dense):
            missed.append((i - 1, desc, k, b, m.stability_margin, m.stability_margin_hz, dense.sm, pc[2]))
        picked = unambiguous(dense, pc)
        if picked is None:
            stats["ambiguous"] += 1
            continue
        tp, tg = picked
        if not methods_agree(poly, frd, METHODS_REL):
            stats["methods_disagree"] += 1
            continue
        if evaluation_error(loop, sl, k, b, (tp, tg)) > EVAL_REL:
            stats["tf_evaluation_off"] += 1
            continue
        stats["qualified"] += 1
        key = (desc["category"], desc["velocity"].split(":")[0], "fractional" if desc["lam"] else "whole")
        kinds[key] = kinds.get(key, 0) + 1
        t = desc["period"]
        gm_h = m.gain_margin if pc[0] > 1 else m.gain_margin_lower
        got = {
            "gm": gm_h, "pm": m.phase_margin_deg,
            "wgc": m.gain_crossover_hz * TWO_PI, "wpc": m.phase_crossover_hz * TWO_PI,
        }
        want_pc = {"gm": pc[0], "pm": pc[1], "wpc": pc[3], "wgc": pc[4]}
        want_dense = {
            "gm": dense.gm(tp), "pm": dense.pm(tg), "wgc": tg / t, "wpc": tp / t,
        }
        bad = []
        for name in got:
            r_pc, r_dense = rel(got[name], want_pc[name]), rel(got[name], want_dense[name])
            worst[name] = max(worst[name], r_pc)
            worst[name + "_dense"] = max(worst[name + "_dense"], r_dense)
            if r_pc > REL or r_dense > DENSE_REL:
                bad.append((name, got[name], want_pc[name], want_dense[name]))
        if not missed or missed[-1][0] != i - 1:
            worst["sm_dense"] = max(worst["sm_dense"], abs(m.stability_margin - dense.sm))
        if rel(poly[2], frd[2]) <= METHODS_REL:
            stats["sm_compared"] += 1
            if not (missed and missed[-1][0] == i - 1):
                worst["sm_pc"] = max(worst["sm_pc"], rel(m.stability_margin, pc[2]))
            if rel(m.stability_margin, pc[2]) > REL and not (missed and missed[-1][0] == i - 1):
                bad.append(("sm", m.stability_margin, pc[2], dense.sm))
        if bad:
            failures.append((i - 1, desc, k, b, bad))
    print(f"\npython-control {control.__version__}: {stats}")
    print("worst relative differences:", {k: f"{v:.2e}" for k, v in worst.items()})
    print("qualified by kind:", dict(sorted(kinds.items())))
    assert not dense_failures, "\n".join(map(str, dense_failures))
    assert stats["qualified"] >= QUALIFIED_MIN, stats
    assert not failures, "\n".join(map(str, failures))
    assert not missed, (
        f"hapstab's stability_margin above the dense min |1 + L| on {len(missed)} of "
        f"{stats['drawn']} loops:\n" + "\n".join(map(str, missed))
    )


def evaluation_error(loop, sl, k, b, thetas):
    """The relative error of python-control's own frequency response of L (its expanded
    transfer function in z, which both of its methods read the margins from) against the
    state-space evaluation, at the crossovers."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tf = control.tf(loop)
    th = np.asarray(thetas)
    mine = sl.value(k, b, th)
    theirs = np.array([complex(tf(np.exp(1j * t))) for t in th])
    return float(np.max(np.abs(theirs - mine) / np.abs(mine)))


def dense_check(m, dense, desc, k, b):
    """hapstab against the dense evaluation on every loop (qualified or not): every gain
    crossover found there is one of hapstab's, with its phase margin, and sm, to 1e-9."""
    t = desc["period"]
    hz = sorted(f for kind, f, _ in m.crossings if kind == "gain")
    bad = []
    for th in dense.gain:
        f = th / (TWO_PI * t)
        near = min(hz, key=lambda x: abs(x - f)) if hz else math.nan
        # the same crossover to 1e-6: at T ≈ 1e-5 the double-precision state-space evaluation
        # itself is off by a few 1e-9 in ln|L| (on the transfer function of order 5 at
        # T = 1.03e-5, d = 3, a 40-digit mpmath evaluation of the same ZOH puts ln|L| = −3e-15
        # at hapstab's crossover, −3.7e-9 at the dense one's, 2e-9 away)
        if not abs(near - f) <= REL * f:
            bad.append(("gain crossover", f, near))
    return [(desc, k, b, bad)] if bad else []


def sm_missed(m, dense):
    """True when hapstab's min |1 + L| lies above the dense evaluation's by more than both
    evaluations' error (SM_ABS: L is evaluated to about 1e-9 absolute at T ≈ 1e-5, where the
    loop's poles crowd z = 1); below it by more is a failure of the dense evaluation's check."""
    assert m.stability_margin >= dense.sm - SM_ABS, (m.stability_margin, dense.sm)
    return m.stability_margin > dense.sm + SM_ABS


# --- python-control's known discrete-time margin failures --------------------------------------

ISSUE_GRID = 10**6
ISSUE_REL = 1e-9


def issue_case(num, den, period):
    """hapstab's margins of L = 1·P_zoh(z) (a TransferFunction plant, the wall K = 1 N/m, B = 0:
    L = (K·PK + B·PB)/P0 = K·num/den of the plant's ZOH), the dense evaluation of the same L
    from python-control's ss(P) sampled by scipy's expm (pc_loops.SampledLoop, 10⁶ angles, every
    crossing refined by brentq), and python-control's answers on c2d(P, T, 'zoh')."""
    lp = hs.Loop(hs.TransferFunction(num, den), period=period)
    m = hs.margins(lp, 1.0, 0.0)
    assert m.stable
    p = control.tf(num, den)
    sl = SampledLoop(p, period, 0, 0.0, control.tf([1.0, -1.0], [period, 0.0], period))
    dense = DenseMargins(lambda th: sl.value(1.0, 0.0, th), dense_grid(ISSUE_GRID))
    pd = control.c2d(p, period, "zoh")
    pcs = {meth: python_control(pd, meth) for meth in ("best", "poly", "frd")}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        pcs["margin"] = [float(x) for x in control.margin(pd)]
    return m, dense, pcs


def assert_dense(m, dense, period):
    """hapstab = the dense evaluation to 1e-9: one gain and one phase crossover."""
    assert len(dense.gain) == 1 and len(dense.phase) == 1, (dense.gain, dense.phase)
    tg, tp = dense.gain[0], dense.phase[0]
    for got, want in [
        (m.gain_margin, dense.gm(tp)),
        (m.phase_crossover_hz * TWO_PI, tp / period),
        (m.phase_margin_deg, dense.pm(tg)),
        (m.gain_crossover_hz * TWO_PI, tg / period),
        (m.stability_margin, dense.sm),
    ]:
        assert rel(got, want) <= ISSUE_REL, (got, want)


def test_issue_465_third_order_with_integrator():
    """2/(s³ + 3s² + 2s) sampled at Ts = 0.05 s (python-control issue #465, "control.margin()
    gives wrong result", python-control/python-control#465; fixed by pull request #469,
    "Stability margins for discrete time systems", and #566, which added the 'frd' fallback).

    MATLAB (printed in the issue): GM 2.79 at 1.36 rad/s, PM 31.5° at 0.749 rad/s.
    python-control 0.8.3 printed (gm, pm, wpc, wgc) = (31.505480557979414, inf,
    3.7736323313549196, nan): the phase margin in the gm slot, no gain crossover. python-control
    0.10.2 gives gm 2.792786201, pm 31.541575274°, wpc 1.363970137, wgc 0.749338711 rad/s with
    its default method (it falls back to 'frd' here, warning of numerical inaccuracy), and
    sm 0.4178369 ('frd', its grid's minimum) or 0.4180410 ('poly': a local minimum only — the
    dense evaluation's min |1 + L| is the former, refined). Those figures are recorded, not
    asserted: the failure is gone in current versions.

    hapstab (K = 1, B = 0 on the TransferFunction plant, so L = P_zoh): gain_margin is the
    factor on K and B together, python-control's gm (the stiffness_margin is the same here
    since B = 0), read at phase_crossover_hz; phase_margin_deg at gain_crossover_hz.
    """
    t = 0.05
    m, dense, pcs = issue_case([2.0], [1.0, 3.0, 2.0, 0.0], t)
    print("\n#465 hapstab", m.gain_margin, m.phase_crossover_hz * TWO_PI, m.phase_margin_deg,
          m.gain_crossover_hz * TWO_PI, m.stability_margin)
    print("#465 python-control", control.__version__, pcs)
    # MATLAB's printed values, to their printed digits
    assert round(m.gain_margin, 2) == 2.79
    assert round(m.phase_crossover_hz * TWO_PI, 2) == 1.36
    assert round(m.phase_margin_deg, 1) == 31.5
    assert round(m.gain_crossover_hz * TWO_PI, 3) == 0.749
    assert m.stiffness_margin == pytest.approx(m.gain_margin, rel=1e-12)
    assert_dense(m, dense, t)


def test_issue_523_lightly_damped_second_order():
    """1.1·ωn²/(s² + 2ζωn s + ωn²), ωn = 2π rad/s, ζ = 0.2, c2d with Ts = 0.05 s (python-control
    issue #523, "stability_margins doesn't find gain=1 crossover frequency correctly for DT
    systems", python-control/python-control#523; pull request #566 added the 'frd' fallback
    for it). In the issue python-control drew no gain crossover and no phase margin on
    bode_plot(plantdisc, margins=True), where MATLAB's margin() showed both (its values are
    in a screenshot only, so the dense evaluation is the referee here).

    python-control 0.10.2 gives gm 2.384196293 at 11.71187198 rad/s, pm 18.16103558° at
    8.747771911 rad/s, sm 0.2695356630 ('poly', its default here), the 'frd' method agreeing to
    3e-9 (recorded, not asserted). hapstab: K = 1, B = 0, L = P_zoh as in the case above.
    """
    t, wn, zeta = 0.05, 2 * math.pi, 0.2
    m, dense, pcs = issue_case([1.1 * wn**2], [1.0, 2 * zeta * wn, wn**2], t)
    print("\n#523 hapstab", m.gain_margin, m.phase_crossover_hz * TWO_PI, m.phase_margin_deg,
          m.gain_crossover_hz * TWO_PI, m.stability_margin)
    print("#523 python-control", control.__version__, pcs)
    assert_dense(m, dense, t)
    # |L| = 1.1 > 1 at ω = 0 and falls through 1 once past the resonance: one gain crossover
    assert m.peak_gain > 1.1 and [k for k, _, _ in m.crossings].count("gain") == 1
