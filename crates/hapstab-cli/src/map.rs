//! `hapstab map`: the paper's grid method (Section V) over any two of α, β, γ, δ, in parallel.

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use hapstab::Normalized;
use hapstab::map::{Axis, AxisRange, MapKind, MapSpec, compute_map};
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::io::IsTerminal;

use crate::output::print_json;

/// Arguments of `hapstab map`.
#[derive(Args, Debug)]
pub struct MapArgs {
    /// Horizontal axis as NAME:LO:HI:N, NAME one of alpha, beta, gamma, delta.
    #[arg(long, allow_hyphen_values = true)]
    x: String,
    /// Vertical axis as NAME:LO:HI:N.
    #[arg(long, allow_hyphen_values = true)]
    y: String,
    /// Fixed α (when not gridded).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    alpha: f64,
    /// Fixed β (when not gridded).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    beta: f64,
    /// Fixed γ (when not gridded).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    gamma: f64,
    /// Fixed δ (when not gridded).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    delta: f64,
    /// Delay d in samples.
    #[arg(long, default_value_t = 0)]
    delay: usize,
    /// Also compute the spectral radius at every point (slower).
    #[arg(long)]
    radius: bool,
    /// Output CSV file (columns x, y, stable[, radius]).
    #[arg(long)]
    out: Option<std::path::PathBuf>,
    /// Print a JSON summary instead of text.
    #[arg(long)]
    json: bool,
}

fn parse_axis(s: &str, flag: &str) -> Result<AxisRange> {
    let parts: Vec<&str> = s.split(':').collect();
    if parts.len() != 4 {
        bail!("--{flag} must be NAME:LO:HI:N (got '{s}')");
    }
    let axis: Axis = parts[0].parse().map_err(|_| {
        anyhow!(
            "--{flag}: unknown parameter '{}' (alpha, beta, gamma, delta)",
            parts[0]
        )
    })?;
    let lo: f64 = parts[1]
        .parse()
        .map_err(|_| anyhow!("--{flag}: bad lower end '{}'", parts[1]))?;
    let hi: f64 = parts[2]
        .parse()
        .map_err(|_| anyhow!("--{flag}: bad upper end '{}'", parts[2]))?;
    let n: usize = parts[3]
        .parse()
        .map_err(|_| anyhow!("--{flag}: bad point count '{}'", parts[3]))?;
    AxisRange::new(axis, lo, hi, n).map_err(|e| anyhow!("--{flag}: {e}"))
}

#[derive(Serialize)]
struct MapSummary {
    points: usize,
    stable_points: usize,
    seconds: f64,
    out: Option<String>,
}

/// Runs `hapstab map`.
pub fn run(a: &MapArgs) -> Result<()> {
    let x = parse_axis(&a.x, "x")?;
    let y = parse_axis(&a.y, "y")?;
    let base = Normalized::new(a.alpha, a.beta, a.gamma, a.delta, a.delay)?;
    let spec = MapSpec::new(x, y, base)?;
    let kind = if a.radius {
        MapKind::SpectralRadius
    } else {
        MapKind::Stability
    };
    let show = !a.json && std::io::stderr().is_terminal() && x.n * y.n >= 1_000_000;
    let bar = if show {
        ProgressBar::new(y.n as u64)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} rows {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let t = std::time::Instant::now();
    let m = compute_map(&spec, kind, &|k| bar.set_position(k as u64));
    let secs = t.elapsed().as_secs_f64();
    bar.finish_and_clear();
    if let Some(path) = &a.out {
        let mut w = csv::Writer::from_path(path)
            .with_context(|| format!("cannot write {}", path.display()))?;
        let name = |ax: Axis| match ax {
            Axis::Alpha => "alpha",
            Axis::Beta => "beta",
            Axis::Gamma => "gamma",
            Axis::Delta => "delta",
        };
        let mut header = vec![name(x.axis), name(y.axis), "stable"];
        if a.radius {
            header.push("spectral_radius");
        }
        w.write_record(&header)?;
        for iy in 0..y.n {
            for ix in 0..x.n {
                let k = iy * x.n + ix;
                let mut rec = vec![
                    format!("{:e}", x.value(ix)),
                    format!("{:e}", y.value(iy)),
                    (m.stable[k] as u8).to_string(),
                ];
                if let Some(r) = &m.radius {
                    rec.push(format!("{:e}", r[k]));
                }
                w.write_record(&rec)?;
            }
        }
        w.flush()?;
    }
    let summary = MapSummary {
        points: x.n * y.n,
        stable_points: m.stable.iter().filter(|&&s| s).count(),
        seconds: secs,
        out: a.out.as_ref().map(|p| p.display().to_string()),
    };
    if a.json {
        return print_json(&summary);
    }
    println!(
        "{} points, {} stable ({:.2} %), computed in {:.3} s{}",
        summary.points,
        summary.stable_points,
        100.0 * summary.stable_points as f64 / summary.points as f64,
        secs,
        summary
            .out
            .map(|p| format!("; written to {p}"))
            .unwrap_or_default()
    );
    Ok(())
}
