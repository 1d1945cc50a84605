//! `hapstab kmax`: the largest stable virtual stiffness in N/m for any loop, beside the
//! linear condition (b + B)/(t_d + T/2) of eq. (22) for the paper's loop.

use anyhow::{Result, bail};
use clap::Args;
use hapstab::AffineFamily;
use serde::Serialize;

use crate::model::{LOOP_FLAGS, LoopArgs, LoopInput, ResolvedLoop, describe_loop};
use crate::output::{eng, print_json};
use crate::plot::{Marker, palette};
use crate::wall_plot::{self, Plane};
use hapstab::loop_analysis::{damping_units, k_max_at_damping, k_max_within, linear_k};

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
    /// Robust design (beyond the paper): K_max stable for every plant in a box, by default
    /// from the ungrabbed device to the device held by the arm (see --box-* flags).
    #[arg(long, conflicts_with_all = LOOP_FLAGS)]
    robust: bool,
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

/// The paper's normalized view of the result (Table I).
#[derive(Serialize)]
struct PaperView {
    alpha_max: Option<f64>,
    beta: Option<f64>,
    gamma: f64,
    delta: f64,
    d: usize,
}

/// The loop and the given damping, or the damping range searched.
#[derive(Serialize)]
struct KmaxInput {
    #[serde(flatten)]
    lp: LoopInput,
    /// B in Ns/m, when given.
    #[serde(skip_serializing_if = "Option::is_none")]
    wall_damping: Option<f64>,
    /// The damping range searched without a B, [lo, hi] in Ns/m (hi null: unbounded).
    #[serde(skip_serializing_if = "Option::is_none")]
    damping_range: Option<[Option<f64>; 2]>,
}

impl KmaxInput {
    fn new(
        rl: &ResolvedLoop,
        wall_damping: Option<f64>,
        damping_range: Option<[Option<f64>; 2]>,
    ) -> Self {
        KmaxInput {
            lp: rl.input(None),
            wall_damping,
            damping_range,
        }
    }
}

#[derive(Serialize)]
struct KmaxOut {
    input: KmaxInput,
    /// Largest stable K in N/m.
    k_max: Option<f64>,
    /// B at which K_max over the damping range is reached (when no B was given), Ns/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    b_at_k_max: Option<f64>,
    /// False where K_max over the band is a supremum: a corner of the region that only the
    /// damping `b_at_k_max` touches, approached as B → `b_at_k_max` (absent with a given B).
    #[serde(skip_serializing_if = "Option::is_none")]
    k_max_attained: Option<bool>,
    /// For a supremum, a damping beside `b_at_k_max` at which `k_stable_near_k_max` is
    /// stable, Ns/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    b_stable_near_k_max: Option<f64>,
    /// For a supremum, a stiffness within 1e-6 of K_max (1e-9 where the corner's wedge is
    /// wide enough) that the verdict confirms stable at `b_stable_near_k_max`, N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    k_stable_near_k_max: Option<f64>,
    /// K_max with no virtual damping (B = 0: the plant's own damping only), N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    k_max_at_zero_damping: Option<f64>,
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
    /// Files written by --plot.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    plot: Vec<std::path::PathBuf>,
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
        input: KmaxInput::new(rl, Some(b), None),
        k_max: best.map(|i| k(i.hi)),
        b_at_k_max: None,
        k_max_attained: None,
        b_stable_near_k_max: None,
        k_stable_near_k_max: None,
        k_max_at_zero_damping: None,
        wall_damping: Some(b),
        k_interval: best.map(|i| [k(i.lo), k(i.hi)]),
        k_linear: linear_k(&rl.lp, b),
        paper: paper_view(rl, best.map(|i| i.hi), Some(bu)),
        plot: Vec::new(),
    })
}

/// K_max over the damping band (Ns/m) and the B that reaches it
/// ([`k_max_within`]), beside K_max at B = 0.
fn within(rl: &ResolvedLoop, fam: &AffineFamily, band: DampingRange) -> Result<KmaxOut> {
    let units = |b: f64| -> Result<f64> {
        if b.is_finite() {
            Ok(damping_units(&rl.lp, fam, b)?)
        } else {
            Ok(b)
        }
    };
    let best = k_max_within(&rl.lp, fam, units(band.lo)?, units(band.hi)?)?;
    let phys = best.map(|p| fam.to_physical(p.alpha, p.beta));
    let at_zero = k_max_at_damping(&rl.lp, fam, 0.0)?;
    Ok(KmaxOut {
        input: KmaxInput::new(
            rl,
            None,
            Some([Some(band.lo), band.hi.is_finite().then_some(band.hi)]),
        ),
        k_max: phys.map(|p| p.0),
        b_at_k_max: phys.map(|p| p.1),
        k_max_attained: best.map(|p| p.attained),
        b_stable_near_k_max: best
            .filter(|p| !p.attained)
            .map(|p| fam.to_physical(0.0, p.beta_stable).1),
        k_stable_near_k_max: best
            .filter(|p| !p.attained)
            .map(|p| fam.to_physical(p.alpha_stable, 0.0).0),
        k_max_at_zero_damping: at_zero.map(|i| fam.to_physical(i.hi, 0.0).0),
        wall_damping: None,
        k_interval: None,
        k_linear: phys.and_then(|p| linear_k(&rl.lp, p.1)),
        paper: paper_view(rl, best.map(|p| p.alpha), best.map(|p| p.beta)),
        plot: Vec::new(),
    })
}

/// The stable region with K_max marked at its B, the damping band or the given B dashed,
/// and K_max at B = 0.
fn figure(
    rl: &ResolvedLoop,
    fam: &AffineFamily,
    out: &KmaxOut,
    band: DampingRange,
) -> Result<crate::plot::Figure> {
    let r = hapstab::loop_analysis::region(&rl.lp, fam)?;
    let plane = Plane::of(rl, fam);
    let mut fig = wall_plot::region_figure(&plane, &r, "Largest stable stiffness K_max")
        .subtitle(wall_plot::loop_line(rl));
    let lines: Vec<f64> = match out.wall_damping {
        Some(b) => vec![b],
        None => [band.lo, band.hi]
            .into_iter()
            .filter(|b| b.is_finite())
            .collect(),
    };
    for (i, b) in lines.iter().enumerate() {
        let label = match out.wall_damping {
            Some(_) => "the given B".to_string(),
            None => format!("damping range {}", band_text(band)),
        };
        wall_plot::damping_line(&mut fig, *b, (i == 0).then_some(label.as_str()));
    }
    // a tag on a damping line is lifted off it (the marker stays at its point)
    let on_line = |b: f64| {
        lines
            .iter()
            .any(|l| (l - b).abs() <= 1e-9 * l.abs().max(1.0))
    };
    let tag = |fig: &mut crate::plot::Figure, at: (f64, f64), style, legend: &str, text| {
        if on_line(at.1) {
            wall_plot::mark_above(fig, at, style, legend, text)
        } else {
            wall_plot::mark(fig, at, style.0, style.1, legend, text)
        }
    };
    if let Some(k) = out.k_max_at_zero_damping {
        tag(
            &mut fig,
            (k, 0.0),
            (Marker::Triangle, palette::GREEN),
            &format!("K_max at B = 0: {}", eng(k, "N/m", 6)),
            "B = 0",
        );
    }
    let b_best = out.b_at_k_max.or(out.wall_damping);
    if let (Some(k), Some(b)) = (out.k_max, b_best) {
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

fn band_text(band: DampingRange) -> String {
    let hi = if band.hi.is_finite() {
        eng(band.hi, "Ns/m", 6)
    } else {
        "∞".to_string()
    };
    format!("{} ≤ B ≤ {hi}", eng(band.lo, "Ns/m", 6))
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
    let n = fam.degree();
    let mut cost = hapstab::limits::interval_cost(n);
    if a.wall_damping.is_none() || a.plot.is_some() {
        cost = cost.then(hapstab::limits::region_cost_of_degree(
            n,
            hapstab::limits::core_degree(&fam),
        ));
    }
    crate::budget::check_loop(&a.lp, &rl.lp, cost, "K_max")?;
    let band = a.damping_range.unwrap_or(DampingRange {
        lo: 0.0,
        hi: f64::INFINITY,
    });
    let mut out = match a.wall_damping {
        Some(b) => at_damping(&rl, &fam, b)?,
        None => within(&rl, &fam, band)?,
    };
    if let Some(path) = &a.plot {
        let fig = figure(&rl, &fam, &out, band)?;
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
    let kt = |k: f64| eng(k, "N/m", 6);
    let bt = |b: f64| eng(b, "Ns/m", 6);
    let linear = |what: &str| {
        out.k_linear
            .map(|k| format!("; linear condition (22){what}: {}", kt(k)))
            .unwrap_or_default()
    };
    // the pure spring first: the number a device renders without virtual damping
    if over_band {
        match out.k_max_at_zero_damping {
            Some(k) => println!(
                "K_max = {} at B = 0 (no virtual damping, the plant's own damping only)",
                kt(k)
            ),
            None => println!("no stiffness is stable at B = 0"),
        }
    }
    match (out.k_max, out.wall_damping, out.b_at_k_max) {
        (None, None, _) => println!("no stiffness is stable for {}", band_text(band)),
        (None, Some(b), _) => println!("no stiffness is stable at B = {}", bt(b)),
        (Some(k), Some(b), _) => println!(
            "K_max = {} at B = {} (stable for {} < K < {}){}",
            kt(k),
            bt(b),
            out.k_interval.map_or("—".into(), |i| kt(i[0])),
            kt(k),
            linear("")
        ),
        (Some(k), None, Some(b)) if out.k_max_attained == Some(false) => println!(
            "K_max = {}, approached as B → {} (largest over {}: a supremum, a corner of the \
             region that no stiffness at exactly that B reaches; K = {} is stable at B = {}){}",
            kt(k),
            bt(b),
            band_text(band),
            out.k_stable_near_k_max
                .map_or("—".into(), |k| eng(k, "N/m", 10)),
            out.b_stable_near_k_max
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
    if over_band
        && band.lo == 0.0
        && band.hi == f64::INFINITY
        && let Some(b) = out.b_at_k_max.filter(|&b| b > 0.0)
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
