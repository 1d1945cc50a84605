//! The command line's side of the wall-plane figures ([`hapstab_plot::wall`]): the plane and
//! the subtitle of a resolved loop, writing a `--plot FILE` and naming the files written.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use hapstab::AffineFamily;
use hapstab_plot::Figure;

pub use hapstab_plot::wall::{
    Part, Plane, damping_line, mark, mark_above, region_figure, room_for_tags, roots_figure,
};

use crate::model::ResolvedLoop;

/// The wall plane of a resolved loop: physical unless given in normalized parameters.
pub fn plane<'a>(rl: &ResolvedLoop, fam: &'a AffineFamily) -> Plane<'a> {
    Plane::new(fam, !rl.normalized)
}

/// The loop a figure shows, in one line for its subtitle ([`hapstab_plot::wall::loop_line`]).
pub fn loop_line(rl: &ResolvedLoop) -> String {
    hapstab_plot::wall::loop_line(&rl.lp, rl.normalized)
}

/// [`loop_line`] without the parts in `omit`.
pub fn loop_line_without(rl: &ResolvedLoop, omit: &[Part]) -> String {
    hapstab_plot::wall::loop_line_without(&rl.lp, rl.normalized, omit)
}

/// Writes `fig` to the file(s) that `path` names (SVG or PNG by its extension), naming the
/// path on failure.
pub fn save(fig: Figure, path: &Path) -> Result<Vec<PathBuf>> {
    room_for_tags(fig)
        .save_as(path)
        .with_context(|| format!("--plot {}", path.display()))
}

/// The written files, for the text output.
pub fn files_text(files: &[PathBuf]) -> String {
    files
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(" and ")
}
