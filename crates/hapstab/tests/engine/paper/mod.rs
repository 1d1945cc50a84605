//! Tests of `hapstab::paper`, the paper's normalized view, one file per module:
//! `reference.rs` the closed-form plant (eq. 2–6, 10), `ranges.rs` eq. (11)–(15),
//! `linear.rs` Sections VI–VII, `nyquist.rs` Section VIII, `map.rs` Section V's grid maps, and
//! `regression.rs` the façade against the paper-only engine it replaced (1000 seeded points).

mod linear;
mod map;
mod nyquist;
mod ranges;
mod reference;
mod regression;
