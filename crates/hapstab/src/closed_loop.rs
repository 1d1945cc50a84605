//! The closed loop of Fig. 3: the characteristic polynomial p(z) (eq. 7–9), affine in the
//! wall, and the transfer function G_x(z) from force to position (eq. 7).
//!
//! With the plant H(z) = N(z)/(z^k D(z)) of [`crate::zoh`] (k = d, or d + 1 with a fractional
//! delay), the velocity estimator T·V(z) = Vn(z)/Vd(z) and the wall F = K·y + B·v, the loop
//! closes on 1 + H(z)(K + B·V(z)) = 0, i.e. in wall units (a, b) = (K/k_u, B/(k_u T)):
//!
//! ```text
//! p(z) = P0(z) + a·PK(z) + b·PB(z),
//! P0 = z^k D Vd,   PK = N Vd,   PB = N Vn,        monic of degree k + n + deg Vd.
//! ```
//!
//! For the paper's loop (backward difference Vn = z − 1, Vd = z, k = d) this is
//! p(z) = z^{d+1} D(z) + N(z)((α + β) z − β): the paper's eq. (9) divided by its leading
//! coefficient −2c1γ. The D-decomposition of [`crate::boundary`] and [`crate::region`] rests
//! on the affinity in (a, b); every analysis works on an [`AffineFamily`].

use num_complex::Complex64;
use serde::Serialize;

use crate::error::Result;
use crate::model::Loop;
use crate::poly;
use crate::zoh::{DiscreteLoop, WallScale};

/// p(z) = P0(z) + a·PK(z) + b·PB(z) with K = a·scale.stiffness, B = b·scale.damping.
///
/// P0 = z^k·P0c(z) is stored as its low-degree core P0c = D·Vd and the power k, so that
/// evaluating on the unit circle costs O(n) for any delay.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AffineFamily {
    /// Core of P0 (ascending): P0 = z^k · p0_core.
    pub p0_core: Vec<f64>,
    /// Power k of the plant's pure delay in P0.
    pub k: usize,
    /// PK (ascending), the stiffness part.
    pub pk: Vec<f64>,
    /// PB (ascending), the damping part.
    pub pb: Vec<f64>,
    /// (P0(1), PK(1), PB(1)) formed in the shifted variable w = z − 1, free of the
    /// cancellation that z-coefficients suffer when every root is near z = 1.
    pub at_one: [f64; 3],
    /// The z-derivatives (P0'(1), PK'(1), PB'(1)), formed the same way.
    pub slope_at_one: [f64; 3],
    /// The z = 1 line exactly, p(1) = N(1)Vd(1)·(s + a + b·V(1)): s = the plant's static
    /// stiffness in wall units (the ZOH keeps the DC gain, H(1) = P(0)) and V(1) = Vn(1)/Vd(1)
    /// the estimator's DC gain (0 for every differentiator). None when N(1)Vd(1) = 0.
    pub plus_one: Option<(f64, f64)>,
    /// Wall units.
    pub scale: WallScale,
    /// The parts in the shifted variable w = z − 1 (P0 = (1 + w)^k·p0_core(w)), formed from
    /// E = Φ − I without the cancellation that z-coefficients suffer near z = 1; None when a
    /// velocity filter is too long to shift (more than [`MAX_SHIFTED_FILTER`] taps).
    pub shifted: Option<ShiftedParts>,
}

/// The parts of p in the shifted variable w = z − 1 (ascending coefficients in w).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShiftedParts {
    /// Core of P0 in w: D(w)·Vd(w).
    pub p0_core: Vec<f64>,
    /// PK in w: N(w)·Vd(w).
    pub pk: Vec<f64>,
    /// PB in w: N(w)·Vn(w).
    pub pb: Vec<f64>,
}

/// Longest velocity filter whose shifted form is kept: the shift of z^N has binomial
/// coefficients C(N, j), exact in doubles up to N ≈ 50 and harmless far beyond, but a filter
/// this long has no cluster of roots near z = 1 to resolve.
pub const MAX_SHIFTED_FILTER: usize = 64;

/// Angles |θ| below this evaluate p on the unit circle in the shifted form: there
/// |w| = 2 sin(θ/2) < 0.5 and the shifted coefficients' growth costs nothing.
pub const SHIFTED_THETA: f64 = 0.5;

/// A polynomial in w = z − 1 (ascending) evaluated with its derivative at w = 0.
fn at_zero(c: &[f64]) -> (f64, f64) {
    (
        c.first().copied().unwrap_or(0.0),
        c.get(1).copied().unwrap_or(0.0),
    )
}

/// (1 + w)^e = exp(e·ln(1 + w)), with ln|1 + w| = ½·ln_1p(2 Re w + |w|²) free of
/// cancellation for small w.
fn pow_one_plus(w: Complex64, e: f64) -> Complex64 {
    let ln_mod = 0.5 * (2.0 * w.re + w.norm_sqr()).ln_1p();
    let arg = w.im.atan2(1.0 + w.re);
    crate::circle::polar((e * ln_mod).exp(), e * arg)
}

impl AffineFamily {
    /// The family of a discrete loop (see the module doc).
    pub fn new(dl: &DiscreteLoop) -> Self {
        let den_w = dl.denominator_shifted();
        let (num_w, k) = dl.numerator_shifted(&den_w);
        let (vn, vd) = (&dl.velocity_num, &dl.velocity_den);
        // the parts in z: D(z) = D(w)|_{w = z − 1}, N(z) likewise
        let p0_core = poly::with_taylor_shift(&den_w, -1.0, |den| poly::mul(den, vd));
        let (pk, pb) =
            poly::with_taylor_shift(&num_w, -1.0, |num| (poly::mul(num, vd), poly::mul(num, vn)));
        // Values and slopes at z = 1 from the shifted forms (product rule).
        let (d1, dd1) = at_zero(&den_w);
        let (n1, dn1) = at_zero(&num_w);
        let (vd1, dvd1) = poly::eval_real(vd, 1.0);
        let (vn1, dvn1) = poly::eval_real(vn, 1.0);
        let kf = k as f64;
        let plus_one = dl
            .dc_stiffness
            .filter(|_| n1 * vd1 != 0.0)
            .map(|s| (s, dl.velocity_dc));
        // P0(1) = N(1)Vd(1)·s: the static stiffness is exact where det(E) rounds; PB(1) =
        // N(1)Vd(1)·V(1) with the estimator's exact DC gain (0 for a differentiator).
        let p0_one = plus_one.map_or(d1 * vd1, |(s, _)| n1 * vd1 * s);
        let pb_one = if vd1 == 0.0 {
            n1 * vn1
        } else {
            n1 * vd1 * dl.velocity_dc
        };
        let at_one = [p0_one, n1 * vd1, pb_one];
        let slope_at_one = [
            kf * d1 * vd1 + dd1 * vd1 + d1 * dvd1,
            dn1 * vd1 + n1 * dvd1,
            dn1 * vn1 + n1 * dvn1,
        ];
        let shifted = (vd.len().max(vn.len()) <= MAX_SHIFTED_FILTER).then(|| {
            let mut parts = poly::with_taylor_shift(vd, 1.0, |vd_w| {
                poly::with_taylor_shift(vn, 1.0, |vn_w| ShiftedParts {
                    p0_core: poly::mul(&den_w, vd_w),
                    pk: poly::mul(&num_w, vd_w),
                    pb: poly::mul(&num_w, vn_w),
                })
            });
            // The values at w = 0 are the parts at z = 1, exactly as `at_one` forms them (the
            // static stiffness where det(E) rounds): a wall on the z = 1 line then has its
            // root at z = 1 exactly in the shifted form, as in the loop.
            for (c, v) in [&mut parts.p0_core, &mut parts.pk, &mut parts.pb]
                .into_iter()
                .zip(at_one)
            {
                if let Some(c0) = c.first_mut() {
                    *c0 = v;
                }
            }
            parts
        });
        Self {
            p0_core,
            k,
            pk,
            pb,
            at_one,
            slope_at_one,
            plus_one,
            scale: dl.scale,
            shifted,
        }
    }

    /// The family of a loop: discretize, then close the loop.
    pub fn of_loop(lp: &Loop) -> Result<Self> {
        Ok(Self::new(&lp.discretize()?))
    }

    /// The same family in stretched wall coordinates (x, y) with a = sx·x, b = sy·y:
    /// p = P0 + x·(sx·PK) + y·(sy·PB). Regions are computed where the stable set is about as
    /// wide as tall ([`crate::region`]); sx, sy > 0.
    pub fn stretched(&self, sx: f64, sy: f64) -> AffineFamily {
        let scaled = |c: &[f64], f: f64| c.iter().map(|x| x * f).collect::<Vec<f64>>();
        let [p0, pk, pb] = self.at_one;
        let [d0, dk, db] = self.slope_at_one;
        AffineFamily {
            p0_core: self.p0_core.clone(),
            k: self.k,
            pk: scaled(&self.pk, sx),
            pb: scaled(&self.pb, sy),
            at_one: [p0, pk * sx, pb * sy],
            slope_at_one: [d0, dk * sx, db * sy],
            // p(1) = N(1)Vd(1)·(s + a + b·V(1)) = sx·N(1)Vd(1)·(s/sx + x + y·sy·V(1)/sx)
            plus_one: self.plus_one.map(|(s, v)| (s / sx, sy * v / sx)),
            scale: WallScale {
                stiffness: self.scale.stiffness * sx,
                damping: self.scale.damping * sy,
            },
            shifted: self.shifted.as_ref().map(|sh| ShiftedParts {
                p0_core: sh.p0_core.clone(),
                pk: scaled(&sh.pk, sx),
                pb: scaled(&sh.pb, sy),
            }),
        }
    }

    /// Degree of p(z) (it is monic).
    pub fn degree(&self) -> usize {
        self.k + self.p0_core.len() - 1
    }

    /// Writes the ascending coefficients of p(z) for wall (a, b) into `out` (length
    /// degree + 1).
    pub fn coefficients_into(&self, a: f64, b: f64, out: &mut [f64]) {
        let n = self.degree();
        out[..=n].fill(0.0);
        out[self.k..self.k + self.p0_core.len()].copy_from_slice(&self.p0_core);
        for (o, (x, y)) in out.iter_mut().zip(self.pk.iter().zip(&self.pb)) {
            *o += a * x + b * y;
        }
        // pk and pb may differ in length
        if self.pk.len() != self.pb.len() {
            let m = self.pk.len().min(self.pb.len());
            for (i, x) in self.pk.iter().enumerate().skip(m) {
                out[i] += a * x;
            }
            for (i, y) in self.pb.iter().enumerate().skip(m) {
                out[i] += b * y;
            }
        }
    }

    /// The ascending coefficients of p(z) for wall (a, b).
    pub fn coefficients(&self, a: f64, b: f64) -> Vec<f64> {
        let mut c = vec![0.0; self.degree() + 1];
        self.coefficients_into(a, b, &mut c);
        c
    }

    /// The ascending coefficients of p(1 + w) in the shifted variable w = z − 1 for wall
    /// (a, b): (1 + w)^k·D(w)Vd(w) + a·N(w)Vd(w) + b·N(w)Vn(w), built from the shifted parts
    /// (exact at w = 0, see [`AffineFamily::new`]) instead of shifting the rounded z-coefficients.
    /// Where many roots crowd z = 1 these coefficients keep the roots that the z-coefficients
    /// lose (a root at distance r from 1 moves by ε^{1/m} for m crowded roots in z, by far less
    /// in w). None when the loop has no shifted form (a velocity filter longer than
    /// [`MAX_SHIFTED_FILTER`]).
    pub fn coefficients_shifted(&self, a: f64, b: f64) -> Option<Vec<f64>> {
        let sh = self.shifted.as_ref()?;
        let mut binom = vec![1.0];
        for _ in 0..self.k {
            binom = poly::mul(&binom, &[1.0, 1.0]);
        }
        let p0 = poly::mul(&binom, &sh.p0_core);
        let mut out = vec![0.0; p0.len().max(sh.pk.len()).max(sh.pb.len())];
        for (i, o) in out.iter_mut().enumerate() {
            let at = |c: &[f64]| c.get(i).copied().unwrap_or(0.0);
            *o = at(&p0) + a * at(&sh.pk) + b * at(&sh.pb);
        }
        Some(out)
    }

    /// (P0(z), PK(z), PB(z)) at a complex point; z^k by repeated squaring.
    pub fn parts_at(&self, z: Complex64) -> (Complex64, Complex64, Complex64) {
        self.parts_with_power(z, z.powu(self.k as u32))
    }

    /// As [`AffineFamily::parts_at`] with z^k supplied by the caller (who may step it along
    /// the unit circle).
    pub fn parts_with_power(
        &self,
        z: Complex64,
        zk: Complex64,
    ) -> (Complex64, Complex64, Complex64) {
        let [c, pk, pb] = poly::eval3(&self.p0_core, &self.pk, &self.pb, z);
        (zk * c, pk, pb)
    }

    /// (P0, PK, PB) at z = e^{iθ}, near z = 1 from the shifted form with
    /// w = e^{iθ} − 1 = −2 sin²(θ/2) + i sin θ (no cancellation), elsewhere from the
    /// z-coefficients; z^k = e^{ikθ} in polar form (not by powers of the rounded z: the
    /// region's refinement at a free mass, γ = δ = 0, relies on z^k to an ulp of the circle).
    pub fn parts_on_circle(&self, theta: f64) -> (Complex64, Complex64, Complex64) {
        let (z, core, pk, pb) = self.unturned_on_circle(theta);
        let zk = match self.k {
            0 => Complex64::new(1.0, 0.0),
            1 => z,
            k => crate::circle::unit(theta * k as f64),
        };
        (zk * core, pk, pb)
    }

    /// (z, core, PK, PB) at z = e^{iθ} with P0 = z^k·core: the parts without the delay's
    /// turn z^k, which leaves every modulus unchanged (|P0| = |core| on the circle). For
    /// |L| alone ([`Self::parts_on_circle`]'s evaluation).
    pub fn unturned_on_circle(&self, theta: f64) -> (Complex64, Complex64, Complex64, Complex64) {
        match &self.shifted {
            Some(sh) if theta.abs() < SHIFTED_THETA => {
                // sin θ = 2 sin(θ/2) cos(θ/2): one sine and cosine for w and z = 1 + w
                let (h, c) = crate::circle::sin_cos(0.5 * theta);
                let w = Complex64::new(-2.0 * h * h, 2.0 * h * c);
                let [core, pk, pb] = poly::eval3(&sh.p0_core, &sh.pk, &sh.pb, w);
                (w + 1.0, core, pk, pb)
            }
            _ => {
                let z = crate::circle::unit(theta);
                let [core, pk, pb] = poly::eval3(&self.p0_core, &self.pk, &self.pb, z);
                (z, core, pk, pb)
            }
        }
    }

    /// (P0, PK, PB) and their derivatives at z = 1 + w, from the shifted form when it exists
    /// and |w| < 1/2 ((1 + w)^k = exp(k·ln(1 + w)) with ln(1 + w) free of cancellation),
    /// else from the z-coefficients. For polishing roots near z = 1.
    pub fn parts_shifted_with_derivative(&self, w: Complex64) -> [(Complex64, Complex64); 3] {
        let Some(sh) = self.shifted.as_ref().filter(|_| w.norm() < 0.5) else {
            return self.parts_with_derivative(w + 1.0);
        };
        let (c, dc) = poly::eval_with_derivative(&sh.p0_core, w);
        let zk = pow_one_plus(w, self.k as f64);
        let dzk = if self.k == 0 {
            Complex64::new(0.0, 0.0)
        } else {
            pow_one_plus(w, self.k as f64 - 1.0) * self.k as f64
        };
        [
            (zk * c, dzk * c + zk * dc),
            poly::eval_with_derivative(&sh.pk, w),
            poly::eval_with_derivative(&sh.pb, w),
        ]
    }

    /// The parts and their z-derivatives at a complex point.
    pub fn parts_with_derivative(&self, z: Complex64) -> [(Complex64, Complex64); 3] {
        let (c, dc) = poly::eval_with_derivative(&self.p0_core, z);
        let zk = z.powu(self.k as u32);
        let dzk = if self.k == 0 {
            Complex64::new(0.0, 0.0)
        } else {
            z.powu(self.k as u32 - 1) * self.k as f64
        };
        [
            (zk * c, dzk * c + zk * dc),
            poly::eval_with_derivative(&self.pk, z),
            poly::eval_with_derivative(&self.pb, z),
        ]
    }

    /// p(z) at a complex point.
    pub fn eval(&self, a: f64, b: f64, z: Complex64) -> Complex64 {
        let (p0, pk, pb) = self.parts_at(z);
        p0 + pk * a + pb * b
    }

    /// p(1), free of cancellation (see `at_one`): zero on the z = 1 line of Section V.
    pub fn value_at_one(&self, a: f64, b: f64) -> f64 {
        self.at_one[0] + a * self.at_one[1] + b * self.at_one[2]
    }

    /// (P0(−1), PK(−1), PB(−1)): the z = −1 line is P0(−1) + a·PK(−1) + b·PB(−1) = 0.
    pub fn at_minus_one(&self) -> [f64; 3] {
        let z = Complex64::new(-1.0, 0.0);
        let (p0, pk, pb) = self.parts_at(z);
        [p0.re, pk.re, pb.re]
    }

    /// Converts wall units (a, b) to a physical wall (K in N/m, B in Ns/m).
    pub fn to_physical(&self, a: f64, b: f64) -> (f64, f64) {
        (a * self.scale.stiffness, b * self.scale.damping)
    }

    /// Converts a physical wall (K, B) to wall units (a, b).
    pub fn to_units(&self, stiffness: f64, damping: f64) -> (f64, f64) {
        (
            stiffness / self.scale.stiffness,
            damping / self.scale.damping,
        )
    }
}
