#!/usr/bin/env python3
"""Coverage of `hapstab identify`'s 95 % intervals over seeded noise realisations.

For each seed, identify_data.py's simulator (numpy/scipy only) records the same plant under
the same force with a new noise realisation; `hapstab identify --json` fits it. The script
counts, per parameter, how often the 95 % interval holds the truth (a calibrated interval:
95 %, i.e. 93-97 % over 200 realisations within the binomial spread), and how often
K_max at B = 0's delta-method interval, its spread and its range over the 95 % box hold the
true K_max, and how often the delta-method interval of K_max over the renderable band holds
the true one (both computed by `hapstab kmax` on the true loop, the band's position
resolution the quantization step, as `identify --quantization` sets it).

  python identify_coverage.py --hapstab target/release/hapstab --realisations 200
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import identify_data  # noqa: E402

QUANTIZATION = "1e-5"

CASES = {
    "msd": (
        ["--model", "mass-spring-damper", "--param", "m=0.6", "--param", "b=7.5",
         "--param", "k=350", "--input", "chirp", "--f1", "40"],
        [],
        {"mass": 0.6, "damping": 7.5, "stiffness": 350.0},
        ["--mass", "0.6", "--damping", "7.5", "--stiffness", "350"],
    ),
    "held": (
        ["--model", "held-device", "--param", "m_L=0.1", "--param", "b_L=1.5",
         "--param", "m_H=1", "--param", "b_H=6", "--param", "k_H=350", "--input", "prbs",
         "--hold", "20", "--amplitude", "2"],
        ["--fix", "device-mass=0.1", "--fix", "device-damping=1.5"],
        {"arm-mass": 1.0, "arm-damping": 6.0, "arm-stiffness": 350.0},
        ["--device-mass", "0.1", "--device-damping", "1.5", "--arm-mass", "1",
         "--arm-damping", "6", "--arm-stiffness", "350"],
    ),
    "two-mass": (
        ["--model", "two-mass", "--param", "J=0.3", "--param", "b_m=2", "--param", "m_h=0.1",
         "--param", "k_t=2300", "--param", "b_t=1", "--input", "chirp", "--f0", "5",
         "--f1", "80", "--amplitude", "2"],
        ["--model", "two-mass"],
        {"motor-mass": 0.3, "motor-damping": 2.0, "handle-mass": 0.1,
         "transmission-stiffness": 2300.0, "transmission-damping": 1.0},
        ["--motor-mass", "0.3", "--motor-damping", "2", "--handle-mass", "0.1",
         "--transmission-stiffness", "2300", "--transmission-damping", "1", "--no-arm"],
    ),
    "tf3": (
        ["--model", "tf", "--num", "2000", "--den", "1,60,4000,20000", "--input", "prbs",
         "--hold", "10"],
        ["--model", "tf:0/3"],
        {"b0": 2000.0, "a0": 20000.0, "a1": 4000.0, "a2": 60.0},
        ["--plant-num", "2000", "--plant-den", "1,60,4000,20000"],
    ),
}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--hapstab", required=True)
    ap.add_argument("--case", default="msd", choices=sorted(CASES))
    ap.add_argument("--realisations", type=int, default=200)
    ap.add_argument("--first-seed", type=int, default=1)
    ap.add_argument("--snr", default="40")
    ap.add_argument("--samples", default="4000")
    ap.add_argument("--draws", default="200")
    args = ap.parse_args(argv)
    sim, fix, truth, flags = CASES[args.case]
    true_k = json.loads(subprocess.run(
        [args.hapstab, "kmax", *flags, "--wall-damping", "0", "--json"],
        check=True, capture_output=True, text=True).stdout)["k_max"]
    true_band = json.loads(subprocess.run(
        [args.hapstab, "kmax", *flags, "--position-resolution", QUANTIZATION, "--json"],
        check=True, capture_output=True, text=True).stdout)["renderable"]["k_max"]
    inside = {p: 0 for p in truth}
    k_inside = 0
    box_inside = 0
    delta_inside = 0
    band_inside = 0
    worst = {p: 0.0 for p in truth}
    with tempfile.TemporaryDirectory() as tmp:
        csv = os.path.join(tmp, "run.csv")
        for seed in range(args.first_seed, args.first_seed + args.realisations):
            identify_data.main([*sim, "--snr", args.snr, "--quantization", QUANTIZATION,
                                "--samples", args.samples, "--seed", str(seed), "--out", csv])
            out = json.loads(subprocess.run(
                [args.hapstab, "identify", "--data", csv, *fix, "--json", "--quantization",
                 QUANTIZATION, "--draws",
                 args.draws, "--seed", str(seed)],
                check=True, capture_output=True, text=True).stdout)
            for p in out["parameters"]:
                if p["name"] in truth:
                    lo, hi = p["ci95"]
                    inside[p["name"]] += lo <= truth[p["name"]] <= hi
                    rel = abs(p["value"] / truth[p["name"]] - 1)
                    worst[p["name"]] = max(worst[p["name"]], rel)
            lim = out["stiffness_limit"]
            lo, hi = lim["spread"]
            k_inside += lo <= true_k <= hi
            box = lim["box_range"]
            box_inside += box is not None and box[0] <= true_k <= box[1]
            lo, hi = lim["interval"]["ci95"]
            delta_inside += lo <= true_k <= hi
            lo, hi = lim["renderable"]["interval"]["ci95"]
            band_inside += lo <= true_band <= hi
    n = args.realisations
    print(f"{args.case}: {n} realisations at {args.snr} dB, {args.samples} samples, seeds"
          f" {args.first_seed}..{args.first_seed + n - 1}")
    for p in truth:
        print(f"  {p:16s} interval holds the truth {inside[p]}/{n} = {100 * inside[p] / n:.1f} %;"
              f" largest error {100 * worst[p]:.3f} %")
    pc = lambda c: f"{c}/{n} = {100 * c / n:.1f} %"  # noqa: E731
    print(f"  K_max at B = 0 ({true_k:.6g} N/m): delta-method interval holds it {pc(delta_inside)};"
          f" spread {pc(k_inside)}; range over the 95 % box {pc(box_inside)}")
    print(f"  K_max over the renderable band ({true_band:.6g} N/m): delta-method interval holds it"
          f" {pc(band_inside)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
