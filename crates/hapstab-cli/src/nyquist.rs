//! `hapstab nyquist`: stable regions up to the Nyquist frequency, the robustly stable region
//! and Colgate's passive region (Section VIII, eq. 25–28, Figs. 8–10), or with physical
//! units the stiffness that brings a device to the Nyquist frequency (Remark 4).

use anyhow::{Result, bail};
use clap::Args;
use hapstab::boundary::AlphaBeta;
use hapstab::limits::{Cost, gamma_sweep_cost, passive_check_cost, robust_region_cost};
use hapstab::nyquist::{
    NyquistStiffness, PassiveCheck, RegionSummary, RobustOptions, RobustRegion,
    gamma_sweep_with_progress, nyquist_gamma, nyquist_stiffness,
    passive_inside_robust_with_progress, passive_region, robust_region_with_progress,
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
/// β samples of the passivity check (Section VIII-A).
const PASSIVE_SAMPLES: usize = 41;

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

/// Below this |α_max| a swept region has no stable point with α > 0: its α_max comes out of
/// the golden-section search at round-off level (about 1e-16·γ for γ up to γ_N ≈ 10), far
/// below this bound, and is reported as 0.
const ALPHA_ROUNDOFF: f64 = 1e-12;

/// The inputs of the normalized analysis, after defaults.
#[derive(Serialize)]
struct SweepInput {
    delta: f64,
    d: usize,
    gamma_fraction: f64,
    steps: usize,
    beta_samples: usize,
    gamma_samples: usize,
}

/// One region of the γ sweep (α_max of 0 when every stable point has α ≤ 0, to round-off).
#[derive(Serialize)]
struct SweepRow {
    gamma: f64,
    degenerate: bool,
    empty: bool,
    beta_min: f64,
    beta_max: f64,
    alpha_min: f64,
    alpha_max: f64,
    /// Null when α_max is 0 to round-off (then reached along a boundary segment).
    beta_at_alpha_max: Option<f64>,
    area: f64,
}

impl From<&RegionSummary> for SweepRow {
    fn from(s: &RegionSummary) -> Self {
        let roundoff = s.alpha_max.abs() <= ALPHA_ROUNDOFF;
        SweepRow {
            gamma: s.gamma,
            degenerate: s.degenerate,
            empty: s.empty,
            beta_min: s.beta_min,
            beta_max: s.beta_max,
            alpha_min: s.alpha_min,
            alpha_max: if roundoff { 0.0 } else { s.alpha_max },
            beta_at_alpha_max: (!roundoff).then_some(s.beta_at_alpha_max),
            area: s.area,
        }
    }
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
    /// Counter-clockwise vertices [alpha, beta].
    polygon: Vec<[f64; 2]>,
}

#[derive(Serialize)]
struct PassiveOut {
    /// Vertices [alpha, beta].
    vertices: Vec<[f64; 2]>,
    area: f64,
    /// Eq. (28) is Colgate's condition for d = 0.
    applies: bool,
    check: PassiveCheck,
}

#[derive(Serialize)]
struct NyquistOut {
    input: SweepInput,
    /// γ_N = π² + δ²/4 (eq. 27).
    gamma_nyquist: f64,
    sweep: Vec<SweepRow>,
    robust: RobustOut,
    #[serde(skip_serializing_if = "Option::is_none")]
    passive: Option<PassiveOut>,
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
    let opts = RobustOptions {
        gamma_samples: a.gamma_samples.max(2),
        ..Default::default()
    };
    let cost = estimate(a, delta, delay, opts);
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
        delay,
        a.gamma_fraction,
        a.steps,
        a.beta_samples,
        &bar.stage(0),
    )?;
    let r = robust_region_with_progress(delta, delay, 0.0, g_hi, opts, &bar.stage(stages[0]))?;
    let passive_progress = bar.stage(stages[0] + stages[1]);
    let passive = passive_out(delta, delay, g_hi, opts, &passive_progress)?;
    bar.finish();
    let out = NyquistOut {
        input: SweepInput {
            delta,
            d: delay,
            gamma_fraction: a.gamma_fraction,
            steps: a.steps,
            beta_samples: a.beta_samples,
            gamma_samples: a.gamma_samples,
        },
        gamma_nyquist: gn,
        sweep: sweep.iter().map(SweepRow::from).collect(),
        robust: robust_out(r, g_hi),
        passive,
    };
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

/// Colgate's passive region at δ > 0 and whether it lies inside the robust region over
/// γ ∈ [0, g_hi] (None at δ = 0, where it is empty).
fn passive_out(
    delta: f64,
    delay: usize,
    g_hi: f64,
    opts: RobustOptions,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Option<PassiveOut>> {
    if delta <= 0.0 {
        return Ok(None);
    }
    let p = passive_region(delta)?;
    let check = passive_inside_robust_with_progress(
        delta,
        delay,
        0.0,
        g_hi,
        PASSIVE_SAMPLES,
        opts,
        progress,
    )?;
    Ok(Some(PassiveOut {
        area: p.area(),
        vertices: pairs(&p.vertices),
        applies: delay == 0,
        check,
    }))
}

/// The robust region over γ ∈ [0, g_hi] as `nyquist` reports it.
fn robust_out(r: RobustRegion, g_hi: f64) -> RobustOut {
    RobustOut {
        gamma_lo: 0.0,
        gamma_hi: g_hi,
        empty: r.empty,
        alpha_max: r.alpha_max,
        beta_at_alpha_max: r.beta_at_alpha_max,
        area: r.area,
        degenerate_gammas: r.degenerate_gammas,
        multiple_intervals: r.multiple_intervals,
        polygon: pairs(&r.polygon),
    }
}

/// Vertices as [alpha, beta] pairs, as every command writes polygons.
fn pairs(v: &[AlphaBeta]) -> Vec<[f64; 2]> {
    v.iter().map(|p| [p.alpha, p.beta]).collect()
}

/// The estimated cost of the sweep, the robust region and the passivity check.
fn estimate(a: &NyquistArgs, delta: f64, delay: usize, opts: RobustOptions) -> Cost {
    let sweep = gamma_sweep_cost(a.steps, a.beta_samples, delay);
    let robust = robust_region_cost(
        opts.gamma_samples,
        opts.beta_samples,
        delay,
        opts.refine_gamma,
        opts.refine_beta_rounds,
    );
    let passive = if delta > 0.0 {
        passive_check_cost(PASSIVE_SAMPLES, opts.gamma_samples, delay)
    } else {
        Cost::ZERO
    };
    sweep.then(robust).then(passive)
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

fn print_text(o: &NyquistOut) {
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
