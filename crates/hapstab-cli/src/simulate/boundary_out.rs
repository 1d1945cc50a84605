//! The answer of `hapstab simboundary`: its rows, inputs and JSON, and the `--csv` file.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use hapstab::simulation::{Effects, EmpiricalPoint, Initial, StableWhen};
use hapstab::zoh::WallScale;
use hapstab_plot::Saved;
use serde::Serialize;

use super::num;
use crate::model::LoopInput;

#[derive(Serialize)]
pub(super) struct BoundaryRow {
    #[serde(flatten)]
    pub(super) point: EmpiricalPoint,
    /// α_simulated / α_linear.
    pub(super) ratio: Option<f64>,
    /// Physical mode: B, K_linear and K_simulated in Ns/m and N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) wall_damping: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) k_linear: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) k_simulated: Option<f64>,
}

/// γ, δ and d of the paper's loop (Table I).
#[derive(Serialize)]
pub(super) struct PaperPlant {
    pub(super) gamma: f64,
    pub(super) delta: f64,
    pub(super) d: usize,
}

/// The inputs of `simboundary`: the loop, the runs' setting and the scan.
#[derive(Serialize)]
pub(super) struct SimboundaryInput {
    #[serde(flatten)]
    pub(super) lp: LoopInput,
    pub(super) effects: Effects,
    pub(super) human_force: f64,
    pub(super) initial: Initial,
    pub(super) samples: usize,
    pub(super) max_samples: usize,
    pub(super) stable_when: StableWhen,
    pub(super) grid: usize,
    pub(super) rel_tol: f64,
}

#[derive(Serialize)]
pub(super) struct SimboundaryOut {
    /// The paper's loop given in physical units: γ, δ, d (Table I).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) normalized: Option<PaperPlant>,
    pub(super) units: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) mass: Option<f64>,
    pub(super) period: f64,
    /// The loop and the runs' setting as given.
    pub(super) input: SimboundaryInput,
    /// Other loops: K = a·stiffness (N/m) and B = b·damping (Ns/m) for the a, b columns.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) wall_units: Option<WallScale>,
    /// α_max of the exact linear stable region (Section V) and the β where it is reached.
    pub(super) exact_alpha_max: f64,
    pub(super) exact_beta_at_alpha_max: f64,
    pub(super) points: Vec<BoundaryRow>,
    /// Why some of the answer is no evidence of stability (e.g. runs that left the wall).
    pub(super) warnings: Vec<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) csv: Option<PathBuf>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) plot: Option<Saved>,
}

/// A row with its physical columns: K = a·k, B = b·kb (None in normalized mode).
pub(super) fn boundary_row(p: &EmpiricalPoint, scale: Option<(f64, f64)>) -> BoundaryRow {
    let ratio = match (p.alpha_simulated, p.alpha_linear) {
        (Some(s), Some(l)) if l.is_finite() && l > 0.0 => Some(s / l),
        _ => None,
    };
    BoundaryRow {
        point: *p,
        ratio,
        wall_damping: scale.map(|(_, kb)| p.beta * kb),
        k_linear: scale.and_then(|(k, _)| p.alpha_linear.map(|x| x * k)),
        k_simulated: scale.and_then(|(k, _)| p.alpha_simulated.map(|x| x * k)),
    }
}

pub(super) fn opt(v: Option<f64>) -> String {
    v.map_or_else(String::new, num)
}

pub(super) fn write_boundary_csv(path: &Path, rows: &[BoundaryRow]) -> Result<()> {
    let mut w = csv::Writer::from_path(path)
        .with_context(|| format!("cannot write CSV {}", path.display()))?;
    w.write_record([
        "beta",
        "alpha_linear",
        "alpha_simulated",
        "alpha_unstable",
        "ratio",
        "censored",
        "alpha_max",
        "runs",
        "inconclusive_alpha",
        "inconclusive_outcome",
    ])?;
    for r in rows {
        let p = &r.point;
        w.write_record([
            num(p.beta),
            opt(p.alpha_linear),
            opt(p.alpha_simulated),
            opt(p.alpha_unstable),
            opt(r.ratio),
            p.censored.to_string(),
            num(p.alpha_max),
            p.runs.to_string(),
            opt(p.inconclusive.map(|i| i.alpha)),
            p.inconclusive
                .map_or("", |i| i.outcome.as_str())
                .to_string(),
        ])?;
    }
    w.flush()
        .with_context(|| format!("cannot write CSV {}", path.display()))?;
    Ok(())
}
