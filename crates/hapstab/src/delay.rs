//! The delay of the wall force in whole and fractional samples (Table I's d, generalized).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result, finite, non_negative, positive};
use crate::param::Param;
use crate::params::MAX_DELAY;

/// The delay of the wall force, t_d = (d + λ)·T with whole samples d and a fraction
/// λ ∈ [0, 1) of a sample (Table I: d = t_d/T, here not necessarily whole).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Delay {
    /// Whole samples d.
    pub samples: usize,
    /// Fraction λ of a sample, in [0, 1).
    pub fraction: f64,
}

/// Relative tolerance below which t_d/T is taken as a whole number of samples: ratios are
/// computed from user-typed decimals (3e-3/1e-3 = 2.9999999999999996), so a few ulps of
/// rounding must not create a fractional delay of 1 − 4e-16 samples.
const WHOLE_SAMPLE_TOL: f64 = 1e-12;

impl Delay {
    /// No delay.
    pub const NONE: Delay = Delay {
        samples: 0,
        fraction: 0.0,
    };

    /// A whole number of samples (the paper's d).
    pub fn samples(d: usize) -> Result<Self> {
        crate::params::check_delay(d)?;
        Ok(Self {
            samples: d,
            fraction: 0.0,
        })
    }

    /// From a delay time t_d >= 0 in seconds and the period T: d = ⌊t_d/T⌋, λ = t_d/T − d.
    pub fn from_time(delay_time: f64, period: f64) -> Result<Self> {
        non_negative(Param::DelayTime, delay_time)?;
        positive(Param::Period, period)?;
        let ratio = delay_time / period;
        if !ratio.is_finite() || ratio > MAX_DELAY as f64 {
            return Err(Error::DelayTooLarge {
                value: ratio,
                max: MAX_DELAY,
            });
        }
        let nearest = ratio.round();
        if (ratio - nearest).abs() <= WHOLE_SAMPLE_TOL * nearest.max(1.0) {
            return Self::samples(nearest as usize);
        }
        let d = ratio.floor();
        Ok(Self {
            samples: d as usize,
            fraction: ratio - d,
        })
    }

    /// t_d/T in samples.
    pub fn in_samples(&self) -> f64 {
        self.samples as f64 + self.fraction
    }

    /// Checks d <= [`MAX_DELAY`] and λ ∈ [0, 1).
    pub fn validated(self) -> Result<Self> {
        crate::params::check_delay(self.samples)?;
        finite(Param::DelayFraction, self.fraction)?;
        if !(0.0..1.0).contains(&self.fraction) {
            return Err(Error::OutOfRange {
                param: Param::DelayFraction,
                value: self.fraction,
                range: "[0, 1)",
            });
        }
        Ok(self)
    }
}
