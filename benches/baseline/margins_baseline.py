"""python-control's stability_margins on the paper's sampled loop (m = 1.1 kg, b = 7.5 Ns/m,
k = 350 N/m, T = 1 ms, d samples, backward-difference velocity), the walls of
crates/hapstab/benches/margins.rs (K = 10 kN/m, B = 10 Ns/m at d = 0, 1; 500 N/m, 0.5 Ns/m at d = 10): L(z) = (K + B (z - 1)/(T z)) P_zoh(z) z^-d; and the bench's order-6 loop at d = 10
(the device and arm behind an 80 Hz resonance, damping ratio 0.05, and two 0.5 ms lags) with
the same wall. Prints the mean time per call.
Run: python3 benches/baseline/margins_baseline.py (needs control, numpy)."""
import time
import warnings

import math

import control as ct

warnings.simplefilter("ignore")
T = 1e-3
P = ct.sample_system(ct.tf([1.0], [1.1, 7.5, 350.0]), T, "zoh")
w, zeta, tau = 2 * math.pi * 80.0, 0.05, 5e-4
P6 = ct.sample_system(
    ct.tf([w * w], [1.1, 7.5, 350.0]) * ct.tf([1.0], [1.0, 2 * zeta * w, w * w])
    * ct.tf([1.0], [tau, 1.0]) * ct.tf([1.0], [tau, 1.0]),
    T, "zoh")
for name, plant, d, K, B in (("paper", P, 0, 1e4, 10.0), ("paper", P, 1, 1e4, 10.0),
                             ("paper", P, 10, 500.0, 0.5), ("order 6", P6, 10, 500.0, 0.5)):
    C = ct.tf([K + B / T, -B / T], [1.0, 0.0], T)
    L = C * plant * ct.tf([1.0], [1.0] + [0.0] * d, T)
    n = 50
    t = time.perf_counter()
    for _ in range(n):
        m = ct.stability_margins(L)
    dt = (time.perf_counter() - t) / n
    print(f"{name} d = {d}: stability_margins {dt * 1e3:.3f} ms  gm {m[0]:.6g} pm {m[1]:.6g} sm {m[2]:.6g}")
