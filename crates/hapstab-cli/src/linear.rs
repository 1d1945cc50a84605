//! `hapstab linear`: the linear stability condition (22)/(23) and where its relative error
//! (24) along the exact boundary first reaches given levels (Sections VI–VII, Fig. 7).

use anyhow::{Result, bail};
use clap::Args;
use hapstab::PlantParams;
use hapstab::limits::validity_points_cost;
use hapstab::model::Loop;
use hapstab::paper::linear::{PhysicalLinear, ValidityPoint, linear_condition};
use serde::Serialize;

use crate::budget::{self, Driver};
use crate::model::{PlantArgs, PlantModel};
use crate::output::{eng, print_json, sig};

/// Arguments of `hapstab linear`.
#[derive(Args, Debug)]
pub struct LinearArgs {
    #[command(flatten)]
    plant: PlantArgs,
    /// Error levels of eq. (24), comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "0.02,0.05",
        allow_hyphen_values = true
    )]
    levels: Vec<f64>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct PointOut {
    level: f64,
    alpha: f64,
    beta: f64,
    /// α_lin of (23) at the same β.
    alpha_linear: f64,
    /// The error (24) at the point.
    error: f64,
    /// K and B in N/m and Ns/m (physical mode only).
    #[serde(skip_serializing_if = "Option::is_none")]
    wall_stiffness: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    wall_damping: Option<f64>,
    /// K_lin of (23) in N/m at the same B (physical mode only).
    #[serde(skip_serializing_if = "Option::is_none")]
    k_linear: Option<f64>,
}

/// The plant as given (after defaults) and the error levels.
#[derive(Serialize)]
struct LinearInput {
    #[serde(flatten)]
    plant: PlantInput,
    levels: Vec<f64>,
}

/// The plant: normalized (Table I) or the effective plant in SI units.
#[derive(Serialize)]
#[serde(untagged)]
enum PlantInput {
    Normalized {
        gamma: f64,
        delta: f64,
        d: usize,
    },
    Physical {
        mass: f64,
        damping: f64,
        stiffness: f64,
        period: f64,
        d: usize,
    },
}

/// The normalized view of a physical plant (Table I).
#[derive(Serialize)]
struct NormalizedPlant {
    gamma: f64,
    delta: f64,
    d: usize,
}

#[derive(Serialize)]
struct LinearOut {
    input: LinearInput,
    /// γ, δ, d of a plant given in physical units.
    #[serde(skip_serializing_if = "Option::is_none")]
    normalized: Option<NormalizedPlant>,
    /// Condition (23): α < (β + δ)/(d + 1/2), as slope and intercept in β.
    linear_slope: f64,
    linear_intercept: f64,
    /// Lower bound (19): α > −γ.
    alpha_lower: f64,
    /// The same in N/m and Ns/m for a plant given in physical units.
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    physical: Option<PhysicalLinear>,
    points: Vec<PointOut>,
}

/// Runs `hapstab linear`.
pub fn run(a: &LinearArgs) -> Result<()> {
    if a.levels.is_empty() {
        bail!("--levels needs at least one value");
    }
    let pm = crate::loop_file::paper_plant(&a.plant, "the linear condition (22)")?.resolve()?;
    budget::check(
        validity_points_cost(a.levels.len(), pm.d),
        &format!("the validity points of {} levels", a.levels.len()),
        &[
            Driver {
                flag: "--levels",
                value: format!("({} values)", a.levels.len()),
                factor: a.levels.len() as f64 / 2.0,
            },
            Driver::delay(pm.d),
        ],
    )?;
    let lp = match pm.physical {
        Some((eff, s)) => Loop::paper(eff, s.period, pm.d)?,
        None => Loop::normalized(PlantParams::new(pm.gamma, pm.delta)?, pm.d)?,
    };
    let lc = linear_condition(&lp, &a.levels)?;
    let scale = pm.physical.map(|_| (lc.units.stiffness, lc.units.damping));
    let pts = &lc.points;
    let out = LinearOut {
        input: LinearInput {
            plant: plant_input(&pm),
            levels: a.levels.clone(),
        },
        normalized: pm.physical.map(|_| NormalizedPlant {
            gamma: pm.gamma,
            delta: pm.delta,
            d: pm.d,
        }),
        linear_slope: lc.slope,
        linear_intercept: lc.intercept,
        alpha_lower: lc.alpha_lower,
        physical: pm.physical.map(|_| lc.physical()),
        points: pts
            .iter()
            .map(|p| PointOut {
                level: p.level,
                alpha: p.alpha,
                beta: p.beta,
                alpha_linear: p.alpha_linear,
                error: p.error,
                wall_stiffness: scale.map(|(k, _)| p.alpha * k),
                wall_damping: scale.map(|(_, b)| p.beta * b),
                k_linear: scale.map(|_| lc.k_linear(p)),
            })
            .collect(),
    };
    if a.json {
        return print_json(&out);
    }
    print_text(&pm, &out, pts);
    Ok(())
}

/// The plant as the user gave it: normalized (γ, δ, d) or physical (m, b, k, T, d).
fn plant_input(pm: &PlantModel) -> PlantInput {
    match pm.physical {
        None => PlantInput::Normalized {
            gamma: pm.gamma,
            delta: pm.delta,
            d: pm.d,
        },
        Some((eff, s)) => PlantInput::Physical {
            mass: eff.mass,
            damping: eff.damping,
            stiffness: eff.stiffness,
            period: s.period,
            d: pm.d,
        },
    }
}

/// The human-readable answer of `linear`: the plant, the linear condition (23) with the bound
/// (19), and where the error (24) first reaches each level — in K and B for a plant given in
/// physical units (the normalized view in brackets), in α and β for normalized input.
fn print_text(pm: &PlantModel, out: &LinearOut, pts: &[ValidityPoint]) {
    let view = format!(
        "γ = {}, δ = {}, d = {}",
        sig(pm.gamma, 6),
        sig(pm.delta, 6),
        pm.d
    );
    match (pm.physical, out.physical) {
        (Some((eff, s)), Some(ph)) => {
            println!(
                "plant       m = {}, b = {}, k = {}, T = {}, d = {}   ({view})",
                eng(eff.mass, "kg", 6),
                eng(eff.damping, "Ns/m", 6),
                eng(eff.stiffness, "N/m", 6),
                eng(s.period, "s", 6),
                pm.d
            );
            println!(
                "linear      (23): K < (B + b)/(T(d + 1/2)) = {}/s · B + {};  (19): K > {}",
                sig(ph.k_linear_slope, 6),
                eng(ph.k_linear_intercept, "N/m", 6),
                eng(ph.k_lower, "N/m", 6)
            );
            println!("error (24) first reaches, going up from B = 0⁺ (K on the exact boundary):");
        }
        _ => {
            println!("plant       {view}");
            println!(
                "linear      (23): α < (β + δ)/(d + 1/2) = {}·β + {};  (19): α > {}",
                sig(out.linear_slope, 6),
                sig(out.linear_intercept, 6),
                sig(out.alpha_lower, 6)
            );
            println!("error (24) first reaches, going up from β = 0⁺ (α on the exact boundary):");
        }
    }
    for (p, q) in out.points.iter().zip(pts) {
        let note = if q.at_start {
            "   (already at 0⁺)"
        } else {
            ""
        };
        let level = sig(p.level * 100.0, 4);
        match (p.wall_stiffness, p.wall_damping, p.k_linear) {
            (Some(k), Some(b), Some(kl)) => println!(
                "  {level:>5} %   B = {}   K = {}   K_lin = {}   (β = {}, α = {}){note}",
                eng(b, "Ns/m", 6),
                eng(k, "N/m", 6),
                eng(kl, "N/m", 6),
                sig(p.beta, 6),
                sig(p.alpha, 6)
            ),
            _ => println!(
                "  {level:>5} %   β = {}   α = {}   α_lin = {}{note}",
                sig(p.beta, 6),
                sig(p.alpha, 6),
                sig(p.alpha_linear, 6)
            ),
        }
    }
}
