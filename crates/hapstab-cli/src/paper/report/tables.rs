//! The cells of the report's α_max and robust-region tables, shared by the Markdown and
//! HTML reports.

use super::{AlphaRow, RobustRow};
use crate::output::sig;

pub(super) fn g(x: f64) -> String {
    if x.is_nan() { "—".into() } else { sig(x, 6) }
}

/// The cells of an α_max row: the figures (through `text`, the format's escaping), γ, δ, d,
/// α_max, β there, the area, and the outline's source with its vertex count.
pub(super) fn alpha_cells(r: &AlphaRow, text: &dyn Fn(&str) -> String) -> [String; 8] {
    [
        text(&r.figures),
        g(r.gamma),
        g(r.delta),
        r.d.to_string(),
        g(r.alpha_max),
        g(r.beta_at_alpha_max),
        g(r.area),
        format!("exact polygon ({} vertices)", r.vertices),
    ]
}

/// The cells of one robust-region row, shared by the Markdown and HTML tables.
pub(super) fn robust_cells(r: &RobustRow) -> [String; 7] {
    [
        r.figure.to_string(),
        g(r.delta),
        r.d.to_string(),
        format!("[0, {}]", g(r.gamma_hi)),
        if r.empty {
            "origin only".to_string()
        } else {
            g(r.alpha_max)
        },
        g(r.beta_at_alpha_max),
        g(r.area),
    ]
}
