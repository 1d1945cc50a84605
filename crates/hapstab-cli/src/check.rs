//! `hapstab check`: verdict, spectral radius, roots and the stable stiffness range at the
//! given damping, for any loop (Sections III, V); for the paper's loop also the normalized
//! view and the linear condition (eq. 22–23).

use anyhow::Result;
use clap::Args;
use hapstab::boundary::Interval;
use hapstab::params::Wall;
use hapstab::stability::Analysis;
use hapstab::{AffineFamily, Normalized};
use num_complex::Complex64;
use serde::Serialize;

use crate::model::{
    LoopArgs, LoopInput, NON_PAPER_PLANT_FLAGS, ResolvedLoop, WallArgs, describe_loop,
    resolve_loop_wall,
};
use crate::output::{print_json, sig};
use hapstab::loop_analysis::{
    characteristic, linear_k, pick_interval, stable_intervals, wall_units,
};

/// Arguments of `hapstab check`.
#[derive(Args, Debug)]
#[command(mut_arg("alpha", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
#[command(mut_arg("beta", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
pub struct CheckArgs {
    #[command(flatten)]
    lp: LoopArgs,
    #[command(flatten)]
    wall: WallArgs,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// The paper's normalized view of the point (Table I) with the linear condition.
#[derive(Serialize)]
struct PaperView {
    normalized: Normalized,
    /// Stable α interval at the given β that contains α, or the one reaching furthest.
    alpha_interval: Option<[f64; 2]>,
    /// Linear condition (23): α < (β + δ)/(d + 1/2).
    alpha_linear: f64,
    /// Linear condition (22) in N/m: K < (b + B)/(t_d + T/2) (physical loops).
    #[serde(skip_serializing_if = "Option::is_none")]
    k_linear: Option<f64>,
}

#[derive(Serialize)]
struct CheckOut {
    input: LoopInput,
    stable: bool,
    verdict: &'static str,
    spectral_radius: f64,
    roots: Vec<Complex64>,
    /// Stable K interval in N/m at the given B (physical loops): the one containing K, or
    /// the one reaching furthest; null when no K is stable at that B.
    #[serde(skip_serializing_if = "Option::is_none")]
    k_interval: Option<Option<[f64; 2]>>,
    #[serde(flatten)]
    paper: Option<PaperView>,
}

/// The stable interval of the wall's stiffness in the loop's units (a, b) at its damping
/// b: the one containing a, or the one reaching furthest.
fn interval_units(rl: &ResolvedLoop, fam: &AffineFamily, w: Wall) -> Result<Option<Interval>> {
    let (a, b) = wall_units(&rl.lp, fam, w)?;
    Ok(pick_interval(&stable_intervals(&rl.lp, fam, b)?, a))
}

/// The same interval in N/m.
fn k_interval(fam: &AffineFamily, iv: Option<Interval>) -> Option<[f64; 2]> {
    iv.map(|iv| [fam.to_physical(iv.lo, 0.0).0, fam.to_physical(iv.hi, 0.0).0])
}

fn paper_view(rl: &ResolvedLoop, fam: &AffineFamily, w: Wall) -> Result<Option<PaperView>> {
    let Some(pp) = rl.lp.paper_view() else {
        return Ok(None);
    };
    let (alpha, beta) = wall_units(&rl.lp, fam, w)?;
    let d = rl.lp.delay.samples;
    let k_linear = if rl.normalized {
        None
    } else {
        linear_k(&rl.lp, w.damping)
    };
    Ok(Some(PaperView {
        normalized: Normalized::new(alpha, beta, pp.gamma, pp.delta, d)?,
        alpha_interval: interval_units(rl, fam, w)?.map(|iv| [iv.lo, iv.hi]),
        alpha_linear: hapstab::linear::linear_alpha_limit(beta, pp.delta, d),
        k_linear,
    }))
}

/// Runs `hapstab check`.
pub fn run(a: &CheckArgs) -> Result<()> {
    let rl = a.lp.resolve(a.wall.normalized())?;
    let fam = AffineFamily::of_loop(&rl.lp)?;
    let w = resolve_loop_wall(&rl, &fam, &a.wall)?;
    let units = wall_units(&rl.lp, &fam, w)?;
    let analysis = Analysis::of_poly(&characteristic(&rl.lp, &fam, units)?)?;
    let k_interval = if rl.normalized {
        None
    } else {
        Some(k_interval(&fam, interval_units(&rl, &fam, w)?))
    };
    let out = CheckOut {
        input: LoopInput::new(&rl, Some(w)),
        stable: analysis.stable(),
        verdict: analysis.verdict.as_str(),
        spectral_radius: analysis.spectral_radius,
        roots: analysis.roots.clone(),
        k_interval,
        paper: paper_view(&rl, &fam, w)?,
    };
    if a.json {
        return print_json(&out);
    }
    print_text(&rl, w, &out);
    Ok(())
}

fn print_text(rl: &ResolvedLoop, w: Wall, o: &CheckOut) {
    if !rl.normalized {
        for line in describe_loop(&rl.lp) {
            println!("{line}");
        }
        println!(
            "wall      K = {} N/m, B = {} Ns/m",
            sig(w.stiffness, 6),
            sig(w.damping, 6)
        );
    }
    if let Some(p) = &o.paper {
        let n = &p.normalized;
        println!(
            "normalized  α = {}, β = {}, γ = {}, δ = {}, d = {}",
            sig(n.alpha, 8),
            sig(n.beta, 8),
            sig(n.gamma, 8),
            sig(n.delta, 8),
            n.d
        );
    }
    println!(
        "verdict     {} (spectral radius {:.15})",
        o.verdict.to_uppercase(),
        o.spectral_radius
    );
    if rl.normalized {
        print_alpha_interval(o);
    } else {
        print_k_interval(w, o);
    }
}

fn print_alpha_interval(o: &CheckOut) {
    let Some(p) = &o.paper else { return };
    let beta = sig(p.normalized.beta, 8);
    match p.alpha_interval {
        Some([lo, hi]) => println!(
            "stiffness   stable for {} < α < {} at β = {beta} (linear condition (23): α < {})",
            sig(lo, 12),
            sig(hi, 12),
            sig(p.alpha_linear, 12)
        ),
        None => println!("stiffness   no stable α at β = {beta}"),
    }
}

fn print_k_interval(w: Wall, o: &CheckOut) {
    let b = sig(w.damping, 6);
    let linear = o
        .paper
        .as_ref()
        .and_then(|p| p.k_linear)
        .map(|k| format!(" (linear condition (22): K < {} N/m)", sig(k, 10)))
        .unwrap_or_default();
    match &o.k_interval {
        Some(Some([lo, hi])) => println!(
            "stiffness   stable for {} < K < {} N/m at B = {b} Ns/m{linear}",
            sig(*lo, 10),
            sig(*hi, 10)
        ),
        Some(None) => println!("stiffness   no stable K at B = {b} Ns/m"),
        None => {}
    }
}
