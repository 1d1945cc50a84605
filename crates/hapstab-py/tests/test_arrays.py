"""Arrays have the documented shapes and dtypes."""

import numpy as np

import hapstab as hs

LOOP = hs.Loop(hs.TwoMass(0.05, 2e4, motor_damping=0.5, handle_mass=0.05), delay=1.5e-3,
               velocity="lowpass:200", force_lag=2e-4)


def test_region_arrays():
    r = hs.region(LOOP)
    assert r.polygons and len(r.polygons) == len(r.thetas) == len(r.edges)
    for p, t, edges in zip(r.polygons, r.thetas, r.edges):
        assert p.dtype == np.float64 and p.ndim == 2 and p.shape[1] == 2 and p.shape[0] >= 3
        assert t.shape == (p.shape[0],) and t.dtype == np.float64
        assert {e.kind for e in edges} <= {"z=1", "z=-1", "complex", "window"}
        assert [e.start for e in edges[1:]] == [e.stop for e in edges[:-1]]
        assert edges[-1].stop == edges[0].start == 0
        for e in edges:
            assert (e.theta_start is None) == (e.kind != "complex")
    # K_max is the largest K of the polygons (to the chord tolerance of the arcs)
    k_top = max(p[:, 0].max() for p in r.polygons)
    assert k_top <= r.k_max * (1 + 1e-12) and k_top >= r.k_max * (1 - 1e-6)


def test_check_roots():
    c = hs.check(LOOP, wall_stiffness=2e3, wall_damping=2.0)
    d = hs.discretize(LOOP, wall_stiffness=2e3, wall_damping=2.0)
    degree = len(d.characteristic) - 1
    assert c.roots.dtype == np.complex128 and c.roots.shape == (degree,)
    assert abs(c.roots[0]) == c.spectral_radius
    assert np.all(np.diff(np.abs(c.roots)) <= 0)


def test_map_shapes():
    ks, bs = np.linspace(0, 4e4, 7), np.linspace(-5, 40, 4)
    g = hs.stability_map(LOOP, ks, bs)
    assert g.stable.shape == (4, 7) and g.stable.dtype == np.bool_
    assert g.spectral_radius is None
    g = hs.stability_map(LOOP, ks, bs, spectral_radius=True)
    assert g.spectral_radius.shape == (4, 7) and g.spectral_radius.dtype == np.float64
    assert np.array_equal(g.stable, g.spectral_radius < 1)
    kk = np.full((2, 3, 5), 1e3)
    p = hs.stability_map(LOOP, kk, np.ones_like(kk), spectral_radius=True)
    assert p.stable.shape == (2, 3, 5) and p.spectral_radius.shape == (2, 3, 5)
    # lists and integers are accepted like arrays
    q = hs.stability_map(LOOP, [0, 1000], [1, 2])
    assert q.stable.shape == (2, 2)
    e = hs.stability_map(LOOP, np.array([]), bs)
    assert e.stable.shape == (4, 0)


def test_discretize_arrays():
    d = hs.discretize(LOOP)
    assert d.characteristic is None
    order = 5  # two-mass device (4) + actuator lag (1)
    assert d.plant_den.shape == (order + 1,) and d.plant_den[0] == 1.0
    assert d.plant_num.ndim == 1 and len(d.plant_num) <= order + 1
    assert d.velocity_num.dtype == np.float64 and d.velocity_den[0] == 1.0
    n = len(d.p0)
    assert d.pk.shape == d.pb.shape == (n,)
    w = hs.discretize(LOOP, 3e3, 4.0)
    np.testing.assert_allclose(w.characteristic, d.p0 + 3e3 * d.pk + 4.0 * d.pb, rtol=1e-12, atol=1e-15)


def test_simulation_arrays():
    s = hs.simulate(hs.Loop.paper(delay=1e-3), 2e3, 2.0, samples=3000)
    n = len(s.time)
    assert s.samples >= 3000 and n == -(-s.samples // s.trace_stride)
    for a in (s.time, s.position, s.velocity, s.wall_force, s.human_force):
        assert a.shape == (n,) and a.dtype == np.float64
    np.testing.assert_allclose(np.diff(s.time), 1e-3 * s.trace_stride, rtol=1e-9)


def test_simulation_of_a_general_loop_agrees_with_check():
    # a low-pass velocity estimate and a fractional delay: the time domain's verdict on each
    # side of the exact boundary is the analysis' (growing iff spectral radius > 1)
    lp = hs.Loop(hs.MassSpringDamper(1.0, 5.0, 100.0), velocity="lowpass:100", delay=1.5e-3)
    k = hs.kmax(lp, wall_damping=1.0)
    for factor, outcome in [(0.8, "decaying"), (1.2, "growing")]:
        c = hs.check(lp, factor * k.k_max, 1.0)
        assert c.verdict == ("stable" if outcome == "decaying" else "unstable")
        s = hs.simulate(lp, factor * k.k_max, 1.0, samples=4000)
        assert s.outcome == outcome, (factor, s.outcome, c.spectral_radius)
