//! Before step 1: the stable set's extent along two exact slices, which sets how the wall plane
//! is stretched (a region 10³ times taller than wide is computed where it is about square) and
//! where the first coarse sampling looks closely.
//!
//! The slices are the exact stable intervals of [`crate::boundary`]: the stiffness axis at
//! b = 0, the damping axis through the middle of its widest interval, and the stiffness axis
//! again through the middle of that (or, when no wall without damping is stable, the same
//! starting from the damping axis at a = 0).

use super::*;
use crate::boundary::{
    CircleTable, Interval, WallLine, line_crossings_tabulated, stable_between,
    stable_stiffness_intervals_tabulated,
};

/// Aspect ratios within this factor of 1 are left alone: the isotropic sampling resolves them
/// (the paper's regions are within 30 of square), and their polygons stay bit for bit those
/// of an unstretched computation.
pub(super) const MAX_UNSTRETCHED_ASPECT: f64 = 100.0;

/// The extent of the stable set seen on two perpendicular exact slices, in wall units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SliceBox {
    /// The box (a0, a1, b0, b1) the two slices' stable intervals span.
    pub(super) bounds: BoxF,
}

impl SliceBox {
    /// The slices of the module doc; None when none finds a stable wall with finite ends.
    /// When neither axis through the wall-free point finds one (an undamped plant, whose
    /// stable set touches the axes only at its corner), the same slices are taken through
    /// points ±10^{−k} of `size` (the bounds' extent) off it, k = 1..[`OFFSET_DECADES`].
    pub(super) fn of(fam: &AffineFamily, table: &CircleTable, size: f64) -> Option<Self> {
        let fam = &(fam, table);
        let offsets = (1..=OFFSET_DECADES).flat_map(|k| {
            let v = size * 10f64.powi(-k);
            [v, -v]
        });
        let bounds = std::iter::once(0.0)
            .chain(offsets)
            .find_map(|v| from_stiffness_axis(fam, v).or_else(|| from_damping_axis(fam, v)))?;
        (bounds.1 > bounds.0 && bounds.3 > bounds.2).then_some(Self { bounds })
    }

    /// The box in the plane stretched by (sx, sy), widened to three times its size about its
    /// centre: the focus of the first coarse sampling.
    pub(super) fn focus(&self, (sx, sy): (f64, f64)) -> BoxF {
        let (a0, a1, b0, b1) = self.bounds;
        let (x0, x1, y0, y1) = (a0 / sx, a1 / sx, b0 / sy, b1 / sy);
        let (hx, hy) = (x1 - x0, y1 - y0);
        (x0 - hx, x1 + hx, y0 - hy, y1 + hy)
    }

    /// Height over width.
    pub(super) fn aspect(&self) -> f64 {
        let (a0, a1, b0, b1) = self.bounds;
        (b1 - b0) / (a1 - a0)
    }
}

/// Decades below the bounds' extent at which slices are taken off the wall-free point.
const OFFSET_DECADES: i32 = 15;

/// A family with its table of the unit circle (one scan serves every slice).
type Tabled<'a> = (&'a AffineFamily, &'a CircleTable);

/// The stable interval's span along the stiffness axis at damping b (lowest end, highest end,
/// middle of the widest interval).
fn along_a(&(fam, table): &Tabled<'_>, b: f64) -> Option<(f64, f64, f64)> {
    span(&stable_stiffness_intervals_tabulated(fam, table, b))
}

/// The same along the damping axis at stiffness a.
fn along_b(&(fam, table): &Tabled<'_>, a: f64) -> Option<(f64, f64, f64)> {
    let line = WallLine {
        from: WallPoint { a, b: 0.0 },
        dir: WallPoint { a: 0.0, b: 1.0 },
    };
    span(&stable_between(
        fam,
        &line,
        &line_crossings_tabulated(fam, table, &line),
    ))
}

/// Three slices from the stiffness axis at damping b: it, the damping axis through the middle
/// of what it found, the stiffness axis again through the middle of that (a region that is a
/// sliver on the first axis, as an undamped plant's, is wide halfway up).
fn from_stiffness_axis(fam: &Tabled<'_>, b: f64) -> Option<BoxF> {
    let (a0, a1, mid) = along_a(fam, b)?;
    let (b0, b1, bmid) = along_b(fam, mid)?;
    let (c0, c1, _) = along_a(fam, bmid).unwrap_or((a0, a1, mid));
    Some((a0.min(c0), a1.max(c1), b0.min(b), b1.max(b)))
}

/// The same three slices starting from the damping axis at stiffness a.
fn from_damping_axis(fam: &Tabled<'_>, a: f64) -> Option<BoxF> {
    let (b0, b1, mid) = along_b(fam, a)?;
    let (a0, a1, amid) = along_a(fam, mid)?;
    let (c0, c1, _) = along_b(fam, amid).unwrap_or((b0, b1, mid));
    Some((a0.min(a), a1.max(a), b0.min(c0), b1.max(c1)))
}

/// The span (lowest finite end, highest finite end, middle of the widest interval) of a set
/// of stable intervals, ignoring infinite ends; None when no interval has a finite width.
fn span(ivs: &[Interval]) -> Option<(f64, f64, f64)> {
    let finite: Vec<&Interval> = ivs
        .iter()
        .filter(|iv| iv.lo.is_finite() && iv.hi.is_finite() && iv.hi > iv.lo)
        .collect();
    let widest = finite
        .iter()
        .max_by(|x, y| (x.hi - x.lo).total_cmp(&(y.hi - y.lo)))?;
    let lo = finite.iter().map(|iv| iv.lo).fold(f64::INFINITY, f64::min);
    let hi = finite
        .iter()
        .map(|iv| iv.hi)
        .fold(f64::NEG_INFINITY, f64::max);
    Some((lo, hi, 0.5 * (widest.lo + widest.hi)))
}

/// The stretch (sx, sy) of the wall plane, a = sx·x, b = sy·y, that makes the slices' box
/// square, when its aspect is beyond [`MAX_UNSTRETCHED_ASPECT`] either way.
pub(super) fn stretch(slices: Option<SliceBox>) -> Option<(f64, f64)> {
    let s = slices?;
    let r = s.aspect();
    (r.is_finite()
        && r > 0.0
        && !(1.0 / MAX_UNSTRETCHED_ASPECT..=MAX_UNSTRETCHED_ASPECT).contains(&r))
    .then_some((1.0, r))
}

/// A region computed in the stretched plane, mapped back to wall units: every vertex, the
/// largest stiffness and its damping, and the area.
pub(super) fn unstretched(mut r: StableRegion, (sx, sy): (f64, f64)) -> StableRegion {
    for poly in &mut r.polygons {
        for v in &mut poly.vertices {
            v.a *= sx;
            v.b *= sy;
        }
    }
    r.a_max *= sx;
    r.a_stable *= sx;
    r.b_at_a_max *= sy;
    r.b_stable *= sy;
    r.area *= sx * sy;
    r
}
