//! The explorer's integration tests, each against a `hapstab-serve` process started on an
//! ephemeral loopback port (`serve_support`): one file per endpoint (`api_kmax.rs` tests
//! `/api/kmax`, …), the page, refusals, hardening against hostile clients, and the page in a
//! headless browser (`e2e.rs`). The latency tests under load (`serve_load.rs`,
//! `serve_timing.rs`) are binaries of their own, so that nothing else runs beside them.
//!
//! Run one file's tests with `cargo test -p hapstab-serve --test serve api_kmax::`.

#[path = "../e2e_browser/mod.rs"]
mod e2e_browser;
#[path = "../serve_support/mod.rs"]
mod serve_support;

mod api_errors;
mod api_kmax;
mod api_loops;
mod api_map;
mod api_page;
mod api_passivity;
mod api_point;
mod api_region;
mod api_robust_box;
mod api_simulate;
mod api_sweep;
mod api_zwidth;
mod e2e;
mod hardening;
