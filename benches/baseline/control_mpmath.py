#!/usr/bin/env python3
"""High-precision referee for the python-control fixture: the same closed loops computed in
mpmath at 60 significant digits, independent of python-control and of hapstab.

Needs `pip install mpmath`. Usage:

    python benches/baseline/control_mpmath.py [FIXTURE] [--ids 3,17,...] [--rust FILE] [--write]

For each case: the continuous state-space model (A, B, C) in SI units, the zero-order hold by
the matrix exponential of [[A, B], [0, 0]]·T (mpmath.expm), the discrete plant
N(z)/D(z) = C adj(zI − Φ)Γ / det(zI − Φ) by the Faddeev–LeVerrier recursion, the closed loop
p(z) = z^d D(z) Vd(z) + N(z) (K Vd(z) + B Vn(z)) and its roots (mpmath.polyroots). Prints the
reference spectral radius beside python-control's, and beside hapstab's when --rust names a
file of "id wall_kind radius" lines (HAPSTAB_CONTROL_DUMP=FILE cargo test -p hapstab --test
engine python_control:: writes one). --write stores the reference in the fixture as
`reference_radius` (the nearest double), the referee of tests/engine/python_control.rs where
python-control and hapstab disagree.
"""

import argparse
import json
import math

import mpmath as mp

mp.mp.dps = 60


def state_space(plant):
    kind = plant["kind"]
    if kind == "mass_spring_damper":
        m, b, k = (mp.mpf(plant[x]) for x in ("mass", "damping", "stiffness"))
        return [[0, 1], [-k / m, -b / m]], [0, 1 / m], [1, 0]
    if kind == "two_mass":
        j, bm = mp.mpf(plant["motor_mass"]), mp.mpf(plant["motor_damping"])
        mh = mp.mpf(plant["handle_mass"]) + mp.mpf(plant["arm"]["mass"])
        kt, bt = mp.mpf(plant["transmission_stiffness"]), mp.mpf(plant["transmission_damping"])
        kh, bh = mp.mpf(plant["arm"]["stiffness"]), mp.mpf(plant["arm"]["damping"])
        a = [
            [0, 1, 0, 0],
            [-kt / j, -(bm + bt) / j, kt / j, bt / j],
            [0, 0, 0, 1],
            [kt / mh, bt / mh, -(kt + kh) / mh, -(bt + bh) / mh],
        ]
        return a, [0, 1 / j, 0, 0], [1, 0, 0, 0]
    num = [mp.mpf(x) for x in plant["num"]]
    den = [mp.mpf(x) for x in plant["den"]]
    while den[0] == 0:
        den.pop(0)
    while num[0] == 0:
        num.pop(0)
    n = len(den) - 1
    lead = den[0]
    a_asc = [den[n - k] / lead for k in range(n)]  # s^k coefficients of the monic den
    num_asc = [num[len(num) - 1 - k] / lead if k < len(num) else mp.mpf(0) for k in range(n)]
    a = [[mp.mpf(1) if j == i + 1 else mp.mpf(0) for j in range(n)] for i in range(n - 1)]
    a.append([-a_asc[k] for k in range(n)])
    b = [mp.mpf(0)] * (n - 1) + [mp.mpf(1)]
    return a, b, num_asc


def with_lag(a, b, c, tau):
    n = len(a)
    r = 1 / mp.mpf(tau)
    a2 = [list(a[i]) + [b[i]] for i in range(n)] + [[0] * n + [-r]]
    return a2, [0] * n + [r], list(c) + [0]


def zoh(a, b, t):
    n = len(a)
    m = mp.zeros(n + 1, n + 1)
    for i in range(n):
        for j in range(n):
            m[i, j] = mp.mpf(a[i][j]) * t
        m[i, n] = mp.mpf(b[i]) * t
    e = mp.expm(m)
    phi = mp.matrix(n, n)
    for i in range(n):
        for j in range(n):
            phi[i, j] = e[i, j]
    gamma = mp.matrix([e[i, n] for i in range(n)])
    return phi, gamma


def discrete_tf(phi, gamma, c):
    """N and D (descending) by Faddeev–LeVerrier: adj(zI − Φ) = Σ_k M_k z^(n−1−k)."""
    n = phi.rows
    eye = mp.eye(n)
    mk = eye
    den = [mp.mpf(1)]
    num = []
    cvec = mp.matrix([c])
    for k in range(1, n + 1):
        num.append((cvec * mk * gamma)[0, 0])
        am = phi * mk
        ck = -sum(am[i, i] for i in range(n)) / k
        den.append(ck)
        mk = am + ck * eye
    return num, den  # num has degree n − 1


def velocity(spec, t):
    kind, _, arg = spec.partition(":")
    t = mp.mpf(t)
    if kind == "backward":
        return [1 / t, -1 / t], [mp.mpf(1), mp.mpf(0)]
    if kind == "lowpass":
        a = mp.exp(-2 * mp.pi * mp.mpf(float(arg)) * t)
        return [(1 - a) / t, -(1 - a) / t], [mp.mpf(1), -a]
    if kind == "average":
        n = int(arg)
        return [1 / (n * t)] + [mp.mpf(0)] * (n - 1) + [-1 / (n * t)], [mp.mpf(1)] + [mp.mpf(0)] * n
    b_txt, a_txt = arg.split("/")
    b = [mp.mpf(float(x)) for x in b_txt.split(",")]
    a = [mp.mpf(float(x)) for x in a_txt.split(",")]
    length = max(len(b), len(a))
    return b + [mp.mpf(0)] * (length - len(b)), a + [mp.mpf(0)] * (length - len(a))


def pmul(p, q):
    out = [mp.mpf(0)] * (len(p) + len(q) - 1)
    for i, x in enumerate(p):
        for j, y in enumerate(q):
            out[i + j] += x * y
    return out


def padd(p, q):
    n = max(len(p), len(q))
    p = [mp.mpf(0)] * (n - len(p)) + list(p)
    q = [mp.mpf(0)] * (n - len(q)) + list(q)
    return [x + y for x, y in zip(p, q)]


def characteristic(case):
    a, b, c = state_space(case["plant"])
    if case["force_lag"] > 0:
        a, b, c = with_lag(a, b, c, case["force_lag"])
    phi, gamma = zoh(a, b, mp.mpf(case["period"]))
    num, den = discrete_tf(phi, gamma, c)
    vn, vd = velocity(case["velocity"], case["period"])
    k, bw = mp.mpf(case["wall"]["stiffness"]), mp.mpf(case["wall"]["damping"])
    p0 = pmul(den + [mp.mpf(0)] * case["delay"], vd)
    wall = padd([k * x for x in vd], [bw * x for x in vn])
    return padd(p0, pmul(num, wall))


def radius(case):
    p = characteristic(case)
    while p[0] == 0:
        p.pop(0)
    roots = mp.polyroots(p, maxsteps=2000, extraprec=400)
    return max(abs(r) for r in roots)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("fixture", nargs="?", default="crates/hapstab/tests/fixtures/control_loops.json")
    ap.add_argument("--ids", default="")
    ap.add_argument("--rust", default="")
    ap.add_argument("--json", default="")
    ap.add_argument("--write", action="store_true")
    args = ap.parse_args()
    fixture = json.load(open(args.fixture))
    cases = fixture["cases"]
    if args.ids:
        ids = {int(x) for x in args.ids.split(",")}
        cases = [c for c in cases if c["id"] in ids]
    rust = {}
    if args.rust:
        for line in open(args.rust):
            i, kind, r = line.split()
            rust[(int(i), kind)] = float(r)
    out = []
    for c in cases:
        ref = radius(c)
        c["reference_radius"] = float(ref)
        pc = c["spectral_radius"]
        rel_pc = float(abs(pc - ref) / ref)
        line = f"{c['id']:4d} {c['wall_kind']:5s} ref {mp.nstr(ref, 20):24s} python-control rel {rel_pc:.2e}"
        h = rust.get((c["id"], c["wall_kind"]))
        rel_h = None
        if h is not None:
            rel_h = float(abs(h - ref) / ref)
            line += f"  hapstab rel {rel_h:.2e}"
        print(line, flush=True)
        out.append({"id": c["id"], "wall_kind": c["wall_kind"], "reference": float(ref),
                    "python_control_rel": rel_pc, "hapstab_rel": rel_h})
    if args.json:
        json.dump(out, open(args.json, "w"), indent=1)
    if args.write:
        fixture["referee"] = "benches/baseline/control_mpmath.py (mpmath %s, %d digits)" % (
            mp.__version__,
            mp.mp.dps,
        )
        with open(args.fixture, "w") as f:
            json.dump(fixture, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
