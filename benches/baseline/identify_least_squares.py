#!/usr/bin/env python3
"""scipy.optimize.least_squares on the same output-error problem as `hapstab identify`.

The model is built independently of hapstab: the plant's transfer function from its physics
(identify_data.plant_tf), put in state space by scipy.signal.tf2ss, sampled by
scipy.signal.cont2discrete(method='zoh') (the augmented matrix exponential), delayed by d
whole samples and run from rest by scipy.signal.dlsim; ŷ_k = C x_k + y_0. The cost is
Σ (y_k − ŷ_k)², positive parameters fitted as logarithms, a transfer function's numerator
and the offset y_0 as they are — the problem hapstab::identify::output_error states.
scipy's method='lm' (MINPACK lmder) runs from the truth of the recording's JSON moved by
+20 %/−20 %, to the tolerances 1e-15.

For each recording the script runs `hapstab identify --json` on it, fits it with scipy, prints
both parameter vectors and their largest relative difference, and the seconds each took;
exit 1 when any differs by more than --tolerance (1e-6).

  python identify_least_squares.py --hapstab target/release/hapstab \
      crates/hapstab/tests/fixtures/identify/msd_chirp_40db.csv ...
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np
import scipy.optimize
import scipy.signal

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from identify_data import plant_tf  # noqa: E402

# model name in the truth JSON -> (hapstab --model, hapstab --fix flags, parameter names in
# hapstab's order, function from those parameters to identify_data's dict)
MODELS = {
    "mass-spring-damper": (
        "mass-spring-damper",
        [],
        ["mass", "damping", "stiffness"],
        lambda p, t: ("mass-spring-damper", {"m": p[0], "b": p[1], "k": p[2]}),
    ),
    "held-device": (
        "mass-spring-damper",
        ["device-mass", "device-damping"],
        ["arm-mass", "arm-damping", "arm-stiffness"],
        lambda p, t: (
            "held-device",
            {"m_L": t["m_L"], "b_L": t["b_L"], "m_H": p[0], "b_H": p[1], "k_H": p[2]},
        ),
    ),
    "two-mass": (
        "two-mass",
        [],
        ["motor-mass", "motor-damping", "handle-mass", "transmission-stiffness",
         "transmission-damping"],
        lambda p, t: ("two-mass", {"J": p[0], "b_m": p[1], "m_h": p[2], "k_t": p[3], "b_t": p[4]}),
    ),
}

TRUTH_NAMES = {
    "mass-spring-damper": ["m", "b", "k"],
    "held-device": ["m_H", "b_H", "k_H"],
    "two-mass": ["J", "b_m", "m_h", "k_t", "b_t"],
}


def tf_setup(truth):
    """(hapstab model, names, truth values, positive mask) of a monic transfer function."""
    num = np.array(truth["num"]) / truth["den"][0]
    den = np.array(truth["den"]) / truth["den"][0]
    n, d = len(num) - 1, len(den) - 1
    names = [f"b{i}" for i in range(n + 1)] + [f"a{i}" for i in range(d)]
    values = list(num[::-1]) + list(den[1:][::-1])
    return f"tf:{n}/{d}", names, values, [False] * (n + 1) + [True] * d


def response(num, den, period, delay, force):
    """C x_k from rest under F_{k−delay} held over each sample."""
    a, b, c, d = scipy.signal.tf2ss(num, den)
    ad, bd, cd, dd, _ = scipy.signal.cont2discrete((a, b, c, d), period, method="zoh")
    u = np.concatenate([np.zeros(delay), force[: force.size - delay]])
    _, y, _ = scipy.signal.dlsim((ad, bd, cd, dd, period), u)
    return y[:, 0]


def fit_scipy(data, truth):
    """scipy's parameters (hapstab's order) and offset."""
    t, force, pos = data
    period = (t[-1] - t[0]) / (t.size - 1)
    kind = truth["model"]
    if kind == "tf":
        _, names, start, positive = tf_setup(truth)
        n_num = len(truth["num"])

        def build(p):
            num = np.array(p[:n_num][::-1])
            den = np.concatenate([[1.0], np.array(p[n_num:][::-1])])
            return num, den
    else:
        _, _, names, to_dict = MODELS[kind]
        start = [truth["params"][k] for k in TRUTH_NAMES[kind]]
        positive = [True] * len(start)

        def build(p):
            model, params = to_dict(p, truth["params"])
            return plant_tf(model, params)

    scale = np.sqrt(np.mean(pos**2))
    moved = [v * (1.2 if i % 2 == 0 else 0.8) for i, v in enumerate(start)]
    x0 = [np.log(v) if pos_ else v / abs(v) for v, pos_ in zip(moved, positive)] + [0.0]
    mags = [abs(v) for v in moved]

    def values(x):
        return [np.exp(xi) if pos_ else xi * m for xi, pos_, m in zip(x, positive, mags)]

    def residuals(x):
        num, den = build(values(x[:-1]))
        y = response(num, den, period, truth["delay"], force) + x[-1] * scale
        return (pos - y) / scale

    r = scipy.optimize.least_squares(
        residuals, x0, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=20000
    )
    return names, values(r.x[:-1]), r.x[-1] * scale


def fit_hapstab(exe, csv, truth):
    period = truth["period"]
    if truth["model"] == "tf":
        model, _, _, _ = tf_setup(truth)
        fix = []
    else:
        model, fixed, _, _ = MODELS[truth["model"]]
        fix = []
        for name, key in zip(fixed, ["m_L", "b_L"]):
            fix += ["--fix", f"{name}={truth['params'][key]!r}"]
    args = [exe, "identify", "--data", csv, "--model", model, "--json", "--draws", "1",
            "--delay-time", repr(truth["delay"] * period)] + fix
    out = json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)
    return {p["name"]: p["value"] for p in out["parameters"]}, out["position_offset"]["value"]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--hapstab", required=True, help="the hapstab binary")
    ap.add_argument("--tolerance", type=float, default=1e-6)
    ap.add_argument("csv", nargs="+")
    args = ap.parse_args(argv)
    worst = 0.0
    for csv in args.csv:
        truth = json.load(open(csv.rsplit(".", 1)[0] + ".json"))
        data = np.loadtxt(csv, delimiter=",", skiprows=1).T
        t0 = time.perf_counter()
        names, sp, s_off = fit_scipy(data, truth)
        t1 = time.perf_counter()
        hp, h_off = fit_hapstab(args.hapstab, csv, truth)
        t2 = time.perf_counter()
        rel = max(abs(hp[n] - v) / abs(v) for n, v in zip(names, sp))
        worst = max(worst, rel)
        print(f"{os.path.basename(csv)}: {len(data[0])} samples; scipy {t1 - t0:.3f} s, "
              f"hapstab {t2 - t1:.3f} s (process); largest relative difference {rel:.2e}")
        for n, v in zip(names, sp):
            print(f"  {n:24s} scipy {v!r:24s} hapstab {hp[n]!r}")
        print(f"  {'position offset':24s} scipy {s_off!r:24s} hapstab {h_off!r}")
    print(f"largest relative difference {worst:.2e} (tolerance {args.tolerance:g})")
    return 0 if worst <= args.tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
