#!/usr/bin/env python3
"""Synthetic identification data from an independent simulator (numpy/scipy only, no hapstab).

A force F_k is commanded at t_k = kT, held over one sample (zero-order hold) and applied after
d whole samples of delay to a continuous plant P(s) from force (N) to position (m); the
position is read at every t_k, then noise at a given SNR (20·log10 of the RMS of the clean
position over the noise's) is added and the result is rounded to a quantization step.

The plant's transfer function is formed from its physics with numpy's polynomial algebra,
put in state space with scipy.signal.tf2ss, and sampled exactly by the matrix exponential of
the augmented matrix [[A, B], [0, 0]]·T (Van Loan 1978): x_{k+1} = Φ x_k + Γ F_{k−d},
y_k = C x_k, from rest (x_0 = 0, F_k = 0 before the run).

Models (--model):
  mass-spring-damper   m, b, k:  P = 1/(m s² + b s + k)
  held-device          device m_L, b_L and arm m_H, b_H, k_H: eq. (1) of Hulin et al. 2008,
                       m = m_L + m_H, b = b_L + b_H, k = k_H
  two-mass             motor J, b_m; handle m_h; transmission k_t, b_t (encoder on the motor)
  tf                   --num and --den coefficients, highest power of s first

Inputs (--input): chirp (linear sweep f0..f1 Hz), prbs (maximum-length sequence, each bit held
--hold samples), step.

With --frequency-response, writes instead the sampled plant's frequency response
H(e^{jωT}) = C (e^{jωT} I − Φ)⁻¹ Γ e^{−jωTd} at --points log-spaced frequencies from --f0 to
--f1 Hz, with Gaussian errors of --db-noise dB and --deg-noise degrees: a CSV with the header
frequency,magnitude_db,phase_deg.

Writes a CSV with the header time,force,position (shortest round-trip decimals) and, beside
it, FILE.json with the truth (model, parameters, settings).

Example:
  python identify_data.py --model mass-spring-damper --param m=0.6 --param b=7.5 \
      --param k=350 --input chirp --snr 40 --quantization 1e-5 --seed 1 --out run.csv
"""
import argparse
import json
import sys

import numpy as np
import scipy.linalg
import scipy.signal

PARAMS = {
    "mass-spring-damper": ["m", "b", "k"],
    "held-device": ["m_L", "b_L", "m_H", "b_H", "k_H"],
    "two-mass": ["J", "b_m", "m_h", "k_t", "b_t"],
}


def plant_tf(model, p, num=None, den=None):
    """Numerator and denominator of P(s), highest power first."""
    if model == "mass-spring-damper":
        return np.array([1.0]), np.array([p["m"], p["b"], p["k"]])
    if model == "held-device":
        m = p["m_L"] + p["m_H"]
        b = p["b_L"] + p["b_H"]
        return np.array([1.0]), np.array([m, b, p["k_H"]])
    if model == "two-mass":
        # J x_m'' = F − b_m x_m' − k_t (x_m − x_h) − b_t (x_m' − x_h')
        # m_h x_h'' = k_t (x_m − x_h) + b_t (x_m' − x_h')
        motor = np.array([p["J"], p["b_m"] + p["b_t"], p["k_t"]])
        handle = np.array([p["m_h"], p["b_t"], p["k_t"]])
        coupling = np.array([p["b_t"], p["k_t"]])
        d = np.polysub(np.polymul(motor, handle), np.polymul(coupling, coupling))
        return handle, d
    if model == "tf":
        return np.asarray(num, float), np.asarray(den, float)
    raise SystemExit(f"unknown model {model}")


def sampled(num, den, period):
    """Exact ZOH sampling (Φ, Γ, C) of num/den by the augmented matrix exponential."""
    a, b, c, d = scipy.signal.tf2ss(num, den)
    if np.any(np.abs(d) > 0):
        raise SystemExit("the plant must be strictly proper")
    n = a.shape[0]
    aug = np.zeros((n + 1, n + 1))
    aug[:n, :n] = a
    aug[:n, n:] = b
    e = scipy.linalg.expm(aug * period)
    return e[:n, :n], e[:n, n], c[0]


def force_signal(kind, n, period, amplitude, seed, f0, f1, hold):
    """The commanded force F_k, k = 0..n−1."""
    t = np.arange(n) * period
    if kind == "chirp":
        return amplitude * scipy.signal.chirp(t, f0=f0, f1=f1, t1=t[-1], method="linear")
    if kind == "prbs":
        nbits = 12
        seq, _ = scipy.signal.max_len_seq(nbits, state=seeded_state(seed, nbits))
        bits = np.repeat(seq.astype(float) * 2.0 - 1.0, hold)
        reps = int(np.ceil(n / bits.size))
        return amplitude * np.tile(bits, reps)[:n]
    if kind == "step":
        f = np.full(n, amplitude)
        f[: n // 10] = 0.0
        return f
    raise SystemExit(f"unknown input {kind}")


def seeded_state(seed, nbits):
    """A non-zero initial register for the maximum-length sequence from the seed."""
    rng = np.random.default_rng(seed)
    state = rng.integers(0, 2, nbits)
    state[0] = 1
    return state


def simulate(phi, gamma, c, force, delay):
    """y_k = C x_k with x_{k+1} = Φ x_k + Γ F_{k−d}, x_0 = 0."""
    n = force.size
    x = np.zeros(phi.shape[0])
    y = np.empty(n)
    for k in range(n):
        y[k] = c @ x
        u = force[k - delay] if k >= delay else 0.0
        x = phi @ x + gamma * u
    return y


def measured(y, snr_db, quantization, seed):
    """Noise at snr_db (None: none), then rounding to the quantization step (0: none)."""
    rng = np.random.default_rng(seed + 7919)
    out = y.copy()
    if snr_db is not None:
        sd = np.sqrt(np.mean(y**2)) / 10.0 ** (snr_db / 20.0)
        out = out + rng.normal(0.0, sd, y.size)
    if quantization > 0:
        out = np.round(out / quantization) * quantization
    return out


def write_frequency_response(args, phi, gamma, c, p, tf_num, tf_den):
    """The sampled plant's response with dB and degree errors (module doc)."""
    f = np.geomspace(args.f0, args.f1, args.points)
    z = np.exp(2j * np.pi * f * args.period)
    n = phi.shape[0]
    h = np.array([c @ np.linalg.solve(zi * np.eye(n) - phi, gamma) * zi ** (-args.delay)
                  for zi in z])
    rng = np.random.default_rng(args.seed + 104729)
    db = 20 * np.log10(np.abs(h)) + rng.normal(0.0, args.db_noise, f.size)
    deg = np.degrees(np.angle(h)) + rng.normal(0.0, args.deg_noise, f.size)
    with open(args.out, "w") as out:
        out.write("frequency,magnitude_db,phase_deg\n")
        for row in zip(f, db, deg):
            out.write(",".join(repr(float(v)) for v in row) + "\n")
    truth = {"model": args.model, "params": p, "num": list(map(float, tf_num)),
             "den": list(map(float, tf_den)), "period": args.period, "delay": args.delay,
             "db_noise": args.db_noise, "deg_noise": args.deg_noise, "seed": args.seed,
             "points": args.points}
    with open(args.out.rsplit(".", 1)[0] + ".json", "w") as out:
        json.dump(truth, out, indent=1)
    return 0


def parse_params(model, items):
    p = {}
    for item in items:
        name, _, value = item.partition("=")
        p[name] = float(value)
    missing = [k for k in PARAMS.get(model, []) if k not in p]
    if missing:
        raise SystemExit(f"--param missing for {model}: {', '.join(missing)}")
    return p


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--model", required=True, choices=[*PARAMS, "tf"])
    ap.add_argument("--param", action="append", default=[], help="NAME=VALUE")
    ap.add_argument("--num", help="tf numerator, comma separated")
    ap.add_argument("--den", help="tf denominator, comma separated")
    ap.add_argument("--period", type=float, default=1e-3)
    ap.add_argument("--delay", type=int, default=0, help="whole samples")
    ap.add_argument("--samples", type=int, default=4000)
    ap.add_argument("--input", default="chirp", choices=["chirp", "prbs", "step"])
    ap.add_argument("--amplitude", type=float, default=1.0, help="N")
    ap.add_argument("--f0", type=float, default=0.5)
    ap.add_argument("--f1", type=float, default=50.0)
    ap.add_argument("--hold", type=int, default=10, help="PRBS samples per bit")
    ap.add_argument("--snr", type=float, default=None, help="dB; none for no noise")
    ap.add_argument("--quantization", type=float, default=0.0, help="m")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--frequency-response", action="store_true")
    ap.add_argument("--points", type=int, default=60)
    ap.add_argument("--db-noise", type=float, default=0.0)
    ap.add_argument("--deg-noise", type=float, default=0.0)
    ap.add_argument("--out", required=True)
    args = ap.parse_args(argv)
    p = parse_params(args.model, args.param)
    num = den = None
    if args.model == "tf":
        num = [float(x) for x in args.num.split(",")]
        den = [float(x) for x in args.den.split(",")]
    tf_num, tf_den = plant_tf(args.model, p, num, den)
    phi, gamma, c = sampled(tf_num, tf_den, args.period)
    if args.frequency_response:
        return write_frequency_response(args, phi, gamma, c, p, tf_num, tf_den)
    force = force_signal(
        args.input, args.samples, args.period, args.amplitude, args.seed, args.f0, args.f1, args.hold
    )
    y = simulate(phi, gamma, c, force, args.delay)
    pos = measured(y, args.snr, args.quantization, args.seed)
    t = np.arange(args.samples) * args.period
    with open(args.out, "w") as f:
        f.write("time,force,position\n")
        for row in zip(t, force, pos):
            f.write(",".join(repr(float(v)) for v in row) + "\n")
    truth = {
        "model": args.model,
        "params": p,
        "num": list(map(float, tf_num)),
        "den": list(map(float, tf_den)),
        "period": args.period,
        "delay": args.delay,
        "input": args.input,
        "snr_db": args.snr,
        "quantization": args.quantization,
        "seed": args.seed,
        "samples": args.samples,
        "clean_rms": float(np.sqrt(np.mean(y**2))),
    }
    with open(args.out.rsplit(".", 1)[0] + ".json", "w") as f:
        json.dump(truth, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
