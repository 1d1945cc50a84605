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
use crate::output::{print_json, sig};
use crate::progress::Bar;

/// Default of `--box-samples`.
const DEFAULT_BOX_SAMPLES: usize = 33;

/// Box flags of `hapstab kmax --robust`. Without them the box runs from the ungrabbed
/// device (the device flags) to the device held by the arm (the arm flags, default a typical
/// arm): mass ∈ [m_L, m_L + m_H], damping ∈ [b_L, b_L + b_H], stiffness ∈ [0, k_H].
#[derive(Args, Debug, Clone, Default)]
pub struct RobustArgs {
    /// Normalized box: γ range "lo,hi" (with --box-delta; α and β are then reported).
    #[arg(long, value_delimiter = ',', num_args = 2, allow_hyphen_values = true)]
    pub box_gamma: Option<Vec<f64>>,
    /// Normalized box: δ range "lo,hi".
    #[arg(long, value_delimiter = ',', num_args = 2, allow_hyphen_values = true)]
    pub box_delta: Option<Vec<f64>>,
    /// Physical box: effective mass range "lo,hi" in kg.
    #[arg(long, value_delimiter = ',', num_args = 2, allow_hyphen_values = true)]
    pub box_mass: Option<Vec<f64>>,
    /// Physical box: effective damping range "lo,hi" in Ns/m.
    #[arg(long, value_delimiter = ',', num_args = 2, allow_hyphen_values = true)]
    pub box_damping: Option<Vec<f64>>,
    /// Physical box: effective stiffness range "lo,hi" in N/m.
    #[arg(long, value_delimiter = ',', num_args = 2, allow_hyphen_values = true)]
    pub box_stiffness: Option<Vec<f64>>,
    /// Stiffness (or γ) samples of the box before refinement.
    #[arg(long, default_value_t = DEFAULT_BOX_SAMPLES)]
    pub box_samples: usize,
}

#[derive(Serialize)]
struct RobustOut {
    /// "normalized" (K = α, B = β) or "physical" (N/m, Ns/m).
    units: &'static str,
    k_max: f64,
    b_at_k_max: f64,
    /// Lower end of the robust K interval at that B.
    k_min: f64,
    /// The plant (m, b, k) that limits K_max.
    worst_plant: [f64; 3],
    /// Linear condition (22) for the worst plant at the same B.
    k_linear_worst: f64,
    #[serde(flatten)]
    result: RobustKmax,
}

fn pair(name: &str, v: &Option<Vec<f64>>) -> Result<Option<[f64; 2]>> {
    match v {
        None => Ok(None),
        Some(x) if x.len() == 2 => Ok(Some([x[0], x[1]])),
        Some(x) => bail!("--{name} needs two values lo,hi (got {})", x.len()),
    }
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
    let ng = pair("box-gamma", &b.box_gamma)?;
    let nd = pair("box-delta", &b.box_delta)?;
    let pm = pair("box-mass", &b.box_mass)?;
    let pd = pair("box-damping", &b.box_damping)?;
    let ps = pair("box-stiffness", &b.box_stiffness)?;
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
    let tr = (pbox.d as f64 + 0.5) * pbox.period;
    let out = RobustOut {
        units: if normalized { "normalized" } else { "physical" },
        k_max: r.stiffness_max,
        b_at_k_max: r.damping_at_max,
        k_min: r.stiffness_min,
        worst_plant: r.worst_plant,
        k_linear_worst: (r.worst_plant[1] + r.damping_at_max) / tr,
        result: r,
    };
    if json {
        return print_json(&out);
    }
    let pb = &out.result.plant_box;
    if normalized {
        println!(
            "box         γ ∈ [{}, {}], δ ∈ [{}, {}], d = {} ({} plants sampled)",
            sig(pb.stiffness[0], 6),
            sig(pb.stiffness[1], 6),
            sig(pb.damping[0], 6),
            sig(pb.damping[1], 6),
            pb.d,
            out.result.plants_sampled
        );
        println!(
            "robust      α_max = {} at β = {} (limited by γ = {}, δ = {})",
            sig(out.k_max, 10),
            sig(out.b_at_k_max, 8),
            sig(out.worst_plant[2], 6),
            sig(out.worst_plant[1], 6)
        );
        println!(
            "linear      (23) for that plant at the same β: α < {}",
            sig(out.k_linear_worst, 10)
        );
    } else {
        println!(
            "box         m ∈ [{}, {}] kg, b ∈ [{}, {}] Ns/m, k ∈ [{}, {}] N/m; T = {} ms, d = {} ({} plants sampled)",
            sig(pb.mass[0], 6),
            sig(pb.mass[1], 6),
            sig(pb.damping[0], 6),
            sig(pb.damping[1], 6),
            sig(pb.stiffness[0], 6),
            sig(pb.stiffness[1], 6),
            sig(pb.period * 1e3, 6),
            pb.d,
            out.result.plants_sampled
        );
        println!(
            "robust      K_max = {} N/m at B = {} Ns/m, stable for every plant of the box",
            sig(out.k_max, 10),
            sig(out.b_at_k_max, 8)
        );
        println!(
            "            limited by m = {} kg, b = {} Ns/m, k = {} N/m",
            sig(out.worst_plant[0], 6),
            sig(out.worst_plant[1], 6),
            sig(out.worst_plant[2], 6)
        );
        println!(
            "linear      (22) for that plant at the same B: K < {} N/m",
            sig(out.k_linear_worst, 10)
        );
    }
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
            box_gamma: Some(vec![0.0, 1e-3]),
            box_delta: Some(vec![0.0, 0.015]),
            box_samples: 5,
            ..Default::default()
        };
        run_robust(&plant, &b, true).unwrap();
        let bad = RobustArgs {
            box_gamma: Some(vec![0.0]),
            ..Default::default()
        };
        assert!(run_robust(&plant, &bad, true).is_err());
        let mixed = RobustArgs {
            box_gamma: Some(vec![0.0, 1e-3]),
            box_mass: Some(vec![0.1, 1.0]),
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
