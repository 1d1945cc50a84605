#!/usr/bin/env python3
"""Regression fixture: the paper's loop as computed by hapstab before the general loop engine.

Runs a hapstab binary built at commit 9660ef8 (the last one with the paper-only engine) on
1000 seeded points of the paper's range (and beyond: gamma up to 1, delta up to 1, d up to
10) and records, per point, the spectral radius and the stable alpha interval at beta (from
`check`) and alpha_max / beta_at_alpha_max (from `boundary`). The Rust test
crates/hapstab/tests/engine/paper/regression.rs checks that the general engine reproduces them to
1e-12.

Usage: python3 paper_regression.py /path/to/hapstab-9660ef8 > crates/hapstab/tests/fixtures/paper_regression.json
"""
import json
import random
import subprocess
import sys


def run(binary, args):
    out = subprocess.run([binary] + args + ["--json"], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def main():
    binary = sys.argv[1]
    rng = random.Random(20261129)
    points = []
    for i in range(1000):
        # log-uniform plant parameters, including exact zeros now and then
        gamma = 0.0 if i % 10 == 0 else 10 ** rng.uniform(-8, 0)
        delta = 0.0 if i % 7 == 0 else 10 ** rng.uniform(-6, 0)
        d = rng.randint(0, 10)
        beta = rng.uniform(-0.05, 1.0) / (1 + d)
        alpha = rng.uniform(-0.01, 0.8) / (1 + d) ** 2
        chk = run(binary, ["check", "--alpha", repr(alpha), "--beta", repr(beta), "--gamma", repr(gamma),
                           "--delta", repr(delta), "--delay", str(d)])
        bnd = run(binary, ["boundary", "--gamma", repr(gamma), "--delta", repr(delta), "--delay", str(d)])
        points.append({
            "gamma": gamma, "delta": delta, "d": d, "alpha": alpha, "beta": beta,
            "spectral_radius": chk["spectral_radius"],
            "alpha_interval": chk.get("alpha_interval"),
            "alpha_max": bnd["alpha_max"], "beta_at_alpha_max": bnd["beta_at_alpha_max"],
        })
    json.dump({"source": "hapstab 9660ef8 (paper-only engine)", "points": points}, sys.stdout, indent=0)


if __name__ == "__main__":
    main()
