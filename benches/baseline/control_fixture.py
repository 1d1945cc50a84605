#!/usr/bin/env python3
"""Independent closed loops computed with python-control only, for hapstab's cross-check.

Needs `pip install control numpy` (benches/baseline/control_fixture.sh makes a venv under
target/ with them). Usage:

    python benches/baseline/control_fixture.py [--seed S] [--loops N] [--out PATH]

Generates N seeded random haptic loops (mass-spring-damper device + arm, two-mass devices,
random stable or marginal transfer functions up to order 6, with or without a first-order
actuator lag; whole delays 0..10 samples; every velocity estimator) and for each two walls
(K, B), one near the stability boundary and one away from it. For every case the closed loop
is formed with python-control alone:

    H = control.sample_system(control.ss(P), T, 'zoh')   plant behind a zero-order hold
    G = H * z^(-d)                                       the wall force's delay (a tf)
    C = K + B * V(z)                                     the wall with the velocity estimator
    poles(control.feedback(G, C))                        1 + G C = 0

The plant is sampled as a state-space model, so python-control closes the loop in state
space and its poles are eigenvalues of the closed loop's state matrix. (Sampling a
TransferFunction instead makes python-control close the loop on expanded polynomials in z,
whose roots lose up to 1e-3 relative when several plant poles lie within 1e-2 of z = 1, as
benches/baseline/control_mpmath.py shows on this fixture's loops.)

The spectral radius max |pole| and the verdict (stable iff it is < 1) are written to the
fixture crates/hapstab/tests/fixtures/control_loops.json that
crates/hapstab/tests/engine/python_control.rs reads. Plants and velocity estimators are written in
hapstab's own forms (serde `PlantModel`, the `--velocity` spec text) so that the Rust test
builds the same loop from the same numbers.
"""

import argparse
import json
import math
import sys

import control
import numpy as np

MAX_DELAY = 10
# The boundary wall is bisected in K to this relative width before being moved off it.
BISECT_REL = 1e-13


def log_uniform(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


# ---- plants -------------------------------------------------------------------------------


def arm(rng):
    if rng.random() < 0.3:
        return {"mass": 0.0, "damping": 0.0, "stiffness": 0.0}
    return {
        "mass": float(rng.uniform(0.3, 2.0)),
        "damping": float(rng.uniform(1.0, 12.0)),
        "stiffness": float(rng.uniform(0.0, 700.0)),
    }


def mass_spring_damper(rng):
    a = arm(rng)
    m_l, b_l = log_uniform(rng, 0.02, 1.0), float(rng.uniform(0.0, 3.0))
    return {
        "kind": "mass_spring_damper",
        "mass": m_l + a["mass"],
        "damping": b_l + a["damping"],
        "stiffness": a["stiffness"],
    }


def two_mass(rng):
    return {
        "kind": "two_mass",
        "motor_mass": log_uniform(rng, 0.01, 0.5),
        "motor_damping": float(rng.uniform(0.0, 2.0)),
        "handle_mass": log_uniform(rng, 0.01, 0.5),
        "transmission_stiffness": log_uniform(rng, 1e3, 1e6),
        "transmission_damping": float(rng.uniform(0.0, 10.0)),
        "arm": arm(rng),
    }


def random_poles(rng, n, period):
    """n poles of a stable or marginal plant: real, complex pairs, integrators, undamped pairs."""
    w_max = 0.5 / period  # keep most modes below a sixth of the sampling frequency
    poles = []
    while len(poles) < n:
        r = rng.random()
        if n - len(poles) >= 2 and r < 0.5:
            w = log_uniform(rng, 2.0, w_max)
            zeta = 0.0 if rng.random() < 0.15 else float(rng.uniform(0.02, 1.0))
            re, im = -zeta * w, w * math.sqrt(1.0 - zeta * zeta)
            poles += [complex(re, im), complex(re, -im)]
        elif r < 0.6 and sum(p == 0 for p in poles) < 2:
            poles.append(0j)  # an integrator; two make a free mass
        else:
            poles.append(complex(-log_uniform(rng, 1.0, w_max), 0.0))
    return poles


def transfer_function(rng, order, period):
    """A strictly proper num(s)/den(s), gain scaled to a mass of 0.1..2 kg at 20 Hz."""
    den = np.real(np.poly(random_poles(rng, order, period)))
    n_zeros = int(rng.integers(0, order))  # numerator degree < order
    zeros = []
    while len(zeros) < n_zeros:
        if n_zeros - len(zeros) >= 2 and rng.random() < 0.4:
            w = log_uniform(rng, 2.0, 0.5 / period)
            zeta = float(rng.uniform(0.05, 1.0))
            zeros += [complex(-zeta * w, w * math.sqrt(1 - zeta * zeta))]
            zeros += [zeros[-1].conjugate()]
        else:
            zeros.append(complex(-log_uniform(rng, 1.0, 0.5 / period), 0.0))
    num = np.real(np.poly(zeros)) if zeros else np.array([1.0])
    w = 2 * math.pi * 20.0
    gain = abs(np.polyval(den, 1j * w) / np.polyval(num, 1j * w)) / (
        log_uniform(rng, 0.1, 2.0) * w * w
    )
    num = num * gain
    return {"kind": "transfer_function", "num": [float(x) for x in num], "den": [float(x) for x in den]}


def continuous_plant(plant):
    """python-control model of a plant from force (N) to position (m), SI units."""
    kind = plant["kind"]
    if kind == "mass_spring_damper":
        return control.tf([1.0], [plant["mass"], plant["damping"], plant["stiffness"]])
    if kind == "transfer_function":
        return control.tf(plant["num"], plant["den"])
    j, bm = plant["motor_mass"], plant["motor_damping"]
    mh = plant["handle_mass"] + plant["arm"]["mass"]
    kt, bt = plant["transmission_stiffness"], plant["transmission_damping"]
    kh, bh = plant["arm"]["stiffness"], plant["arm"]["damping"]
    a = [
        [0, 1, 0, 0],
        [-kt / j, -(bm + bt) / j, kt / j, bt / j],
        [0, 0, 0, 1],
        [kt / mh, bt / mh, -(kt + kh) / mh, -(bt + bh) / mh],
    ]
    return control.ss(a, [[0], [1 / j], [0], [0]], [[1, 0, 0, 0]], [[0]])


def reference_mass(plant, period):
    """The mass that scales walls: 1/(w^2 |P(jw)|) at w = 1/T."""
    w = 1.0 / period
    p = continuous_plant(plant)
    g = abs(complex(control.evalfr(p, 1j * w)))
    return 1.0 / (w * w * g)


# ---- velocity estimators ------------------------------------------------------------------


def velocity_spec(rng, period):
    kind = rng.integers(0, 4)
    if kind == 0:
        return "backward"
    if kind == 1:
        return f"lowpass:{log_uniform(rng, 5.0, 0.3 / period)!r}"
    if kind == 2:
        return f"average:{int(rng.integers(1, 21))}"
    # a low-passed difference: (1 - z^-1)/T times a stable second-order low-pass of unit DC gain
    r, th = float(rng.uniform(0.2, 0.9)), float(rng.uniform(0.0, 1.2))
    a = [1.0, -2 * r * math.cos(th), r * r]
    g = sum(a)
    b = [g / period, -g / period]
    if rng.random() < 0.5:  # and sometimes an extra numerator tap
        b.append(float(rng.uniform(-0.2, 0.2)) * g / period)
    return "iir:" + ",".join(repr(x) for x in b) + "/" + ",".join(repr(x) for x in a)


def velocity_tf(spec, period):
    """The estimator as a python-control discrete tf from position (m) to velocity (m/s)."""
    kind, _, arg = spec.partition(":")
    t = period
    if kind == "backward":
        return control.tf([1.0, -1.0], [t, 0.0], t)
    if kind == "lowpass":
        a = math.exp(-2 * math.pi * float(arg) * t)
        return control.tf([(1 - a), -(1 - a)], [t, -a * t], t)
    if kind == "average":
        n = int(arg)
        num = [1.0] + [0.0] * (n - 1) + [-1.0]
        den = [n * t] + [0.0] * n
        return control.tf(num, den, t)
    b_txt, a_txt = arg.split("/")
    b = [float(x) for x in b_txt.split(",")]
    a = [float(x) for x in a_txt.split(",")]
    length = max(len(b), len(a))  # sum b_i z^-i = z^-(L-1) sum b_i z^(L-1-i)
    return control.tf(b + [0.0] * (length - len(b)), a + [0.0] * (length - len(a)), t)


# ---- the closed loop ----------------------------------------------------------------------


class ClosedLoop:
    """The open loop G = H z^-d and V(z) of one loop; walls close it."""

    def __init__(self, case):
        t = case["period"]
        p = continuous_plant(case["plant"])
        if case["force_lag"] > 0:
            p = p * control.tf([1.0], [case["force_lag"], 1.0])
        h = control.sample_system(control.ss(p), t, "zoh")
        delay = control.tf([1.0], [1.0] + [0.0] * case["delay"], t)
        self.g = h * delay
        self.v = velocity_tf(case["velocity"], t)
        self.t = t

    def poles(self, k, b):
        c = control.tf([k], [1.0], self.t) + b * self.v
        return control.poles(control.feedback(self.g, c))

    def radius(self, k, b):
        return float(np.max(np.abs(self.poles(k, b))))


def boundary_k(cl, b, k_ref):
    """A K where the radius crosses 1 at damping b (scanning then bisecting), or None."""
    ks = [k_ref * 10.0 ** e for e in np.linspace(-5, 3, 49)]
    rs = [cl.radius(k, b) for k in ks]
    for (k0, r0), (k1, r1) in zip(zip(ks, rs), zip(ks[1:], rs[1:])):
        if (r0 < 1) != (r1 < 1):
            lo, hi, slo = k0, k1, r0 < 1
            while hi - lo > BISECT_REL * hi:
                mid = 0.5 * (lo + hi)
                if (cl.radius(mid, b) < 1) == slo:
                    lo = mid
                else:
                    hi = mid
            return 0.5 * (lo + hi), ks, rs
    return None, ks, rs


def random_case(rng, i):
    period = float(rng.choice([1e-4, 2.5e-4, 5e-4, 1e-3, 2e-3]))
    category = ["mass_spring_damper", "two_mass", "transfer_function"][i % 3]
    if category == "mass_spring_damper":
        plant = mass_spring_damper(rng)
    elif category == "two_mass":
        plant = two_mass(rng)
    lag = log_uniform(rng, 5e-5, 3e-3) if rng.random() < 0.3 else 0.0
    if category == "transfer_function":
        order = int(rng.integers(1, 6 if lag > 0 else 7))
        plant = transfer_function(rng, order, period)
    return {
        "category": category,
        "plant": plant,
        "force_lag": lag,
        "period": period,
        "delay": int(rng.integers(0, MAX_DELAY + 1)),
        "velocity": velocity_spec(rng, period),
    }


def walls(rng, case, cl):
    """One wall near the boundary (K off by 1e-7..1e-3 relative) and one away from it (half
    of them stable where the scan found stable walls)."""
    m = reference_mass(case["plant"], case["period"])
    k_ref = m / case["period"] ** 2
    b = float(rng.uniform(0.0, 1.0)) * m / case["period"] / (case["delay"] + 1)
    for _ in range(6):  # a damping too large for the delay has no stable K: halve it
        kb, ks, rs = boundary_k(cl, b, k_ref)
        if kb is not None:
            break
        b *= 0.5
    stable = [i for i, r in enumerate(rs) if r < 1]
    pool = stable if stable and rng.random() < 0.5 else list(range(len(ks)))
    away = pool[int(rng.integers(0, len(pool)))]
    out = [("away", ks[away], b)]
    if kb is not None:
        side = 1 if rng.random() < 0.5 else -1
        out.append(("near", kb * (1 + side * 10.0 ** rng.uniform(-7, -3)), b))
    return out


def record(case, kind, k, b, cl):
    poles = cl.poles(k, b)
    rho = float(np.max(np.abs(poles)))
    return dict(
        case,
        wall_kind=kind,
        wall={"stiffness": float(k), "damping": float(b)},
        degree=len(poles),
        spectral_radius=rho,
        verdict="stable" if rho < 1 else "unstable",
    )


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seed", type=int, default=20080922)
    ap.add_argument("--loops", type=int, default=240)
    ap.add_argument("--out", default="crates/hapstab/tests/fixtures/control_loops.json")
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    cases = []
    for i in range(args.loops):
        case = random_case(rng, i)
        case["id"] = i
        cl = ClosedLoop(case)
        for kind, k, b in walls(rng, case, cl):
            cases.append(record(case, kind, k, b, cl))
    fixture = {
        "generator": "benches/baseline/control_fixture.py",
        "seed": args.seed,
        "python_control": control.__version__,
        "numpy": np.__version__,
        "cases": cases,
    }
    with open(args.out, "w") as f:
        json.dump(fixture, f, indent=1)
        f.write("\n")
    print(f"{len(cases)} cases from {args.loops} loops written to {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
