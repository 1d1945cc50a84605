//! Nyquist frequency, robust stability and passivity (Section VIII, eq. 25–28, Figs. 8–10,
//! Remark 4), and a robust design across a range of human arms (beyond the paper).
//!
//! A mass-spring-damper oscillates at ω = √(k/m − b²/(4m²)) (eq. 25; the paper prints the
//! second term as b²/4m, which is not dimensionally consistent; eq. 26 is the consistent
//! form), i.e. ω = √(γ − δ²/4)/T (eq. 26), and reaches the Nyquist frequency π/T at
//! γ_N = π² + δ²/4 (eq. 27).
//!
//! # Robustly stable regions
//!
//! The robustly stable region over a γ-interval is the intersection of the stable regions
//! for every γ in it. It is computed slice by slice in β: at fixed β the stable α-set of each
//! γ is a union of intervals, exact by D-decomposition
//! ([`crate::boundary::stable_stiffness_intervals`]); the robust α-set is their intersection. The
//! γ-interval is sampled uniformly (endpoints included) and, when the intersection is one
//! interval, its ends are refined by a golden-section search in γ between the neighbours of
//! the worst sample (the ends of the stable interval are smooth in γ between the points where
//! a different boundary piece takes over). The robust set is thus approached from outside; the
//! tests compare it with a four times denser γ grid. The region polygon is built from the
//! slice ends on a β grid that is refined where the ends bend (vertices are exact boundary
//! points, edges are chords) and whose extreme β are located by bisection. No polygon
//! boolean library is needed, and every number stays an exact per-β computation.
//!
//! # Degenerate plants
//!
//! For δ = 0 and γ = (jπ)², j = 1, 2, …, the plant's poles and a zero of N(z) meet on the unit
//! circle (at z = −1 for odd j, z = 1 for even j) and p(z) keeps that root for every (α, β):
//! every point is at best limit stable (Section VIII-B, last paragraph). There the strict
//! stable region is empty; [`region_summary`] reports `degenerate`, and the robust region
//! takes the limit from inside the γ-interval instead (reported in `degenerate_gammas`).
//!
//! The module holds one concept per file: the oscillation frequency and Remark 4
//! (`frequency`), the degenerate plants (`degenerate`), Colgate's passive region and its
//! place in a robust region (`passive`), the summary of one stable region and its sweep
//! over γ (`summary`), the robust α-set at one β (`slice`), the robust region over a
//! γ-interval (`robust`), the robust K_max over a box of plants (`plant_box`), and the
//! one-dimensional searches they share (`search`).

use std::sync::atomic::{AtomicUsize, Ordering};

mod degenerate;
mod frequency;
mod passive;
mod plant_box;
mod robust;
mod search;
mod section;
mod slice;
mod summary;

pub use degenerate::{DEGENERATE_OFFSET, DEGENERATE_TOL, unit_circle_pole};
pub use frequency::{
    NyquistStiffness, normalized_frequency, nyquist_gamma, nyquist_stiffness, oscillation_frequency,
};
pub use passive::{
    PASSIVE_END_GAP, PassiveCheck, PassiveRegion, passive_inside_robust,
    passive_inside_robust_with_progress, passive_region,
};
pub use plant_box::{
    BoxOptions, PlantBox, RobustKmax, robust_kmax, robust_kmax_with_progress,
    robust_stiffness_interval,
};
pub use robust::{
    GammaRange, RobustOptions, RobustRegion, RobustSlice, polygon_area, robust_region,
    robust_region_with_progress,
};
pub use section::{
    ALPHA_ROUNDOFF, NyquistRegions, PASSIVE_SAMPLES, PassiveOut, RobustOut, SweepInput, SweepRow,
    nyquist_regions,
};
pub use summary::{
    RegionSummary, beta_bound, gamma_sweep, gamma_sweep_with_progress, region_summary,
};

/// A progress callback of a long analysis: called, possibly from worker threads, with the
/// number of its steps done so far (each function documents what a step is).
pub type Progress<'a> = &'a (dyn Fn(usize) + Sync);

/// A progress callback that does nothing.
pub fn no_progress(_: usize) {}

/// Counts finished steps across threads and reports each new count.
struct Ticker<'a> {
    done: AtomicUsize,
    progress: Progress<'a>,
}

impl<'a> Ticker<'a> {
    fn new(progress: Progress<'a>) -> Self {
        Self {
            done: AtomicUsize::new(0),
            progress,
        }
    }

    fn tick(&self) {
        (self.progress)(self.done.fetch_add(1, Ordering::Relaxed) + 1);
    }
}
