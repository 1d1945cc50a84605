//! The written report of `hapstab paper`: claims.json (machine-readable), report.md and a
//! self-contained report.html (figures embedded as base64 PNG, no network).

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use serde::Serialize;

use super::claims::Claim;
use super::compute::{Key, Results, RobustKey, Source};
use crate::output::sig;

/// One row of the α_max table.
#[derive(Debug, Clone, Serialize)]
pub struct AlphaRow {
    /// Figures that show the region.
    pub figures: String,
    /// γ.
    pub gamma: f64,
    /// δ.
    pub delta: f64,
    /// d.
    pub d: usize,
    /// α_max.
    pub alpha_max: f64,
    /// β at α_max.
    pub beta_at_alpha_max: f64,
    /// Area.
    pub area: f64,
    /// Outline vertices.
    pub vertices: usize,
    /// Where the outline comes from.
    pub source: Source,
}

/// One row of the robust-region table.
#[derive(Debug, Clone, Serialize)]
pub struct RobustRow {
    /// Figure.
    pub figure: &'static str,
    /// δ.
    pub delta: f64,
    /// d.
    pub d: usize,
    /// Upper end of the γ interval (lower end 0).
    pub gamma_hi: f64,
    /// No robustly stable interior point.
    pub empty: bool,
    /// Largest robust α.
    pub alpha_max: f64,
    /// β there.
    pub beta_at_alpha_max: f64,
    /// Area.
    pub area: f64,
}

/// A figure written.
#[derive(Debug, Clone, Serialize)]
pub struct FigureRow {
    /// File stem.
    pub name: &'static str,
    /// SVG file name.
    pub svg: String,
    /// PNG file name.
    pub png: String,
    /// Caption.
    pub caption: String,
}

/// Everything in the report.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// hapstab version.
    pub version: &'static str,
    /// Seconds spent computing and drawing (before writing the report).
    pub seconds: f64,
    /// Axis convention of the figures.
    pub axes: &'static str,
    /// Claims C1–C11.
    pub claims: Vec<Claim>,
    /// α_max for every (γ, δ, d) in the figures.
    pub alpha_max: Vec<AlphaRow>,
    /// Robust regions of Figs. 8–10.
    pub robust: Vec<RobustRow>,
    /// The figures.
    pub figures: Vec<FigureRow>,
    /// Notes on methods and on the library.
    pub notes: Vec<String>,
}

/// The axis convention.
pub const AXES: &str = "α (normalized virtual stiffness KT²/m) on the horizontal axis, β (normalized \
     virtual damping BT/m) on the vertical axis: the paper speaks of the \"left vertical \
     boundary α = −γ\", the \"bottom boundary\" and the \"left-half plane (α ≤ 0)\".";

/// Rows of the α_max table.
pub fn alpha_rows(r: &Results, shown: &[(Key, Vec<&'static str>)]) -> Result<Vec<AlphaRow>> {
    shown
        .iter()
        .map(|(k, figs)| {
            let reg = r.region(*k)?;
            Ok(AlphaRow {
                figures: figs.join(", "),
                gamma: k.gamma,
                delta: k.delta,
                d: k.d,
                alpha_max: reg.alpha_max,
                beta_at_alpha_max: reg.beta_at_alpha_max,
                area: reg.area,
                vertices: reg.vertices,
                source: reg.source,
            })
        })
        .collect()
}

/// Rows of the robust table.
pub fn robust_rows(r: &Results) -> Result<Vec<RobustRow>> {
    let mut out = Vec::new();
    for (delta, d, figure) in [(0.0, 0, "8"), (1.0, 0, "9"), (0.0, 1, "10"), (1.0, 1, "10")] {
        for full in [false, true] {
            let k = RobustKey { delta, d, full };
            let rr = r.robust(k)?;
            out.push(RobustRow {
                figure,
                delta,
                d,
                gamma_hi: k.gamma_hi(),
                empty: rr.empty,
                alpha_max: rr.alpha_max,
                beta_at_alpha_max: rr.beta_at_alpha_max,
                area: rr.area,
            });
        }
    }
    Ok(out)
}

fn md_cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

fn html(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn g(x: f64) -> String {
    if x.is_nan() { "—".into() } else { sig(x, 6) }
}

/// The cells of one robust-region row, shared by the Markdown and HTML tables.
/// The cells of an α_max row: the figures (through `text`, the format's escaping), γ, δ, d,
/// α_max, β there, the area, and the outline's source with its vertex count.
fn alpha_cells(r: &AlphaRow, text: &dyn Fn(&str) -> String) -> [String; 8] {
    [
        text(&r.figures),
        g(r.gamma),
        g(r.delta),
        r.d.to_string(),
        g(r.alpha_max),
        g(r.beta_at_alpha_max),
        g(r.area),
        format!("{} ({} vertices)", source_text(r.source), r.vertices),
    ]
}

fn robust_cells(r: &RobustRow) -> [String; 7] {
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

fn source_text(s: Source) -> &'static str {
    match s {
        Source::Exact => "exact polygon",
        Source::Slices => "β-slices (see notes)",
    }
}

/// Standard base64 (RFC 4648) with padding.
pub fn base64(data: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(data.len().div_ceil(3) * 4);
    for c in data.chunks(3) {
        let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        out.push(T[(n >> 18) as usize & 63] as char);
        out.push(T[(n >> 12) as usize & 63] as char);
        out.push(if c.len() > 1 {
            T[(n >> 6) as usize & 63] as char
        } else {
            '='
        });
        out.push(if c.len() > 2 {
            T[n as usize & 63] as char
        } else {
            '='
        });
    }
    out
}

/// Writes claims.json, report.md and report.html into `dir`; returns their paths.
pub fn write(dir: &Path, rep: &Report) -> Result<Vec<String>> {
    let json = dir.join("claims.json");
    std::fs::write(&json, serde_json::to_string_pretty(rep)?)
        .with_context(|| format!("cannot write {}", json.display()))?;
    let md = dir.join("report.md");
    std::fs::write(&md, markdown(rep)).with_context(|| format!("cannot write {}", md.display()))?;
    let ht = dir.join("report.html");
    std::fs::write(&ht, html_report(dir, rep)?)
        .with_context(|| format!("cannot write {}", ht.display()))?;
    Ok([json, md, ht]
        .iter()
        .map(|p| p.display().to_string())
        .collect())
}

fn markdown(rep: &Report) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# Hulin, Preusche & Hirzinger (2008), \"Stability Boundary for Haptic Rendering: Influence of Human Operator\" — reproduced\n"
    );
    let _ = writeln!(
        s,
        "Generated by `hapstab paper` (hapstab {}) in {:.2} s. Every number comes from the hapstab library; \
         the figures draw the exact region polygons.\n\nAxes: {}\n",
        rep.version, rep.seconds, rep.axes
    );
    let _ = writeln!(s, "## Claims\n");
    let _ = writeln!(
        s,
        "| id | claim | tested by | measured | verdict |\n|---|---|---|---|---|"
    );
    for c in &rep.claims {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | **{}** |",
            c.id,
            md_cell(c.claim),
            md_cell(c.figure),
            md_cell(&c.measured),
            c.verdict.as_str()
        );
    }
    let _ = writeln!(s, "\n### Criteria\n");
    for c in &rep.claims {
        let _ = writeln!(s, "- **{}** ({}): {}", c.id, c.verdict.as_str(), c.note);
    }
    let _ = writeln!(s, "\n## Figures\n");
    for f in &rep.figures {
        let _ = writeln!(
            s,
            "![{}]({})\n\n{} ([SVG]({}))\n",
            f.name, f.png, f.caption, f.svg
        );
    }
    let _ = writeln!(s, "## α_max of every region shown\n");
    let _ = writeln!(
        s,
        "| figures | γ | δ | d | α_max | β at α_max | area | outline |\n|---|---|---|---|---|---|---|---|"
    );
    for r in &rep.alpha_max {
        let _ = writeln!(s, "| {} |", alpha_cells(r, &|t| t.to_string()).join(" | "));
    }
    let _ = writeln!(s, "\n## Robustly stable regions (Figs. 8–10)\n");
    let _ = writeln!(
        s,
        "| figure | δ | d | γ range | robust α_max | β at α_max | area |\n|---|---|---|---|---|---|---|"
    );
    for r in &rep.robust {
        let _ = writeln!(s, "| {} |", robust_cells(r).join(" | "));
    }
    let _ = writeln!(s, "\n## Notes\n");
    for n in &rep.notes {
        let _ = writeln!(s, "- {n}");
    }
    s
}

fn html_report(dir: &Path, rep: &Report) -> Result<String> {
    let mut s = String::new();
    s.push_str(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>hapstab paper: Hulin et al. 2008 reproduced</title>\n<style>\
         body{font-family:system-ui,-apple-system,'DejaVu Sans',sans-serif;max-width:1200px;margin:2em auto;padding:0 1em;line-height:1.4;color:#222}\
         table{border-collapse:collapse;margin:1em 0;font-size:0.92em}th,td{border:1px solid #bbb;padding:4px 8px;vertical-align:top;text-align:left}\
         th{background:#eee}td.num{text-align:right;font-variant-numeric:tabular-nums}\
         .reproduced{background:#e3f4e3}.partly{background:#fff3d6}.differs{background:#fbe0e0}\
         figure{margin:2em 0}figure img{max-width:100%;height:auto;border:1px solid #ddd}figcaption{font-size:0.95em;color:#444}\
         </style></head><body>\n",
    );
    let _ = writeln!(
        s,
        "<h1>Hulin, Preusche &amp; Hirzinger (2008), “Stability Boundary for Haptic Rendering: Influence of Human Operator” — reproduced</h1>\
         <p>Generated by <code>hapstab paper</code> (hapstab {}) in {:.2} s. Every number comes from the hapstab library; the figures draw the exact region polygons.</p>\
         <p>Axes: {}</p>",
        html(rep.version),
        rep.seconds,
        html(rep.axes)
    );
    html_claims(&mut s, rep);
    html_figures(&mut s, dir, rep)?;
    s.push_str("<h2>α<sub>max</sub> of every region shown</h2>\n<table><tr><th>figures</th><th>γ</th><th>δ</th><th>d</th><th>α<sub>max</sub></th><th>β at α<sub>max</sub></th><th>area</th><th>outline</th></tr>\n");
    for r in &rep.alpha_max {
        let [figures, nums @ .., outline] = alpha_cells(r, &html);
        let _ = writeln!(
            s,
            "<tr><td>{figures}</td><td class=\"num\">{}</td><td>{outline}</td></tr>",
            nums.join("</td><td class=\"num\">")
        );
    }
    s.push_str("</table>\n<h2>Robustly stable regions (Figs. 8–10)</h2>\n<table><tr><th>figure</th><th>δ</th><th>d</th><th>γ range</th><th>robust α<sub>max</sub></th><th>β at α<sub>max</sub></th><th>area</th></tr>\n");
    for r in &rep.robust {
        let _ = writeln!(
            s,
            "<tr><td>{}</td></tr>",
            robust_cells(r).join("</td><td class=\"num\">")
        );
    }
    s.push_str("</table>\n<h2>Notes</h2>\n<ul>\n");
    for n in &rep.notes {
        let _ = writeln!(s, "<li>{}</li>", html(n));
    }
    s.push_str("</ul>\n</body></html>\n");
    Ok(s)
}

/// The report's claims as an HTML table, each verdict coloured.
fn html_claims(s: &mut String, rep: &Report) {
    s.push_str("<h2>Claims</h2>\n<table><tr><th>id</th><th>claim</th><th>tested by</th><th>measured</th><th>verdict</th></tr>\n");
    for c in &rep.claims {
        let class = match c.verdict {
            super::claims::Verdict::Reproduced => "reproduced",
            super::claims::Verdict::Partly => "partly",
            super::claims::Verdict::Differs => "differs",
        };
        let _ = writeln!(
            s,
            "<tr id=\"{}\"><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"{class}\"><b>{}</b><br><small>{}</small></td></tr>",
            c.id,
            c.id,
            html(c.claim),
            html(c.figure),
            html(&c.measured),
            c.verdict.as_str(),
            html(&c.note)
        );
    }
    s.push_str("</table>\n");
}

/// The report's figures as HTML, each PNG embedded as a data URL with its caption.
fn html_figures(s: &mut String, dir: &Path, rep: &Report) -> Result<()> {
    s.push_str("<h2>Figures</h2>\n");
    for f in &rep.figures {
        let png = dir.join(&f.png);
        let bytes =
            std::fs::read(&png).with_context(|| format!("cannot read {}", png.display()))?;
        let _ = writeln!(
            s,
            "<figure id=\"{}\"><img alt=\"{}\" src=\"data:image/png;base64,{}\"><figcaption>{}</figcaption></figure>",
            f.name,
            html(f.name),
            base64(&bytes),
            html(&f.caption)
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::base64;

    #[test]
    fn base64_rfc4648_vectors() {
        for (i, o) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(i.as_bytes()), o);
        }
    }
}
