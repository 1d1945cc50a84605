//! The paper's claims C1–C11, each measured through the library and judged.
//!
//! Parts: [`plant_effects`] C1–C4 (Section V: the physical plant's effect on the region,
//! Figs. 4–6), [`linear_condition`] C5–C6 (Sections VI–VII, Fig. 7), [`nyquist`] C7–C9
//! (Section VIII, Figs. 8–10), [`remarks`] C10–C11 (Remarks 4 and 2).

mod linear_condition;
mod nyquist;
mod plant_effects;
mod remarks;

use std::collections::BTreeMap;

use anyhow::Result;
use hapstab::params::{Arm, Device};
use serde::Serialize;

use super::compute::{Key, Results};
use crate::output::sig;
use linear_condition::{c5, c6};
use nyquist::{c7, c8, c9};
use plant_effects::{c1, c2, c3, c4};
use remarks::{c10, c11};

/// Verdict on a claim.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Verdict {
    /// hapstab measures what the paper says.
    #[serde(rename = "reproduced")]
    Reproduced,
    /// Part of the claim holds; the note says which part does not.
    #[serde(rename = "partly reproduced")]
    Partly,
    /// hapstab measures something else.
    #[serde(rename = "differs")]
    Differs,
}

impl Verdict {
    /// The word used in the reports.
    pub fn as_str(&self) -> &'static str {
        match self {
            Verdict::Reproduced => "reproduced",
            Verdict::Partly => "partly reproduced",
            Verdict::Differs => "differs",
        }
    }

    fn from(ok: bool) -> Self {
        if ok {
            Verdict::Reproduced
        } else {
            Verdict::Differs
        }
    }
}

/// One claim of the paper with what hapstab measured.
#[derive(Debug, Clone, Serialize)]
pub struct Claim {
    /// C1 … C11.
    pub id: &'static str,
    /// The claim, as the paper states it.
    pub claim: &'static str,
    /// The figure or number that tests it.
    pub figure: &'static str,
    /// What hapstab measured (text).
    pub measured: String,
    /// The measured numbers.
    pub values: BTreeMap<&'static str, f64>,
    /// Verdict.
    pub verdict: Verdict,
    /// How the verdict was reached (criterion), and any difference.
    pub note: String,
}

/// Sampling period of the physical examples (C4, C10): 1 ms.
pub const PERIOD: f64 = 1e-3;

/// Window of the close-up Fig. 5: α range.
pub const FIG5_ALPHA: (f64, f64) = (-0.0015, 0.006);
/// Window of the close-up Fig. 5: β range.
pub const FIG5_BETA: (f64, f64) = (-0.02, 0.018);

/// A shift counts as visible from this fraction of an axis range on (0.5 %, about 4 px of an
/// 800 px panel): claims C2 and C3.
pub const VISIBLE: f64 = 0.005;

/// The C4 plants: the PHANToM-like device alone, with each element of the typical arm added
/// on its own, and with the whole arm: (name, m, b, k) in SI units.
pub fn c4_plants() -> [(&'static str, f64, f64, f64); 5] {
    let (dv, arm) = (Device::PHANTOM_LIKE, Arm::TYPICAL);
    [
        ("device alone", dv.mass, dv.damping, 0.0),
        ("+ arm mass", dv.mass + arm.mass, dv.damping, 0.0),
        ("+ arm damping", dv.mass, dv.damping + arm.damping, 0.0),
        ("+ arm stiffness", dv.mass, dv.damping, arm.stiffness),
        (
            "+ whole arm",
            dv.mass + arm.mass,
            dv.damping + arm.damping,
            arm.stiffness,
        ),
    ]
}

fn c4_key(m: f64, b: f64, k: f64) -> Key {
    Key::new(k * PERIOD * PERIOD / m, b * PERIOD / m, 0)
}

/// Region keys the claims need beyond the figures.
pub fn extra_keys() -> Vec<Key> {
    c4_plants()
        .iter()
        .map(|&(_, m, b, k)| c4_key(m, b, k))
        .collect()
}

fn pct(x: f64) -> String {
    format!("{} %", sig(100.0 * x, 3))
}

/// Measures every claim.
pub fn claims(r: &Results) -> Result<Vec<Claim>> {
    Ok(vec![
        c1(r)?,
        c2(r)?,
        c3(r)?,
        c4(r)?,
        c5()?,
        c6(r)?,
        c7(r)?,
        c8(r)?,
        c9(r)?,
        c10()?,
        c11()?,
    ])
}
