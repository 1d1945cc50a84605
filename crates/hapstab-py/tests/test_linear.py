"""The linear condition (22)-(23) and its validity points (eq. 24, Fig. 7) from Python: the
numbers of `hapstab linear --json` bit for bit, the closed form of (23), the validity point
on the exact boundary (an independent verdict there), and the refusals."""

import json
import subprocess

import numpy as np
import pytest

import hapstab as hs

LEVELS = [0.01, 0.02, 0.05, 0.2]

CASES = [
    ("paper physical, d = 1", hs.Loop.paper(delay=1e-3), ["--delay", "1"]),
    ("paper physical, d = 0", hs.Loop.paper(), []),
    (
        "paper normalized, d = 2",
        hs.Loop.normalized(gamma=0.001, delta=0.015, d=2),
        ["--gamma", "0.001", "--delta", "0.015", "--delay", "2"],
    ),
]


def cli(exe, *args):
    done = subprocess.run([str(exe), *args, "--json"], check=True, capture_output=True, text=True)
    return json.loads(done.stdout)


@pytest.mark.parametrize("name, lp, flags", CASES, ids=[c[0] for c in CASES])
def test_linear_condition_equals_the_command_line(hapstab_cli, name, lp, flags):
    levels = ",".join(str(x) for x in LEVELS)
    want = cli(hapstab_cli, "linear", *flags, "--levels", levels)
    got = hs.linear_condition(lp, levels=LEVELS)
    assert got.linear_slope == want["linear_slope"]
    assert got.linear_intercept == want["linear_intercept"]
    assert got.alpha_lower == want["alpha_lower"]
    pts = want["points"]
    for key in ("level", "alpha", "beta", "alpha_linear", "error"):
        column = got.levels if key == "level" else getattr(got, key)
        np.testing.assert_array_equal(column, [p[key] for p in pts], err_msg=key)
    if pts[0].get("wall_stiffness") is None:  # normalized input: alpha and beta only
        assert got.wall_stiffness is None and got.wall_damping is None
        assert got.k_linear is None and got.k_linear_slope is None and got.k_lower is None
    else:
        for key in ("wall_stiffness", "wall_damping", "k_linear"):
            np.testing.assert_array_equal(getattr(got, key), [p[key] for p in pts], err_msg=key)
        for key in ("k_linear_slope", "k_linear_intercept", "k_lower"):
            assert getattr(got, key) == want[key], key


def test_condition_23_and_points_on_the_exact_boundary():
    gamma, delta, d = 0.001, 0.015, 2
    lc = hs.linear_condition(hs.Loop.normalized(gamma=gamma, delta=delta, d=d), levels=LEVELS)
    tr = d + 0.5
    assert (lc.gamma, lc.delta, lc.d) == (gamma, delta, d)
    assert lc.linear_slope == 1.0 / tr and lc.linear_intercept == delta / tr
    assert lc.alpha_lower == -gamma
    # (23): alpha_lin = (beta + delta)/(d + 1/2) at each point
    np.testing.assert_allclose(lc.alpha_linear, (lc.beta + delta) / tr, rtol=1e-15)
    # eq. (24): the error |alpha_lin - alpha|/(alpha + gamma) reaches the level there
    err = np.abs(lc.alpha_linear - lc.alpha) / (lc.alpha + gamma)
    np.testing.assert_allclose(err, LEVELS, rtol=1e-6)
    # the points lie on the exact boundary: a root on the unit circle (spectral radius 1)
    for a, b in zip(lc.alpha, lc.beta):
        rho = hs.check(hs.Loop.normalized(gamma=gamma, delta=delta, d=d), alpha=a, beta=b).spectral_radius
        assert abs(rho - 1.0) < 1e-9, (a, b, rho)
    assert lc.beta[0] < lc.beta[-1]  # a larger error is reached further out


def test_physical_points_are_the_normalized_ones_in_si_units():
    lp = hs.Loop.paper(delay=1e-3)
    lc = hs.linear_condition(lp, levels=LEVELS)
    m, t = 1.1, 1e-3  # the default device + arm: m_L + m_H, T
    np.testing.assert_allclose(lc.wall_stiffness, lc.alpha * m / t**2, rtol=1e-14)
    np.testing.assert_allclose(lc.wall_damping, lc.beta * m / t, rtol=1e-14)
    # (23) and (19) in N/m: K < (B + b)/(T(d + 1/2)), K > -k (b = 7.5 Ns/m, k = 350 N/m)
    b, k, tr = 7.5, 350.0, t * 1.5
    assert abs(lc.k_linear_slope - 1 / tr) <= 1e-12 / tr
    assert abs(lc.k_linear_intercept - b / tr) <= 1e-12 * b / tr
    assert abs(lc.k_lower + k) <= 1e-12 * k
    np.testing.assert_allclose(lc.k_linear, (lc.wall_damping + b) / tr, rtol=1e-12)
    assert repr(lc).startswith("LinearCondition(k_linear_slope=")


def test_loops_without_the_normalized_view_and_bad_levels_are_refused():
    lowpass = hs.Loop(plant=hs.MassSpringDamper(mass=1.1, damping=7.5, stiffness=350.0),
                      period=1e-3, velocity="lowpass:100")
    with pytest.raises(ValueError, match="^loop: .*normalized view"):
        hs.linear_condition(lowpass)
    with pytest.raises(ValueError, match="^levels"):
        hs.linear_condition(hs.Loop.paper(), levels=[0.05, -0.1])
    with pytest.raises(ValueError, match="^levels"):
        hs.linear_condition(hs.Loop.paper(), levels=[float("nan")])
