//! The command line's integration tests, run against the built `hapstab` binary: one file per
//! command or concern (`margins.rs` for `check`'s margins, `loop_file.rs` for `--loop`, the
//! JSON schema in `output.rs`, the explorer against the command line in `serve_parity*.rs`),
//! with the helpers they share in `common` and the explorer's test server from hapstab-serve.
//!
//! Run one file's tests with `cargo test -p hapstab-cli --test cli margins::`.

mod common;
#[path = "../../../hapstab-serve/tests/e2e_browser/mod.rs"]
mod e2e_browser;
#[path = "../../../hapstab-serve/tests/serve_support/mod.rs"]
mod serve_support;

mod audit;
mod budget;
mod cli;
mod cli_fuzz;
mod extremes;
mod figures;
mod human_output;
mod identify;
mod linear;
mod loop_file;
mod loop_flags_check;
mod loop_flags_discretize;
mod loop_flags_map_boundary_kmax;
mod loop_flags_refusals;
mod map_output;
mod margins;
mod named_filters;
mod output;
mod paper;
mod passivity_zwidth;
mod plots;
mod population;
mod robust_box;
mod serve_parity;
mod serve_parity_browser;
mod serve_parity_matrix;
mod simboundary;
mod simulate;
