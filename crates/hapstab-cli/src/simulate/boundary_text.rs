//! The text `hapstab simboundary` prints: the loop, the runs' setting, the exact α_max and
//! the table of the simulated boundary against the linear one, with notes and warnings.

use hapstab::simulation::{Outcome, StableWhen};

use super::boundary::SimboundaryOut;
use super::run_args::RunSettings;
use super::{Units, describe_effects};
use crate::model::{ResolvedLoop, describe_loop};
use crate::output::{eng, sig};

/// The loop of a boundary search: the paper's (γ, δ, d), or the loop in words with its wall
/// units.
fn print_boundary_loop(o: &SimboundaryOut, rl: &ResolvedLoop, units: Units) {
    let Some((gamma, delta, d)) = rl
        .lp
        .paper_view()
        .map(|pp| (pp.gamma, pp.delta, rl.lp.delay.samples))
    else {
        for line in describe_loop(&rl.lp) {
            println!("{line}");
        }
        if let Some(w) = o.wall_units {
            println!(
                "units     a = K/k_u, b = B/(k_u·T) with k_u = {} N/m, k_u·T = {} Ns/m (the α and β columns and flags)",
                sig(w.stiffness, 6),
                sig(w.damping, 6)
            );
        }
        return;
    };
    println!(
        "plant       γ = {}, δ = {}, d = {}{}",
        sig(gamma, 6),
        sig(delta, 6),
        d,
        match o.mass {
            Some(m) if units.physical => {
                format!(" (m = {} kg, T = {} ms)", sig(m, 6), sig(o.period * 1e3, 6))
            }
            _ => String::new(),
        }
    );
}

pub(super) fn print_simboundary(
    o: &SimboundaryOut,
    rl: &ResolvedLoop,
    s: &RunSettings,
    units: Units,
) {
    print_boundary_loop(o, rl, units);
    println!("effects     {}", describe_effects(s, units.force()));
    println!(
        "runs        {} samples each (extended up to {} until settled) from x(0) = {}; stable = {}",
        o.input.samples,
        o.input.max_samples,
        eng(o.input.initial.position, "m", 6),
        match o.input.stable_when {
            StableWhen::Decaying => "decaying".to_string(),
            StableWhen::AmplitudeBelow(m) => format!(
                "decaying or limit cycle below {} peak-to-peak",
                eng(m, "m", 4)
            ),
        }
    );
    match o.wall_units {
        None => println!(
            "exact       α_max = {} at β = {} (linear stable region, Section V)",
            sig(o.exact_alpha_max, 6),
            sig(o.exact_beta_at_alpha_max, 6)
        ),
        Some(w) => println!(
            "exact       K_max = {} N/m at B = {} Ns/m (a = {}, b = {}; linear stable region)",
            sig(o.exact_alpha_max * w.stiffness, 6),
            sig(o.exact_beta_at_alpha_max * w.damping, 6),
            sig(o.exact_alpha_max, 6),
            sig(o.exact_beta_at_alpha_max, 6)
        ),
    }
    println!();
    let phys = units.physical;
    let (sa, sb) = if o.wall_units.is_some() {
        ("a", "b")
    } else {
        ("α", "β")
    };
    if phys {
        println!(
            "{:>10} {:>10} {:>14} {:>14} {:>8} {:>12} {:>12}  note",
            sb,
            "B (Ns/m)",
            format!("{sa} linear"),
            format!("{sa} simulated"),
            "ratio",
            "K lin (N/m)",
            "K sim (N/m)"
        );
    } else {
        println!(
            "{:>10} {:>14} {:>14} {:>8}  note",
            "β", "α linear", "α simulated", "ratio"
        );
    }
    let f = |v: Option<f64>, n| v.map_or_else(|| "-".to_string(), |x| sig(x, n));
    for r in &o.points {
        let p = &r.point;
        let note = if let Some(i) = p.inconclusive.filter(|i| {
            p.alpha_unstable.is_none_or(|u| i.alpha < u)
                && p.alpha_simulated.is_none_or(|s| i.alpha > s)
        }) {
            let what = match i.outcome {
                Outcome::Separated => "left the wall",
                _ => "undecided",
            };
            format!("{what} at α = {}: no verdict beyond", sig(i.alpha, 6))
        } else if p.alpha_simulated.is_none() {
            format!("unstable already at α = {}", f(p.alpha_unstable, 4))
        } else if p.censored {
            format!("stable up to scan end α = {}", sig(p.alpha_max, 4))
        } else {
            String::new()
        };
        if phys {
            println!(
                "{:>10} {:>10} {:>14} {:>14} {:>8} {:>12} {:>12}  {note}",
                sig(p.beta, 6),
                f(r.wall_damping, 5),
                f(p.alpha_linear, 8),
                f(p.alpha_simulated, 8),
                f(r.ratio, 4),
                f(r.k_linear, 6),
                f(r.k_simulated, 6)
            );
        } else {
            println!(
                "{:>10} {:>14} {:>14} {:>8}  {note}",
                sig(p.beta, 6),
                f(p.alpha_linear, 8),
                f(p.alpha_simulated, 8),
                f(r.ratio, 4)
            );
        }
    }
    println!();
    if s.effects.quantization.is_some()
        && o.input.stable_when == StableWhen::Decaying
        && o.points.iter().any(|r| {
            r.point.alpha_simulated.is_none()
                && r.point.alpha_unstable.is_some()
                && r.point.inconclusive.is_none()
        })
    {
        println!(
            "note        quantized runs often settle into small limit cycles instead of decaying;\n            --stable-amplitude M counts cycles below M metres as stable"
        );
    }
    for w in &o.warnings {
        println!("warning     {w}");
    }
    if let Some(c) = &o.csv {
        println!("csv         {}", c.display());
    }
    if let Some(p) = &o.plot {
        println!("plot        {}, {}", p.svg.display(), p.png.display());
    }
}
