//! `hapstab map`: the paper's grid method (Section V) in parallel — over any two of α, β, γ,
//! δ for the paper's normalized loop, or over the physical wall (K, B) of any loop.
//!
//! The grid goes to a file in one of two layouts, one record per grid point, the horizontal
//! axis varying fastest (point (ix, iy) is record iy·nx + ix):
//!
//! - CSV: a header, then `x,y,stable[,spectral_radius]` with the axes' names as column names,
//!   shortest round-trip floats and stable as 0/1;
//! - NPY (NumPy format 1.0): a one-dimensional structured array of shape (nx·ny,) with the same
//!   fields, x and y as `<f8`, `stable` as `|u1` and `spectral_radius` as `<f8`, packed
//!   little-endian; `np.load(f)["stable"].reshape(ny, nx)` is the map as an image.
//!
//! `--plot` draws the map as a heatmap with the shared plotting module.
//!
//! Parts: [`axes`] parses `--x`/`--y`, [`values`] computes the grid, [`cost`] refuses a map
//! beyond the budget, [`file`] writes the `--out` file, [`plot`] draws the heatmap.

mod axes;
mod cost;
mod file;
mod plot;
mod values;

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::answer::{MapInput, MapSummary};
use hapstab::limits::map_cost_of_degree;
use hapstab::map::MapKind;
use serde::Serialize;

use crate::model::{LOOP_FLAGS, LoopArgs, LoopInput, PHYSICAL_PLANT_FLAGS};
use crate::output::print_json;
use axes::{Grid, Name, axis_label, parse_axis};
use file::{Format, write_csv, write_npy};
use plot::heatmap;
use values::{loop_map, normalized_map};

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
    /// Fixed α of a normalized map (when not gridded) [default: 0].
    #[arg(long, allow_hyphen_values = true)]
    alpha: Option<f64>,
    /// Fixed β of a normalized map (when not gridded) [default: 0].
    #[arg(long, allow_hyphen_values = true)]
    beta: Option<f64>,
    /// Also compute the spectral radius at every point (slower).
    #[arg(long)]
    radius: bool,
    /// Output file: one record per grid point, the x axis varying fastest, with the columns
    /// x, y, stable (0/1)[, spectral_radius].
    #[arg(long)]
    out: Option<std::path::PathBuf>,
    /// Layout of the --out file: csv (a header, shortest round-trip floats) or npy (a NumPy
    /// structured array of shape (nx·ny,), fields x, y as <f8, stable as |u1,
    /// spectral_radius as <f8; np.load(f)["stable"].reshape(ny, nx) is the map).
    #[arg(long, value_enum, default_value_t = Format::Csv, requires = "out")]
    format: Format,
    /// Draw the map as a heatmap to FILE: SVG or PNG by its extension (both FILE.svg and
    /// FILE.png for any other name); K (N/m) and B (Ns/m) axes for a physical loop.
    #[arg(long, value_name = "FILE")]
    plot: Option<std::path::PathBuf>,
    /// Print a JSON summary instead of text.
    #[arg(long)]
    json: bool,
}

/// Stable flags and radii of a map, row-major.
struct Values {
    stable: Vec<bool>,
    radius: Option<Vec<f64>>,
    input: LoopInput,
    /// The loop in words, for the figure's subtitle.
    loop_line: String,
}

#[derive(Serialize)]
struct MapOut {
    /// The map's summary with its inputs, as the explorer's `/api/map` gives it.
    #[serde(flatten)]
    summary: MapSummary,
    out: Option<String>,
    /// Files written by --plot.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    plot: Vec<std::path::PathBuf>,
}

/// The bar over the map's rows, shown when the map's estimated cost (p(z) of `degree`) is
/// long ([`crate::progress::LONG_SECONDS`]).
fn map_bar(a: &MapArgs, x: Grid, y: Grid, degree: usize) -> crate::progress::Bar {
    let points = x.range.n as f64 * y.range.n as f64;
    let cost = map_cost_of_degree(points, degree, a.radius, 1.0).seconds;
    crate::progress::Bar::new(
        y.range.n,
        "rows",
        !a.json && cost >= crate::progress::LONG_SECONDS,
    )
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
    let t = std::time::Instant::now();
    let v = match (x.name, y.name) {
        (Name::Normalized(_), Name::Normalized(_)) => normalized_map(a, x, y, kind)?,
        (Name::K, Name::B) => loop_map(a, x, y, kind)?,
        _ => bail!(
            "--x and --y must both be normalized (alpha, beta, gamma, delta), or --x K and --y B (got {} and {})",
            axis_label(x.name),
            axis_label(y.name)
        ),
    };
    let secs = t.elapsed().as_secs_f64();
    if let Some(path) = &a.out {
        match a.format {
            Format::Csv => write_csv(path, x, y, &v)?,
            Format::Npy => write_npy(path, x, y, &v)?,
        }
    }
    let plot = match &a.plot {
        Some(p) => heatmap(x, y, &v)
            .save_as(p)
            .with_context(|| format!("--plot {}", p.display()))?,
        None => Vec::new(),
    };
    let points = x.range.n * y.range.n;
    let stable_points = v.stable.iter().filter(|&&s| s).count();
    let out = a.out.as_ref().map(|p| p.display().to_string());
    if a.json {
        return print_json(&MapOut {
            summary: MapSummary {
                input: MapInput {
                    x: a.x.clone(),
                    y: a.y.clone(),
                    lp: v.input,
                    radius: a.radius,
                },
                points,
                stable_points,
                seconds: secs,
            },
            out,
            plot,
        });
    }
    println!(
        "{points} points, {stable_points} stable ({:.2} %), computed in {secs:.3} s{}",
        100.0 * stable_points as f64 / points as f64,
        out.map(|p| format!("; written to {p}")).unwrap_or_default()
    );
    if !plot.is_empty() {
        println!("plot written to {}", crate::wall_plot::files_text(&plot));
    }
    Ok(())
}
