#!/usr/bin/env python3
"""Independent state-space referee for hapstab's stability verdicts: the closed-loop spectral
radius of a haptic loop from its state matrix (numpy/scipy), redone at 40 significant digits
in mpmath where double precision is doubtful.

A library module of benches/baseline/statespace_fixture.py (which writes the fixture
crates/hapstab/tests/fixtures/statespace_loops.json) and statespace_validate.py (which checks
this referee against python-control's fixture and a closed form). Needs numpy, scipy and
mpmath; benches/baseline/statespace_fixture.sh makes a venv under target/ with them.

The loop (the same physics as hapstab's, implemented here from its definition):

- plant from force to measured position, written in normalized time tau = t/T (one unit per
  sample) with the force in units of k_ref = m_ref/T^2 (a diagonal similarity and a scale:
  neither changes an eigenvalue): a mass-spring-damper 1/(m s^2 + b s + k) in the state
  (y, T y'); a two-mass device (motor x_m, handle x_h, transmission k_t, b_t, arm on the
  handle) in (x_m, T v_m, x_h, T v_h); a transfer function num(s)/den(s) in OBSERVABLE
  canonical form in sigma = sT, balanced by powers of two (scipy.linalg.matrix_balance);
  an actuator lag 1/(tau s + 1) as one more state;
- zero-order hold with the held interval split at the fractional delay: the force computed at
  sample j acts from jT + t_d to (j+1)T + t_d, t_d = (d + lam)T, so over one sample the input
  is u_{k-d-1} on [0, lam) and u_{k-d} on [lam, 1):
      x_{k+1} = Phi x_k + G0 u_{k-d} + G1 u_{k-d-1},
      Phi = e^{A(1-lam)} e^{A lam},  G0 = Psi(1-lam) B,  G1 = e^{A(1-lam)} Psi(lam) B,
  each e^{Ah} and Psi(h)B = int_0^h e^{As} ds B read off the exponential of the augmented
  matrix [[A, B], [0, 0]] h (scipy.linalg.expm; mpmath.expm at 40 digits);
- delay states u_{k-1} .. u_{k-D} (D = d, or d + 1 with a fraction);
- the velocity estimator as a direct-form-I filter on the position,
  v_k = (sum_i b_i y_{k-i} - sum_{i>=1} a_i v_{k-i}) / a0 (m/s), with its past positions and
  past velocities as states: backward b = [1, -1]/T; lowpass:FC b = (1 - c)[1, -1]/T,
  a = [1, -c], c = exp(-2 pi FC T); average:N b = [1, 0, .., 0, -1]/(N T); iir:b/a as given;
- the wall's force on the device u_k = -(K y_k + B v_k) (the wall pushes back; hapstab's
  loop closes on 1 + H(z)(K + B V(z)) = 0, the same sign).

The closed loop is the state matrix M(K, B) = M0 + a Ma + b Mb with a = K/k_ref, b = B/(k_ref
T); its eigenvalues (numpy.linalg.eigvals) give rho = max |lambda|; stable iff rho < 1.

The 40-digit path (used where |rho - 1| < 1e-6, where two or more eigenvalues lie within
1e-3 of z = 1, or where the dominant eigenvalue's error exceeds 1e-13: its condition number
times the rounding unit and the norm, or the spread of the radius over two random diagonal
similarities of M, which catches the square-root sensitivity near a multiple eigenvalue):
the plant, its exponentials and the estimator are rebuilt from the same input numbers in
mpmath, and every eigenvalue of M that could be the dominant one (within
1e-3 of the largest modulus, or within 1e-3 of z = 1) is refined to 40 digits by
simultaneous Newton steps (Aberth's correction among the refined set) on the closed loop's
characteristic function, the determinant of zI - M reduced by the matrix determinant lemma
to the plant's blocks:
    chi(z) = z^(d+1) det(zI - Phi) A~(z) + (z N0(z) + N1(z)) (a A~(z) + b B~(z)),
    N_i(z) = C adj(zI - Phi) G_i = -det([[zI - Phi, G_i], [C, 0]]),
with A~, B~ the estimator's denominator and (T times) numerator in powers of z. No
polynomial coefficients are formed: chi is evaluated at each point from the 40-digit blocks.
"""

import cmath
import math

import mpmath as mp
import numpy as np
import scipy.linalg

# Significant digits of the high-precision path.
DIGITS = 40
mp.mp.dps = DIGITS

# A double-precision radius closer to 1 than this is redone at 40 digits (its verdict could
# hang on the last digits of a poorly conditioned eigenvalue).
DOUBTFUL_RADIUS = 1e-6
# Eigenvalues within this distance of z = 1 "crowd" it: slow plant modes at fast sampling,
# where double-precision eigenvalues lose digits.
CROWD_RADIUS = 1e-3
# Largest first-order error (condition number x rounding unit x ||M||) of the dominant
# eigenvalue trusted in double precision: the fixture's radii must be good to far better
# than the 1e-9 that hapstab is checked to.
TRUSTED_ERROR = 1e-13
# Beyond this distance of 1 no double radius is doubted (the worst error seen is 2e-5).
SPREAD_RADIUS = 1e-2
# In a bisection the double radius decides the side of the circle unless it lies within
# this many times its first-order error bound of 1 (the bound is an estimate, not a proof).
SIGN_MARGIN = 10.0
# Eigenvalues this close (in modulus) to the largest one are refined at 40 digits.
REFINE_BAND = 1e-3
# Newton steps stop when the correction falls below this (relative): 6 digits below the
# 40 carried.
REFINE_STOP = mp.mpf(10) ** (6 - DIGITS)
# A root of multiplicity m is determined to only (1e-40)^(1/m) at 40 digits (a double root:
# a rigid-body mode at K = B = 0, to 1e-20); radii are stored as doubles, so Newton steps
# that stall below 1e-18 (relative) are accepted.
REFINE_ACCEPT = mp.mpf("1e-18")
# Every start is moved this far (relative) off its double-precision value, in a different
# direction each: Newton steps from a real start on a real function stay real, and a pair
# of real double-precision eigenvalues may be a complex pair (two eigenvalues 1e-8 apart
# near a rigid-body double root at z = 1).
START_NUDGE = mp.mpf("1e-9")
# Newton iterations allowed (a double root converges linearly, one bit per step).
REFINE_ITERATIONS = 200
# Largest distance allowed between a double-precision eigenvalue and its 40-digit
# refinement; more would mean the two paths model different loops (near a multiple root at
# z = 1 the double eigenvalues can be off by the square root of the rounding, 2e-5 seen).
REFINE_MAX_SHIFT = CROWD_RADIUS


# ---- numbers: one model code, in doubles or in 40-digit mpmath numbers ---------------------


class Doubles:
    """Arithmetic in IEEE doubles."""

    real = staticmethod(float)
    exp = staticmethod(math.exp)
    pi = math.pi

    @staticmethod
    def complex(x):
        return complex(x)


class Digits:
    """Arithmetic in mpmath at DIGITS significant digits."""

    real = staticmethod(mp.mpf)
    exp = staticmethod(mp.exp)
    pi = mp.pi

    @staticmethod
    def complex(x):
        return mp.mpc(x)


def poly_desc(c, s):
    """Horner evaluation of descending coefficients at s."""
    acc = 0 * s
    for x in c:
        acc = acc * s + x
    return acc


def strip(c):
    c = list(c)
    while c and c[0] == 0:
        c.pop(0)
    return c


# ---- continuous plant in normalized time and force units -----------------------------------


def reference_mass(plant, period, f):
    """The mass that scales the force: m for a mass-spring-damper, the total mass of a
    two-mass device, 1/(w^2 |P(jw)|) at w = 1/T for a transfer function (any scale would do:
    it only sets the units the walls are scanned in)."""
    kind = plant["kind"]
    if kind == "mass_spring_damper":
        return f.real(plant["mass"])
    if kind == "two_mass":
        return f.real(plant["motor_mass"]) + f.real(plant["handle_mass"]) + f.real(plant["arm"]["mass"])
    w = 1 / f.real(period)
    s = f.complex(1j) * w
    num = [f.real(x) for x in strip(plant["num"])]
    den = [f.real(x) for x in strip(plant["den"])]
    g = abs(poly_desc(num, s) / poly_desc(den, s))
    return 1 / (w * w * g)


def mechanics(plant, period, f):
    """(A, B, C) of the plant in normalized time, force in units of m_ref/T^2."""
    t = f.real(period)
    m_ref = reference_mass(plant, period, f)
    kind = plant["kind"]
    if kind == "mass_spring_damper":
        m, b, k = (f.real(plant[x]) for x in ("mass", "damping", "stiffness"))
        a = [[0 * t, 1 + 0 * t], [-k * t * t / m, -b * t / m]]
        return a, [0 * t, m_ref / m], [1 + 0 * t, 0 * t]
    if kind == "two_mass":
        j, bm = f.real(plant["motor_mass"]), f.real(plant["motor_damping"])
        arm = plant["arm"]
        mh = f.real(plant["handle_mass"]) + f.real(arm["mass"])
        kt = f.real(plant["transmission_stiffness"]) * t * t
        bt = f.real(plant["transmission_damping"]) * t
        kh, bh = f.real(arm["stiffness"]) * t * t, f.real(arm["damping"]) * t
        z, one = 0 * t, 1 + 0 * t
        a = [
            [z, one, z, z],
            [-kt / j, -(bm * t + bt) / j, kt / j, bt / j],
            [z, z, z, one],
            [kt / mh, bt / mh, -(kt + kh) / mh, -(bt + bh) / mh],
        ]
        return a, [z, m_ref / j, z, z], [one, z, z, z]
    return observable_form(plant, t, m_ref, f)


def observable_form(plant, t, m_ref, f):
    """num(s)/den(s) with s = sigma/T in observable canonical form: x' = A x + B u, y = x_1
    with A[i][0] = -alpha_{n-1-i}, A[i][i+1] = 1, B[i] = beta_{n-1-i} for the monic
    sigma-polynomials sigma^n + sum alpha_k sigma^k and sum beta_k sigma^k."""
    num = [f.real(x) for x in strip(plant["num"])]
    den = [f.real(x) for x in strip(plant["den"])]
    n = len(den) - 1
    lead = den[0]
    k_u = m_ref / (t * t)
    asc_den = den[::-1]
    asc_num = num[::-1] + [0 * t] * (n - len(num))
    alpha = [asc_den[k] * t ** (n - k) / lead for k in range(n)]
    beta = [asc_num[k] * k_u * t ** (n - k) / lead for k in range(n)]
    z = 0 * t
    a = [[z] * n for _ in range(n)]
    for i in range(n):
        a[i][0] = -alpha[n - 1 - i]
        if i + 1 < n:
            a[i][i + 1] = 1 + z
    b = [beta[n - 1 - i] for i in range(n)]
    c = [1 + z] + [z] * (n - 1)
    return a, b, c


def with_lag(a, b, c, ratio):
    """Appends the actuator lag u_a' = r (u - u_a), r = T/tau, in front of the input."""
    n = len(a)
    z = 0 * ratio
    a2 = [list(a[i]) + [b[i]] for i in range(n)] + [[z] * n + [-ratio]]
    return a2, [z] * n + [ratio], list(c) + [z]


def continuous(case, f):
    """(A, B, C) of the case's plant with its actuator lag, normalized time and force."""
    a, b, c = mechanics(case["plant"], case["period"], f)
    lag = case["force_lag"]
    if lag > 0:
        a, b, c = with_lag(a, b, c, f.real(case["period"]) / f.real(lag))
    return a, b, c


# ---- zero-order hold with the split interval ------------------------------------------------


def hold_blocks_double(a, b, lam):
    """(Phi, G0, G1) in doubles, by scipy.linalg.expm of the augmented matrix."""
    n = len(a)
    aug = np.zeros((n + 1, n + 1))
    aug[:n, :n] = np.array(a, dtype=float)
    aug[:n, n] = np.array(b, dtype=float)

    def exp_h(h):
        if h == 0:
            return np.eye(n), np.zeros(n)
        e = scipy.linalg.expm(aug * h)
        return e[:n, :n], e[:n, n]

    e2, p2 = exp_h(1.0 - lam)
    if lam == 0:
        return e2, p2, np.zeros(n)
    e1, p1 = exp_h(lam)
    return e2 @ e1, p2, e2 @ p1


def hold_blocks_digits(a, b, lam):
    """(Phi, G0, G1) at 40 digits, by mpmath.expm of the augmented matrix."""
    n = len(a)
    lam = mp.mpf(lam)

    def exp_h(h):
        m = mp.zeros(n + 1, n + 1)
        for i in range(n):
            for j in range(n):
                m[i, j] = a[i][j] * h
            m[i, n] = b[i] * h
        e = mp.expm(m)
        return e[:n, :n], e[:n, n]

    e2, p2 = exp_h(1 - lam)
    if lam == 0:
        return e2, p2, mp.zeros(n, 1)
    e1, p1 = exp_h(lam)
    return e2 * e1, p2, e2 * p1


# ---- the velocity estimator --------------------------------------------------------------------


def estimator(spec, period, f):
    """(b, a) of v = (b0 + b1 q^-1 + ..)/(a0 + a1 q^-1 + ..) y, b scaled by T (output T v)."""
    kind, _, arg = spec.partition(":")
    t = f.real(period)
    one = 1 + 0 * t
    if kind == "backward":
        return [one, -one], [one]
    if kind == "lowpass":
        c = f.exp(-2 * f.pi * f.real(float(arg)) * t)
        return [1 - c, c - 1], [one, -c]
    if kind == "average":
        n = int(arg)
        return [one / n] + [0 * t] * (n - 1) + [-one / n], [one]
    if kind == "iir":
        b_txt, a_txt = arg.split("/")
        b = [f.real(float(x)) * t for x in b_txt.split(",")]
        a = [f.real(float(x)) for x in a_txt.split(",")]
        return b, a
    raise ValueError(f"unknown velocity estimator {spec!r}")


# ---- the closed loop in doubles -------------------------------------------------------------------


class Layout:
    """Indices of the closed loop's states: plant x, delay line u_{k-1..k-D}, past positions
    y_{k-1..k-P}, past velocities v_{k-1..k-Q}."""

    def __init__(self, n, delay, nb, na):
        self.n, self.d, self.lam = n, delay["samples"], delay["fraction"]
        self.depth = self.d + (1 if self.lam > 0 else 0)
        self.p, self.q = nb - 1, na - 1
        self.w0 = n
        self.y0 = n + self.depth
        self.v0 = self.y0 + self.p
        self.size = self.v0 + self.q


def closed_loop_parts(case):
    """(M0, Ma, Mb) with M(a, b) = M0 + a Ma + b Mb, in doubles."""
    a, b, c = continuous(case, Doubles)
    if case["plant"]["kind"] == "transfer_function":
        a_bal, (scale, _) = scipy.linalg.matrix_balance(
            np.array(a, dtype=float), permute=False, separate=True
        )
        a, b, c = a_bal, np.array(b, dtype=float) / scale, np.array(c, dtype=float) * scale
    lay_delay = case["delay"]
    phi, g0, g1 = hold_blocks_double(a, b, lay_delay["fraction"])
    c = np.array(c, dtype=float)
    vb, va = estimator(case["velocity"], case["period"], Doubles)
    lay = Layout(len(c), lay_delay, len(vb), len(va))
    size = lay.size
    y_row = np.zeros(size)
    y_row[: lay.n] = c
    v_row = vb[0] * y_row
    for i in range(1, len(vb)):
        v_row[lay.y0 + i - 1] += vb[i]
    for i in range(1, len(va)):
        v_row[lay.v0 + i - 1] -= va[i]
    v_row = v_row / va[0]
    m0, ma, mb = np.zeros((size, size)), np.zeros((size, size)), np.zeros((size, size))
    m0[: lay.n, : lay.n] = phi

    def add_input(gain, lag):
        """Adds gain * u_{k-lag} to the plant rows."""
        if lag == 0:
            ma[: lay.n, :] -= np.outer(gain, y_row)
            mb[: lay.n, :] -= np.outer(gain, v_row)
        else:
            m0[: lay.n, lay.w0 + lag - 1] += gain

    add_input(g0, lay.d)
    if lay.lam > 0:
        add_input(g1, lay.d + 1)
    if lay.depth:
        ma[lay.w0, :] = -y_row
        mb[lay.w0, :] = -v_row
        for j in range(1, lay.depth):
            m0[lay.w0 + j, lay.w0 + j - 1] = 1.0
    if lay.p:
        m0[lay.y0, :] = y_row
        for j in range(1, lay.p):
            m0[lay.y0 + j, lay.y0 + j - 1] = 1.0
    if lay.q:
        m0[lay.v0, :] = v_row
        for j in range(1, lay.q):
            m0[lay.v0 + j, lay.v0 + j - 1] = 1.0
    return m0, ma, mb


# ---- the characteristic function at 40 digits -------------------------------------------------


class Characteristic:
    """chi(z) of the module doc from the case's blocks at 40 digits."""

    def __init__(self, case):
        a, b, c = continuous(case, Digits)
        t = mp.mpf(case["period"])
        self.k_ref = reference_mass(case["plant"], case["period"], Digits) / (t * t)
        self.b_ref = self.k_ref * t
        phi, g0, g1 = hold_blocks_digits(a, b, case["delay"]["fraction"])
        self.phi = [[phi[i, j] for j in range(phi.cols)] for i in range(phi.rows)]
        self.n = len(c)
        self.c = c
        self.d = case["delay"]["samples"]
        vb, va = estimator(case["velocity"], case["period"], Digits)
        length = max(len(vb), len(va))
        self.vb = [x / va[0] for x in vb] + [mp.mpf(0)] * (length - len(vb))
        self.va = [x / va[0] for x in va] + [mp.mpf(0)] * (length - len(va))
        self.g = [[g0[i] for i in range(g0.rows)], [g1[i] for i in range(g1.rows)]]

    def blocks(self, z):
        """det(zI - Phi) and C adj(zI - Phi) G_i, from one LU factorization of zI - Phi with
        partial pivoting: adj(A) g = det(A) A^-1 g. The product is a polynomial in A's
        entries, so the backward-stable LU gives it accurately even where A is nearly
        singular (z near a plant pole); an exactly zero pivot falls back to the bordered
        determinants -det([[A, g], [C, 0]])."""
        n = self.n
        lu = [[-self.phi[i][j] for j in range(n)] for i in range(n)]
        for i in range(n):
            lu[i][i] += z
        rhs = [list(g) for g in self.g]
        det = mp.mpc(1)
        for k in range(n):
            p = max(range(k, n), key=lambda r: abs(lu[r][k]))
            if lu[p][k] == 0:
                return self.bordered(z)
            if p != k:
                lu[k], lu[p] = lu[p], lu[k]
                for r in rhs:
                    r[k], r[p] = r[p], r[k]
                det = -det
            piv = lu[k][k]
            det *= piv
            for i in range(k + 1, n):
                f = lu[i][k] / piv
                if f:
                    row, top = lu[i], lu[k]
                    for j in range(k + 1, n):
                        row[j] -= f * top[j]
                    for r in rhs:
                        r[i] -= f * r[k]
        nums = []
        for r in rhs:
            x = [mp.mpc(0)] * n
            for i in range(n - 1, -1, -1):
                acc = r[i] - mp.fsum(lu[i][j] * x[j] for j in range(i + 1, n))
                x[i] = acc / lu[i][i]
            nums.append(det * mp.fsum(c * xi for c, xi in zip(self.c, x)))
        return det, nums

    def bordered(self, z):
        """The same blocks by mpmath determinants (no division)."""
        n = self.n
        m = mp.matrix(n + 1, n + 1)
        for i in range(n):
            for j in range(n):
                m[i, j] = -self.phi[i][j]
            m[i, i] += z
        det = mp.det(m[:n, :n])
        nums = []
        for g in self.g:
            for i in range(n):
                m[i, n] = g[i]
                m[n, i] = self.c[i]
            m[n, n] = 0
            nums.append(-mp.det(m))
        return det, nums

    def __call__(self, z, a, b):
        det, (n0, n1) = self.blocks(z)
        av = poly_desc(self.va, z)
        bv = poly_desc(self.vb, z)
        return z ** (self.d + 1) * det * av + (z * n0 + n1) * (a * av + b * bv)


def refine(chi, a, b, starts):
    """40-digit roots of chi near the given double-precision eigenvalues: Newton steps with
    Aberth's correction among them (so that no two converge to the same root), the
    derivative by a central difference at 40 digits (step 1e-13: truncation 1e-26, rounding
    1e-27 relative)."""
    zs = [mp.mpc(complex(s)) + START_NUDGE * mp.expj(0.7 + 1.3 * i) * max(abs(complex(s)), 1e-3)
          for i, s in enumerate(starts)]
    worst = mp.mpf(1)
    for _ in range(REFINE_ITERATIONS):
        worst = mp.mpf(0)
        for i, z in enumerate(zs):
            h = mp.mpf("1e-13") * max(1, abs(z))
            f0 = chi(z, a, b)
            if f0 == 0:
                continue
            df = (chi(z + h, a, b) - chi(z - h, a, b)) / (2 * h)
            ratio = f0 / df
            rep = sum(1 / (z - w) for j, w in enumerate(zs) if j != i)
            step = ratio / (1 - ratio * rep)
            zs[i] = z - step
            worst = max(worst, abs(step) / max(1, abs(z)))
        if worst < REFINE_STOP:
            return zs
    if worst < REFINE_ACCEPT:
        return zs
    raise RuntimeError(f"40-digit refinement did not converge at a={a}, b={b}")


# ---- the referee of one loop ----------------------------------------------------------------


class Referee:
    """Spectral radius of one loop at any wall (K, B) in N/m, Ns/m; see the module doc."""

    def __init__(self, case):
        self.case = case
        self.m0, self.ma, self.mb = closed_loop_parts(case)
        t = case["period"]
        self.k_ref = float(reference_mass(case["plant"], t, Doubles)) / (t * t)
        self.b_ref = self.k_ref * t
        self._chi = None
        self.precise_calls = 0
        size = self.m0.shape[0]
        gen = np.random.default_rng(1)
        self.similarities = [2.0 ** gen.uniform(-3, 3, size) + 0.1 * gen.random(size) for _ in range(2)]

    def units(self, k, b):
        return k / self.k_ref, b / self.b_ref

    def matrix(self, k, b):
        a, bb = self.units(k, b)
        return self.m0 + a * self.ma + bb * self.mb

    def eigenvalues(self, k, b):
        return np.linalg.eigvals(self.matrix(k, b))

    def radius_double(self, k, b):
        return float(np.max(np.abs(self.eigenvalues(k, b))))

    def dominant_error(self, k, b):
        """First-order error bound of the dominant eigenvalue, kappa * eps * ||M||_F on the
        balanced matrix (the similarity LAPACK's eigenvalue routine applies itself), with
        kappa = 1/|y^H x| from unit left and right eigenvectors."""
        m, _ = scipy.linalg.matrix_balance(self.matrix(k, b), permute=False)
        w, vl, vr = scipy.linalg.eig(m, left=True, right=True)
        i = int(np.argmax(np.abs(w)))
        x, y = vr[:, i], vl[:, i]
        cos = abs(np.vdot(y, x)) / (np.linalg.norm(x) * np.linalg.norm(y))
        kappa = 1.0 / max(cos, 1e-300)
        return kappa * np.finfo(float).eps * np.linalg.norm(m)

    def spread(self, k, b):
        """The double radius's error as seen: the spread of the largest eigenvalue modulus of
        M and of two fixed random diagonal similarities D M D^-1 of it (the same spectrum,
        rounded differently). It catches what the first-order bound misses near a multiple
        eigenvalue, where the error grows like the square root of the rounding."""
        m = self.matrix(k, b)
        rhos = [float(np.max(np.abs(np.linalg.eigvals(m))))]
        for d in self.similarities:
            rhos.append(float(np.max(np.abs(np.linalg.eigvals(d[:, None] * m / d[None, :])))))
        return max(rhos) - min(rhos)

    def error(self, k, b):
        """The larger of the first-order bound and the spread."""
        return max(self.dominant_error(k, b), self.spread(k, b))

    def doubtful(self, k, b, eig=None):
        """True where the double-precision radius is not trusted (module doc)."""
        eig = self.eigenvalues(k, b) if eig is None else eig
        rho = float(np.max(np.abs(eig)))
        crowd = int(np.sum(np.abs(eig - 1.0) < CROWD_RADIUS))
        return abs(rho - 1.0) < DOUBTFUL_RADIUS or crowd >= 2 or self.error(k, b) > TRUSTED_ERROR

    def radius_precise(self, k, b):
        """The 40-digit radius (an mpf) and the largest shift of a refined eigenvalue."""
        if self._chi is None:
            self._chi = Characteristic(self.case)
        self.precise_calls += 1
        eig = self.eigenvalues(k, b)
        top = float(np.max(np.abs(eig)))
        pick = [z for z in eig if abs(z) >= top - REFINE_BAND or abs(z - 1.0) < CROWD_RADIUS]
        chi = self._chi
        zs = refine(chi, mp.mpf(k) / chi.k_ref, mp.mpf(b) / chi.b_ref, pick)
        shift = max(abs(complex(z) - s) for z, s in zip(zs, pick))
        if shift > REFINE_MAX_SHIFT:
            raise RuntimeError(f"40-digit root moved {shift:.1e} from its eigenvalue at K={k}, B={b}")
        rest = [abs(z) for z in eig if not (abs(z) >= top - REFINE_BAND or abs(z - 1.0) < CROWD_RADIUS)]
        rho = max([abs(z) for z in zs] + [mp.mpf(x) for x in rest])
        return rho, shift

    def radius(self, k, b):
        """(rho, precise): the double radius, or the 40-digit one (as the nearest double)
        where the double one is doubtful."""
        eig = self.eigenvalues(k, b)
        if self.doubtful(k, b, eig):
            rho, _ = self.radius_precise(k, b)
            return float(rho), True
        return float(np.max(np.abs(eig))), False

    def stable(self, k, b, rho=None):
        """rho < 1 for the scans and bisections: the double radius (`rho` when given) unless
        it lies within SIGN_MARGIN times its dominant eigenvalue's error bound of 1 (then the
        40-digit one)."""
        rho = self.radius_double(k, b) if rho is None else rho
        if abs(rho - 1.0) < SPREAD_RADIUS and abs(rho - 1.0) < SIGN_MARGIN * self.error(k, b):
            # the nearest double decides, as for the fixture's walls: a root exactly on the
            # circle (rho = 1 - 1e-38 at 40 digits) is not stable
            return float(self.radius_precise(k, b)[0]) < 1.0
        return rho < 1.0


# ---- boundaries and stable intervals --------------------------------------------------------------

# Bisections stop at this relative width in K, or at BISECT_FLOOR times the wall scale for
# a crossing at K = 0 (where no relative width is ever reached).
BISECT_REL = 1e-12
BISECT_FLOOR = 1e-24
# The K scan: |a| = |K|/k_ref on a log grid over SCAN_DECADES with SCAN_PER_DECADE points
# per decade, both signs, and a = 0. The span is wide on purpose: k_ref is only a scale
# (for a high-order transfer function it can be 1e10 times the stiffness that matters).
SCAN_DECADES = (-12.0, 5.0)
SCAN_PER_DECADE = 24
# Local extrema of rho on the grid this close to 1 are refined by a golden-section search
# between their neighbours: a stable (or unstable) island narrower than the grid spacing
# shows as a dip of rho towards 1 (or a bump) there.
EXTREMUM_WINDOW = 0.1
GOLDEN_STEPS = 60


def scan_grid(k_ref):
    lo, hi = SCAN_DECADES
    e = np.linspace(lo, hi, int(round((hi - lo) * SCAN_PER_DECADE)) + 1)
    pos = list(k_ref * 10.0**e)
    return [-x for x in reversed(pos)] + [0.0] + pos


def bisect(ref, b, k_lo, k_hi, lo_stable):
    """The K in (k_lo, k_hi) where stability changes at damping b."""
    floor = BISECT_FLOOR * ref.k_ref
    while k_hi - k_lo > max(BISECT_REL * max(abs(k_lo), abs(k_hi)), floor):
        mid = 0.5 * (k_lo + k_hi)
        if ref.stable(mid, b) == lo_stable:
            k_lo = mid
        else:
            k_hi = mid
    return 0.5 * (k_lo + k_hi)


def golden(fun, lo, hi):
    """Minimum of fun on [lo, hi] by golden-section search: (x, fun(x))."""
    g = (math.sqrt(5.0) - 1.0) / 2.0
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = fun(x1), fun(x2)
    for _ in range(GOLDEN_STEPS):
        if f1 < f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - g * (hi - lo)
            f1 = fun(x1)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + g * (hi - lo)
            f2 = fun(x2)
    return (x1, f1) if f1 < f2 else (x2, f2)


def islands(ref, b, ks, rhos):
    """Extra scan points inside islands the grid stepped over: at each local minimum of rho
    in [1, 1 + EXTREMUM_WINDOW) the minimum between its neighbours (a stable island if it
    is < 1), at each local maximum in (1 - EXTREMUM_WINDOW, 1) the maximum (an unstable
    one if it is >= 1)."""
    extra = []
    for i in range(1, len(ks) - 1):
        r0, r1, r2 = rhos[i - 1], rhos[i], rhos[i + 1]
        dip = r1 <= r0 and r1 <= r2 and 1.0 <= r1 < 1.0 + EXTREMUM_WINDOW
        bump = r1 >= r0 and r1 >= r2 and 1.0 - EXTREMUM_WINDOW < r1 < 1.0
        if not (dip or bump):
            continue
        sign = 1.0 if dip else -1.0
        k, r = golden(lambda x: sign * ref.radius_double(x, b), ks[i - 1], ks[i + 1])
        rho = sign * r
        if (rho < 1.0) if dip else (rho >= 1.0):
            extra.append(k)
    return extra


def stable_intervals(ref, b):
    """All stable intervals of K at damping b: the scan's sign changes (with the islands the
    grid stepped over), each bisected. Returns (intervals [(lo, hi)], crossings [K]); an end
    beyond the scan is None."""
    ks = scan_grid(ref.k_ref)
    rhos = [ref.radius_double(k, b) for k in ks]
    extra = islands(ref, b, ks, rhos)
    pts = sorted(list(zip(ks, rhos)) + [(k, None) for k in extra], key=lambda p: p[0])
    ks = [k for k, _ in pts]
    st = [ref.stable(k, b, r) for k, r in pts]
    crossings, intervals = [], []
    if st[0]:
        intervals.append([None, None])
    for i in range(len(ks) - 1):
        if st[i] != st[i + 1]:
            kc = bisect(ref, b, ks[i], ks[i + 1], st[i])
            crossings.append(kc)
            if st[i + 1]:
                intervals.append([kc, None])
            else:
                intervals[-1][1] = kc
    return [tuple(iv) for iv in intervals], crossings


def polar(z):
    """(modulus, angle) of a complex number, for reports."""
    return abs(z), cmath.phase(z)
