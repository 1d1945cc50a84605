"""Baseline: all roots of p(z) with numpy.roots (LAPACK eigenvalues of the companion matrix).

Same plant and polynomial as crates/hapstab/benches/roots.rs: γ = 0.001, δ = 0.015,
α = 0.5/(d + 1/2), β = 1/(d + 1/2)^{1/2}, p(z) = z^{d+1} D(z) + N(z)((α+β)z − β), with the
plant coefficients of benches/baseline/numpy_map.py. Each degree is timed over `reps` calls
(at least one) or about 2 s, whichever ends first.

Prints one JSON line per d: {"d": .., "calls": .., "seconds_per_call": .., "spectral_radius": ..}
"""
import json
import sys
import time

import numpy as np

from numpy_map import plant


def poly(d):
    n1, n0, a1, a0 = plant(0.001, 0.015)
    t = d + 0.5
    a, b = 0.5 / t, 1.0 / np.sqrt(t)
    p = np.zeros(d + 4)  # descending coefficients
    p[0], p[1], p[2] = 1.0, -a1, a0
    s = a + b
    p[-3] += n1 * s
    p[-2] += n0 * s - n1 * b
    p[-1] += -n0 * b
    return p


def main():
    ds = [int(x) for x in sys.argv[1:]] or [10, 200, 2000]
    for d in ds:
        p = poly(d)
        calls, start = 0, time.perf_counter()
        while True:
            r = np.roots(p)
            calls += 1
            sec = time.perf_counter() - start
            if sec > 2.0 or calls >= 1000:
                break
        print(json.dumps({"d": d, "calls": calls, "seconds_per_call": sec / calls,
                          "spectral_radius": float(np.max(np.abs(r)))}))


if __name__ == "__main__":
    main()
