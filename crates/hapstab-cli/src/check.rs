//! `hapstab check`: verdict, spectral radius, roots and the stable stiffness range at the
//! given damping, for any loop (Sections III, V); for the paper's loop also the normalized
//! view and the linear condition (eq. 22–23); the wall's gain, phase and delay margins and the
//! frequency at which it would oscillate.

use anyhow::Result;
use clap::Args;
use hapstab::answer::{CheckAnswer, check_answer};
use hapstab::margins::report::MarginsReport;
use hapstab::params::Wall;
use serde::Serialize;

use crate::model::{
    LoopArgs, NON_PAPER_PLANT_FLAGS, ResolvedLoop, WallArgs, print_loop_and_wall, resolve_loop_wall,
};
use crate::output::{eng, print_json, radius_text, sig};
use crate::wall_plot;
use hapstab::System;

/// Arguments of `hapstab check`.
#[derive(Args, Debug)]
#[command(mut_arg("alpha", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
#[command(mut_arg("beta", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
pub struct CheckArgs {
    #[command(flatten)]
    lp: LoopArgs,
    #[command(flatten)]
    wall: WallArgs,
    /// Draw the stable region with the wall marked and, beside it, the roots of p(z) with
    /// the unit circle, each over a zoom (onto the wall and its nearest boundary, onto z = 1),
    /// to FILE: SVG or PNG by its extension (both FILE.svg and FILE.png for any other name);
    /// K (N/m) and B (Ns/m) for a physical loop, α and β normalized.
    #[arg(long, value_name = "FILE")]
    plot: Option<std::path::PathBuf>,
    /// Exit with status 1 when the wall is not stable (marginal or unstable), for scripts and
    /// CI; without it the status is 0 whenever the check ran (2 for bad input).
    #[arg(long)]
    fail_unstable: bool,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// The library's check answer with the files --plot wrote.
#[derive(Serialize)]
struct CheckOut {
    #[serde(flatten)]
    answer: CheckAnswer,
    /// Files written by --plot.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    plot: Vec<std::path::PathBuf>,
}

/// Refuses a check beyond the command-line budget: the roots and the interval grow as n²
/// and n in the degree n of p(z), the margins of a stable wall (the Schur–Cohn test, O(n²),
/// says whether they run) as n times the degree of the loop's parts without the pure delay,
/// and a --plot draws the exact region. Blames the flag that sets most of the degree.
fn check_budget(a: &CheckArgs, rl: &ResolvedLoop, sys: &System, units: (f64, f64)) -> Result<()> {
    let fam = sys.family();
    let n = fam.degree();
    let core = hapstab::limits::core_degree(fam);
    let stable = sys.decide(units).verdict == hapstab::Verdict::Stable;
    let mut cost = hapstab::limits::check_cost(n, core, stable);
    if a.plot.is_some() {
        cost = cost.then(hapstab::limits::region_cost_of_degree(n, core));
    }
    let what = if stable {
        "the verdict and the margins"
    } else {
        "the verdict"
    };
    crate::budget::check(cost, what, &crate::budget::degree_drivers(&a.lp, &rl.lp))
}

/// Runs `hapstab check`.
pub fn run(a: &CheckArgs) -> Result<()> {
    let rl = a.lp.resolve(a.wall.normalized())?;
    let sys = rl.system()?;
    let fam = sys.family();
    let w = resolve_loop_wall(&rl, fam, &a.wall)?;
    let units = sys.wall_units(w)?;
    check_budget(a, &rl, &sys, units)?;
    let mut out = CheckOut {
        answer: check_answer(&sys, rl.normalized, w)?,
        plot: Vec::new(),
    };
    if let Some(path) = &a.plot {
        let fig = crate::check_plot::CheckFigure {
            wall: units,
            verdict: out.answer.verdict,
            roots: &out.answer.roots,
            spectral_radius: out.answer.spectral_radius,
        };
        out.plot = crate::check_plot::save(&rl, &sys, &fig, path)?;
    }
    if a.json {
        print_json(&out)?;
    } else {
        print_text(&rl, w, &out.answer);
        if !out.plot.is_empty() {
            println!("plot        {}", wall_plot::files_text(&out.plot));
        }
    }
    if a.fail_unstable && !out.answer.stable {
        use std::io::Write;
        let _ = std::io::stdout().flush();
        std::process::exit(1);
    }
    Ok(())
}

fn print_text(rl: &ResolvedLoop, w: Wall, o: &CheckAnswer) {
    if !rl.normalized {
        print_loop_and_wall(&rl.lp, w);
    }
    // physical input speaks K, B; the paper's normalized view stays in the JSON
    if let (Some(p), true) = (&o.paper, rl.normalized) {
        let n = &p.point;
        println!(
            "normalized  α = {}, β = {}, γ = {}, δ = {}, d = {}",
            sig(n.alpha, 6),
            sig(n.beta, 6),
            sig(n.gamma, 6),
            sig(n.delta, 6),
            n.d
        );
    }
    println!(
        "verdict     {} (spectral radius {})",
        o.verdict.to_uppercase(),
        radius_text(o.spectral_radius)
    );
    if rl.normalized {
        print_alpha_interval(o);
    } else {
        print_k_interval(w, o);
    }
    print_margins(rl, &o.margins);
}

fn print_margins(rl: &ResolvedLoop, m: &MarginsReport) {
    let hz = |f: f64| {
        if rl.normalized {
            format!("{} cycles/sample", sig(f, 6))
        } else {
            eng(f, "Hz", 6)
        }
    };
    let secs = |s: f64| {
        if rl.normalized {
            format!("{} samples", sig(s, 6))
        } else {
            eng(s, "s", 6)
        }
    };
    let mut parts: Vec<String> = Vec::new();
    let at = |f: Option<f64>| f.map(|f| format!(" (at {})", hz(f))).unwrap_or_default();
    let both = |up: Option<f64>, down: Option<f64>| match (up, down) {
        (Some(u), Some(d)) => Some(format!("×{} / ×{}", sig(u, 6), sig(d, 6))),
        (Some(u), None) => Some(format!("×{}", sig(u, 6))),
        (None, Some(d)) => Some(format!("×{}", sig(d, 6))),
        (None, None) => None,
    };
    if let Some(g) = both(m.gain_margin, m.gain_margin_lower) {
        parts.push(format!("gain {g} on (K, B){}", at(m.phase_crossover_hz)));
    }
    if let Some(g) = both(m.stiffness_margin, m.stiffness_margin_lower) {
        parts.push(format!("{g} on K{}", at(m.stiffness_crossover_hz)));
    }
    if let Some(p) = m.phase_margin_deg {
        parts.push(format!("phase {}°{}", sig(p, 6), at(m.gain_crossover_hz)));
    }
    if let Some(d) = m.delay_margin {
        let pm = m
            .delay_margin_pm_over_wc
            .map(|x| format!(", PM/ω_c {}", secs(x)))
            .unwrap_or_default();
        parts.push(format!(
            "delay +{}{}{pm}",
            secs(d),
            at(m.delay_margin_frequency_hz)
        ));
    }
    if let Some(d) = m.delay_margin_at_least {
        parts.push(format!("delay > +{}", secs(d)));
    }
    if let Some(sm) = m.stability_margin {
        parts.push(format!(
            "min |1 + L| = {}{}",
            sig(sm, 6),
            at(m.stability_margin_hz)
        ));
    }
    let mut label = "margins    ";
    for part in &parts {
        println!("{label} {part}");
        label = "           ";
    }
    for n in &m.margin_notes {
        println!("{label} {n}");
        label = "           ";
    }
}

fn print_alpha_interval(o: &CheckAnswer) {
    let Some(p) = &o.paper else { return };
    let beta = sig(p.point.beta, 6);
    match p.alpha_interval {
        Some([lo, hi]) => println!(
            "stiffness   stable for {} < α < {} at β = {beta} (linear condition (23): α < {})",
            sig(lo, 6),
            sig(hi, 6),
            sig(p.alpha_linear, 6)
        ),
        None => println!("stiffness   no stable α at β = {beta}"),
    }
}

fn print_k_interval(w: Wall, o: &CheckAnswer) {
    let b = eng(w.damping, "Ns/m", 6);
    let linear = o
        .paper
        .as_ref()
        .and_then(|p| p.k_linear)
        .map(|k| format!(" (linear condition (22): K < {})", eng(k, "N/m", 6)))
        .unwrap_or_default();
    match &o.k_interval {
        Some(Some([lo, hi])) => println!(
            "stiffness   stable for {} < K < {} at B = {b}{linear}",
            eng(*lo, "N/m", 6),
            eng(*hi, "N/m", 6)
        ),
        Some(None) => println!("stiffness   no stable K at B = {b}"),
        None => {}
    }
}
