//! The frequency response of the open loop of a virtual wall, the data of a Bode and of a
//! Nyquist plot: L(e^{jωT}) = (a·PK + b·PB)/P0 of eq. 7–9 (the characteristic equation
//! p(z) = 0 is 1 + L = 0, the same open loop as [`crate::margins`]), evaluated on the exact
//! discrete loop ([`crate::zoh`]) at angular frequencies ω in rad/s, θ = ωT.
//!
//! The default grid runs from well below the slowest crossing up to the Nyquist frequency
//! π/T: [`POINTS_PER_DECADE`] log-spaced angles, joined with the margins' own frequency grid
//! ([`crate::margins::frequency::frequency_grid`], which resolves every lightly damped mode
//! and turns the phase of a long delay by less than 3° per step) and with the angle of every
//! crossing, so that the margins marked on a plot lie on its curve. The phase is unwrapped
//! along the grid (steps of at most 180°), starting in (−270°, 90°].
//!
//! The margins beside the curve are [`crate::margins::margins_beside_verdict`]'s (the same as
//! `check` reports): the gain crossovers |L| = 1 with their phase margins, the phase
//! crossovers (L real) with their gain factors, and min |1 + L|, the distance of the Nyquist
//! curve to −1, with the point of the curve where it is reached.

use std::f64::consts::PI;

use num_complex::Complex64;
use serde::Serialize;

use crate::closed_loop::AffineFamily;
use crate::error::{Error, Result};
use crate::margins::frequency::{frequency_grid, loop_value, stability_margin};
use crate::margins::{CrossingKind, Margins, margins_beside_verdict};
use crate::model::Loop;
use crate::param::Param;
use crate::params::Wall;
use crate::stability::Verdict;
use crate::system::System;

/// Log-spaced samples per decade of the default grid.
pub const POINTS_PER_DECADE: usize = 200;

/// The default grid starts at this fraction of the Nyquist frequency, or a decade below the
/// slowest crossing when that is lower.
pub const LOWEST_FRACTION: f64 = 1e-4;

/// One crossing of the open loop as a Bode or Nyquist plot marks it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Mark {
    /// Gain crossover (|L| = 1) or phase crossover (L real).
    pub kind: CrossingKind,
    /// Angular frequency in rad/s.
    pub omega: f64,
    /// Frequency in Hz.
    pub frequency_hz: f64,
    /// The phase margin in degrees (gain crossover), the factor on (K, B) that puts a root on
    /// the unit circle (phase crossover).
    pub value: f64,
    /// 20·log10 |L| there, dB.
    pub magnitude_db: f64,
    /// The phase of L there in degrees, on the branch of the unwrapped curve.
    pub phase_deg: f64,
    /// Re L there.
    pub re: f64,
    /// Im L there.
    pub im: f64,
    /// True at the crossing where the reported margin is read: the gain margin (the factor
    /// > 1 on (K, B)) or the phase margin (the smallest in magnitude).
    pub primary: bool,
}

/// The point of the Nyquist curve closest to −1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Closest {
    /// min over frequency of |1 + L|.
    pub distance: f64,
    /// Angular frequency where it is reached, rad/s.
    pub omega: f64,
    /// The same in Hz.
    pub frequency_hz: f64,
    /// Re L there.
    pub re: f64,
    /// Im L there.
    pub im: f64,
}

/// The open loop's frequency response with its crossings (module doc).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrequencyResponse {
    /// Sampling period T in s.
    pub period: f64,
    /// The Nyquist frequency 1/(2T) in Hz.
    pub nyquist_hz: f64,
    /// Angular frequencies ω in rad/s: as given, or the default grid (increasing).
    pub omega: Vec<f64>,
    /// ω/(2π) in Hz.
    pub frequency_hz: Vec<f64>,
    /// Re L(e^{jωT}).
    pub re: Vec<f64>,
    /// Im L(e^{jωT}).
    pub im: Vec<f64>,
    /// 20·log10 |L|, dB.
    pub magnitude_db: Vec<f64>,
    /// arg L in degrees, unwrapped along the grid.
    pub phase_deg: Vec<f64>,
    /// Every gain and phase crossover in (0, π/T), increasing (none when the wall is not
    /// stable: margins are defined for stable walls).
    pub marks: Vec<Mark>,
    /// min |1 + L| and where (given for any wall: it is a distance of the curve).
    pub closest: Option<Closest>,
    /// The wall's margins as `check` reports them.
    pub margins: Margins,
}

/// The frequency response of the wall on the loop at the angular frequencies `omega` (rad/s,
/// each finite and > 0), or on the default grid (module doc) when None.
pub fn frequency_response(
    lp: &Loop,
    wall: Wall,
    omega: Option<&[f64]>,
) -> Result<FrequencyResponse> {
    if let Some(w) = omega {
        check_omega(w)?;
    }
    let sys = System::of(lp)?;
    let fam = sys.family();
    let stable = sys.decide(sys.wall_units(wall)?).verdict == Verdict::Stable;
    let margins = margins_beside_verdict(lp, wall, stable)?;
    let (a, b) = fam.to_units(wall.stiffness, wall.damping);
    let t = lp.period;
    let (sm, sm_theta) = stability_margin(fam, a, b);
    let thetas: Vec<f64> = match omega {
        Some(w) => w.iter().map(|w| w * t).collect(),
        None => default_grid(fam, a, b, &margins, sm_theta),
    };
    let values: Vec<Complex64> = thetas.iter().map(|&th| loop_value(fam, a, b, th)).collect();
    let phase_deg = unwrap_degrees(values.iter().map(|l| l.arg().to_degrees()));
    let hz = |th: f64| th / (2.0 * PI * t);
    let marks = margins
        .crossings
        .iter()
        .filter(|c| c.theta > 0.0 && c.theta < PI)
        .map(|c| {
            let l = loop_value(fam, a, b, c.theta);
            Mark {
                kind: c.kind,
                omega: c.theta / t,
                frequency_hz: hz(c.theta),
                value: c.value,
                magnitude_db: db(l),
                phase_deg: on_branch(l.arg().to_degrees(), &thetas, &phase_deg, c.theta),
                re: l.re,
                im: l.im,
                primary: match c.kind {
                    CrossingKind::Gain => margins.phase.is_some_and(|p| p.theta == c.theta),
                    CrossingKind::Phase => margins.gain.is_some_and(|g| g.theta == c.theta),
                },
            }
        })
        .collect();
    let closest = sm.is_finite().then(|| {
        let l = loop_value(fam, a, b, sm_theta);
        Closest {
            distance: sm,
            omega: sm_theta / t,
            frequency_hz: hz(sm_theta),
            re: l.re,
            im: l.im,
        }
    });
    Ok(FrequencyResponse {
        period: t,
        nyquist_hz: 0.5 / t,
        omega: match omega {
            Some(w) => w.to_vec(),
            None => thetas.iter().map(|th| th / t).collect(),
        },
        frequency_hz: thetas.iter().map(|&th| hz(th)).collect(),
        re: values.iter().map(|l| l.re).collect(),
        im: values.iter().map(|l| l.im).collect(),
        magnitude_db: values.iter().map(|&l| db(l)).collect(),
        phase_deg,
        marks,
        closest,
        margins,
    })
}

/// Refuses an empty list or an ω that is not finite and > 0.
fn check_omega(omega: &[f64]) -> Result<()> {
    if omega.is_empty() {
        return Err(Error::Invalid {
            param: Param::Omega,
            reason: "needs at least one frequency".into(),
        });
    }
    match omega.iter().find(|w| !(w.is_finite() && **w > 0.0)) {
        Some(&w) => Err(Error::OutOfRange {
            param: Param::Omega,
            value: w,
            range: "finite angular frequencies > 0 in rad/s",
        }),
        None => Ok(()),
    }
}

/// 20·log10 |L|.
fn db(l: Complex64) -> f64 {
    20.0 * l.norm().log10()
}

/// The default angles (module doc), sorted, in (0, π].
fn default_grid(fam: &AffineFamily, a: f64, b: f64, m: &Margins, sm_theta: f64) -> Vec<f64> {
    let marked: Vec<f64> = m
        .crossings
        .iter()
        .map(|c| c.theta)
        .chain([sm_theta])
        .filter(|th| th.is_finite() && *th > 0.0 && *th < PI)
        .collect();
    let slowest = marked.iter().copied().fold(f64::INFINITY, f64::min);
    let lo = (LOWEST_FRACTION * PI).min(0.1 * slowest);
    let decades = (PI / lo).log10();
    let n = (decades * POINTS_PER_DECADE as f64).ceil().max(1.0) as usize;
    let mut ts: Vec<f64> = (0..=n)
        .map(|i| lo * 10f64.powf(decades * i as f64 / n as f64))
        .collect();
    ts.extend(frequency_grid(fam, a, b).into_iter().filter(|&t| t > lo));
    ts.extend(marked);
    ts.retain(|&t| t > 0.0 && t <= PI);
    ts.push(PI);
    ts.sort_by(f64::total_cmp);
    ts.dedup();
    ts
}

/// Unwraps a sequence of angles in degrees: each step of at most 180°, the first in
/// (−270°, 90°].
pub fn unwrap_degrees(angles: impl IntoIterator<Item = f64>) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    for d in angles {
        let v = match out.last() {
            None => {
                let w = d.rem_euclid(360.0);
                if w > 90.0 { w - 360.0 } else { w }
            }
            Some(&prev) if d.is_finite() && prev.is_finite() => {
                d + 360.0 * ((prev - d) / 360.0).round()
            }
            Some(_) => d,
        };
        out.push(v);
    }
    out
}

/// The angle `deg` moved by whole turns onto the branch of the unwrapped curve at the grid
/// angle nearest `theta`.
fn on_branch(deg: f64, thetas: &[f64], unwrapped: &[f64], theta: f64) -> f64 {
    let nearest = thetas
        .iter()
        .enumerate()
        .min_by(|x, y| (x.1 - theta).abs().total_cmp(&(y.1 - theta).abs()))
        .map(|(i, _)| unwrapped[i]);
    match nearest {
        Some(p) if p.is_finite() => deg + 360.0 * ((p - deg) / 360.0).round(),
        _ => deg,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Effective;

    /// The paper's pure mass without delay, B = 0: L = α/2 · (z + 1)/(z − 1)² (ZOH of 1/ms²).
    #[test]
    fn pure_mass_matches_the_closed_form() {
        let (m, t) = (2.0, 1e-3);
        let lp = Loop::paper(Effective::new(m, 0.0, 0.0).unwrap(), t, 0).unwrap();
        let k = 5000.0;
        let wall = Wall {
            stiffness: k,
            damping: 0.0,
        };
        let omega = [1.0, 10.0, 100.0, 1000.0, 3000.0];
        let fr = frequency_response(&lp, wall, Some(&omega)).unwrap();
        for (i, w) in omega.iter().enumerate() {
            let z = crate::circle::unit(w * t);
            let l = k * t * t / (2.0 * m) * (z + 1.0) / ((z - 1.0) * (z - 1.0));
            let got = Complex64::new(fr.re[i], fr.im[i]);
            assert!((got - l).norm() <= 1e-10 * l.norm(), "{w}: {got} vs {l}");
        }
        assert!(frequency_response(&lp, wall, Some(&[1.0, -1.0])).is_err());
        assert!(frequency_response(&lp, wall, Some(&[])).is_err());
    }

    #[test]
    fn unwrapping_keeps_steps_below_half_a_turn() {
        let u = unwrap_degrees([170.0, -170.0, -10.0, 170.0]);
        assert_eq!(u, vec![-190.0, -170.0, -10.0, -190.0]);
    }
}
