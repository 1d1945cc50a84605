"""kmax without a damping: K_max at B = 0, over the renderable band and over B >= 0, equal
to `hapstab kmax --json` bit for bit; the band against its closed form on the pure mass
(B_r = F_n·√12·T/(Δ·√2), K_max = 2β(2 − β)/(2 + β)·m/T² at β = B_r·T/m); refusals."""

import json
import math
import subprocess

import pytest

import hapstab as hs


def pure_mass(m, period):
    return hs.Loop(hs.MassSpringDamper(m, 0.0, 0.0), period=period)


@pytest.mark.parametrize("m, t, dx, fn", [(0.1, 1e-3, 1e-5, 0.05), (1.0, 5e-4, 2e-6, 0.1)])
def test_renderable_band_of_the_pure_mass(m, t, dx, fn):
    k = hs.kmax(pure_mass(m, t), position_resolution=dx, force_noise=fn)
    rb = k.renderable
    b_r = fn * math.sqrt(12.0) * t / (dx * math.sqrt(2.0))
    assert rb.b_max == pytest.approx(b_r, rel=1e-14)
    assert rb.velocity_noise_gain == pytest.approx(math.sqrt(2.0) / t, rel=1e-14)
    beta = b_r * t / m
    assert rb.k_max == pytest.approx(2 * beta * (2 - beta) / (2 + beta) * m / t**2, rel=1e-9)
    assert (rb.position_resolution, rb.force_noise) == (dx, fn)
    # B = 0 of the pure mass with the backward difference: no stiffness is stable but K → 0
    assert k.k_max_at_zero_damping is None or k.k_max_at_zero_damping < 1e-6 * rb.k_max


def test_defaults_are_the_command_line_s(hapstab_cli):
    lp = hs.Loop.paper()
    got = hs.kmax(lp)
    out = subprocess.run([hapstab_cli, "kmax", "--json"], capture_output=True, text=True,
                         check=True)
    cli = json.loads(out.stdout)
    assert (got.k_max, got.b_at_k_max, got.k_max_at_zero_damping) == (
        cli["k_max"], cli["b_at_k_max"], cli["k_max_at_zero_damping"])
    assert {f: getattr(got.renderable, f) for f in cli["renderable"]} == cli["renderable"]
    out = subprocess.run([hapstab_cli, "kmax", "--json", "--position-resolution", "3e-6",
                          "--force-noise", "0.2"], capture_output=True, text=True, check=True)
    cli = json.loads(out.stdout)["renderable"]
    got = hs.kmax(lp, position_resolution=3e-6, force_noise=0.2).renderable
    assert {f: getattr(got, f) for f in cli} == cli


def test_with_a_damping_there_is_no_band():
    k = hs.kmax(hs.Loop.paper(), wall_damping=5.0)
    assert k.renderable is None and k.k_max_at_zero_damping is None
    assert k.b_at_k_max == 5.0


@pytest.mark.parametrize("kwargs, keyword", [
    (dict(position_resolution=0.0), "position_resolution"),
    (dict(force_noise=-1.0), "force_noise"),
    (dict(force_noise=math.nan), "force_noise"),
    (dict(wall_damping=1.0, force_noise=0.1), "position_resolution, force_noise"),
])
def test_refusals_name_the_keyword(kwargs, keyword):
    with pytest.raises(ValueError) as e:
        hs.kmax(hs.Loop.paper(), **kwargs)
    assert str(e.value).startswith(keyword), str(e.value)
