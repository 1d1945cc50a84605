//! The engine's integration tests, one file per module of the library (`kmax_band.rs` tests
//! `hapstab::kmax_band`, `zoh.rs` the discretization, …), with the helpers they share in
//! `common`. Expected values come from closed forms, the paper, published examples or an
//! independent method, never from the program's own output; a fixture hapstab made itself is
//! named `*_regression` and says which commit made it.
//!
//! Run one file's tests with `cargo test -p hapstab --test engine kmax_band::`.

mod common;

mod boundary;
mod extremes;
mod identify;
mod kmax;
mod kmax_band;
mod loop_spec;
mod map;
mod margins;
mod margins_delay;
mod margins_property;
mod matrix_exp;
mod paper;
mod passivity;
mod passivity_quantized;
mod population;
mod python_control;
mod python_reference;
mod region;
mod region_hard_cases;
mod robust;
mod roots;
mod simulation;
mod simulation_clip;
mod simulation_loop;
mod simulation_verdicts;
mod stability;
mod statespace_referee;
mod verdict;
mod zoh;
mod zwidth_sweep;
