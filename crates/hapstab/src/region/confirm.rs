//! After step 6: the largest stable stiffness confirmed before it is reported.
//!
//! The polygons' K_max and its damping B* are checked against the exact stable intervals at
//! B* ([`crate::boundary::stable_stiffness_intervals`]): their highest end must be K_max to 1e-9
//! (it then replaces the polygon's value, exact to rounding), and the point test must find
//! every root of the wall (K_max − δ, B*) inside the unit circle and not of (K_max + δ, B*),
//! δ = [`CONFIRM_REL`]·|K_max|. Where
//! K_max is a corner of the region that only one damping touches, no stiffness near K_max is
//! stable at B* itself: K_max is then a supremum, approached as B → B*, and the confirmation
//! finds the damping nearest B* (by decades) at which a stiffness of the wedge's stable
//! interval is confirmed stable by the point test, within [`SUPREMUM_REL`] of K_max where the
//! wedge is wide enough to certify a wall there, and at most [`CONFIRM_REL`] below it. A
//! candidate that fails either way is a wrong region, and the caller refuses or retries it.

use super::*;
use crate::boundary::{CircleTable, LazyCircleTable, stable_stiffness_intervals_tabulated};

/// Relative distance of the walls beside K_max that the verdict must call stable (inside) and
/// not stable (outside): far above the rounding of K_max, far below any margin that matters.
pub const CONFIRM_REL: f64 = 1e-6;

/// Relative shortfall sought for the stiffness confirmed stable beside a supremum's damping.
/// A wedge whose opening near its corner is below double precision's resolution of the verdict
/// (a root within ~1e-11 of the circle on both sides) certifies walls only further out, up to
/// [`CONFIRM_REL`].
pub const SUPREMUM_REL: f64 = 1e-9;

/// Points of a wedge's interval tried toward its upper end: halving the distance to it 30
/// times reaches 1e-9 of the interval's width.
const WEDGE_STEPS: i32 = 30;

/// Relative distances are taken of K_max (of B*) but never of less than this fraction of the
/// region's size: a K_max of 0 or of rounding size (a corner at the wall-free point) is
/// confirmed at 1e-6 of 1 % of the region, where walls can be told apart from the corner.
const UNIT_FLOOR: f64 = 1e-2;

/// A stable interval's highest end agrees with the polygon's K_max when within this relative
/// distance (the polygon's chord tolerance is 1e-9 of the region; its maximum is refined on
/// the curve itself).
const AGREE_REL: f64 = 1e-9;

/// The confirmed K_max of a region or band.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ConfirmedMax {
    /// The largest stable stiffness (a supremum where `attained` is false), wall units.
    pub a: f64,
    /// The damping at which it is reached or approached, wall units.
    pub b: f64,
    /// True when stiffnesses up to K_max·(1 − 1e-6) are stable at `b` itself.
    pub attained: bool,
    /// A damping at which `a_stable` is stable: `b` when attained, else one beside it.
    pub b_stable: f64,
    /// A stiffness confirmed stable at `beta_stable` by the verdict: K_max·(1 − 1e-6) when
    /// attained, else the middle of the wedge's interval there (within 1e-9 of K_max where
    /// the wedge allows, at most 1e-6 below it).
    pub a_stable: f64,
}

/// K_max attained at b* by the verdict alone: (K_max − δ, b*) stable and (K_max + δ, b*) not,
/// with the candidate on the boundary curve (a vertex refined on its arc, within the chord
/// tolerance elsewhere). None when either side disagrees: the exact intervals at b* decide.
fn attained_locally(
    stable: &mut impl FnMut(f64, f64) -> bool,
    cand: WallPoint,
    delta: f64,
) -> Option<f64> {
    let b = cand.b;
    (stable(cand.a - delta, b) && !stable(cand.a + delta, b)).then_some(cand.a)
}

/// The highest finite end of the stable intervals at damping b.
fn top(fam: &AffineFamily, table: &CircleTable, b: f64) -> Option<f64> {
    stable_stiffness_intervals_tabulated(fam, table, b)
        .iter()
        .map(|iv| iv.hi)
        .filter(|h| h.is_finite())
        .reduce(f64::max)
}

/// Confirms a candidate K_max at damping b* (see the module doc), searching for the supremum's
/// stable damping within [b_lo, b_hi]; `scale` is the region's size (the unit of relative
/// distances where K_max is 0). None when the candidate contradicts the exact intervals or
/// the verdict.
pub fn confirm_max(
    fam: &AffineFamily,
    cand: WallPoint,
    band: (f64, f64),
    scale: f64,
) -> Option<ConfirmedMax> {
    confirm_max_tabulated(fam, &LazyCircleTable::new(fam), cand, band, scale)
}

/// [`confirm_max`] with the crossing scans taken from `table`, the [`CircleTable`] of `fam`
/// (the region keeps one for its slices and its confirmation; it is built only when the
/// local confirmation below does not settle K_max).
pub fn confirm_max_tabulated(
    fam: &AffineFamily,
    table: &LazyCircleTable,
    cand: WallPoint,
    (b_lo, b_hi): (f64, f64),
    scale: f64,
) -> Option<ConfirmedMax> {
    let unit = cand.a.abs().max(UNIT_FLOOR * scale).max(f64::MIN_POSITIVE);
    let mut coeffs = vec![0.0; fam.degree() + 1];
    // Every root inside the unit circle, certified (Schur–Cohn or the argument principle), as
    // the region's faces are classified: near a wedge's corner the walls confirmed inside may
    // lie within the marginal band that `check` reports walls by.
    let mut stable = |a: f64, b: f64| inside_unit_circle(fam, a, b, &mut coeffs) == Some(true);
    let delta = CONFIRM_REL * unit;
    let attained = |t: f64| ConfirmedMax {
        a: t,
        b: cand.b,
        attained: true,
        b_stable: cand.b,
        a_stable: t - delta,
    };
    if let Some(t) = attained_locally(&mut stable, cand, delta) {
        return Some(attained(t));
    }
    let table = table.get();
    let highest = top(fam, table, cand.b);
    if let Some(t) = highest.filter(|t| (t - cand.a).abs() <= AGREE_REL * unit) {
        if stable(t + delta, cand.b) {
            return None;
        }
        if stable(t - delta, cand.b) {
            return Some(attained(t));
        }
    }
    if highest.is_some_and(|t| t > cand.a + AGREE_REL * unit) {
        return None;
    }
    if stable(cand.a + delta, cand.b) {
        return None;
    }
    // Beside a corner the stable intervals shrink to the corner: the nearest damping (by
    // decades) with a stiffness in its interval within CONFIRM_REL of K_max and confirmed
    // stable, tried from the middle toward the upper end (a wedge whose other side is steep
    // has its middle far below the corner).
    // The supremum's stiffness is sought within CONFIRM_REL of K_max or of the region's size,
    // whichever is larger: a corner at the wall-free point of an undamped plant (K_max = 0,
    // approached as B → 0) has walls that double precision certifies only 1e-9 of the region
    // away from it.
    let floor = cand.a - CONFIRM_REL * cand.a.abs().max(scale);
    let b_unit = cand.b.abs().max(UNIT_FLOOR * scale).max(f64::MIN_POSITIVE);
    (3..=15)
        .rev()
        .flat_map(|k| [1.0, -1.0].map(|s| cand.b + s * b_unit * 10f64.powi(-k)))
        .filter(|&b| b >= b_lo && b <= b_hi)
        .find_map(|b| {
            stable_stiffness_intervals_tabulated(fam, table, b)
                .iter()
                .filter(|iv| iv.lo.is_finite() && iv.hi.is_finite() && iv.hi > iv.lo)
                .flat_map(|iv| (1..=WEDGE_STEPS).map(|j| iv.hi - (iv.hi - iv.lo) * 0.5f64.powi(j)))
                .find(|&m| m >= floor && m <= cand.a && stable(m, b))
                .map(|m| (b, m))
        })
        .map(|(b, m)| ConfirmedMax {
            a: cand.a,
            b: cand.b,
            attained: false,
            b_stable: b,
            a_stable: m,
        })
}
