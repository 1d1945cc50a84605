//! `hapstab sweep`: K_max (stable, exact; and passive) against one parameter of the loop —
//! delay, sampling period, filter cut-off or any plant parameter — as text, CSV, JSON and a
//! plot, computed in parallel.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::answer::{SweepAnswer, sweep_answer};
use hapstab::sweep::{KmaxAt, SweepParam, SweepPoint, SweepRange};
use serde::Serialize;

use crate::model::{LoopArgs, print_loop};
use crate::output::{csv_num, csv_opt, eng, print_json, sig};
use hapstab_plot::{Figure, Legend, Marker, Series, palette};

/// Arguments of `hapstab sweep`.
#[derive(Args, Debug)]
pub struct SweepArgs {
    #[command(flatten)]
    lp: LoopArgs,
    /// The swept parameter as NAME:START:END:POINTS, e.g. delay-time:0:0.005:50. NAME is one
    /// of delay-time, period (the delay time is kept), cutoff (with --velocity lowpass:FC,
    /// butterworth:N:FC, bessel:N:FC or critically-damped:N:FC), window (with --velocity average:N), force-lag, mass, damping, stiffness (the effective
    /// m, b, k of eq. 1), motor-mass, motor-damping, handle-mass, transmission-stiffness,
    /// transmission-damping, arm-mass, arm-damping, arm-stiffness (the arm holding the device,
    /// or a two-mass device's arm).
    #[arg(long, value_name = "NAME:START:END:N")]
    param: String,
    /// K_max at this virtual damping B in Ns/m [default: over every B].
    #[arg(long, allow_hyphen_values = true, conflicts_with = "damping_range")]
    wall_damping: Option<f64>,
    /// K_max with the virtual damping B in LO:HI (Ns/m; `inf` allowed), e.g. 0:inf for a
    /// device that cannot render negative damping (as `kmax --damping-range`).
    #[arg(long, value_name = "LO:HI", allow_hyphen_values = true, alias = "damping-band",
          value_parser = crate::kmax::parse_damping_range)]
    damping_range: Option<crate::kmax::DampingRange>,
    /// Write the points as CSV.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    /// Write the plot as FILE.svg and FILE.png.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct SweepOut {
    /// The sweep with its inputs, as the explorer's `/api/sweep` gives it.
    #[serde(flatten)]
    answer: SweepAnswer,
    #[serde(skip_serializing_if = "Option::is_none")]
    plot: Option<hapstab_plot::Saved>,
}

fn k_max_at(a: &SweepArgs) -> Result<KmaxAt> {
    if let Some(b) = a.wall_damping {
        if !b.is_finite() {
            bail!("--wall-damping B must be a finite number of Ns/m (got {b})");
        }
        return Ok(KmaxAt::Damping { damping: b });
    }
    Ok(match a.damping_range {
        Some(r) => KmaxAt::Band { lo: r.lo, hi: r.hi },
        None => KmaxAt::Overall,
    })
}

/// Refuses a sweep beyond the command-line budget: every point is a stable region (or one
/// interval at a given damping) and a passive K_max of the loop at that value, whose cost
/// grows as the square of its p(z)'s degree; blames --param.
fn check_budget(
    a: &SweepArgs,
    base: &hapstab::model::Loop,
    range: &SweepRange,
    at: KmaxAt,
) -> Result<()> {
    let cost = hapstab::limits::sweep_cost(base, range.param, &range.values(), at);
    crate::budget::check(
        cost,
        &format!("the sweep of {} points", range.n),
        &[crate::budget::Driver {
            flag: "--param",
            value: a.param.clone(),
            factor: 1.0,
        }],
    )
}

/// Runs `hapstab sweep`.
pub fn run(a: &SweepArgs) -> Result<()> {
    let range: SweepRange = a.param.parse().context("--param")?;
    let at = k_max_at(a)?;
    let rl = a.lp.resolve(false)?;
    if rl.normalized {
        bail!("sweep works in physical units; give the device, not --gamma/--delta");
    }
    check_budget(a, &rl.lp, &range, at)?;
    let bar = crate::progress::Bar::new(range.n, "points", !a.json);
    let answer = sweep_answer(&rl.lp, &range, at, &bar.stage(0))
        .with_context(|| format!("--param {}", a.param))?;
    bar.finish();
    let points = &answer.points;
    if let Some(path) = &a.csv {
        write_csv(path, range.param, points)?;
    }
    let plot = match &a.plot {
        Some(p) => Some(figure(range.param, at, points, &swept_line(&rl, range.param)).save(p)?),
        None => None,
    };
    let out = SweepOut { answer, plot };
    if a.json {
        return print_json(&out);
    }
    print_text(&rl.lp, &out);
    Ok(())
}

fn value_text(p: SweepParam, v: f64) -> String {
    match p {
        SweepParam::Window => format!("{v}"),
        _ => eng(v, p.unit(), 6),
    }
}

fn print_text(lp: &hapstab::Loop, out: &SweepOut) {
    let o = &out.answer;
    print_loop(lp);
    let at = match o.input.k_max_at {
        KmaxAt::Overall => "over every damping B".to_string(),
        KmaxAt::Damping { damping } => format!("at B = {}", eng(damping, "Ns/m", 6)),
        KmaxAt::Band { lo, hi } => format!("for {} ≤ B ≤ {} Ns/m", sig(lo, 6), sig(hi, 6)),
    };
    println!(
        "sweep       {} ({} points), K_max {at}",
        o.input.param.name(),
        o.points.len()
    );
    let with_arm = o.points.iter().any(|p| p.k_max_passive_with_arm.is_some());
    println!(
        "  {:>14}  {:>14}  {:>14}  {:>14}{}",
        o.input.param.name(),
        "K_max stable",
        "B at K_max",
        "K_max passive",
        if with_arm {
            format!("  {:>14}", "with arm (28)")
        } else {
            String::new()
        }
    );
    let k = |x: Option<f64>| x.map_or_else(|| "—".into(), |v| eng(v, "N/m", 6));
    for p in &o.points {
        let b = p
            .b_at_k_max
            .map_or_else(|| "—".into(), |v| eng(v, "Ns/m", 6));
        let arm = if with_arm {
            format!("  {:>14}", k(p.k_max_passive_with_arm))
        } else {
            String::new()
        };
        println!(
            "  {:>14}  {:>14}  {:>14}  {:>14}{arm}",
            value_text(o.input.param, p.value),
            k(p.k_max),
            b,
            k(p.k_max_passive)
        );
        if let Some(n) = &p.note {
            println!("  {:>14}  undecided: {n}", "");
        }
    }
    if with_arm {
        println!(
            "passive     for the device's own damping b_L (any passive operator); \"with arm (28)\": \
             the paper's eq. (28) with b = b_L + b_H, towards this operator only"
        );
    }
    let mut reasons: Vec<&str> = o
        .points
        .iter()
        .filter_map(|p| p.passive_note.as_deref())
        .collect();
    reasons.sort_unstable();
    reasons.dedup();
    for r in reasons {
        println!("passive     — : passivity does not apply: {r}");
    }
    if let Some(s) = &out.plot {
        println!("plot        {} and {}", s.svg.display(), s.png.display());
    }
}

fn write_csv(path: &std::path::Path, param: SweepParam, points: &[SweepPoint]) -> Result<()> {
    let mut w =
        csv::Writer::from_path(path).with_context(|| format!("cannot write {}", path.display()))?;
    w.write_record([
        param.name(),
        "k_max",
        "b_at_k_max",
        "k_max_passive",
        "k_max_passive_with_arm",
        "note",
    ])?;
    let cell = csv_opt;
    for p in points {
        w.write_record([
            csv_num(p.value),
            cell(p.k_max),
            cell(p.b_at_k_max),
            cell(p.k_max_passive),
            cell(p.k_max_passive_with_arm),
            p.note.clone().unwrap_or_default(),
        ])?;
    }
    w.flush()?;
    Ok(())
}

/// The loop in words without the part that the swept parameter changes.
fn swept_line(rl: &crate::model::ResolvedLoop, param: SweepParam) -> String {
    use crate::wall_plot::Part;
    let part = match param {
        SweepParam::DelayTime => Part::Delay,
        SweepParam::Period => Part::Period,
        SweepParam::Cutoff | SweepParam::Window => Part::Estimator,
        SweepParam::ForceLag => Part::Lag,
        _ => Part::Plant,
    };
    crate::wall_plot::loop_line_without(rl, &[part])
}

/// K_max (stable, solid with markers) and the passive K_max (dashed) against the parameter,
/// K on a log axis.
fn figure(param: SweepParam, at: KmaxAt, points: &[SweepPoint], subtitle: &str) -> Figure {
    // times in ms (delays and periods of a haptic loop are milliseconds)
    let (xs, unit) = match param.unit() {
        "s" => (1e3, "ms"),
        u => (1.0, u),
    };
    // K on a log axis: the passive K_max is often a small fraction of the stable one
    let series = |f: fn(&SweepPoint) -> Option<f64>| -> Vec<(f64, f64)> {
        points
            .iter()
            .map(|p| {
                let k = f(p).filter(|k| *k > 0.0).map_or(f64::NAN, f64::log10);
                (p.value * xs, k)
            })
            .collect()
    };
    let title = match at {
        KmaxAt::Overall => "Largest stable stiffness (over every damping)".to_string(),
        KmaxAt::Damping { damping } => format!("Largest stable stiffness at B = {damping} Ns/m"),
        KmaxAt::Band { lo, hi } => format!("Largest stable stiffness for {lo} ≤ B ≤ {hi} Ns/m"),
    };
    let mut f = Figure::new(title)
        .subtitle(subtitle)
        .x_label(format!("{} ({unit})", param.name()))
        .y_label("K_max (N/m, log scale)")
        .y_log10()
        .legend(Legend::Below);
    let stable = series(|p| p.k_max);
    f.add(
        Series::line(stable.clone())
            .color(palette::BLUE)
            .label("stable (exact)"),
    );
    f.add(
        Series::scatter(stable, Marker::Circle)
            .color(palette::BLUE)
            .size(4),
    );
    if points.iter().any(|p| p.k_max_passive.is_some()) {
        f.add(
            Series::dashed(series(|p| p.k_max_passive))
                .color(palette::GREEN)
                .label("passive, device's own b_L (Colgate–Schenkel)"),
        );
    }
    if points.iter().any(|p| p.k_max_passive_with_arm.is_some()) {
        f.add(
            Series::dashed(series(|p| p.k_max_passive_with_arm))
                .color(palette::ORANGE)
                .label("eq. (28) with the arm's b_H counted (this operator only)"),
        );
    }
    f
}
