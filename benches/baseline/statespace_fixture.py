#!/usr/bin/env python3
"""Seeded random haptic loops refereed in state space (statespace_referee.py), written to
crates/hapstab/tests/fixtures/statespace_loops.json for crates/hapstab/tests/engine/statespace_referee.rs.

Usage (benches/baseline/statespace_fixture.sh runs it in a venv with numpy, scipy, mpmath):

    python benches/baseline/statespace_fixture.py [--seed S] [--loops N] [--out PATH]

Loops: mass-spring-damper devices with and without an arm (pure masses among them),
two-mass devices with and without an arm (undamped ones among them: motor and transmission
damping 0, no arm: a lossless resonance over a rigid-body mode), transfer functions of order
1 to 6 (integrators and undamped pairs among their poles), each with or without an actuator
lag; whole delays (--delay d) and fractional ones (--delay-time t_d), d mostly 0..20 and
sometimes up to 64; T log-uniform in [1e-4, 1e-2] s; every velocity estimator (backward,
lowpass:FC, average:N, iir:b/a). The audit loops of AUDIT_LOOPS are added verbatim.

Per loop, at three dampings B (0 and two drawn ones): the referee's stable K intervals (a
log-grid scan of K over both signs, every sign change bisected to 1e-12 relative), walls
1e-6 relative either side of the largest crossing (K_max) at each B and of every crossing at
the first drawn B; a stable and an unstable wall away from the boundary; walls at K = 0 and
at B = 0; a negative K. Per wall: K, B, the referee's spectral radius, the verdict (stable iff
rho < 1) and whether the 40-digit path gave it.
"""

import argparse
import json
import math
import multiprocessing
import sys

import mpmath as mp
import numpy as np
import scipy

import statespace_referee as ref_mod
from statespace_referee import Referee, scan_grid, stable_intervals

# Near walls sit this far (relative in K) either side of a bisected crossing.
NEAR_OFFSET = 1e-6
# Largest whole delay of most loops, and of the few long ones.
MAX_DELAY, MAX_LONG_DELAY = 20, 64
# Quarterings of the damping scale tried before a loop is taken to have no stable wall.
DAMPING_TRIES = 24
# Mirror of hapstab's Delay::from_time snapping (a ratio within 1e-12 of a whole number is
# that number): the fixture stores the (d, lam) that hapstab reads from --delay-time.
WHOLE_SAMPLE_TOL = 1e-12


def log_uniform(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


# ---- plants -----------------------------------------------------------------------------------


def arm(rng, p_none):
    if rng.random() < p_none:
        return {"mass": 0.0, "damping": 0.0, "stiffness": 0.0}
    return {
        "mass": float(rng.uniform(0.3, 2.0)),
        "damping": float(rng.uniform(1.0, 12.0)),
        "stiffness": float(rng.uniform(0.0, 700.0)),
    }


def mass_spring_damper(rng):
    a = arm(rng, 0.4)
    m_l = log_uniform(rng, 0.02, 1.0)
    b_l = 0.0 if a["mass"] == 0 and rng.random() < 0.25 else float(rng.uniform(0.0, 3.0))
    return {"kind": "mass_spring_damper", "mass": m_l + a["mass"], "damping": b_l + a["damping"],
            "stiffness": a["stiffness"]}


def two_mass(rng):
    undamped = rng.random() < 0.3
    return {
        "kind": "two_mass",
        "motor_mass": log_uniform(rng, 0.01, 1.0),
        "motor_damping": 0.0 if undamped else float(rng.uniform(0.0, 2.0)),
        "handle_mass": log_uniform(rng, 0.01, 0.5),
        "transmission_stiffness": log_uniform(rng, 1e3, 1e6),
        "transmission_damping": 0.0 if undamped else float(rng.uniform(0.0, 10.0)),
        "arm": arm(rng, 1.0 if undamped else 0.5),
    }


def random_poles(rng, n, period):
    """n poles of a stable or marginal plant: real, complex pairs, integrators, undamped pairs."""
    w_max = 0.5 / period
    poles = []
    while len(poles) < n:
        r = rng.random()
        if n - len(poles) >= 2 and r < 0.5:
            w = log_uniform(rng, 2.0, w_max)
            zeta = 0.0 if rng.random() < 0.15 else float(rng.uniform(0.02, 1.0))
            re, im = -zeta * w, w * math.sqrt(1.0 - zeta * zeta)
            poles += [complex(re, im), complex(re, -im)]
        elif r < 0.6 and sum(p == 0 for p in poles) < 2:
            poles.append(0j)
        else:
            poles.append(complex(-log_uniform(rng, 1.0, w_max), 0.0))
    return poles


def transfer_function(rng, order, period):
    """A strictly proper num(s)/den(s), its gain that of a 0.1..2 kg mass at 20 Hz."""
    den = np.real(np.poly(random_poles(rng, order, period)))
    n_zeros = int(rng.integers(0, order))
    zeros = []
    while len(zeros) < n_zeros:
        if n_zeros - len(zeros) >= 2 and rng.random() < 0.4:
            w = log_uniform(rng, 2.0, 0.5 / period)
            zeta = float(rng.uniform(0.05, 1.0))
            z = complex(-zeta * w, w * math.sqrt(1 - zeta * zeta))
            zeros += [z, z.conjugate()]
        else:
            zeros.append(complex(-log_uniform(rng, 1.0, 0.5 / period), 0.0))
    num = np.real(np.poly(zeros)) if zeros else np.array([1.0])
    w = 2 * math.pi * 20.0
    gain = abs(np.polyval(den, 1j * w) / np.polyval(num, 1j * w)) / (log_uniform(rng, 0.1, 2.0) * w * w)
    return {"kind": "transfer_function", "num": [float(x) for x in num * gain], "den": [float(x) for x in den]}


# ---- velocity estimators and delays ---------------------------------------------------------


def velocity_spec(rng, period):
    kind = int(rng.integers(0, 4))
    if kind == 0:
        return "backward"
    if kind == 1:
        return f"lowpass:{log_uniform(rng, 5.0, 0.3 / period)!r}"
    if kind == 2:
        return f"average:{int(rng.integers(1, 21))}"
    r, th = float(rng.uniform(0.2, 0.9)), float(rng.uniform(0.0, 1.2))
    a = [1.0, -2 * r * math.cos(th), r * r]
    g = sum(a)
    if rng.random() < 0.25:  # a general filter, not blocking DC
        b = [float(x) * g / period for x in rng.uniform(-1.0, 1.0, int(rng.integers(2, 5)))]
        b[0] = abs(b[0]) + 0.5 * g / period
    else:  # a low-passed difference, sometimes with an extra tap
        b = [g / period, -g / period]
        if rng.random() < 0.5:
            b.append(float(rng.uniform(-0.2, 0.2)) * g / period)
    return "iir:" + ",".join(repr(x) for x in b) + "/" + ",".join(repr(x) for x in a)


def delay_from_time(delay_time, period):
    """hapstab's Delay::from_time: d = floor(t_d/T), lam = t_d/T - d, whole when within
    1e-12 of a whole number (the same double operations, so the same (d, lam))."""
    ratio = delay_time / period
    nearest = round(ratio)
    if abs(ratio - nearest) <= WHOLE_SAMPLE_TOL * max(nearest, 1.0):
        return {"samples": int(nearest), "fraction": 0.0}
    d = math.floor(ratio)
    return {"samples": int(d), "fraction": ratio - d}


def random_delay(rng, period):
    """(delay, delay_time): whole samples (delay_time None) or a delay time in seconds."""
    d = int(rng.integers(0, MAX_LONG_DELAY + 1)) if rng.random() < 0.08 else int(rng.integers(0, MAX_DELAY + 1))
    if rng.random() < 0.4:
        return {"samples": d, "fraction": 0.0}, None
    t_d = (d + float(rng.uniform(0.02, 0.98))) * period
    return delay_from_time(t_d, period), t_d


def random_case(rng, i):
    period = log_uniform(rng, 1e-4, 1e-2)
    category = ["mass_spring_damper", "two_mass", "transfer_function"][i % 3]
    lag = log_uniform(rng, 5e-5, 3e-3) if rng.random() < 0.35 else 0.0
    if category == "mass_spring_damper":
        plant = mass_spring_damper(rng)
    elif category == "two_mass":
        plant = two_mass(rng)
    else:
        plant = transfer_function(rng, int(rng.integers(1, 7)), period)
    delay, delay_time = random_delay(rng, period)
    return {"category": category, "plant": plant, "force_lag": lag, "period": period, "delay": delay,
            "delay_time": delay_time, "velocity": velocity_spec(rng, period)}


# ---- the audit loops -------------------------------------------------------------------------------

UNDAMPED_TWO_MASS = {
    "kind": "two_mass", "motor_mass": 0.804655568232, "motor_damping": 0.0, "handle_mass": 0.417894852263,
    "transmission_stiffness": 21962.7190042, "transmission_damping": 0.0,
    "arm": {"mass": 0.0, "damping": 0.0, "stiffness": 0.0},
}
UNDAMPED_FLAGS = ("--motor-mass 0.804655568232 --transmission-stiffness 21962.7190042 "
                  "--handle-mass 0.417894852263 --no-arm --period 0.000117311337797 "
                  "--force-lag 0.000175330026909 --velocity lowpass:176.784120008")
UNDAMPED_WALLS = [(1.558e8, 38541.1), (689.65, 0.67492)]


def audit_loops():
    """The loops (and walls) on which an audit found wrong regions, K_max or map radii, in
    hapstab's serde form, with the flags that give them on the command line."""
    t1 = 0.000117311337797
    base = {"category": "two_mass", "plant": UNDAMPED_TWO_MASS, "force_lag": 0.000175330026909,
            "period": t1, "velocity": "lowpass:176.784120008"}
    return [
        dict(base, delay={"samples": 0, "fraction": 0.0}, delay_time=None, cli=UNDAMPED_FLAGS,
             audit_walls=UNDAMPED_WALLS),
        dict(base, delay=delay_from_time(0.000208330779878, t1), delay_time=0.000208330779878,
             cli=UNDAMPED_FLAGS + " --delay-time 0.000208330779878", audit_walls=UNDAMPED_WALLS),
        {"category": "transfer_function",
         "plant": {"kind": "transfer_function", "num": [1.0], "den": [0.01, 0.5, 20.0, 100.0, 1000.0]},
         "force_lag": 1e-3, "period": 1e-4, "delay": {"samples": 3, "fraction": 0.0}, "delay_time": None,
         "velocity": "lowpass:50",
         "cli": "--plant-num 1 --plant-den 0.01,0.5,20,100,1000 --period 1e-4 --delay 3 "
                "--velocity lowpass:50 --force-lag 1e-3",
         "audit_walls": [(2400.0, 0.0), (1000.0, 0.0)]},
        {"category": "mass_spring_damper",
         "plant": {"kind": "mass_spring_damper", "mass": 0.1, "damping": 1.5, "stiffness": 0.0},
         "force_lag": 0.0, "period": 1e-3, "delay": {"samples": 0, "fraction": 0.0}, "delay_time": None,
         "velocity": "iir:600,-500,-100/1,-0.4,0.05",
         "cli": "--no-arm --velocity iir:600,-500,-100/1,-0.4,0.05", "audit_walls": [(0.0, 10.0)]},
        {"category": "mass_spring_damper",
         "plant": {"kind": "mass_spring_damper", "mass": 0.25 + 1.0, "damping": 2.0 + 6.0, "stiffness": 350.0},
         "force_lag": 0.0, "period": 0.00005, "delay": delay_from_time(0.0004, 0.00005), "delay_time": 0.0004,
         "velocity": "lowpass:10",
         "cli": "--device-mass 0.25 --device-damping 2 --period 0.00005 --velocity lowpass:10 --delay-time 0.0004",
         "audit_walls": []},
    ]


def cli_flags(case):
    """The command-line flags that give the case's loop."""
    p = case["plant"]
    if p["kind"] == "mass_spring_damper":
        out = [f"--mass {p['mass']!r} --damping {p['damping']!r} --stiffness {p['stiffness']!r}"]
    elif p["kind"] == "two_mass":
        out = [f"--motor-mass {p['motor_mass']!r} --motor-damping {p['motor_damping']!r} "
               f"--handle-mass {p['handle_mass']!r} --transmission-stiffness {p['transmission_stiffness']!r} "
               f"--transmission-damping {p['transmission_damping']!r}"]
        a = p["arm"]
        if a["mass"] == 0 and a["damping"] == 0 and a["stiffness"] == 0:
            out.append("--no-arm")
        else:
            out.append(f"--arm-mass {a['mass']!r} --arm-damping {a['damping']!r} --arm-stiffness {a['stiffness']!r}")
    else:
        out = ["--plant-num " + ",".join(repr(x) for x in p["num"])]
        out.append("--plant-den " + ",".join(repr(x) for x in p["den"]))
    out.append(f"--period {case['period']!r}")
    if case["delay_time"] is not None:
        out.append(f"--delay-time {case['delay_time']!r}")
    elif case["delay"]["samples"]:
        out.append(f"--delay {case['delay']['samples']}")
    if case["force_lag"] > 0:
        out.append(f"--force-lag {case['force_lag']!r}")
    out.append(f"--velocity {case['velocity']}")
    return " ".join(out)


# ---- walls ------------------------------------------------------------------------------------------


def damping_guess(case):
    """A damping scale in units of m_ref/T: the paper's pure mass is stable for
    0 < BT/m < 2 without delay, and roughly below 1/(t_d/T + 1/2) with one."""
    d = case["delay"]["samples"] + case["delay"]["fraction"]
    return 1.0 / (d + 0.5)


def clearly_stable_somewhere(ref, b):
    """True when a coarse K grid (a quarter of the scan's density) has a wall whose double
    radius is below 1 - 1e-9 by ten times its error (the spread of the referee): the cheap
    test of the damping search, which must not take rounding noise for a stable wall."""
    for k in scan_grid(ref.k_ref)[::4]:
        rho = ref.radius_double(k, b)
        if rho < 1.0 - 1e-9 and rho + 10.0 * ref.spread(k, b) < 1.0 - 1e-9:
            return True
    return False


def dampings(rng, ref, case):
    """[0, B1, B2], each with its stable intervals and crossings. B1, B2 are drawn below a
    damping scale that is quartered (at most DAMPING_TRIES times) until some K is stable at
    it: the referee's wall scale need not be the loop's (module doc of the referee)."""
    out = [(0.0,) + stable_intervals(ref, 0.0)]
    top = damping_guess(case) * ref.b_ref
    for _ in range(DAMPING_TRIES):
        if clearly_stable_somewhere(ref, top):
            break
        top *= 0.25
    ivs, cr = stable_intervals(ref, top)
    for _ in range(2):
        b = float(rng.uniform(0.05, 1.0)) * top
        ivs_b, cr_b = stable_intervals(ref, b)
        if not ivs_b and ivs:  # the stable band in B need not reach down to b
            b, ivs_b, cr_b = top, ivs, cr
        out.append((b, ivs_b, cr_b))
    return out


def loop_walls(rng, ref, levels):
    """The walls of one loop (kind, K, B) from its dampings' intervals (see the module doc)."""
    walls = []
    for i, (b, ivs, cr) in enumerate(levels):
        picks = cr if i == 1 else cr[-1:]
        for kc in picks[:6]:
            off = NEAR_OFFSET * (abs(kc) if abs(kc) > 1e-9 * ref.k_ref else max(abs(cr[-1]), ref.k_ref))
            walls += [("near", kc - off, b), ("near", kc + off, b)]
    b1, ivs1, cr1 = levels[1]
    kmax = cr1[-1] if cr1 else ref.k_ref
    finite = [iv for iv in ivs1 if iv[0] is not None and iv[1] is not None]
    u_stable, u_unstable = float(rng.uniform(0.2, 0.8)), float(rng.uniform(1.5, 20.0))
    if finite:
        lo, hi = max(finite, key=lambda iv: iv[1] - iv[0])
        walls.append(("far", lo + u_stable * (hi - lo), b1))
    walls.append(("far", abs(kmax) * u_unstable, b1))
    walls.append(("zero_k", 0.0, b1))
    walls.append(("zero_k", 0.0, 0.0))
    walls.append(("zero_b", abs(kmax) * float(rng.uniform(0.05, 1.2)), 0.0))
    lower = [iv[0] for iv in ivs1 if iv[0] is not None and iv[0] < -1e-6 * ref.k_ref]
    inside, u_in, u_out = rng.random() < 0.6, float(rng.uniform(0.2, 0.8)), float(rng.uniform(0.05, 5.0))
    if lower and inside:  # a stable negative stiffness
        walls.append(("negative_k", lower[0] * u_in, b1))
    else:
        walls.append(("negative_k", -abs(kmax) * u_out, b1))
    return walls


def record(ref, kind, k, b):
    rho, precise = ref.radius(k, b)
    return {"kind": kind, "stiffness": float(k), "damping": float(b), "radius": rho,
            "verdict": "stable" if rho < 1 else "unstable", "precise": precise}


def referee_case(rng, case):
    """The case with its walls and intervals."""
    ref = Referee(case)
    levels = dampings(rng, ref, case)
    walls = [("audit", k, b) for k, b in case.get("audit_walls", [])] + loop_walls(rng, ref, levels)
    out = {key: case[key] for key in ("category", "plant", "force_lag", "period", "delay", "delay_time", "velocity")}
    out["cli"] = case.get("cli") or cli_flags(case)
    out["wall_scale"] = {"stiffness": ref.k_ref, "damping": ref.b_ref}
    out["intervals"] = [{"damping": b, "stiffness": [list(iv) for iv in ivs]} for b, ivs, _ in levels]
    out["walls"] = [record(ref, *w) for w in walls]
    return out


def write_fixture(fixture, path):
    """The fixture as JSON with one loop per line (readable diffs, small file)."""
    head = {k: v for k, v in fixture.items() if k != "loops"}
    text = json.dumps(head, indent=1)[:-2] + ',\n "loops": [\n'
    text += ",\n".join(json.dumps(lp, separators=(",", ":")) for lp in fixture["loops"])
    with open(path, "w") as f:
        f.write(text + "\n ]\n}\n")


def one_loop(job):
    """The refereed loop i: the audit loop i, or random loop i - len(audit loops), each with its
    own generator seeded by (seed, i) so that loops do not depend on one another."""
    seed, i = job
    rng = np.random.default_rng([seed, i])
    audit = audit_loops()
    case = audit[i] if i < len(audit) else random_case(rng, i - len(audit))
    loop = referee_case(rng, case)
    loop["id"] = i
    loop["audit"] = "audit_walls" in case
    n, p = len(loop["walls"]), sum(w["precise"] for w in loop["walls"])
    print(f"{i:4d} {case['category']:18s} {n:2d} walls, {p:2d} at {ref_mod.DIGITS} digits",
          file=sys.stderr, flush=True)
    return loop


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seed", type=int, default=20081022)
    ap.add_argument("--loops", type=int, default=300, help="random loops (the audit loops come first)")
    ap.add_argument("--jobs", type=int, default=1, help="worker processes")
    ap.add_argument("--out", default="crates/hapstab/tests/fixtures/statespace_loops.json")
    args = ap.parse_args()
    jobs = [(args.seed, i) for i in range(len(audit_loops()) + args.loops)]
    if args.jobs > 1:
        with multiprocessing.Pool(args.jobs) as pool:
            loops = list(pool.imap(one_loop, jobs, chunksize=1))
    else:
        loops = [one_loop(j) for j in jobs]
    fixture = {
        "generator": "benches/baseline/statespace_fixture.py (referee: statespace_referee.py)",
        "seed": args.seed,
        "digits": ref_mod.DIGITS,
        "near_offset": NEAR_OFFSET,
        "scan_decades": list(ref_mod.SCAN_DECADES),
        "versions": {"numpy": np.__version__, "scipy": scipy.__version__, "mpmath": mp.__version__},
        "loops": loops,
    }
    write_fixture(fixture, args.out)
    walls = sum(len(lp["walls"]) for lp in loops)
    print(f"{len(loops)} loops, {walls} walls written to {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
