//! The figures of hapstab: a [`Figure`] (one panel) or a [`Grid`] of panels, written as
//! `<stem>.svg` and `<stem>.png` with plotters, the figures every front end shares (the wall
//! plane and the roots of p(z) in [`wall`], Bode and Nyquist plots in [`freq`], P(stable) in
//! [`population`]), the thinning of dense data in [`simplify`] and the numbers written on
//! them in [`text`].
//!
//! Pure Rust: plotters runs without its system-font (`ttf`/font-kit/fontconfig) feature; its
//! `ab_glyph` feature rasterizes text with DejaVu Sans, embedded at compile time by the
//! `dejavu` crate (Bitstream Vera / public-domain licence) and registered once as
//! `sans-serif`, so α, β, γ, δ and other Unicode glyphs render in the PNG. The SVG keeps text
//! as `<text>` elements (searchable, selectable).
//!
//! ```no_run
//! use hapstab_plot::{Figure, Marker, Series, palette};
//! # let (region, linear, points) = (vec![(0.0, 0.0)], vec![(0.0, 0.0)], vec![(0.0, 0.0)]);
//! let mut fig = Figure::new("Stable region, d = 0").x_label("α").y_label("β");
//! fig.add(Series::polygon(region).color(palette::BLUE).label("stable (exact)"));
//! fig.add(Series::dashed(linear).color(palette::BLACK).label("linear (23)"));
//! fig.add(Series::scatter(points, Marker::Circle).color(palette::VERMILLION));
//! fig.save("out/fig4")?; // out/fig4.svg and out/fig4.png
//! # Ok::<(), hapstab_plot::PlotError>(())
//! ```
//!
//! Data are clipped to the axis ranges here (plotters does not clip): polylines by segment
//! (Liang–Barsky), polygons by Sutherland–Hodgman, markers by containment; NaN points break
//! a polyline into pieces.
//!
//! One concept per file: the data [`Series`] (`series`), one panel [`Figure`] (`figure`) and
//! how plotters draws it (`draw`), the legend below the axes (`legend`), a [`Grid`] of panels
//! (`grid`), writing the SVG and PNG files (`save`), clipping to the axis ranges (`clip`).

#![deny(missing_docs)]
#![warn(unreachable_pub)]

use std::path::PathBuf;
use std::sync::OnceLock;

use plotters::style::FontStyle;

pub use plotters::style::RGBColor;

mod clip;
mod draw;
mod figure;
pub mod freq;
mod grid;
mod legend;
pub mod population;
mod save;
mod series;
pub mod simplify;
pub mod text;
pub mod wall;

pub use clip::{segment_distance, segment_meets_box};
pub use figure::{Annotation, Figure, Legend};
pub use grid::Grid;
pub use save::{Saved, output_paths, requested_paths};
pub use series::{Kind, Marker, Series};
pub use simplify::decimate_minmax;

/// Why a figure could not be written: a figure that cannot be drawn, or a file that cannot
/// be written (each names the figure or the file).
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The figure cannot be drawn: an axis range that is empty or not finite, a grid
    /// without panels.
    #[error("plot '{title}': {what}")]
    Figure {
        /// The figure's title.
        title: String,
        /// What is wrong with it.
        what: String,
    },
    /// An empty file name.
    #[error("empty plot file name")]
    EmptyPath,
    /// A folder of the file's path could not be created.
    #[error("cannot create folder {}: {reason}", .path.display())]
    Folder {
        /// The folder.
        path: PathBuf,
        /// The system's reason.
        reason: std::io::Error,
    },
    /// Drawing into the file failed.
    #[error("writing {}: {reason}", .path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The drawing backend's reason.
        reason: String,
    },
    /// The file is not there after writing it.
    #[error("could not write {}", .path.display())]
    Missing {
        /// The file.
        path: PathBuf,
    },
    /// The embedded font could not be registered.
    #[error("the embedded DejaVu Sans font could not be loaded")]
    Font,
}

/// The outcome of writing a figure.
pub type Result<T, E = PlotError> = std::result::Result<T, E>;

/// Colour-blind safe colours (Okabe–Ito) plus black and grey.
pub mod palette {
    use super::RGBColor;
    /// Black.
    pub const BLACK: RGBColor = RGBColor(0, 0, 0);
    /// Blue.
    pub const BLUE: RGBColor = RGBColor(0, 114, 178);
    /// Vermillion.
    pub const VERMILLION: RGBColor = RGBColor(213, 94, 0);
    /// Bluish green.
    pub const GREEN: RGBColor = RGBColor(0, 158, 115);
    /// Orange.
    pub const ORANGE: RGBColor = RGBColor(230, 159, 0);
    /// Reddish purple.
    pub const PURPLE: RGBColor = RGBColor(204, 121, 167);
    /// Sky blue.
    pub const SKY: RGBColor = RGBColor(86, 180, 233);
    /// Grey.
    pub const GREY: RGBColor = RGBColor(110, 110, 110);
    /// Cycle for series without an explicit colour.
    pub const CYCLE: [RGBColor; 7] = [BLUE, VERMILLION, GREEN, ORANGE, PURPLE, SKY, BLACK];
}

/// Default PNG/SVG size of a single figure (px): legible in a paper column.
pub const DEFAULT_SIZE: (u32, u32) = (900, 700);

const FONT: &str = "sans-serif";

/// Registers the embedded DejaVu Sans as `sans-serif` (once per process).
fn ensure_font() -> Result<()> {
    static OK: OnceLock<bool> = OnceLock::new();
    let ok = *OK.get_or_init(|| {
        let reg = |style, bytes| plotters::style::register_font(FONT, style, bytes).is_ok();
        reg(FontStyle::Normal, dejavu::sans::regular())
            & reg(FontStyle::Bold, dejavu::sans::bold())
            & reg(FontStyle::Oblique, dejavu::sans::oblique())
            & reg(FontStyle::Italic, dejavu::sans::oblique())
    });
    if ok { Ok(()) } else { Err(PlotError::Font) }
}
