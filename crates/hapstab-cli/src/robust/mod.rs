//! Robust K_max across a range of plants (beyond the paper): the largest virtual stiffness
//! that stays stable for every plant of a box, e.g. from the ungrabbed device to a device
//! held firmly by an arm. Wired into `hapstab kmax --robust`.
//!
//! Parts: [`json`] is the `--json` answer, [`text`] the printed one.

mod json;
mod text;

use anyhow::{Result, bail};
use clap::Args;
use hapstab::limits::{box_plants, robust_kmax_cost};
use hapstab::paper::nyquist::{BoxOptions, PlantBox, robust_kmax_with_progress};
use hapstab::params::{Arm, Device};

use crate::budget::{self, Driver};
use crate::model::PlantArgs;
use crate::output::sig;
use crate::progress::Bar;
use json::json_out;
use text::print_text;

/// Default of `--box-samples`.
const DEFAULT_BOX_SAMPLES: usize = 33;

/// Box flags of `hapstab kmax --robust`. Without them the box runs from the ungrabbed
/// device (the device flags) to the device held by the arm (the arm flags, default a typical
/// arm): mass ∈ [m_L, m_L + m_H], damping ∈ [b_L, b_L + b_H], stiffness ∈ [0, k_H].
#[derive(Args, Debug, Clone, Default)]
pub struct RobustArgs {
    /// Normalized box: γ range LO,HI or LO:HI (with --box-delta; α and β are then reported).
    #[arg(long, value_name = "LO,HI", value_parser = parse_span, allow_hyphen_values = true)]
    pub box_gamma: Option<Span>,
    /// Normalized box: δ range LO,HI or LO:HI.
    #[arg(long, value_name = "LO,HI", value_parser = parse_span, allow_hyphen_values = true)]
    pub box_delta: Option<Span>,
    /// Physical box: effective mass range LO,HI or LO:HI in kg, e.g. 0.2,1.2.
    #[arg(long, value_name = "LO,HI", value_parser = parse_span, allow_hyphen_values = true)]
    pub box_mass: Option<Span>,
    /// Physical box: effective damping range LO,HI or LO:HI in Ns/m.
    #[arg(long, value_name = "LO,HI", value_parser = parse_span, allow_hyphen_values = true)]
    pub box_damping: Option<Span>,
    /// Physical box: effective stiffness range LO,HI or LO:HI in N/m.
    #[arg(long, value_name = "LO,HI", value_parser = parse_span, allow_hyphen_values = true)]
    pub box_stiffness: Option<Span>,
    /// Stiffness (or γ) samples of the box before refinement.
    #[arg(long, default_value_t = DEFAULT_BOX_SAMPLES)]
    pub box_samples: usize,
}

/// A closed range [lo, hi] of a box flag.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span(pub [f64; 2]);

/// Parses a box range written LO,HI or LO:HI (two finite numbers).
fn parse_span(s: &str) -> Result<Span, String> {
    let (lo, hi) = s
        .split_once(',')
        .or_else(|| s.split_once(':'))
        .ok_or_else(|| format!("expected LO,HI or LO:HI, e.g. 0.2,1.2 (got '{s}')"))?;
    let num = |t: &str| match t.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("'{}' is not a finite number (in '{s}')", t.trim())),
    };
    Ok(Span([num(lo)?, num(hi)?]))
}

/// Runs the robust K_max search of `hapstab kmax --robust` on the box described by the
/// plant flags and the `--box-*` flags (robust design beyond the paper).
pub fn run_robust(plant: &PlantArgs, b: &RobustArgs, json: bool) -> Result<()> {
    if plant.gamma.is_some() || plant.delta.is_some() {
        bail!("with --robust give a normalized box as --box-gamma lo,hi --box-delta lo,hi");
    }
    if plant.mass.is_some() || plant.damping.is_some() || plant.stiffness.is_some() {
        bail!(
            "with --robust give ranges as --box-mass/--box-damping/--box-stiffness lo,hi (or device and arm flags)"
        );
    }
    let span = |v: Option<Span>| v.map(|s| s.0);
    let ng = span(b.box_gamma);
    let nd = span(b.box_delta);
    let pm = span(b.box_mass);
    let pd = span(b.box_damping);
    let ps = span(b.box_stiffness);
    let sampling = plant.sampling()?;
    let normalized = ng.is_some() || nd.is_some();
    let pbox = if normalized {
        if pm.is_some() || pd.is_some() || ps.is_some() {
            bail!("give either a normalized box (--box-gamma/--box-delta) or a physical one");
        }
        PlantBox::normalized(
            ng.unwrap_or([0.0, 0.0]),
            nd.unwrap_or([0.0, 0.0]),
            sampling.delay,
        )?
    } else {
        let device = Device {
            mass: plant.device_mass.unwrap_or(Device::PHANTOM_LIKE.mass),
            damping: plant.device_damping.unwrap_or(Device::PHANTOM_LIKE.damping),
        };
        let base = if plant.no_arm {
            Arm::NONE
        } else {
            Arm::TYPICAL
        };
        let arm = Arm {
            mass: plant.arm_mass.unwrap_or(base.mass),
            damping: plant.arm_damping.unwrap_or(base.damping),
            stiffness: plant.arm_stiffness.unwrap_or(base.stiffness),
        };
        let mut pb = PlantBox::ungrabbed_to_grabbed(device, arm, sampling.period, sampling.delay)?;
        if let Some(r) = pm {
            pb.mass = r;
        }
        if let Some(r) = pd {
            pb.damping = r;
        }
        if let Some(r) = ps {
            pb.stiffness = r;
        }
        pb.validated()?
    };
    let opts = BoxOptions {
        stiffness_samples: b.box_samples.max(2),
        ..Default::default()
    };
    let bar = checked_bar(&pbox, opts, b.box_samples, json)?;
    let r = robust_kmax_with_progress(&pbox, opts, &bar.stage(0))?;
    bar.finish();
    if json {
        return json_out(&r, b.box_samples, normalized);
    }
    print_text(&r, normalized);
    Ok(())
}

/// Samples of a range: one when it is a single value.
fn samples_of(range: [f64; 2], n: usize) -> usize {
    if range[1] > range[0] { n } else { 1 }
}

/// Refuses a box search beyond the command-line budget (naming --box-samples or --delay)
/// and returns the progress bar of the damping scan.
fn checked_bar(pbox: &PlantBox, opts: BoxOptions, box_samples: usize, json: bool) -> Result<Bar> {
    let plants = box_plants(
        samples_of(pbox.mass, opts.mass_samples),
        samples_of(pbox.damping, opts.damping_samples),
        samples_of(pbox.stiffness, opts.stiffness_samples),
    );
    budget::check(
        robust_kmax_cost(plants, opts.beta_samples, pbox.d),
        &format!("the robust search over {} plants", sig(plants, 3)),
        &[
            Driver::count("--box-samples", box_samples, DEFAULT_BOX_SAMPLES),
            Driver::delay(pbox.d),
        ],
    )?;
    Ok(Bar::new(opts.beta_samples.max(8), "dampings", !json))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalized_and_physical_boxes_run() {
        let plant = PlantArgs::default();
        let b = RobustArgs {
            box_gamma: Some(Span([0.0, 1e-3])),
            box_delta: Some(Span([0.0, 0.015])),
            box_samples: 5,
            ..Default::default()
        };
        run_robust(&plant, &b, true).unwrap();
        assert!(parse_span("0").is_err());
        assert!(parse_span("0,x").is_err());
        assert_eq!(parse_span("0.2:1.2"), Ok(Span([0.2, 1.2])));
        assert_eq!(parse_span("-1,2"), Ok(Span([-1.0, 2.0])));
        let mixed = RobustArgs {
            box_gamma: Some(Span([0.0, 1e-3])),
            box_mass: Some(Span([0.1, 1.0])),
            ..Default::default()
        };
        assert!(run_robust(&plant, &mixed, false).is_err());
        let phys = RobustArgs {
            box_samples: 5,
            ..Default::default()
        };
        run_robust(&plant, &phys, false).unwrap();
    }
}
