//! `hapstab nyquist`: stable regions up to the Nyquist frequency, the robustly stable region
//! and Colgate's passive region (Section VIII, eq. 25–28, Figs. 8–10), or with physical
//! units the stiffness that brings a device to the Nyquist frequency (Remark 4).

use anyhow::{Result, bail};
use clap::Args;
use hapstab::paper::nyquist::{
    NyquistRegions, NyquistStiffness, SweepInput, nyquist_regions, nyquist_stiffness,
};
use serde::Serialize;

use crate::budget::{self, Driver};
use crate::model::{DEFAULT_PERIOD, PlantArgs, delay_samples};
use crate::output::{eng, or_dash, print_json, sig};
use crate::progress::Bar;

/// Default of `--steps`.
const DEFAULT_STEPS: usize = 4;
/// Default of `--beta-samples`.
const DEFAULT_BETA_SAMPLES: usize = 201;
/// Default of `--gamma-samples`.
const DEFAULT_GAMMA_SAMPLES: usize = 41;
/// Arguments of `hapstab nyquist`: the normalized plant (--delta, --delay) for the regions,
/// or the plant in physical units (the same flags as every command) for Remark 4.
/// `--gamma` and `--stiffness` are refused (γ is swept, Remark 4 computes the stiffness), so
/// their help is hidden.
#[derive(Args, Debug)]
#[command(mut_arg("gamma", |a| a.hide(true)))]
#[command(mut_arg("stiffness", |a| a.hide(true)))]
pub struct NyquistArgs {
    #[command(flatten)]
    plant: PlantArgs,
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
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// Remark 4's inputs: the effective mass and damping and the period.
#[derive(Serialize)]
struct Remark4Input {
    mass: f64,
    damping: f64,
    period: f64,
}

/// `nyquist --json` with physical units (Remark 4).
#[derive(Serialize)]
struct Remark4Out {
    input: Remark4Input,
    /// k = π² m/T² + b²/(4m) in N/m.
    stiffness: f64,
    /// δ = bT/m.
    delta: f64,
    /// γ_N = π² + δ²/4 (eq. 27).
    gamma_nyquist: f64,
    /// The Nyquist frequency 1/(2T) in Hz.
    nyquist_frequency_hz: f64,
}

/// The plant flags with a --loop file's paper loop filled in, but not the parts that
/// `nyquist` sweeps or that Remark 4 leaves out (γ, k, the delay of a physical loop).
fn nyquist_plant(given: &PlantArgs) -> Result<PlantArgs> {
    let mut p = crate::loop_file::paper_plant(given, "nyquist")?;
    p.gamma = given.gamma;
    p.stiffness = given.stiffness;
    p.arm_stiffness = given.arm_stiffness;
    if p.any_physical() {
        p.delay = given.delay;
    }
    Ok(p)
}

/// Runs `hapstab nyquist`.
pub fn run(a: &NyquistArgs) -> Result<()> {
    let p = &nyquist_plant(&a.plant)?;
    if p.gamma.is_some() {
        bail!("--gamma: nyquist sweeps γ itself up to γ_N; give the plant's --delta");
    }
    if let Some(t) = p.delay_time {
        bail!(
            "--delay-time {t}: nyquist's regions take a whole delay of the normalized loop (--delay d), and Remark 4 (physical units) does not depend on the delay; leave it out"
        );
    }
    if p.any_physical() {
        if let Some(d) = p.delay {
            bail!(
                "--delay {d}: Remark 4 (physical units) does not depend on the delay; leave it out, or give the normalized plant (--delta) for the regions at that delay"
            );
        }
        return run_remark4(a, p);
    }
    let delta = p.delta.unwrap_or(0.0);
    let delay = delay_samples(p.delay.unwrap_or(0.0))?;
    check_sweep_args(a)?;
    let input = SweepInput {
        delta,
        d: delay,
        gamma_fraction: a.gamma_fraction,
        steps: a.steps,
        beta_samples: a.beta_samples,
        gamma_samples: a.gamma_samples,
    };
    let cost = input.cost();
    budget::check(
        cost,
        "the sweep and the robust region",
        &[
            Driver::count("--steps", a.steps, DEFAULT_STEPS),
            Driver::count("--beta-samples", a.beta_samples, DEFAULT_BETA_SAMPLES),
            Driver::count("--gamma-samples", a.gamma_samples, DEFAULT_GAMMA_SAMPLES),
            Driver::delay(delay),
        ],
    )?;
    // one bar over the three stages: sweep regions, robust slices, passivity slices
    let bar = Bar::new(
        input.stages().iter().sum::<usize>(),
        "steps",
        !a.json && cost.seconds >= crate::progress::LONG_SECONDS,
    );
    let out = nyquist_regions(input, &bar.stage(0))?;
    bar.finish();
    if a.json {
        return print_json(&out);
    }
    print_text(&out);
    Ok(())
}

/// The sweep's own flags: --gamma-fraction finite and ≥ 0, --steps ≥ 1.
fn check_sweep_args(a: &NyquistArgs) -> Result<()> {
    if !(a.gamma_fraction.is_finite() && a.gamma_fraction >= 0.0) {
        bail!(
            "--gamma-fraction must be a finite number >= 0 (got {})",
            a.gamma_fraction
        );
    }
    if a.steps == 0 {
        bail!("--steps must be >= 1");
    }
    Ok(())
}

/// Remark 4 for the effective plant of the physical flags: the stiffness that brings it to
/// the Nyquist frequency (the arm's own stiffness and the delay play no part).
fn run_remark4(a: &NyquistArgs, p: &PlantArgs) -> Result<()> {
    if p.stiffness.is_some() {
        bail!(
            "--stiffness: Remark 4 computes the stiffness that reaches the Nyquist frequency; leave it out"
        );
    }
    let eff = p.effective()?;
    let r = nyquist_stiffness(eff.mass, eff.damping, p.period.unwrap_or(DEFAULT_PERIOD))?;
    if a.json {
        return print_json(&Remark4Out {
            input: Remark4Input {
                mass: r.mass,
                damping: r.damping,
                period: r.period,
            },
            stiffness: r.stiffness,
            delta: r.delta,
            gamma_nyquist: r.gamma,
            nyquist_frequency_hz: 0.5 / r.period,
        });
    }
    print_remark4(&r);
    Ok(())
}

fn print_remark4(r: &NyquistStiffness) {
    println!(
        "device      m = {}, b = {}, T = {} (δ = {})",
        eng(r.mass, "kg", 6),
        eng(r.damping, "Ns/m", 6),
        eng(r.period, "s", 6),
        sig(r.delta, 6)
    );
    println!(
        "Remark 4    k = π² m/T² + b²/(4m) = {} reaches the Nyquist frequency π/T = {} rad/s ({})",
        eng(r.stiffness, "N/m", 6),
        sig(r.nyquist_frequency, 6),
        eng(0.5 / r.period, "Hz", 6)
    );
    println!(
        "            (γ_N = π² + δ²/4 = {}, eq. 27)",
        sig(r.gamma, 6)
    );
}

fn print_text(o: &NyquistRegions) {
    let (delta, gn) = (o.input.delta, o.gamma_nyquist);
    println!(
        "plant       δ = {}, d = {};  Nyquist at γ_N = π² + δ²/4 = {} (eq. 27)",
        sig(delta, 6),
        o.input.d,
        sig(gn, 6)
    );
    println!("stable regions (exact α-intervals on a β grid; — where undefined):");
    println!(
        "  {:>12}  {:>12}  {:>12}  {:>12}  {:>12}  note",
        "γ", "γ/γ_N", "α_max", "β at α_max", "area"
    );
    for s in &o.sweep {
        let note = if s.degenerate {
            "pole at z = ±1 for every (α, β): limit stable at best"
        } else if s.empty {
            "empty"
        } else if s.beta_at_alpha_max.is_none() {
            "every stable point has α ≤ 0 (α_max below 1e-12: round-off)"
        } else {
            ""
        };
        let num = |x: f64| or_dash(x, |v| sig(v, 6));
        println!(
            "  {:>12}  {:>12}  {:>12}  {:>12}  {:>12}  {note}",
            sig(s.gamma, 6),
            sig(s.gamma / gn, 6),
            num(s.alpha_max),
            s.beta_at_alpha_max.map_or("—".into(), num),
            num(s.area)
        );
    }
    let r = &o.robust;
    if r.empty {
        println!(
            "robust      over γ ∈ [0, {}]: no robustly stable point off the boundary (at most the origin)",
            sig(r.gamma_hi, 6)
        );
    } else {
        println!(
            "robust      over γ ∈ [0, {}]: α_max = {} at β = {}, area = {} ({} polygon vertices)",
            sig(r.gamma_hi, 6),
            sig(r.alpha_max, 6),
            sig(r.beta_at_alpha_max, 6),
            sig(r.area, 6),
            r.polygon.len()
        );
    }
    if !r.degenerate_gammas.is_empty() {
        let gs: Vec<String> = r.degenerate_gammas.iter().map(|g| sig(*g, 6)).collect();
        println!(
            "            degenerate γ (limit from inside used): {}",
            gs.join(", ")
        );
    }
    if let Some(p) = &o.passive {
        println!(
            "passive     eq. (28): δ > α/2 + |β|, α ≥ 0: triangle (0, ±{}), ({}, 0), area {}{}",
            sig(delta, 6),
            sig(2.0 * delta, 6),
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
            sig(p.check.min_right_margin, 6),
            sig(p.check.beta_at_min_right_margin, 6)
        );
    }
}
