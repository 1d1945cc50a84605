//! `hapstab kmax`: the largest stable virtual stiffness in N/m for any loop, beside the
//! linear condition (b + B)/(t_d + T/2) of eq. (22) for the paper's loop.

use anyhow::{Result, bail};
use clap::Args;
use hapstab::AffineFamily;
use serde::Serialize;

use crate::model::{LOOP_FLAGS, LoopArgs, LoopInput, ResolvedLoop, describe_loop};
use crate::output::{eng, print_json};
use hapstab::loop_analysis::{damping_units, k_max_at_damping, linear_k, region};

/// Arguments of `hapstab kmax`.
#[derive(Args, Debug)]
pub struct KmaxArgs {
    #[command(flatten)]
    lp: LoopArgs,
    /// Virtual damping B in Ns/m; without it, the overall K_max and the B that reaches it.
    #[arg(long, allow_hyphen_values = true)]
    wall_damping: Option<f64>,
    /// Robust design (beyond the paper): K_max stable for every plant in a box, by default
    /// from the ungrabbed device to the device held by the arm (see --box-* flags).
    #[arg(long, conflicts_with_all = LOOP_FLAGS)]
    robust: bool,
    #[command(flatten)]
    robust_box: crate::robust::RobustArgs,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// The paper's normalized view of the result (Table I).
#[derive(Serialize)]
struct PaperView {
    alpha_max: Option<f64>,
    beta: Option<f64>,
    gamma: f64,
    delta: f64,
    d: usize,
}

/// The loop and the given damping.
#[derive(Serialize)]
struct KmaxInput {
    #[serde(flatten)]
    lp: LoopInput,
    /// B in Ns/m, when given.
    #[serde(skip_serializing_if = "Option::is_none")]
    wall_damping: Option<f64>,
}

impl KmaxInput {
    fn new(rl: &ResolvedLoop, wall_damping: Option<f64>) -> Self {
        KmaxInput {
            lp: LoopInput::new(rl, None),
            wall_damping,
        }
    }
}

#[derive(Serialize)]
struct KmaxOut {
    input: KmaxInput,
    /// Largest stable K in N/m.
    k_max: Option<f64>,
    /// B at which the overall K_max is reached (when no B was given), Ns/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    b_at_k_max: Option<f64>,
    /// The given B, Ns/m (echoed under `input`).
    #[serde(skip)]
    wall_damping: Option<f64>,
    /// Stable K interval at the given B, N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    k_interval: Option<[f64; 2]>,
    /// Linear condition (22): (b + B)/(t_d + T/2) at the same B, N/m (the paper's loop).
    #[serde(skip_serializing_if = "Option::is_none")]
    k_linear: Option<f64>,
    /// The paper's loop: the same result in normalized units (Table I).
    #[serde(rename = "normalized", skip_serializing_if = "Option::is_none")]
    paper: Option<PaperView>,
}

/// The stable interval with the largest upper end at damping B (Ns/m), in wall units.
fn at_damping(rl: &ResolvedLoop, fam: &AffineFamily, b: f64) -> Result<KmaxOut> {
    if !b.is_finite() {
        bail!("wall damping B must be a finite number (got {b})");
    }
    let bu = damping_units(&rl.lp, fam, b)?;
    let best = k_max_at_damping(&rl.lp, fam, bu)?;
    let k = |a: f64| fam.to_physical(a, 0.0).0;
    Ok(KmaxOut {
        input: KmaxInput::new(rl, Some(b)),
        k_max: best.map(|i| k(i.hi)),
        b_at_k_max: None,
        wall_damping: Some(b),
        k_interval: best.map(|i| [k(i.lo), k(i.hi)]),
        k_linear: linear_k(&rl.lp, b),
        paper: paper_view(rl, best.map(|i| i.hi), Some(bu)),
    })
}

/// The overall K_max of the stable region and the B that reaches it.
fn overall(rl: &ResolvedLoop, fam: &AffineFamily) -> Result<KmaxOut> {
    let r = region(&rl.lp, fam)?;
    let found = !r.polygons.is_empty();
    let (k, b) = fam.to_physical(r.alpha_max, r.beta_at_alpha_max);
    Ok(KmaxOut {
        input: KmaxInput::new(rl, None),
        k_max: found.then_some(k),
        b_at_k_max: found.then_some(b),
        wall_damping: None,
        k_interval: None,
        k_linear: linear_k(&rl.lp, if found { b } else { 0.0 }),
        paper: paper_view(
            rl,
            found.then_some(r.alpha_max),
            found.then_some(r.beta_at_alpha_max),
        ),
    })
}

fn paper_view(rl: &ResolvedLoop, alpha_max: Option<f64>, beta: Option<f64>) -> Option<PaperView> {
    rl.lp.paper_view().map(|pp| PaperView {
        alpha_max,
        beta,
        gamma: pp.gamma,
        delta: pp.delta,
        d: rl.lp.delay.samples,
    })
}

/// Runs `hapstab kmax`.
pub fn run(a: &KmaxArgs) -> Result<()> {
    if a.robust {
        return crate::robust::run_robust(&a.lp.plant, &a.robust_box, a.json);
    }
    let rl = a.lp.resolve(false)?;
    if rl.normalized {
        bail!("kmax works in physical units; for normalized parameters use `hapstab boundary`");
    }
    let fam = AffineFamily::of_loop(&rl.lp)?;
    let out = match a.wall_damping {
        Some(b) => at_damping(&rl, &fam, b)?,
        None => overall(&rl, &fam)?,
    };
    if a.json {
        return print_json(&out);
    }
    for line in describe_loop(&rl.lp) {
        println!("{line}");
    }
    let kt = |k: f64| eng(k, "N/m", 6);
    let bt = |b: f64| eng(b, "Ns/m", 6);
    let linear = |what: &str| {
        out.k_linear
            .map(|k| format!("; linear condition (22){what}: {}", kt(k)))
            .unwrap_or_default()
    };
    match (out.k_max, out.wall_damping, out.b_at_k_max) {
        (None, _, _) => println!("no stable virtual stiffness exists"),
        (Some(k), Some(b), _) => println!(
            "K_max = {} at B = {} (stable for {} < K < {}){}",
            kt(k),
            bt(b),
            out.k_interval.map_or("—".into(), |i| kt(i[0])),
            kt(k),
            linear("")
        ),
        (Some(k), None, Some(b)) => println!(
            "K_max = {}, reached at B = {}{}",
            kt(k),
            bt(b),
            linear(" at that B")
        ),
        _ => {}
    }
    Ok(())
}
