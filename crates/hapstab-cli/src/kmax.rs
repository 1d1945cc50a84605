//! `hapstab kmax`: the largest stable virtual stiffness in N/m for any loop, beside the
//! linear condition (b + B)/(t_d + T/2) of eq. (22) for the paper's loop.

use anyhow::{Result, bail};
use clap::Args;
use hapstab::System;
use serde::Serialize;

use crate::model::{LoopArgs, ResolvedLoop, describe_loop};
use crate::output::{eng, print_json};
use crate::wall_plot::{self, Plane};
use hapstab::answer::{KmaxAnswer, kmax_answer};
use hapstab::kmax::{KmaxQuery, KmaxReport, NoiseModel, RenderableBand};
use hapstab_plot::{Marker, palette};

/// A band of virtual damping lo ≤ B ≤ hi in Ns/m (`LO:HI`; `inf` for no upper bound).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DampingRange {
    /// Lower end in Ns/m.
    pub lo: f64,
    /// Upper end in Ns/m (may be +∞).
    pub hi: f64,
}

/// Parses `LO:HI` in Ns/m: LO finite, HI finite or `inf`, LO ≤ HI.
pub fn parse_damping_range(s: &str) -> Result<DampingRange, String> {
    let (lo, hi) = s
        .split_once(':')
        .ok_or_else(|| format!("expected LO:HI in Ns/m, e.g. 0:50 or 0:inf (got '{s}')"))?;
    let num = |t: &str| -> Result<f64, String> {
        t.trim()
            .parse::<f64>()
            .map_err(|_| format!("'{t}' is not a number (in '{s}')"))
    };
    let (lo, hi) = (num(lo)?, num(hi)?);
    if !lo.is_finite() || hi.is_nan() || hi == f64::NEG_INFINITY {
        return Err(format!(
            "LO must be finite and HI finite or inf (got '{s}')"
        ));
    }
    if lo > hi {
        return Err(format!("LO must not exceed HI (got '{s}')"));
    }
    Ok(DampingRange { lo, hi })
}

/// Arguments of `hapstab kmax`.
#[derive(Args, Debug)]
pub struct KmaxArgs {
    #[command(flatten)]
    lp: LoopArgs,
    /// Virtual damping B in Ns/m; without it, the largest K_max over --damping-range and the
    /// B that reaches it.
    #[arg(long, allow_hyphen_values = true)]
    wall_damping: Option<f64>,
    /// Virtual damping the device can render, LO:HI in Ns/m (HI may be `inf`): K_max is
    /// searched with LO ≤ B ≤ HI [default: 0:inf]
    #[arg(long, value_name = "LO:HI", value_parser = parse_damping_range,
          allow_hyphen_values = true, conflicts_with_all = ["wall_damping", "robust"])]
    damping_range: Option<DampingRange>,
    /// Position resolution Δ at the handle in m (encoder step): with --force-noise it sets the
    /// renderable damping band 0 ≤ B ≤ F_n·√12/(Δ·‖V‖₂) reported without --wall-damping and
    /// --damping-range (‖V‖₂: the velocity estimator's noise gain)
    #[arg(long, value_name = "M", allow_hyphen_values = true, default_value_t = hapstab::kmax::DEFAULT_POSITION_RESOLUTION,
          conflicts_with_all = ["wall_damping", "damping_range", "robust"])]
    position_resolution: f64,
    /// Largest force noise the virtual damper may add, RMS in N (sets the renderable band
    /// with --position-resolution)
    #[arg(long, value_name = "N", allow_hyphen_values = true, default_value_t = hapstab::kmax::DEFAULT_FORCE_NOISE,
          conflicts_with_all = ["wall_damping", "damping_range", "robust"])]
    force_noise: f64,
    /// Robust design (beyond the paper): K_max stable for every plant in a box. With --box:
    /// any loop, at --wall-damping (default 0), over the box of its parameters; without:
    /// the paper's loop from the ungrabbed device to the device held by the arm (see the
    /// --box-* flags), over every damping.
    #[arg(long)]
    robust: bool,
    /// A side of the robust box, NAME:LO:HI with NAME one of `sweep --param`'s names
    /// (arm-stiffness, arm-mass, arm-damping, mass, damping, stiffness, motor-mass,
    /// transmission-stiffness, cutoff, delay-time, period, force-lag, …), repeatable.
    #[arg(long = "box", value_name = "NAME:LO:HI", value_parser = hapstab_serve::robust_box::parse_side,
          requires = "robust", allow_hyphen_values = true)]
    boxes: Vec<hapstab::robust::BoxSide>,
    /// With --box: uniform samples of the box before refinement.
    #[arg(long, default_value_t = hapstab::robust::RobustOptions::default().samples,
          requires = "boxes")]
    samples: usize,
    /// With --box: random plants of the box verified stable at K_max·(1 − 1e-6).
    #[arg(long, default_value_t = hapstab::robust::RobustOptions::default().verify,
          requires = "boxes")]
    verify: usize,
    /// With --box: seed of the samples and of the verification plants.
    #[arg(long, default_value_t = hapstab::robust::RobustOptions::default().seed,
          requires = "boxes")]
    seed: u64,
    #[command(flatten)]
    robust_box: crate::robust::RobustArgs,
    /// Draw the stable region to FILE with K_max and its B marked: SVG or PNG by its
    /// extension (both FILE.svg and FILE.png for any other name), K in N/m, B in Ns/m.
    #[arg(long, value_name = "FILE", conflicts_with = "robust")]
    plot: Option<std::path::PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct KmaxOut {
    /// The answer with its inputs, as the explorer's `/api/kmax` gives it.
    #[serde(flatten)]
    answer: KmaxAnswer,
    /// The given B, Ns/m (echoed under `input`).
    #[serde(skip)]
    wall_damping: Option<f64>,
    /// Files written by --plot.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    plot: Vec<std::path::PathBuf>,
}

/// The library's answer to the query, with the loop and the query echoed.
fn answer(sys: &System, query: KmaxQuery) -> Result<KmaxOut> {
    let answer = kmax_answer(sys, query)?;
    Ok(KmaxOut {
        wall_damping: answer.input.wall_damping,
        answer,
        plot: Vec::new(),
    })
}

/// The stable region with K_max marked at its B, the damping band or the given B dashed,
/// and K_max at B = 0.
fn figure(
    rl: &ResolvedLoop,
    sys: &System,
    out: &KmaxOut,
    band: DampingRange,
) -> Result<hapstab_plot::Figure> {
    let r = sys.region()?;
    let plane = wall_plot::plane(rl, sys.family());
    let mut fig = wall_plot::region_figure(&plane, &r, "Largest stable stiffness K_max")
        .subtitle(wall_plot::loop_line(rl));
    let mut lines: Vec<f64> = match out.wall_damping {
        Some(b) => vec![b],
        None => [band.lo, band.hi]
            .into_iter()
            .filter(|b| b.is_finite())
            .collect(),
    };
    if let Some(rb) = &out.answer.report.renderable {
        lines.push(rb.b_max);
    }
    let band_lines = lines.len() - usize::from(out.answer.report.renderable.is_some());
    for (i, b) in lines[..band_lines].iter().enumerate() {
        let label = match out.wall_damping {
            Some(_) => "the given B".to_string(),
            None => format!("damping range {}", band_text(band)),
        };
        wall_plot::damping_line(&mut fig, *b, (i == 0).then_some(label.as_str()));
    }
    // the renderable band's top after the band's lines (each spans the ranges drawn so far)
    if let Some(rb) = &out.answer.report.renderable {
        mark_renderable(&mut fig, rb, &plane);
    }
    // a tag on a damping line is lifted off it (the marker stays at its point)
    let on_line = |b: f64| {
        lines
            .iter()
            .any(|l| (l - b).abs() <= 1e-9 * l.abs().max(1.0))
    };
    let tag = |fig: &mut hapstab_plot::Figure, at: (f64, f64), style, legend: &str, text| {
        if on_line(at.1) {
            wall_plot::mark_above(fig, at, style, legend, text)
        } else {
            wall_plot::mark(fig, at, style.0, style.1, legend, text)
        }
    };
    if let Some(k) = out.answer.report.k_max_at_zero_damping {
        tag(
            &mut fig,
            (k, 0.0),
            (Marker::Triangle, palette::GREEN),
            &format!("K_max at B = 0: {}", eng(k, "N/m", 6)),
            "B = 0",
        );
    }
    let b_best = out.answer.report.b_at_k_max.or(out.wall_damping);
    if let (Some(k), Some(b)) = (out.answer.report.k_max, b_best) {
        tag(
            &mut fig,
            (k, b),
            (Marker::Circle, palette::VERMILLION),
            &format!("K_max: {}", plane.describe((k, b))),
            "K_max",
        );
    }
    Ok(fig)
}

/// The renderable band's top B_r dashed, and K_max over the band marked above it.
fn mark_renderable(fig: &mut hapstab_plot::Figure, rb: &RenderableBand, plane: &Plane) {
    let label = format!("renderable band 0 ≤ B ≤ {}", eng(rb.b_max, "Ns/m", 6));
    wall_plot::damping_line(fig, rb.b_max, Some(label.as_str()));
    if let (Some(k), Some(b)) = (rb.k_max, rb.b_at_k_max) {
        wall_plot::mark_above(
            fig,
            (k, b),
            (Marker::Square, palette::PURPLE),
            &format!("K_max over the renderable band: {}", plane.describe((k, b))),
            "",
        );
    }
}

fn band_text(band: DampingRange) -> String {
    let hi = if band.hi.is_finite() {
        eng(band.hi, "Ns/m", 6)
    } else {
        "∞".to_string()
    };
    format!("{} ≤ B ≤ {hi}", eng(band.lo, "Ns/m", 6))
}

/// The query the flags ask: at --wall-damping, over --damping-range, or the design query
/// (B = 0, the renderable band of the noise flags, B ≥ 0).
fn query(a: &KmaxArgs) -> Result<KmaxQuery> {
    Ok(match (a.wall_damping, a.damping_range) {
        (Some(b), _) => KmaxQuery::AtDamping(b),
        (None, Some(r)) => KmaxQuery::Band { lo: r.lo, hi: r.hi },
        (None, None) => {
            for (flag, v) in [
                ("--position-resolution", a.position_resolution),
                ("--force-noise", a.force_noise),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    bail!("{flag} must be a positive finite number (got {v})");
                }
            }
            KmaxQuery::Design(NoiseModel::new(a.position_resolution, a.force_noise)?)
        }
    })
}

/// The first flag beyond the paper's loop that is given, as typed (`--velocity`, …).
fn first_loop_flag(lp: &LoopArgs) -> Option<&'static str> {
    [
        (lp.plant_num.is_some(), "--plant-num"),
        (lp.plant_den.is_some(), "--plant-den"),
        (lp.motor_mass.is_some(), "--motor-mass"),
        (lp.motor_damping.is_some(), "--motor-damping"),
        (lp.handle_mass.is_some(), "--handle-mass"),
        (
            lp.transmission_stiffness.is_some(),
            "--transmission-stiffness",
        ),
        (lp.transmission_damping.is_some(), "--transmission-damping"),
        (lp.force_lag.is_some(), "--force-lag"),
        (lp.velocity.is_some(), "--velocity"),
        (lp.plant.loop_file.is_some(), "--loop"),
    ]
    .into_iter()
    .find_map(|(given, flag)| given.then_some(flag))
}

/// Runs `hapstab kmax`.
pub fn run(a: &KmaxArgs) -> Result<()> {
    if a.robust && !a.boxes.is_empty() {
        let opts = hapstab::robust::RobustOptions {
            samples: a.samples,
            verify: a.verify,
            seed: a.seed,
        };
        return crate::robust_box::run(&a.lp, &a.boxes, a.wall_damping, opts, a.json);
    }
    if a.robust {
        if let Some(flag) = first_loop_flag(&a.lp) {
            bail!(
                "--robust without --box cannot be used with {flag} (it takes the paper's loop): \
                 for this loop give the box as --box NAME:LO:HI"
            );
        }
        return crate::robust::run_robust(&a.lp.plant, &a.robust_box, a.json);
    }
    let rl = a.lp.resolve(false)?;
    if rl.normalized {
        bail!("kmax works in physical units; for normalized parameters use `hapstab boundary`");
    }
    let query = query(a)?;
    let sys = rl.system()?;
    let fam = sys.family();
    let n = fam.degree();
    let mut cost = hapstab::limits::interval_cost(n);
    if a.wall_damping.is_none() || a.plot.is_some() {
        cost = cost.then(hapstab::limits::region_cost_of_degree(
            n,
            hapstab::limits::core_degree(fam),
        ));
    }
    crate::budget::check_loop(&a.lp, &rl.lp, cost, "K_max")?;
    let band = a.damping_range.unwrap_or(DampingRange {
        lo: 0.0,
        hi: f64::INFINITY,
    });
    let mut out = answer(&sys, query)?;
    if let Some(path) = &a.plot {
        let fig = figure(&rl, &sys, &out, band)?;
        out.plot = wall_plot::save(fig, path)?;
    }
    if a.json {
        return print_json(&out);
    }
    print_text(&rl, &out, band, a.wall_damping.is_none());
    Ok(())
}

/// The human-readable answer of `kmax`: the loop, K_max with where it is reached (or why no
/// stiffness is stable), the plot's files, and over a damping band K_max at B = 0 as well.
fn print_text(rl: &ResolvedLoop, out: &KmaxOut, band: DampingRange, over_band: bool) {
    for line in describe_loop(&rl.lp) {
        println!("{line}");
    }
    let r = &out.answer.report;
    // the pure spring first: the number a device renders without virtual damping
    if over_band {
        match r.k_max_at_zero_damping {
            Some(k) => println!(
                "K_max = {} at B = 0 (no virtual damping, the plant's own damping only)",
                kt(k)
            ),
            None => println!("no stiffness is stable at B = 0"),
        }
    }
    if let Some(rb) = &r.renderable {
        print_renderable(rl, rb);
    }
    print_main(r, out.wall_damping, band);
    if over_band
        && band.lo == 0.0
        && band.hi == f64::INFINITY
        && let Some(b) = r.b_at_k_max.filter(|&b| b > 0.0)
        && r.renderable.as_ref().is_none_or(|rb| b > rb.b_max)
    {
        println!(
            "            (that needs the device to render B = {}; --damping-range LO:HI \
             gives K_max over the dampings yours renders)",
            bt(b)
        );
    }
    if !out.plot.is_empty() {
        println!("plot written to {}", wall_plot::files_text(&out.plot));
    }
}

fn kt(k: f64) -> String {
    eng(k, "N/m", 6)
}

fn bt(b: f64) -> String {
    eng(b, "Ns/m", 6)
}

/// K_max over the renderable band and how the band is set.
fn print_renderable(rl: &ResolvedLoop, rb: &RenderableBand) {
    let band = format!("the renderable band 0 ≤ B ≤ {}", bt(rb.b_max));
    match (rb.k_max, rb.b_at_k_max) {
        (Some(k), Some(b)) => println!(
            "K_max = {}, {} B = {} (largest over {band})",
            kt(k),
            if rb.k_max_attained == Some(false) {
                "approached as"
            } else {
                "reached at"
            },
            bt(b)
        ),
        _ => println!("no stiffness is stable over {band}"),
    }
    println!(
        "            (the damper's force noise stays ≤ {} RMS there: {} position steps through \
         the {} estimator, noise gain {} s⁻¹; --position-resolution, --force-noise)",
        eng(rb.noise.force_noise, "N", 6),
        eng(rb.noise.position_resolution, "m", 6),
        rl.lp.velocity,
        crate::output::sig(rb.velocity_noise_gain, 6),
    );
}

/// K_max at the given B, or over the band with where it is reached.
fn print_main(r: &KmaxReport, wall_damping: Option<f64>, band: DampingRange) {
    let linear = |what: &str| {
        r.k_linear
            .map(|k| format!("; linear condition (22){what}: {}", kt(k)))
            .unwrap_or_default()
    };
    match (r.k_max, wall_damping, r.b_at_k_max) {
        (None, None, _) => println!("no stiffness is stable for {}", band_text(band)),
        (None, Some(b), _) => println!("no stiffness is stable at B = {}", bt(b)),
        (Some(k), Some(b), _) => println!(
            "K_max = {} at B = {} (stable for {} < K < {}){}",
            kt(k),
            bt(b),
            r.k_interval.map_or("—".into(), |i| kt(i[0])),
            kt(k),
            linear("")
        ),
        (Some(k), None, Some(b)) if r.k_max_attained == Some(false) => println!(
            "K_max = {}, approached as B → {} (largest over {}: a supremum, a corner of the \
             region that no stiffness at exactly that B reaches; K = {} is stable at B = {}){}",
            kt(k),
            bt(b),
            band_text(band),
            r.k_stable_near_k_max
                .map_or("—".into(), |k| eng(k, "N/m", 10)),
            r.b_stable_near_k_max
                .map_or("—".into(), |b| eng(b, "Ns/m", 10)),
            linear(" at that B")
        ),
        (Some(k), None, Some(b)) => println!(
            "K_max = {}, reached at B = {} (largest over {}){}",
            kt(k),
            bt(b),
            band_text(band),
            linear(" at that B")
        ),
        _ => {}
    }
}
