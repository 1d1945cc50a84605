//! The one progress bar of every long command (indicatif): drawn on standard error only when
//! it is a terminal (an explicit check, and indicatif's stderr target hides itself on a
//! non-terminal too), hidden otherwise (pipes, files, tests), so machine-readable output
//! stays clean and standard error stays empty on success.

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Estimated core-seconds from which a command shows a bar: shorter runs end before a bar
/// would tell anything ("about a second").
pub const LONG_SECONDS: f64 = 1.0;

/// A bar over `len` steps, possibly split into stages that report their own counts.
pub struct Bar {
    bar: ProgressBar,
}

impl Bar {
    /// A bar of `len` `unit`s, visible when `show` and standard error is a terminal.
    pub fn new(len: usize, unit: &str, show: bool) -> Self {
        let bar = if show && std::io::stderr().is_terminal() {
            ProgressBar::with_draw_target(Some(len as u64), ProgressDrawTarget::stderr())
        } else {
            ProgressBar::hidden()
        };
        let template =
            format!("{{bar:40}} {{pos}}/{{len}} {unit} {{elapsed}} (eta {{eta}}) {{msg}}");
        bar.set_style(
            ProgressStyle::with_template(&template)
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Self { bar }
    }

    /// A progress callback for a stage whose steps start at `offset`.
    pub fn stage(&self, offset: usize) -> impl Fn(usize) + Sync + '_ {
        move |done| self.bar.set_position((offset + done) as u64)
    }

    /// One more step done.
    pub fn inc(&self) {
        self.bar.inc(1);
    }

    /// Names what runs now (after the counts).
    pub fn message(&self, m: &'static str) {
        self.bar.set_message(m);
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}
