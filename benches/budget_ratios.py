#!/usr/bin/env python3
"""Estimate against measured cost: runs seeded heavy command lines of every command family
with HAPSTAB_ESTIMATE=1, reads each estimate (core-seconds, summed when a command prints
several) and compares it with the measured CPU time (user + system, core-seconds) of the run.

    cargo build --release
    python3 benches/budget_ratios.py target/release/hapstab --seed 1 --count 50

prints one line per run (ratio = estimate / measured) and a summary: the median, the range
and how many ratios lie within a factor of three. Exit code 1 when fewer than 90 % do.
"""

import argparse
import os
import random
import resource
import statistics
import subprocess
import sys
import time


def wall_stable():
    """A soft wall that the paper's loop keeps stable at every delay (margins run)."""
    return ["--wall-stiffness", "1", "--wall-damping", "0.1"]


def families(rng):
    """One random heavy command line per family, each about 0.2 to 30 core-seconds."""
    d = lambda lo, hi: str(rng.randint(lo, hi))
    return [
        lambda: ["check", "--delay", d(800, 2000)] + wall_stable(),
        lambda: ["check", "--delay", d(1000, 2000)],
        lambda: ["check", "--velocity", f"average:{d(80, 250)}"],
        lambda: ["boundary", "--delay", d(600, 2000)],
        lambda: ["kmax", "--delay", d(600, 2000)],
        lambda: ["passivity", "--delay", d(1000, 2000)],
        lambda: ["zwidth", "--delay", d(300, 900)],
        lambda: ["map", "--x", f"K:0:{rng.choice([30, 1e3, 1e4])}:{d(100, 300)}",
                 "--y", f"B:0:10:{d(50, 150)}", "--delay", d(300, 1000)],
        lambda: ["map", "--x", f"K:0:1e4:{d(10, 40)}", "--y", "B:0:10:10",
                 "--delay", d(300, 1000), "--radius"],
        lambda: ["sweep", "--param", f"delay-time:0:{rng.choice([0.005, 0.05, 0.2])}:{d(100, 600)}"],
        lambda: ["simulate", "--duration", d(2000, 10000)] + ["--wall-stiffness", "100"],
    ]


def run(binary, args):
    """(estimate, measured core-seconds, exit code) of one command line."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    env = dict(os.environ, HAPSTAB_ESTIMATE="1")
    p = subprocess.run([binary] + args, env=env, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    est = sum(float(l.split()[1]) for l in p.stderr.splitlines() if l.startswith("estimate: "))
    return est, cpu, p.returncode


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--count", type=int, default=50)
    a = ap.parse_args()
    rng = random.Random(a.seed)
    fams = families(rng)
    ratios = []
    t0 = time.time()
    for i in range(a.count):
        args = fams[i % len(fams)]()
        est, cpu, code = run(a.binary, args)
        ratio = est / max(cpu, 0.01)
        ratios.append(ratio)
        print(f"{ratio:6.2f}  est {est:8.3f}  cpu {cpu:8.3f}  rc {code}  {' '.join(args)}", flush=True)
    within = sum(1 for r in ratios if 1 / 3 <= r <= 3)
    print(f"\n{len(ratios)} runs in {time.time() - t0:.0f} s: median ratio {statistics.median(ratios):.2f}, "
          f"range {min(ratios):.2f}–{max(ratios):.2f}, within ×3: {within}/{len(ratios)}")
    sys.exit(0 if within >= 0.9 * len(ratios) else 1)


if __name__ == "__main__":
    main()
