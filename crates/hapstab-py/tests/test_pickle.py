"""Loops and every result object pickle (multiprocessing, joblib and dask send them to and
from workers) to the same loop and the same numbers bit for bit, and the package names its
version."""

import math
import pickle
from pathlib import Path
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import hapstab as hs

LOOPS = [
    hs.Loop.paper(delay=1e-3),
    hs.Loop.normalized(gamma=0.3, delta=0.1, d=2),
    hs.Loop(hs.TwoMass(0.3, 2300.0, handle_mass=0.1), period=0.002, delay=3.7e-3,
            velocity="butterworth:2:40", force_lag=2e-4),
    hs.Loop(hs.TransferFunction([10.0], [1.0, 3.0, 10.0]), velocity="iir:0.5,0,-0.5/1,-0.2"),
]


def k_max(lp):
    return hs.kmax(lp, wall_damping=0.01 if lp.is_normalized else 2.0).k_max


def test_loops_pickle_to_the_same_loop():
    for lp in LOOPS:
        back = pickle.loads(pickle.dumps(lp))
        assert repr(back) == repr(lp) and back.to_json() == lp.to_json()
        assert back.is_normalized == lp.is_normalized
        assert k_max(back) == k_max(lp)


def test_loops_go_to_worker_processes():
    with ProcessPoolExecutor(max_workers=2) as pool:
        got = list(pool.map(k_max, LOOPS))
    assert got == [k_max(lp) for lp in LOOPS]


def test_version():
    assert hs.__version__ == "0.1.0"


IDENTIFY_RUN = (Path(__file__).resolve().parents[2] / "hapstab" / "tests" / "fixtures"
                / "identify" / "msd_chirp_40db.csv")


def results(lp, wall):
    """One of every result type for a loop and a stable wall of it."""
    grid_k, grid_b = np.linspace(0.0, 2.0 * wall[0], 5), np.linspace(0.0, 2.0 * wall[1], 4)
    return [
        hs.check(lp, *wall), hs.region(lp), hs.kmax(lp), hs.margins(lp, *wall),
        hs.passivity(lp, *wall), hs.frequency_response(lp, *wall),
        hs.root_locus(lp, wall_damping=wall[1]), hs.discretize(lp, *wall),
        hs.simulate(lp, *wall), hs.sweep(lp, "arm-stiffness", [100.0, 300.0]), hs.zwidth(lp),
        hs.stability_map(lp, grid_k, grid_b), hs.linear_condition(lp),
        hs.nyquist_regions(0.1, 1, steps=2, beta_samples=16, gamma_samples=3),
        hs.robust_kmax(lp, {"period": (lp.period, 1.5 * lp.period)}, wall_damping=wall[1],
                       samples=8, verify=50),
        hs.stability_probability(lp, distributions={"period": "uniform:1e-3:2e-3"},
                                 wall_stiffness=wall[0], wall_damping=wall[1], samples=20),
        hs.stability_probability(lp, distributions={"period": "uniform:1e-3:2e-3"},
                                 wall_damping=wall[1], samples=20),
        hs.identify(*np.loadtxt(IDENTIFY_RUN, delimiter=",", skiprows=1).T, draws=20),
    ]


def same(a, b):
    """Equal field for field: arrays equal in shape, dtype and every value (NaN where NaN),
    nested results and lists compared the same way."""
    if isinstance(a, np.ndarray):
        return isinstance(b, np.ndarray) and a.dtype == b.dtype and np.array_equal(a, b, equal_nan=True)
    if isinstance(a, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if type(a).__module__.startswith("hapstab"):
        fields = [n for n in dir(type(a)) if not n.startswith("_") and not callable(getattr(a, n))]
        return type(a) is type(b) and all(same(getattr(a, f), getattr(b, f)) for f in fields)
    if isinstance(a, float) and math.isnan(a):
        return isinstance(b, float) and math.isnan(b)
    return a == b


def test_every_result_type_pickles_field_for_field():
    lp = hs.Loop.paper(delay=1e-3)
    got = results(lp, (1e4, 10.0))
    names = {type(r).__name__ for r in got}
    # every result class the package exports, nested ones (Edge, Mark, PassiveRegion) inside
    assert names | {"Edge", "Mark", "PassiveRegion", "RenderableBand"} == {
        n for n in hs.__all__ if n[0].isupper()
    } - {"Loop", "MassSpringDamper", "TwoMass", "TransferFunction", "NumericalError"}
    for r in got:
        back = pickle.loads(pickle.dumps(r))
        assert same(back, r), type(r).__name__
        assert repr(back) == repr(r)


def test_a_malformed_pickle_state_is_refused_naming_what_is_missing():
    with pytest.raises(ValueError, match='state: no field "k_max"'):
        hs._rebuild("Kmax", {})
    with pytest.raises(ValueError, match='name: no result class "Nope"'):
        hs._rebuild("Nope", {})


def kmax_of_arm(stiffness):
    lp = hs.Loop(hs.MassSpringDamper.from_device_and_arm(arm_stiffness=stiffness), delay=1e-3)
    return hs.kmax(lp, wall_damping=2.0)


def test_joblib_parallel_over_100_loops():
    joblib = pytest.importorskip("joblib")
    stiffness = np.linspace(0.0, 2000.0, 100)
    got = joblib.Parallel(n_jobs=2)(joblib.delayed(kmax_of_arm)(k) for k in stiffness)
    want = [kmax_of_arm(k) for k in stiffness]
    assert len(got) == 100 and all(same(g, w) for g, w in zip(got, want))
    assert not same(got[0], got[-1])  # the comparison tells different results apart
