//! `hapstab check`: verdict, spectral radius, roots and the stable stiffness range at the
//! given damping (Sections III, V; eq. 22–23 for the linear estimate).

use anyhow::Result;
use clap::Args;
use hapstab::boundary::{Interval, stable_alpha_intervals};
use hapstab::stability::Analysis;
use hapstab::{Normalized, PolyFamily};
use num_complex::Complex64;
use serde::Serialize;

use crate::model::{PlantArgs, WallArgs, resolve_point};
use crate::output::{print_json, sig};

/// Arguments of `hapstab check`.
#[derive(Args, Debug)]
pub struct CheckArgs {
    #[command(flatten)]
    plant: PlantArgs,
    #[command(flatten)]
    wall: WallArgs,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct PhysicalOut {
    mass: f64,
    damping: f64,
    stiffness: f64,
    period: f64,
    delay_time: f64,
    wall_stiffness: f64,
    wall_damping: f64,
    /// Stable K range at the given B, N/m.
    k_interval: Option<[f64; 2]>,
    /// Linear condition (22): K < (b + B)/(t_d + T/2), N/m.
    k_linear: f64,
}

#[derive(Serialize)]
struct CheckOut {
    stable: bool,
    verdict: &'static str,
    spectral_radius: f64,
    roots: Vec<Complex64>,
    normalized: Normalized,
    /// Stable α interval at the given β that contains α, or the one reaching furthest.
    alpha_interval: Option<[f64; 2]>,
    /// Linear condition (23): α < (β + δ)/(d + 1/2).
    alpha_linear: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    physical: Option<PhysicalOut>,
}

fn pick_interval(ivs: &[Interval], alpha: f64) -> Option<Interval> {
    ivs.iter()
        .find(|iv| iv.lo < alpha && alpha < iv.hi)
        .or_else(|| ivs.iter().max_by(|a, b| a.hi.total_cmp(&b.hi)))
        .copied()
}

/// Runs `hapstab check`.
pub fn run(a: &CheckArgs) -> Result<()> {
    let pm = resolve_point(&a.plant, &a.wall)?;
    let n = pm.normalized;
    let analysis = Analysis::new(n)?;
    let fam = PolyFamily::new(n.plant(), n.d)?;
    let iv = pick_interval(&stable_alpha_intervals(&fam, n.beta), n.alpha);
    let alpha_linear = (n.beta + n.delta) / (n.d as f64 + 0.5);
    let physical = pm.physical.map(|p| {
        let k_per_alpha = p.plant.mass / (p.sampling.period * p.sampling.period);
        let tr = p.sampling.delay_time() + p.sampling.period / 2.0;
        PhysicalOut {
            mass: p.plant.mass,
            damping: p.plant.damping,
            stiffness: p.plant.stiffness,
            period: p.sampling.period,
            delay_time: p.sampling.delay_time(),
            wall_stiffness: p.wall.stiffness,
            wall_damping: p.wall.damping,
            k_interval: iv.map(|i| [i.lo * k_per_alpha, i.hi * k_per_alpha]),
            k_linear: (p.plant.damping + p.wall.damping) / tr,
        }
    });
    let out = CheckOut {
        stable: analysis.stable(),
        verdict: analysis.verdict.as_str(),
        spectral_radius: analysis.spectral_radius,
        roots: analysis.roots.clone(),
        normalized: n,
        alpha_interval: iv.map(|i| [i.lo, i.hi]),
        alpha_linear,
        physical,
    };
    if a.json {
        return print_json(&out);
    }
    print_text(&out);
    Ok(())
}

fn print_text(o: &CheckOut) {
    let n = &o.normalized;
    if let Some(p) = &o.physical {
        println!(
            "plant   m = {} kg, b = {} Ns/m, k = {} N/m; T = {} ms, delay d = {} ({} ms)",
            sig(p.mass, 6),
            sig(p.damping, 6),
            sig(p.stiffness, 6),
            sig(p.period * 1e3, 6),
            n.d,
            sig(p.delay_time * 1e3, 6)
        );
        println!(
            "wall    K = {} N/m, B = {} Ns/m",
            sig(p.wall_stiffness, 6),
            sig(p.wall_damping, 6)
        );
    }
    println!(
        "normalized  α = {}, β = {}, γ = {}, δ = {}, d = {}",
        sig(n.alpha, 8),
        sig(n.beta, 8),
        sig(n.gamma, 8),
        sig(n.delta, 8),
        n.d
    );
    println!(
        "verdict     {} (spectral radius {:.15})",
        o.verdict.to_uppercase(),
        o.spectral_radius
    );
    match (&o.physical, o.alpha_interval) {
        (Some(p), _) => match p.k_interval {
            Some([lo, hi]) => println!(
                "stiffness   stable for {} < K < {} N/m at B = {} Ns/m (linear condition (22): K < {} N/m)",
                sig(lo, 10),
                sig(hi, 10),
                sig(p.wall_damping, 6),
                sig(p.k_linear, 10)
            ),
            None => println!(
                "stiffness   no stable K at B = {} Ns/m",
                sig(p.wall_damping, 6)
            ),
        },
        (None, Some([lo, hi])) => println!(
            "stiffness   stable for {} < α < {} at β = {} (linear condition (23): α < {})",
            sig(lo, 12),
            sig(hi, 12),
            sig(n.beta, 8),
            sig(o.alpha_linear, 12)
        ),
        (None, None) => println!("stiffness   no stable α at β = {}", sig(n.beta, 8)),
    }
}
