"""frequency_response and root_locus: the same data as `hapstab bode --json` and
`hapstab locus --json` (to 1e-12), and what the data mean, checked independently: the
response equals H(z)·(K + B·V(z)) evaluated from `discretize`'s coefficient arrays, every gain
crossover has |L| = 1 and every phase crossover Im L = 0, and the locus puts a root on the
unit circle at its K_max sample."""

import json
import math
import subprocess

import numpy as np
import pytest

import hapstab as hs
from test_passivity_margins import cli_loops, run_cli, walls

SEED = 2026_12_03
CLI_REL = 1e-12


@pytest.fixture(scope="module")
def cases():
    rng = np.random.default_rng(SEED)
    return [(lp, flags, w) for lp, flags in cli_loops(rng) for w in walls(lp, rng)]


def close(got, want, rel=CLI_REL):
    got, want = np.asarray(got), np.asarray(want)
    assert got.shape == want.shape, (got.shape, want.shape)
    scale = np.maximum(np.abs(want), 1e-300)
    assert np.all(np.abs(got - want) <= rel * scale), np.max(np.abs(got - want) / scale)


def test_frequency_response_equals_bode_json(hapstab_cli, cases):
    seen_marks = 0
    for lp, flags, wall in cases:
        want = run_cli(hapstab_cli, "bode", flags, wall)
        got = hs.frequency_response(lp, *wall)
        curve = want["curve"]
        close(got.omega, curve["omega_rad_s"])
        close(got.frequency_hz, curve["frequency_hz"])
        close(got.response.real, curve["re"])
        close(got.response.imag, curve["im"])
        close(got.magnitude_db, curve["magnitude_db"])
        close(got.phase_deg, curve["phase_deg"])
        assert got.nyquist_hz == want["nyquist_hz"]
        assert got.margins.stable == want["stable"]
        assert len(got.marks) == len(want["marks"]), flags
        for m, w in zip(got.marks, want["marks"]):
            assert m.kind == w["kind"] and m.primary == w["primary"]
            close([m.omega, m.value, m.response.real, m.response.imag], [w["omega"], w["value"], w["re"], w["im"]])
        seen_marks += len(got.marks)
        d, f, z = got.closest
        close([d, f, z.real, z.imag], [want["closest"][k] for k in ("distance", "frequency_hz", "re", "im")])
    assert seen_marks > 0


def independent_response(lp, k, b, omega):
    """L(e^{jωT}) = z^(−k)·num/den·(K + B·vnum/vden) from discretize's coefficients."""
    d = hs.discretize(lp)
    z = np.exp(1j * omega * d.period)
    h = z ** (-d.plant_delay) * np.polyval(d.plant_num, z) / np.polyval(d.plant_den, z)
    v = np.polyval(d.velocity_num, z) / np.polyval(d.velocity_den, z)
    return h * (k + b * v)


def test_response_is_the_open_loop_of_the_discretized_wall(cases):
    for lp, _, (k, b) in cases:
        omega = np.geomspace(1e-2, math.pi / lp.period * 0.999, 301)
        got = hs.frequency_response(lp, k, b, omega)
        np.testing.assert_array_equal(got.omega, omega)
        want = independent_response(lp, k, b, omega)
        assert np.max(np.abs(got.response - want) / np.abs(want)) < 1e-9


def test_marks_are_crossings(cases):
    for lp, _, wall in cases:
        fr = hs.frequency_response(lp, *wall)
        if not fr.margins.stable:
            assert fr.marks == []
            continue
        for m in fr.marks:
            l = complex(hs.frequency_response(lp, *wall, np.array([m.omega])).response[0])
            if m.kind == "gain":
                assert abs(abs(l) - 1) < 1e-9, (m, l)
            else:
                assert abs(l.imag) < 1e-9 * abs(l) and abs(-1 / l.real - m.value) < 1e-9 * abs(m.value)


def run_locus(exe, flags, b):
    args = [str(exe), "locus", *map(str, flags), "--wall-damping", repr(b), "--json"]
    return json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)


def test_root_locus_equals_locus_json(hapstab_cli, cases):
    for lp, flags, (_, b) in cases[::2]:
        want = run_locus(hapstab_cli, flags, b)
        got = hs.root_locus(lp, b)
        close(got.wall_stiffness, want["stiffness"])
        close(got.spectral_radius, want["spectral_radius"])
        roots = np.array([[complex(re, im) for re, im in row] for row in want["roots"]])
        assert np.max(np.abs(got.roots - roots)) <= CLI_REL * max(1.0, np.max(np.abs(roots)))
        assert got.k_max == want["k_max"] and got.k_max_index == want["k_max_index"]
        assert got.crossing == complex(want["crossing"]["re"], want["crossing"]["im"])


def test_root_locus_crosses_the_unit_circle_at_kmax(cases):
    for lp, _, (_, b) in cases[::2]:
        rl = hs.root_locus(lp, b)
        k_max = hs.kmax(lp, wall_damping=b).k_max
        i = rl.k_max_index
        assert rl.wall_stiffness[i] == pytest.approx(k_max, rel=1e-12)
        assert abs(abs(rl.crossing) - 1) < 1e-9
        assert rl.spectral_radius[i] == pytest.approx(1.0, abs=1e-9)
        assert rl.spectral_radius[i - 1] < 1 < rl.spectral_radius[i + 1]


def test_given_stiffnesses_are_swept_as_given():
    lp = hs.Loop.paper()
    ks = np.array([0.0, 1e4, 3e4, 5e4])
    rl = hs.root_locus(lp, 10.0, ks)
    np.testing.assert_array_equal(rl.wall_stiffness, ks)
    for k, row, r in zip(ks, rl.roots, rl.spectral_radius):
        c = hs.check(lp, float(k), 10.0)
        np.testing.assert_allclose(np.sort_complex(row), np.sort_complex(c.roots), atol=1e-12)
        assert r == pytest.approx(c.spectral_radius, rel=1e-12)
    assert rl.spectral_radius[2] < 1 < rl.spectral_radius[3]  # K_max = 34.7 kN/m


@pytest.mark.parametrize(
    "call, keyword",
    [
        (lambda lp: hs.frequency_response(lp, 1e4, 10.0, [1.0, -2.0]), "omega"),
        (lambda lp: hs.frequency_response(lp, 1e4, 10.0, []), "omega"),
        (lambda lp: hs.frequency_response(lp, math.nan, 10.0), "wall_stiffness"),
        (lambda lp: hs.frequency_response(hs.Loop.normalized(gamma=0.0, delta=0.01), 1.0, 0.1), "loop"),
        (lambda lp: hs.root_locus(lp, math.inf), "wall_damping"),
        (lambda lp: hs.root_locus(lp, 10.0, [1.0, math.nan]), "wall_stiffness"),
        (lambda lp: hs.root_locus(hs.Loop.normalized(gamma=0.0, delta=0.01), 0.1), "loop"),
    ],
)
def test_bad_input_names_the_keyword(call, keyword):
    with pytest.raises(ValueError, match=f"^{keyword}:"):
        call(hs.Loop.paper())
