"""Baseline: simulating the sampled-data wall loop (Fig. 3) the way it is done in Python today,
one sample at a time with numpy (exact ZOH matrices from the paper's eq. (5)/(6) via a 2x2
matrix exponential, delay line in a list). Same case as crates/hapstab/benches/simulation.rs:
alpha = 0.05, beta = 0.1, gamma = 1e-4, delta = 0.015, d = 1, constant push 1 N, m = 0.1 kg,
T = 1 ms.

Prints one JSON line: {"samples": .., "seconds": .., "samples_per_second": ..}
"""
import json
import sys
import time

import numpy as np


def zoh(gamma, delta):
    # normalized plant x'' + delta x' + gamma x = u over one sample, by an augmented expm
    a = np.array([[0.0, 1.0, 0.0], [-gamma, -delta, 1.0], [0.0, 0.0, 0.0]])
    # scaling and squaring with a Taylor series (numpy has no expm; users often use scipy)
    s = 10
    m = a / 2**s
    e = np.eye(3)
    term = np.eye(3)
    for k in range(1, 20):
        term = term @ m / k
        e = e + term
    for _ in range(s):
        e = e @ e
    return e[:2, :2], e[:2, 2]


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 200_000
    alpha, beta, gamma, delta, d = 0.05, 0.1, 1e-4, 0.015, 1
    mass, period, push = 0.1, 1e-3, 1.0
    phi, gam = zoh(gamma, delta)
    scale = period * period / mass
    x = np.array([0.0, 0.05 * period])  # (x, T*v)
    hist = [0.0] * (d + 2)
    start = time.perf_counter()
    for _ in range(n):
        hist.insert(0, x[0])
        hist.pop()
        xd, xd1 = hist[d], hist[d + 1]
        f_wall = alpha * xd + beta * (xd - xd1)  # normalized: alpha x + beta (x - x_prev)
        u = push * scale - f_wall
        x = phi @ x + gam * u
    sec = time.perf_counter() - start
    print(json.dumps({"samples": n, "seconds": sec, "samples_per_second": n / sec}))


if __name__ == "__main__":
    main()
