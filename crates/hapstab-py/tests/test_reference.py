"""The Python package gives the Rust library's results: seeded loops of every kind built
through the Python API, compared with the values the library computed by itself
(crates/hapstab/tests/engine/python_reference.rs): α_max and K_max bit-equal, spectral radii to
1e-12, maps and coefficient arrays equal."""

import numpy as np
import pytest

import hapstab as hs
from conftest import loop_of

# Spectral radii: the acceptance tolerance (both sides run the same arithmetic, so they
# agree far closer; 1e-12 leaves room for nothing but a different computation).
RADIUS_REL = 1e-12
# Interval ends and coefficients: formed by the same arithmetic from the same inputs.
VALUE_REL = 1e-12


def close(a, b, rel=VALUE_REL):
    return a is None and b is None or abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


def test_reference_covers_every_kind_of_loop(reference):
    cases = reference["cases"]
    kinds = {c["loop"]["kind"] for c in cases}
    plants = {c["loop"]["plant"]["kind"] for c in cases}
    velocities = {c["loop"]["velocity"].split(":")[0] for c in cases}
    assert kinds == {"normalized", "paper", "loop"}
    assert plants == {"mass_spring_damper", "two_mass", "transfer_function"}
    assert velocities == {"backward", "lowpass", "average", "iir"}
    assert any(c["loop"]["force_lag"] > 0 for c in cases)
    fractional = [c for c in cases if loop_of(c["loop"]).delay_samples % 1]
    assert fractional, "no fractional delay"


def test_region_alpha_max_bit_equal(reference):
    for c in reference["cases"]:
        lp = loop_of(c["loop"])
        r = hs.region(lp)
        want = c["region"]
        assert r.k_max == want["k_max"] and r.b_at_k_max == want["b_at_k_max"], c["id"]
        # the library's values in wall units, given in N/m and Ns/m (the paper's loop: α, β)
        kpa, bpb = r.wall_units["stiffness"], r.wall_units["damping"]
        assert r.k_max == want["alpha_max"] * kpa, (c["id"], r.k_max.hex(), want["alpha_max"])
        assert r.b_at_k_max == want["beta_at_alpha_max"] * bpb, c["id"]
        assert r.area == want["area"] * kpa * bpb, c["id"]
        if r.normalized is not None:
            assert r.normalized["alpha_max"] == want["alpha_max"], c["id"]
            assert r.normalized["area"] == want["area"], c["id"]
        assert [len(p) for p in r.polygons] == want["vertices"], c["id"]


def test_check_spectral_radius_and_interval(reference):
    n = 0
    for c in reference["cases"]:
        lp = loop_of(c["loop"])
        for want in c["checks"]:
            k, b = want["wall"]
            got = hs.check(lp, wall_stiffness=k, wall_damping=b)
            assert close(got.spectral_radius, want["spectral_radius"], RADIUS_REL), (c["id"], want)
            assert got.verdict == want["verdict"], (c["id"], want)
            assert got.stable == (want["verdict"] == "stable")
            if want["k_interval"] is None:
                assert got.k_interval is None
            else:
                assert all(map(close, got.k_interval, want["k_interval"])), (c["id"], want)
            n += 1
    assert n >= 40


def test_kmax_at_damping_and_over_a_band(reference):
    for c in reference["cases"]:
        lp = loop_of(c["loop"])
        for want in c["kmax_at"]:
            got = hs.kmax(lp, wall_damping=want["wall_damping"])
            assert got.k_max == want["k_max"], (c["id"], want)
            if want["k_interval"] is not None:
                assert list(got.k_interval) == want["k_interval"]
        band = c["kmax_within"]
        got = hs.kmax(lp, damping_range=tuple(band["damping_range"]))
        want = band["result"]
        assert got.k_max == want["k_max"] and got.b_at_k_max == want["b_at_k_max"], c["id"]
        if got.normalized is not None:
            assert got.normalized["alpha_max"] == want["alpha_max"], c["id"]


def test_stability_map_equals_the_library_map(reference):
    for c in reference["cases"]:
        lp = loop_of(c["loop"])
        m = c["map"]
        ks, bs = np.array(m["wall_stiffness"]), np.array(m["wall_damping"])
        got = hs.stability_map(lp, ks, bs, spectral_radius=True)
        shape = (len(bs), len(ks))
        want_stable = np.array(m["stable"]).reshape(shape)
        want_rho = np.array(m["spectral_radius"]).reshape(shape)
        np.testing.assert_array_equal(got.stable, want_stable, err_msg=str(c["id"]))
        np.testing.assert_allclose(got.spectral_radius, want_rho, rtol=RADIUS_REL, atol=0)
        # the same walls elementwise (meshgrid form) give the same answer
        kk, bb = np.meshgrid(ks, bs)
        pts = hs.stability_map(lp, kk, bb, spectral_radius=True)
        np.testing.assert_array_equal(pts.stable, got.stable)
        np.testing.assert_array_equal(pts.spectral_radius, got.spectral_radius)


@pytest.mark.parametrize(
    "key", ["plant_num", "plant_den", "velocity_num", "velocity_den", "characteristic"]
)
def test_discretize_coefficients(reference, key):
    for c in reference["cases"]:
        lp = loop_of(c["loop"])
        want = c["discretize"]
        k, b = want["wall"]
        got = hs.discretize(lp, wall_stiffness=k, wall_damping=b)
        assert got.plant_delay == want["plant_delay"]
        np.testing.assert_allclose(getattr(got, key), want[key], rtol=VALUE_REL, atol=0)
