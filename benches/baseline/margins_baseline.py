"""python-control's stability_margins on the paper's sampled loop (m = 1.1 kg, b = 7.5 Ns/m,
k = 350 N/m, T = 1 ms, d samples, backward-difference velocity), the walls of
crates/hapstab/benches/margins.rs (K = 10 kN/m, B = 10 Ns/m at d = 0, 1; 500 N/m, 0.5 Ns/m at d = 10): L(z) = (K + B (z - 1)/(T z)) P_zoh(z) z^-d. Prints the mean time per call.
Run: python3 benches/baseline/margins_baseline.py (needs control, numpy)."""
import time
import warnings

import control as ct

warnings.simplefilter("ignore")
T = 1e-3
P = ct.sample_system(ct.tf([1.0], [1.1, 7.5, 350.0]), T, "zoh")
for d, K, B in ((0, 1e4, 10.0), (1, 1e4, 10.0), (10, 500.0, 0.5)):
    C = ct.tf([K + B / T, -B / T], [1.0, 0.0], T)
    L = C * P * ct.tf([1.0], [1.0] + [0.0] * d, T)
    n = 50
    t = time.perf_counter()
    for _ in range(n):
        m = ct.stability_margins(L)
    dt = (time.perf_counter() - t) / n
    print(f"d = {d}: stability_margins {dt * 1e3:.3f} ms  gm {m[0]:.6g} pm {m[1]:.6g} sm {m[2]:.6g}")
