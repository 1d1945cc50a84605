//! The positive real roots of a real polynomial, all of them, by the derivative cascade:
//! between two consecutive real roots of p′ the polynomial p is monotone, so it has at most one
//! root there, found where its sign changes; the roots of p′ come the same way from p″, down
//! to a linear polynomial (Collins & Loos, "Real zeros of polynomials", in *Computer Algebra*,
//! Springer 1983, §4; the classical isolation by Rolle's theorem). Each bracketed root is
//! refined by Laguerre's method safeguarded by bisection (Press et al., *Numerical Recipes*,
//! 3rd ed., §9.5 for Laguerre's step, §9.4 `rtsafe` for the safeguard; for a polynomial whose
//! roots are all real Laguerre's step converges cubically from any start toward the nearest
//! root, where Newton's crawls across a cluster of roots), bisecting geometrically while a
//! bracket spans decades. Below x = 1 the iteration runs on p, above on the reversed
//! polynomial in y = 1/x (the same roots inverted), so that no power of a large x overflows.
//!
//! The roots are sought within the Fujiwara bounds of p's root moduli (Fujiwara 1916:
//! every root has |x| ≤ 2·max_j |c_j/c_n|^{1/(n−j)}, and by the reversed polynomial
//! |x| ≥ ½·1/max_j |c_j/c_0|^{1/j}), so a root of 1e-17 and one of 1e17 are both found to
//! full relative precision. Where the coefficients' sign variations (Descartes' bound on the
//! positive roots) are met by sign changes between approximate roots from Laguerre's method
//! with deflation, those cuts bracket every root at once and the cascade is not needed
//! ([`deflation`]). A double root (a tangency) is found only where rounding leaves a
//! sign change; a pair of roots closer than the polynomial's rounding allows may be lost as a
//! pair, which the callers' confirmation by the point test guards.

mod deflation;

/// Newton steps at most per root before the bracket is bisected to the end (each halves the
/// bracket at worst; quadratic convergence needs about six from a bracket of a few ulps'
/// worth of decades).
const MAX_STEPS: usize = 200;

/// Relative Newton step below which the root is taken (the next step's error, quadratic in
/// this one, is below the double's rounding).
const NEWTON_DONE: f64 = 1e-9;

/// The same for a derivative's roots, which only end the next level's brackets: Laguerre's
/// step converges cubically, so after a step of 1e-4 the error is of order 1e-12 relative,
/// far below any sign test's resolution.
const BRACKET_DONE: f64 = 1e-4;

/// A bracket is bisected geometrically (at √(lo·hi)) while hi/lo exceeds this ratio: a root
/// at 1e-17 in a bracket reaching 1 is then found in a few dozen steps instead of 60
/// arithmetic halvings that never reach it.
const GEOMETRIC_RATIO: f64 = 8.0;

/// The distinct positive real roots of the polynomial with ascending coefficients `c`,
/// increasing (see the module doc). Exact zeros at x = 0 are not positive roots and are
/// dropped; an identically zero polynomial has none.
pub fn positive_roots(c: &[f64]) -> Vec<f64> {
    let Some(p) = normalized(c).filter(|p| p.len() > 1) else {
        return Vec::new();
    };
    let (lo, hi) = root_bounds(&p);
    match deflation::descartes_cuts(&p, (lo, hi)) {
        Some(cuts) => {
            let (mut scratch, mut roots) = (Scratch::default(), Vec::new());
            roots_between_ends(&p, &cuts, NEWTON_DONE, &mut scratch, &mut roots);
            roots
        }
        None => cascade(&p, &[(lo, hi)]),
    }
}

/// The distinct real roots of the polynomial with ascending coefficients `c` inside the open
/// intervals `windows` (disjoint, increasing, within [0, ∞]), increasing: the cascade of the
/// module doc run on the windows alone (between consecutive roots of p′ inside a window, and
/// the window's ends, p is monotone), so that roots outside them cost nothing. A root on a
/// window's end may be reported or not. Each window is first cut by Descartes' rule of signs
/// into intervals holding one root or none ([`isolated`]), the cascade taking over where that
/// is not sure.
pub fn positive_roots_within(c: &[f64], windows: &[(f64, f64)]) -> Vec<f64> {
    let Some(p) = normalized(c) else {
        return Vec::new();
    };
    let n = p.len() - 1;
    if n == 0 {
        return Vec::new();
    }
    let (lo, hi) = root_bounds(&p);
    // the windows clipped to the bounds of the roots' moduli
    let spans: Vec<(f64, f64)> = windows
        .iter()
        .map(|&(a, b)| (a.max(lo), b.min(hi)))
        .filter(|(a, b)| a < b)
        .collect();
    let mut scratch = Scratch::default();
    let (mut roots, mut found) = (Vec::new(), Vec::new());
    for &span in &spans {
        match isolated(&p, span) {
            Some(ends) => roots_between_ends(&p, &ends, NEWTON_DONE, &mut scratch, &mut found),
            None => found = cascade(&p, &[span]),
        }
        roots.extend_from_slice(&found);
    }
    roots.dedup();
    roots
}

/// Subintervals isolated by Descartes' rule of signs at most, per span: the Vincent–Collins–
/// Akritas bisection (Collins & Akritas 1976).
const ISOLATION_NODES: usize = 48;

/// Points cutting the span (l, r) into intervals that hold no root of p or exactly one, with
/// p's sign changing across it (Descartes' rule of signs on each, [`sign_variations`],
/// bisected while it counts two or more), every cut's sign of p above its rounding; None
/// where a sign is not sure or the bisection does not settle within [`ISOLATION_NODES`] (the
/// cascade decides then).
fn isolated(p: &[f64], (l, r): (f64, f64)) -> Option<Vec<f64>> {
    sure_sign(p, l)?;
    sure_sign(p, r)?;
    let mut ends: Vec<f64> = vec![l];
    let mut budget = ISOLATION_NODES;
    bisected(p, (l, r), &mut budget, &mut ends)?;
    Some(ends)
}

/// [`isolated`] on (l, r), whose ends' signs are sure, l already in `ends`.
fn bisected(p: &[f64], (l, r): (f64, f64), budget: &mut usize, ends: &mut Vec<f64>) -> Option<()> {
    *budget = budget.checked_sub(1)?;
    match sign_variations(p, l, r)? {
        0 => {}
        1 => {
            // exactly one root: the sign changes across it
            (sure_sign(p, l)? != sure_sign(p, r)?).then_some(())?;
        }
        _ => {
            let m = middle(l, r);
            (m > l && m < r).then_some(())?;
            sure_sign(p, m)?;
            bisected(p, (l, m), budget, ends)?;
            return bisected(p, (m, r), budget, ends);
        }
    }
    ends.push(r);
    Some(())
}

/// The Taylor shifts, scaling and reversal of [`sign_variations`] and the evaluation of
/// [`sure_sign`] err by at most about 4n·ε times the same computation on the coefficients'
/// magnitudes (a first-order bound of two shifts of n additions each); a sign counts only
/// where its value exceeds twice that, this many ulps per degree.
const ULPS_PER_DEGREE: f64 = 8.0;

/// The sign of c(x) (true: positive) at 0 < x < ∞ where the value exceeds its rounding bound
/// ([`ULPS_PER_DEGREE`]), by Horner's rule below 1 and on the reversed polynomial above.
pub(crate) fn sure_sign(c: &[f64], x: f64) -> Option<bool> {
    let (mut v, mut m) = (0.0_f64, 0.0_f64);
    let step = |(v, m): (f64, f64), a: f64, y: f64| (v * y + a, m * y + a.abs());
    if x <= 1.0 {
        for &a in c.iter().rev() {
            (v, m) = step((v, m), a, x);
        }
    } else {
        for &a in c {
            (v, m) = step((v, m), a, 1.0 / x);
        }
    }
    let bound = ULPS_PER_DEGREE * c.len() as f64 * f64::EPSILON * m;
    (v.is_finite() && m.is_finite() && v.abs() > bound).then_some(v > 0.0)
}

/// The sign variations of (1 + x)^n·c(l + (r − l)/(1 + x)) (ascending c of degree n,
/// 0 ≤ l < r < ∞; r = ∞: of c(l + x)), whose positive roots are c's roots in (l, r): by
/// Descartes' rule of signs at least the number of c's roots there, of the same parity, and
/// exactly it when 0 or 1. None where a nonzero coefficient lies within its rounding bound
/// ([`ULPS_PER_DEGREE`]) or is not finite.
pub(crate) fn sign_variations(c: &[f64], l: f64, r: f64) -> Option<usize> {
    // each coefficient with the same computation on the magnitudes (l ≥ 0: it bounds the
    // magnitudes of the terms summed)
    let mut v: Vec<(f64, f64)> = c.iter().map(|&a| (a, a.abs())).collect();
    shift(&mut v, l);
    if r.is_finite() {
        // x ↦ (r − l)·y, then y = 1/(1 + x): a reversal and a shift by 1
        let w = r - l;
        let mut f = 1.0;
        for (a, b) in v.iter_mut() {
            *a *= f;
            *b *= f;
            f *= w;
        }
        v.reverse();
        shift(&mut v, 1.0);
    }
    let tol = ULPS_PER_DEGREE * c.len() as f64 * f64::EPSILON;
    let mut last: Option<bool> = None;
    let mut count = 0;
    for &(a, b) in &v {
        if !(a.is_finite() && b.is_finite()) || (b != 0.0 && a.abs() <= tol * b) {
            return None;
        }
        if b == 0.0 {
            continue; // an exact zero
        }
        let positive = a > 0.0;
        count += usize::from(last.is_some_and(|s| s != positive));
        last = Some(positive);
    }
    Some(count)
}

/// Degrees up to which [`shift`] reads its binomials from one table (exact in doubles up to
/// C(56, 28) < 2^53; the stationary polynomial of a degree-28 loop has degree 54); above, the
/// shift is the synthetic division.
const BINOMIAL_DEGREE: usize = 56;

/// Pascal's triangle up to [`BINOMIAL_DEGREE`] by columns: row k holds C(j, k) at j ≥ k.
fn binomials() -> &'static [[f64; BINOMIAL_DEGREE + 1]] {
    static TABLE: std::sync::OnceLock<Vec<[f64; BINOMIAL_DEGREE + 1]>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut cols = vec![[0.0; BINOMIAL_DEGREE + 1]; BINOMIAL_DEGREE + 1];
        for j in 0..=BINOMIAL_DEGREE {
            cols[0][j] = 1.0;
            for k in 1..=j {
                cols[k][j] = cols[k - 1][j - 1] + cols[k][j - 1];
            }
        }
        cols
    })
}

/// Independent partial sums of a coefficient of [`shift`], so that its additions overlap.
const PARTIAL_SUMS: usize = 4;

/// c(x) ↦ c(x + s) in place on the pairs (value, magnitude bound): with e_j = s^j·c_j,
/// c'_k = s^{−k}·Σ_j C(j, k)·e_j, each coefficient a sum of independent terms, where the
/// synthetic division's chain of dependent steps waits on every one
/// ([`crate::poly::taylor_shift`]; used beyond [`BINOMIAL_DEGREE`] or where a power of s
/// leaves the doubles' range).
fn shift(c: &mut [(f64, f64)], s: f64) {
    let n = c.len();
    if s == 0.0 || n == 0 {
        return;
    }
    let mut e = [0.0_f64; BINOMIAL_DEGREE + 1];
    let mut m = [0.0_f64; BINOMIAL_DEGREE + 1];
    let mut inv = [0.0_f64; BINOMIAL_DEGREE + 1];
    let fits = n <= BINOMIAL_DEGREE + 1 && {
        let (mut p, mut q) = (1.0_f64, 1.0_f64);
        for j in 0..n {
            (e[j], m[j], inv[j]) = (p * c[j].0, p.abs() * c[j].1, q);
            p *= s;
            q /= s;
        }
        p.is_normal() && q.is_normal()
    };
    if !fits {
        for i in 0..n {
            for j in (i..n - 1).rev() {
                c[j].0 += s * c[j + 1].0;
                c[j].1 += s * c[j + 1].1;
            }
        }
        return;
    }
    let table = binomials();
    for k in 0..n {
        let row = &table[k][k..n];
        let (ek, mk) = (&e[k..n], &m[k..n]);
        let (mut v, mut w) = ([0.0; PARTIAL_SUMS], [0.0; PARTIAL_SUMS]);
        let mut chunks = row
            .chunks_exact(PARTIAL_SUMS)
            .zip(ek.chunks_exact(PARTIAL_SUMS));
        for (r, x) in chunks.by_ref() {
            for l in 0..PARTIAL_SUMS {
                v[l] += r[l] * x[l];
            }
        }
        for (r, x) in mk
            .chunks_exact(PARTIAL_SUMS)
            .zip(row.chunks_exact(PARTIAL_SUMS))
        {
            for l in 0..PARTIAL_SUMS {
                w[l] += r[l] * x[l];
            }
        }
        let tail = row.len() - row.len() % PARTIAL_SUMS;
        let (mut tv, mut tw) = (0.0, 0.0);
        for j in tail..row.len() {
            tv += row[j] * ek[j];
            tw += row[j] * mk[j];
        }
        let sv: f64 = v.iter().sum::<f64>() + tv;
        let sw: f64 = w.iter().sum::<f64>() + tw;
        c[k] = (sv * inv[k], sw * inv[k].abs());
    }
}

/// The roots of the normalized p of degree ≥ 1 inside the spans (module doc).
fn cascade(p: &[f64], spans: &[(f64, f64)]) -> Vec<f64> {
    let n = p.len() - 1;
    // The cascade: the k-th derivative (scaled) at chain[starts[k]..], down to the linear one,
    // in one buffer.
    let mut chain = Vec::with_capacity((n + 1) * (n + 2) / 2);
    let mut starts = Vec::with_capacity(n);
    chain.extend_from_slice(p);
    starts.push(0);
    for k in 1..n {
        let from = starts[k - 1];
        let len = n + 2 - k;
        starts.push(chain.len());
        for j in 1..len {
            chain.push(chain[from + j] * j as f64 / (len - 1) as f64);
        }
    }
    let mut scratch = Scratch::default();
    let mut roots: Vec<f64> = Vec::new();
    let mut found: Vec<f64> = Vec::new();
    let mut next: Vec<f64> = Vec::new();
    let mut ends: Vec<f64> = Vec::with_capacity(n + 2);
    for (level, &start) in starts.iter().enumerate().rev() {
        let q = &chain[start..start + n + 1 - level];
        // a derivative's roots only bound the next level's brackets
        let done = if level == 0 {
            NEWTON_DONE
        } else {
            BRACKET_DONE
        };
        next.clear();
        for &(lo, hi) in spans {
            ends.clear();
            ends.push(lo);
            ends.extend(roots.iter().copied().filter(|&r| r > lo && r < hi));
            ends.push(hi);
            roots_between_ends(q, &ends, done, &mut scratch, &mut found);
            next.extend_from_slice(&found);
        }
        next.dedup();
        std::mem::swap(&mut roots, &mut next);
    }
    roots
}

/// Buffers reused from level to level of the cascade.
#[derive(Default)]
struct Scratch {
    values: Vec<f64>,
    brackets: Vec<Bracket>,
    active: Vec<usize>,
}

/// The polynomial without its exact zero roots (low zero coefficients) and its exact zero
/// leading coefficients, scaled so that its largest coefficient is 1; None when identically
/// zero or not finite.
fn normalized(c: &[f64]) -> Option<Vec<f64>> {
    let first = c.iter().position(|&x| x != 0.0)?;
    let last = c.iter().rposition(|&x| x != 0.0)?;
    let big = c.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if !big.is_finite() || c.iter().any(|x| !x.is_finite()) {
        return None;
    }
    Some(c[first..=last].iter().map(|x| x / big).collect())
}

/// Lower and upper bounds of the moduli of p's roots (Fujiwara), p with nonzero constant and
/// leading coefficients.
fn root_bounds(p: &[f64]) -> (f64, f64) {
    let n = p.len() - 1;
    // in logarithms: a leading or constant coefficient near underflow leaves the ratios finite
    let ln = |x: f64| x.abs().ln();
    let (l0, ln_n) = (ln(p[0]), ln(p[n]));
    let upper = (0..n)
        .filter(|&j| p[j] != 0.0)
        .map(|j| (ln(p[j]) - ln_n) / (n - j) as f64)
        .fold(f64::NEG_INFINITY, f64::max);
    let lower_inv = (1..=n)
        .filter(|&j| p[j] != 0.0)
        .map(|j| (ln(p[j]) - l0) / j as f64)
        .fold(f64::NEG_INFINITY, f64::max);
    // a hair outside the bounds so that a root on a bound still has its sign change inside
    let lo = (0.5 * 0.999) * (-lower_inv).exp();
    let hi = (2.0 * 1.001) * upper.exp();
    (
        lo.clamp(f64::MIN_POSITIVE, 1e300),
        hi.clamp(f64::MIN_POSITIVE, 1e300),
    )
}

/// Brackets iterated side by side: independent recurrences in registers, which the processor
/// overlaps.
const LANES: usize = 4;

/// The value of p at x > 0 with its sign: by Horner's rule up to 1, beyond as the reversed
/// polynomial at 1/x (p(x) = x^n·p_rev(1/x), the same sign).
fn sign_value(p: &[f64], x: f64) -> f64 {
    if x <= 1.0 {
        p.iter().rev().fold(0.0, |v, &c| v * x + c)
    } else {
        let y = 1.0 / x;
        p.iter().fold(0.0, |v, &c| v * y + c)
    }
}

/// (q, q′, q″/2) at [`LANES`] points at once by Horner's rule, the coefficients of q given
/// from the highest power down.
#[inline]
fn horner_lanes<'a>(coeffs: impl Iterator<Item = &'a f64>, x: &[f64; LANES]) -> [[f64; LANES]; 3] {
    let (mut v, mut d, mut s) = ([0.0; LANES], [0.0; LANES], [0.0; LANES]);
    for &c in coeffs {
        for l in 0..LANES {
            s[l] = s[l] * x[l] + d[l];
            d[l] = d[l] * x[l] + v[l];
            v[l] = v[l] * x[l] + c;
        }
    }
    [v, d, s]
}

/// A root's bracket during the safeguarded iteration, in x (below 1) or in y = 1/x (above).
#[derive(Debug, Clone, Copy)]
struct Bracket {
    lo: f64,
    hi: f64,
    /// The polynomial is positive at lo (negative at hi).
    lo_positive: bool,
    /// The current iterate.
    x: f64,
    /// Relative step below which the root is taken.
    done_rel: f64,
    /// The previous step's length (rtsafe's halving rule).
    last_step: f64,
    done: bool,
    /// The bracket lies in y = 1/x, on the reversed polynomial.
    reversed: bool,
}

impl Bracket {
    /// The bracket [lo, hi] with values flo, fhi of opposite signs, started at the secant
    /// point where it is narrow and at its geometric middle where it spans decades.
    fn new((lo, flo): (f64, f64), (hi, fhi): (f64, f64), done_rel: f64, reversed: bool) -> Self {
        let x = if wide(lo, hi) {
            middle(lo, hi)
        } else {
            lo + (hi - lo) * (flo / (flo - fhi))
        };
        Self {
            lo,
            hi,
            lo_positive: flo > 0.0,
            x,
            done_rel,
            last_step: hi - lo,
            done: false,
            reversed,
        }
    }

    /// The root in x.
    fn root(&self) -> f64 {
        let r = self.x.clamp(self.lo, self.hi);
        if self.reversed { 1.0 / r } else { r }
    }

    /// One safeguarded step from q(x) = v, q′(x) = d, q″(x) = 2s for q of degree n:
    /// Laguerre's step while it stays inside and at least halves the step, else bisection.
    fn step(&mut self, [v, d, s]: [f64; 3], n: f64) {
        let x = self.x;
        if v == 0.0 {
            self.done = true;
            return;
        }
        if (v > 0.0) == self.lo_positive {
            self.lo = x;
        } else {
            self.hi = x;
        }
        if self.hi - self.lo <= 4.0 * f64::EPSILON * x.abs() {
            self.done = true;
            return;
        }
        let step = laguerre_step(v, d, s, n);
        let next = x - step;
        let (lo, hi) = (self.lo, self.hi);
        // cubic (at worst quadratic) convergence: the error after a step of 1e-9 is below
        // rounding
        if step.abs() <= self.done_rel * x.abs() {
            self.done = true;
            self.x = next.clamp(lo, hi);
            return;
        }
        if next > lo && next < hi && !wide(lo, hi) && step.abs() <= 0.5 * self.last_step {
            self.x = next;
            self.last_step = step.abs();
        } else {
            self.x = middle(lo, hi);
            self.last_step = hi - lo;
        }
    }
}

/// Laguerre's step for a polynomial of degree n with value v, derivative d and half second
/// derivative s (Press et al. §9.5): n/(G ± √((n − 1)(nH − G²))), G = d/v, H = G² − 2s/v, the
/// sign that makes the denominator largest; Newton's v/d where the square root's argument is
/// negative (a complex pair nearby) or the step is not finite.
fn laguerre_step(v: f64, d: f64, s: f64, n: f64) -> f64 {
    // in units of v (one division): G·v = d, H·v² = d² − 2s·v, and the step
    // n/(G ± √·) = n·v/(d ± √((n − 1)(n·(d² − 2s·v) − d²)))
    let disc = (n - 1.0) * (n * (d * d - 2.0 * s * v) - d * d);
    // (a NaN argument fails the test too)
    if disc.is_nan() || disc < 0.0 || n < 2.0 {
        return v / d;
    }
    let root = disc.sqrt();
    // the sign of G = d/v times v's: the denominator largest in magnitude
    let den = d + root.copysign(d);
    let step = n * v / den;
    if step.is_finite() { step } else { v / d }
}

/// A bracket spans decades (bisected geometrically).
fn wide(lo: f64, hi: f64) -> bool {
    lo > 0.0 && hi > GEOMETRIC_RATIO * lo
}

/// The bisection point: geometric across decades, arithmetic otherwise.
fn middle(lo: f64, hi: f64) -> f64 {
    if wide(lo, hi) {
        (lo * hi).sqrt()
    } else {
        0.5 * (lo + hi)
    }
}

/// The roots of p between consecutive `ends` (increasing, p monotone between them) into
/// `roots`, increasing: one where the sign changes, refined by safeguarded Laguerre steps
/// taken for every bracket at once (module doc), in x below 1 and in y = 1/x above.
fn roots_between_ends(
    p: &[f64],
    ends: &[f64],
    done_rel: f64,
    scratch: &mut Scratch,
    roots: &mut Vec<f64>,
) {
    let Scratch {
        values,
        brackets,
        active,
    } = scratch;
    values.clear();
    values.extend(ends.iter().map(|&x| sign_value(p, x)));
    roots.clear();
    brackets.clear();
    for (e, v) in ends.windows(2).zip(values.windows(2)) {
        let (flo, fhi) = (v[0], v[1]);
        if flo == 0.0 {
            roots.push(e[0]);
        } else if fhi != 0.0 && (flo > 0.0) != (fhi > 0.0) {
            match bracket_in_space(p, (e[0], flo), (e[1], fhi), done_rel) {
                Ok(b) => brackets.push(b),
                Err(one) => roots.push(one),
            }
        }
    }
    if values.last() == Some(&0.0) {
        roots.extend(ends.last());
    }
    iterate(p, brackets, active);
    roots.extend(brackets.iter().map(Bracket::root));
    roots.sort_by(f64::total_cmp);
}

/// The bracket of a sign change of p on [lo, hi] in x where it lies below 1, in y = 1/x where
/// above (q(y) = y^n·p(1/y) has the sign of p); one straddling 1 keeps the side of 1 where the
/// sign changes. Err(1) when p(1) = 0.
fn bracket_in_space(
    p: &[f64],
    (lo, flo): (f64, f64),
    (hi, fhi): (f64, f64),
    done_rel: f64,
) -> Result<Bracket, f64> {
    let reversed = |(lo, flo): (f64, f64), (hi, fhi): (f64, f64)| {
        Bracket::new((1.0 / hi, fhi), (1.0 / lo, flo), done_rel, true)
    };
    if hi <= 1.0 {
        return Ok(Bracket::new((lo, flo), (hi, fhi), done_rel, false));
    }
    if lo >= 1.0 {
        return Ok(reversed((lo, flo), (hi, fhi)));
    }
    let f1: f64 = p.iter().sum();
    if f1 == 0.0 {
        Err(1.0)
    } else if (f1 > 0.0) != (flo > 0.0) {
        Ok(Bracket::new((lo, flo), (1.0, f1), done_rel, false))
    } else {
        Ok(reversed((1.0, f1), (hi, fhi)))
    }
}

/// Safeguarded steps for every bracket until each is done, the brackets in x and in y = 1/x
/// each evaluated [`LANES`] at a time.
fn iterate(p: &[f64], brackets: &mut [Bracket], active: &mut Vec<usize>) {
    let n = (p.len() - 1) as f64;
    for reversed in [false, true] {
        active.clear();
        active.extend((0..brackets.len()).filter(|&i| brackets[i].reversed == reversed));
        for _ in 0..MAX_STEPS {
            if active.is_empty() {
                break;
            }
            for block in active.chunks(LANES) {
                let mut x = [0.0; LANES];
                for (l, &i) in block.iter().enumerate() {
                    x[l] = brackets[i].x;
                }
                let [v, d, s] = if reversed {
                    horner_lanes(p.iter(), &x)
                } else {
                    horner_lanes(p.iter().rev(), &x)
                };
                for (l, &i) in block.iter().enumerate() {
                    brackets[i].step([v[l], d[l], s[l]], n);
                }
            }
            active.retain(|&i| !brackets[i].done);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_every_positive_root_to_full_precision() {
        let rs = [1e-12, 3e-5, 0.5, 0.75, 2.0, 7e3];
        let mut p = crate::poly::from_real_roots(&rs);
        // a complex pair and a negative root that must not be reported
        p = crate::poly::mul(&p, &[2.0, 1.0, 1.0]);
        p = crate::poly::mul(&p, &[3.0, 1.0]);
        let got = positive_roots(&p);
        assert_eq!(got.len(), rs.len(), "{got:?}");
        for (g, r) in got.iter().zip(rs) {
            assert!((g - r).abs() <= 1e-12 * r, "{g} vs {r}");
        }
    }

    #[test]
    fn close_pairs_and_wide_scales() {
        // Wilkinson-like cluster: roots 1, 1 + 1e-6 and widely scaled ones
        let rs = [1e-15, 1.0, 1.000001, 1e15];
        let got = positive_roots(&crate::poly::from_real_roots(&rs));
        assert_eq!(got.len(), 4, "{got:?}");
        for (g, r) in got.iter().zip(rs) {
            assert!((g - r).abs() <= 1e-9 * r, "{g} vs {r}");
        }
    }

    #[test]
    fn a_cluster_of_roots_and_roots_on_both_sides_of_one() {
        // six roots 5 % apart (where Newton's step crawls across the cluster), their mirror
        // images above 1 (the reversed polynomial's side) and a pair straddling x = 1
        let mut rs: Vec<f64> = (0..6).map(|j| 0.5 * (1.0 + 0.05 * j as f64)).collect();
        rs.extend((0..6).map(|j| 2.0 * (1.0 + 0.05 * j as f64)));
        rs.extend([0.99, 1.01]);
        rs.sort_by(f64::total_cmp);
        let got = positive_roots(&crate::poly::from_real_roots(&rs));
        assert_eq!(got.len(), rs.len(), "{got:?}");
        for (g, r) in got.iter().zip(&rs) {
            // the cluster is ill-conditioned: rounding the coefficients alone moves its roots
            // by up to 2.8e-6 relative (numpy.roots on the same coefficients)
            assert!((g - r).abs() <= 1e-5 * r, "{g} vs {r}");
        }
    }

    #[test]
    fn no_positive_roots() {
        assert!(positive_roots(&[1.0, 2.0, 1.0]).is_empty()); // (x + 1)²
        assert!(positive_roots(&[0.0, 0.0, 1.0]).is_empty()); // x²
        assert!(positive_roots(&[0.0; 4]).is_empty());
        assert!(positive_roots(&[5.0]).is_empty());
        assert_eq!(positive_roots(&[-2.0, 1.0]), vec![2.0]);
    }
}
#[cfg(test)]
mod window_tests {
    use super::*;

    #[test]
    fn roots_within_windows_are_the_roots_there() {
        // roots 0.1 … 9.1 and a complex pair near 3
        let mut p = vec![1.0];
        for j in 0..10 {
            p = crate::poly::mul(&p, &[-(0.1 + j as f64), 1.0]);
        }
        p = crate::poly::mul(&p, &[9.01, -6.0, 1.0]);
        let all = positive_roots(&p);
        assert_eq!(all.len(), 10, "{all:?}");
        let windows = [(0.0, 0.5), (1.5, 4.5), (8.5, f64::INFINITY)];
        let got = positive_roots_within(&p, &windows);
        let want: Vec<f64> = all
            .iter()
            .copied()
            .filter(|r| windows.iter().any(|&(l, h)| *r > l && *r < h))
            .collect();
        assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
        // ten roots a unit apart and a complex pair 0.1 from one of them are ill-conditioned:
        // p's rounding near 3.1 is flat over about 1e-9 of it, and the two brackets'
        // iterations stop anywhere in that band
        for (g, w) in got.iter().zip(&want) {
            assert!((g - w).abs() <= 1e-8 * w, "{g} vs {w}");
        }
    }

    #[test]
    fn shift_matches_synthetic_division() {
        let c = [3.0, -2.0, 0.5, 7.0, -1.25, 2.0];
        for s in [1.0, 0.3, 2.5] {
            let want = crate::poly::taylor_shift(&c, s);
            let mut got: Vec<(f64, f64)> = c.iter().map(|&a| (a, a.abs())).collect();
            shift(&mut got, s);
            for (g, w) in got.iter().zip(&want) {
                assert!((g.0 - w).abs() <= 1e-12 * w.abs().max(1.0), "{g:?} {w}");
            }
        }
    }
}
