"""Baseline: the stability map the way users compute it today, point by point with numpy.roots.

Same plant, same grid as crates/hapstab/benches/map.rs (γ = 0.001, δ = 0.015, 1000 × 1000
points over α ∈ [−0.05, 1/(d+1/2)], β ∈ [−0.05, 2/√(d+1/2)]). The ZOH plant coefficients are
computed once with the paper's eq. (5)/(6) in complex arithmetic (c1 is imaginary here); the
characteristic polynomial p(z) = z^{d+1} D(z) + N(z)((α+β)z − β) is then built and rooted with
numpy.roots at every timed point. Timing a full million points takes minutes, so a regular
sub-grid (every `stride`-th row and column) is timed and the per-point time reported.

Prints one JSON line: {"d": .., "points_timed": .., "seconds": .., "ns_per_point": .., "stable_fraction": ..}
"""
import cmath
import json
import sys
import time

import numpy as np


def plant(gamma, delta):
    c1 = cmath.sqrt(delta * delta - 4 * gamma)
    c2 = cmath.exp(-(delta + c1) / 2)
    c3 = cmath.exp(-(delta - c1) / 2)
    ed = np.exp(-delta)
    den = c1 * gamma
    # eq. (5) with the T^2/(2m) factor dropped: N(z) = (n1 z + n0)/(2 c1 γ)
    n1 = ((2 - c2 - c3) * c1 + (c2 - c3) * delta) / (2 * den)
    n0 = ((2 * ed - c3 - c2) * c1 + (c3 - c2) * delta) / (2 * den)
    a1 = c2 + c3
    return n1.real, n0.real, a1.real, ed


def main():
    d = int(sys.argv[1]) if len(sys.argv) > 1 else 0
    stride = int(sys.argv[2]) if len(sys.argv) > 2 else 10
    n1, n0, a1, a0 = plant(0.001, 0.015)
    t = d + 0.5
    alphas = np.linspace(-0.05, 1.0 / t, 1000)[::stride]
    betas = np.linspace(-0.05, 2.0 / np.sqrt(t), 1000)[::stride]
    base = np.zeros(d + 4)  # descending coefficients of z^{d+1} D(z)
    base[0], base[1], base[2] = 1.0, -a1, a0
    stable = 0
    start = time.perf_counter()
    for b in betas:
        for a in alphas:
            p = base.copy()
            s = a + b
            p[-3] += n1 * s
            p[-2] += n0 * s - n1 * b
            p[-1] += -n0 * b
            if np.max(np.abs(np.roots(p))) < 1.0:
                stable += 1
    sec = time.perf_counter() - start
    npts = len(alphas) * len(betas)
    print(json.dumps({"d": d, "points_timed": npts, "seconds": sec,
                      "ns_per_point": sec / npts * 1e9, "stable_fraction": stable / npts}))


if __name__ == "__main__":
    main()
