//! `hapstab ranges`: the γ and δ bounds of real haptic systems for a sampling period
//! (Section IV, eq. 11–15).

use anyhow::Result;
use clap::Args;
use hapstab::paper::ranges::{Ranges, ranges};
use serde::Serialize;

use crate::output::{eng, print_json, sig};

/// Arguments of `hapstab ranges`.
#[derive(Args, Debug)]
pub struct RangesArgs {
    /// Sampling period T in s.
    #[arg(long, allow_hyphen_values = true, default_value_t = 1e-3)]
    period: f64,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct RangesInput {
    period: f64,
}

/// `ranges --json`: the period under `input`, the ranges at the top level.
#[derive(Serialize)]
struct RangesOut<'a> {
    input: RangesInput,
    limits: &'a hapstab::paper::ranges::RatioLimits,
    gamma_max: f64,
    delta_max: f64,
    extended_gamma_max: f64,
    extended_delta_max: f64,
    within_extended: bool,
}

/// Runs `hapstab ranges`.
pub fn run(a: &RangesArgs) -> Result<()> {
    let r = ranges(a.period)?;
    if a.json {
        return print_json(&RangesOut {
            input: RangesInput { period: r.period },
            limits: &r.limits,
            gamma_max: r.gamma_max,
            delta_max: r.delta_max,
            extended_gamma_max: r.extended_gamma_max,
            extended_delta_max: r.extended_delta_max,
            within_extended: r.within_extended,
        });
    }
    print_text(&r);
    Ok(())
}

fn print_text(r: &Ranges) {
    let l = &r.limits;
    println!("period      T = {}", eng(r.period, "s", 6));
    println!(
        "ratios      k_H/m_H < {} s⁻², b_H/m_H < {} s⁻¹ (eq. 11), b_L/m_L < {} s⁻¹",
        sig(l.arm_stiffness_per_mass, 6),
        sig(l.arm_damping_per_mass, 6),
        sig(l.device_damping_per_mass, 6)
    );
    println!(
        "eq. (14)    0 ≤ γ < {}   (T²·{} s⁻²)",
        sig(r.gamma_max, 6),
        sig(l.arm_stiffness_per_mass, 6)
    );
    println!(
        "            0 ≤ δ < {}   (T·{} s⁻¹)",
        sig(r.delta_max, 6),
        sig(l.damping_per_mass(), 6)
    );
    println!(
        "eq. (15)    0 ≤ γ < {}, 0 ≤ δ < {} (extended range for T ≤ 1 ms): {}",
        sig(r.extended_gamma_max, 3),
        sig(r.extended_delta_max, 3),
        if r.within_extended {
            "covers eq. (14)"
        } else {
            "does NOT cover eq. (14) at this period"
        }
    );
}
