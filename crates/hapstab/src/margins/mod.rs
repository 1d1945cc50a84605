//! Stability margins of a virtual wall on any loop, in the conventions of MATLAB's
//! `allmargin` and python-control's `stability_margins`, computed on the exact discrete loop
//! ([`crate::zoh`]) so that they hold for the sampled system.
//!
//! The open loop is L = (K·PK + B·PB)/P0 (the characteristic equation 1 + L = 0, eq. 7–9):
//! scaling the wall (K, B) by g scales L by g. Hence
//!
//! - **gain margin** (`gain_margin`, `gain_margin_lower`): the factors g > 1 and g < 1 on
//!   (K, B) together that reach the stability boundary — python-control's `gm` is the first,
//!   read at a **phase crossover** (L real and negative, `phase_crossover_hz`); both are the
//!   ends of the exact stable interval along the ray through the wall (Section V's
//!   D-decomposition, [`crate::boundary::line_crossings`]);
//! - **stiffness margin** (`stiffness_margin`, `stiffness_margin_lower`): the same on K alone
//!   at the given B, the ends of the stable K interval;
//! - **phase margin** at every **gain crossover** |L(e^{iθ})| = 1 ([`frequency::gain_scan`]:
//!   a grid that resolves every mode, so no crossover is lost), 180° + arg L; the reported one
//!   is the smallest in magnitude, as python-control reports it;
//! - **delay margin**, exact ([`delay::delay_margin`]): the smallest added delay, any fraction
//!   of a sample, at which a root reaches the unit circle — and beside it the MATLAB-style
//!   figure PM/ω_c, which ignores that a fractional delay also changes |L|;
//! - **stability margin** (modulus margin) min |1 + L|, the distance of the Nyquist curve to
//!   −1 (python-control's `sm`).
//!
//! Margins are defined for stable walls only; for a wall that is not stable every margin is
//! absent. The stability test is the verdict's own ([`crate::verdict`]).

pub mod delay;
pub mod fraction;
pub mod frequency;
pub mod report;

use serde::Serialize;

use crate::boundary::{CircleTable, WallLine, WallPoint, line_crossings_tabulated, stable_between};
use crate::closed_loop::AffineFamily;
use crate::error::Result;
use crate::model::Loop;
use crate::params::{MAX_DELAY, Wall};
use crate::verdict::stable as verdict_stable;
use crate::zoh::DiscreteLoop;
use fraction::FractionLoop;

pub use delay::{DelayScan, delay_margin, delay_scan};
pub use frequency::{
    GainCrossover, GainScan, frequency_grid, gain_scan, gain_scan_tabulated, loop_value,
    margin_grid, stability_margin, stability_margin_tabulated, wrap_degrees,
};

/// θ samples per degree of p for the certified delay scan's robustness bound.
pub(crate) const SAMPLES_PER_DEGREE: usize = 256;

/// A margin as a factor, and where the boundary is met.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GainMargin {
    /// The factor that puts the wall on the boundary (> 1 upward, < 1 downward).
    pub factor: f64,
    /// Angle θ ∈ [0, π] of the root on the unit circle there.
    pub theta: f64,
    /// θ/(2πT) in Hz.
    pub frequency_hz: f64,
}

/// The phase margin at one gain crossover.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhaseMargin {
    /// 180° + arg L(e^{iθ}) in degrees, in (−180, 180].
    pub degrees: f64,
    /// The crossover angle θ.
    pub theta: f64,
    /// θ/(2πT) in Hz.
    pub frequency_hz: f64,
}

/// The delay margin and the oscillation that sets in there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DelayMargin {
    /// The extra delay in seconds that brings the loop to the boundary.
    pub seconds: f64,
    /// The angle of the root pair on the unit circle at that delay.
    pub theta: f64,
    /// θ/(2πT) in Hz.
    pub frequency_hz: f64,
}

/// The stability (modulus) margin min |1 + L|.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StabilityMargin {
    /// min over θ of |1 + L(e^{iθ})|.
    pub value: f64,
    /// Where it is reached.
    pub theta: f64,
    /// θ/(2πT) in Hz.
    pub frequency_hz: f64,
}

/// The kind of a crossing of the open loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CrossingKind {
    /// |L| = 1: a phase margin is read here; `value` is that phase margin in degrees.
    Gain,
    /// L real (phase −180°, or 0° for `value` < 0): a gain margin is read here; `value` is
    /// the factor on (K, B) that puts a root on the circle (1/|L| with the sign of −L).
    Phase,
}

/// One crossing of the open loop, as MATLAB's `allmargin` lists them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Crossing {
    /// Gain or phase crossover.
    pub kind: CrossingKind,
    /// The angle θ ∈ [0, π].
    pub theta: f64,
    /// θ/(2πT) in Hz.
    pub frequency_hz: f64,
    /// The phase margin (degrees) at a gain crossover, the gain factor at a phase crossover.
    pub value: f64,
}

/// The margins of one wall. Each is None when the wall is not stable, or when no finite
/// margin exists (see `notes`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Margins {
    /// True iff the verdict says stable; otherwise no margin is given.
    pub stable: bool,
    /// Factor > 1 on (K, B) together to the boundary (the loop's gain margin).
    pub gain: Option<GainMargin>,
    /// Factor < 1 on (K, B) together to the boundary (None when the ray is stable to 0).
    pub gain_lower: Option<GainMargin>,
    /// Factor > 1 on K alone at the given B.
    pub stiffness: Option<GainMargin>,
    /// Factor < 1 on K alone at the given B (None when stable down to K = 0 and beyond).
    pub stiffness_lower: Option<GainMargin>,
    /// The phase margin smallest in magnitude over the gain crossovers.
    pub phase: Option<PhaseMargin>,
    /// The exact delay margin.
    pub delay: Option<DelayMargin>,
    /// min PM/ω_c over the gain crossovers, seconds (MATLAB's figure for a pure delay).
    pub delay_pm_over_wc: Option<f64>,
    /// When the delay scan stopped at its work bound before a crossing: the added delay in
    /// seconds up to which the loop was shown stable (the margin is at least this).
    pub delay_at_least: Option<f64>,
    /// min |1 + L|.
    pub stability_margin: Option<StabilityMargin>,
    /// max |L| over frequency and where (Hz).
    pub peak_gain: Option<(f64, f64)>,
    /// Every gain and phase crossover, in increasing frequency.
    pub crossings: Vec<Crossing>,
    /// Why a margin is absent, in words.
    pub notes: Vec<String>,
}

impl Margins {
    /// No margins, with one reason.
    fn withheld(stable: bool, note: &str) -> Self {
        Margins {
            stable,
            gain: None,
            gain_lower: None,
            stiffness: None,
            stiffness_lower: None,
            phase: None,
            delay: None,
            delay_pm_over_wc: None,
            delay_at_least: None,
            stability_margin: None,
            peak_gain: None,
            crossings: Vec::new(),
            notes: vec![note.to_string()],
        }
    }
}

/// Why every margin is withheld beside a verdict that is not stable.
pub const NOT_STABLE_NOTE: &str = "the wall is not stable: margins are defined for stable walls";

/// Computes every margin of a physical wall on a loop (module doc).
pub fn margins(lp: &Loop, wall: Wall) -> Result<Margins> {
    let dl = lp.discretize()?;
    let fam = AffineFamily::new(&dl);
    let (a, b) = fam.to_units(wall.stiffness, wall.damping);
    if !verdict_stable(&fam, a, b, &mut fam.coefficients(a, b)) {
        return Ok(Margins::withheld(false, NOT_STABLE_NOTE));
    }
    margins_of_stable(lp, &dl, &fam, wall)
}

/// The margins reported beside a stability verdict (what `check` and the Python package
/// print): none, with the reason in `notes`, when the verdict is not stable; otherwise every
/// margin of the module doc. `stable` is the verdict's ([`crate::verdict::decide`]).
pub fn margins_beside_verdict(lp: &Loop, wall: Wall, stable: bool) -> Result<Margins> {
    if !stable {
        return Ok(Margins::withheld(false, NOT_STABLE_NOTE));
    }
    let dl = lp.discretize()?;
    margins_of_stable(lp, &dl, &AffineFamily::new(&dl), wall)
}

/// Every margin of a wall that the verdict calls stable, on the loop's family: the margins
/// read on the frequency response, then the delay margin (they share the loop's
/// [`frequency_grid`]), side by side on two threads (about a fifth faster at order 6 and
/// d = 10 than one after the other; the two take comparable time).
fn margins_of_stable(
    lp: &Loop,
    dl: &DiscreteLoop,
    fam: &AffineFamily,
    wall: Wall,
) -> Result<Margins> {
    if rayon::current_thread_index().is_none() {
        // enter the thread pool once, not at every join below (each entry from outside
        // wakes a worker and waits on it)
        return rayon::join(|| margins_of_stable(lp, dl, fam, wall), || ()).0;
    }
    let (a, b) = fam.to_units(wall.stiffness, wall.damping);
    // the fraction loop's own part is built while the loop's grid is found; then the
    // frequency response's margins and the delay margin run side by side
    let (modes, fraction_loop) = rayon::join(
        || frequency_grid(fam, a, b),
        || FractionLoop::unjoined(lp, dl, a, b),
    );
    let fraction_loop = fraction_loop?.joined(&modes);
    let ((mut out, scan), delay) = rayon::join(
        || frequency_margins(lp, fam, (a, b), &modes),
        || delay::delay_margin_with(lp, wall, &fraction_loop),
    );
    out.delay_pm_over_wc = delay::pm_over_wc(&scan, lp.period);
    delay_note(&mut out, delay?);
    Ok(out)
}

/// The margins read on the loop's frequency response (all but the delay margin), with the
/// gain scan they came from; `modes` is the loop's [`frequency_grid`].
fn frequency_margins(
    lp: &Loop,
    fam: &AffineFamily,
    (a, b): (f64, f64),
    modes: &[f64],
) -> (Margins, GainScan) {
    let p = WallPoint { a, b };
    let hz = |theta: f64| theta / (2.0 * std::f64::consts::PI * lp.period);
    let table = CircleTable::on(fam, margin_grid(fam, modes));
    // the factors on two lines and the readings of the response, side by side on one table
    let ((ray, axis), (scan, (sm, sm_theta))) = rayon::join(
        || {
            rayon::join(
                || {
                    (!(a == 0.0 && b == 0.0))
                        .then(|| factors(fam, &table, &WallLine::ray(p), 1.0, hz))
                },
                || (a != 0.0).then(|| factors(fam, &table, &WallLine::stiffness_axis(b), a, hz)),
            )
        },
        || {
            (
                gain_scan_tabulated(fam, a, b, &table),
                stability_margin_tabulated(fam, a, b, &table),
            )
        },
    );
    let mut out = Margins::withheld(true, "");
    out.notes.clear();
    put_factors(&mut out, ray.as_ref(), axis.as_ref());
    put_gain_scan(&mut out, &scan, hz);
    out.stability_margin = sm.is_finite().then(|| StabilityMargin {
        value: sm,
        theta: sm_theta,
        frequency_hz: hz(sm_theta),
    });
    (out, scan)
}

/// The gain and stiffness margins from the factors along the ray through the wall and along
/// the K axis (None where the wall has no such line), with the notes for unbounded ones.
fn put_factors(out: &mut Margins, ray: Option<&Factors>, axis: Option<&Factors>) {
    if let Some(r) = ray {
        (out.gain, out.gain_lower) = (r.upper, r.lower);
        out.crossings = r.crossings.clone();
    }
    if let Some(k) = axis {
        (out.stiffness, out.stiffness_lower) = (k.upper, k.lower);
    }
    if out.gain.is_none() {
        out.notes.push(if ray.is_none() {
            "K = B = 0: no factor on the wall changes it".into()
        } else {
            "no factor on (K, B) makes the wall unstable (gain margin unbounded)".into()
        });
    }
    if axis.is_none() {
        out.notes
            .push("K = 0: no factor on K changes the wall".into());
    } else if out.stiffness.is_none() {
        out.notes
            .push("no factor on K makes the wall unstable (stiffness margin unbounded)".into());
    }
}

/// The peak gain, the gain crossovers (joined to the crossings in increasing frequency) and
/// the phase margin smallest in magnitude over them, from the gain scan.
fn put_gain_scan(out: &mut Margins, scan: &GainScan, hz: impl Fn(f64) -> f64) {
    out.peak_gain = scan
        .peak
        .1
        .is_finite()
        .then(|| (scan.peak.0, hz(scan.peak.1)));
    out.crossings
        .extend(scan.crossovers.iter().map(|c| Crossing {
            kind: CrossingKind::Gain,
            theta: c.theta,
            frequency_hz: hz(c.theta),
            value: c.phase_margin_deg,
        }));
    out.crossings.sort_by(|x, y| x.theta.total_cmp(&y.theta));
    out.phase = scan
        .crossovers
        .iter()
        .min_by(|x, y| {
            x.phase_margin_deg
                .abs()
                .total_cmp(&y.phase_margin_deg.abs())
        })
        .map(|c| PhaseMargin {
            degrees: c.phase_margin_deg,
            theta: c.theta,
            frequency_hz: hz(c.theta),
        });
    if out.phase.is_none() {
        out.notes.push(format!(
            "|L| never crosses 1 (max |L| = {:.4}): no gain crossover, phase margin unbounded",
            scan.peak.0
        ));
    }
}

/// The delay margin's outcome into the margins and their notes.
fn delay_note(out: &mut Margins, delay: DelayScan) {
    match delay {
        DelayScan::Crossing(d) => out.delay = Some(d),
        DelayScan::SmallGain(gain) => out.notes.push(format!(
            "stable for every added delay: |L| ≤ {gain:.4} < 1 at every frequency and every \
             fraction of a sample (small gain)"
        )),
        DelayScan::StableUpToMax => out.notes.push(format!(
            "stable for every added delay up to the largest modelled delay ({MAX_DELAY} samples)"
        )),
        DelayScan::AtLeast(seconds) => {
            out.delay_at_least = Some(seconds);
            out.notes.push(format!(
                "delay margin undecided beyond {seconds:.6e} s: the scan stopped at its work \
                 bound without a crossing (the margin is at least that)"
            ));
        }
    }
}

/// The two factors along a line through the wall, and the line's crossings.
struct Factors {
    upper: Option<GainMargin>,
    lower: Option<GainMargin>,
    crossings: Vec<Crossing>,
}

/// The factors that reach the boundary along `line` from the wall at parameter t0 (the ends
/// of the exact stable interval containing t0, divided by t0: upward the end away from t = 0,
/// downward the end toward it when it lies on the same side of 0), and every crossing of the
/// line as a phase crossover with its factor t/t0.
fn factors(
    fam: &AffineFamily,
    table: &CircleTable,
    line: &WallLine,
    t0: f64,
    hz: impl Fn(f64) -> f64,
) -> Factors {
    let crossings = line_crossings_tabulated(fam, table, line);
    let ivs = stable_between(fam, line, &crossings);
    let margin = |end: f64| -> Option<GainMargin> {
        let theta = crossings.iter().find(|c| c.t == end)?.theta;
        (end.is_finite() && end / t0 > 0.0).then(|| GainMargin {
            factor: end / t0,
            theta,
            frequency_hz: hz(theta),
        })
    };
    let iv = ivs.iter().find(|iv| iv.lo < t0 && t0 < iv.hi);
    let (away, toward) = match iv {
        Some(iv) if t0 > 0.0 => (iv.hi, iv.lo),
        Some(iv) => (iv.lo, iv.hi),
        None => (f64::NAN, f64::NAN),
    };
    Factors {
        upper: margin(away),
        lower: margin(toward),
        crossings: crossings
            .iter()
            .map(|c| Crossing {
                kind: CrossingKind::Phase,
                theta: c.theta,
                frequency_hz: hz(c.theta),
                value: c.t / t0,
            })
            .collect(),
    }
}
