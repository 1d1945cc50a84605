//! `hapstab boundary`: the exact stable region of a loop in the wall plane (Section V,
//! Figs. 4–6): in (α, β) for the paper's loop, and in physical (K, B) for a physical loop.

use anyhow::{Context, Result};
use clap::Args;
use hapstab::AffineFamily;
use hapstab::answer::{PhysicalRegion, RegionAnswer, region_answer};
use hapstab::region::{EdgeKind, StableRegion};
use serde::Serialize;

use crate::model::{LoopArgs, ResolvedLoop, print_loop};
use crate::output::{csv_num, eng, print_json, sig};
use crate::wall_plot;
use hapstab_plot::{Marker, palette};

/// Arguments of `hapstab boundary`.
#[derive(Args, Debug)]
pub struct BoundaryArgs {
    #[command(flatten)]
    lp: LoopArgs,
    /// Write the polygon vertices to this CSV file: polygon, vertex, K (N/m), B (Ns/m), theta,
    /// edge (alpha and beta instead of K and B for normalized input).
    #[arg(long)]
    csv: Option<std::path::PathBuf>,
    /// Draw the stable region to FILE: SVG or PNG by its extension (both FILE.svg and
    /// FILE.png for any other name); in K (N/m) and B (Ns/m) for a physical loop, in α and β
    /// for the normalized one, K_max marked.
    #[arg(long, value_name = "FILE")]
    plot: Option<std::path::PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// The library's region answer with the files --plot wrote.
#[derive(Serialize)]
struct BoundaryOut {
    #[serde(flatten)]
    answer: RegionAnswer,
    /// Files written by --plot.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    plot: Vec<std::path::PathBuf>,
}

/// An edge's kind in words; the z = 1 line of the paper's loop in its units (α = −γ, or
/// K = −k in physical units).
fn kind_name(k: &EdgeKind, paper: bool, normalized: bool) -> String {
    match k {
        EdgeKind::ZPlusOne if paper && normalized => "z = 1 line (α = −γ)".into(),
        EdgeKind::ZPlusOne if paper => "z = 1 line (K = −k)".into(),
        EdgeKind::ZPlusOne => "z = 1 line".into(),
        EdgeKind::ZMinusOne => "z = −1 line".into(),
        EdgeKind::Complex {
            theta_start,
            theta_end,
        } => format!(
            "complex pair, θ from {} to {}",
            sig(*theta_start, 6),
            sig(*theta_end, 6)
        ),
        EdgeKind::Window => "search window".into(),
    }
}

fn edge_tag(k: &EdgeKind) -> &'static str {
    match k {
        EdgeKind::ZPlusOne => "z=1",
        EdgeKind::ZMinusOne => "z=-1",
        EdgeKind::Complex { .. } => "complex",
        EdgeKind::Window => "window",
    }
}

/// Writes the vertices; every failure (open, write, flush) names the file.
fn write_csv(path: &std::path::Path, r: &StableRegion, fam: Option<&AffineFamily>) -> Result<()> {
    write_vertices(path, r, fam).with_context(|| format!("cannot write {}", path.display()))
}

fn write_vertices(
    path: &std::path::Path,
    r: &StableRegion,
    fam: Option<&AffineFamily>,
) -> Result<()> {
    let mut w = csv::Writer::from_path(path)?;
    // A physical loop's vertices in N/m and Ns/m, the normalized loop's in α and β.
    let (x, y) = if fam.is_some() {
        ("K", "B")
    } else {
        ("alpha", "beta")
    };
    w.write_record(["polygon", "vertex", x, y, "theta", "edge"])?;
    for (pi, p) in r.polygons.iter().enumerate() {
        let mut ei = 0;
        for (vi, v) in p.vertices.iter().enumerate() {
            while ei + 1 < p.edges.len() && p.edges[ei + 1].start <= vi {
                ei += 1;
            }
            let (a, b) = match fam {
                Some(f) => f.to_physical(v.a, v.b),
                None => (v.a, v.b),
            };
            let rec = [
                pi.to_string(),
                vi.to_string(),
                csv_num(a),
                csv_num(b),
                csv_num(p.thetas[vi]),
                edge_tag(&p.edges[ei].kind).to_string(),
            ];
            w.write_record(&rec)?;
        }
    }
    w.flush()?;
    Ok(())
}

/// Runs `hapstab boundary`.
pub fn run(a: &BoundaryArgs) -> Result<()> {
    let rl = a.lp.resolve(false)?;
    let sys = rl.system()?;
    let fam = sys.family();
    let cost =
        hapstab::limits::region_cost_of_degree(fam.degree(), hapstab::limits::core_degree(fam));
    crate::budget::check_loop(&a.lp, &rl.lp, cost, "the exact region")?;
    let r = sys.region()?;
    if let Some(path) = &a.csv {
        write_csv(path, &r, (!rl.normalized).then_some(fam))?;
    }
    let mut out = BoundaryOut {
        answer: region_answer(&sys, rl.normalized, &r),
        plot: Vec::new(),
    };
    if let Some(path) = &a.plot {
        out.plot = wall_plot::save(figure(&rl, fam, &r), path)?;
    }
    if a.json {
        return print_json(&out);
    }
    print_text(&rl, fam, &r, &out);
    if let Some(path) = &a.csv {
        println!("vertices written to {}", path.display());
    }
    if !out.plot.is_empty() {
        println!("plot written to {}", wall_plot::files_text(&out.plot));
    }
    Ok(())
}

/// The stable region with K_max (α_max) marked.
fn figure(rl: &ResolvedLoop, fam: &AffineFamily, r: &StableRegion) -> hapstab_plot::Figure {
    let plane = wall_plot::plane(rl, fam);
    let mut fig =
        wall_plot::region_figure(&plane, r, "Stable region").subtitle(wall_plot::loop_line(rl));
    if !r.polygons.is_empty() {
        let at = plane.point(r.a_max, r.b_at_a_max);
        let name = if rl.normalized { "α_max" } else { "K_max" };
        wall_plot::mark(
            &mut fig,
            at,
            Marker::Circle,
            palette::VERMILLION,
            &format!("{name}: {}", plane.describe(at)),
            name,
        );
    }
    fig
}

/// The human-readable answer of `boundary`: in normalized mode the region in α and β; in
/// physical mode the loop, K_max and the area in N/m and Ns/m, and for the paper's loop its
/// normalized view on one labelled line; then every polygon's edges.
fn print_text(rl: &ResolvedLoop, fam: &AffineFamily, r: &StableRegion, out: &BoundaryOut) {
    let paper = rl.lp.paper_view().map(|pp| (pp, rl.lp.delay.samples));
    let empty = r.polygons.is_empty();
    if rl.normalized {
        if let Some((pp, d)) = paper {
            println!(
                "stable region for γ = {}, δ = {}, d = {d}",
                sig(pp.gamma, 6),
                sig(pp.delta, 6),
            );
        }
        if !empty {
            println!(
                "α_max = {} at β = {}",
                sig(r.a_max, 6),
                sig(r.b_at_a_max, 6)
            );
            println!("area  = {} (in α·β)", sig(r.area, 6));
        }
    } else {
        println!("stable region of the loop");
        print_loop(&rl.lp);
    }
    if empty {
        println!("empty: no wall (K, B) makes this loop stable");
        return;
    }
    if let Some(p) = &out.answer.physical {
        print_k_max(p);
    }
    // polygons are numbered from 0, as in the CSV's polygon column and the JSON arrays
    for (i, p) in r.polygons.iter().enumerate() {
        println!("polygon {i} ({} vertices):", p.vertices.len());
        for e in &p.edges {
            let v = p.vertices[e.start];
            let at = if rl.normalized {
                format!("(α, β) = ({}, {})", sig(v.a, 6), sig(v.b, 6))
            } else {
                let (k, b) = fam.to_physical(v.a, v.b);
                format!("(K, B) = ({}, {})", eng(k, "N/m", 6), eng(b, "Ns/m", 6))
            };
            println!(
                "  from {at}: {}",
                kind_name(&e.kind, paper.is_some(), rl.normalized)
            );
        }
    }
}

/// K_max with the damping that reaches it (or, for a supremum at a corner of the region, a
/// stable wall beside it) and the region's area, in physical units.
fn print_k_max(p: &PhysicalRegion) {
    if p.k_max_attained {
        println!(
            "K_max = {} at B = {}",
            eng(p.k_max, "N/m", 6),
            eng(p.b_at_k_max, "Ns/m", 6)
        );
    } else {
        println!(
            "K_max = {}, approached as B → {} (a supremum: a corner of the region; K = {} \
             is stable at B = {})",
            eng(p.k_max, "N/m", 6),
            eng(p.b_at_k_max, "Ns/m", 6),
            eng(p.k_stable_near_k_max, "N/m", 10),
            eng(p.b_stable_near_k_max, "Ns/m", 10)
        );
    }
    println!("area  = {} N²·s/m²", sig(p.area, 6));
}
