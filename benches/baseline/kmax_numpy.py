"""K_max the way it is done today: a bisection on K with numpy.roots, for the general loop of
`cargo bench -p hapstab --bench kmax` (a two-mass device held by the typical arm, a 0.2 ms
actuator lag, a 200 Hz low-pass velocity estimate, T = 1 ms) at d = 0, 1, 10.

p(z) is affine in the wall, p = P0 + K*PK + B*PB, so its coefficients follow from
`hapstab discretize --json` at three walls. At B = 5 Ns/m: K doubled from 1 N/m until the
spectral radius reaches 1, then 50 bisection steps (numpy.roots each). Over the band B >= 0 a
designer grids B: 50 dampings from 0 to the largest stable one, a bisection at each.
Prints one JSON line per delay: the time per K_max at one damping, the time of the band grid,
and the K_max found (to compare with `hapstab kmax`).
Usage: python kmax_numpy.py HAPSTAB_BINARY
"""
import json
import subprocess
import sys
import time

import numpy as np

LOOP = ["--motor-mass", "0.05", "--motor-damping", "0.5", "--handle-mass", "0.05",
        "--transmission-stiffness", "2e4", "--transmission-damping", "2", "--force-lag", "2e-4",
        "--velocity", "lowpass:200"]


def characteristic(binary, d, k, b):
    out = subprocess.run([binary, "discretize", *LOOP, "--delay", str(d), "--wall-stiffness",
                          str(k), "--wall-damping", str(b), "--json"], check=True,
                         capture_output=True, text=True).stdout
    return np.array(json.loads(out)["characteristic"], dtype=float)  # descending powers of z


def stable(p):
    return np.max(np.abs(np.roots(p))) < 1.0


def k_max(p0, pk, pb, b, steps=50):
    """Largest K of the stable interval from K = 0 up, by bisection (None if K = 0 unstable)."""
    if not stable(p0 + b * pb):
        return None
    lo, hi = 0.0, 1.0
    while stable(p0 + hi * pk + b * pb):
        lo, hi = hi, 2.0 * hi
        if hi > 1e12:
            return None
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        if stable(p0 + mid * pk + b * pb):
            lo = mid
        else:
            hi = mid
    return lo


def main():
    binary = sys.argv[1]
    for d in (0, 1, 10):
        p0 = characteristic(binary, d, 0.0, 0.0)
        pk = characteristic(binary, d, 1.0, 0.0) - p0
        pb = characteristic(binary, d, 0.0, 1.0) - p0
        reps = 20
        t0 = time.perf_counter()
        for _ in range(reps):
            k5 = k_max(p0, pk, pb, 5.0)
        at_damping = (time.perf_counter() - t0) / reps
        # the band B >= 0 on a grid of 50 dampings up to the largest stable one
        b_top = 1.0
        while k_max(p0, pk, pb, b_top, steps=5) is not None and b_top < 1e6:
            b_top *= 2.0
        t0 = time.perf_counter()
        best = max((k_max(p0, pk, pb, b) or 0.0, b) for b in np.linspace(0.0, b_top, 50))
        band = time.perf_counter() - t0
        print(json.dumps({"d": d, "degree": len(p0) - 1, "at_damping_s": at_damping,
                          "k_max_at_5": k5, "band_grid_s": band, "band_grid_k_max": best[0],
                          "band_grid_b": best[1]}))


if __name__ == "__main__":
    main()
