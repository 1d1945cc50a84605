//! A grid of panels saved as one image.

use std::path::Path;

use super::save::{Saved, save_both};
use super::{DEFAULT_SIZE, Figure, Result};

/// Space in px above a grid's title, so that its tallest glyphs clear the image's edge.
pub(super) const GRID_TITLE_TOP: u32 = 8;

/// A grid of panels saved as one image: `cols` columns, rows as needed, panels in reading
/// order, each of `panel_size` px, with an optional overall title.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Overall title (may be empty).
    pub title: String,
    /// A second, smaller overall title line (may be empty): which loop is shown.
    pub subtitle: String,
    /// Number of columns (>= 1).
    pub cols: usize,
    /// Panels in reading order.
    pub panels: Vec<Figure>,
    /// Size of one panel in px.
    pub panel_size: (u32, u32),
}

impl Grid {
    /// An empty grid with `cols` columns of 900×700 px panels.
    pub fn new(title: impl Into<String>, cols: usize) -> Self {
        Self {
            title: title.into(),
            subtitle: String::new(),
            cols: cols.max(1),
            panels: Vec::new(),
            panel_size: DEFAULT_SIZE,
        }
    }

    /// Sets the size of one panel in px.
    pub fn panel_size(mut self, w: u32, h: u32) -> Self {
        self.panel_size = (w, h);
        self
    }

    /// Sets the second overall title line.
    pub fn subtitle(mut self, s: impl Into<String>) -> Self {
        self.subtitle = s.into();
        self
    }

    /// Adds a panel.
    pub fn push(&mut self, f: Figure) -> &mut Self {
        self.panels.push(f);
        self
    }

    pub(super) fn rows(&self) -> usize {
        self.panels.len().div_ceil(self.cols).max(1)
    }

    pub(super) fn title_height(&self) -> u32 {
        let title = if self.title.is_empty() {
            0
        } else {
            GRID_TITLE_TOP + 56
        };
        let subtitle = if self.subtitle.is_empty() { 0 } else { 42 };
        title + subtitle
    }

    /// Writes `<stem>.svg` and `<stem>.png` (see [`Figure::save`]).
    pub fn save(&self, stem: impl AsRef<Path>) -> Result<Saved> {
        save_both(self, stem.as_ref())
    }
}
