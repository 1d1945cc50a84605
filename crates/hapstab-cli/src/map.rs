//! `hapstab map`: the paper's grid method (Section V) in parallel — over any two of α, β, γ,
//! δ for the paper's normalized loop, or over the physical wall (K, B) of any loop.

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use hapstab::limits::map_cost;
use hapstab::map::{Axis, AxisRange, MapKind, MapSpec, compute_map, wall_map};
use hapstab::{AffineFamily, Normalized};
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::io::IsTerminal;

use crate::budget::{self, Driver};
use crate::model::{LOOP_FLAGS, LoopArgs, LoopInput, PHYSICAL_PLANT_FLAGS};
use crate::output::print_json;

/// Arguments of `hapstab map`.
#[derive(Args, Debug)]
#[command(mut_arg("alpha", |a| a.conflicts_with_all(PHYSICAL_PLANT_FLAGS).conflicts_with_all(LOOP_FLAGS)))]
#[command(mut_arg("beta", |a| a.conflicts_with_all(PHYSICAL_PLANT_FLAGS).conflicts_with_all(LOOP_FLAGS)))]
pub struct MapArgs {
    /// Horizontal axis as NAME:LO:HI:N, NAME one of alpha, beta, gamma, delta (the paper's
    /// normalized loop), or K (the wall stiffness of any loop in N/m, with --y B:…).
    #[arg(long, allow_hyphen_values = true)]
    x: String,
    /// Vertical axis as NAME:LO:HI:N (B: the wall damping in Ns/m, with --x K:…).
    #[arg(long, allow_hyphen_values = true)]
    y: String,
    #[command(flatten)]
    lp: LoopArgs,
    /// Fixed α of a normalized map (when not gridded) [default 0].
    #[arg(long, allow_hyphen_values = true)]
    alpha: Option<f64>,
    /// Fixed β of a normalized map (when not gridded) [default 0].
    #[arg(long, allow_hyphen_values = true)]
    beta: Option<f64>,
    /// Also compute the spectral radius at every point (slower).
    #[arg(long)]
    radius: bool,
    /// Output CSV file (columns x, y, stable[, spectral_radius]).
    #[arg(long)]
    out: Option<std::path::PathBuf>,
    /// Print a JSON summary instead of text.
    #[arg(long)]
    json: bool,
}

/// What an axis grids.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Name {
    /// A parameter of the paper's normalized loop.
    Normalized(Axis),
    /// The wall stiffness K in N/m.
    K,
    /// The wall damping B in Ns/m.
    B,
}

/// A parsed axis: its name and n points from lo to hi.
#[derive(Debug, Clone, Copy)]
struct Grid {
    name: Name,
    range: AxisRange,
}

fn parse_axis(s: &str, flag: &str) -> Result<Grid> {
    let parts: Vec<&str> = s.split(':').collect();
    if parts.len() != 4 {
        bail!("--{flag} must be NAME:LO:HI:N (got '{s}')");
    }
    let name = match parts[0] {
        "K" => Name::K,
        "B" => Name::B,
        other => Name::Normalized(other.parse().map_err(|_| {
            anyhow!("--{flag}: unknown parameter '{other}' (alpha, beta, gamma, delta, K, B)")
        })?),
    };
    let lo: f64 = parts[1]
        .parse()
        .map_err(|_| anyhow!("--{flag}: bad lower end '{}'", parts[1]))?;
    let hi: f64 = parts[2]
        .parse()
        .map_err(|_| anyhow!("--{flag}: bad upper end '{}'", parts[2]))?;
    let n: usize = parts[3]
        .parse()
        .map_err(|_| anyhow!("--{flag}: bad point count '{}'", parts[3]))?;
    let axis = match name {
        Name::Normalized(a) => a,
        Name::K => Axis::Alpha,
        Name::B => Axis::Beta,
    };
    let range = AxisRange::new(axis, lo, hi, n).map_err(|e| anyhow!("--{flag}: {e}"))?;
    Ok(Grid { name, range })
}

fn axis_label(name: Name) -> &'static str {
    match name {
        Name::Normalized(Axis::Alpha) => "alpha",
        Name::Normalized(Axis::Beta) => "beta",
        Name::Normalized(Axis::Gamma) => "gamma",
        Name::Normalized(Axis::Delta) => "delta",
        Name::K => "K",
        Name::B => "B",
    }
}

/// Stable flags and radii of a map, row-major.
struct Values {
    stable: Vec<bool>,
    radius: Option<Vec<f64>>,
    input: Option<LoopInput>,
}

#[derive(Serialize)]
struct MapSummary {
    #[serde(skip_serializing_if = "Option::is_none")]
    input: Option<LoopInput>,
    points: usize,
    stable_points: usize,
    seconds: f64,
    out: Option<String>,
}

fn normalized_map(
    a: &MapArgs,
    x: Grid,
    y: Grid,
    kind: MapKind,
    bar: &ProgressBar,
) -> Result<Values> {
    if a.lp.any_physical() {
        bail!(
            "maps over alpha, beta, gamma, delta are of the paper's normalized loop; for a physical loop grid --x K:LO:HI:N --y B:LO:HI:N"
        );
    }
    let p = &a.lp.plant;
    let d = crate::model::delay_samples(p.delay.unwrap_or(0.0))?;
    let base = Normalized::new(
        a.alpha.unwrap_or(0.0),
        a.beta.unwrap_or(0.0),
        p.gamma.unwrap_or(0.0),
        p.delta.unwrap_or(0.0),
        d,
    )?;
    let spec = MapSpec::new(x.range, y.range, base)?;
    check_budget(a, x, y, d + 3, "--delay", &d.to_string())?;
    let m = compute_map(&spec, kind, &|k| bar.set_position(k as u64));
    Ok(Values {
        stable: m.stable,
        radius: m.radius,
        input: None,
    })
}

/// The map of a loop's wall: K along x and B along y, converted to the family's wall units.
fn loop_map(a: &MapArgs, x: Grid, y: Grid, kind: MapKind, bar: &ProgressBar) -> Result<Values> {
    if a.lp.plant.normalized_mode() {
        bail!("K and B axes map a physical loop; with --gamma/--delta grid alpha and beta");
    }
    let rl = a.lp.resolve(false)?;
    let fam = AffineFamily::of_loop(&rl.lp)?;
    let (a_lo, b_lo) = fam.to_units(x.range.lo, y.range.lo);
    let (a_hi, b_hi) = fam.to_units(x.range.hi, y.range.hi);
    let xa = AxisRange::new(Axis::Alpha, a_lo, a_hi, x.range.n)?;
    let yb = AxisRange::new(Axis::Beta, b_lo, b_hi, y.range.n)?;
    let n = fam.degree();
    check_budget(a, x, y, n, "the loop's degree", &n.to_string())?;
    let m = wall_map(&fam, xa, yb, kind, &|k| bar.set_position(k as u64))?;
    Ok(Values {
        stable: m.stable,
        radius: m.radius,
        input: Some(LoopInput::new(&rl, None)),
    })
}

/// Refuses a map beyond the command-line budget (a point test is O(n²) in the degree n of
/// p(z), a spectral radius O(n³)), naming --x, --y or what sets the degree.
fn check_budget(
    a: &MapArgs,
    x: Grid,
    y: Grid,
    degree: usize,
    what: &str,
    value: &str,
) -> Result<()> {
    let points = x.range.n as f64 * y.range.n as f64;
    let d = degree.saturating_sub(3);
    budget::check(
        map_cost(points, d, a.radius),
        &format!("the map of {points} points"),
        &[
            Driver {
                flag: "--x",
                value: a.x.clone(),
                factor: x.range.n as f64 / 100.0,
            },
            Driver {
                flag: "--y",
                value: a.y.clone(),
                factor: y.range.n as f64 / 100.0,
            },
            Driver {
                flag: what,
                value: value.to_string(),
                factor: (degree.max(3) as f64 / 3.0).powi(if a.radius { 3 } else { 2 }),
            },
        ],
    )
}

/// Writes the grid as CSV; the caller names the file in any error (open, write, flush).
fn write_csv(path: &std::path::Path, x: Grid, y: Grid, v: &Values) -> Result<()> {
    let mut w = csv::Writer::from_path(path)?;
    let mut header = vec![axis_label(x.name), axis_label(y.name), "stable"];
    if v.radius.is_some() {
        header.push("spectral_radius");
    }
    w.write_record(&header)?;
    for iy in 0..y.range.n {
        for ix in 0..x.range.n {
            let k = iy * x.range.n + ix;
            let mut rec = vec![
                format!("{:e}", x.range.value(ix)),
                format!("{:e}", y.range.value(iy)),
                (v.stable[k] as u8).to_string(),
            ];
            if let Some(r) = &v.radius {
                rec.push(format!("{:e}", r[k]));
            }
            w.write_record(&rec)?;
        }
    }
    w.flush()?;
    Ok(())
}

fn progress_bar(a: &MapArgs, x: Grid, y: Grid) -> ProgressBar {
    let show = !a.json && std::io::stderr().is_terminal() && x.range.n * y.range.n >= 1_000_000;
    let bar = if show {
        ProgressBar::new(y.range.n as u64)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} rows {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar
}

/// Runs `hapstab map`.
pub fn run(a: &MapArgs) -> Result<()> {
    let x = parse_axis(&a.x, "x")?;
    let y = parse_axis(&a.y, "y")?;
    let kind = if a.radius {
        MapKind::SpectralRadius
    } else {
        MapKind::Stability
    };
    let bar = progress_bar(a, x, y);
    let t = std::time::Instant::now();
    let v = match (x.name, y.name) {
        (Name::Normalized(_), Name::Normalized(_)) => normalized_map(a, x, y, kind, &bar)?,
        (Name::K, Name::B) => loop_map(a, x, y, kind, &bar)?,
        _ => bail!(
            "--x and --y must both be normalized (alpha, beta, gamma, delta), or --x K and --y B (got {} and {})",
            axis_label(x.name),
            axis_label(y.name)
        ),
    };
    let secs = t.elapsed().as_secs_f64();
    bar.finish_and_clear();
    if let Some(path) = &a.out {
        write_csv(path, x, y, &v).with_context(|| format!("cannot write {}", path.display()))?;
    }
    let points = x.range.n * y.range.n;
    let stable_points = v.stable.iter().filter(|&&s| s).count();
    let out = a.out.as_ref().map(|p| p.display().to_string());
    if a.json {
        return print_json(&MapSummary {
            input: v.input,
            points,
            stable_points,
            seconds: secs,
            out,
        });
    }
    println!(
        "{points} points, {stable_points} stable ({:.2} %), computed in {secs:.3} s{}",
        100.0 * stable_points as f64 / points as f64,
        out.map(|p| format!("; written to {p}")).unwrap_or_default()
    );
    Ok(())
}
