"""Every entry point with a command-line counterpart has its budget, checked from the inputs'
sizes before anything is copied or computed; inputs beyond the representable range get a
ValueError naming the keyword; type errors name the argument too."""

import resource
import time

import numpy as np
import pytest

import hapstab as hs

LOOP = hs.Loop.paper()
LOOP_2000 = hs.Loop.paper(delay=2.0)  # d = 2000 samples at T = 1 ms


def refused_quickly(keyword, call):
    t = time.perf_counter()
    with pytest.raises(ValueError) as e:
        call()
    assert time.perf_counter() - t < 2.0, f"took {time.perf_counter() - t:.1f} s"
    msg = str(e.value)
    assert msg.startswith(keyword + ": "), msg
    assert "\n" not in msg and len(msg) < 400, msg
    return msg


def test_a_run_of_ten_billion_samples_is_refused():
    msg = refused_quickly("samples", lambda: hs.simulate(LOOP, 1e3, 1.0, samples=10**10))
    assert "10000000000" in msg


def test_a_run_of_a_billion_seconds_is_refused():
    refused_quickly("duration", lambda: hs.simulate(LOOP, 1e3, 1.0, duration=1e9))


def test_a_huge_horizon_is_refused():
    refused_quickly("max_samples", lambda: hs.simulate(LOOP, 1e3, 1.0, max_samples=10**11))


def test_a_radius_map_of_ten_thousand_squared_walls_is_refused():
    k = np.linspace(0.0, 1e4, 10_000)
    b = np.linspace(0.0, 10.0, 10_000)
    msg = refused_quickly(
        "wall_stiffness, wall_damping",
        lambda: hs.stability_map(LOOP_2000, k, b, spectral_radius=True),
    )
    assert "delay of 2000 samples" in msg, msg


def test_huge_arrays_are_refused_before_they_are_copied():
    # 10⁸ walls as int64 (a conversion to float64 would copy 800 MB each) as one elementwise
    # map at d = 2000: far beyond the time budget, refused from the shapes alone
    k = np.zeros(10**8, dtype=np.int64)
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    refused_quickly(
        "wall_stiffness, wall_damping",
        lambda: hs.stability_map(LOOP_2000, k, k, grid=False),
    )
    after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    assert after - before < 200e6, f"peak grew by {(after - before) / 1e6:.0f} MB"


def test_a_heavy_region_at_a_long_filter_is_refused_naming_the_loop():
    # p(z) of degree 4002 whose parts without the delay have degree 2002: half an hour
    lp = hs.Loop(hs.MassSpringDamper(1.1, 7.5, 350.0), velocity="average:2000", delay_samples=2000)
    for call in (lambda: hs.region(lp), lambda: hs.kmax(lp)):
        msg = refused_quickly("loop", call)
        assert "degree 4002" in msg, msg


def test_grid_makes_the_layout_explicit():
    k = np.array([1e3, 1e6])
    b = np.array([10.0, 10.0])
    # default: two 1-D arrays are the grid's axes
    assert hs.stability_map(LOOP, k, b).stable.shape == (2, 2)
    assert hs.stability_map(LOOP, k, b, grid=True).stable.shape == (2, 2)
    # grid=False: one wall per element, each the same as a check of that wall
    m = hs.stability_map(LOOP, k, b, grid=False, spectral_radius=True)
    assert m.stable.shape == (2,)
    for i in range(2):
        c = hs.check(LOOP, k[i], b[i])
        assert m.stable[i] == (c.verdict == "stable")
        assert m.spectral_radius[i] == pytest.approx(c.spectral_radius, rel=1e-9)
    with pytest.raises(ValueError, match=r"^wall_stiffness, wall_damping: .*grid=True"):
        hs.stability_map(LOOP, np.zeros((2, 2)), np.zeros((2, 2)), grid=True)
    with pytest.raises(ValueError, match=r"^wall_stiffness, wall_damping: "):
        hs.stability_map(LOOP, np.zeros(2), np.zeros(3), grid=False)


@pytest.mark.parametrize(
    "keyword, call",
    [
        ("wall_stiffness", lambda: hs.check(LOOP, 1e308, 1.0)),
        ("wall_damping", lambda: hs.check(LOOP, 1.0, -1e308)),
        ("wall_stiffness", lambda: hs.passivity(hs.Loop.paper(arm_mass=0.0, arm_damping=0.0, arm_stiffness=0.0), 1e308, 1e308)),
        ("velocity", lambda: hs.Loop(hs.MassSpringDamper(1.0, 1.0, 1.0), velocity="iir:1e300,-1e300/1")),
        ("velocity", lambda: hs.Loop(hs.MassSpringDamper(1.0, 1.0, 1.0), velocity="iir:1000,-1000/1e-320")),
        ("motor_mass", lambda: hs.Loop(hs.TwoMass(1e300, 1e4))),
        ("motor_mass", lambda: hs.Loop(hs.TwoMass(1e-300, 1e4))),
        ("plant.mass", lambda: hs.Loop(hs.MassSpringDamper(1e-300, 1.0, 1.0))),
        ("plant.mass", lambda: hs.Loop(hs.MassSpringDamper(1e20, 7.5, 350.0))),
    ],
)
def test_inputs_beyond_the_representable_name_their_keyword(keyword, call):
    with pytest.raises(ValueError) as e:
        call()
    msg = str(e.value)
    assert msg.startswith(keyword + ": "), msg
    assert "numerical" not in msg.lower() and "not finite" not in msg, msg


def test_a_long_list_is_echoed_as_an_excerpt():
    spec = "iir:" + ",".join(["1"] * 10_000) + ",y/1"
    with pytest.raises(ValueError) as e:
        hs.Loop(hs.MassSpringDamper(1.0, 1.0, 1.0), velocity=spec)
    msg = str(e.value)
    assert msg.startswith("velocity: ") and len(msg) < 400, msg
    assert "10001 coefficients (1, 1, 1, …)" in msg, msg


@pytest.mark.parametrize(
    "keyword, call",
    [
        ("wall_stiffness", lambda: hs.check(LOOP, "stiff", 1.0)),
        ("wall_damping", lambda: hs.kmax(LOOP, wall_damping="x")),
        ("samples", lambda: hs.simulate(LOOP, 1e3, 1.0, samples="many")),
        ("wall_stiffness", lambda: hs.stability_map(LOOP, ["a", "b"], [1.0, 2.0])),
        ("loop", lambda: hs.check(3.0, 1.0, 1.0)),
        ("loop", lambda: hs.simulate(300.0, 1.0, 1.0)),
    ],
)
def test_type_errors_start_with_the_argument_name(keyword, call):
    with pytest.raises(TypeError) as e:
        call()
    assert str(e.value).startswith(keyword + ": "), str(e.value)
