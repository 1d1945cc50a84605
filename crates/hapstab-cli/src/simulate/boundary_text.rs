//! The text `hapstab simboundary` prints: the loop, the runs' setting, the exact K_max (α_max
//! in normalized units) and the table of the simulated boundary against the linear one, with
//! notes and warnings.

use hapstab::simulation::{Outcome, StableWhen};

use super::boundary_out::SimboundaryOut;
use super::run_args::RunSettings;
use super::{Units, describe_effects};
use crate::model::{ResolvedLoop, print_loop};
use crate::output::{eng, sig};

/// The loop of a boundary search: in physical units the loop in words (and, beyond the
/// paper's loop, its wall units); in normalized units the paper's (γ, δ, d).
fn print_boundary_loop(o: &SimboundaryOut, rl: &ResolvedLoop, units: Units) {
    match rl.lp.paper_view() {
        Some(pp) if !units.physical => println!(
            "plant       γ = {}, δ = {}, d = {}",
            sig(pp.gamma, 6),
            sig(pp.delta, 6),
            rl.lp.delay.samples
        ),
        _ => {
            print_loop(&rl.lp);
            if let Some(w) = o.wall_units {
                println!(
                    "units     a = K/k_u, b = B/(k_u·T) with k_u = {} N/m, k_u·T = {} Ns/m (the a and b of --alpha/--beta)",
                    sig(w.stiffness, 6),
                    sig(w.damping, 6)
                );
            }
        }
    }
}

/// N/m per unit of the wall's normalized stiffness (α for the paper's loop: m/T², Table I;
/// a for another loop: its wall units), in physical units.
fn k_per_unit(o: &SimboundaryOut, units: Units) -> Option<f64> {
    if !units.physical {
        return None;
    }
    o.wall_units
        .map(|w| w.stiffness)
        .or(o.mass.map(|m| m / (o.period * o.period)))
}

/// The exact K_max (α_max) of the linear loop.
fn print_exact(o: &SimboundaryOut, k_per: Option<f64>) {
    match k_per {
        None => println!(
            "exact       α_max = {} at β = {} (linear stable region, Section V)",
            sig(o.exact.0, 6),
            sig(o.exact.1, 6)
        ),
        Some(k) => {
            let b_per = k * o.period;
            println!(
                "exact       K_max = {} at B = {} (linear stable region, Section V)",
                eng(o.exact.0 * k, "N/m", 6),
                eng(o.exact.1 * b_per, "Ns/m", 6)
            );
        }
    }
}

/// Why a row's simulated boundary is what it is, in the table's stiffness.
fn row_note(p: &hapstab::simulation::EmpiricalPoint, k_per: Option<f64>) -> String {
    let at = |alpha: f64| match k_per {
        Some(k) => format!("K = {}", eng(alpha * k, "N/m", 4)),
        None => format!("α = {}", sig(alpha, 6)),
    };
    if let Some(i) = p
        .inconclusive
        .filter(|i| p.a_unstable.is_none_or(|u| i.a < u) && p.a_simulated.is_none_or(|s| i.a > s))
    {
        let what = match i.outcome {
            Outcome::Separated => "left the wall",
            _ => "undecided",
        };
        format!("{what} at {}: no verdict beyond", at(i.a))
    } else if p.a_simulated.is_none() {
        p.a_unstable.map_or_else(
            || "unstable".into(),
            |u| format!("unstable already at {}", at(u)),
        )
    } else if p.censored {
        format!("stable up to scan end {}", at(p.a_max))
    } else {
        String::new()
    }
}

/// The table of the simulated boundary against the linear one: K and B in physical units,
/// α and β in normalized units.
fn print_table(o: &SimboundaryOut, k_per: Option<f64>) {
    let f = |v: Option<f64>, n| v.map_or_else(|| "-".to_string(), |x| sig(x, n));
    if k_per.is_some() {
        println!(
            "{:>12} {:>16} {:>16} {:>8}  note",
            "B (Ns/m)", "K linear (N/m)", "K simulated (N/m)", "ratio"
        );
    } else {
        println!(
            "{:>10} {:>14} {:>14} {:>8}  note",
            "β", "α linear", "α simulated", "ratio"
        );
    }
    for r in &o.points {
        let p = &r.point;
        let note = row_note(p, k_per);
        if let Some(q) = r.physical() {
            println!(
                "{:>12} {:>16} {:>16} {:>8}  {note}",
                sig(q.wall_damping, 6),
                f(q.k_linear, 8),
                f(q.k_simulated, 8),
                f(r.ratio, 4)
            );
        } else {
            println!(
                "{:>10} {:>14} {:>14} {:>8}  {note}",
                sig(p.b, 6),
                f(p.a_linear, 8),
                f(p.a_simulated, 8),
                f(r.ratio, 4)
            );
        }
    }
}

/// The runs' setting: length, start and what counts as stable.
fn print_runs(o: &SimboundaryOut) {
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
}

pub(super) fn print_simboundary(
    o: &SimboundaryOut,
    rl: &ResolvedLoop,
    s: &RunSettings,
    units: Units,
) {
    print_boundary_loop(o, rl, units);
    println!("effects     {}", describe_effects(s, units.force()));
    print_runs(o);
    let k_per = k_per_unit(o, units);
    print_exact(o, k_per);
    println!();
    print_table(o, k_per);
    println!();
    if s.effects.quantization.is_some()
        && o.input.stable_when == StableWhen::Decaying
        && o.points.iter().any(|r| {
            r.point.a_simulated.is_none()
                && r.point.a_unstable.is_some()
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
