"""The long computations release the GIL: another Python thread keeps running meanwhile."""

import threading
import time

import numpy as np

import hapstab as hs

# Python iterations the main thread must make while the map runs. Holding the GIL, the map
# would allow none (a thread waiting for the GIL gets it only when the holder drops it).
MIN_ITERATIONS = 100


def run_and_count(work):
    """Runs work() in a thread and counts the main thread's loop iterations meanwhile."""
    started, done = threading.Event(), threading.Event()
    out = {}

    def worker():
        started.set()
        t0 = time.perf_counter()
        out["result"] = work()
        out["seconds"] = time.perf_counter() - t0
        done.set()

    t = threading.Thread(target=worker)
    t.start()
    started.wait()
    n = 0
    while not done.is_set():
        n += 1
        time.sleep(0)  # a Python-level switch point; the count is Python bytecode progress
    t.join()
    return n, out


def test_a_large_map_releases_the_gil():
    lp = hs.Loop.normalized(gamma=0.001, delta=0.015, d=10)
    ks = np.linspace(-0.05, 1 / 10.5, 2000)
    bs = np.linspace(-0.05, 2 / 10.5**0.5, 2000)
    n, out = run_and_count(lambda: hs.stability_map(lp, ks, bs))
    assert out["result"].stable.shape == (2000, 2000)
    assert out["seconds"] > 0.05, out  # long enough for the count to mean something
    assert n >= MIN_ITERATIONS, (n, out["seconds"])
