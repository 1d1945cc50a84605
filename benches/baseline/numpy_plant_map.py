"""A map whose axes are the plant's (gamma, delta) the way a user would compute it: for every
point, the zero-order hold of the paper's normalized plant 1/(s^2 + delta*s + gamma) by
scipy.linalg.expm of the augmented matrix (Van Loan), the characteristic polynomial of eq. (9)
p(z) = z^(d+1) D(z) + N(z)((alpha + beta) z - beta), and numpy.roots.

Every `step`-th row and column is timed; the time per point is scaled to the whole map, and
the verdicts are compared with hapstab's CSV of the same map (points within 1e-9 of |z| = 1
skipped).
Usage: python numpy_plant_map.py HAPSTAB_BINARY [step]   prints one JSON line.
"""
import csv
import json
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.linalg import expm

ALPHA, BETA, D = 0.15, 0.3, 2
GAMMA = (0.0, 0.05, 400)
DELTA = (0.0, 0.5, 400)


def radius(gamma, delta):
    """Largest root modulus of p(z) at (ALPHA, BETA) for the plant (gamma, delta), T = m = 1."""
    aug = np.zeros((3, 3))
    aug[:2, :2] = [[0.0, 1.0], [-gamma, -delta]]
    aug[:2, 2] = [0.0, 1.0]
    e = expm(aug)
    phi, gam = e[:2, :2], e[:2, 2]
    den = np.array([1.0, -np.trace(phi), np.linalg.det(phi)])  # z^2 - tr z + det
    # N(z) = C adj(zI - Phi) Gamma with C = [1, 0]
    num = np.array([gam[0], phi[0, 1] * gam[1] - phi[1, 1] * gam[0]])
    p = np.polyadd(np.polymul(np.r_[1.0, np.zeros(D + 1)], den),
                   np.polymul(num, [ALPHA + BETA, -BETA]))
    return np.max(np.abs(np.roots(p)))


def main():
    binary = sys.argv[1]
    step = int(sys.argv[2]) if len(sys.argv) > 2 else 10
    with tempfile.NamedTemporaryFile(suffix=".csv") as f:
        subprocess.run([binary, "map", "--x", "gamma:%g:%g:%d" % GAMMA,
                        "--y", "delta:%g:%g:%d" % DELTA, "--alpha", str(ALPHA),
                        "--beta", str(BETA), "--delay", str(D), "--out", f.name],
                       check=True, capture_output=True)
        rows = list(csv.DictReader(open(f.name)))
    nx, ny = GAMMA[2], DELTA[2]
    gammas = np.linspace(*GAMMA[:2], nx)
    deltas = np.linspace(*DELTA[:2], ny)
    points, disagree, skipped = 0, 0, 0
    t0 = time.perf_counter()
    radii = {}
    for iy in range(0, ny, step):
        for ix in range(0, nx, step):
            radii[(ix, iy)] = radius(gammas[ix], deltas[iy])
            points += 1
    seconds = time.perf_counter() - t0
    for (ix, iy), r in radii.items():
        if abs(r - 1.0) < 1e-9:
            skipped += 1
            continue
        if (r < 1.0) != (rows[iy * nx + ix]["stable"] == "1"):
            disagree += 1
    print(json.dumps({"points_timed": points, "seconds_per_point": seconds / points,
                      "scaled_to_map_s": seconds / points * nx * ny,
                      "disagreements": disagree, "skipped_near_circle": skipped}))


if __name__ == "__main__":
    main()
