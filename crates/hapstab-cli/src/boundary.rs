//! `hapstab boundary`: the exact stable region for fixed (γ, δ, d) (Section V, Figs. 4–6).

use anyhow::{Context, Result};
use clap::Args;
use hapstab::PolyFamily;
use hapstab::region::{EdgeKind, StableRegion, stable_region};
use serde::Serialize;

use crate::model::{PlantArgs, PlantModel};
use crate::output::{print_json, sig};

/// Arguments of `hapstab boundary`.
#[derive(Args, Debug)]
pub struct BoundaryArgs {
    #[command(flatten)]
    plant: PlantArgs,
    /// Write the polygon vertices to this CSV file (polygon, vertex, alpha, beta, theta, edge).
    #[arg(long)]
    csv: Option<std::path::PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct EdgeOut {
    start: usize,
    #[serde(flatten)]
    kind: EdgeKind,
}

#[derive(Serialize)]
struct PhysicalRegion {
    /// K_max in N/m.
    k_max: f64,
    /// B at K_max in Ns/m.
    b_at_k_max: f64,
    /// N/m per unit α (m/T²).
    k_per_alpha: f64,
    /// Ns/m per unit β (m/T).
    b_per_beta: f64,
}

#[derive(Serialize)]
struct BoundaryOut {
    gamma: f64,
    delta: f64,
    d: usize,
    alpha_max: f64,
    beta_at_alpha_max: f64,
    area: f64,
    /// Closed polygons, each an array of [alpha, beta] (counter-clockwise, first vertex not
    /// repeated).
    polygons: Vec<Vec<[f64; 2]>>,
    /// Edge labels per polygon.
    edges: Vec<Vec<EdgeOut>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    physical: Option<PhysicalRegion>,
}

/// Computes the region for a resolved plant.
pub fn region_of(pm: &PlantModel) -> Result<StableRegion> {
    let fam = PolyFamily::new(hapstab::PlantParams::new(pm.gamma, pm.delta)?, pm.d)?;
    Ok(stable_region(&fam)?)
}

fn kind_name(k: &EdgeKind) -> String {
    match k {
        EdgeKind::ZPlusOne => "z = 1 line (α = −γ)".into(),
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

fn write_csv(path: &std::path::Path, r: &StableRegion) -> Result<()> {
    let mut w =
        csv::Writer::from_path(path).with_context(|| format!("cannot write {}", path.display()))?;
    w.write_record(["polygon", "vertex", "alpha", "beta", "theta", "edge"])?;
    for (pi, p) in r.polygons.iter().enumerate() {
        let mut ei = 0;
        for (vi, v) in p.vertices.iter().enumerate() {
            while ei + 1 < p.edges.len() && p.edges[ei + 1].start <= vi {
                ei += 1;
            }
            let kind = match p.edges[ei].kind {
                EdgeKind::ZPlusOne => "z=1",
                EdgeKind::ZMinusOne => "z=-1",
                EdgeKind::Complex { .. } => "complex",
                EdgeKind::Window => "window",
            };
            w.write_record([
                pi.to_string(),
                vi.to_string(),
                format!("{:e}", v.alpha),
                format!("{:e}", v.beta),
                format!("{:e}", p.thetas[vi]),
                kind.to_string(),
            ])?;
        }
    }
    w.flush()?;
    Ok(())
}

/// Runs `hapstab boundary`.
pub fn run(a: &BoundaryArgs) -> Result<()> {
    let pm = a.plant.resolve()?;
    let r = region_of(&pm)?;
    if let Some(path) = &a.csv {
        write_csv(path, &r)?;
    }
    let physical = pm.physical.map(|(eff, s)| {
        let kpa = eff.mass / (s.period * s.period);
        let bpb = eff.mass / s.period;
        PhysicalRegion {
            k_max: r.alpha_max * kpa,
            b_at_k_max: r.beta_at_alpha_max * bpb,
            k_per_alpha: kpa,
            b_per_beta: bpb,
        }
    });
    let out = BoundaryOut {
        gamma: pm.gamma,
        delta: pm.delta,
        d: pm.d,
        alpha_max: r.alpha_max,
        beta_at_alpha_max: r.beta_at_alpha_max,
        area: r.area,
        polygons: r
            .polygons
            .iter()
            .map(|p| p.vertices.iter().map(|v| [v.alpha, v.beta]).collect())
            .collect(),
        edges: r
            .polygons
            .iter()
            .map(|p| {
                p.edges
                    .iter()
                    .map(|e| EdgeOut {
                        start: e.start,
                        kind: e.kind,
                    })
                    .collect()
            })
            .collect(),
        physical,
    };
    if a.json {
        return print_json(&out);
    }
    println!(
        "stable region for γ = {}, δ = {}, d = {}",
        sig(pm.gamma, 10),
        sig(pm.delta, 10),
        pm.d
    );
    if r.polygons.is_empty() {
        println!("empty: no (α, β) makes this loop stable");
        return Ok(());
    }
    println!(
        "α_max = {:.15e} at β = {:.15e}",
        r.alpha_max, r.beta_at_alpha_max
    );
    println!("area  = {:.12e}", r.area);
    if let Some(p) = &out.physical {
        println!(
            "K_max = {} N/m at B = {} Ns/m",
            sig(p.k_max, 12),
            sig(p.b_at_k_max, 12)
        );
    }
    for (i, p) in r.polygons.iter().enumerate() {
        println!("polygon {} ({} vertices):", i + 1, p.vertices.len());
        for e in &p.edges {
            let v = p.vertices[e.start];
            println!(
                "  from (α, β) = ({}, {}): {}",
                sig(v.alpha, 10),
                sig(v.beta, 10),
                kind_name(&e.kind)
            );
        }
    }
    if let Some(path) = &a.csv {
        println!("vertices written to {}", path.display());
    }
    Ok(())
}
