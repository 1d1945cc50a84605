//! `hapstab nyquist`: stable regions up to the Nyquist frequency, the robustly stable region
//! and Colgate's passive region (Section VIII, eq. 25–28, Figs. 8–10), or with physical
//! units the stiffness that brings a device to the Nyquist frequency (Remark 4).

use anyhow::{Result, bail};
use clap::Args;
use hapstab::boundary::AlphaBeta;
use hapstab::limits::{Cost, gamma_sweep_cost, passive_check_cost, robust_region_cost};
use hapstab::nyquist::{
    NyquistStiffness, PassiveCheck, RegionSummary, RobustOptions, gamma_sweep_with_progress,
    nyquist_gamma, nyquist_stiffness, passive_inside_robust_with_progress, passive_region,
    robust_region_with_progress,
};
use serde::Serialize;

use crate::budget::{self, Driver};
use crate::output::{print_json, sig};
use crate::progress::Bar;

/// Default of `--steps`.
const DEFAULT_STEPS: usize = 4;
/// Default of `--beta-samples`.
const DEFAULT_BETA_SAMPLES: usize = 201;
/// Default of `--gamma-samples`.
const DEFAULT_GAMMA_SAMPLES: usize = 41;
/// β samples of the passivity check (Section VIII-A).
const PASSIVE_SAMPLES: usize = 41;

/// Arguments of `hapstab nyquist`.
#[derive(Args, Debug)]
pub struct NyquistArgs {
    /// Normalized physical damping δ = bT/m.
    #[arg(long, allow_hyphen_values = true)]
    delta: Option<f64>,
    /// Delay d in whole samples.
    #[arg(long, default_value_t = 0)]
    delay: usize,
    /// Sweep γ up to this fraction of γ_N = π² + δ²/4 (eq. 27).
    #[arg(long, allow_hyphen_values = true, default_value_t = 1.0)]
    gamma_fraction: f64,
    /// Number of γ steps of the sweep.
    #[arg(long, default_value_t = DEFAULT_STEPS)]
    steps: usize,
    /// β samples per stable region of the sweep.
    #[arg(long, default_value_t = DEFAULT_BETA_SAMPLES)]
    beta_samples: usize,
    /// γ samples of the robust region.
    #[arg(long, default_value_t = DEFAULT_GAMMA_SAMPLES)]
    gamma_samples: usize,
    /// Remark 4: effective mass m in kg.
    #[arg(long, allow_hyphen_values = true)]
    mass: Option<f64>,
    /// Remark 4: sampling period T in s [default 0.001].
    #[arg(long, allow_hyphen_values = true)]
    period: Option<f64>,
    /// Remark 4: effective damping b in Ns/m [default 0].
    #[arg(long, allow_hyphen_values = true)]
    damping: Option<f64>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct RobustOut {
    gamma_lo: f64,
    gamma_hi: f64,
    empty: bool,
    alpha_max: f64,
    beta_at_alpha_max: f64,
    area: f64,
    degenerate_gammas: Vec<f64>,
    multiple_intervals: bool,
    polygon: Vec<AlphaBeta>,
}

#[derive(Serialize)]
struct PassiveOut {
    vertices: Vec<AlphaBeta>,
    area: f64,
    /// Eq. (28) is Colgate's condition for d = 0.
    applies: bool,
    check: PassiveCheck,
}

#[derive(Serialize)]
struct NyquistOut {
    delta: f64,
    d: usize,
    /// γ_N = π² + δ²/4 (eq. 27).
    gamma_nyquist: f64,
    sweep: Vec<RegionSummary>,
    robust: RobustOut,
    #[serde(skip_serializing_if = "Option::is_none")]
    passive: Option<PassiveOut>,
}

/// Runs `hapstab nyquist`.
pub fn run(a: &NyquistArgs) -> Result<()> {
    let physical = a.mass.is_some() || a.period.is_some() || a.damping.is_some();
    if physical {
        if a.delta.is_some() {
            bail!("give either --delta (normalized) or --mass/--period/--damping, not both");
        }
        let Some(m) = a.mass else {
            bail!("Remark 4 needs --mass (kg)");
        };
        let r = nyquist_stiffness(m, a.damping.unwrap_or(0.0), a.period.unwrap_or(1e-3))?;
        if a.json {
            return print_json(&r);
        }
        print_remark4(&r);
        return Ok(());
    }
    let delta = a.delta.unwrap_or(0.0);
    if !(a.gamma_fraction.is_finite() && a.gamma_fraction >= 0.0) {
        bail!(
            "--gamma-fraction must be a finite number >= 0 (got {})",
            a.gamma_fraction
        );
    }
    if a.steps == 0 {
        bail!("--steps must be >= 1");
    }
    hapstab::params::check_delay(a.delay)?;
    let opts = RobustOptions {
        gamma_samples: a.gamma_samples.max(2),
        ..Default::default()
    };
    let cost = estimate(a, delta, opts);
    budget::check(
        cost,
        "the sweep and the robust region",
        &[
            Driver::count("--steps", a.steps, DEFAULT_STEPS),
            Driver::count("--beta-samples", a.beta_samples, DEFAULT_BETA_SAMPLES),
            Driver::count("--gamma-samples", a.gamma_samples, DEFAULT_GAMMA_SAMPLES),
            Driver::delay(a.delay),
        ],
    )?;
    let gn = nyquist_gamma(delta);
    let g_hi = gn * a.gamma_fraction;
    // one bar over the three stages: sweep regions, robust slices, passivity slices
    let stages = [a.steps + 1, opts.beta_samples.max(8), PASSIVE_SAMPLES];
    let bar = Bar::new(
        stages.iter().sum::<usize>(),
        "steps",
        !a.json && cost.seconds >= crate::progress::LONG_SECONDS,
    );
    let sweep = gamma_sweep_with_progress(
        delta,
        a.delay,
        a.gamma_fraction,
        a.steps,
        a.beta_samples,
        &bar.stage(0),
    )?;
    let r = robust_region_with_progress(delta, a.delay, 0.0, g_hi, opts, &bar.stage(stages[0]))?;
    let passive = if delta > 0.0 {
        let p = passive_region(delta)?;
        let check = passive_inside_robust_with_progress(
            delta,
            a.delay,
            0.0,
            g_hi,
            PASSIVE_SAMPLES,
            opts,
            &bar.stage(stages[0] + stages[1]),
        )?;
        Some(PassiveOut {
            area: p.area(),
            vertices: p.vertices,
            applies: a.delay == 0,
            check,
        })
    } else {
        None
    };
    bar.finish();
    let out = NyquistOut {
        delta,
        d: a.delay,
        gamma_nyquist: gn,
        sweep,
        robust: RobustOut {
            gamma_lo: 0.0,
            gamma_hi: g_hi,
            empty: r.empty,
            alpha_max: r.alpha_max,
            beta_at_alpha_max: r.beta_at_alpha_max,
            area: r.area,
            degenerate_gammas: r.degenerate_gammas,
            multiple_intervals: r.multiple_intervals,
            polygon: r.polygon,
        },
        passive,
    };
    if a.json {
        return print_json(&out);
    }
    print_text(&out);
    Ok(())
}

/// The estimated cost of the sweep, the robust region and the passivity check.
fn estimate(a: &NyquistArgs, delta: f64, opts: RobustOptions) -> Cost {
    let sweep = gamma_sweep_cost(a.steps, a.beta_samples, a.delay);
    let robust = robust_region_cost(
        opts.gamma_samples,
        opts.beta_samples,
        a.delay,
        opts.refine_gamma,
        opts.refine_beta_rounds,
    );
    let passive = if delta > 0.0 {
        passive_check_cost(PASSIVE_SAMPLES, opts.gamma_samples, a.delay)
    } else {
        Cost::ZERO
    };
    sweep.then(robust).then(passive)
}

fn print_remark4(r: &NyquistStiffness) {
    println!(
        "device      m = {} kg, b = {} Ns/m, T = {} ms (δ = {})",
        sig(r.mass, 6),
        sig(r.damping, 6),
        sig(r.period * 1e3, 6),
        sig(r.delta, 6)
    );
    println!(
        "Remark 4    k = π² m/T² + b²/(4m) = {:.1} kN/m ({} N/m) reaches the Nyquist frequency π/T = {} rad/s",
        r.stiffness / 1e3,
        sig(r.stiffness, 10),
        sig(r.nyquist_frequency, 6)
    );
    println!(
        "            (γ_N = π² + δ²/4 = {}, eq. 27)",
        sig(r.gamma, 10)
    );
}

fn print_text(o: &NyquistOut) {
    println!(
        "plant       δ = {}, d = {};  Nyquist at γ_N = π² + δ²/4 = {} (eq. 27)",
        sig(o.delta, 8),
        o.d,
        sig(o.gamma_nyquist, 10)
    );
    println!("stable regions (exact α-intervals on a β grid):");
    println!(
        "  {:>12}  {:>12}  {:>14}  {:>12}  {:>12}  note",
        "γ", "γ/γ_N", "α_max", "β at α_max", "area"
    );
    for s in &o.sweep {
        let note = if s.degenerate {
            "pole at z = ±1 for every (α, β): limit stable at best"
        } else if s.empty {
            "empty"
        } else if s.alpha_max <= 1e-12 {
            "all stable points have α ≤ 0"
        } else {
            ""
        };
        println!(
            "  {:>12}  {:>12}  {:>14}  {:>12}  {:>12}  {note}",
            sig(s.gamma, 8),
            sig(s.gamma / o.gamma_nyquist, 4),
            sig(s.alpha_max, 8),
            sig(s.beta_at_alpha_max, 6),
            sig(s.area, 6)
        );
    }
    let r = &o.robust;
    if r.empty {
        println!(
            "robust      over γ ∈ [0, {}]: no robustly stable point off the boundary (at most the origin)",
            sig(r.gamma_hi, 8)
        );
    } else {
        println!(
            "robust      over γ ∈ [0, {}]: α_max = {} at β = {}, area = {} ({} polygon vertices)",
            sig(r.gamma_hi, 8),
            sig(r.alpha_max, 8),
            sig(r.beta_at_alpha_max, 6),
            sig(r.area, 6),
            r.polygon.len()
        );
    }
    if !r.degenerate_gammas.is_empty() {
        println!(
            "            degenerate γ (limit from inside used): {:?}",
            r.degenerate_gammas
        );
    }
    if let Some(p) = &o.passive {
        println!(
            "passive     eq. (28): δ > α/2 + |β|, α ≥ 0: triangle (0, ±{}), ({}, 0), area {}{}",
            sig(o.delta, 6),
            sig(2.0 * o.delta, 6),
            sig(p.area, 6),
            if p.applies {
                ""
            } else {
                " (Colgate's condition is for d = 0)"
            }
        );
        println!(
            "            {} the robust region (smallest margin {} at β = {})",
            if p.check.inside {
                "inside"
            } else {
                "NOT inside"
            },
            sig(p.check.min_right_margin, 4),
            sig(p.check.beta_at_min_right_margin, 6)
        );
    }
}
