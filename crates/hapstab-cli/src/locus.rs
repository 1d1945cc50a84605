//! `hapstab locus`: the root locus in the virtual stiffness K at a given damping B
//! ([`hapstab::locus`]): the roots of p(z) as K sweeps from 0 to beyond K_max, with the unit
//! circle and the crossing at the exact K_max marked; a CSV of the roots and a JSON on request.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::locus::{RootLocus, root_locus};
use num_complex::Complex64;
use serde::Serialize;

use crate::model::{DEFAULT_WALL, LoopArgs, LoopInput, describe_loop};
use crate::output::{csv_num, eng, print_json, radius_text, sig};
use crate::wall_plot::files_text;
use hapstab_plot::{Annotation, Figure, Grid, Legend, Marker, Series, palette};

/// Arguments of `hapstab locus`.
#[derive(Args, Debug)]
pub struct LocusArgs {
    #[command(flatten)]
    lp: LoopArgs,
    /// Virtual damping B in Ns/m at which K is swept [default: 10].
    #[arg(long, allow_hyphen_values = true)]
    wall_damping: Option<f64>,
    /// Draw the locus to FILE: SVG or PNG by its extension, both FILE.svg and FILE.png for
    /// any other name.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Write the roots to FILE as CSV: stiffness_n_per_m, branch, re, im, modulus, one row
    /// per root and stiffness.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// Where the locus meets the unit circle at K_max.
#[derive(Serialize)]
struct CrossingOut {
    re: f64,
    im: f64,
    modulus: f64,
    /// |arg z|/(2πT), Hz: the frequency of the oscillation at K_max.
    frequency_hz: f64,
}

#[derive(Serialize)]
struct LocusOut<'a> {
    input: LoopInput,
    wall_damping: f64,
    k_max: Option<f64>,
    k_interval: Option<[f64; 2]>,
    /// Index of K = K_max in `stiffness`.
    k_max_index: Option<usize>,
    crossing: Option<CrossingOut>,
    /// The sweep of K in N/m.
    stiffness: &'a [f64],
    /// The roots at each K as [re, im] pairs, branch-ordered.
    roots: &'a [Vec<Complex64>],
    /// max |z| at each K.
    spectral_radius: &'a [f64],
    #[serde(skip_serializing_if = "Vec::is_empty")]
    plot: Vec<PathBuf>,
    #[serde(skip_serializing_if = "Option::is_none")]
    csv: Option<PathBuf>,
}

/// Runs `hapstab locus`.
pub fn run(a: &LocusArgs) -> Result<()> {
    let rl = a.lp.resolve(false)?;
    if rl.normalized {
        bail!(
            "locus works in physical units (N/m, Ns/m): give the plant in kg, Ns/m, N/m and \
             --period, not --gamma/--delta"
        );
    }
    let b = a.wall_damping.unwrap_or(DEFAULT_WALL.damping);
    if !b.is_finite() {
        bail!("--wall-damping: wall damping B must be a finite number (got {b})");
    }
    let sys = rl.system()?;
    let fam = sys.family();
    let n = fam.degree();
    let per = hapstab::limits::roots_cost(n);
    let sweep = hapstab::limits::Cost {
        seconds: per.seconds * (hapstab::locus::DEFAULT_SAMPLES + 3) as f64,
        memory: per.memory,
    };
    let cost = hapstab::limits::interval_cost(n).then(sweep);
    crate::budget::check_loop(&a.lp, &rl.lp, cost, "the root locus")?;
    let locus = root_locus(&rl.lp, b, None)?;
    let mut plot = Vec::new();
    if let Some(path) = &a.plot {
        let title = format!("Root locus in K at B = {} Ns/m", sig(b, 4));
        let sub = crate::wall_plot::loop_line(&rl);
        plot = figure(&locus, rl.lp.period, &title, &sub)
            .save_as(path)
            .with_context(|| format!("--plot {}", path.display()))?;
    }
    if let Some(path) = &a.csv {
        write_csv(path, &locus)
            .with_context(|| format!("--csv: cannot write {}", path.display()))?;
    }
    let crossing = locus.crossing.map(|z| CrossingOut {
        re: z.re,
        im: z.im,
        modulus: z.norm(),
        frequency_hz: z.arg().abs() / (2.0 * std::f64::consts::PI * rl.lp.period),
    });
    if a.json {
        return print_json(&LocusOut {
            input: rl.input(None),
            wall_damping: b,
            k_max: locus.k_max,
            k_interval: locus.k_interval,
            k_max_index: locus.k_max_index,
            crossing,
            stiffness: &locus.stiffness,
            roots: &locus.roots,
            spectral_radius: &locus.spectral_radius,
            plot,
            csv: a.csv.clone(),
        });
    }
    for line in describe_loop(&rl.lp) {
        println!("{line}");
    }
    print_summary(&locus, crossing.as_ref());
    if !plot.is_empty() {
        println!("plot      {}", files_text(&plot));
    }
    if let Some(p) = &a.csv {
        println!("csv       {}", p.display());
    }
    Ok(())
}

fn print_summary(l: &RootLocus, crossing: Option<&CrossingOut>) {
    let kt = |k: f64| eng(k, "N/m", 6);
    let (k0, k1) = (
        l.stiffness.first().copied().unwrap_or(f64::NAN),
        l.stiffness.last().copied().unwrap_or(f64::NAN),
    );
    println!(
        "locus     {} stiffnesses from {} to {} at B = {}, {} roots each",
        l.stiffness.len(),
        kt(k0),
        kt(k1),
        eng(l.damping, "Ns/m", 6),
        l.roots.first().map_or(0, Vec::len)
    );
    match (l.k_interval, crossing) {
        (Some([lo, hi]), Some(c)) => {
            println!("stiffness stable for {} < K < {}", kt(lo), kt(hi));
            println!(
                "crossing  at K_max = {} a root reaches the unit circle at z = {} {} {}j \
                 (|z| = {}, {})",
                kt(hi),
                sig(c.re, 6),
                if c.im < 0.0 { "−" } else { "+" },
                sig(c.im.abs(), 6),
                radius_text(c.modulus),
                eng(c.frequency_hz, "Hz", 6)
            );
        }
        _ => println!("stiffness no stable K at this B"),
    }
}

/// One row per root and stiffness.
fn write_csv(path: &Path, l: &RootLocus) -> Result<()> {
    let mut w = csv::Writer::from_path(path)?;
    w.write_record(["stiffness_n_per_m", "branch", "re", "im", "modulus"])?;
    for (k, roots) in l.stiffness.iter().zip(&l.roots) {
        for (i, z) in roots.iter().enumerate() {
            w.write_record([
                csv_num(*k),
                i.to_string(),
                csv_num(z.re),
                csv_num(z.im),
                csv_num(z.norm()),
            ])?;
        }
    }
    w.flush()?;
    Ok(())
}

/// Largest |z| shown: the locus beyond it is clipped.
const REACH_CAP: f64 = 3.0;

/// Side of each square panel (px; a little wider than tall for the y-axis labels).
const PANEL: (u32, u32) = (840, 800);

/// The zoom panel holds the moving roots within this distance of the crossing.
const ZOOM_RADIUS: f64 = 0.5;

/// The z-plane with every branch, and beside it a zoom on the crossing at K_max.
fn figure(l: &RootLocus, period: f64, title: &str, subtitle: &str) -> Grid {
    let reach = l
        .spectral_radius
        .iter()
        .copied()
        .filter(|r| r.is_finite())
        .fold(1.0_f64, f64::max)
        .min(REACH_CAP)
        * 1.12;
    let full = [-reach, reach, -reach, reach];
    let zoom = zoom_box(l);
    let mut g = Grid::new(title, if zoom.is_some() { 2 } else { 1 })
        .subtitle(subtitle)
        .panel_size(PANEL.0, PANEL.1);
    g.push(panel(l, period, full, "z-plane", true));
    if let Some(b) = zoom {
        g.push(panel(l, period, b, "near the crossing at K_max", false));
    }
    g
}

/// A square window around the crossing holding the branches that move within
/// [`ZOOM_RADIUS`] of it (None without a crossing).
fn zoom_box(l: &RootLocus) -> Option<[f64; 4]> {
    let c = l.crossing?;
    let c = Complex64::new(c.re, c.im.abs());
    let branches = l.roots.first().map_or(0, Vec::len);
    let (mut x0, mut x1, mut y0, mut y1) = (c.re, c.re, -c.im, c.im);
    for j in 0..branches {
        let path: Vec<Complex64> = l.roots.iter().filter_map(|r| r.get(j).copied()).collect();
        let moves = path.iter().any(|z| (z - path[0]).norm() > 1e-6);
        for z in path
            .iter()
            .filter(|z| moves && (*z - c).norm().min((z.conj() - c).norm()) < ZOOM_RADIUS)
        {
            (x0, x1, y0, y1) = (x0.min(z.re), x1.max(z.re), y0.min(z.im), y1.max(z.im));
        }
    }
    let half = 0.5 * (x1 - x0).max(y1 - y0).max(1e-3) * 1.15;
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    Some([cx - half, cx + half, cy - half, cy + half])
}

/// One panel: the unit circle, each branch as a line, the roots at K = 0 and the roots on
/// the circle at K_max, in the window [x0, x1, y0, y1].
fn panel(l: &RootLocus, period: f64, w: [f64; 4], title: &str, legend: bool) -> Figure {
    let mut fig = Figure::new(title)
        .x_label("Re z")
        .y_label("Im z")
        .x_range(w[0], w[1])
        .y_range(w[2], w[3])
        .legend(if legend {
            Legend::Below
        } else {
            Legend::Hidden
        });
    let circle = (0..=3600).map(|i| {
        let t = (i as f64 / 10.0).to_radians();
        (t.cos(), t.sin())
    });
    fig.add(
        Series::dashed(circle)
            .color(palette::GREY)
            .width(2)
            .label("unit circle |z| = 1"),
    );
    let branches = l.roots.first().map_or(0, Vec::len);
    for j in 0..branches {
        let pts = l
            .roots
            .iter()
            .filter_map(|r| r.get(j))
            .map(|z| (z.re, z.im));
        let s = Series::line(pts).color(palette::BLUE).width(2);
        fig.add(if j == 0 {
            s.label(format!(
                "roots of p(z), K = 0 … {} N/m",
                sig(l.stiffness.last().copied().unwrap_or(f64::NAN), 4)
            ))
        } else {
            s
        });
    }
    if let Some(r0) = l.roots.first() {
        fig.add(
            Series::scatter(r0.iter().map(|z| (z.re, z.im)), Marker::Cross)
                .color(palette::BLACK)
                .label("K = 0"),
        );
    }
    mark_crossing(&mut fig, l, period, w);
    fig
}

/// The roots on the unit circle at K_max, with the value written beside the upper one.
fn mark_crossing(fig: &mut Figure, l: &RootLocus, period: f64, w: [f64; 4]) {
    let (Some(i), Some(k)) = (l.k_max_index, l.k_max) else {
        return;
    };
    let on: Vec<(f64, f64)> = l.roots[i]
        .iter()
        .filter(|z| (z.norm() - 1.0).abs() < 1e-6)
        .map(|z| (z.re, z.im))
        .collect();
    let f = l.crossing.map_or(f64::NAN, |z| {
        z.arg().abs() / (2.0 * std::f64::consts::PI * period)
    });
    fig.add(
        Series::scatter(on.clone(), Marker::Circle)
            .color(palette::VERMILLION)
            .size(9)
            .label(format!("K_max = {} N/m ({} Hz)", sig(k, 6), sig(f, 4))),
    );
    if let Some(&at) = on.iter().max_by(|x, y| x.1.total_cmp(&y.1)) {
        let text = format!("K_max = {} N/m   ", sig(k, 6));
        // written to the left of the point when it lies in the right half
        let span = w[1] - w[0];
        let x = if at.0 > 0.5 * (w[0] + w[1]) {
            at.0 - text.chars().count() as f64 * 12.0 / 640.0 * span
        } else {
            at.0
        };
        fig.annotations.push(Annotation {
            at: (x, at.1 + 0.04 * span),
            text,
            color: palette::VERMILLION,
            lift: false,
        });
    }
}
