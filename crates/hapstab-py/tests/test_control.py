"""Cross-check against python-control: spectral radius to 1e-9 on 100 seeded loops.

The loops are drawn by the generator of benches/baseline/control_fixture.py (plants of every
kind with or without actuator lag, whole delays 0–10 samples, every velocity estimator) and
closed by python-control alone through its state-space route (sample_system(ss(P), T,
'zoh'), the delay z^(−d), the wall K + B·V(z), feedback, poles); hapstab builds the same loop
from the same numbers through the Python API. Walls are drawn away from the boundary.

As in crates/hapstab/tests/engine/python_control.rs, loops whose dominant root is ill-conditioned
in the coefficients of p(z) (condition number κ with κ·ε > 1e-9, several roots crowding
z = 1) are set aside: no root finder working from those coefficients reaches 1e-9. At most
a tenth of the drawn loops may be set aside. Where hapstab and python-control differ by more
than 1e-9, the loop is refereed in mpmath at 60 digits (benches/baseline/control_mpmath.py):
hapstab must match the referee, and python-control may be the one that is off (it is on a few
strongly unstable loops, as the Rust-side test found) on at most a twentieth of the loops.
"""

import math
import sys

import numpy as np
import hapstab as hs
from conftest import ROOT, plant_of

sys.path.insert(0, str(ROOT / "benches" / "baseline"))
import control_fixture  # noqa: E402  (python-control and numpy only)
import control_mpmath  # noqa: E402  (mpmath only)

LOOPS = 100
SEED = 15_2008
RADIUS_REL = 1e-9
CONDITION_LIMIT = RADIUS_REL / np.finfo(float).eps
MAX_SET_ASIDE = 0.1
MAX_CONTROL_OFF = 0.05


def hapstab_loop(case):
    return hs.Loop(
        plant_of(case["plant"]),
        period=case["period"],
        delay_samples=case["delay"],
        velocity=case["velocity"],
        force_lag=case["force_lag"],
    )


def wall(rng, case):
    """K from 1e-4 to 0.3 of m/T², B up to m/T/(d + 1): mostly near the stable region."""
    m = control_fixture.reference_mass(case["plant"], case["period"])
    t = case["period"]
    k = m / t**2 * 10 ** rng.uniform(-4, math.log10(0.3))
    b = rng.uniform(0, 1) * m / t / (case["delay"] + 1)
    return float(k), float(b)


def condition(coeffs, z):
    """κ of the root z's modulus under relative perturbations of the coefficients."""
    c = np.asarray(coeffs)[::-1]  # ascending
    powers = np.abs(z) ** np.arange(len(c))
    dp = np.polyval(np.polyder(coeffs), z)
    return float(np.sum(np.abs(c) * powers) / (abs(z) * abs(dp)))


def test_spectral_radius_matches_python_control():
    rng = np.random.default_rng(SEED)
    good, set_aside, failures, control_off, i = 0, 0, [], [], 0
    while good < LOOPS:
        case = control_fixture.random_case(rng, i)
        i += 1
        k, b = wall(rng, case)
        rho_control = control_fixture.ClosedLoop(case).radius(k, b)
        lp = hapstab_loop(case)
        c = hs.check(lp, wall_stiffness=k, wall_damping=b)
        p = hs.discretize(lp, wall_stiffness=k, wall_damping=b).characteristic
        assert len(p) - 1 == len(c.roots)
        if condition(p, c.roots[0]) > CONDITION_LIMIT:
            set_aside += 1
            assert set_aside <= MAX_SET_ASIDE * LOOPS, f"{set_aside} loops ill-conditioned"
            continue
        good += 1
        if abs(c.spectral_radius - rho_control) <= RADIUS_REL * rho_control:
            continue
        rho_ref = float(control_mpmath.radius(dict(case, wall={"stiffness": k, "damping": b})))
        what = (i - 1, case["category"], case["velocity"], k, b, c.spectral_radius, rho_control, rho_ref)
        if abs(c.spectral_radius - rho_ref) > RADIUS_REL * rho_ref:
            failures.append(what)
        else:
            control_off.append(what)
    assert not failures, "\n".join(map(str, failures))
    assert len(control_off) <= MAX_CONTROL_OFF * LOOPS, "\n".join(map(str, control_off))
