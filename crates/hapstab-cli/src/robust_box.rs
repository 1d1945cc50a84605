//! `hapstab kmax --robust --box NAME:LO:HI …`: robust K_max of any loop over a box of its
//! parameters ([`hapstab::robust::robust_kmax`]), as text or JSON.

use anyhow::{Result, bail};
use hapstab::AffineFamily;
use hapstab::robust::{BoxSide, RobustKmax, RobustOptions, robust_kmax};
use hapstab::sweep::SweepParam;
use serde::Serialize;

use crate::model::{LoopArgs, LoopInput, describe_loop};
use crate::output::{eng, print_json};

/// Parses one side of the box, `NAME:LO:HI` with NAME one of `sweep --param`'s names.
pub fn parse_side(s: &str) -> Result<BoxSide, String> {
    let parts: Vec<&str> = s.split(':').collect();
    let [name, lo, hi] = parts[..] else {
        return Err(format!(
            "expected NAME:LO:HI, e.g. arm-stiffness:0:2000 (got '{s}')"
        ));
    };
    let param: SweepParam = name.parse().map_err(|e| format!("{e} (in '{s}')"))?;
    let num = |t: &str| -> Result<f64, String> {
        t.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| format!("'{t}' is not a finite number (in '{s}')"))
    };
    let (lo, hi) = (num(lo)?, num(hi)?);
    if lo > hi {
        return Err(format!("LO must not exceed HI (got '{s}')"));
    }
    Ok(BoxSide { param, lo, hi })
}

/// The JSON answer: the loop and the box echoed, then the library's report.
#[derive(Serialize)]
struct RobustOut<'a> {
    input: RobustInput<'a>,
    #[serde(flatten)]
    report: &'a RobustKmax,
}

#[derive(Serialize)]
struct RobustInput<'a> {
    #[serde(flatten)]
    lp: LoopInput,
    #[serde(rename = "box")]
    sides: &'a [BoxSide],
    samples: usize,
    verify: usize,
    seed: u64,
}

/// Runs the robust K_max of the resolved loop over the box at damping B (default 0).
pub fn run(
    args: &LoopArgs,
    sides: &[BoxSide],
    wall_damping: Option<f64>,
    opts: RobustOptions,
    json: bool,
) -> Result<()> {
    let rl = args.resolve(false)?;
    if rl.normalized {
        bail!("kmax --robust --box works in physical units");
    }
    let b = wall_damping.unwrap_or(0.0);
    let fam = AffineFamily::of_loop(&rl.lp)?;
    let n = fam.degree();
    let cost = hapstab::limits::robust_box_cost(n, sides.len(), &opts);
    crate::budget::check_loop(args, &rl.lp, cost, "the robust K_max")?;
    let report = robust_kmax(&rl.lp, sides, b, &opts)?;
    if json {
        return print_json(&RobustOut {
            input: RobustInput {
                lp: rl.input(None),
                sides,
                samples: opts.samples,
                verify: opts.verify,
                seed: opts.seed,
            },
            report: &report,
        });
    }
    for line in describe_loop(&rl.lp) {
        println!("{line}");
    }
    print_text(sides, &report);
    Ok(())
}

fn value(v: f64, unit: &str) -> String {
    match unit {
        "samples" => format!("{v} samples"),
        u => eng(v, u, 6),
    }
}

fn print_text(sides: &[BoxSide], r: &RobustKmax) {
    let box_text: Vec<String> = sides
        .iter()
        .map(|s| {
            let u = s.param.unit();
            format!(
                "{} ∈ [{}, {}]",
                s.param.name(),
                value(s.lo, u),
                value(s.hi, u)
            )
        })
        .collect();
    println!("box       {}", box_text.join(", "));
    let worst: Vec<String> = r
        .worst_plant
        .iter()
        .map(|p| format!("{} = {}", p.param, value(p.value, p.unit)))
        .collect();
    let bt = eng(r.wall_damping, "Ns/m", 6);
    match (r.k_max, r.k_min) {
        (Some(k), Some(lo)) => println!(
            "robust    K_max = {} at B = {bt}: stable for {} < K < {} for every plant checked",
            eng(k, "N/m", 6),
            eng(lo, "N/m", 6),
            eng(k, "N/m", 6)
        ),
        _ => println!("robust    no stiffness is stable at B = {bt} for every plant of the box"),
    }
    println!("          limited by {}", worst.join(", "));
    if let Some(k) = r.k_max_nominal {
        println!(
            "nominal   K_max = {} for the loop as given",
            eng(k, "N/m", 6)
        );
    }
    println!(
        "checked   {} plants solved exactly (corners, centre, samples, compass refinement), \
         {} random plants verified by the verdict at K_max·(1 − 1e-6){}",
        r.plants_evaluated,
        r.plants_verified,
        if r.verification_found > 0 {
            format!(" ({} found below it and folded in)", r.verification_found)
        } else {
            String::new()
        }
    );
}
