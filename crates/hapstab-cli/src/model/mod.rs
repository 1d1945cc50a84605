//! Model arguments shared by the commands: normalized (α, β, γ, δ, d) or physical units.
//!
//! - [`flags`]: the flag-name lists the argument structs conflict on;
//! - [`plant_args`]: the paper's plant and sampling flags ([`PlantArgs`]) and their resolution;
//! - [`point`]: one parameter point from plant and wall flags ([`resolve_point`]);
//! - [`loop_args`]: the general loop's flags ([`LoopArgs`]) resolved to a [`ResolvedLoop`];
//! - [`wall_args`]: the wall flags ([`WallArgs`]) in the loop's units ([`resolve_loop_wall`]);
//! - [`describe`]: the loop in words for text output ([`print_loop`], [`print_loop_and_wall`]).

mod describe;
mod flags;
mod loop_args;
mod plant_args;
mod point;
mod wall_args;

use hapstab::System;
use hapstab::model::Loop;
use hapstab::params::Wall;

pub use describe::{print_loop, print_loop_and_wall};
pub use flags::{LOOP_FLAGS, NON_PAPER_PLANT_FLAGS, PHYSICAL_PLANT_FLAGS};
pub use hapstab::loop_spec::LoopInput;
pub use hapstab::loop_spec::{DEFAULT_PERIOD, DEFAULT_WALL};
pub use loop_args::LoopArgs;
pub use plant_args::{PlantArgs, PlantModel, delay_samples};
pub use point::resolve_point;
pub use wall_args::{WallArgs, resolve_loop_wall};

/// A loop resolved from the flags.
#[derive(Debug, Clone)]
pub struct ResolvedLoop {
    /// The loop (for a normalized plant: [`Loop::normalized`], m = T = 1, so K = α, B = β).
    pub lp: Loop,
    /// True when the plant was given normalized (--gamma/--delta, or --alpha/--beta alone).
    pub normalized: bool,
    /// The wall of the --loop file, in the loop's units, when it names one.
    pub wall: Option<Wall>,
}

impl ResolvedLoop {
    /// The loop's analysis object (discretized and closed once).
    pub fn system(&self) -> hapstab::Result<System> {
        System::of(&self.lp)
    }

    /// The inputs of a command on this loop and an optional wall in the loop's units, echoed
    /// in its JSON under `input` (the form `--loop` reads back).
    pub fn input(&self, wall: Option<Wall>) -> LoopInput {
        LoopInput::new(&self.lp, self.normalized, wall)
    }
}
