//! `hapstab locus`: the root locus in the virtual stiffness K at a given damping B
//! ([`hapstab::locus`]): the roots of p(z) as K sweeps from 0 to beyond K_max, with the unit
//! circle and the crossing at the exact K_max marked; a CSV of the roots and a JSON on request.
//!
//! Parts: [`text`] prints the summary, [`csv_file`] writes the roots, [`plot`] draws the locus.

mod csv_file;
mod plot;
mod text;

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::locus::root_locus;
use num_complex::Complex64;
use serde::Serialize;

use crate::model::{DEFAULT_WALL, LoopArgs, LoopInput, print_loop};
use crate::output::{print_json, sig};
use crate::wall_plot::files_text;
use csv_file::write_csv;
use plot::figure;
use text::print_summary;

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
        plot = figure(&locus, &title, &sub)
            .save_as(path)
            .with_context(|| format!("--plot {}", path.display()))?;
    }
    if let Some(path) = &a.csv {
        write_csv(path, &locus)
            .with_context(|| format!("--csv: cannot write {}", path.display()))?;
    }
    let crossing = locus
        .crossing
        .zip(locus.crossing_frequency_hz)
        .map(|(z, frequency_hz)| CrossingOut {
            re: z.re,
            im: z.im,
            modulus: z.norm(),
            frequency_hz,
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
    print_loop(&rl.lp);
    print_summary(&locus, crossing.as_ref());
    if !plot.is_empty() {
        println!("plot      {}", files_text(&plot));
    }
    if let Some(p) = &a.csv {
        println!("csv       {}", p.display());
    }
    Ok(())
}
