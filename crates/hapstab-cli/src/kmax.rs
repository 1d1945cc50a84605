//! `hapstab kmax`: the largest stable virtual stiffness in N/m for a device (with an optional
//! arm), beside the linear condition (b + B)/(t_d + T/2) of eq. (22).

use anyhow::{Result, bail};
use clap::Args;
use hapstab::PolyFamily;
use hapstab::boundary::stable_alpha_intervals;
use serde::Serialize;

use crate::model::PlantArgs;
use crate::output::{print_json, sig};

/// Arguments of `hapstab kmax`.
#[derive(Args, Debug)]
pub struct KmaxArgs {
    #[command(flatten)]
    plant: PlantArgs,
    /// Virtual damping B in Ns/m; without it, the overall K_max and the B that reaches it.
    #[arg(long, allow_hyphen_values = true)]
    wall_damping: Option<f64>,
    /// Robust design (beyond the paper): K_max stable for every plant in a box, by default
    /// from the ungrabbed device to the device held by the arm (see --box-* flags).
    #[arg(long)]
    robust: bool,
    #[command(flatten)]
    robust_box: crate::robust::RobustArgs,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct KmaxOut {
    /// Largest stable K in N/m.
    k_max: Option<f64>,
    /// B at which the overall K_max is reached (when no B was given), Ns/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    b_at_k_max: Option<f64>,
    /// The given B, Ns/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    wall_damping: Option<f64>,
    /// Stable K interval at the given B (lower end is −k), N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    k_interval: Option<[f64; 2]>,
    /// Linear condition (22): (b + B)/(t_d + T/2) at the same B, N/m.
    k_linear: f64,
    /// Normalized values.
    alpha_max: Option<f64>,
    beta: Option<f64>,
    gamma: f64,
    delta: f64,
    d: usize,
}

/// Runs `hapstab kmax`.
pub fn run(a: &KmaxArgs) -> Result<()> {
    if a.robust {
        return crate::robust::run_robust(&a.plant, &a.robust_box, a.json);
    }
    let pm = a.plant.resolve()?;
    let Some((eff, s)) = pm.physical else {
        bail!("kmax works in physical units; for normalized parameters use `hapstab boundary`");
    };
    let kpa = eff.mass / (s.period * s.period);
    let bpb = eff.mass / s.period;
    let tr = s.delay_time() + s.period / 2.0;
    let fam = PolyFamily::new(hapstab::PlantParams::new(pm.gamma, pm.delta)?, pm.d)?;
    let out = match a.wall_damping {
        Some(b) => {
            if !b.is_finite() {
                bail!("wall damping B must be a finite number (got {b})");
            }
            let beta = b / bpb;
            let best = stable_alpha_intervals(&fam, beta)
                .into_iter()
                .max_by(|x, y| x.hi.total_cmp(&y.hi));
            KmaxOut {
                k_max: best.map(|i| i.hi * kpa),
                b_at_k_max: None,
                wall_damping: Some(b),
                k_interval: best.map(|i| [i.lo * kpa, i.hi * kpa]),
                k_linear: (eff.damping + b) / tr,
                alpha_max: best.map(|i| i.hi),
                beta: Some(beta),
                gamma: pm.gamma,
                delta: pm.delta,
                d: pm.d,
            }
        }
        None => {
            let r = hapstab::region::stable_region(&fam)?;
            let found = !r.polygons.is_empty();
            let b = r.beta_at_alpha_max * bpb;
            KmaxOut {
                k_max: found.then_some(r.alpha_max * kpa),
                b_at_k_max: found.then_some(b),
                wall_damping: None,
                k_interval: None,
                k_linear: (eff.damping + if found { b } else { 0.0 }) / tr,
                alpha_max: found.then_some(r.alpha_max),
                beta: found.then_some(r.beta_at_alpha_max),
                gamma: pm.gamma,
                delta: pm.delta,
                d: pm.d,
            }
        }
    };
    if a.json {
        return print_json(&out);
    }
    println!(
        "plant m = {} kg, b = {} Ns/m, k = {} N/m; T = {} ms, d = {}",
        sig(eff.mass, 6),
        sig(eff.damping, 6),
        sig(eff.stiffness, 6),
        sig(s.period * 1e3, 6),
        pm.d
    );
    match (out.k_max, out.wall_damping, out.b_at_k_max) {
        (None, _, _) => println!("no stable virtual stiffness exists"),
        (Some(k), Some(b), _) => println!(
            "K_max = {} N/m at B = {} Ns/m (stable for {} < K < {}); linear condition (22): {} N/m",
            sig(k, 12),
            sig(b, 8),
            sig(out.k_interval.map_or(f64::NAN, |i| i[0]), 8),
            sig(k, 12),
            sig(out.k_linear, 12)
        ),
        (Some(k), None, Some(b)) => println!(
            "K_max = {} N/m, reached at B = {} Ns/m; linear condition (22) at that B: {} N/m",
            sig(k, 12),
            sig(b, 12),
            sig(out.k_linear, 12)
        ),
        _ => {}
    }
    Ok(())
}
