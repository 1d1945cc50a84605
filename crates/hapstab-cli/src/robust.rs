//! Robust K_max across a range of plants (beyond the paper): the largest virtual stiffness
//! that stays stable for every plant of a box, e.g. from the ungrabbed device to a device
//! held firmly by an arm. Wired into `hapstab kmax --robust`.

use anyhow::{Result, bail};
use clap::Args;
use hapstab::limits::{box_plants, robust_kmax_cost};
use hapstab::nyquist::{BoxOptions, PlantBox, RobustKmax, robust_kmax_with_progress};
use hapstab::params::{Arm, Device};
use serde::Serialize;

use crate::budget::{self, Driver};
use crate::model::PlantArgs;
use crate::output::{eng, print_json, sig};
use crate::progress::Bar;

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

/// The box as given, after defaults: physical (kg, Ns/m, N/m) or normalized (γ, δ).
#[derive(Serialize)]
#[serde(untagged)]
enum BoxInput {
    Physical {
        mass: [f64; 2],
        damping: [f64; 2],
        stiffness: [f64; 2],
        period: f64,
        d: usize,
    },
    Normalized {
        gamma: [f64; 2],
        delta: [f64; 2],
        d: usize,
    },
}

#[derive(Serialize)]
struct RobustInput {
    #[serde(rename = "box")]
    plant_box: BoxInput,
    box_samples: usize,
}

/// The plant of the box that limits K_max.
#[derive(Serialize)]
#[serde(untagged)]
enum WorstPlant {
    Physical {
        mass: f64,
        damping: f64,
        stiffness: f64,
    },
    Normalized {
        gamma: f64,
        delta: f64,
    },
}

/// `kmax --robust --json` of a physical box (N/m, Ns/m).
#[derive(Serialize)]
struct PhysicalOut {
    input: RobustInput,
    k_max: f64,
    b_at_k_max: f64,
    /// Lower end of the robust K interval at that B.
    k_min: f64,
    worst_plant: WorstPlant,
    /// Linear condition (22) for the worst plant at the same B.
    k_linear_worst: f64,
    /// K_max and its B normalized with the smallest mass of the box: K T²/m, B T/m.
    normalized_at_min_mass: hapstab::boundary::AlphaBeta,
    plants_sampled: usize,
}

/// `kmax --robust --json` of a normalized box (α, β).
#[derive(Serialize)]
struct NormalizedOut {
    input: RobustInput,
    alpha_max: f64,
    beta_at_alpha_max: f64,
    alpha_min: f64,
    worst_plant: WorstPlant,
    /// Linear condition (23) for the worst plant at the same β.
    alpha_linear_worst: f64,
    plants_sampled: usize,
}

fn json_out(r: &RobustKmax, samples: usize, normalized: bool) -> Result<()> {
    let pb = &r.plant_box;
    let [m, b, k] = r.worst_plant;
    let k_linear_worst = (b + r.damping_at_max) / ((pb.d as f64 + 0.5) * pb.period);
    if normalized {
        let input = RobustInput {
            plant_box: BoxInput::Normalized {
                gamma: pb.stiffness,
                delta: pb.damping,
                d: pb.d,
            },
            box_samples: samples,
        };
        return print_json(&NormalizedOut {
            input,
            alpha_max: r.stiffness_max,
            beta_at_alpha_max: r.damping_at_max,
            alpha_min: r.stiffness_min,
            worst_plant: WorstPlant::Normalized { gamma: k, delta: b },
            alpha_linear_worst: k_linear_worst,
            plants_sampled: r.plants_sampled,
        });
    }
    let input = RobustInput {
        plant_box: BoxInput::Physical {
            mass: pb.mass,
            damping: pb.damping,
            stiffness: pb.stiffness,
            period: pb.period,
            d: pb.d,
        },
        box_samples: samples,
    };
    print_json(&PhysicalOut {
        input,
        k_max: r.stiffness_max,
        b_at_k_max: r.damping_at_max,
        k_min: r.stiffness_min,
        worst_plant: WorstPlant::Physical {
            mass: m,
            damping: b,
            stiffness: k,
        },
        k_linear_worst,
        normalized_at_min_mass: r.normalized_at_min_mass,
        plants_sampled: r.plants_sampled,
    })
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

fn print_text(r: &RobustKmax, normalized: bool) {
    let pb = &r.plant_box;
    let [m, b, k] = r.worst_plant;
    let k_linear_worst = (b + r.damping_at_max) / ((pb.d as f64 + 0.5) * pb.period);
    if normalized {
        println!(
            "box         γ ∈ [{}, {}], δ ∈ [{}, {}], d = {} ({} plants sampled)",
            sig(pb.stiffness[0], 6),
            sig(pb.stiffness[1], 6),
            sig(pb.damping[0], 6),
            sig(pb.damping[1], 6),
            pb.d,
            r.plants_sampled
        );
        println!(
            "robust      α_max = {} at β = {} (limited by γ = {}, δ = {})",
            sig(r.stiffness_max, 6),
            sig(r.damping_at_max, 6),
            sig(k, 6),
            sig(b, 6)
        );
        println!(
            "linear      (23) for that plant at the same β: α < {}",
            sig(k_linear_worst, 6)
        );
    } else {
        println!(
            "box         m ∈ [{}, {}], b ∈ [{}, {}], k ∈ [{}, {}]; T = {}, d = {} ({} plants sampled)",
            eng(pb.mass[0], "kg", 6),
            eng(pb.mass[1], "kg", 6),
            eng(pb.damping[0], "Ns/m", 6),
            eng(pb.damping[1], "Ns/m", 6),
            eng(pb.stiffness[0], "N/m", 6),
            eng(pb.stiffness[1], "N/m", 6),
            eng(pb.period, "s", 6),
            pb.d,
            r.plants_sampled
        );
        println!(
            "robust      K_max = {} at B = {}, stable for every plant of the box",
            eng(r.stiffness_max, "N/m", 6),
            eng(r.damping_at_max, "Ns/m", 6)
        );
        println!(
            "            limited by m = {}, b = {}, k = {}",
            eng(m, "kg", 6),
            eng(b, "Ns/m", 6),
            eng(k, "N/m", 6)
        );
        println!(
            "linear      (22) for that plant at the same B: K < {}",
            eng(k_linear_worst, "N/m", 6)
        );
    }
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
