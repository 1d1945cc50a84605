//! The analysis object: one [`Loop`] with its closed-loop family p(z) = P0 + a·PK + b·PB
//! (eq. 9, generalized), built once and asked every question the product answers — the
//! wall in the loop's units, the characteristic polynomial and the verdict at a wall, the
//! stable stiffness intervals at a damping, the stable region, K_max (at a damping, over a
//! band, the design query), the margins, passivity, the frequency response and the root
//! locus. The command line, the explorer and the Python package build a `System` from a
//! [`crate::loop_spec::LoopSpec`]'s loop and call these methods; the free functions of the
//! analysis modules ([`crate::kmax::kmax`], [`crate::answer`]) take a `&System` too.
//!
//! Everything is in the loop family's wall units (a, b) (α, β of Table I for the paper's
//! loop); convert with [`AffineFamily::to_physical`]. A loop with the paper's normalized view
//! ([`Loop::paper_view`]) is analysed through the paper's family (eq. 9 in (α, β)), formed
//! once here, as every command has always formed it.

use crate::boundary::{Interval, stable_stiffness_intervals};
use crate::closed_loop::AffineFamily;
use crate::error::Result;
use crate::kmax_band::{BandMax, k_max_band};
use crate::model::{Loop, PlantModel};
use crate::paper::NormalizedFamily;
use crate::params::{Physical, Sampling, Wall};
use crate::region::{ConfirmedMax, StableRegion, alpha_max_within, stable_region};
use crate::stability::Analysis;
use crate::verdict::{Decision, decide};

/// A loop and its closed-loop family, built once ([`System::new`]); every analysis of the
/// loop is a method here or a free function taking `&System`.
#[derive(Debug, Clone)]
pub struct System {
    lp: Loop,
    family: AffineFamily,
    paper: Option<NormalizedFamily>,
}

impl System {
    /// Discretize the loop (exact ZOH), close it (eq. 7–9) and, for the paper's loop, form
    /// the paper's family in (α, β) beside it.
    pub fn new(lp: Loop) -> Result<Self> {
        let family = AffineFamily::of_loop(&lp)?;
        let paper = lp
            .paper_view()
            .map(|pp| NormalizedFamily::new(pp, lp.delay.samples))
            .transpose()?;
        Ok(Self { lp, family, paper })
    }

    /// [`System::new`] on a copy of the loop.
    pub fn of(lp: &Loop) -> Result<Self> {
        Self::new(lp.clone())
    }

    /// The loop.
    pub fn lp(&self) -> &Loop {
        &self.lp
    }

    /// The closed-loop family p(z) = P0 + a·PK + b·PB in the loop's wall units.
    pub fn family(&self) -> &AffineFamily {
        &self.family
    }

    /// The family the verdict, the intervals and the region are computed in: the paper's
    /// family in (α, β) for the paper's loop, else [`System::family`] (both in the same wall
    /// units; convert with [`System::family`]'s [`AffineFamily::to_physical`]).
    pub fn verdict_family(&self) -> &AffineFamily {
        match &self.paper {
            Some(pf) => pf,
            None => &self.family,
        }
    }

    /// The wall in the family's units (a, b): for the paper's loop the (α, β) of Table I
    /// exactly as [`Physical::normalized`] forms them (α = KT²/m, β = BT/m), so that every
    /// front end reports the same α and β; otherwise (K/k_u, B/(k_u T))
    /// ([`AffineFamily::to_units`]).
    pub fn wall_units(&self, w: Wall) -> Result<(f64, f64)> {
        match self.paper {
            Some(_) => paper_units(&self.lp, w),
            None => Ok(self.family.to_units(w.stiffness, w.damping)),
        }
    }

    /// `System::new(lp)?.decide(wall_units(w))` without forming the parts of the System the
    /// verdict does not need (one family instead of two for the paper's loop): for the many
    /// plants of a population or a robust search. The same family, units and verdict.
    pub fn decide_wall(lp: &Loop, w: Wall) -> Result<Decision> {
        match lp.paper_view() {
            Some(pp) => {
                let pf = NormalizedFamily::new(pp, lp.delay.samples)?;
                let (a, b) = paper_units(lp, w)?;
                Ok(decide(&pf, a, b, &mut pf.coefficients(a, b)))
            }
            None => {
                let fam = AffineFamily::of_loop(lp)?;
                let (a, b) = fam.to_units(w.stiffness, w.damping);
                Ok(decide(&fam, a, b, &mut fam.coefficients(a, b)))
            }
        }
    }

    /// A wall damping B in Ns/m in the family's units b, formed as [`System::wall_units`]
    /// forms it (β = BT/m for the paper's loop), so that K_max at a damping and the check of
    /// a wall at that damping see the same b.
    pub fn damping_units(&self, wall_damping: f64) -> Result<f64> {
        let w = Wall {
            stiffness: 0.0,
            damping: wall_damping,
        };
        Ok(self.wall_units(w)?.1)
    }

    /// The ascending coefficients of p(z) (eq. 9, generalized) for a wall in the family's
    /// units; for the paper's loop through the paper's family in (α, β).
    pub fn characteristic(&self, (a, b): (f64, f64)) -> Vec<f64> {
        match &self.paper {
            Some(pf) => pf.coefficients(a, b),
            None => self.family.coefficients(a, b),
        }
    }

    /// The full stability answer (verdict, spectral radius, roots) for a wall in the family's
    /// units ([`Analysis::of_family`], Section V); for the paper's loop through the paper's
    /// family.
    pub fn analysis(&self, (a, b): (f64, f64)) -> Result<Analysis> {
        match &self.paper {
            Some(pf) => Analysis::of_family(pf, a, b),
            None => Analysis::of_family(&self.family, a, b),
        }
    }

    /// The verdict alone of a wall in the family's units ([`decide`]: Schur–Cohn, the
    /// argument principle where that is not sure), without the roots; for the paper's loop
    /// through the paper's family, as [`System::analysis`] decides it.
    pub fn decide(&self, (a, b): (f64, f64)) -> Decision {
        let fam = self.verdict_family();
        decide(fam, a, b, &mut fam.coefficients(a, b))
    }

    /// Stable intervals lo < a < hi of the wall's stiffness at fixed damping b, in wall
    /// units (Section V).
    pub fn stable_intervals(&self, b: f64) -> Vec<Interval> {
        match &self.paper {
            Some(pf) => stable_stiffness_intervals(pf, b),
            None => stable_stiffness_intervals(&self.family, b),
        }
    }

    /// The stable region in the wall plane, in wall units (Section V, Figs. 4–6).
    pub fn region(&self) -> Result<StableRegion> {
        match &self.paper {
            Some(pf) => stable_region(pf),
            None => stable_region(&self.family),
        }
    }

    /// K_max at a fixed damping b (wall units): the stable stiffness interval with the
    /// largest upper end (Section V); None when no stiffness is stable at that damping.
    pub fn k_max_at_damping(&self, b: f64) -> Option<Interval> {
        highest_interval(&self.stable_intervals(b)).copied()
    }

    /// K_max with the damping restricted to the band b_lo ≤ b ≤ b_hi (wall units; either end
    /// may be infinite), and the damping that reaches it, confirmed by the exact intervals
    /// and the verdict beside it (a supremum says so and where it is approached): from the
    /// D-decomposition's candidates without the region's polygon ([`k_max_band`]), and from
    /// the region ([`alpha_max_within`]) where those do not settle it. None when nothing in
    /// the band is stable.
    pub fn k_max_within(&self, b_lo: f64, b_hi: f64) -> Result<Option<ConfirmedMax>> {
        let fast = match &self.paper {
            Some(pf) => k_max_band(pf, b_lo, b_hi),
            None => k_max_band(&self.family, b_lo, b_hi),
        };
        match fast {
            BandMax::Max(m) => Ok(Some(m)),
            BandMax::NoneStable => Ok(None),
            BandMax::Undecided => self.k_max_within_region(&self.region()?, b_lo, b_hi),
        }
    }

    /// [`System::k_max_within`] on the loop's region already computed ([`System::region`]),
    /// for several bands of one loop.
    pub fn k_max_within_region(
        &self,
        r: &StableRegion,
        b_lo: f64,
        b_hi: f64,
    ) -> Result<Option<ConfirmedMax>> {
        match &self.paper {
            Some(pf) => alpha_max_within(pf, r, b_lo, b_hi),
            None => alpha_max_within(&self.family, r, b_lo, b_hi),
        }
    }

    /// The linear condition (22) K < (b + B)/(t_d + T/2) in N/m for the paper's loop in
    /// physical units (Section VI); None for other loops.
    pub fn linear_k(&self, wall_damping: f64) -> Option<f64> {
        self.paper.as_ref()?;
        let PlantModel::MassSpringDamper(e) = &self.lp.plant.model else {
            return None;
        };
        let wall = Wall {
            stiffness: 0.0,
            damping: wall_damping,
        };
        let sampling = Sampling::new(self.lp.period, self.lp.delay.samples).ok()?;
        let p = Physical::new(*e, wall, sampling).ok()?;
        Some(crate::paper::linear::linear_stiffness_limit(&p))
    }
}

/// The paper's (α, β) of a wall (Table I) exactly as [`Physical::normalized`] forms them, for a
/// loop with the paper's view.
fn paper_units(lp: &Loop, w: Wall) -> Result<(f64, f64)> {
    let PlantModel::MassSpringDamper(e) = &lp.plant.model else {
        return Err(crate::error::Error::Invalid {
            param: crate::param::Param::Operator,
            reason: "the paper's units need a mass-spring-damper plant".into(),
        });
    };
    let sampling = Sampling::new(lp.period, lp.delay.samples)?;
    let n = Physical::new(*e, w, sampling)?.normalized()?;
    Ok((n.alpha, n.beta))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Effective;

    fn paper_system() -> System {
        System::new(Loop::paper(Effective::new(1.1, 7.5, 350.0).unwrap(), 1e-3, 1).unwrap())
            .unwrap()
    }

    #[test]
    fn k_max_within_a_band() {
        let sys = paper_system();
        let r = sys.region().unwrap();
        let b_star = r.b_at_a_max;
        // a band holding the overall maximum gives the region's (to rounding: the band's
        // K_max comes without the polygon)
        let p = sys.k_max_within(0.0, 2.0 * b_star).unwrap().unwrap();
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs();
        assert!(close(p.a, r.a_max) && close(p.b, b_star), "{p:?} vs {r:?}");
        // a band below it is limited by its upper edge, where K_max at that damping holds
        let p = sys.k_max_within(0.0, 0.5 * b_star).unwrap().unwrap();
        let at_edge = sys.k_max_at_damping(0.5 * b_star).unwrap();
        assert!(p.a < r.a_max);
        assert_eq!((p.a, p.b), (at_edge.hi, 0.5 * b_star));
        // no stable wall with a damping beyond the region
        assert!(sys.k_max_within(10.0, 20.0).unwrap().is_none());
    }

    #[test]
    fn wall_units_of_the_paper_loop_are_table_one() {
        let sys = paper_system();
        let w = Wall {
            stiffness: 2000.0,
            damping: 3.0,
        };
        let (a, b) = sys.wall_units(w).unwrap();
        assert_eq!((a, b), (2000.0 * 1e-3 * 1e-3 / 1.1, 3.0 * 1e-3 / 1.1));
        assert_eq!(sys.damping_units(3.0).unwrap(), b);
    }
}
