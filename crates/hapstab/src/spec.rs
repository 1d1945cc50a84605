//! Text forms of a loop's parts, shared by every front end (command-line flags, the browser
//! explorer, the Python package) so that the same text means the same loop everywhere.
//!
//! - A velocity estimator (see [`VelocityEstimator`] for the formulas):
//!   `backward` | `lowpass:FC` (f_c in Hz) | `butterworth:N:FC` | `bessel:N:FC` |
//!   `critically-damped:N:FC` (order N, f_c in Hz) | `average:N` (N samples) |
//!   `iir:b0,b1,…/a0,a1,…` (coefficients in powers of z⁻¹).
//! - A coefficient list: comma-separated numbers, e.g. the `num` and `den` of a transfer
//!   function (highest power of s first, as MATLAB's and python-control's `tf`).
//!
//! Parsing validates: a spec that parses is a usable estimator ([`VelocityEstimator::validated`]).
//! [`std::fmt::Display`] writes the same form back with shortest round-trip numbers, so
//! `text.parse::<VelocityEstimator>()?.to_string().parse()` gives the same estimator.

use std::fmt;
use std::str::FromStr;

use crate::error::{Error, Result, finite};
use crate::lowpass_design::{Family, NamedLowPass};
use crate::model::VelocityEstimator;
use crate::param::Param;

/// The accepted forms of a velocity estimator spec, for error messages and help texts.
pub const VELOCITY_FORMS: &str = "backward, lowpass:FC, butterworth:N:FC, bessel:N:FC, \
     critically-damped:N:FC, average:N or iir:b0,b1,…/a0,a1,…";

fn bad_velocity(text: &str, why: &str) -> Error {
    Error::Invalid {
        param: Param::Velocity,
        reason: format!("'{}' {why} (expected {VELOCITY_FORMS})", excerpt(text)),
    }
}

/// Items of a list shown in full in a message; a longer list is shown by its length and
/// its first [`EXCERPT_ITEMS`] items.
pub const EXCERPT_ITEMS: usize = 3;

/// Characters of a text shown in full in a message (a longer text is cut, see [`excerpt`]).
pub const EXCERPT_CHARS: usize = 60;

/// A coefficient list for a message: in full up to 8 numbers, else "2001 coefficients
/// (1, 1, 1, …)".
pub fn excerpt_list(c: &[f64]) -> String {
    if c.len() <= 8 {
        return c.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
    }
    let head: Vec<String> = c[..EXCERPT_ITEMS].iter().map(f64::to_string).collect();
    format!("{} coefficients ({}, …)", c.len(), head.join(", "))
}

/// A text typed by a user, for a message: in full up to [`EXCERPT_CHARS`] characters; a
/// longer comma-separated list as its number of items and the first few
/// ("iir: 2001 coefficients (1, 1, 1, …)/1"), any other long text cut with its length.
pub fn excerpt(text: &str) -> String {
    if text.chars().count() <= EXCERPT_CHARS {
        return text.to_string();
    }
    let (kind, body) = match text.split_once(':') {
        Some((k, b)) if !k.contains(',') => (format!("{k}: "), b),
        _ => (String::new(), text),
    };
    let lists: Vec<String> = body.split('/').map(excerpt_items).collect();
    let short = format!("{kind}{}", lists.join("/"));
    if short.chars().count() <= 3 * EXCERPT_CHARS {
        return short;
    }
    let cut: String = text.chars().take(EXCERPT_CHARS).collect();
    format!("{cut}… ({} characters)", text.chars().count())
}

/// One comma-separated list in full when short, else "N coefficients (x, y, z, …)".
fn excerpt_items(list: &str) -> String {
    let items: Vec<&str> = list.split(',').map(str::trim).collect();
    if items.len() <= 8 {
        return items.join(",");
    }
    format!(
        "{} coefficients ({}, …)",
        items.len(),
        items[..EXCERPT_ITEMS].join(", ")
    )
}

/// Parses a comma-separated list of finite numbers; `param` names the parameter in errors.
pub fn parse_coefficients(param: Param, text: &str) -> Result<Vec<f64>> {
    let text = text.trim();
    if text.is_empty() {
        return Err(Error::Invalid {
            param,
            reason: "is empty (expected comma-separated numbers, e.g. 1,3,10)".into(),
        });
    }
    text.split(',')
        .map(|tok| {
            let tok = tok.trim();
            let x: f64 = tok.parse().map_err(|_| Error::Invalid {
                param,
                reason: format!(
                    "has '{}', which is not a number (in '{}')",
                    excerpt(tok),
                    excerpt(text)
                ),
            })?;
            finite(param, x)
        })
        .collect()
}

fn parse_iir(text: &str, body: &str) -> Result<VelocityEstimator> {
    let Some((b, a)) = body.split_once('/') else {
        return Err(bad_velocity(
            text,
            "needs a '/' between numerator and denominator",
        ));
    };
    let b = parse_coefficients(Param::VelocityFilterNumerator, b)?;
    let a = parse_coefficients(Param::VelocityFilterDenominator, a)?;
    VelocityEstimator::Iir { b, a }.validated()
}

fn parse_number<T: FromStr>(text: &str, value: &str, what: &str) -> Result<T> {
    value.trim().parse().map_err(|_| {
        bad_velocity(
            text,
            &format!("has '{}', which is not {what}", excerpt(value.trim())),
        )
    })
}

/// `butterworth:N:FC`, `bessel:N:FC` or `critically-damped:N:FC` (`body` the text after the
/// family's keyword and ':').
fn parse_named(text: &str, family: Family, body: Option<&str>) -> Result<VelocityEstimator> {
    let Some(body) = body else {
        return Err(bad_velocity(text, "needs a parameter after ':'"));
    };
    let Some((n, fc)) = body.split_once(':') else {
        return Err(bad_velocity(
            text,
            &format!("needs {}:ORDER:FC", family.keyword()),
        ));
    };
    let f = NamedLowPass::new(
        family,
        parse_number(text, n, "a whole filter order")?,
        parse_number(text, fc, "a cut-off frequency in Hz")?,
    );
    VelocityEstimator::from(f).validated()
}

impl FromStr for VelocityEstimator {
    type Err = Error;

    /// Parses `backward`, `lowpass:FC`, `butterworth:N:FC`, `bessel:N:FC`,
    /// `critically-damped:N:FC`, `average:N` or `iir:b0,b1,…/a0,a1,…` and validates the
    /// parameters (f_c > 0, 1 ≤ order ≤ 8, N >= 1, a0 ≠ 0).
    fn from_str(s: &str) -> Result<Self> {
        let text = s.trim();
        let (kind, body) = match text.split_once(':') {
            Some((k, b)) => (k.trim(), Some(b)),
            None => (text, None),
        };
        let est = match (kind.to_ascii_lowercase().as_str(), body) {
            ("backward", None) => VelocityEstimator::Backward,
            ("lowpass", Some(fc)) => VelocityEstimator::LowPass {
                cutoff_hz: parse_number(text, fc, "a cut-off frequency in Hz")?,
            },
            ("average", Some(n)) => VelocityEstimator::Average {
                samples: parse_number(text, n, "a whole number of samples")?,
            },
            ("iir", Some(body)) => return parse_iir(text, body),
            ("backward", Some(_)) => return Err(bad_velocity(text, "takes no parameter")),
            ("lowpass" | "average" | "iir", None) => {
                return Err(bad_velocity(text, "needs a parameter after ':'"));
            }
            (word, body) if let Some(family) = Family::from_keyword(word) => {
                return parse_named(text, family, body);
            }
            _ => return Err(bad_velocity(text, "is not a velocity estimator")),
        };
        est.validated()
    }
}

fn join(c: &[f64]) -> String {
    c.iter().map(f64::to_string).collect::<Vec<_>>().join(",")
}

impl fmt::Display for VelocityEstimator {
    /// The spec form that [`FromStr`] reads, with shortest round-trip numbers.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VelocityEstimator::Backward => write!(f, "backward"),
            VelocityEstimator::LowPass { cutoff_hz } => write!(f, "lowpass:{cutoff_hz}"),
            VelocityEstimator::Average { samples } => write!(f, "average:{samples}"),
            VelocityEstimator::Butterworth { order, cutoff_hz } => {
                write!(f, "{}:{order}:{cutoff_hz}", Family::Butterworth.keyword())
            }
            VelocityEstimator::Bessel { order, cutoff_hz } => {
                write!(f, "{}:{order}:{cutoff_hz}", Family::Bessel.keyword())
            }
            VelocityEstimator::CriticallyDamped { order, cutoff_hz } => {
                write!(
                    f,
                    "{}:{order}:{cutoff_hz}",
                    Family::CriticallyDamped.keyword()
                )
            }
            VelocityEstimator::Iir { b, a } => write!(f, "iir:{}/{}", join(b), join(a)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_form_parses_and_round_trips() {
        let cases = [
            ("backward", VelocityEstimator::Backward),
            ("lowpass:50", VelocityEstimator::LowPass { cutoff_hz: 50.0 }),
            (" average:15 ", VelocityEstimator::Average { samples: 15 }),
            (
                "butterworth:2:150",
                VelocityEstimator::Butterworth {
                    order: 2,
                    cutoff_hz: 150.0,
                },
            ),
            (
                "Bessel: 4 : 62.5",
                VelocityEstimator::Bessel {
                    order: 4,
                    cutoff_hz: 62.5,
                },
            ),
            (
                "critically-damped:3:0.3",
                VelocityEstimator::CriticallyDamped {
                    order: 3,
                    cutoff_hz: 0.3,
                },
            ),
            (
                "iir:1, -1/0.001,0.0005",
                VelocityEstimator::Iir {
                    b: vec![1.0, -1.0],
                    a: vec![0.001, 0.0005],
                },
            ),
        ];
        for (text, want) in cases {
            let got: VelocityEstimator = text.parse().unwrap();
            assert_eq!(got, want, "{text}");
            assert_eq!(got.to_string().parse::<VelocityEstimator>().unwrap(), want);
        }
        // shortest round-trip numbers survive the text form exactly
        let v = VelocityEstimator::LowPass {
            cutoff_hz: 0.1 + 0.2,
        };
        assert_eq!(v.to_string().parse::<VelocityEstimator>().unwrap(), v);
    }

    #[test]
    fn bad_specs_name_the_text() {
        for (text, needle) in [
            ("forward", "'forward'"),
            ("backward:2", "takes no parameter"),
            ("lowpass", "needs a parameter"),
            ("lowpass:fast", "'fast'"),
            ("lowpass:-5", "-5"),
            ("lowpass:0", "f_c"),
            ("average:0", "window N"),
            ("average:2.5", "'2.5'"),
            ("iir:1,-1", "'/'"),
            ("iir:1,x/1", "'x'"),
            ("iir:1,-1/0,1", "a0"),
            ("iir:0/1", "numerator"),
            ("iir:1/", "empty"),
            ("bessel", "needs a parameter"),
            ("bessel:40", "needs bessel:ORDER:FC"),
            ("bessel:0:40", "Bessel order N"),
            ("bessel:9:40", "Bessel order N"),
            ("bessel:2.5:40", "'2.5'"),
            ("critically-damped:2:-3", "critically damped cut-off f_c"),
            ("critically-damped:x:3", "'x'"),
            ("critically-damped:9:3", "critically damped order N"),
            ("critically_damped:2:3", "is not a velocity estimator"),
        ] {
            let e = text.parse::<VelocityEstimator>().unwrap_err().to_string();
            assert!(e.contains(needle), "{text}: {e}");
            assert!(!e.contains('\n'), "{text}: {e}");
        }
    }

    #[test]
    fn long_lists_are_shown_by_an_excerpt() {
        let ones = vec!["1"; 2001].join(",");
        let text = format!("iir:{ones},y/1");
        let e = text.parse::<VelocityEstimator>().unwrap_err().to_string();
        assert!(e.len() < 300, "{} characters: {e}", e.len());
        assert!(e.contains("2002 coefficients (1, 1, 1, …)"), "{e}");
        let e = format!("iir:{ones}")
            .parse::<VelocityEstimator>()
            .unwrap_err()
            .to_string();
        assert!(e.contains("'iir: 2001 coefficients (1, 1, 1, …)'"), "{e}");
        let e = parse_coefficients(Param::PlantNum, &format!("{ones},y"))
            .unwrap_err()
            .to_string();
        assert!(e.len() < 300 && e.contains("'y'"), "{e}");
        assert_eq!(excerpt_list(&[1.0, 2.0]), "1,2");
        assert_eq!(
            excerpt_list(&[0.5; 10]),
            "10 coefficients (0.5, 0.5, 0.5, …)"
        );
        let garbage = "x".repeat(500);
        assert!(excerpt(&garbage).contains("(500 characters)"));
    }

    #[test]
    fn coefficient_lists() {
        assert_eq!(
            parse_coefficients(Param::PlantNum, "1, 3,10").unwrap(),
            vec![1.0, 3.0, 10.0]
        );
        assert_eq!(
            parse_coefficients(Param::PlantNum, "-2.5e-3").unwrap(),
            vec![-2.5e-3]
        );
        assert!(parse_coefficients(Param::PlantNum, "").is_err());
        assert!(parse_coefficients(Param::PlantNum, "1,,2").is_err());
        let e = parse_coefficients(Param::PlantNum, "1,inf")
            .unwrap_err()
            .to_string();
        assert!(e.contains("num") && e.contains("inf"), "{e}");
    }
}
