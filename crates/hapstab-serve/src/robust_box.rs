//! The robust K_max of any loop over a box of its parameters
//! ([`hapstab::robust::robust_kmax`]) as both front ends give it: the explorer's
//! `robust_kmax` and `hapstab kmax --robust --box NAME:LO:HI … [--json]` share the answer's
//! keys, its text and the parsing of a box side.

use hapstab::Loop;
use hapstab::limits::Cost;
use hapstab::loop_spec::LoopInput;
use hapstab::robust::{BoxSide, RobustKmax, RobustOptions, robust_kmax};
use hapstab::sweep::SweepParam;
use hapstab_plot::text::eng;
use serde::Serialize;

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

/// The answer of `kmax --robust --box … --json`, and the explorer's `robust_kmax` (the same
/// keys): the loop and the box echoed under `input`, then the library's report.
#[derive(Debug, Clone, Serialize)]
pub struct RobustBoxAnswer {
    /// The loop, the box and the search's settings.
    pub input: RobustBoxInput,
    /// The library's report.
    #[serde(flatten)]
    pub report: RobustKmax,
}

/// The inputs of a robust K_max over a box.
#[derive(Debug, Clone, Serialize)]
pub struct RobustBoxInput {
    /// The loop (SI units) and its delay time.
    #[serde(flatten)]
    pub lp: LoopInput,
    /// The box's sides.
    #[serde(rename = "box")]
    pub sides: Vec<BoxSide>,
    /// Uniform samples of the box.
    pub samples: usize,
    /// Random plants verified.
    pub verify: usize,
    /// Seed of the samples and of the verification plants.
    pub seed: u64,
}

/// Estimated cost of the robust K_max of `lp` over the box: the library's estimate at the
/// largest degree of p(z) over the box.
pub fn cost(lp: &Loop, sides: &[BoxSide], opts: &RobustOptions) -> hapstab::Result<Cost> {
    let n = hapstab::robust::box_degree(lp, sides)?;
    Ok(hapstab::limits::robust_box_cost(n, sides.len(), opts))
}

/// The robust K_max of a physical loop over the box at damping B (Ns/m), with its inputs.
pub fn answer(
    lp: &Loop,
    sides: &[BoxSide],
    b: f64,
    opts: RobustOptions,
) -> hapstab::Result<RobustBoxAnswer> {
    let report = robust_kmax(lp, sides, b, &opts)?;
    Ok(RobustBoxAnswer {
        input: RobustBoxInput {
            lp: LoopInput::new(lp, false, None),
            sides: sides.to_vec(),
            samples: opts.samples,
            verify: opts.verify,
            seed: opts.seed,
        },
        report,
    })
}

/// A value in its unit: engineering notation, a window in samples as a plain count.
pub fn value(v: f64, unit: &str) -> String {
    match unit {
        "samples" => format!("{v} samples"),
        u => eng(v, u, 6),
    }
}

/// The text of a robust K_max over a box, a line per item: the box, the robust K_max and
/// its interval, the worst plant, the nominal K_max and what was checked (the guarantee).
/// The command line prints it; the explorer shows it beside its overlay.
pub fn text_lines(sides: &[BoxSide], r: &RobustKmax) -> Vec<String> {
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
    let mut out = vec![format!("box       {}", box_text.join(", "))];
    let worst: Vec<String> = r
        .worst_plant
        .iter()
        .map(|p| format!("{} = {}", p.param, value(p.value, p.unit)))
        .collect();
    let bt = eng(r.wall_damping, "Ns/m", 6);
    out.push(match (r.k_max, r.k_min) {
        (Some(k), Some(lo)) => format!(
            "robust    K_max = {} at B = {bt}: stable for {} < K < {} for every plant checked",
            eng(k, "N/m", 6),
            eng(lo, "N/m", 6),
            eng(k, "N/m", 6)
        ),
        _ => format!("robust    no stiffness is stable at B = {bt} for every plant of the box"),
    });
    out.push(format!("          limited by {}", worst.join(", ")));
    if let Some(k) = r.k_max_nominal {
        out.push(format!(
            "nominal   K_max = {} for the loop as given",
            eng(k, "N/m", 6)
        ));
    }
    out.push(format!(
        "checked   {} plants solved exactly (corners, centre, samples, compass refinement), \
         {} random plants verified by the verdict at K_max·(1 − 1e-6){}",
        r.plants_evaluated,
        r.plants_verified,
        if r.verification_found > 0 {
            format!(" ({} found below it and folded in)", r.verification_found)
        } else {
            String::new()
        }
    ));
    out
}
