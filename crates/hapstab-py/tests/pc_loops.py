"""Sampled open loops L(z) built independently of hapstab (python-control, numpy, scipy), and
a dense evaluation of their crossovers: the referee of test_margins_python_control.py.

The loop of a wall (K, B) on a plant P(s) (force to position) sampled at T with the wall
force delayed by t_d = (d + λ)T and held (zero-order hold) is

    L(z) = (K + B·V(z)) · H(z),   H(z) = C (zI − Φ)⁻¹ (Γ_b + Γ_a z⁻¹) · z⁻ᵈ,

Φ = e^{AT}, Γ_b = ∫₀^{(1−λ)T} e^{Aτ} dτ B, Γ_a = e^{A(1−λ)T} ∫₀^{λT} e^{Aτ} dτ B (the force of
sample k − d − 1 acts over the first λT of a sample, that of k − d over the rest: the
modified z-transform). For λ = 0 this is python-control's own sample_system(ss(P), T, 'zoh')
times z⁻ᵈ, which is what is handed to python-control then; for λ > 0 the one extra input
state of Γ_a is built here with scipy's expm, independently of hapstab.
"""

import math

import control
import numpy as np
import scipy.linalg
import scipy.optimize


def exp_and_integral(a, b, h):
    """(e^{Ah}, ∫₀ʰ e^{Aτ} dτ B) from one matrix exponential of [[A, B], [0, 0]]·h."""
    n, m = b.shape
    big = np.zeros((n + m, n + m))
    big[:n, :n], big[:n, n:] = a, b
    e = scipy.linalg.expm(big * h)
    return e[:n, :n], e[:n, n:]


class SampledLoop:
    """H(z) of a continuous plant (a python-control LTI) at period T with delay (d + λ)T, and
    the wall's C(z) = K + B·V(z)."""

    def __init__(self, plant, period, d, lam, velocity_tf):
        t = period
        s = control.ss(plant)
        a, b, c = (np.asarray(x, float) for x in (s.A, s.B, s.C))
        if lam == 0.0:
            hd = control.sample_system(s, t, "zoh")
            phi, gb, ga = np.asarray(hd.A), np.asarray(hd.B), np.zeros_like(b)
        else:
            phi, _ = exp_and_integral(a, b, t)
            e1, gb = exp_and_integral(a, b, (1.0 - lam) * t)
            _, i_lam = exp_and_integral(a, b, lam * t)
            ga = e1 @ i_lam
            n = len(a)
            # the state [x; u_{k−1}]: x⁺ = Φx + Γ_b u + Γ_a w, w⁺ = u
            hd = control.ss(
                np.block([[phi, ga], [np.zeros((1, n)), np.zeros((1, 1))]]),
                np.vstack([gb, [[1.0]]]),
                np.hstack([c, [[0.0]]]),
                [[0.0]],
                t,
            )
        self.period, self.d = t, d
        self.phi, self.gb, self.ga, self.c = phi, gb, ga, c
        self.h = hd * control.tf([1.0], [1.0] + [0.0] * d, t)
        self.v = velocity_tf

    def control_loop(self, k, b):
        """L(z) for python-control: the wall times H(z) with its delay."""
        wall = control.tf([k], [1.0], self.period) + b * self.v
        return wall * self.h

    def value(self, k, b, theta):
        """L(e^{iθ}) by batched solves of (zI − Φ) (no polynomial in z is formed)."""
        theta = np.atleast_1d(np.asarray(theta, float))
        z = np.exp(1j * theta)
        n = len(self.phi)
        m = z[:, None, None] * np.eye(n) - self.phi[None, :, :]
        rhs = self.gb[None, :, :] + self.ga[None, :, :] / z[:, None, None]
        x = np.linalg.solve(m, rhs.astype(complex))
        h = (self.c[None, :, :] @ x)[:, 0, 0] * z ** (-self.d)
        num, den = (np.asarray(p, float).ravel() for p in (self.v.num[0][0], self.v.den[0][0]))
        v = np.polyval(num, z) / np.polyval(den, z)
        return (k + b * v) * h


def dense_grid(points=10**6):
    """θ in (0, π): half uniform, half log-spaced from 1e-9 to π (crossovers near 0)."""
    half = points // 2
    uni = np.linspace(0.0, math.pi, half + 2)[1:-1]
    logs = np.logspace(-9, math.log10(math.pi), half, endpoint=False)
    return np.unique(np.concatenate([uni, logs]))


def brent(f, lo, hi):
    return scipy.optimize.brentq(f, lo, hi, xtol=1e-15 * hi, rtol=4 * np.finfo(float).eps, maxiter=200)


class DenseMargins:
    """Every gain crossover (|L| = 1) and every crossing of the negative real axis (phase
    −180°) of L on a dense grid, each refined by Brent's method, and min |1 + L| refined by a
    bounded scalar minimization: the independent evaluation."""

    def __init__(self, f, grid):
        self.f = f
        vals = f(grid)
        mag = np.abs(vals)
        lg = np.log(mag) if np.all(mag > 0) else np.log(np.maximum(mag, 1e-300))
        g = lambda t: float(np.log(abs(f(t)[0])))  # noqa: E731
        im = lambda t: float(f(t)[0].imag)  # noqa: E731
        idx = np.nonzero(np.sign(lg[1:]) != np.sign(lg[:-1]))[0]
        self.gain = [brent(g, grid[i], grid[i + 1]) for i in idx]
        sgn = np.sign(vals.imag)
        idx = np.nonzero((sgn[1:] != sgn[:-1]) & (vals.real[1:] < 0) & (vals.real[:-1] < 0))[0]
        self.phase = [brent(im, grid[i], grid[i + 1]) for i in idx]
        self.at_pi = complex(f(np.array([math.pi]))[0])
        self.at_zero = complex(f(np.array([grid[0]]))[0])
        dist = np.abs(1 + vals)
        i = int(np.argmin(dist))
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
        r = scipy.optimize.minimize_scalar(
            lambda t: abs(1 + f(t)[0]), bounds=(lo, hi), method="bounded",
            options={"xatol": 1e-14 * hi},
        )
        self.sm = min(float(r.fun), float(dist[i]), abs(1 + self.at_pi))
        self.grid_gap = float(np.max(np.diff(grid)))

    def pm(self, theta):
        w = (180.0 + math.degrees(np.angle(self.f(theta)[0]))) % 360.0
        return w - 360.0 if w > 180.0 else w

    def gm(self, theta):
        return -1.0 / float(self.f(theta)[0].real)
