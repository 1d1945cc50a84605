"""Baseline: the population and robust questions the way they are answered today, with
numpy.roots per operator.

Same loop as crates/hapstab/benches/population.rs: the PHANToM-like device (0.1 kg, 1.5 Ns/m)
held by an arm, T = 1 ms, d = 0, backward-difference velocity; the paper's Section IV
population (m_H uniform 0.5..2 kg, k_H/m_H uniform 0..710 s⁻², b_H/m_H uniform 0..12.6 s⁻¹).
Each operator's ZOH plant comes from the paper's eq. (5) in complex arithmetic (normalized:
γ = kT²/m, δ = bT/m, α = KT²/m, β = BT/m), p(z) = z D(z) + N(z)((α + β)z − β) is rooted with
numpy.roots.

- wall: P(stable) of the wall K = 20 kN/m, B = 5 Ns/m over `n_wall` operators, per operator;
- robust: K_max at B = 5 of each of `n_robust` plants of the box k_H 0..2000 N/m,
  m_H 0.2..2 kg, b_H 2..12 Ns/m by bisection on K (50 steps, numpy.roots each), per plant.

Prints one JSON line: {"wall_us_per_operator": .., "robust_ms_per_plant": .., "p_stable": ..}
"""
import cmath
import json
import sys
import time

import numpy as np

T, M_L, B_L = 1e-3, 0.1, 1.5


def plant(gamma, delta):
    """(n1, n0, a1, a0) of eq. (5)/(6) (the common factor T²/m dropped)."""
    c1 = cmath.sqrt(delta * delta - 4 * gamma)
    if abs(c1) < 1e-12:
        c1 = 1e-12
    c2 = cmath.exp(-(delta + c1) / 2)
    c3 = cmath.exp(-(delta - c1) / 2)
    ed = np.exp(-delta)
    den = c1 * gamma if gamma != 0 else c1 * 1e-300
    n1 = ((2 - c2 - c3) * c1 + (c2 - c3) * delta) / (2 * den)
    n0 = ((2 * ed - c3 - c2) * c1 + (c3 - c2) * delta) / (2 * den)
    return n1.real, n0.real, (c2 + c3).real, ed


def stable(m_h, b_h, k_h, k, b):
    m = M_L + m_h
    gamma, delta = max(k_h, 1e-9) * T * T / m, (B_L + b_h) * T / m
    alpha, beta = k * T * T / m, b * T / m
    n1, n0, a1, a0 = plant(gamma, delta)
    # z·(z² − a1 z + a0) + (n1 z + n0)((α + β) z − β)
    p = np.array([1.0, -a1, a0, 0.0])
    p[1:] += np.convolve([n1, n0], [alpha + beta, -beta])
    return np.max(np.abs(np.roots(p))) < 1.0


def main():
    n_wall = int(sys.argv[1]) if len(sys.argv) > 1 else 20000
    n_robust = int(sys.argv[2]) if len(sys.argv) > 2 else 50
    rng = np.random.default_rng(1)
    m = rng.uniform(0.5, 2.0, n_wall)
    ops = np.stack([m, rng.uniform(0, 12.6, n_wall) * m, rng.uniform(0, 710, n_wall) * m], 1)
    t0 = time.perf_counter()
    count = sum(stable(mh, bh, kh, 2e4, 5.0) for mh, bh, kh in ops)
    wall = (time.perf_counter() - t0) / n_wall
    box = np.stack([rng.uniform(0.2, 2.0, n_robust), rng.uniform(2, 12, n_robust),
                    rng.uniform(0, 2000, n_robust)], 1)
    t0 = time.perf_counter()
    worst = np.inf
    for mh, bh, kh in box:
        lo, hi = 0.0, 1e6
        for _ in range(50):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if stable(mh, bh, kh, mid, 5.0) else (lo, mid)
        worst = min(worst, lo)
    robust = (time.perf_counter() - t0) / n_robust
    print(json.dumps({"wall_us_per_operator": wall * 1e6, "robust_ms_per_plant": robust * 1e3,
                      "p_stable": count / n_wall, "robust_k_max_sampled": worst}))


if __name__ == "__main__":
    main()
