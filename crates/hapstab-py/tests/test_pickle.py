"""Loops pickle (multiprocessing, joblib and dask send them to workers) to the same loop bit
for bit, and the package names its version."""

import pickle
from concurrent.futures import ProcessPoolExecutor

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
