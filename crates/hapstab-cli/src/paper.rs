//! `hapstab paper --out DIR`: recomputes Hulin, Preusche & Hirzinger (2008) — Figs. 4–10 as
//! SVG and PNG, the claims C1–C11 with verdicts and the α_max table — into DIR/report.md,
//! DIR/report.html (self-contained) and DIR/claims.json (machine-readable).

mod claims;
mod compute;
mod figures;
mod report;

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Args;
use rayon::prelude::*;
use serde::Serialize;

use crate::output::print_json;
use hapstab_plot::Saved;

/// Arguments of `hapstab paper`.
#[derive(Args, Debug)]
pub struct PaperArgs {
    /// Output folder (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Print a JSON summary (files, claims with verdicts, seconds) instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct ClaimSummary {
    id: &'static str,
    verdict: &'static str,
    measured: String,
}

#[derive(Serialize)]
struct PaperInput {
    out: String,
}

#[derive(Serialize)]
struct Summary {
    input: PaperInput,
    files: Vec<String>,
    claims: Vec<ClaimSummary>,
    seconds: f64,
}

fn notes() -> Vec<String> {
    vec![
        "Regions are the exact polygons of hapstab::region::stable_region (every vertex is a point where p(z) has a root on the unit circle); \
         for drawing, outlines are thinned by Douglas–Peucker to 1e-4 of the axis range (a tenth of a pixel)."
            .to_string(),
        "Fig. 7: the 2 % and 5 % points are hapstab::paper::linear::validity_points (first β > 0 where the error (24) reaches the level, on the exact boundary)."
            .to_string(),
        "Figs. 8–10: γ is swept in fractions of the Nyquist frequency, γ = (fπ)² + δ²/4 (eq. 26); the robust regions are hapstab::paper::nyquist::robust_region over 0 ≤ γ ≤ the panel's last γ, \
         with 41 γ samples and no golden-section refinement between them (an outer approximation within about 1 % in area); claim C8 uses the refined check passive_inside_robust."
            .to_string(),
        "At δ = 0, γ = π² every (α, β) is limit stable (a root at z = −1), so Figs. 8 and 10 draw the limit γ = π²(1 − 1e-6)."
            .to_string(),
    ]
}

/// Runs `hapstab paper`.
pub fn run(a: &PaperArgs) -> Result<()> {
    let t0 = Instant::now();
    std::fs::create_dir_all(&a.out)
        .with_context(|| format!("cannot create folder {}", a.out.display()))?;
    let jobs = compute::jobs(&claims::extra_keys());
    let n_fig = 7;
    let total = jobs.len() + n_fig + 2;
    let bar = crate::progress::Bar::new(total, "steps", !a.json);
    bar.message("regions, validity points, robust regions");
    let results = compute::run(&jobs, &|| bar.inc())?;
    bar.message("claims");
    let claim_list = claims::claims(&results)?;
    bar.inc();
    bar.message("figures");
    let figs = figures::build(&results)?;
    let saved: Vec<_> = figs
        .par_iter()
        .with_max_len(1)
        .map(|f| {
            let s = f.save(&a.out);
            bar.inc();
            s
        })
        .collect::<Result<_>>()?;
    bar.message("report");
    let shown = figures::shown();
    let rows = report::alpha_rows(&results, &shown)?;
    let rep = report::Report {
        version: env!("CARGO_PKG_VERSION"),
        seconds: t0.elapsed().as_secs_f64(),
        axes: report::AXES,
        claims: claim_list,
        robust: report::robust_rows(&results)?,
        figures: figure_rows(&figs, &saved),
        notes: notes(),
        alpha_max: rows,
    };
    let mut files: Vec<String> = saved
        .iter()
        .flat_map(|s| [s.svg.display().to_string(), s.png.display().to_string()])
        .collect();
    files.extend(report::write(&a.out, &rep)?);
    bar.inc();
    bar.finish();
    let seconds = t0.elapsed().as_secs_f64();
    let summary = Summary {
        input: PaperInput {
            out: a.out.display().to_string(),
        },
        files,
        claims: rep
            .claims
            .iter()
            .map(|c| ClaimSummary {
                id: c.id,
                verdict: c.verdict.as_str(),
                measured: c.measured.clone(),
            })
            .collect(),
        seconds,
    };
    if a.json {
        return print_json(&summary);
    }
    print_text(&summary, &rep);
    Ok(())
}

/// The report's row of each figure: its name, the file names of its SVG and PNG, its caption.
fn figure_rows(figs: &[figures::PaperFigure], saved: &[Saved]) -> Vec<report::FigureRow> {
    let file_name = |p: &std::path::Path| {
        p.file_name()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    figs.iter()
        .zip(saved)
        .map(|(f, s)| report::FigureRow {
            name: f.name,
            svg: file_name(&s.svg),
            png: file_name(&s.png),
            caption: f.caption.clone(),
        })
        .collect()
}

/// The human-readable answer of `paper`: the files written and every claim's verdict.
fn print_text(summary: &Summary, rep: &report::Report) {
    println!(
        "wrote {} files to {} in {:.2} s",
        summary.files.len(),
        summary.input.out,
        summary.seconds
    );
    for c in &rep.claims {
        println!("  {:<4} {:<18} {}", c.id, c.verdict.as_str(), c.claim);
    }
}
