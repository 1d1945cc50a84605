"""`.plot()` on the results draws the result's own data headless (Agg): the region's
polygons, the map's grid, the Z-width's regions, the sweep's curves, the Bode curves and
crossover marks, the locus and the simulated position, with engineering-prefixed K axes.
The figures are written to HAPSTAB_PLOT_DIR (default target/python-plots) to be looked at."""

import os
from pathlib import Path

import numpy as np
import pytest

import hapstab as hs

mpl = pytest.importorskip("matplotlib")
mpl.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUT = Path(os.environ.get("HAPSTAB_PLOT_DIR", Path(__file__).parents[3] / "target" / "python-plots"))
LOOP = hs.Loop.paper(delay=1e-3)
WALL = (1e4, 10.0)


def save(ax, name):
    OUT.mkdir(parents=True, exist_ok=True)
    fig = (ax[0] if isinstance(ax, (tuple, list, np.ndarray)) else ax).figure
    fig.savefig(OUT / f"{name}.png", dpi=90)
    plt.close(fig)


def drawn_lines(ax):
    return [np.asarray(line.get_xydata()) for line in ax.get_lines()]


def test_region_plot_outlines_every_polygon_and_marks_k_max():
    r = hs.region(LOOP)
    ax = r.plot()
    lines = drawn_lines(ax)
    for p in r.polygons:
        closed = np.vstack([p, p[:1]])
        assert any(l.shape == closed.shape and np.array_equal(l, closed) for l in lines)
    assert any(l.shape == (1, 2) and np.array_equal(l[0], [r.k_max, r.b_at_k_max]) for l in lines)
    assert ax.get_legend() is not None
    assert ax.xaxis.get_major_formatter()(2e4) == "20 k" and ax.get_xlabel().endswith("(N/m)")
    save(ax, "region")


def test_a_given_axes_is_drawn_on_and_returned():
    fig, ax = plt.subplots()
    assert hs.region(LOOP).plot(ax=ax) is ax
    plt.close(fig)


def test_stability_map_plot_shows_the_grid_it_was_computed_on():
    k, b = np.linspace(0.0, 6e4, 61), np.linspace(0.0, 60.0, 41)
    m = hs.stability_map(LOOP, k, b)
    assert np.array_equal(m.wall_stiffness, k) and np.array_equal(m.wall_damping, b) and m.grid
    ax = m.plot()
    mesh = ax.collections[0]
    assert np.array_equal(np.asarray(mesh.get_array()).reshape(m.stable.shape), m.stable.astype(float))
    save(ax, "stability_map")
    rho = hs.stability_map(LOOP, k, b, spectral_radius=True)
    save(rho.plot(), "stability_map_radius")
    points = hs.stability_map(LOOP, np.array([1e4, 9e4]), np.array([10.0, 1.0]), grid=False)
    ax = points.plot()
    assert sum(len(c.get_offsets()) for c in ax.collections) == 2
    save(ax, "stability_map_points")


def test_zwidth_plot_outlines_the_passive_region_over_the_stable_one():
    z = hs.zwidth(LOOP)
    ax = z.plot()
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "stable" in labels and "passive" in labels
    save(ax, "zwidth")


def test_sweep_plot_draws_k_max_against_the_parameter():
    s = hs.sweep(LOOP, "arm-stiffness", np.linspace(0.0, 2000.0, 9))
    ax = s.plot()
    first = drawn_lines(ax)[0]
    assert np.array_equal(first[:, 0], s.values) and np.array_equal(first[:, 1], s.k_max)
    assert "arm-stiffness" in ax.get_xlabel()
    save(ax, "sweep")


def test_bode_plot_marks_every_crossover_on_the_curves():
    f = hs.frequency_response(LOOP, *WALL)
    mag, phase = f.plot()
    assert np.array_equal(drawn_lines(mag)[0][:, 1], f.magnitude_db)
    assert np.array_equal(drawn_lines(phase)[0][:, 1], f.phase_deg)
    marks = [l for a in (mag, phase) for l in drawn_lines(a) if l.shape == (1, 2)]
    assert len(marks) == len(f.marks) > 0
    save(mag, "bode")


def test_root_locus_plot_draws_every_root_and_the_roots_at_k_max():
    r = hs.root_locus(LOOP, wall_damping=WALL[1])
    ax = r.plot()
    assert len(ax.collections[0].get_offsets()) == r.roots.size
    save(ax, "root_locus")


def test_simulation_plot_draws_the_position_in_mm():
    s = hs.simulate(LOOP, *WALL)
    ax = s.plot()
    line = drawn_lines(ax)[0]
    assert np.allclose(line[:, 1], 1e3 * s.position, rtol=0, atol=0)
    save(ax, "simulation")
