"""The Python package against the independent state-space referee: the loops and walls of
crates/hapstab/tests/fixtures/statespace_loops.json (refereed by
benches/baseline/statespace_referee.py: exact zero-order hold by the matrix exponential,
closed-loop eigenvalues, 40-digit mpmath where double precision is doubtful; nothing of
hapstab's), built through the Python API and checked by `check`, `stability_map` in both
modes and `kmax` at the referee's dampings."""

import json

import numpy as np
import pytest

import hapstab as hs
from conftest import ROOT, plant_of

FIXTURE = ROOT / "crates" / "hapstab" / "tests" / "fixtures" / "statespace_loops.json"
# As the Rust test: radii to 1e-9 of the referee; verdicts where the referee's radius is at
# least the documented marginal band away from 1; interval ends to 1e-6.
RADIUS_REL = 1e-9
MARGINAL_BAND = 5e-11
INTERVAL_REL = 1e-6


@pytest.fixture(scope="module")
def fixture():
    with open(FIXTURE) as f:
        return json.load(f)


def loop_of(c: dict) -> hs.Loop:
    """The referee's loop through the Python constructor (a whole delay in seconds)."""
    delay = c["delay_time"]
    if delay is None:
        delay = c["delay"]["samples"] * c["period"]
    return hs.Loop(
        plant_of(c["plant"]),
        period=c["period"],
        delay=delay,
        velocity=c["velocity"],
        force_lag=c["force_lag"],
    )


def decidable(w: dict) -> bool:
    return abs(w["radius"] - 1.0) >= MARGINAL_BAND


def rel(a: float, b: float) -> float:
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def test_fixture_covers_every_kind(fixture):
    loops = fixture["loops"]
    assert len(loops) >= 300
    assert sum(len(c["walls"]) for c in loops) >= 3000
    assert {c["category"] for c in loops} >= {"two_mass", "transfer_function"}


def test_check_and_both_maps_agree_with_the_referee(fixture):
    wrong = []
    for i, c in enumerate(fixture["loops"]):
        lp = loop_of(c)
        ks = np.array([w["stiffness"] for w in c["walls"]])
        bs = np.array([w["damping"] for w in c["walls"]])
        flags = hs.stability_map(lp, ks, bs, grid=False).stable
        radius_map = hs.stability_map(lp, ks, bs, spectral_radius=True, grid=False)
        for j, w in enumerate(c["walls"]):
            r = hs.check(lp, w["stiffness"], w["damping"])
            where = f"loop {i} ({c['cli']}) K={w['stiffness']!r} B={w['damping']!r}"
            if rel(r.spectral_radius, w["radius"]) > RADIUS_REL:
                wrong.append(f"{where}: check ρ {r.spectral_radius!r} vs {w['radius']!r}")
            if rel(radius_map.spectral_radius[j], w["radius"]) > RADIUS_REL:
                wrong.append(f"{where}: map ρ {radius_map.spectral_radius[j]!r}")
            if decidable(w):
                want = w["verdict"] == "stable"
                if r.verdict != w["verdict"]:
                    wrong.append(f"{where}: check says {r.verdict}, referee {w['verdict']}")
                if bool(flags[j]) != want or bool(radius_map.stable[j]) != want:
                    wrong.append(f"{where}: map flags {flags[j]}, {radius_map.stable[j]}")
            # one verdict: the flag never depends on whether the radius was asked for
            if bool(flags[j]) != bool(radius_map.stable[j]) or bool(flags[j]) != r.stable:
                wrong.append(f"{where}: flags differ between the map modes and check")
    assert not wrong, f"{len(wrong)} disagreements:\n" + "\n".join(wrong[:20])


def test_kmax_at_a_damping_agrees_with_the_referee(fixture):
    """K_max at each of the referee's dampings is the highest end of its stable intervals."""
    wrong = []
    for i, c in enumerate(fixture["loops"]):
        lp = loop_of(c)
        for iv in c["intervals"]:
            if not iv["stiffness"]:
                continue
            hi = max(e[1] for e in iv["stiffness"])
            width = max(e[1] - e[0] for e in iv["stiffness"])
            k = hs.kmax(lp, wall_damping=iv["damping"])
            if k.k_max is None or abs(k.k_max - hi) > INTERVAL_REL * max(abs(hi), width):
                wrong.append(f"loop {i} ({c['cli']}) B={iv['damping']!r}: {k.k_max} vs {hi}")
    assert not wrong, f"{len(wrong)} disagreements:\n" + "\n".join(wrong[:20])
