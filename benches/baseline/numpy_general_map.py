"""numpy.roots point by point over the general-loop map of `cargo bench -p hapstab --bench map`
(general_loop_order5_d1: a two-mass device with a 0.2 ms actuator lag, a 200 Hz low-pass
velocity estimate and one sample of delay; K from -2 kN/m to 40 kN/m and B from -5 to
40 Ns/m, 1000 x 1000).

p(z) is affine in the wall, p = P0 + K*PK + B*PB, so its coefficients at any wall follow from
`hapstab discretize --json` at three walls. Every `step`-th row and column is timed (numpy.roots
and the spectral radius < 1), and the time per point is scaled to the whole map.
Usage: python numpy_general_map.py HAPSTAB_BINARY [step]   prints one JSON line.
"""
import json
import subprocess
import sys
import time

import numpy as np

LOOP = ["--motor-mass", "0.05", "--motor-damping", "0.5", "--handle-mass", "0.05",
        "--transmission-stiffness", "2e4", "--transmission-damping", "2", "--force-lag", "2e-4",
        "--velocity", "lowpass:200", "--delay", "1"]


def characteristic(binary, k, b):
    out = subprocess.run([binary, "discretize", *LOOP, "--wall-stiffness", str(k),
                          "--wall-damping", str(b), "--json"], check=True, capture_output=True,
                         text=True).stdout
    return np.array(json.loads(out)["characteristic"], dtype=float)  # descending powers of z


def main():
    binary = sys.argv[1]
    step = int(sys.argv[2]) if len(sys.argv) > 2 else 50
    p0 = characteristic(binary, 0.0, 0.0)
    pk = characteristic(binary, 1.0, 0.0) - p0
    pb = characteristic(binary, 0.0, 1.0) - p0
    ks = np.linspace(-2e3, 40e3, 1000)[::step]
    bs = np.linspace(-5.0, 40.0, 1000)[::step]
    stable = 0
    t0 = time.perf_counter()
    for b in bs:
        for k in ks:
            r = np.roots(p0 + k * pk + b * pb)
            stable += bool(np.max(np.abs(r)) < 1.0)
    dt = time.perf_counter() - t0
    n = len(ks) * len(bs)
    print(json.dumps({"points_timed": n, "ns_per_point": dt / n * 1e9,
                      "stable_fraction": stable / n, "degree": len(p0) - 1}))


if __name__ == "__main__":
    main()
