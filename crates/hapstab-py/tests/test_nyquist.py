"""Section VIII from Python (nyquist_regions): the numbers of `hapstab nyquist --json` bit
for bit, and closed forms: gamma_N = pi^2 + delta^2/4 (eq. 27), the swept gammas, the pure
mass's alpha_max = 12 - 8*sqrt(2) (Section V), Colgate's passive triangle of area 2*delta^2
(eq. 28); refusals naming the keyword."""

import json
import math
import subprocess

import numpy as np
import pytest

import hapstab as hs

CASES = [
    dict(delta=0.0, d=0, gamma_fraction=1.0, steps=2, beta_samples=32, gamma_samples=5),
    dict(delta=0.1, d=0, gamma_fraction=0.5, steps=3, beta_samples=24, gamma_samples=4),
    dict(delta=0.3, d=1, gamma_fraction=1.0, steps=2, beta_samples=16, gamma_samples=3),
]


def nan_for_null(xs):
    """JSON writes NaN as null."""
    return [math.nan if x is None else x for x in xs]


def cli(exe, c):
    args = [str(exe), "nyquist", "--delta", str(c["delta"]), "--delay", str(c["d"]),
            "--gamma-fraction", str(c["gamma_fraction"]), "--steps", str(c["steps"]),
            "--beta-samples", str(c["beta_samples"]), "--gamma-samples", str(c["gamma_samples"]),
            "--json"]
    return json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)


@pytest.mark.parametrize("c", CASES, ids=lambda c: f"delta={c['delta']},d={c['d']}")
def test_nyquist_regions_equal_the_command_line(hapstab_cli, c):
    want = cli(hapstab_cli, c)
    got = hs.nyquist_regions(c["delta"], c["d"], gamma_fraction=c["gamma_fraction"],
                             steps=c["steps"], beta_samples=c["beta_samples"],
                             gamma_samples=c["gamma_samples"])
    assert got.gamma_nyquist == want["gamma_nyquist"]
    rows = want["sweep"]
    for key in ("gamma", "alpha_max", "alpha_min", "beta_min", "beta_max", "area"):
        np.testing.assert_array_equal(getattr(got, "sweep_" + key),
                                      nan_for_null(r[key] for r in rows), err_msg=key)
    np.testing.assert_array_equal(got.sweep_beta_at_alpha_max,
                                  nan_for_null(r["beta_at_alpha_max"] for r in rows))
    assert got.sweep_empty == [r["empty"] for r in rows]
    assert got.sweep_degenerate == [r["degenerate"] for r in rows]
    rob = want["robust"]
    np.testing.assert_array_equal(got.robust_polygon, np.array(rob["polygon"]).reshape(-1, 2))
    np.testing.assert_array_equal(
        [got.robust_alpha_max, got.robust_beta_at_alpha_max, got.robust_area, got.robust_gamma_hi],
        nan_for_null([rob["alpha_max"], rob["beta_at_alpha_max"], rob["area"], rob["gamma_hi"]]))
    if "passive" not in want:
        assert got.passive_polygon is None and got.passive_inside_robust is None
    else:
        p = want["passive"]
        np.testing.assert_array_equal(got.passive_polygon, p["vertices"])
        assert got.passive_area == p["area"]
        assert got.passive_inside_robust == p["check"]["inside"]
        assert got.passive_applies == p["applies"]


def test_closed_forms_of_section_viii():
    delta, d, steps = 0.1, 0, 4
    r = hs.nyquist_regions(delta, d, steps=steps, beta_samples=64, gamma_samples=5)
    gn = math.pi**2 + delta**2 / 4
    assert abs(r.gamma_nyquist - gn) <= 1e-15 * gn
    np.testing.assert_allclose(r.sweep_gamma, gn * np.arange(steps + 1) / steps, rtol=1e-15)
    # Colgate's passive region alpha <= 2(delta - |beta|), alpha >= 0: a triangle of 2 delta^2
    assert abs(r.passive_area - 2 * delta**2) <= 1e-12
    assert r.passive_applies  # d = 0
    # the pure mass (gamma = delta = d = 0): alpha_max = 12 - 8 sqrt 2 at beta = 2(sqrt 2 - 1)
    pure = hs.nyquist_regions(0.0, 0, steps=1, beta_samples=64, gamma_samples=3)
    assert abs(pure.sweep_alpha_max[0] - (12 - 8 * math.sqrt(2))) < 1e-9
    assert abs(pure.sweep_beta_at_alpha_max[0] - 2 * (math.sqrt(2) - 1)) < 1e-6
    assert pure.passive_polygon is None  # delta = 0: no passive region


def test_bad_arguments_name_the_keyword():
    with pytest.raises(ValueError, match="^delta"):
        hs.nyquist_regions(-0.1)
    with pytest.raises(ValueError, match="^delta"):
        hs.nyquist_regions(float("nan"))
    with pytest.raises(ValueError, match="^gamma_fraction"):
        hs.nyquist_regions(0.1, gamma_fraction=-1.0)
    with pytest.raises(ValueError, match="^steps"):
        hs.nyquist_regions(0.1, steps=0)
    with pytest.raises(ValueError, match="^d"):
        hs.nyquist_regions(0.1, d=10**6)
    with pytest.raises(ValueError, match="^beta_samples"):
        hs.nyquist_regions(0.1, steps=10**6, beta_samples=10**6)
