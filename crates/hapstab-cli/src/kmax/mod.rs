//! `hapstab kmax`: the largest stable virtual stiffness in N/m for any loop, beside the
//! linear condition (b + B)/(t_d + T/2) of eq. (22) for the paper's loop.

use anyhow::{Result, bail};
use clap::Args;
use hapstab::System;
use serde::Serialize;

mod plot;
mod text;

use crate::model::LoopArgs;
use crate::output::{eng, print_json};
use crate::wall_plot;
use hapstab::answer::{KmaxAnswer, kmax_answer};
use hapstab::kmax::{KmaxQuery, NoiseModel};

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
        let fig = plot::figure(&rl, &sys, &out, band)?;
        out.plot = wall_plot::save(fig, path)?;
    }
    if a.json {
        return print_json(&out);
    }
    text::print_text(&rl, &out, band, a.wall_damping.is_none());
    Ok(())
}
