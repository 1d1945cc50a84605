//! Typed errors of the hapstab library.

use thiserror::Error;

use crate::param::Param;

/// Everything that can go wrong when building or analysing a model.
///
/// Each variant names the parameter (a [`Param`]) and the offending value so that a front end
/// can print one clear line and name the argument that carries the parameter.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Error {
    /// A parameter is NaN or infinite.
    #[error("{param} must be a finite number (got {value})")]
    NotFinite {
        /// The parameter.
        param: Param,
        /// Offending value.
        value: f64,
    },
    /// A parameter that must be strictly positive is not.
    #[error("{param} must be > 0 (got {value})")]
    NotPositive {
        /// The parameter.
        param: Param,
        /// Offending value.
        value: f64,
    },
    /// A parameter that must be non-negative is negative.
    #[error("{param} must be >= 0 (got {value})")]
    Negative {
        /// The parameter.
        param: Param,
        /// Offending value.
        value: f64,
    },
    /// The delay time is not a whole number of sampling periods.
    #[error(
        "delay time t_d = {delay_time} s is not a whole number of sampling periods T = {period} s (t_d/T = {ratio})"
    )]
    FractionalDelay {
        /// Delay time t_d in s.
        delay_time: f64,
        /// Sampling period T in s.
        period: f64,
        /// t_d / T.
        ratio: f64,
    },
    /// A delay (in samples) above the supported maximum.
    #[error("delay d must be at most {max} samples (got {value})")]
    DelayTooLarge {
        /// Requested delay in samples.
        value: f64,
        /// Largest supported delay.
        max: usize,
    },
    /// A parameter lies outside a documented range.
    #[error("{param} must be in {range} (got {})", shown(*.value))]
    OutOfRange {
        /// The parameter.
        param: Param,
        /// Offending value.
        value: f64,
        /// The allowed range, as text.
        range: &'static str,
    },
    /// A parameter is unusable for a reason other than its range (a zero polynomial, an
    /// improper transfer function, …).
    #[error("{param} {reason}")]
    Invalid {
        /// The parameter.
        param: Param,
        /// Why, in words, starting with a verb ("must be …", "is …").
        reason: String,
    },
    /// A physical parameter whose normalized form (Table I) overflows: the normalized value
    /// derived from it is not a finite number.
    #[error("{param} = {value:?} makes {derived} = {result:?}, not a finite number")]
    Unrepresentable {
        /// The physical parameter to blame.
        param: Param,
        /// Its value.
        value: f64,
        /// The derived normalized quantity, e.g. "δ = bT/m".
        derived: &'static str,
        /// The derived value (±inf or NaN).
        result: f64,
    },
    /// A numerical routine did not converge.
    #[error("numerical failure: {0}")]
    Numerical(String),
}

impl Error {
    /// The parameter the error is about (None for a numerical failure).
    pub fn param(&self) -> Option<Param> {
        match self {
            Error::NotFinite { param, .. }
            | Error::NotPositive { param, .. }
            | Error::Negative { param, .. }
            | Error::OutOfRange { param, .. }
            | Error::Invalid { param, .. }
            | Error::Unrepresentable { param, .. } => Some(*param),
            Error::FractionalDelay { .. } => Some(Param::DelayTime),
            Error::DelayTooLarge { .. } => Some(Param::Delay),
            Error::Numerical(_) => None,
        }
    }

    /// The offending value, when the error has one number to show.
    pub fn value(&self) -> Option<f64> {
        match self {
            Error::NotFinite { value, .. }
            | Error::NotPositive { value, .. }
            | Error::Negative { value, .. }
            | Error::OutOfRange { value, .. }
            | Error::Unrepresentable { value, .. }
            | Error::DelayTooLarge { value, .. } => Some(*value),
            Error::FractionalDelay { delay_time, .. } => Some(*delay_time),
            Error::Invalid { .. } | Error::Numerical(_) => None,
        }
    }
}

/// A value in an error message: plain below 1e15 and from 1e-4 on, else in e-notation.
fn shown(v: f64) -> String {
    if v == 0.0 || (1e-4..1e15).contains(&v.abs()) || !v.is_finite() {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Result type of the library.
pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` is finite.
pub(crate) fn finite(param: Param, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NotFinite { param, value })
    }
}

/// Checks that `value` is finite and > 0.
pub(crate) fn positive(param: Param, value: f64) -> Result<f64> {
    finite(param, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(Error::NotPositive { param, value })
    }
}

/// Checks that `value` is finite and >= 0.
pub(crate) fn non_negative(param: Param, value: f64) -> Result<f64> {
    finite(param, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::Negative { param, value })
    }
}

/// Checks that `value` is finite, >= 0 and <= `max` (`range` says the interval in words).
pub(crate) fn at_most(param: Param, value: f64, max: f64, range: &'static str) -> Result<f64> {
    non_negative(param, value)?;
    if value <= max {
        Ok(value)
    } else {
        Err(Error::OutOfRange {
            param,
            value,
            range,
        })
    }
}
