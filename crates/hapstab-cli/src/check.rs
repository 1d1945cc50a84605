//! `hapstab check`: verdict, spectral radius, roots and the stable stiffness range at the
//! given damping, for any loop (Sections III, V); for the paper's loop also the normalized
//! view and the linear condition (eq. 22–23); the wall's gain, phase and delay margins and the
//! frequency at which it would oscillate.

use anyhow::Result;
use clap::Args;
use hapstab::boundary::Interval;
use hapstab::margins::margins_beside_verdict;
use hapstab::margins::report::MarginsReport;
use hapstab::params::Wall;
use hapstab::{AffineFamily, Normalized};
use num_complex::Complex64;
use serde::Serialize;

use crate::model::{
    LoopArgs, LoopInput, NON_PAPER_PLANT_FLAGS, ResolvedLoop, WallArgs, describe_loop,
    resolve_loop_wall,
};
use crate::output::{eng, print_json, radius_text, sig};
use crate::wall_plot;
use hapstab::loop_analysis::{analysis, linear_k, pick_interval, stable_intervals, wall_units};

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

/// The paper's normalized view of the point (Table I) with the linear condition.
#[derive(Serialize)]
struct PaperView {
    /// The point in normalized units (used by the text output in both modes).
    #[serde(skip)]
    point: Normalized,
    /// The same point in the output, for a loop given in physical units only (in normalized
    /// mode it is the input).
    #[serde(skip_serializing_if = "Option::is_none")]
    normalized: Option<Normalized>,
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
    #[serde(flatten)]
    margins: MarginsReport,
    /// Files written by --plot.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    plot: Vec<std::path::PathBuf>,
}

/// The margins of the wall in the report's form, or none with the reason when the check's
/// verdict says the wall is not stable.
fn margins_out(rl: &ResolvedLoop, w: Wall, stable: bool) -> Result<MarginsReport> {
    Ok(MarginsReport::from(&margins_beside_verdict(
        &rl.lp, w, stable,
    )?))
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
    let point = Normalized::new(alpha, beta, pp.gamma, pp.delta, d)?;
    Ok(Some(PaperView {
        point,
        normalized: (!rl.normalized).then_some(point),
        alpha_interval: interval_units(rl, fam, w)?.map(|iv| [iv.lo, iv.hi]),
        alpha_linear: hapstab::linear::linear_alpha_limit(beta, pp.delta, d),
        k_linear,
    }))
}

/// Refuses a check beyond the command-line budget: the roots and the interval grow as n²
/// and n in the degree n of p(z), the margins of a stable wall (the Schur–Cohn test, O(n²),
/// says whether they run) as n times the degree of the loop's parts without the pure delay,
/// and a --plot draws the exact region. Blames the flag that sets most of the degree.
fn check_budget(
    a: &CheckArgs,
    rl: &ResolvedLoop,
    fam: &AffineFamily,
    (alpha, beta): (f64, f64),
) -> Result<()> {
    let n = fam.degree();
    let core = hapstab::limits::core_degree(fam);
    let stable = hapstab::stability::schur_stable(&fam.coefficients(alpha, beta));
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
    let fam = AffineFamily::of_loop(&rl.lp)?;
    let w = resolve_loop_wall(&rl, &fam, &a.wall)?;
    let units = wall_units(&rl.lp, &fam, w)?;
    check_budget(a, &rl, &fam, units)?;
    let analysis = analysis(&rl.lp, &fam, units)?;
    let k_interval = if rl.normalized {
        None
    } else {
        Some(k_interval(&fam, interval_units(&rl, &fam, w)?))
    };
    let mut out = CheckOut {
        input: rl.input(Some(w)),
        stable: analysis.stable(),
        verdict: analysis.verdict.as_str(),
        spectral_radius: analysis.spectral_radius,
        roots: analysis.roots.clone(),
        k_interval,
        paper: paper_view(&rl, &fam, w)?,
        margins: margins_out(&rl, w, analysis.stable())?,
        plot: Vec::new(),
    };
    if let Some(path) = &a.plot {
        let fig = crate::check_plot::CheckFigure {
            wall: units,
            verdict: out.verdict,
            roots: &out.roots,
            spectral_radius: out.spectral_radius,
        };
        out.plot = crate::check_plot::save(&rl, &fam, &fig, path)?;
    }
    if a.json {
        print_json(&out)?;
    } else {
        print_text(&rl, w, &out);
        if !out.plot.is_empty() {
            println!("plot        {}", wall_plot::files_text(&out.plot));
        }
    }
    if a.fail_unstable && !out.stable {
        use std::io::Write;
        let _ = std::io::stdout().flush();
        std::process::exit(1);
    }
    Ok(())
}

fn print_text(rl: &ResolvedLoop, w: Wall, o: &CheckOut) {
    if !rl.normalized {
        for line in describe_loop(&rl.lp) {
            println!("{line}");
        }
        println!(
            "wall      K = {}, B = {}",
            eng(w.stiffness, "N/m", 6),
            eng(w.damping, "Ns/m", 6)
        );
    }
    if let Some(p) = &o.paper {
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

fn print_alpha_interval(o: &CheckOut) {
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

fn print_k_interval(w: Wall, o: &CheckOut) {
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
