//! The open loop as a function of the fraction λ ∈ [0, 1) of a sample of delay, from one
//! set of polynomials (the modified z-transform's dependence on λ: the paper's exact ZOH model,
//! Section III eq. 2–6, with the fractional delay of [`crate::zoh`]; L as in eq. 7–9).
//!
//! The hold splits the input as Γ0(λ) = Ψ(1 − λ)B and Γ1 = Γ − Γ0 with Γ = Ψ(1)B, so the
//! plant's numerator at a fractional delay is
//!
//! ```text
//! N_λ(z) = C adj(zI − Φ)(z·Γ0 + Γ1) = C adj(zI − Φ)Γ + (z − 1)·C adj(zI − Φ)Γ0(λ),
//! ```
//!
//! affine in the n-vector g(λ) = Γ0(λ). So is W_λ = a·PK + b·PB, while P0 = z·D·Vd does not
//! depend on λ. With W_∅ the part at Γ0 = 0 and W_j the part at Γ0 = e_j (the same P0),
//!
//! ```text
//! L_λ(θ) = [W_∅(θ) + Σ_j g_j(λ)·ΔW_j(θ)] / P0(θ),    ΔW_j = W_j − W_∅,
//! ```
//!
//! which is exact at every λ: L_λ is the loop delayed by λ samples (g(0) = Γ gives it without
//! delay, g → 0 as λ → 1 one sample later: |L_0| = |L_1|). One evaluation of the n + 2
//! parts at θ then gives L at every fraction for n multiplications each.
//!
//! **A bound over every fraction.** Splitting g(λ) = (1 − λ)Γ + e(λ), the first part is
//! affine in λ, so its |·| is largest at an end (where it is |L_0|·|P0|), and e(0) = e(1) = 0
//! with e'' = g'' = A·e^{A(1−λ)}B, so |e_j| ≤ δ_j: the largest |e_j| on the fraction grid
//! plus h²/8·max |g''_j| for the grid's step h. Hence
//! max_λ |L_λ(θ)| ≤ [max(|W_∅|, |W_∅ + Σ Γ_j ΔW_j|) + Σ_j δ_j·|ΔW_j|]/|P0|.

use num_complex::Complex64;
use rayon::prelude::*;

use super::frequency::{UNIFORM_PER_DEGREE, root_grid, trimmed};
use crate::closed_loop::{AffineFamily, SHIFTED_THETA, ShiftedParts};
use crate::error::Result;
use crate::extremum::{golden_max, merge_grid, refine_max, sample_maxima};
use crate::model::{Delay, Loop};
use crate::poly::{self, Mat, modulus};
use crate::zoh::{DiscreteLoop, StateSpace, WallScale, exp_and_integral};

/// Angles per block of [`FractionTable::new`]'s evaluation, one parallel task each.
const TABLE_BLOCK: usize = 64;

/// Fractions j/FRACTIONS of a sample (j = 0 … FRACTIONS − 1) on which the crossovers of every
/// fraction's loop are tabulated, and on which the bound's δ_j is sampled.
pub const FRACTIONS: usize = 64;

/// The hold input between tabulated fractions is advanced by a Taylor series where ‖A‖δ is at
/// most this (20 terms then reach 1e-19 relative); beyond, by the matrix exponential.
const HOLD_SERIES_NORM: f64 = 0.5;

/// Ψ(δ)x = δ·Σ_k (Aδ)^k x/(k + 1)! for ‖A‖δ ≤ [`HOLD_SERIES_NORM`], summed until a term falls
/// below an ulp of the sum.
fn psi_times(a: &Mat, delta: f64, x: &[f64]) -> Vec<f64> {
    let mut term = x.to_vec();
    let mut sum = x.to_vec();
    for k in 1..40 {
        let f = delta / (k + 1) as f64;
        term = poly::mat_vec(a, &term).iter().map(|t| t * f).collect();
        let l1 = |v: &[f64]| v.iter().map(|x| x.abs()).sum::<f64>();
        let (tn, sn) = (l1(&term), l1(&sum));
        for (s, t) in sum.iter_mut().zip(&term) {
            *s += t;
        }
        if tn <= 1e-17 * sn {
            break;
        }
    }
    sum.iter().map(|s| s * delta).collect()
}

/// Local maxima of ln|L_λ| within this of 0 that stay below it are refined: a pair of
/// crossovers the grid straddled (the grid samples every mode's peak within a tenth of its
/// width, so a farther one cannot reach 1).
const REFINE_LOG: f64 = std::f64::consts::LN_2;

/// Refinement of a maximum stops at this relative width in θ (a seed needs no more).
const SEED_THETA_REL: f64 = 1e-9;

/// The loop of one wall at every fraction of a sample (module doc), on the frequency grid of
/// the loop without a fraction and of the loop at half a sample.
pub struct FractionLoop {
    /// State matrix A of the continuous plant (normalized time).
    a_mat: Mat,
    /// Input vector B.
    b_vec: Vec<f64>,
    /// Γ = Ψ(1)B = g(0).
    gamma: Vec<f64>,
    /// P0's core and the wall parts W_∅, ΔW_1 … ΔW_n, ascending in z.
    in_z: Polys,
    /// The same in w = z − 1, for angles below [`SHIFTED_THETA`] (None for a velocity filter
    /// without a shifted form).
    in_w: Option<Polys>,
    /// Wall units of the loop.
    scale: WallScale,
    /// ‖A‖₁.
    a_norm: f64,
    /// The hold inputs at the fractions j/[`FRACTIONS`], j = 0 … FRACTIONS.
    holds: HoldTable,
    /// The frequency grid of the table.
    pub grid: Vec<f64>,
}

/// The n + 2 parts of [`FractionLoop`] at one θ: [P0, W_∅, ΔW_1 … ΔW_n] (e^{iθ} put in).
#[derive(Debug, Clone, Copy)]
pub struct FractionParts<'a>(&'a [Complex64]);

impl<'a> FractionParts<'a> {
    /// P0(e^{iθ}).
    pub fn p0(&self) -> Complex64 {
        self.0[0]
    }

    /// W_∅(e^{iθ}).
    pub fn base(&self) -> Complex64 {
        self.0[1]
    }

    /// ΔW_j(e^{iθ}), j = 1 … n.
    pub fn deltas(&self) -> &'a [Complex64] {
        &self.0[2..]
    }

    /// L_λ = (W_∅ + Σ g_j ΔW_j)/P0 for the hold input g = g(λ).
    pub fn loop_at(&self, g: &[f64]) -> Complex64 {
        let w = self
            .deltas()
            .iter()
            .zip(g)
            .fold(self.base(), |acc, (d, &gj)| acc + d * gj);
        w / self.p0()
    }

    /// Σ g'_j ΔW_j / P0: the λ-derivative of L_λ for g' = dg/dλ.
    pub fn slope_at(&self, dg: &[f64]) -> Complex64 {
        let w = self
            .deltas()
            .iter()
            .zip(dg)
            .fold(Complex64::new(0.0, 0.0), |acc, (d, &gj)| acc + d * gj);
        w / self.p0()
    }
}

/// The parts at one angle, owned ([`FractionLoop::parts`]).
#[derive(Debug, Clone)]
pub struct PartsAt(Vec<Complex64>);

impl PartsAt {
    /// The parts as [`FractionParts`].
    pub fn view(&self) -> FractionParts<'_> {
        FractionParts(&self.0)
    }
}

/// The hold input at one fraction: g(λ) = Ψ(1 − λ)B, its λ-derivative −e^{A(1−λ)}B and its
/// second derivative A·e^{A(1−λ)}B.
#[derive(Debug, Clone)]
pub struct HoldInput {
    /// g(λ).
    pub g: Vec<f64>,
    /// dg/dλ.
    pub dg: Vec<f64>,
    /// d²g/dλ².
    pub ddg: Vec<f64>,
}

/// The hold inputs at the fractions j/[`FRACTIONS`], j = 0 … FRACTIONS, in one buffer: g,
/// dg/dλ and d²g/dλ² of each fraction side by side.
#[derive(Debug, Clone, Default)]
pub struct HoldTable {
    n: usize,
    data: Vec<f64>,
}

/// One row of a [`HoldTable`]: g(λ), dg/dλ and d²g/dλ² at one fraction.
#[derive(Debug, Clone, Copy)]
pub struct HoldRow<'a> {
    /// g(λ).
    pub g: &'a [f64],
    /// dg/dλ.
    pub dg: &'a [f64],
    /// d²g/dλ².
    pub ddg: &'a [f64],
}

impl HoldTable {
    /// The row at fraction j/[`FRACTIONS`] (None past the table).
    pub fn get(&self, j: usize) -> Option<HoldRow<'_>> {
        let n = self.n;
        let row = self.data.get(3 * n * j..3 * n * (j + 1))?;
        Some(HoldRow {
            g: &row[..n],
            dg: &row[n..2 * n],
            ddg: &row[2 * n..],
        })
    }

    /// The rows from λ = 0 up.
    pub fn rows(&self) -> impl Iterator<Item = HoldRow<'_>> {
        (0..self.len()).filter_map(|j| self.get(j))
    }

    /// The number of rows.
    pub fn len(&self) -> usize {
        self.data.len().checked_div(3 * self.n).unwrap_or(0)
    }

    /// True when the table has no rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// P0's core and the wall parts of a [`FractionLoop`] in one variable (P0 = z·core: the hold
/// splits into one more sample, k = 1).
struct Polys {
    p0_core: Vec<f64>,
    /// W_∅, then ΔW_1 … ΔW_n.
    walls: Vec<Vec<f64>>,
    /// The longest of the polynomials.
    len: usize,
}

impl Polys {
    /// P0's core, W_∅ and the ΔW_j.
    fn new(p0_core: Vec<f64>, walls: Vec<Vec<f64>>) -> Self {
        let len = walls.iter().map(Vec::len).fold(p0_core.len(), usize::max);
        Self {
            p0_core,
            walls,
            len,
        }
    }

    /// W_∅ + Σ g_j ΔW_j: the wall part at the hold input g.
    fn wall_at(&self, g: &[f64]) -> Vec<f64> {
        let mut w = vec![0.0; self.len];
        for (c, s) in self.walls.iter().zip(std::iter::once(&1.0).chain(g)) {
            for (wi, ci) in w.iter_mut().zip(c) {
                *wi += s * ci;
            }
        }
        w
    }

    /// The parts at x (z or w) into `out` ([P0, W_∅, ΔW…], P0 = z·core(x)), from the powers
    /// of x (`powers`, scratch): every polynomial is then one dot product, side by side.
    fn at_into(
        &self,
        x: Complex64,
        z: Complex64,
        powers: &mut Vec<Complex64>,
        out: &mut [Complex64],
    ) {
        powers.clear();
        let mut p = Complex64::new(1.0, 0.0);
        for _ in 0..self.len {
            powers.push(p);
            p *= x;
        }
        let dot = |c: &[f64]| {
            let (re, im) = c
                .iter()
                .zip(powers.iter())
                .fold((0.0, 0.0), |(re, im), (ci, pi)| {
                    (re + ci * pi.re, im + ci * pi.im)
                });
            Complex64::new(re, im)
        };
        out[0] = z * dot(&self.p0_core);
        for (o, c) in out[1..].iter_mut().zip(&self.walls) {
            *o = dot(c);
        }
    }
}

/// The step of [`super::frequency::frequency_grid`]'s uniform grid for these polynomials.
fn uniform_step(polys: &Polys) -> f64 {
    std::f64::consts::PI / (UNIFORM_PER_DEGREE * (polys.len + 1)) as f64
}

/// C adj(wI − E)e_j for every j (ascending in w): with det(wI − E) = Σ c_k w^k and
/// adj(wI − E) = Σ_{k<n} B_k w^k, (wI − E)·adj = det·I gives B_{n−1} = I and
/// B_{k−1} = E·B_k + c_k·I, so the rows r_k = C·B_k follow from r_{n−1} = C,
/// r_{k−1} = r_k·E + c_k·C (n³ in all), and N_{e_j} has the coefficients r_k[j].
fn unit_numerators(e: &Mat, c: &[f64], den_w: &[f64]) -> Vec<Vec<f64>> {
    let n = c.len();
    let mut rows = vec![Vec::new(); n];
    let mut r = c.to_vec();
    for k in (0..n).rev() {
        if k + 1 < n {
            r = (0..n)
                .map(|j| (0..n).map(|i| r[i] * e[i][j]).sum::<f64>() + den_w[k + 1] * c[j])
                .collect();
        }
        rows[k] = r.clone();
    }
    (0..n)
        .map(|j| rows.iter().map(|r| r[j]).collect())
        .collect()
}

/// The wall part a·Vd + b·Vn of the velocity estimator (ascending).
fn wall_filter(vd: &[f64], vn: &[f64], (a, b): (f64, f64)) -> Vec<f64> {
    poly::add_scaled(&poly::add_scaled(&[], a, vd), b, vn)
}

impl FractionLoop {
    /// The fraction loop of a wall (a, b) in wall units on a loop and its discretization `dl`
    /// (its whole-sample delay is not part of it: the caller turns the phase by e^{−iwθ} for
    /// w whole samples); `modes`
    /// is the [`super::frequency::frequency_grid`] of the loop as it is, joined here by the
    /// runs around the roots of the wall part at half a sample.
    ///
    /// W_∅ and P0 come from the family at g = 0 (exact at z = 1, [`AffineFamily::new`]); the
    /// ΔW_j = (z − 1)·C adj(zI − Φ)e_j·(a·Vd + b·Vn) from one numerator each (module doc).
    pub fn new(lp: &Loop, dl: &DiscreteLoop, a: f64, b: f64, modes: &[f64]) -> Result<Self> {
        Ok(Self::unjoined(lp, dl, a, b)?.joined(modes))
    }

    /// [`FractionLoop::new`] with the grid of the wall part at half a sample alone, built
    /// while the loop's own grid is still being found; [`FractionLoop::joined`] adds that.
    pub fn unjoined(lp: &Loop, dl: &DiscreteLoop, a: f64, b: f64) -> Result<Self> {
        let ss = StateSpace::of_plant(&lp.plant, lp.period)?;
        // Γ = Γ0 + Γ1 = Ψ(1)B at any fraction of the loop's own delay
        let gamma: Vec<f64> = dl
            .gamma0
            .iter()
            .zip(&dl.gamma1)
            .map(|(x, y)| x + y)
            .collect();
        let n = gamma.len();
        // the loop split at a fraction (k = 1), with the whole input in the later sample
        let base_loop = DiscreteLoop {
            gamma0: vec![0.0; n],
            gamma1: gamma.clone(),
            delay: Delay {
                samples: 0,
                fraction: 0.5,
            },
            ..dl.clone()
        };
        let base = AffineFamily::new(&base_loop);
        let den_w = base_loop.denominator_shifted();
        let units = unit_numerators(&base_loop.phi_minus_identity, &base_loop.c, &den_w);
        let (vn, vd) = (&base_loop.velocity_num, &base_loop.velocity_den);
        let in_z = {
            let filter = poly::mul(&[-1.0, 1.0], &wall_filter(vd, vn, (a, b)));
            let mut walls = vec![poly::add_scaled(
                &poly::add_scaled(&[], a, &base.pk),
                b,
                &base.pb,
            )];
            walls.extend(
                units
                    .iter()
                    .map(|u| poly::mul(&poly::taylor_shift(u, -1.0), &filter)),
            );
            Polys::new(base.p0_core.clone(), walls)
        };
        let in_w = base.shifted.as_ref().map(|sh| {
            let (vd_w, vn_w) = (poly::taylor_shift(vd, 1.0), poly::taylor_shift(vn, 1.0));
            let filter = poly::shift_up(&wall_filter(&vd_w, &vn_w, (a, b)), 1);
            let mut walls = vec![poly::add_scaled(
                &poly::add_scaled(&[], a, &sh.pk),
                b,
                &sh.pb,
            )];
            walls.extend(units.iter().map(|u| poly::mul(u, &filter)));
            Polys::new(sh.p0_core.clone(), walls)
        });
        let mut fl = Self {
            a_mat: ss.a,
            b_vec: ss.b,
            gamma,
            in_z,
            in_w,
            scale: base.scale,
            a_norm: 0.0,
            holds: HoldTable::default(),
            grid: Vec::new(),
        };
        fl.a_norm = poly::norm1(&fl.a_mat);
        fl.holds = fl.hold_table();
        // the wall part at half a sample, in w where there is a shifted form (modes's rule)
        let g_half = fl.hold(0.5).g;
        let (half, shift) = match &fl.in_w {
            Some(w) => (w.wall_at(&g_half), 1.0),
            None => (fl.in_z.wall_at(&g_half), 0.0),
        };
        fl.grid = root_grid(&[trimmed(&half)], shift, uniform_step(&fl.in_z));
        Ok(fl)
    }

    /// The loop with the loop's own [`super::frequency::frequency_grid`] `modes` joined to
    /// its grid.
    pub fn joined(mut self, modes: &[f64]) -> Self {
        self.grid.extend_from_slice(modes);
        merge_grid(&mut self.grid);
        self
    }

    /// The number of parts at one angle, n + 2.
    fn width(&self) -> usize {
        self.gamma.len() + 2
    }

    /// The parts at θ into `out` (length n + 2; module doc): in w = e^{iθ} − 1 =
    /// −2 sin²(θ/2) + i sin θ below [`SHIFTED_THETA`] (no cancellation near z = 1, as
    /// [`AffineFamily::parts_on_circle`]), in z above.
    fn parts_into(&self, theta: f64, powers: &mut Vec<Complex64>, out: &mut [Complex64]) {
        match &self.in_w {
            Some(w_polys) if theta.abs() < SHIFTED_THETA => {
                // sin θ = 2 sin(θ/2) cos(θ/2): one sine and cosine for w and z = 1 + w
                let (h, c) = crate::circle::sin_cos(0.5 * theta);
                let w = Complex64::new(-2.0 * h * h, 2.0 * h * c);
                w_polys.at_into(w, w + 1.0, powers, out)
            }
            _ => {
                let z = crate::circle::unit(theta);
                self.in_z.at_into(z, z, powers, out)
            }
        }
    }

    /// The parts at θ (module doc).
    pub fn parts(&self, theta: f64) -> PartsAt {
        let mut out = vec![Complex64::new(0.0, 0.0); self.width()];
        self.parts_into(theta, &mut Vec::new(), &mut out);
        PartsAt(out)
    }

    /// The family of the loop at w whole samples and the fraction whose hold input is g, with
    /// the wall folded in: p = z^w·P0 + W_λ = P0' + 1·PK' (PB' = 0, wall (1, 0)): the
    /// characteristic polynomial at that delay for the verdict, from the same parts.
    pub fn family_at(&self, whole: usize, g: &[f64]) -> AffineFamily {
        let at_zero = |c: &[f64], i: usize| c.get(i).copied().unwrap_or(0.0);
        let shifted = self.in_w.as_ref().map(|w| ShiftedParts {
            p0_core: w.p0_core.clone(),
            pk: w.wall_at(g),
            pb: vec![0.0],
        });
        let k = whole + 1;
        let (at_one, slope_at_one) = match &shifted {
            Some(sh) => (
                [at_zero(&sh.p0_core, 0), at_zero(&sh.pk, 0), 0.0],
                [
                    k as f64 * at_zero(&sh.p0_core, 0) + at_zero(&sh.p0_core, 1),
                    at_zero(&sh.pk, 1),
                    0.0,
                ],
            ),
            None => ([f64::NAN; 3], [f64::NAN; 3]),
        };
        AffineFamily {
            p0_core: self.in_z.p0_core.clone(),
            k,
            pk: self.in_z.wall_at(g),
            pb: vec![0.0],
            at_one,
            slope_at_one,
            plus_one: None,
            scale: self.scale,
            shifted,
        }
    }

    /// The hold input at the fraction λ ∈ [0, 1] (module doc): from the tabulated fraction
    /// m/[`FRACTIONS`] just above λ (τ_m = 1 − m/FRACTIONS just below τ = 1 − λ, δ = τ − τ_m)
    /// by g(τ) = g(τ_m) + Ψ(δ)u_m and u(τ) = u_m + A·Ψ(δ)u_m with u = e^{Aτ}B, Ψ(δ)u_m by
    /// its Taylor series where ‖A‖δ ≤ [`HOLD_SERIES_NORM`]; else directly.
    pub fn hold(&self, lambda: f64) -> HoldInput {
        let m = ((lambda * FRACTIONS as f64).ceil().max(0.0) as usize).min(FRACTIONS);
        let delta = m as f64 / FRACTIONS as f64 - lambda;
        match self.holds.get(m) {
            Some(at) if delta >= 0.0 && self.a_norm * delta <= HOLD_SERIES_NORM => {
                let u0: Vec<f64> = at.dg.iter().map(|x| -x).collect();
                let v = psi_times(&self.a_mat, delta, &u0);
                let u: Vec<f64> = u0
                    .iter()
                    .zip(poly::mat_vec(&self.a_mat, &v))
                    .map(|(x, y)| x + y)
                    .collect();
                self.hold_input(at.g.iter().zip(&v).map(|(x, y)| x + y).collect(), &u)
            }
            _ => self.hold_direct(lambda),
        }
    }

    /// The hold input at λ from the matrix exponential at τ = 1 − λ.
    fn hold_direct(&self, lambda: f64) -> HoldInput {
        let (e, psi) = exp_and_integral(&self.a_mat, 1.0 - lambda);
        let g = poly::mat_vec(&psi, &self.b_vec);
        let u: Vec<f64> = poly::mat_vec(&e, &self.b_vec)
            .iter()
            .zip(&self.b_vec)
            .map(|(x, y)| x + y)
            .collect();
        self.hold_input(g, &u)
    }

    /// The hold input from g and u = e^{Aτ}B: dg = −u, ddg = A·u.
    fn hold_input(&self, g: Vec<f64>, u: &[f64]) -> HoldInput {
        HoldInput {
            g,
            ddg: poly::mat_vec(&self.a_mat, u),
            dg: u.iter().map(|x| -x).collect(),
        }
    }

    /// The hold inputs at the fractions j/[`FRACTIONS`], j = 0 … FRACTIONS (the last, λ = 1,
    /// only for the bound), tabulated when the loop was built.
    pub fn holds(&self) -> &HoldTable {
        &self.holds
    }

    /// The table of [`FractionLoop::holds`] by the exact one-step recursion in τ = 1 − λ
    /// with step h = 1/FRACTIONS: g(τ + h) = Ψ(h)B + e^{Ah}g(τ), e^{A(τ+h)}B = e^{Ah}e^{Aτ}B.
    fn hold_table(&self) -> HoldTable {
        let (e, psi) = exp_and_integral(&self.a_mat, 1.0 / FRACTIONS as f64);
        let step = poly::mat_vec(&psi, &self.b_vec);
        let n = self.b_vec.len();
        // x ← x + E(h)·x (+ step for g), into the second buffer (e is e^{Ah} − I)
        let advance = |x: &[f64], extra: &[f64], next: &mut [f64]| {
            for i in 0..n {
                let ex: f64 = e[i].iter().zip(x).map(|(a, b)| a * b).sum();
                next[i] = x[i] + ex + extra.get(i).copied().unwrap_or(0.0);
            }
        };
        let (mut g, mut u) = (vec![0.0; n], self.b_vec.clone());
        let (mut g_next, mut u_next) = (vec![0.0; n], vec![0.0; n]);
        // rows from τ = 0 (λ = 1) up, reversed below
        let mut rows = vec![0.0; 3 * n * (FRACTIONS + 1)];
        for (m, row) in rows.chunks_exact_mut(3 * n).enumerate() {
            let (rg, rest) = row.split_at_mut(n);
            let (rdg, rddg) = rest.split_at_mut(n);
            rg.copy_from_slice(&g);
            for i in 0..n {
                rdg[i] = -u[i];
                rddg[i] = self.a_mat[i].iter().zip(&u).map(|(a, b)| a * b).sum();
            }
            if m < FRACTIONS {
                advance(&g, &step, &mut g_next);
                advance(&u, &[], &mut u_next);
                std::mem::swap(&mut g, &mut g_next);
                std::mem::swap(&mut u, &mut u_next);
            }
        }
        let data = rows.chunks_exact(3 * n).rev().flatten().copied().collect();
        HoldTable { n, data }
    }

    /// δ_j of the module doc: a bound of |g_j(λ) − (1 − λ)Γ_j| over λ ∈ [0, 1].
    pub fn deviation_bound(&self, holds: &HoldTable) -> Vec<f64> {
        let h = 1.0 / FRACTIONS as f64;
        (0..self.gamma.len())
            .map(|j| {
                let (mut dev, mut curv) = (0.0_f64, 0.0_f64);
                for (i, hi) in holds.rows().enumerate() {
                    let lambda = i as f64 * h;
                    dev = dev.max((hi.g[j] - (1.0 - lambda) * self.gamma[j]).abs());
                    curv = curv.max(hi.ddg[j].abs());
                }
                dev + h * h / 8.0 * curv
            })
            .collect()
    }

    /// Bounds (below, above) of |L_λ(θ)| over every fraction from its parts (module doc): the
    /// affine part's distance to 0 (the nearest point of its segment) and its largest end,
    /// each moved by the deviation's spread.
    pub fn gain_bounds(&self, parts: FractionParts, delta: &[f64]) -> (f64, f64) {
        let full = parts
            .deltas()
            .iter()
            .zip(&self.gamma)
            .fold(parts.base(), |acc, (d, &gj)| acc + d * gj);
        let spread: f64 = parts
            .deltas()
            .iter()
            .zip(delta)
            .map(|(d, dj)| modulus(*d) * dj)
            .sum();
        let m = modulus(parts.p0());
        let (x, y) = (parts.base(), full);
        let dir = y - x;
        let t = if dir.norm_sqr() > 0.0 {
            (-(x.conj() * dir).re / dir.norm_sqr()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let nearest = modulus(x + dir * t);
        (
            (nearest - spread).max(0.0) / m,
            (modulus(x).max(modulus(y)) + spread) / m,
        )
    }
}

/// The table of a [`FractionLoop`] on its grid, with the bound over every fraction.
pub struct FractionTable<'a> {
    fl: &'a FractionLoop,
    /// The parts at every grid angle, n + 2 per angle ([`FractionParts`]).
    values: Vec<Complex64>,
    /// Bounds (below, above) of |L_λ| over every fraction at every grid angle.
    pub bounds: Vec<(f64, f64)>,
    delta: Vec<f64>,
}

/// A crossover |L_λ(θ)| = 1 of one fraction's loop, with L there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FractionCrossover {
    /// The fraction λ.
    pub lambda: f64,
    /// The angle θ.
    pub theta: f64,
    /// L_λ(e^{iθ}) (|L| = 1 to the grid's interpolation).
    pub value: Complex64,
}

impl<'a> FractionTable<'a> {
    /// Tabulates the parts and the bound on the grid.
    pub fn new(fl: &'a FractionLoop) -> Self {
        let delta = fl.deviation_bound(fl.holds());
        let width = fl.width();
        let mut values = vec![Complex64::new(0.0, 0.0); width * fl.grid.len()];
        // in blocks of angles that an idle thread may take (the margins' other half)
        let mut bounds = vec![(0.0, 0.0); fl.grid.len()];
        values
            .par_chunks_mut(width * TABLE_BLOCK)
            .zip(bounds.par_chunks_mut(TABLE_BLOCK))
            .zip(fl.grid.par_chunks(TABLE_BLOCK))
            .for_each(|((values, bounds), thetas)| {
                let mut powers = Vec::new();
                for ((&t, out), bound) in thetas
                    .iter()
                    .zip(values.chunks_exact_mut(width))
                    .zip(bounds)
                {
                    fl.parts_into(t, &mut powers, out);
                    *bound = fl.gain_bounds(FractionParts(out), &delta);
                }
            });
        Self {
            fl,
            values,
            bounds,
            delta,
        }
    }

    /// The parts at the grid's i-th angle.
    fn at(&self, i: usize) -> FractionParts<'_> {
        let w = self.fl.width();
        FractionParts(&self.values[i * w..(i + 1) * w])
    }

    /// The largest bound over θ: the grid's largest, and every local maximum within a factor
    /// of two of 1, refined by golden section ([`crate::extremum`]).
    pub fn peak_bound(&self) -> f64 {
        let ts = &self.fl.grid;
        let f = |t: f64| self.fl.gain_bounds(self.fl.parts(t).view(), &self.delta).1;
        let upper: Vec<f64> = self.bounds.iter().map(|b| b.1).collect();
        let mut peak = upper.iter().copied().fold(0.0, f64::max);
        let top = (0..ts.len()).max_by(|&i, &j| upper[i].total_cmp(&upper[j]));
        for i in sample_maxima(&upper).chain(top) {
            if upper[i] > 0.5 {
                peak = peak.max(refine_max(f, ts, i, SEED_THETA_REL).1);
            }
        }
        peak
    }

    /// Every crossover of every fraction j/[`FRACTIONS`]'s loop: sign changes of ln|L_λ| on
    /// the grid, located by linear interpolation, and the maxima that reach 1 between
    /// samples. L_λ is evaluated only where the bounds leave |L_λ| − 1 of either sign at some
    /// fraction, beside a neighbour whose sign the bounds fix otherwise, and around every
    /// local maximum of the upper bound above 1/2.
    pub fn crossovers(&self) -> Vec<FractionCrossover> {
        let n = self.fl.grid.len();
        let side: Vec<i8> = self
            .bounds
            .iter()
            .map(|&(lo, hi)| {
                if lo > 1.0 {
                    1
                } else if hi < 1.0 {
                    -1
                } else {
                    0
                }
            })
            .collect();
        // a local maximum of the upper bound within a factor of two of 1 may hide a pair of
        // crossovers between its samples: it and its neighbours are evaluated too
        let upper: Vec<f64> = self.bounds.iter().map(|b| b.1).collect();
        let mut peak = vec![false; n];
        for i in sample_maxima(&upper).filter(|&i| upper[i] > 0.5) {
            peak[i - 1..=i + 1].fill(true);
        }
        let near: Vec<usize> = (0..n)
            .filter(|&i| {
                side[i] == 0
                    || peak[i]
                    || (i > 0 && side[i - 1] != side[i])
                    || (i + 1 < n && side[i + 1] != side[i])
            })
            .collect();
        let mut out = Vec::new();
        let (mut ls, mut vs) = (
            Vec::with_capacity(near.len()),
            Vec::with_capacity(near.len()),
        );
        for (j, hold) in self.fl.holds().rows().take(FRACTIONS).enumerate() {
            let lambda = j as f64 / FRACTIONS as f64;
            ls.clear();
            ls.extend(near.iter().map(|&i| self.at(i).loop_at(hold.g)));
            vs.clear();
            vs.extend(ls.iter().map(|&l| modulus(l).ln()));
            for k in 1..near.len() {
                let (i0, i1) = (near[k - 1], near[k]);
                if i1 != i0 + 1 || (vs[k - 1] > 0.0) == (vs[k] > 0.0) {
                    continue;
                }
                let t = vs[k - 1] / (vs[k - 1] - vs[k]);
                let (t0, t1) = (self.fl.grid[i0], self.fl.grid[i1]);
                out.push(FractionCrossover {
                    lambda,
                    theta: t0 + t * (t1 - t0),
                    value: ls[k - 1] + (ls[k] - ls[k - 1]) * t,
                });
            }
            out.extend(self.hidden_pairs(lambda, hold.g, &near, &vs));
        }
        out
    }

    /// Maxima of ln|L_λ| just below 0 at the samples that rise above it between them.
    fn hidden_pairs(
        &self,
        lambda: f64,
        hold_g: &[f64],
        near: &[usize],
        vs: &[f64],
    ) -> Vec<FractionCrossover> {
        let ts = &self.fl.grid;
        let g = |t: f64| modulus(self.fl.parts(t).view().loop_at(hold_g)).ln();
        sample_maxima(vs)
            .filter(|&k| vs[k] <= 0.0 && vs[k] > -REFINE_LOG)
            .filter(|&k| near[k] > 0 && near[k] + 1 < ts.len())
            .filter_map(|k| {
                let i = near[k];
                let (t, v) = golden_max(g, ts[i - 1], ts[i + 1], SEED_THETA_REL * ts[i]);
                (v > 0.0).then(|| FractionCrossover {
                    lambda,
                    theta: t,
                    value: self.fl.parts(t).view().loop_at(hold_g),
                })
            })
            .collect()
    }
}

#[cfg(test)]
#[path = "fraction_tests.rs"]
mod tests;
