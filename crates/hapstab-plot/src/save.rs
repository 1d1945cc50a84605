//! Writing a figure or a grid as `<stem>.svg` and `<stem>.png` (or the one file a path
//! names), with the font registered and every failure naming its file.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use super::draw::fit_font;
use super::{FONT, Figure, Grid, PlotError, Result, ensure_font};

/// The files written by a save.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Saved {
    /// The SVG file.
    pub svg: PathBuf,
    /// The PNG file.
    pub png: PathBuf,
}

pub(super) trait Render {
    fn pixels(&self) -> (u32, u32);
    fn check(&self) -> Result<()>;
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>;
}

impl Render for Figure {
    fn pixels(&self) -> (u32, u32) {
        self.size
    }
    fn check(&self) -> Result<()> {
        Figure::check(self)
    }
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        self.draw(root)
    }
}

impl Render for Grid {
    fn pixels(&self) -> (u32, u32) {
        let (w, h) = self.panel_size;
        (
            w * self.cols as u32,
            h * self.rows() as u32 + self.title_height(),
        )
    }
    fn check(&self) -> Result<()> {
        if self.panels.is_empty() {
            return Err(PlotError::Figure {
                title: self.title.clone(),
                what: "no panels".into(),
            });
        }
        self.panels.iter().try_for_each(Figure::check)
    }
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let width = root.dim_in_pixel().0;
        let mut body = root.clone();
        if !self.title.is_empty() {
            let size = fit_font(40.0, &self.title, width);
            body = body.margin(super::grid::GRID_TITLE_TOP, 0, 0, 0);
            body = body.titled(&self.title, (FONT, size).into_font())?;
        }
        if !self.subtitle.is_empty() {
            let size = fit_font(30.0, &self.subtitle, width);
            let style = (FONT, size).into_font().color(&RGBColor(60, 60, 60));
            body = body.titled(&self.subtitle, style)?;
        }
        let areas = body.split_evenly((self.rows(), self.cols));
        // the panels of a row keep one legend strip height, so that their axes line up
        let width = self.panel_size.0;
        for (row, chunk) in self.panels.chunks(self.cols).enumerate() {
            let strip = chunk
                .iter()
                .map(|p| p.strip_height(width))
                .max()
                .unwrap_or(0);
            for (k, panel) in chunk.iter().enumerate() {
                panel.draw_reserving(&areas[row * self.cols + k], strip)?;
            }
        }
        Ok(())
    }
}

/// `<stem>.svg` and `<stem>.png`; a trailing `.svg`/`.png` on the stem is dropped.
pub fn output_paths(stem: &Path) -> (PathBuf, PathBuf) {
    let base = match stem.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("svg") || e.eq_ignore_ascii_case("png") => {
            stem.with_extension("")
        }
        _ => stem.to_path_buf(),
    };
    let with = |ext: &str| {
        let mut s = base.clone().into_os_string();
        s.push(".");
        s.push(ext);
        PathBuf::from(s)
    };
    (with("svg"), with("png"))
}

pub(super) fn save_both<R: Render>(r: &R, stem: &Path) -> Result<Saved> {
    if stem.as_os_str().is_empty() {
        return Err(PlotError::EmptyPath);
    }
    let (svg, png) = output_paths(stem);
    write_files(r, &[&svg, &png])?;
    Ok(Saved { svg, png })
}

/// What `path` asks for: only an SVG for a `.svg` extension, only a PNG for `.png`, both
/// `<path>.svg` and `<path>.png` for any other name.
pub fn requested_paths(path: &Path) -> Vec<PathBuf> {
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("svg") || e.eq_ignore_ascii_case("png") => {
            vec![path.to_path_buf()]
        }
        _ => {
            let (svg, png) = output_paths(path);
            vec![svg, png]
        }
    }
}

/// Writes the files that `path` names ([`requested_paths`]) and returns them.
fn save_requested<R: Render>(r: &R, path: &Path) -> Result<Vec<PathBuf>> {
    if path.as_os_str().is_empty() {
        return Err(PlotError::EmptyPath);
    }
    let paths = requested_paths(path);
    let refs: Vec<&Path> = paths.iter().map(PathBuf::as_path).collect();
    write_files(r, &refs)?;
    Ok(paths)
}

impl Figure {
    /// Writes the file that `path` names: an SVG for `.svg`, a PNG for `.png`, both
    /// `<path>.svg` and `<path>.png` for any other name ([`requested_paths`]).
    pub fn save_as(&self, path: impl AsRef<Path>) -> Result<Vec<PathBuf>> {
        save_requested(self, path.as_ref())
    }
}

impl Grid {
    /// Writes the file that `path` names (see [`Figure::save_as`]).
    pub fn save_as(&self, path: impl AsRef<Path>) -> Result<Vec<PathBuf>> {
        save_requested(self, path.as_ref())
    }
}

/// Renders `r` into each path, as SVG or PNG by its extension (missing parent folders are
/// created); every failure names the file.
fn write_files<R: Render>(r: &R, paths: &[&Path]) -> Result<()> {
    r.check()?;
    ensure_font()?;
    for path in paths {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|reason| PlotError::Folder {
                path: dir.to_path_buf(),
                reason,
            })?;
        }
        let size = r.pixels();
        let fail = |e: &dyn std::fmt::Display| PlotError::Write {
            path: path.to_path_buf(),
            reason: e.to_string(),
        };
        let svg = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
        if svg {
            let root = SVGBackend::new(path, size).into_drawing_area();
            root.fill(&WHITE).map_err(|e| fail(&e))?;
            r.render(&root).map_err(|e| fail(&e))?;
            root.present().map_err(|e| fail(&e))?;
        } else {
            let root = BitMapBackend::new(path, size).into_drawing_area();
            root.fill(&WHITE).map_err(|e| fail(&e))?;
            r.render(&root).map_err(|e| fail(&e))?;
            root.present().map_err(|e| fail(&e))?;
        }
        // plotters reports some write failures only on drop: make sure the file is there.
        if !path.is_file() {
            return Err(PlotError::Missing {
                path: path.to_path_buf(),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::{DEFAULT_SIZE, Marker, Series, palette};

    fn sample_figure() -> Figure {
        let circle: Vec<(f64, f64)> = (0..100)
            .map(|i| {
                let t = i as f64 / 100.0 * std::f64::consts::TAU;
                (0.5 + 0.4 * t.cos(), 0.5 + 0.4 * t.sin())
            })
            .collect();
        let mut f = Figure::new("Test: stable region")
            .x_label("virtual stiffness α")
            .y_label("virtual damping β")
            .x_range(-0.2, 1.2)
            .y_range(-0.2, 1.2);
        f.add(Series::polygon(circle).color(palette::BLUE).label("region"));
        f.add(
            Series::dashed([(-1.0, -1.0), (2.0, 2.0)])
                .color(palette::BLACK)
                .label("dashed, clipped"),
        );
        f.add(Series::line([
            (0.0, 1.0),
            (f64::NAN, 0.0),
            (1.0, 0.0),
            (0.5, 0.5),
        ]));
        f.add(
            Series::scatter([(0.2, 0.2), (0.8, 0.8), (5.0, 5.0)], Marker::Circle)
                .color(palette::VERMILLION)
                .label("2 %"),
        );
        f.add(
            Series::scatter([(0.3, 0.7)], Marker::Square)
                .color(palette::GREEN)
                .hollow()
                .label("5 %"),
        );
        f.annotate(0.1, 1.05, "γ = 0.001, δ = 0.015");
        f
    }

    fn check_png(path: &Path, size: (u32, u32)) {
        let img = image::open(path).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), size);
        let non_white = img.pixels().filter(|p| p.0 != [255, 255, 255]).count();
        let total = (size.0 * size.1) as usize;
        // Axes, text and a filled region: clearly not blank, clearly not all ink.
        assert!(non_white > total / 50, "{non_white} of {total}");
        assert!(non_white < total * 3 / 4, "{non_white} of {total}");
        // The 25 % blue fill blends to about (191, 220, 236).
        let colored = img
            .pixels()
            .filter(|p| p.0[2] > 200 && p.0[0] < 210 && p.0[0] > 170)
            .count();
        assert!(colored > total / 50, "fill missing: {colored}");
    }

    #[test]
    fn figure_writes_svg_and_png_with_labels() {
        let dir = tempfile::tempdir().unwrap();
        let f = sample_figure();
        let saved = f.save(dir.path().join("sub").join("fig.svg")).unwrap();
        assert_eq!(saved.svg, dir.path().join("sub/fig.svg"));
        assert_eq!(saved.png, dir.path().join("sub/fig.png"));
        check_png(&saved.png, DEFAULT_SIZE);
        let svg = std::fs::read_to_string(&saved.svg).unwrap();
        assert!(svg.starts_with("<svg"), "{}", &svg[..80.min(svg.len())]);
        for t in [
            "virtual stiffness α",
            "virtual damping β",
            "Test: stable region",
            "γ = 0.001, δ = 0.015",
            "dashed, clipped",
        ] {
            assert!(svg.contains(t), "SVG lacks {t}");
        }
        assert!(svg.contains("<polygon"), "no filled polygon");
        // Every text is at least 18 px (readable when a paper column prints 900 px wide).
        let sizes: Vec<f64> = svg
            .split("font-size=\"")
            .skip(1)
            .map(|t| t.split('"').next().unwrap().parse().unwrap())
            .collect();
        assert!(sizes.len() > 10, "{sizes:?}");
        assert!(sizes.iter().all(|&v| v >= 18.0), "{sizes:?}");
        assert!(svg.contains("opacity=\"0.25\""), "no alpha fill");
    }

    #[test]
    fn grid_writes_one_image_of_all_panels() {
        let dir = tempfile::tempdir().unwrap();
        let mut g = Grid::new("Two panels", 2).panel_size(600, 450);
        g.push(sample_figure().x_label("left α"));
        g.push(sample_figure().x_label("right β"));
        g.push(sample_figure().x_label("third"));
        let saved = g.save(dir.path().join("grid")).unwrap();
        check_png(&saved.png, (1200, 900 + 8 + 56));
        let svg = std::fs::read_to_string(&saved.svg).unwrap();
        for t in ["left α", "right β", "third", "Two panels"] {
            assert!(svg.contains(t), "SVG lacks {t}");
        }
    }

    #[test]
    fn bad_ranges_and_paths_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let f = Figure::new("x").x_range(1.0, 1.0);
        assert!(f.save(dir.path().join("a")).is_err());
        let f = Figure::new("x").y_range(0.0, f64::NAN);
        assert!(f.save(dir.path().join("b")).is_err());
        assert!(sample_figure().save("").is_err());
        // A file where a folder is needed.
        std::fs::write(dir.path().join("file"), "x").unwrap();
        assert!(sample_figure().save(dir.path().join("file/fig")).is_err());
        // Auto range of an empty figure is usable.
        assert_eq!(Figure::new("e").ranges(), ((0.0, 1.0), (0.0, 1.0)));
    }
}
