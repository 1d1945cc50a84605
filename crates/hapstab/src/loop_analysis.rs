//! The answers every front end gives about one [`Loop`] and its wall, computed once here so
//! that the command line, the explorer and the Python package report the same numbers: the
//! wall in the loop's units, the characteristic polynomial at a wall, the stable stiffness
//! intervals at a damping, the stable region, K_max (overall, at a damping, or over a damping
//! band) and the paper's linear condition (22).
//!
//! Everything is in the loop family's wall units (a, b) (α, β of Table I for the paper's
//! loop); convert with [`AffineFamily::to_physical`]. A loop with the paper's normalized view
//! ([`Loop::paper_view`]) is analysed through the paper's family (eq. 9 in (α, β)), as every
//! command has always formed it.

use crate::boundary::{Interval, stable_alpha_intervals};
use crate::closed_loop::{AffineFamily, PolyFamily};
use crate::error::Result;
use crate::kmax_band::{BandMax, k_max_band};
use crate::model::{Loop, PlantModel};
use crate::params::{Physical, Sampling, Wall};
use crate::region::{ConfirmedMax, StableRegion, alpha_max_within, stable_region};
use crate::stability::Analysis;

/// The paper's family of a loop that has the normalized view (eq. 9 in (α, β)); its (α, β)
/// are the loop family's wall units (a, b).
fn paper_family(lp: &Loop) -> Result<Option<PolyFamily>> {
    lp.paper_view()
        .map(|pp| PolyFamily::new(pp, lp.delay.samples))
        .transpose()
}

/// Stable intervals lo < a < hi of the wall's stiffness at fixed damping b, in wall units
/// (Section V).
pub fn stable_intervals(lp: &Loop, fam: &AffineFamily, b: f64) -> Result<Vec<Interval>> {
    Ok(match paper_family(lp)? {
        Some(pf) => stable_alpha_intervals(&pf, b),
        None => stable_alpha_intervals(fam, b),
    })
}

/// The stable region in the wall plane, in wall units (Section V, Figs. 4–6).
pub fn region(lp: &Loop, fam: &AffineFamily) -> Result<StableRegion> {
    Ok(match paper_family(lp)? {
        Some(pf) => stable_region(&pf)?,
        None => stable_region(fam)?,
    })
}

/// The stable interval that contains a, or else the one reaching furthest (largest upper
/// end); None when there is none.
pub fn pick_interval(ivs: &[Interval], a: f64) -> Option<Interval> {
    ivs.iter()
        .find(|iv| iv.lo < a && a < iv.hi)
        .or_else(|| highest_interval(ivs))
        .copied()
}

fn highest_interval(ivs: &[Interval]) -> Option<&Interval> {
    ivs.iter().max_by(|x, y| x.hi.total_cmp(&y.hi))
}

/// K_max at a fixed damping b (wall units): the stable stiffness interval with the largest
/// upper end (Section V); None when no stiffness is stable at that damping.
pub fn k_max_at_damping(lp: &Loop, fam: &AffineFamily, b: f64) -> Result<Option<Interval>> {
    Ok(highest_interval(&stable_intervals(lp, fam, b)?).copied())
}

/// K_max with the damping restricted to the band b_lo ≤ b ≤ b_hi (wall units; either end may
/// be infinite), and the damping that reaches it, confirmed by the exact intervals and the
/// verdict beside it (a supremum says so and where it is approached): from the
/// D-decomposition's candidates without the region's polygon ([`k_max_band`]), and from the
/// region ([`alpha_max_within`]) where those do not settle it. None when nothing in the band
/// is stable.
pub fn k_max_within(
    lp: &Loop,
    fam: &AffineFamily,
    b_lo: f64,
    b_hi: f64,
) -> Result<Option<ConfirmedMax>> {
    let fast = match paper_family(lp)? {
        Some(pf) => k_max_band(&pf, b_lo, b_hi),
        None => k_max_band(fam, b_lo, b_hi),
    };
    match fast {
        BandMax::Max(m) => Ok(Some(m)),
        BandMax::NoneStable => Ok(None),
        BandMax::Undecided => k_max_within_region(lp, fam, &region(lp, fam)?, b_lo, b_hi),
    }
}

/// [`k_max_within`] on the loop's region already computed ([`region`]), for several bands of
/// one loop.
pub fn k_max_within_region(
    lp: &Loop,
    fam: &AffineFamily,
    r: &StableRegion,
    b_lo: f64,
    b_hi: f64,
) -> Result<Option<ConfirmedMax>> {
    match paper_family(lp)? {
        Some(pf) => alpha_max_within(&pf, r, b_lo, b_hi),
        None => alpha_max_within(fam, r, b_lo, b_hi),
    }
}

/// The linear condition (22) K < (b + B)/(t_d + T/2) in N/m for the paper's loop in physical
/// units (Section VI); None for other loops.
pub fn linear_k(lp: &Loop, wall_damping: f64) -> Option<f64> {
    lp.paper_view()?;
    let PlantModel::MassSpringDamper(e) = &lp.plant.model else {
        return None;
    };
    let wall = Wall {
        stiffness: 0.0,
        damping: wall_damping,
    };
    let sampling = Sampling::new(lp.period, lp.delay.samples).ok()?;
    let p = Physical::new(*e, wall, sampling).ok()?;
    Some(crate::linear::linear_stiffness_limit(&p))
}

/// The wall in the family's units (a, b): for the paper's loop the (α, β) of Table I exactly
/// as [`Physical::normalized`] forms them (α = KT²/m, β = BT/m), so that every front end
/// reports the same α and β; otherwise (K/k_u, B/(k_u T)) ([`AffineFamily::to_units`]).
pub fn wall_units(lp: &Loop, fam: &AffineFamily, w: Wall) -> Result<(f64, f64)> {
    if let (Some(_), PlantModel::MassSpringDamper(e)) = (lp.paper_view(), &lp.plant.model) {
        let sampling = Sampling::new(lp.period, lp.delay.samples)?;
        let n = Physical::new(*e, w, sampling)?.normalized()?;
        return Ok((n.alpha, n.beta));
    }
    Ok(fam.to_units(w.stiffness, w.damping))
}

/// A wall damping B in Ns/m in the family's units b, formed as [`wall_units`] forms it (β =
/// BT/m for the paper's loop), so that K_max at a damping and the check of a wall at that
/// damping see the same b.
pub fn damping_units(lp: &Loop, fam: &AffineFamily, wall_damping: f64) -> Result<f64> {
    let w = Wall {
        stiffness: 0.0,
        damping: wall_damping,
    };
    Ok(wall_units(lp, fam, w)?.1)
}

/// The ascending coefficients of p(z) (eq. 9, generalized) for a wall in the family's units;
/// for the paper's loop through the paper's family in (α, β).
pub fn characteristic(lp: &Loop, fam: &AffineFamily, (a, b): (f64, f64)) -> Result<Vec<f64>> {
    Ok(match paper_family(lp)? {
        Some(pf) => pf.coefficients(a, b),
        None => fam.coefficients(a, b),
    })
}

/// The full stability answer (verdict, spectral radius, roots) for a wall in the family's
/// units ([`Analysis::of_family`], Section V); for the paper's loop through the paper's family.
pub fn analysis(lp: &Loop, fam: &AffineFamily, (a, b): (f64, f64)) -> Result<Analysis> {
    match paper_family(lp)? {
        Some(pf) => Analysis::of_family(&pf, a, b),
        None => Analysis::of_family(fam, a, b),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Effective;

    fn paper_loop() -> Loop {
        Loop::paper(Effective::new(1.1, 7.5, 350.0).unwrap(), 1e-3, 1).unwrap()
    }

    #[test]
    fn k_max_within_a_band() {
        let lp = paper_loop();
        let fam = AffineFamily::of_loop(&lp).unwrap();
        let r = region(&lp, &fam).unwrap();
        let b_star = r.beta_at_alpha_max;
        // a band holding the overall maximum gives the region's (to rounding: the band's
        // K_max comes without the polygon)
        let p = k_max_within(&lp, &fam, 0.0, 2.0 * b_star).unwrap().unwrap();
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs();
        assert!(
            close(p.alpha, r.alpha_max) && close(p.beta, b_star),
            "{p:?} vs {r:?}"
        );
        // a band below it is limited by its upper edge, where K_max at that damping holds
        let p = k_max_within(&lp, &fam, 0.0, 0.5 * b_star).unwrap().unwrap();
        let at_edge = k_max_at_damping(&lp, &fam, 0.5 * b_star).unwrap().unwrap();
        assert!(p.alpha < r.alpha_max);
        assert_eq!((p.alpha, p.beta), (at_edge.hi, 0.5 * b_star));
        // no stable wall with a damping beyond the region
        assert!(k_max_within(&lp, &fam, 10.0, 20.0).unwrap().is_none());
    }

    #[test]
    fn wall_units_of_the_paper_loop_are_table_one() {
        let lp = paper_loop();
        let fam = AffineFamily::of_loop(&lp).unwrap();
        let w = Wall {
            stiffness: 2000.0,
            damping: 3.0,
        };
        let (a, b) = wall_units(&lp, &fam, w).unwrap();
        assert_eq!((a, b), (2000.0 * 1e-3 * 1e-3 / 1.1, 3.0 * 1e-3 / 1.1));
        assert_eq!(damping_units(&lp, &fam, 3.0).unwrap(), b);
    }
}
