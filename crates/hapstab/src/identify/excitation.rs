//! Recordings without a device: a force excitation and the exact sampled response of a loop's
//! plant to it, with measurement noise and encoder quantization — the log that
//! [`super::identify`] reads, so that the path from a recording to K_max can be tried on a
//! known plant.
//!
//! - **chirp**: F_k = A·cos(2π(f0·t + (f1 − f0)·t²/(2·t_end))), a linear sweep from f0 to f1
//!   Hz over the run (scipy's `chirp(method='linear')`);
//! - **PRBS**: a seeded random binary sequence ±A, each level held for `hold` samples (its
//!   spectrum is flat up to about 1/(2·hold·T));
//! - **step**: 0 for the first tenth of the run, then A.
//!
//! The position is the plant's exact response from rest ([`super::response`]), plus white
//! Gaussian noise of standard deviation RMS(y)·10^(−SNR/20), then rounded to the
//! quantization step q (y ↦ q·round(y/q)).

use serde::Serialize;

use super::response::SampledModel;
use crate::error::{Error, Result};
use crate::model::Loop;
use crate::param::Param;
use crate::splitmix::SplitMix;

/// A force excitation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Excitation {
    /// A linear sweep from `f0` to `f1` Hz.
    Chirp {
        /// Start frequency in Hz.
        f0: f64,
        /// End frequency in Hz.
        f1: f64,
    },
    /// A random binary sequence, each level held `hold` samples.
    Prbs {
        /// Samples per level (≥ 1).
        hold: usize,
    },
    /// A step at a tenth of the run.
    Step,
}

impl std::fmt::Display for Excitation {
    /// The text [`Excitation::from_str`] reads.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Excitation::Chirp { f0, f1 } => write!(f, "chirp:{f0}:{f1}"),
            Excitation::Prbs { hold } => write!(f, "prbs:{hold}"),
            Excitation::Step => write!(f, "step"),
        }
    }
}

impl std::str::FromStr for Excitation {
    type Err = Error;

    /// Parses `chirp:F0:F1`, `prbs:HOLD` or `step`.
    fn from_str(text: &str) -> Result<Self> {
        let bad = |why: &str| Error::Invalid {
            param: Param::Excitation,
            reason: format!("'{text}': {why}"),
        };
        let parts: Vec<&str> = text.split(':').collect();
        let num = |s: &str| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v >= 0.0)
        };
        match parts.as_slice() {
            ["chirp", a, b] => match (num(a), num(b)) {
                (Some(f0), Some(f1)) => Ok(Excitation::Chirp { f0, f1 }),
                _ => Err(bad("chirp:F0:F1 needs two frequencies ≥ 0 in Hz")),
            },
            ["prbs", h] => match h.trim().parse::<usize>() {
                Ok(hold) if hold >= 1 => Ok(Excitation::Prbs { hold }),
                _ => Err(bad("prbs:HOLD needs a whole number of samples ≥ 1")),
            },
            ["step"] => Ok(Excitation::Step),
            _ => Err(bad("expected chirp:F0:F1, prbs:HOLD or step")),
        }
    }
}

/// The force F_k in N of `samples` samples at period T in s (module doc); `seed` draws the
/// PRBS levels.
pub fn force(ex: Excitation, amplitude: f64, samples: usize, period: f64, seed: u64) -> Vec<f64> {
    let t_end = (samples.max(2) - 1) as f64 * period;
    match ex {
        Excitation::Chirp { f0, f1 } => (0..samples)
            .map(|k| {
                let t = k as f64 * period;
                let phase = f0 * t + (f1 - f0) * t * t / (2.0 * t_end);
                amplitude * (2.0 * std::f64::consts::PI * phase).cos()
            })
            .collect(),
        Excitation::Prbs { hold } => {
            let mut rng = SplitMix::stream(seed, 0);
            let mut level = 0.0;
            (0..samples)
                .map(|k| {
                    if k % hold == 0 {
                        level = if rng.next_f64() < 0.5 {
                            -amplitude
                        } else {
                            amplitude
                        };
                    }
                    level
                })
                .collect()
        }
        Excitation::Step => (0..samples)
            .map(|k| if k < samples / 10 { 0.0 } else { amplitude })
            .collect(),
    }
}

/// The measured position of the loop's plant under `force` (module doc): the exact sampled
/// response from rest, noise at `snr_db` (None: none) drawn with `seed`, quantization `q`
/// in m (0: none).
pub fn measured_position(
    lp: &Loop,
    force: &[f64],
    snr_db: Option<f64>,
    q: f64,
    seed: u64,
) -> Result<Vec<f64>> {
    let mut y = SampledModel::of_loop(lp)?.simulate(force);
    if let Some(snr) = snr_db {
        let rms = (y.iter().map(|v| v * v).sum::<f64>() / y.len().max(1) as f64).sqrt();
        let sd = rms * 10f64.powf(-snr / 20.0);
        let mut rng = SplitMix::stream(seed ^ 0x0001_D0A7_A5EE_D000, 1);
        for v in y.iter_mut() {
            let u1 = 1.0 - rng.next_f64();
            let u2 = rng.next_f64();
            *v += sd * (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos();
        }
    }
    if q > 0.0 {
        for v in y.iter_mut() {
            *v = q * (*v / q).round();
        }
    }
    Ok(y)
}
