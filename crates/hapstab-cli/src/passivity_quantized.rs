//! The quantization section of `hapstab passivity`: with `--quantization Δ --coulomb f_c`,
//! Abbott and Okamura's closed forms K ≤ min(2b/T, 2f_c/Δ) (IEEE TRO 2005) and Diolaiti et
//! al.'s sampling bound with a delay (IEEE TRO 2006), through
//! [`hapstab::passivity_quantized::quantized_passivity`].
//!
//! Meant to be wired into `PassivityArgs` by `#[command(flatten)] quantized: QuantizationArgs`
//! and called from `passivity::run` with the wall, the period, the delay and the device damping.

use anyhow::{Result, bail};
use clap::Args;
use hapstab::passivity_quantized::{
    ConditionKind, QuantizedPassivity, QuantizedVerdict, QuantizedWall, quantized_passivity,
};
use serde::Serialize;

use crate::output::eng;

/// `--quantization Δ --coulomb f_c`: the encoder step and the device's Coulomb friction.
#[derive(Args, Debug, Clone, Copy, Default)]
pub struct QuantizationArgs {
    /// Encoder resolution Δ in m: adds Abbott & Okamura's condition K ≤ 2 f_c/Δ (needs
    /// --coulomb).
    #[arg(long, value_name = "Δ", requires = "coulomb")]
    pub quantization: Option<f64>,
    /// The device's Coulomb friction f_c in N (with --quantization).
    #[arg(long, value_name = "F_C", requires = "quantization")]
    pub coulomb: Option<f64>,
}

/// The sampled wall and device the section is about (physical units).
#[derive(Debug, Clone, Copy)]
pub struct QuantizedInput {
    /// K in N/m.
    pub stiffness: f64,
    /// B in Ns/m.
    pub damping: f64,
    /// T in s.
    pub period: f64,
    /// Whole samples of delay.
    pub delay: usize,
    /// The device's viscous damping b in Ns/m.
    pub device_damping: f64,
}

/// The section in the JSON output (`quantized` beside the Colgate–Schenkel fields).
#[derive(Debug, Clone, Serialize)]
pub struct QuantizedOut {
    /// Δ in m (not `quantization`: the flattened result names its condition so).
    pub quantization_step: f64,
    /// f_c in N.
    pub coulomb_friction: f64,
    /// Both conditions, the binding one, K_max and the verdict.
    #[serde(flatten)]
    pub result: QuantizedPassivity,
}

/// The quantized-spring passivity section: None without the flags; otherwise the
/// serializable result and its text lines (Abbott & Okamura 2005, K ≤ min(2b/T, 2f_c/Δ);
/// Diolaiti et al. 2006 for a delay). Errors name a flag out of range.
pub fn quantized_section(
    args: &QuantizationArgs,
    input: QuantizedInput,
) -> Result<Option<(QuantizedOut, Vec<String>)>> {
    let (Some(quantization), Some(coulomb)) = (args.quantization, args.coulomb) else {
        if args.quantization.is_some() || args.coulomb.is_some() {
            bail!("--quantization and --coulomb go together");
        }
        return Ok(None);
    };
    let wall = QuantizedWall {
        stiffness: input.stiffness,
        damping: input.damping,
        period: input.period,
        delay: input.delay,
        device_damping: input.device_damping,
        coulomb,
        quantization,
    };
    let result = quantized_passivity(&wall)?;
    let lines = text_lines(&result);
    Ok(Some((
        QuantizedOut {
            quantization_step: quantization,
            coulomb_friction: coulomb,
            result,
        },
        lines,
    )))
}

fn bound(k: f64) -> String {
    if k == f64::NEG_INFINITY {
        "none (b < |B|)".into()
    } else {
        eng(k, "N/m", 6)
    }
}

fn text_lines(r: &QuantizedPassivity) -> Vec<String> {
    let mark = |met: bool| if met { "met" } else { "violated" };
    let note = |within: bool| {
        if within {
            ""
        } else {
            " (outside the published assumptions)"
        }
    };
    let binding = match r.binding {
        ConditionKind::Sampling => "sampling",
        ConditionKind::Quantization => "quantization",
    };
    let verdict = match r.verdict {
        QuantizedVerdict::Passive => "passive",
        QuantizedVerdict::NotPassive => "not passive",
        QuantizedVerdict::PassiveOutsideAssumptions => {
            "passive by the closed forms, applied outside their assumptions"
        }
    };
    vec![
        format!(
            "sampling      K ≤ 2(b − |B|)/(T + 2dT) = {}: {}{}",
            bound(r.sampling.k_bound),
            mark(r.sampling.met),
            note(r.sampling.within_assumptions)
        ),
        format!(
            "quantization  K ≤ 2 f_c/Δ = {}: {}{}",
            bound(r.quantization.k_bound),
            mark(r.quantization.met),
            note(r.quantization.within_assumptions)
        ),
        format!("K_max {} ({binding} binds): {verdict}", bound(r.k_max)),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input(k: f64) -> QuantizedInput {
        QuantizedInput {
            stiffness: k,
            damping: 0.0,
            period: 1e-3,
            delay: 0,
            device_damping: 1.5,
        }
    }

    #[test]
    fn without_flags_there_is_no_section() {
        assert!(
            quantized_section(&QuantizationArgs::default(), input(1.0))
                .unwrap()
                .is_none()
        );
    }

    #[test]
    fn section_gives_the_closed_forms() {
        // 2b/T = 3000 N/m, 2 f_c/Δ = 2·0.05/1e-4 = 1000 N/m
        let args = QuantizationArgs {
            quantization: Some(1e-4),
            coulomb: Some(0.05),
        };
        let (out, lines) = quantized_section(&args, input(1200.0)).unwrap().unwrap();
        assert_eq!(out.result.quantization.k_bound, 1000.0);
        assert_eq!(out.result.sampling.k_bound, 3000.0);
        assert_eq!(out.result.binding, ConditionKind::Quantization);
        assert_eq!(out.result.verdict, QuantizedVerdict::NotPassive);
        assert_eq!(lines.len(), 3);
        assert!(lines[1].contains("violated") && lines[2].contains("quantization binds"));
        let v = serde_json::to_value(&out).unwrap();
        assert_eq!(v["k_max"], 1000.0);
        assert_eq!(v["binding"], "quantization");
        assert_eq!(v["verdict"], "not_passive");
        let (ok, _) = quantized_section(&args, input(900.0)).unwrap().unwrap();
        assert_eq!(ok.result.verdict, QuantizedVerdict::Passive);
    }

    #[test]
    fn bad_values_are_errors() {
        let args = QuantizationArgs {
            quantization: Some(-1e-4),
            coulomb: Some(0.05),
        };
        assert!(quantized_section(&args, input(1.0)).is_err());
        let half = QuantizationArgs {
            quantization: Some(1e-4),
            coulomb: None,
        };
        assert!(quantized_section(&half, input(1.0)).is_err());
    }
}
