//! Exact stability boundaries by D-decomposition (Section V, Figs. 4–6), for any loop.
//!
//! p(z) = P0(z) + a·PK(z) + b·PB(z) is affine in the wall (see [`AffineFamily`]; for the
//! paper's loop (a, b) = (α, β)). A root on the unit circle at z = e^{iθ} is two real linear
//! equations in (a, b); for θ in (0, π) their solution is the *curve*
//!
//! ```text
//! a(θ) = Im(P0·conj PB) / Im(conj PK·PB),     b(θ) = Im(PK·conj P0) / Im(conj PK·PB),
//! ```
//!
//! (for the paper's loop: α(θ) = Im(R(z)(1 − z))/sin θ, β(θ) = −Im R(z)/sin θ with
//! R = z^d D/N). A real root at z = 1 or z = −1 is one real equation: the *lines*
//! P0(±1) + a·PK(±1) + b·PB(±1) = 0 (for the paper's loop α = −γ and
//! α + 2β = (−1)^{d+1} D(−1)/N(−1)). Between these sets the number of roots outside the
//! unit circle is constant, so one Schur–Cohn test per piece decides it.

use std::f64::consts::PI;

use num_complex::Complex64;
use rayon::prelude::*;

use crate::bracket::sign_change;
use serde::Serialize;

use crate::cayley::CayleyFamily;
use crate::closed_loop::AffineFamily;

/// A point of the wall plane in wall units (a, b); for the paper's loop (α, β). It is written
/// as `{"alpha": a, "beta": b}`, the paper's output.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WallPoint {
    /// Virtual stiffness in wall units a = K/k_u (α for the paper's loop).
    #[serde(rename = "alpha")]
    pub a: f64,
    /// Virtual damping in wall units b = B/(k_u T) (β for the paper's loop).
    #[serde(rename = "beta")]
    pub b: f64,
}

/// The set of walls with a real root at z = ±1: p0 + a·pk + b·pb = 0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RootLine {
    /// P0(±1).
    pub p0: f64,
    /// PK(±1).
    pub pk: f64,
    /// PB(±1).
    pub pb: f64,
    /// +1 where a monic Schur-stable p has this sign of p0 + a·pk + b·pb: p(1) > 0 and
    /// (−1)^n p(−1) > 0 (necessary conditions of the Schur–Cohn test).
    pub stable_sign: f64,
}

impl RootLine {
    /// p(±1) at wall (a, b).
    pub fn value(&self, p: WallPoint) -> f64 {
        self.p0 + p.a * self.pk + p.b * self.pb
    }

    /// The a on the line at a given b (None when the line is parallel to the a-axis).
    pub fn stiffness_at(&self, b: f64) -> Option<f64> {
        let a = -(self.p0 + b * self.pb) / self.pk;
        a.is_finite().then_some(a)
    }
}

/// The z = 1 line (Section V: α = −γ for the paper's loop), from the cancellation-free
/// values at z = 1; None when the wall does not act at z = 1 (PK(1) = PB(1) = 0).
pub fn plus_one_line(fam: &AffineFamily) -> Option<RootLine> {
    if let Some((s, v1)) = fam.plus_one {
        // p(1) = N(1)Vd(1)·(s + a + b·V(1)): exact coefficients, and the stable side keeps
        // the sign of N(1)Vd(1).
        return Some(RootLine {
            p0: s,
            pk: 1.0,
            pb: v1,
            stable_sign: fam.at_one[1].signum(),
        });
    }
    let [p0, pk, pb] = fam.at_one;
    (pk != 0.0 || pb != 0.0).then_some(RootLine {
        p0,
        pk,
        pb,
        stable_sign: 1.0,
    })
}

/// A value of a polynomial below this fraction of its coefficients' 1-norm is rounding noise:
/// 100 ulps leaves room for the evaluation's error growth with the degree.
const ROUNDING_ZERO: f64 = 1e-14;

/// The z = −1 line (Section VIII: a pole at z = −1); None when the wall does not act at
/// z = −1 (PK(−1) = PB(−1) = 0, as for a pure mass whose N(−1) = 0).
pub fn minus_one_line(fam: &AffineFamily) -> Option<RootLine> {
    let [p0, pk, pb] = fam.at_minus_one();
    // PK(−1), PB(−1) at the rounding level of their evaluation are zeros (e.g. N(−1) = 0
    // exactly for an undamped mass-spring, computed as 1e-17): no line then.
    let l1 = |c: &[f64]| c.iter().map(|x| x.abs()).sum::<f64>();
    let tiny = ROUNDING_ZERO * (l1(&fam.pk) + l1(&fam.pb)) + 1e-300;
    if pk.abs() <= tiny && pb.abs() <= tiny {
        return None;
    }
    let sign = if fam.degree().is_multiple_of(2) {
        1.0
    } else {
        -1.0
    };
    Some(RootLine {
        p0,
        pk,
        pb,
        stable_sign: sign,
    })
}

/// Solves a·x + b·y = w for complex x, y, w read as plane vectors.
fn solve_pair(x: Complex64, y: Complex64, w: Complex64) -> Option<WallPoint> {
    let det = (x.conj() * y).im;
    if det == 0.0 {
        return None;
    }
    let p = WallPoint {
        a: (w.conj() * y).im / det,
        b: (x.conj() * w).im / det,
    };
    (p.a.is_finite() && p.b.is_finite()).then_some(p)
}

/// The boundary point for a complex root pair at angle θ ∈ (0, π): the wall for which
/// p(e^{iθ}) = 0 (D-decomposition, Section V). None where the two equations are dependent
/// (the curve runs to infinity there).
pub fn curve_point(fam: &AffineFamily, theta: f64) -> Option<WallPoint> {
    let (p0, pk, pb) = fam.parts_on_circle(theta);
    solve_pair(pk, pb, -p0)
}

/// As [`curve_point`] for z = e^{iθ} given directly (|z| = 1, Im z > 0), which lets callers
/// that step along the circle avoid a sine and cosine per point. Near z = 1 use
/// [`curve_point`], which evaluates in the shifted variable.
pub fn curve_point_at(fam: &AffineFamily, z: Complex64) -> Option<WallPoint> {
    let (p0, pk, pb) = fam.parts_at(z);
    solve_pair(pk, pb, -p0)
}

/// The curve's end point at θ = 0 (z = 1) or θ = π (z = −1): the wall with a double root
/// there, p(±1) = p'(±1) = 0 (the limit of the curve by l'Hôpital's rule). None when the
/// limit does not exist (the curve runs to infinity).
pub fn curve_end(fam: &AffineFamily, at_plus_one: bool) -> Option<WallPoint> {
    let (v, s) = if at_plus_one {
        (fam.at_one, fam.slope_at_one)
    } else {
        let parts = fam.parts_with_derivative(Complex64::new(-1.0, 0.0));
        (parts.map(|p| p.0.re), parts.map(|p| p.1.re))
    };
    let det = v[1] * s[2] - v[2] * s[1];
    if det == 0.0 {
        return None;
    }
    let p = WallPoint {
        a: (-v[0] * s[2] + v[2] * s[0]) / det,
        b: (-v[1] * s[0] + v[0] * s[1]) / det,
    };
    (p.a.is_finite() && p.b.is_finite()).then_some(p)
}

/// da/dθ along the curve, analytically (for the largest stable stiffness on an arc); near
/// z = 1 in the shifted variable.
pub fn da_dtheta(fam: &AffineFamily, theta: f64) -> f64 {
    let z = crate::circle::unit(theta);
    let iz = Complex64::i() * z;
    // near z = 1 from the shifted form (w = e^{iθ} − 1 without cancellation), as the curve
    // itself is evaluated there: the z-coefficients place no stationary point at θ ≪ 1
    let [(p0, d0), (pk, dk), (pb, db)] = if theta < crate::closed_loop::SHIFTED_THETA {
        let h = (0.5 * theta).sin();
        fam.parts_shifted_with_derivative(Complex64::new(-2.0 * h * h, theta.sin()))
    } else {
        fam.parts_with_derivative(z)
    };
    let (d0, dk, db) = (iz * d0, iz * dk, iz * db);
    let f = (p0 * pb.conj()).im;
    let g = (pk.conj() * pb).im;
    let df = (d0 * pb.conj() + p0 * db.conj()).im;
    let dg = (dk.conj() * pb + pk.conj() * db).im;
    (df * g - f * dg) / (g * g)
}

/// A line in the wall plane, from + t·dir (t real): the stiffness axis at fixed damping
/// (from = (0, b), dir = (1, 0)) or the ray through a wall from the origin (from = (0, 0),
/// dir = the wall), along which gain margins are measured.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WallLine {
    /// The point at t = 0.
    pub from: WallPoint,
    /// The direction (the point at t = 1 minus `from`).
    pub dir: WallPoint,
}

impl WallLine {
    /// The stiffness axis at damping b: a = t.
    pub fn stiffness_axis(b: f64) -> Self {
        Self {
            from: WallPoint { a: 0.0, b },
            dir: WallPoint { a: 1.0, b: 0.0 },
        }
    }

    /// The ray from the origin through a wall: the wall scaled by t.
    pub fn ray(wall: WallPoint) -> Self {
        Self {
            from: WallPoint { a: 0.0, b: 0.0 },
            dir: wall,
        }
    }

    /// The point at parameter t.
    pub fn at(&self, t: f64) -> WallPoint {
        WallPoint {
            a: self.from.a + t * self.dir.a,
            b: self.from.b + t * self.dir.b,
        }
    }
}

/// A parameter t at which the line's p(z) has a root on the unit circle, and the angle θ of
/// that root (0 on the z = 1 line, π on the z = −1 line, else the complex pair e^{±iθ}).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LineCrossing {
    /// The line parameter.
    pub t: f64,
    /// The root's angle in [0, π].
    pub theta: f64,
}

/// Im(Q conj D) with Q = P0 + from·(PK, PB), D = dir·(PK, PB) at z = e^{iθ} (the shifted
/// form near z = 1): zero where a real t puts a root there; and that t = −Re(Q conj D)/|D|².
pub(crate) fn crossing_function(fam: &AffineFamily, line: &WallLine, theta: f64) -> (f64, f64) {
    crossing_from_parts(fam.parts_on_circle(theta), line)
}

/// [`crossing_function`] from the parts (P0, PK, PB) at one θ.
fn crossing_from_parts(
    (p0, pk, pb): (Complex64, Complex64, Complex64),
    line: &WallLine,
) -> (f64, f64) {
    let q = p0 + pk * line.from.a + pb * line.from.b;
    let d = pk * line.dir.a + pb * line.dir.b;
    let qc = q * d.conj();
    let nd = d.norm_sqr();
    (qc.im, if nd > 0.0 { -qc.re / nd } else { f64::NAN })
}

/// d/dθ of Im(Q conj D) at z = e^{iθ} (d/dθ = iz·d/dz), from the shifted form near z = 1.
pub(crate) fn crossing_slope(fam: &AffineFamily, line: &WallLine, theta: f64) -> f64 {
    let z = crate::circle::unit(theta);
    let parts = if theta < crate::closed_loop::SHIFTED_THETA {
        let h = (0.5 * theta).sin();
        fam.parts_shifted_with_derivative(Complex64::new(-2.0 * h * h, theta.sin()))
    } else {
        fam.parts_with_derivative(z)
    };
    let [(p0, d0), (pk, dk), (pb, db)] = parts;
    let iz = Complex64::i() * z;
    let (fa, fb) = (line.from.a, line.from.b);
    let (da, db_) = (line.dir.a, line.dir.b);
    let (q, dq) = (p0 + pk * fa + pb * fb, (d0 + dk * fa + db * fb) * iz);
    let (d, dd) = (pk * da + pb * db_, (dk * da + db * db_) * iz);
    (dq * d.conj() + q * dd.conj()).im
}

/// The θ grid of the crossing scan: p has at most `degree` roots, so its phase turns at most
/// `degree` times around the circle and 256 samples per turn leave room; near θ = 0 a
/// geometric run from 1e-12 up to the first step brackets roots close to z = 1 (fast
/// sampling, slow modes), which cross at angles far below the uniform step.
fn scan_thetas(fam: &AffineFamily) -> Vec<f64> {
    let m = 256 * (fam.degree() + 1);
    let h = PI / m as f64;
    let mut ts = Vec::with_capacity(m + 256);
    let mut t = 1e-12_f64.min(1e-9 * h);
    while t < h {
        ts.push(t);
        t *= NEAR_ONE_RATIO;
    }
    ts.extend((1..m).map(|i| i as f64 * h));
    ts.push(PI * (1.0 - 1e-12));
    ts
}

/// All a at which, for fixed b, p(z) has a root on the unit circle (D-decomposition along
/// the stiffness, Section V); see [`line_crossings`].
pub fn stiffness_crossings(fam: &AffineFamily, b: f64) -> Vec<f64> {
    line_crossings(fam, &WallLine::stiffness_axis(b))
        .into_iter()
        .map(|c| c.t)
        .collect()
}

/// The t on a root line where the wall line meets it (None when parallel).
pub(crate) fn root_line_t(l: &RootLine, line: &WallLine) -> Option<f64> {
    let t = -l.value(line.from) / (line.dir.a * l.pk + line.dir.b * l.pb);
    t.is_finite().then_some(t)
}

/// All t at which p(z) of the wall from + t·dir has a root on the unit circle, with the
/// root's angle, sorted by t (D-decomposition along a line, Section V): the z = ±1 lines
/// and the zeros of Im(Q conj D) on a θ scan. Sign changes between samples are refined by
/// Brent's method; where the sign does not change but the slope does, the extremum between
/// is located and, if it crosses zero, both zeros on either side of it are kept (two
/// crossings closer than a sample, as a thin region of a lightly damped loop makes them).
pub fn line_crossings(fam: &AffineFamily, line: &WallLine) -> Vec<LineCrossing> {
    match CayleyFamily::new(fam) {
        Some(cf) => crate::line_decomposition::line_crossings(fam, &cf, line),
        None => scanned_line_crossings(fam, line),
    }
}

/// [`line_crossings`] from the θ scan alone (the method for loops above
/// [`crate::cayley::MAX_DEGREE`], and the independent check of the Cayley crossings).
pub fn scanned_line_crossings(fam: &AffineFamily, line: &WallLine) -> Vec<LineCrossing> {
    let ts = scan_thetas(fam);
    let fs: Vec<f64> = ts
        .iter()
        .map(|&t| crossing_function(fam, line, t).0)
        .collect();
    crossings_on_scan(fam, line, &ts, &fs)
}

/// Angles per parallel task of a [`CircleTable`]: a few hundred evaluations outweigh a task's
/// start.
const TABLE_BLOCK: usize = 512;

/// Angles per parallel task of [`CircleTable::on`] (a few hundred angles in all).
const SHARED_BLOCK: usize = 128;

/// The parts (P0, PK, PB) of a family on the θ grid of the crossing scan, computed once for
/// many lines: [`line_crossings_tabulated`] then finds the same crossings as
/// [`line_crossings`] (the same values at the same θ) without re-evaluating p on the grid,
/// as a robust region's many slices of one plant need.
#[derive(Debug, Clone)]
pub struct CircleTable {
    thetas: Vec<f64>,
    parts: Vec<(Complex64, Complex64, Complex64)>,
}

impl CircleTable {
    /// The table of `fam` on its scan grid.
    pub fn new(fam: &AffineFamily) -> Self {
        Self::in_blocks(fam, scan_thetas(fam), TABLE_BLOCK)
    }

    /// The table of `fam` on the given sorted angles in (0, π): one analysis's shared grid
    /// (the margins'), in blocks of [`SHARED_BLOCK`] angles that an idle thread may take.
    /// Its crossings are those of [`line_crossings`] on that grid.
    pub fn on(fam: &AffineFamily, thetas: Vec<f64>) -> Self {
        Self::in_blocks(fam, thetas, SHARED_BLOCK)
    }

    /// The parts of `fam` at `thetas`, in parallel blocks of at least `block` angles (each
    /// the same value as unblocked).
    fn in_blocks(fam: &AffineFamily, thetas: Vec<f64>, block: usize) -> Self {
        let parts = thetas
            .par_iter()
            .with_min_len(block)
            .map(|&t| fam.parts_on_circle(t))
            .collect();
        Self { thetas, parts }
    }

    /// The table's angles, increasing.
    pub fn thetas(&self) -> &[f64] {
        &self.thetas
    }

    /// (P0, PK, PB) at each angle.
    pub fn parts(&self) -> &[(Complex64, Complex64, Complex64)] {
        &self.parts
    }
}

/// The [`CircleTable`] of a family, built on first use: a region that its plain attempt
/// resolves and confirms locally never needs it, one measured by slices builds it once.
#[derive(Debug)]
pub struct LazyCircleTable<'a> {
    fam: &'a AffineFamily,
    cell: std::sync::OnceLock<CircleTable>,
}

impl<'a> LazyCircleTable<'a> {
    /// The (not yet built) table of `fam`.
    pub fn new(fam: &'a AffineFamily) -> Self {
        Self {
            fam,
            cell: std::sync::OnceLock::new(),
        }
    }

    /// The table, built now if it was not before.
    pub fn get(&self) -> &CircleTable {
        self.cell.get_or_init(|| CircleTable::new(self.fam))
    }
}

/// [`line_crossings`] with the scan's values taken from `table`, which must be the
/// [`CircleTable`] of `fam`.
pub fn line_crossings_tabulated(
    fam: &AffineFamily,
    table: &CircleTable,
    line: &WallLine,
) -> Vec<LineCrossing> {
    let fs: Vec<f64> = table
        .parts
        .iter()
        .map(|&p| crossing_from_parts(p, line).0)
        .collect();
    crossings_on_scan(fam, line, &table.thetas, &fs)
}

/// The crossings from the scan's samples `fs` of Im(Q conj D) at `ts` (see
/// [`line_crossings`]).
fn crossings_on_scan(
    fam: &AffineFamily,
    line: &WallLine,
    ts: &[f64],
    fs: &[f64],
) -> Vec<LineCrossing> {
    let mut out: Vec<LineCrossing> = Vec::new();
    for (l, theta) in [(plus_one_line(fam), 0.0), (minus_one_line(fam), PI)] {
        if let Some(t) = l.and_then(|l| root_line_t(&l, line)) {
            out.push(LineCrossing { t, theta });
        }
    }
    let f = |t: f64| crossing_function(fam, line, t).0;
    let df = |t: f64| crossing_slope(fam, line, t);
    let mut push = |theta: f64| {
        let t = crossing_function(fam, line, theta).1;
        if t.is_finite() {
            out.push(LineCrossing { t, theta });
        }
    };
    for i in 1..ts.len() {
        let (t0, t1, f0, f1) = (ts[i - 1], ts[i], fs[i - 1], fs[i]);
        if f1 == 0.0 || (f0 > 0.0) != (f1 > 0.0) {
            push(if f1 == 0.0 {
                t1
            } else {
                sign_change(t0, t1, f)
            });
            continue;
        }
        // A local minimum of |f| at sample i: f may dip through zero and back between its
        // neighbours. Locate the extremum by the slope; two zeros if it crosses.
        let Some(&f2) = fs.get(i + 1) else { continue };
        let t2 = ts[i + 1];
        if f1.abs() < f0.abs() && f1.abs() <= f2.abs() && (f2 > 0.0) == (f1 > 0.0) {
            let (d0, d2) = (df(t0), df(t2));
            if (d0 > 0.0) == (d2 > 0.0) {
                continue;
            }
            let te = sign_change(t0, t2, df);
            if (f(te) > 0.0) != (f1 > 0.0) {
                push(sign_change(t0, te, f));
                push(sign_change(te, t2, f));
            }
        }
    }
    out.sort_by(|a, b| a.t.total_cmp(&b.t));
    out.dedup_by(|a, b| (a.t - b.t).abs() <= 1e-15 * a.t.abs().max(b.t.abs()));
    out
}

/// Ratio of the geometric θ grid near z = 1 (about 20 samples per decade).
const NEAR_ONE_RATIO: f64 = 1.122;

/// A stable interval lo < a < hi (either end may be infinite).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Interval {
    /// Lower end (exclusive).
    pub lo: f64,
    /// Upper end (exclusive).
    pub hi: f64,
}

/// The stable intervals of the wall stiffness a (in the family's wall units; α for the
/// paper's loop) at a given damping b (Section V): between consecutive boundary crossings the
/// number of unstable roots is constant, so one Schur–Cohn test per gap decides it.
pub fn stable_stiffness_intervals(fam: &AffineFamily, b: f64) -> Vec<Interval> {
    stable_line_intervals(fam, &WallLine::stiffness_axis(b))
}

/// [`stable_stiffness_intervals`] with the crossing scan taken from `table`, the
/// [`CircleTable`] of `fam` (identical results).
pub fn stable_stiffness_intervals_tabulated(
    fam: &AffineFamily,
    table: &CircleTable,
    b: f64,
) -> Vec<Interval> {
    let line = WallLine::stiffness_axis(b);
    stable_between(fam, &line, &line_crossings_tabulated(fam, table, &line))
}

/// The stable intervals of t on a wall line (see [`stable_stiffness_intervals`], Section V).
pub fn stable_line_intervals(fam: &AffineFamily, line: &WallLine) -> Vec<Interval> {
    match CayleyFamily::new(fam) {
        Some(cf) => crate::line_decomposition::stable_intervals(fam, &cf, line),
        None => stable_between(fam, line, &line_crossings(fam, line)),
    }
}

/// A gap between crossings narrower than this (relative to its ends) is one double crossing
/// split by rounding — a tangency, or a corner of the region on the line: every wall inside it
/// has a root within rounding of the circle, so it counts as stable only where the Schur–Cohn
/// recursion is sure of it, and the argument principle (a hundred times the cost, and no
/// better at that distance) is not asked. What it could add to or take from an interval is
/// far below the confirmation distance of any reported end.
const SLIVER_REL: f64 = 1e-12;

/// The stable intervals of t on a wall line from its crossings (as returned by
/// [`line_crossings`], sorted by t): one test of the roots inside the circle in each gap
/// ([`crate::verdict::inside_unit_circle`]; the recursion alone in a sliver, see
/// [`SLIVER_REL`]), merged into intervals.
/// Every finite interval end is one of the crossings' t, exactly.
pub fn stable_between(
    fam: &AffineFamily,
    line: &WallLine,
    crossings: &[LineCrossing],
) -> Vec<Interval> {
    let xs: Vec<f64> = crossings.iter().map(|c| c.t).collect();
    if xs.is_empty() {
        return Vec::new();
    }
    let scale = xs.iter().fold(1e-3_f64, |m, x| m.max(x.abs()));
    let mut coeffs = vec![0.0; fam.degree() + 1];
    let mut sliver = coeffs.clone();
    // A gap holds a constant number of roots inside the circle: it is classified by that
    // count, not by one wall's banded verdict (a gap thinner than the marginal band is still
    // stable where its roots are inside).
    let mut stable_at = |t: f64| {
        let p = line.at(t);
        crate::verdict::inside_unit_circle(fam, p.a, p.b, &mut coeffs) == Some(true)
    };
    let mut out: Vec<Interval> = Vec::new();
    let push = |lo: f64, hi: f64, out: &mut Vec<Interval>| match out.last_mut() {
        Some(last) if last.hi == lo => last.hi = hi,
        _ => out.push(Interval { lo, hi }),
    };
    let first = xs[0];
    if stable_at(first - scale) {
        push(f64::NEG_INFINITY, first, &mut out);
    }
    for w in xs.windows(2) {
        let mid = 0.5 * (w[0] + w[1]);
        let stable = if w[1] - w[0] <= SLIVER_REL * w[0].abs().max(w[1].abs()) {
            let p = line.at(mid);
            fam.coefficients_into(p.a, p.b, &mut sliver);
            let sc = crate::schur_cohn::schur_cohn(&sliver, 1.0, 0.0);
            sc.sure && sc.stable
        } else {
            stable_at(mid)
        };
        if stable {
            push(w[0], w[1], &mut out);
        }
    }
    let last = xs[xs.len() - 1];
    if stable_at(last + scale) {
        push(last, f64::INFINITY, &mut out);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PlantParams;
    use crate::paper::NormalizedFamily;

    #[test]
    fn pure_mass_interval_is_closed_form() {
        let fam = NormalizedFamily::new(PlantParams::new(0.0, 0.0).unwrap(), 0).unwrap();
        for beta in [0.1, 0.7, 1.5] {
            let iv = stable_stiffness_intervals(&fam, beta);
            let hi = 2.0 * beta * (2.0 - beta) / (2.0 + beta);
            assert_eq!(iv.len(), 1, "{iv:?}");
            assert_eq!(iv[0].lo, 0.0);
            assert!((iv[0].hi - hi).abs() < 1e-14 * hi, "{} vs {hi}", iv[0].hi);
        }
        assert!(stable_stiffness_intervals(&fam, -0.1).is_empty());
        assert!(stable_stiffness_intervals(&fam, 2.1).is_empty());
    }

    #[test]
    fn tabulated_crossings_are_the_crossings() {
        for (g, dl, d) in [(0.001, 0.015, 0), (0.5, 1.0, 1), (9.8, 0.0, 2)] {
            let pf = crate::paper::NormalizedFamily::new(
                crate::paper::PlantParams::new(g, dl).unwrap(),
                d,
            )
            .unwrap();
            let table = CircleTable::new(&pf);
            for b in [-0.3, 0.0, 0.01, 0.4, 1.5] {
                let line = WallLine::stiffness_axis(b);
                let scanned = scanned_line_crossings(&pf, &line);
                assert_eq!(line_crossings_tabulated(&pf, &table, &line), scanned);
                assert_eq!(
                    stable_stiffness_intervals_tabulated(&pf, &table, b),
                    stable_between(&pf, &line, &scanned)
                );
            }
        }
    }

    #[test]
    fn curve_points_put_a_root_on_the_circle() {
        let fam = NormalizedFamily::new(PlantParams::new(1e-3, 0.015).unwrap(), 2).unwrap();
        for t in [0.01, 0.5, 1.0, 2.0, 3.0] {
            let p = curve_point(&fam, t).unwrap();
            let v = fam.eval(p.a, p.b, crate::circle::unit(t));
            assert!(v.norm() < 1e-14 * (1.0 + p.a.abs() + p.b.abs()), "{v}");
        }
    }

    #[test]
    fn curve_ends_are_double_roots() {
        // Paper's loop: the end at z = 1 lies on α = −γ, the end at z = −1 on the z = −1 line.
        let fam = NormalizedFamily::new(PlantParams::new(1e-3, 0.015).unwrap(), 1).unwrap();
        let e0 = curve_end(&fam, true).unwrap();
        assert!((e0.a + 1e-3).abs() < 1e-12, "{e0:?}");
        let e1 = curve_end(&fam, false).unwrap();
        let line = minus_one_line(&fam).unwrap();
        assert!(line.value(e1).abs() < 1e-12, "{e1:?}");
        // and the curve tends to them
        let near0 = curve_point(&fam, 1e-6).unwrap();
        assert!((near0.a - e0.a).abs() < 1e-6 && (near0.b - e0.b).abs() < 1e-6);
    }
}
