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

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use anyhow::{Context, Result, anyhow, bail};
use clap::{Args, ValueEnum};
use hapstab::answer::{MapInput, MapSummary};
use hapstab::limits::map_cost_of_degree;
use hapstab::map::{Axis, AxisRange, MapKind, MapSpec, compute_map, wall_map_physical};
use hapstab::{AffineFamily, Normalized};
use hapstab_plot::RGBColor;
use serde::Serialize;

use crate::budget::{self, Driver};
use crate::model::{LOOP_FLAGS, LoopArgs, LoopInput, PHYSICAL_PLANT_FLAGS};
use crate::output::print_json;
use hapstab_plot::{Figure, Legend, Series, palette};

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
    input: LoopInput,
    /// The loop in words, for the figure's subtitle.
    loop_line: String,
}

/// Layout of the `--out` file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Format {
    /// Comma-separated values with a header.
    Csv,
    /// NumPy .npy structured array.
    Npy,
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

fn normalized_map(a: &MapArgs, x: Grid, y: Grid, kind: MapKind) -> Result<Values> {
    if a.lp.any_physical() {
        bail!(
            "maps over alpha, beta, gamma, delta are of the paper's normalized loop; for a physical loop grid --x K:LO:HI:N --y B:LO:HI:N"
        );
    }
    let p = &crate::loop_file::paper_plant(&a.lp.plant, "a map over alpha, beta, gamma, delta")?;
    if p.any_physical() {
        bail!(
            "maps over alpha, beta, gamma, delta are of the paper's normalized loop; --loop holds a physical loop: grid --x K:LO:HI:N --y B:LO:HI:N"
        );
    }
    let d = crate::model::delay_samples(p.delay.unwrap_or(0.0))?;
    let base = Normalized::new(
        a.alpha.unwrap_or(0.0),
        a.beta.unwrap_or(0.0),
        p.gamma.unwrap_or(0.0),
        p.delta.unwrap_or(0.0),
        d,
    )?;
    let spec = MapSpec::new(x.range, y.range, base)?;
    check_budget(a, (x, y), d + 3, 1.0, ("--delay", &d.to_string()))?;
    let bar = map_bar(a, x, y, d + 3);
    let m = compute_map(&spec, kind, &bar.stage(0));
    Ok(Values {
        stable: m.stable,
        radius: m.radius,
        loop_line: normalized_line(base, (x.name, y.name))?,
        input: LoopInput::Normalized {
            gamma: base.gamma,
            delta: base.delta,
            d,
            alpha: Some(base.alpha),
            beta: Some(base.beta),
        },
    })
}

/// The fixed parameters of a normalized map (those of α, β, γ, δ that are no axis), then the
/// rest of the paper's loop ([`crate::wall_plot::loop_line_without`] its plant).
fn normalized_line(base: Normalized, axes: (Name, Name)) -> Result<String> {
    let on_axis = |a: Axis| axes.0 == Name::Normalized(a) || axes.1 == Name::Normalized(a);
    let mut parts: Vec<String> = [
        (Axis::Alpha, "α", base.alpha),
        (Axis::Beta, "β", base.beta),
        (Axis::Gamma, "γ", base.gamma),
        (Axis::Delta, "δ", base.delta),
    ]
    .into_iter()
    .filter(|(a, _, _)| !on_axis(*a))
    .map(|(_, n, v)| format!("{n} = {}", crate::output::sig(v, 4)))
    .collect();
    let pp = hapstab::PlantParams {
        gamma: base.gamma,
        delta: base.delta,
    };
    let rl = crate::model::ResolvedLoop {
        lp: hapstab::model::Loop::normalized(pp, base.d)?,
        normalized: true,
        wall: None,
    };
    use crate::wall_plot::Part;
    parts.push(crate::wall_plot::loop_line_without(&rl, &[Part::Plant]));
    Ok(parts.join(", "))
}

/// The map of a loop's wall: K along x and B along y, converted to the family's wall units.
fn loop_map(a: &MapArgs, x: Grid, y: Grid, kind: MapKind) -> Result<Values> {
    if a.lp.plant.normalized_mode() {
        bail!("K and B axes map a physical loop; with --gamma/--delta grid alpha and beta");
    }
    let rl = a.lp.resolve(false)?;
    let sys = rl.system()?;
    let fam = sys.family();
    let n = fam.degree();
    let degree = crate::budget::degree_drivers(&a.lp, &rl.lp)
        .into_iter()
        .max_by(|p, q| p.factor.total_cmp(&q.factor))
        .map(|d| (d.flag, d.value));
    let (flag, value) = degree.unwrap_or(("--delay", "0".into()));
    let (a_lo, b_lo) = fam.to_units(x.range.lo, y.range.lo);
    let (a_hi, b_hi) = fam.to_units(x.range.hi, y.range.hi);
    let stable = stable_share(fam, (a_lo, a_hi), (b_lo, b_hi));
    check_budget(a, (x, y), n, stable, (flag, &value))?;
    let bar = map_bar(a, x, y, n);
    let m = wall_map_physical(
        fam,
        ((x.range.lo, x.range.hi), x.range.n),
        ((y.range.lo, y.range.hi), y.range.n),
        kind,
        &bar.stage(0),
    )?;
    Ok(Values {
        stable: m.stable,
        radius: m.radius,
        loop_line: crate::wall_plot::loop_line(&rl),
        input: rl.input(None),
    })
}

/// Refuses a map beyond the command-line budget (a point test is O(n²) in the degree n of
/// p(z), a spectral radius about the cost of its roots, O(n²) per sweep), naming --x, --y or
/// the flag that sets most of the degree.
fn check_budget(
    a: &MapArgs,
    (x, y): (Grid, Grid),
    degree: usize,
    stable: f64,
    (what, value): (&str, &str),
) -> Result<()> {
    let points = x.range.n as f64 * y.range.n as f64;
    budget::check(
        map_cost_of_degree(points, degree, a.radius, stable),
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
                factor: (degree.max(3) as f64 / 3.0).powi(2),
            },
        ],
    )
}

/// Points per axis of the sample that estimates a map's stable share.
const SHARE_SAMPLES: usize = 8;

/// The share of stable walls on an 8 × 8 sample of the map's window (the Schur–Cohn test,
/// O(n²) each): a stable point costs a full test, an unstable one a small part of it.
fn stable_share(fam: &AffineFamily, (a0, a1): (f64, f64), (b0, b1): (f64, f64)) -> f64 {
    let at = |lo: f64, hi: f64, i: usize| lo + (hi - lo) * i as f64 / (SHARE_SAMPLES - 1) as f64;
    let mut stable = 0usize;
    for i in 0..SHARE_SAMPLES {
        for j in 0..SHARE_SAMPLES {
            let c = fam.coefficients(at(a0, a1, i), at(b0, b1, j));
            stable += usize::from(hapstab::stability::schur_stable(&c));
        }
    }
    // one stable point in the sample stands for at least its share of the grid
    (stable as f64 + 0.5) / (SHARE_SAMPLES * SHARE_SAMPLES) as f64
}

/// The column names of the output file.
fn columns(x: Grid, y: Grid, v: &Values) -> Vec<&'static str> {
    let mut cols = vec![axis_label(x.name), axis_label(y.name), "stable"];
    if v.radius.is_some() {
        cols.push("spectral_radius");
    }
    cols
}

/// The grid values of an axis as shortest round-trip decimal text, formatted once.
fn axis_text(r: &AxisRange) -> Vec<String> {
    let mut buf = ryu::Buffer::new();
    (0..r.n)
        .map(|i| buf.format(r.value(i)).to_owned())
        .collect()
}

/// Writes the map as CSV: the axis values are formatted once per axis and every record is
/// assembled from borrowed bytes (no allocation per field).
fn write_csv(path: &Path, x: Grid, y: Grid, v: &Values) -> Result<()> {
    let file = File::create(path).with_context(|| format!("cannot write {}", path.display()))?;
    let mut w = csv::WriterBuilder::new()
        .buffer_capacity(1 << 20)
        .from_writer(file);
    w.write_record(columns(x, y, v))?;
    let (xs, ys) = (axis_text(&x.range), axis_text(&y.range));
    let mut buf = ryu::Buffer::new();
    for (iy, yt) in ys.iter().enumerate() {
        for (ix, xt) in xs.iter().enumerate() {
            let k = iy * xs.len() + ix;
            w.write_field(xt)?;
            w.write_field(yt)?;
            w.write_field(if v.stable[k] { "1" } else { "0" })?;
            if let Some(r) = &v.radius {
                w.write_field(buf.format(r[k]))?;
            }
            w.write_record(None::<&[u8]>)?;
        }
    }
    w.flush()
        .with_context(|| format!("cannot write {}", path.display()))
}

/// The NPY 1.0 header for `points` records of the map's columns: magic, version, header
/// length, and the dict padded with spaces to a multiple of 64 bytes ending in a newline.
fn npy_header(cols: &[&str], points: usize) -> Vec<u8> {
    let fields: Vec<String> = cols
        .iter()
        .map(|c| format!("('{c}', '{}')", if *c == "stable" { "|u1" } else { "<f8" }))
        .collect();
    let dict = format!(
        "{{'descr': [{}], 'fortran_order': False, 'shape': ({points},), }}",
        fields.join(", ")
    );
    let total = (10 + dict.len() + 1).div_ceil(64) * 64;
    let mut h = b"\x93NUMPY\x01\x00".to_vec();
    h.extend_from_slice(&((total - 10) as u16).to_le_bytes());
    h.extend_from_slice(dict.as_bytes());
    h.resize(total - 1, b' ');
    h.push(b'\n');
    h
}

/// Writes the map as a NumPy structured array (see the module documentation).
fn write_npy(path: &Path, x: Grid, y: Grid, v: &Values) -> Result<()> {
    let fail = || format!("cannot write {}", path.display());
    let file = File::create(path).with_context(fail)?;
    let mut w = BufWriter::with_capacity(1 << 20, file);
    let (xr, yr) = (&x.range, &y.range);
    w.write_all(&npy_header(&columns(x, y, v), xr.n * yr.n))
        .with_context(fail)?;
    let xs: Vec<[u8; 8]> = (0..xr.n).map(|i| xr.value(i).to_le_bytes()).collect();
    for iy in 0..yr.n {
        let yb = yr.value(iy).to_le_bytes();
        for (ix, xb) in xs.iter().enumerate() {
            let k = iy * xr.n + ix;
            w.write_all(xb).with_context(fail)?;
            w.write_all(&yb).with_context(fail)?;
            w.write_all(&[v.stable[k] as u8]).with_context(fail)?;
            if let Some(r) = &v.radius {
                w.write_all(&r[k].to_le_bytes()).with_context(fail)?;
            }
        }
    }
    w.flush().with_context(fail)
}

/// Colour classes of a radius heatmap: (upper bound of ρ, colour, legend entry).
fn radius_classes() -> [(f64, RGBColor, &'static str); 4] {
    [
        (0.99, palette::BLUE, "ρ < 0.99"),
        (1.0, palette::SKY, "0.99 ≤ ρ < 1"),
        (1.01, palette::ORANGE, "1 ≤ ρ < 1.01"),
        (f64::INFINITY, palette::VERMILLION, "ρ ≥ 1.01"),
    ]
}

/// The points of class `c` (by `class_of`, a function of the point's index) as rectangles
/// merged into runs along each row: a few rectangles per row instead of one per point.
fn runs(
    x: &AxisRange,
    y: &AxisRange,
    class_of: &dyn Fn(usize) -> Option<usize>,
    c: usize,
) -> Vec<((f64, f64), (f64, f64))> {
    let (hx, hy) = (x.step() / 2.0, y.step() / 2.0);
    let mut out = Vec::new();
    for iy in 0..y.n {
        let yv = y.value(iy);
        let mut ix = 0;
        while ix < x.n {
            if class_of(iy * x.n + ix) != Some(c) {
                ix += 1;
                continue;
            }
            let start = ix;
            while ix < x.n && class_of(iy * x.n + ix) == Some(c) {
                ix += 1;
            }
            out.push((
                (x.value(start) - hx, yv - hy),
                (x.value(ix - 1) + hx, yv + hy),
            ));
        }
    }
    out
}

/// The axis title of a gridded quantity, with units for the physical wall.
fn axis_title(name: Name) -> &'static str {
    match name {
        Name::Normalized(Axis::Alpha) => "α",
        Name::Normalized(Axis::Beta) => "β",
        Name::Normalized(Axis::Gamma) => "γ",
        Name::Normalized(Axis::Delta) => "δ",
        Name::K => "K (N/m)",
        Name::B => "B (Ns/m)",
    }
}

/// The heatmap of a map: stable points (or the spectral radius in classes) as filled cells.
fn heatmap(x: Grid, y: Grid, v: &Values) -> Figure {
    let (xr, yr) = (&x.range, &y.range);
    let (hx, hy) = (xr.step() / 2.0, yr.step() / 2.0);
    let mut fig = Figure::new("Stability map")
        .subtitle(&v.loop_line)
        .x_label(axis_title(x.name))
        .y_label(axis_title(y.name))
        .x_range(xr.lo - hx, xr.hi + hx)
        .y_range(yr.lo - hy, yr.hi + hy)
        .legend(Legend::Below);
    match &v.radius {
        None => {
            let stable = |k: usize| v.stable[k].then_some(0);
            let cells = runs(xr, yr, &stable, 0);
            add_cells(&mut fig, cells, palette::BLUE, "stable (Schur–Cohn)");
        }
        Some(r) => {
            let classes = radius_classes();
            let class_of = |k: usize| classes.iter().position(|(hi, _, _)| r[k] < *hi);
            for (c, (_, color, label)) in classes.iter().enumerate() {
                add_cells(&mut fig, runs(xr, yr, &class_of, c), *color, label);
            }
        }
    }
    fig
}

/// Adds rectangles as opaque, unoutlined polygons of one colour, the first one labelled.
fn add_cells(fig: &mut Figure, rects: Vec<((f64, f64), (f64, f64))>, color: RGBColor, label: &str) {
    for (i, ((x0, y0), (x1, y1))) in rects.into_iter().enumerate() {
        let cell = Series::polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
            .color(color)
            .alpha(1.0)
            .no_outline();
        fig.add(if i == 0 { cell.label(label) } else { cell });
    }
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
