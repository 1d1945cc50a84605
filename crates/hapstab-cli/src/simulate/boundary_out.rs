//! The answer of `hapstab simboundary`: its rows, inputs and JSON, and the `--csv` file.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use hapstab::simulation::{Effects, EmpiricalPoint, InconclusiveRun, Initial, Outcome, StableWhen};
use hapstab::zoh::WallScale;
use hapstab_plot::Saved;
use serde::Serialize;

use super::num;
use crate::model::LoopInput;

/// One damping of the boundary: the library's point in wall units and, for a physical loop,
/// the N/m and Ns/m per wall unit. Its JSON speaks the user's units: K and B for a physical
/// loop ([`PhysicalRow`]), α and β for normalized input.
pub(super) struct BoundaryRow {
    pub(super) point: EmpiricalPoint,
    /// α_simulated / α_linear (= K_simulated / K_linear).
    pub(super) ratio: Option<f64>,
    /// Physical mode: (N/m, Ns/m) per unit of a and b.
    scale: Option<(f64, f64)>,
}

/// A row in physical units: the keys of a physical loop's JSON.
#[derive(Serialize)]
pub(super) struct PhysicalRow {
    /// Virtual damping B, Ns/m.
    pub(super) wall_damping: f64,
    /// The exact linear boundary K at this B (Section V), N/m.
    pub(super) k_linear: Option<f64>,
    /// The simulated boundary: the largest K found stable below every K that was not, N/m.
    pub(super) k_simulated: Option<f64>,
    /// Smallest K found unstable, N/m.
    pub(super) k_unstable: Option<f64>,
    /// K_simulated / K_linear.
    pub(super) ratio: Option<f64>,
    /// Smallest K whose run was inconclusive (separated or undecided).
    pub(super) inconclusive: Option<PhysicalInconclusive>,
    /// True if every K up to the scan end was stable.
    pub(super) censored: bool,
    /// Upper end of the K scan, N/m.
    pub(super) k_max: f64,
    /// Number of simulated runs.
    pub(super) runs: usize,
}

/// An inconclusive run at a wall stiffness in N/m.
#[derive(Serialize)]
pub(super) struct PhysicalInconclusive {
    pub(super) wall_stiffness: f64,
    pub(super) outcome: Outcome,
}

/// A row of normalized input: the library's point in α and β.
#[derive(Serialize)]
struct NormalizedRow<'a> {
    #[serde(flatten)]
    point: &'a EmpiricalPoint,
    ratio: Option<f64>,
}

impl BoundaryRow {
    /// The row in N/m and Ns/m; None for normalized input.
    pub(super) fn physical(&self) -> Option<PhysicalRow> {
        let (k, b) = self.scale?;
        let p = &self.point;
        Some(PhysicalRow {
            wall_damping: p.b * b,
            k_linear: p.a_linear.map(|x| x * k),
            k_simulated: p.a_simulated.map(|x| x * k),
            k_unstable: p.a_unstable.map(|x| x * k),
            ratio: self.ratio,
            inconclusive: p.inconclusive.map(|i| PhysicalInconclusive {
                wall_stiffness: i.a * k,
                outcome: i.outcome,
            }),
            censored: p.censored,
            k_max: p.a_max * k,
            runs: p.runs,
        })
    }
}

impl Serialize for BoundaryRow {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self.physical() {
            Some(row) => row.serialize(s),
            None => NormalizedRow {
                point: &self.point,
                ratio: self.ratio,
            }
            .serialize(s),
        }
    }
}

/// The exact linear K_max of the loop: in N/m and Ns/m for a physical loop, in α and β for
/// normalized input.
#[derive(Serialize)]
#[serde(untagged)]
pub(super) enum ExactOut {
    Physical {
        exact_k_max: f64,
        exact_b_at_k_max: f64,
    },
    Normalized {
        exact_alpha_max: f64,
        exact_beta_at_alpha_max: f64,
    },
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
    /// The exact linear stable region's (Section V) α_max and the β where it is reached, in
    /// wall units (the text's numbers).
    #[serde(skip)]
    pub(super) exact: (f64, f64),
    /// The same in the user's units.
    #[serde(flatten)]
    pub(super) exact_out: ExactOut,
    pub(super) points: Vec<BoundaryRow>,
    /// Why some of the answer is no evidence of stability (e.g. runs that left the wall).
    pub(super) warnings: Vec<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) csv: Option<PathBuf>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) plot: Option<Saved>,
}

impl ExactOut {
    /// K_max in the user's units from (α_max, β at α_max) in wall units and, for a physical
    /// loop, the N/m and Ns/m per wall unit.
    pub(super) fn new(a: f64, b: f64, per_unit: Option<(f64, f64)>) -> Self {
        match per_unit {
            Some((k, kb)) => Self::Physical {
                exact_k_max: a * k,
                exact_b_at_k_max: b * kb,
            },
            None => Self::Normalized {
                exact_alpha_max: a,
                exact_beta_at_alpha_max: b,
            },
        }
    }
}

/// A row with its physical scale: K = a·k, B = b·kb (None in normalized mode).
pub(super) fn boundary_row(p: &EmpiricalPoint, scale: Option<(f64, f64)>) -> BoundaryRow {
    let ratio = match (p.a_simulated, p.a_linear) {
        (Some(s), Some(l)) if l.is_finite() && l > 0.0 => Some(s / l),
        _ => None,
    };
    BoundaryRow {
        point: *p,
        ratio,
        scale,
    }
}

pub(super) fn opt(v: Option<f64>) -> String {
    v.map_or_else(String::new, num)
}

/// Writes the rows as CSV: wall_damping (Ns/m), k_linear, k_simulated, k_unstable (N/m), …
/// for a physical loop, beta, alpha_linear, … for normalized input.
pub(super) fn write_boundary_csv(path: &Path, rows: &[BoundaryRow]) -> Result<()> {
    let mut w = csv::Writer::from_path(path)
        .with_context(|| format!("cannot write CSV {}", path.display()))?;
    let physical = rows.first().is_some_and(|r| r.scale.is_some());
    w.write_record(if physical {
        [
            "wall_damping",
            "k_linear",
            "k_simulated",
            "k_unstable",
            "ratio",
            "censored",
            "k_max",
            "runs",
            "inconclusive_k",
            "inconclusive_outcome",
        ]
    } else {
        [
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
        ]
    })?;
    for r in rows {
        let p = match r.physical() {
            Some(q) => EmpiricalPoint {
                b: q.wall_damping,
                a_linear: q.k_linear,
                a_simulated: q.k_simulated,
                a_unstable: q.k_unstable,
                inconclusive: q.inconclusive.map(|i| InconclusiveRun {
                    a: i.wall_stiffness,
                    outcome: i.outcome,
                }),
                censored: q.censored,
                a_max: q.k_max,
                runs: q.runs,
            },
            None => r.point,
        };
        w.write_record([
            num(p.b),
            opt(p.a_linear),
            opt(p.a_simulated),
            opt(p.a_unstable),
            opt(r.ratio),
            p.censored.to_string(),
            num(p.a_max),
            p.runs.to_string(),
            opt(p.inconclusive.map(|i| i.a)),
            p.inconclusive
                .map_or("", |i| i.outcome.as_str())
                .to_string(),
        ])?;
    }
    w.flush()
        .with_context(|| format!("cannot write CSV {}", path.display()))?;
    Ok(())
}
