#!/usr/bin/env python3
"""The 1000 × 1000 stability map of `cargo bench -p hapstab --bench map` from Python: with the
hapstab package (hapstab.stability_map, the whole grid, mean and best of repeated runs) and
with python-control point by point (the closed loop's poles through its state-space route,
timed on a subset of the grid and scaled per point).

The grid is the Rust bench's: the paper's loop with γ = 0.001, δ = 0.015 and d samples of
delay in normalized units (Loop.normalized: K = α, B = β), α ∈ [−0.05, 1/(d + 1/2)],
β ∈ [−0.05, 2/(d + 1/2)^(1/2)], 1000 points each. Prints one JSON object per d.

Needs the hapstab package, numpy and python-control (benches/python_compare.sh makes the
venv). Usage: python benches/baseline/python_map.py [--runs N] [--stride S]
"""

import argparse
import json
import time

import control
import numpy as np

import hapstab as hs

GAMMA, DELTA, N = 0.001, 0.015, 1000


def axes(d):
    t = d + 0.5
    return np.linspace(-0.05, 1.0 / t, N), np.linspace(-0.05, 2.0 / t**0.5, N)


def hapstab_seconds(d, runs):
    lp = hs.Loop.normalized(gamma=GAMMA, delta=DELTA, d=d)
    a, b = axes(d)
    hs.stability_map(lp, a, b)  # warm-up (thread pool, page faults)
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        m = hs.stability_map(lp, a, b)
        times.append(time.perf_counter() - t0)
    return times, int(m.stable.sum())


class ControlLoop:
    """The same loop with python-control alone: P = 1/(s² + δs + γ) sampled with T = 1 as a
    state-space model, the delay z^(−d), the wall α + β(z − 1)/z (backward difference)."""

    def __init__(self, d):
        h = control.sample_system(control.ss(control.tf([1.0], [1.0, DELTA, GAMMA])), 1.0, "zoh")
        self.g = h * control.tf([1.0], [1.0] + [0.0] * d, 1.0)
        self.v = control.tf([1.0, -1.0], [1.0, 0.0], 1.0)

    def stable(self, alpha, beta):
        c = control.tf([alpha], [1.0], 1.0) + beta * self.v
        return bool(np.max(np.abs(control.poles(control.feedback(self.g, c)))) < 1.0)


def control_seconds_per_point(d, stride):
    cl = ControlLoop(d)
    a, b = axes(d)
    pts = [(x, y) for y in b[::stride] for x in a[::stride]]
    t0 = time.perf_counter()
    n_stable = sum(cl.stable(x, y) for x, y in pts)
    return (time.perf_counter() - t0) / len(pts), len(pts), n_stable


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=10)
    ap.add_argument("--stride", type=int, default=50)
    args = ap.parse_args()
    for d in (0, 10):
        times, stable = hapstab_seconds(d, args.runs)
        per_point, timed, _ = control_seconds_per_point(d, args.stride)
        print(json.dumps({
            "d": d,
            "hapstab_mean_s": float(np.mean(times)),
            "hapstab_min_s": float(np.min(times)),
            "stable_points": stable,
            "control_s_per_point": per_point,
            "control_points_timed": timed,
            "control_s_per_map": per_point * N * N,
        }))


if __name__ == "__main__":
    main()
