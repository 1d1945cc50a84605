//! # hapstab
//!
//! Exact stability analysis of a virtual wall rendered by an impedance-type haptic device
//! held by a human operator, after Hulin, Preusche and Hirzinger, "Stability Boundary for
//! Haptic Rendering: Influence of Human Operator" (IROS 2008).
//!
//! A loop is described once ([`loop_spec::LoopSpec`]: plant, period, delay, velocity
//! estimator, the defaults in one place; the form of a loop file), resolved to a validated
//! [`Loop`], and analysed through one object, [`System`] (the loop with its closed-loop
//! family p(z) = P0 + K·PK + B·PB, built once): the verdict at a wall, the stable stiffness
//! intervals, the stable region, K_max, margins, passivity, the frequency response and the
//! root locus. The answers every front end prints are the serde types of [`answer`].
//!
//! ```
//! use hapstab::kmax::{KmaxQuery, kmax};
//! use hapstab::loop_spec::LoopSpec;
//! use hapstab::{System, Verdict, Wall};
//! // the default loop: the default device held by the typical arm, T = 1 ms, no delay
//! let sys = System::new(LoopSpec::default().resolve()?)?;
//! let wall = Wall { stiffness: 2000.0, damping: 5.0 };
//! assert_eq!(sys.decide(sys.wall_units(wall)?).verdict, Verdict::Stable);
//! // the largest stable stiffness at B = 5 Ns/m lies above it
//! let k_max = kmax(&sys, KmaxQuery::AtDamping(5.0))?.k_max.unwrap();
//! assert!(k_max > 2000.0);
//! # Ok::<(), hapstab::Error>(())
//! ```
//!
//! The modules, beside the paper (its normalized view α = KT²/m, β = BT/m, γ, δ, d of
//! Table I is a change of units on the same family):
//!
//! | module | paper |
//! |---|---|
//! | [`loop_spec`], [`model`] | the loop a user describes, and its validated form |
//! | [`system`] | the analysis object: one loop, its family, every question about a wall |
//! | [`params`] | Section II, eq. (1): device, arm, effective plant, wall, sampling |
//! | [`paper`] | the paper's normalized view α, β, γ, δ, d and the analyses defined only for its plant: eq. (10) for comparison with the engine, parameter ranges (eq. 11–15), the linear condition (Sections VI–VII), Nyquist, robust stability and passivity in γ (Section VIII), grid maps |
//! | [`closed_loop`] | eq. (7)–(9) |
//! | [`verdict`], [`stability`] | Section V (roots inside the unit circle) |
//! | [`polyroots`] | Section V (the roots of p(z): Aberth–Ehrlich, companion matrix) |
//! | [`limits`] | the computing time and memory of each analysis, estimated before it starts |
//! | [`passivity`] | Section VIII, eq. (28), for any loop (Colgate & Schenkel 1997) |
//! | [`map`] | Section V's grid method for any loop over its wall, in parallel |
//! | [`margins`] | gain, phase and delay margins on the exact sampled loop |
//! | [`freqresp`] | the open loop's frequency response (Bode and Nyquist plot data) |
//! | [`kmax`] | Section V: K_max at a damping, over a band, and over the renderable band |
//! | [`answer`] | the answers of check, K_max, sweep, Z-width, map and passivity with their inputs, as every front end writes them |
//! | [`population`] | beyond the paper: P(stable) over a population of operators |
//! | [`robust`] | beyond the paper: robust K_max of any loop over a box of its parameters |
//! | [`locus`] | the root locus in K at a fixed B, crossing the unit circle at K_max |
//! | [`zwidth`] | Z-width of a device (Colgate & Brown 1994) |
//! | [`sweep`] | K_max against a parameter of the loop |
//! | [`identify`] | beyond the paper: the plant from a recording of force and position, with its uncertainty |

#![deny(missing_docs)]

pub mod answer;
pub mod argument;
pub mod boundary;
pub mod bracket;
pub mod cayley;
pub mod circle;
pub mod closed_loop;
pub mod delay;
pub mod error;
pub mod extent;
pub mod extremum;
pub mod freqresp;
pub mod grid;
pub mod identify;
pub mod json;
pub mod kmax;
pub mod kmax_band;
pub mod limits;
pub mod line_decomposition;
pub mod locus;
pub mod loop_spec;
pub mod lowpass_design;
pub mod map;
pub mod margins;
pub mod matrix_exp;
pub mod model;
pub mod operator;
pub mod paper;
pub mod param;
pub mod params;
pub mod passivity;
pub mod passivity_quantized;
pub mod poly;
pub mod polyroots;
pub mod population;
pub mod real_roots;
pub mod region;
pub mod robust;
pub mod schur_cohn;
pub mod simulation;
pub mod spec;
mod splitmix;
pub mod stability;

pub mod sweep;
pub mod system;
pub mod verdict;
pub mod zoh;
pub mod zwidth;

pub use closed_loop::AffineFamily;
pub use error::{Error, Result};
pub use model::{Delay, Loop, Plant, PlantModel, TwoMass, VelocityEstimator};
pub use paper::{Normalized, PlantParams, is_stable};
pub use param::Param;
pub use params::{Arm, Device, Effective, Physical, Sampling, Wall};
pub use schur_cohn::schur_stable;
pub use stability::Analysis;
pub use system::System;
pub use verdict::{Basis, Decision, MARGINAL_BAND, Verdict, decide};
pub use zoh::{DiscreteLoop, DiscreteTf, WallScale};
