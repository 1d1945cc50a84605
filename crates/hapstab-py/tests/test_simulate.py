"""simulate: the run's outcome agrees with the analysis while the wall acts linearly."""

import numpy as np

import hapstab as hs


def test_linear_runs_agree_with_the_spectral_radius():
    lp = hs.Loop.paper(period=1e-3, delay=1e-3)
    for k in (2e3, 12e3):
        c = hs.check(lp, wall_stiffness=k, wall_damping=2.0)
        s = hs.simulate(lp, wall_stiffness=k, wall_damping=2.0)
        assert s.linear_window
        assert s.spectral_radius == c.spectral_radius
        assert s.outcome == ("decaying" if c.stable else "growing"), (c, s.reason)


def test_normalized_wall_and_human_profile():
    lp = hs.Loop.normalized(gamma=1e-3, delta=0.015, d=1)
    prof = np.r_[np.zeros(100), np.full(100, 1e-4)]
    s = hs.simulate(lp, alpha=0.05, beta=0.3, samples=1000, human_force=prof, initial_position=0.0)
    np.testing.assert_array_equal(s.human_force[:200], prof)
    assert s.human_force[-1] == 1e-4  # the last value is held
    assert s.time[1] - s.time[0] == 1.0  # T = 1: time counts samples


def test_unilateral_wall_with_saturation_reports_contact():
    lp = hs.Loop.paper()
    s = hs.simulate(lp, 5e3, 5.0, contact="unilateral", saturation=5.0, initial_velocity=0.1)
    assert set(s.contact) >= {"contacts", "separations", "in_contact_at_end"}
    assert s.outcome in {"decaying", "limit_cycle", "growing", "separated", "undecided"}
    assert np.all(np.abs(s.wall_force) <= 5.0)
