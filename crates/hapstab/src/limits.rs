//! Resource limits shared by every front end: each analysis estimates its computing time and
//! memory from its inputs before it starts ([`Cost`]), and a front end refuses a request
//! whose estimate exceeds its [`Budget`], naming the input that drives the cost.
//!
//! Costs are counted in *core-seconds* (seconds of one core of the 2-core reference machine
//! the project is tested on) and bytes. They are estimates from the sizes of the inputs
//! (samples, grid points, polynomial degree d + 3), calibrated by measurement; they are meant
//! to be right within a factor of about three, which is what a limit needs: a request either
//! fits with room to spare or is far beyond it.
//!
//! | budget | time | memory | used by |
//! |---|---|---|---|
//! | [`Budget::COMMAND_LINE`] | [`MAX_COMMAND_SECONDS`] | [`MAX_COMMAND_MEMORY`] | `hapstab` commands |
//! | [`Budget::INTERACTIVE`] | [`MAX_JOB_SECONDS`] | [`MAX_JOB_MEMORY`] | one request to `hapstab serve` |

use std::fmt;

use serde::Serialize;

pub use crate::map::MAX_POINTS as MAX_MAP_POINTS;
pub use crate::params::MAX_DELAY;

/// Core-seconds of one call of [`crate::boundary::stable_stiffness_intervals`] per unit of
/// (d + 4): the D-decomposition crossings and one Schur–Cohn test per gap grow linearly with
/// the degree in practice. Measured with `kmax --robust` (10 µs at d = 0 and d = 12, golden
/// refinements included) and `nyquist` (d = 0, 4, 12).
pub const SWEEP_SECONDS_PER_DEGREE: f64 = 10e-6;
/// Core-seconds of one Schur–Cohn point test: a fixed 100 ns (measured with `map`, 10⁶ points
/// at d = 0) ...
pub const POINT_TEST_SECONDS: f64 = 100e-9;
/// ... plus 0.4 ns per n² for degree n = d + 3 at a stable point (the test is O(n²);
/// measured with `map` at d = 1000, 0.36 ms per stable point).
pub const POINT_TEST_SECONDS_PER_N2: f64 = 0.4e-9;
/// Core-seconds of forming one plant's exact family for a map whose axes change the plant
/// (γ or δ): the discretization and the parts of p(z), about 1.2 µs (measured with
/// `map --x gamma:0:0.05:400 --y delta:0:0.5:400 --alpha 0.15 --beta 0.3 --delay 2`,
/// 0.19–0.20 core-seconds for 160 000 plants and their tests) — [`plants_cost`].
pub const PLANT_FAMILY_SECONDS: f64 = 1.25e-6;
/// Core-seconds of the roots of a polynomial ([`roots_cost`]): a fixed 20 µs ...
pub const ROOTS_SECONDS: f64 = 20e-6;
/// ... plus 40 ns per n² (Aberth–Ehrlich: O(n²) per sweep; measured with `check`, 0.19
/// core-seconds at degree 2003 with the interval and the loop's discretization).
pub const ROOTS_SECONDS_PER_N2: f64 = 40e-9;
/// Core-seconds of one evaluation of P0, PK and PB at a point of the unit circle per
/// coefficient of the loop's parts (measured with `check --velocity average:400`, 16 s for
/// about 2.7·10⁹ coefficient evaluations of the margins).
pub const CIRCLE_EVAL_SECONDS: f64 = 6e-9;
/// Frequencies per degree of p(z) of the margins' scans (the margins' own grid).
pub const MARGIN_GRID_PER_DEGREE: f64 = 256.0;
/// Scans of the whole grid at p's degree: the phase margin and the two gain margins' line
/// crossings.
pub const MARGIN_SCANS: f64 = 3.0;
/// Parts of the delay margin's fraction table at each frequency ([`crate::margins::fraction`]):
/// P0, the hold part without the fraction and one per plant state — at most 15 (a transfer
/// function of order 12 with an actuator lag), each of the core's degree.
pub const MARGIN_FRACTION_PARTS: f64 = 15.0;
/// Core-seconds of the delay margin's scan at most (its work bound).
pub const DELAY_SCAN_SECONDS: f64 = 0.3;
/// Point tests of the delay margin's bisection (to 1e-13 of the delay, about 45 halvings).
pub const DELAY_BISECTION_TESTS: f64 = 45.0;
/// Core-seconds of an exact region's fixed part: its seed slices and checks (measured with
/// `boundary` at d = 0, 10).
pub const REGION_SECONDS: f64 = 1e-3;
/// Core-seconds of an exact region per n²·(core + [`REGION_CORE_OFFSET`]) (measured with
/// `boundary`: 0.43 s at d = 1000 and 2.0 s at d = 2000 with parts of degree 3; 0.48 s with
/// `--velocity average:200`, 1.5 s with `average:100` at d = 500).
pub const REGION_SECONDS_PER_N2_CORE: f64 = 55e-9;
/// What the per-point work of a region adds to the degree of the loop's parts (the fixed
/// work of each curve point and slice besides the evaluation).
pub const REGION_CORE_OFFSET: f64 = 6.0;
/// A sweep's region at its coarser chord tolerance ([`crate::sweep::SWEEP_REL_TOL`]) takes
/// about this fraction of a drawn region's time.
pub const SWEEP_REGION_FACTOR: f64 = 0.5;
/// Exact regions' worth of work of one loop's Z-width ([`crate::zwidth`]): its stable region
/// and K_max table trace about two regions (measured with `zwidth`: 0.85 s at d = 760 against
/// 0.38 s for `boundary`).
pub const ZWIDTH_REGIONS: f64 = 2.0;
/// Core-seconds of a passive region's fixed part (measured with `passivity`).
pub const PASSIVITY_SECONDS: f64 = 1e-3;
/// Core-seconds of a passive region per n² (measured with `passivity`: 0.16 s at d = 2000).
pub const PASSIVITY_SECONDS_PER_N2: f64 = 4e-8;
/// ... plus this per n·core (measured with `passivity --velocity average:200`: 0.11 s).
pub const PASSIVITY_SECONDS_PER_N_CORE: f64 = 2.5e-6;
/// Core-seconds per n² of one spectral radius of a map: 20 ns, between the two ways of
/// computing it, so that either is within a factor of two: the bisection on the Schur–Cohn
/// test of p(rz) (measured with `map --radius`, 10 ns per n² at d = 1000) and the polished
/// roots of [`roots_cost`] (40 ns per n²).
pub const MAP_RADIUS_SECONDS_PER_N2: f64 = 20e-9;
/// Share of a full Schur–Cohn test that an unstable point costs (measured with `map`: 15 µs
/// per point at d = 1000 where nearly every point is unstable, against 0.4 ms for a full
/// test).
pub const UNSTABLE_TEST_FRACTION: f64 = 0.04;
/// Steps of the delay margin's scan that the estimate counts (each an O(n·core) robustness
/// bound and an O(n²) test); the scan itself stops at [`DELAY_SCAN_SECONDS`].
pub const DELAY_SCAN_STEPS: f64 = 10.0;
/// Extra interval sweeps of a golden-section or bisection refinement (about 50 steps to full
/// double precision, twice: one per end of an interval).
pub const REFINEMENT_SWEEPS: f64 = 100.0;
/// Bytes held per plant configuration of a robust analysis (the discretized plant, its
/// scale and its coordinates, with allocator overhead).
pub const CONFIG_BYTES: f64 = 256.0;
/// Bytes held per β slice (the slice value, its interval ends and the refinement bookkeeping).
pub const SLICE_BYTES: f64 = 96.0;
/// Bytes per sampled curve point of the region construction (the engine documents 4·10⁶
/// points as about 100 MB).
pub const REGION_BYTES_PER_POINT: f64 = 25.0;
/// Core-seconds of one simulated sample: the delay is a ring buffer and the velocity filter
/// a short recursion, so a step costs about the same whatever the loop (measured with
/// `simulate`: 0.35–0.42 s for 10⁷ samples of the paper's loop at d = 0 and d = 2000 and
/// with `average:100`).
pub const SIMULATION_SECONDS_PER_SAMPLE: f64 = 40e-9;
/// Largest run length of a simulation in samples, in every front end: 10⁹ samples (about 40
/// core-seconds of stepping, 11.6 days of a 1 kHz loop).
pub const MAX_SIMULATION_SAMPLES: f64 = 1e9;
/// Bytes per recorded row of a simulated trace (time, position, velocity, forces).
pub const TRACE_ROW_BYTES: f64 = 64.0;

/// Largest estimated computing time of one command: 600 core-seconds, about five minutes on
/// the two cores of the reference machine (commands show a progress bar on a terminal).
pub const MAX_COMMAND_SECONDS: f64 = 600.0;
/// Largest estimated memory of one command: 2 GiB, a tenth of the reference machine.
pub const MAX_COMMAND_MEMORY: f64 = 2.0 * 1024.0 * 1024.0 * 1024.0;
/// Largest estimated computing time of one request to the explorer: 5 core-seconds, half of
/// its 10 s time limit, so that an estimate off by a factor of two still finishes.
pub const MAX_JOB_SECONDS: f64 = 5.0;
/// Largest estimated memory of one request to the explorer: 128 MiB, room for one exact
/// region at the engine's bound (about 100 MB), so that the explorer's four concurrent jobs
/// stay under 1 GB together.
pub const MAX_JOB_MEMORY: f64 = 128.0 * 1024.0 * 1024.0;

/// The estimated cost of an analysis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Cost {
    /// Computing time in core-seconds.
    pub seconds: f64,
    /// Peak memory of the analysis' own tables in bytes.
    pub memory: f64,
}

impl Cost {
    /// Nothing.
    pub const ZERO: Cost = Cost {
        seconds: 0.0,
        memory: 0.0,
    };

    /// Two analyses run one after the other: times add, memory is the larger peak.
    pub fn then(self, next: Cost) -> Cost {
        Cost {
            seconds: self.seconds + next.seconds,
            memory: self.memory.max(next.memory),
        }
    }
}

/// Which resource a cost exceeds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Resource {
    /// Computing time.
    Time,
    /// Memory.
    Memory,
}

/// A cost beyond a budget: the resource, the estimate and the limit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Exceeded {
    /// The resource.
    pub resource: Resource,
    /// The estimate (core-seconds or bytes).
    pub estimate: f64,
    /// The limit (core-seconds or bytes).
    pub limit: f64,
}

impl fmt::Display for Exceeded {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.resource {
            Resource::Time => write!(
                f,
                "would need about {} of computing on one core (limit {})",
                duration(self.estimate),
                duration(self.limit)
            ),
            Resource::Memory => write!(
                f,
                "would hold about {} in memory (limit {})",
                bytes(self.estimate),
                bytes(self.limit)
            ),
        }
    }
}

/// A duration in s, min, h or years for messages.
fn duration(s: f64) -> String {
    if !s.is_finite() || s > 3.15e9 {
        "more than a century".into()
    } else if s >= 2.0 * 86400.0 * 365.0 {
        format!("{:.0} years", s / (86400.0 * 365.0))
    } else if s >= 7200.0 {
        format!("{:.0} h", s / 3600.0)
    } else if s >= 120.0 {
        format!("{:.0} min", s / 60.0)
    } else {
        format!("{:.2} s", s)
    }
}

/// A byte count in kB, MB, GB or TB for messages.
fn bytes(b: f64) -> String {
    if !b.is_finite() || b >= 1e15 {
        return format!("{b:.1e} bytes");
    }
    let (v, unit) = match b {
        b if b >= 1e12 => (b / 1e12, "TB"),
        b if b >= 1e9 => (b / 1e9, "GB"),
        b if b >= 1e6 => (b / 1e6, "MB"),
        b => (b / 1e3, "kB"),
    };
    format!("{v:.1} {unit}")
}

/// The largest cost a front end accepts for one analysis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Budget {
    /// Core-seconds.
    pub seconds: f64,
    /// Bytes.
    pub memory: f64,
}

impl Budget {
    /// One `hapstab` command.
    pub const COMMAND_LINE: Budget = Budget {
        seconds: MAX_COMMAND_SECONDS,
        memory: MAX_COMMAND_MEMORY,
    };
    /// One request to the explorer (`hapstab serve`).
    pub const INTERACTIVE: Budget = Budget {
        seconds: MAX_JOB_SECONDS,
        memory: MAX_JOB_MEMORY,
    };

    /// Ok when the cost fits (NaN estimates, from absurd inputs, never fit).
    pub fn check(&self, cost: Cost) -> Result<(), Exceeded> {
        let fits =
            |estimate: f64, limit: f64| estimate.partial_cmp(&limit).is_some_and(|o| o.is_le());
        if !fits(cost.memory, self.memory) {
            return Err(Exceeded {
                resource: Resource::Memory,
                estimate: cost.memory,
                limit: self.memory,
            });
        }
        if !fits(cost.seconds, self.seconds) {
            return Err(Exceeded {
                resource: Resource::Time,
                estimate: cost.seconds,
                limit: self.seconds,
            });
        }
        Ok(())
    }
}

/// (d + 4) as a float: the per-degree factor of one interval sweep.
fn degree_factor(d: usize) -> f64 {
    d as f64 + 4.0
}

/// `count` interval sweeps at delay d.
fn sweeps(count: f64, d: usize) -> f64 {
    count * degree_factor(d) * SWEEP_SECONDS_PER_DEGREE
}

/// Cost of [`crate::paper::nyquist::region_summary`] with `beta_samples` slices: one sweep per slice
/// and the refinements of the extent and of α_max.
pub fn region_summary_cost(beta_samples: usize, d: usize) -> Cost {
    let n = (beta_samples as f64).max(8.0);
    Cost {
        seconds: sweeps(n + 2.0 * REFINEMENT_SWEEPS, d),
        memory: n * SLICE_BYTES,
    }
}

/// Cost of [`crate::paper::nyquist::gamma_sweep`]: `steps + 1` region summaries, one at a time.
pub fn gamma_sweep_cost(steps: usize, beta_samples: usize, d: usize) -> Cost {
    let one = region_summary_cost(beta_samples, d);
    Cost {
        seconds: one.seconds * (steps as f64 + 1.0),
        memory: one.memory,
    }
}

/// Cost of [`crate::paper::nyquist::robust_region`]: every β slice (initial grid, then up to
/// `refine_beta_rounds` rounds that may double it) intersects the intervals of all γ
/// samples, plus a golden-section search per slice end when refining in γ.
pub fn robust_region_cost(
    gamma_samples: usize,
    beta_samples: usize,
    d: usize,
    refine_gamma: bool,
    refine_beta_rounds: usize,
) -> Cost {
    let gs = (gamma_samples as f64).max(2.0);
    let n = (beta_samples as f64).max(8.0);
    // refinement rounds add midpoints where the outline bends: typically about one grid's
    // worth per round (the memory bound below allows the full doubling)
    let slices = n * (1.0 + refine_beta_rounds as f64);
    let per_slice = gs + if refine_gamma { REFINEMENT_SWEEPS } else { 0.0 };
    let max_slices = n * 2f64.powi(refine_beta_rounds.min(64) as i32);
    Cost {
        seconds: sweeps(slices * per_slice, d),
        memory: gs * CONFIG_BYTES + max_slices * SLICE_BYTES,
    }
}

/// Cost of [`crate::paper::nyquist::passive_inside_robust`]: `samples` slices over `gamma_samples`
/// configurations, each refined in γ.
pub fn passive_check_cost(samples: usize, gamma_samples: usize, d: usize) -> Cost {
    let gs = (gamma_samples as f64).max(2.0);
    let n = (samples as f64).max(3.0);
    Cost {
        seconds: sweeps(n * (gs + REFINEMENT_SWEEPS), d),
        memory: gs * CONFIG_BYTES + n * SLICE_BYTES,
    }
}

/// Number of plants a robust K_max search samples: masses × dampings × stiffnesses (as a
/// float, so that absurd sample counts do not overflow).
pub fn box_plants(mass_samples: usize, damping_samples: usize, stiffness_samples: usize) -> f64 {
    (mass_samples.max(1) as f64)
        * (damping_samples.max(1) as f64)
        * (stiffness_samples.max(1) as f64)
}

/// Cost of [`crate::paper::nyquist::robust_kmax`]: a scan of `beta_samples` dampings over every
/// sampled plant, then a golden-section search over B whose every step refines the
/// stiffness.
pub fn robust_kmax_cost(plants: f64, beta_samples: usize, d: usize) -> Cost {
    let n = (beta_samples as f64).max(8.0);
    let scan = n * plants;
    let refine = REFINEMENT_SWEEPS * (plants + REFINEMENT_SWEEPS);
    Cost {
        seconds: sweeps(scan + refine, d),
        memory: plants * CONFIG_BYTES + n * SLICE_BYTES,
    }
}

/// Interval sweeps of the geometric β scan of one validity point at most: from
/// [`crate::paper::linear::VALIDITY_BETA_START`] = 1e-7 by 1 % steps up to β ≈ 1 (ln 10⁷ / ln 1.01
/// ≈ 1620) and the bisection after it (about 45 halvings).
pub const VALIDITY_SCAN_SWEEPS: f64 = 1700.0;

/// Cost of [`crate::paper::linear::validity_points`] for `levels` error levels: one scan and
/// bisection per level, at most.
pub fn validity_points_cost(levels: usize, d: usize) -> Cost {
    Cost {
        seconds: sweeps(levels as f64 * VALIDITY_SCAN_SWEEPS, d),
        memory: levels as f64 * SLICE_BYTES,
    }
}

/// Cost of a stability map ([`crate::paper::map::compute_map`]) of `points` grid points of the
/// paper's loop at delay d: [`map_cost_of_degree`] at n = d + 3 with every point stable
/// (the most a map can cost).
pub fn map_cost(points: f64, d: usize, radius: bool) -> Cost {
    map_cost_of_degree(points, d + 3, radius, 1.0)
}

/// Cost of a stability map of `points` grid points whose p(z) has degree n, of which the
/// fraction `stable` is stable: one Schur–Cohn test per point, O(n²) at a stable point, and
/// about [`UNSTABLE_TEST_FRACTION`] of that at an unstable one (the recursion stops at the
/// first reflection coefficient of modulus 1 or more); or with `radius` one spectral radius
/// per point, [`MAP_RADIUS_SECONDS_PER_N2`]·n². One byte per point for the verdicts and
/// eight more for the radii.
pub fn map_cost_of_degree(points: f64, n: usize, radius: bool, stable: f64) -> Cost {
    let nf = n as f64;
    let per_point = if radius {
        ROOTS_SECONDS + MAP_RADIUS_SECONDS_PER_N2 * nf * nf
    } else {
        let share = stable + (1.0 - stable) * UNSTABLE_TEST_FRACTION;
        POINT_TEST_SECONDS + POINT_TEST_SECONDS_PER_N2 * nf * nf * share
    };
    Cost {
        seconds: points * per_point,
        memory: points * if radius { 9.0 } else { 1.0 },
    }
}

/// The degree of a loop's parts without the plant's pure delay z^k (the largest of P0's
/// core, PK and PB): what one evaluation of p on the unit circle costs.
pub fn core_degree(fam: &crate::closed_loop::AffineFamily) -> usize {
    fam.p0_core
        .len()
        .max(fam.pk.len())
        .max(fam.pb.len())
        .saturating_sub(1)
}

/// Cost of the roots of a polynomial of degree n by Aberth–Ehrlich
/// ([`crate::stability::roots`], what `check` reports): [`ROOTS_SECONDS`] +
/// [`ROOTS_SECONDS_PER_N2`]·n² (O(n²) per sweep, a number of sweeps that hardly grows with n).
pub fn roots_cost(n: usize) -> Cost {
    let nf = n as f64;
    Cost {
        seconds: ROOTS_SECONDS + ROOTS_SECONDS_PER_N2 * nf * nf,
        memory: 64.0 * (nf + 1.0),
    }
}

/// Cost of one exact stable interval of the stiffness at one damping
/// ([`crate::boundary::stable_stiffness_intervals`]) for p(z) of degree n.
pub fn interval_cost(n: usize) -> Cost {
    Cost {
        seconds: (n as f64 + 1.0) * SWEEP_SECONDS_PER_DEGREE,
        memory: 64.0 * (n as f64 + 1.0),
    }
}

/// Cost of a robust K_max over a box ([`crate::robust::robust_kmax`]) for p(z) of degree n:
/// each sampled, refined and folded-in plant one exact stable interval (the discretization
/// counted as three more), each verified plant one point test. n is the largest degree over
/// the box ([`crate::robust::box_degree`]), not the given loop's alone: a box over the delay
/// or the period changes it.
pub fn robust_box_cost(n: usize, params: usize, opts: &crate::robust::RobustOptions) -> Cost {
    use crate::robust::{MAX_CORNER_PARAMS, REFINE_BUDGET, REFINE_STARTS, VERIFY_ROUNDS};
    let corners = if params <= MAX_CORNER_PARAMS {
        1usize << params
    } else {
        0
    };
    let solved = (opts.samples + corners + (REFINE_STARTS + VERIFY_ROUNDS) * REFINE_BUDGET) as f64;
    let one = interval_cost(n);
    Cost {
        seconds: one.seconds * (4.0 * solved + (VERIFY_ROUNDS * opts.verify) as f64),
        memory: one.memory * opts.verify.max(1) as f64,
    }
}

/// Cost of P(stable) over `samples` operators ([`crate::population`]) for p(z) of degree n:
/// each operator one exact stable interval with its discretization (counted as three more),
/// and the draws and intervals kept.
pub fn population_cost(n: usize, samples: usize) -> Cost {
    Cost {
        seconds: 4.0 * interval_cost(n).seconds * samples as f64,
        memory: 96.0 * samples as f64,
    }
}

/// Cost of the stability margins of one stable wall ([`crate::margins::margins`]) for p(z)
/// of degree n whose parts without the plant's pure delay have degree `core`: the phase
/// margin and the two gain margins scan [`MARGIN_GRID_PER_DEGREE`]·(n + 1) frequencies, each
/// an O(core) evaluation; the delay margin's fraction table evaluates
/// [`MARGIN_FRACTION_PARTS`] parts on a grid of the core's degree;
/// the delay scan (where the exact solve does not confirm) takes about [`DELAY_SCAN_STEPS`] steps and ends at its own work bound,
/// [`DELAY_SCAN_SECONDS`], and its bisection tests about
/// [`DELAY_BISECTION_TESTS`] delays with the O(n²) point test.
pub fn margins_cost(n: usize, core: usize) -> Cost {
    let (nf, cf) = (n as f64 + 1.0, core as f64 + 1.0);
    let grid = MARGIN_GRID_PER_DEGREE * nf * cf * CIRCLE_EVAL_SECONDS;
    let gain = MARGIN_GRID_PER_DEGREE * MARGIN_FRACTION_PARTS * cf * cf * CIRCLE_EVAL_SECONDS;
    let test = POINT_TEST_SECONDS_PER_N2 * nf * nf;
    let scan = (DELAY_SCAN_STEPS * (grid + test)).min(DELAY_SCAN_SECONDS);
    let bisection = DELAY_BISECTION_TESTS * test;
    Cost {
        seconds: MARGIN_SCANS * grid + gain + scan + bisection,
        memory: 64.0 * MARGIN_GRID_PER_DEGREE * nf,
    }
}

/// Cost of `check` at one wall for p(z) of degree n (core degree `core`, see
/// [`margins_cost`]): the roots and the verdict, the stable stiffness interval at the wall's
/// damping (twice for the paper's loop: in N/m and normalized), and the margins when the wall
/// is stable.
pub fn check_cost(n: usize, core: usize, stable: bool) -> Cost {
    let base = roots_cost(n).then(interval_cost(n)).then(interval_cost(n));
    if stable {
        base.then(margins_cost(n, core))
    } else {
        base
    }
}

/// Cost of the passive region of one loop ([`crate::passivity`]) for p(z) of degree n with
/// parts of degree `core`: a frequency scan and refinement that grow as n², and as n·core
/// with the evaluation of the parts.
pub fn passivity_cost(n: usize, core: usize) -> Cost {
    let nf = n as f64;
    let evals = PASSIVITY_SECONDS_PER_N_CORE * nf * core as f64;
    Cost {
        seconds: PASSIVITY_SECONDS + PASSIVITY_SECONDS_PER_N2 * nf * nf + evals,
        memory: 64.0 * MARGIN_GRID_PER_DEGREE * (nf + 1.0),
    }
}

/// Cost of one point of a K_max sweep ([`crate::sweep::sweep_param`]) for p(z) of degree n
/// (parts of degree `core`):
/// a stable region at the sweep's coarser tolerance and the passive K_max.
pub fn sweep_point_cost(n: usize, core: usize) -> Cost {
    let r = region_cost_of_degree(n, core);
    Cost {
        seconds: r.seconds * SWEEP_REGION_FACTOR,
        memory: r.memory,
    }
    .then(passivity_cost(n, core))
}

/// Cost of one exact stable region ([`crate::region::stable_region`]) of the paper's loop at
/// delay d: [`region_cost_of_degree`] at n = d + 3 with parts of degree 3.
pub fn region_cost(d: usize) -> Cost {
    region_cost_of_degree(d + 3, 3)
}

/// Cost of one exact stable region of a loop whose p(z) has degree n and whose parts without
/// the plant's pure delay have degree `core` (see [`AffineFamily::degree`] and its `p0_core`):
/// the complex-root curve is sampled at O(n) points per slice over O(n) slices, each
/// evaluation O(core), so the time is [`REGION_SECONDS`] +
/// [`REGION_SECONDS_PER_N2_CORE`]·n²·(core + [`REGION_CORE_OFFSET`]); the memory is the
/// engine's own bound, [`crate::region::MAX_CURVE_POINTS`] points, past which it ends with
/// an error.
///
/// [`AffineFamily::degree`]: crate::closed_loop::AffineFamily::degree
pub fn region_cost_of_degree(n: usize, core: usize) -> Cost {
    let n = n as f64;
    let core = core as f64 + REGION_CORE_OFFSET;
    Cost {
        seconds: REGION_SECONDS + REGION_SECONDS_PER_N2_CORE * n * n * core,
        memory: crate::region::MAX_CURVE_POINTS as f64 * REGION_BYTES_PER_POINT,
    }
}

/// Cost of forming the exact families of `plants` plants of a map over γ or δ
/// ([`PLANT_FAMILY_SECONDS`] each; [`crate::paper::map::MapSpec::plants`]).
pub fn plants_cost(plants: f64) -> Cost {
    Cost {
        seconds: plants * PLANT_FAMILY_SECONDS,
        memory: 0.0,
    }
}

/// Cost of the verdict, roots and spectral radius at one point of the paper's loop at delay
/// d (degree n = d + 3): [`roots_cost`].
pub fn point_cost(d: usize) -> Cost {
    roots_cost(d + 3)
}

/// Cost of a simulation of `samples` samples at delay d recording `rows` trace rows: a
/// fixed time per sample ([`SIMULATION_SECONDS_PER_SAMPLE`]); the memory of the trace and
/// of the d + 3 states.
pub fn simulation_cost(samples: f64, d: usize, rows: f64) -> Cost {
    let states = d as f64 + 3.0;
    Cost {
        seconds: samples * SIMULATION_SECONDS_PER_SAMPLE,
        memory: rows * TRACE_ROW_BYTES + states * 64.0,
    }
}

/// The degree of a loop's p(z) without discretizing it: the plant's order, the actuator lag,
/// the velocity filter's order and the delay (one more for a fraction of a sample), as
/// [`crate::AffineFamily::degree`] counts them.
pub fn loop_degree(lp: &crate::model::Loop) -> usize {
    use crate::model::{PlantModel, VelocityEstimator};
    let plant = match &lp.plant.model {
        PlantModel::MassSpringDamper(_) => 2,
        PlantModel::TwoMass(_) => 4,
        PlantModel::TransferFunction { den, .. } => den.len().saturating_sub(1),
    };
    let lag = usize::from(lp.plant.force_lag > 0.0);
    let filter = match &lp.velocity {
        VelocityEstimator::Backward | VelocityEstimator::LowPass { .. } => 1,
        VelocityEstimator::Butterworth { order, .. }
        | VelocityEstimator::Bessel { order, .. }
        | VelocityEstimator::CriticallyDamped { order, .. } => order + 1,
        VelocityEstimator::Average { samples } => *samples,
        VelocityEstimator::Iir { b, a } => b.len().max(a.len()).saturating_sub(1),
    };
    let fraction = usize::from(lp.delay.fraction > 0.0);
    plant + lag + filter + lp.delay.samples + fraction
}

/// A K_max sweep ([`crate::sweep::sweep_param`]): per point a stable region (or one interval
/// at a given damping) and a passive K_max of the loop at that value, whose cost grows as
/// the square of its p(z)'s degree; values the loop refuses are left out (the sweep ends
/// with their message before any analysis).
pub fn sweep_cost(
    base: &crate::model::Loop,
    param: crate::sweep::SweepParam,
    values: &[f64],
    at: crate::sweep::KmaxAt,
) -> Cost {
    let mut cost = Cost::ZERO;
    for &v in values {
        let Ok(lp) = param.apply(base, v) else {
            continue;
        };
        let n = loop_degree(&lp);
        let core = n.saturating_sub(lp.delay.samples);
        let one = match at {
            crate::sweep::KmaxAt::Damping { .. } => interval_cost(n).then(passivity_cost(n, core)),
            _ => sweep_point_cost(n, core),
        };
        cost = Cost {
            seconds: cost.seconds + one.seconds,
            memory: cost.memory.max(one.memory),
        };
    }
    cost
}

/// The Z-width of one loop ([`crate::zwidth::zwidth`]) with a table of `rows` dampings: its
/// stable and passive regions and the table's intervals.
pub fn zwidth_cost(fam: &crate::closed_loop::AffineFamily, rows: usize) -> Cost {
    let (n, core) = (fam.degree(), core_degree(fam));
    let region = region_cost_of_degree(n, core);
    let table = interval_cost(n);
    Cost {
        seconds: region.seconds * ZWIDTH_REGIONS,
        memory: region.memory,
    }
    .then(passivity_cost(n, core))
    .then(Cost {
        seconds: table.seconds * rows as f64,
        memory: table.memory,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn budgets_refuse_huge_inputs_and_nan() {
        let c = robust_kmax_cost(box_plants(5, 3, 10_000_000), 97, 0);
        let e = Budget::COMMAND_LINE.check(c).unwrap_err();
        assert_eq!(e.resource, Resource::Memory, "{e}");
        assert!(e.to_string().contains("GB"), "{e}");
        // the default search fits easily
        let c = robust_kmax_cost(box_plants(5, 3, 33), 97, 0);
        assert!(Budget::COMMAND_LINE.check(c).is_ok(), "{c:?}");
        assert!(c.seconds > 0.5 && c.seconds < 10.0, "{c:?}");
        // sample counts near usize::MAX do not overflow and are refused
        let c = gamma_sweep_cost(usize::MAX, usize::MAX, MAX_DELAY);
        assert!(Budget::COMMAND_LINE.check(c).is_err());
        let nan = Cost {
            seconds: f64::NAN,
            memory: 0.0,
        };
        assert!(Budget::INTERACTIVE.check(nan).is_err());
    }

    #[test]
    fn costs_scale_with_samples_and_degree() {
        let a = robust_region_cost(10, 64, 0, false, 2);
        let b = robust_region_cost(20, 64, 0, false, 2);
        let c = robust_region_cost(10, 64, 12, false, 2);
        assert!((b.seconds / a.seconds - 2.0).abs() < 1e-12);
        assert!((c.seconds / a.seconds - 4.0).abs() < 1e-12);
        let m1 = map_cost(1e6, 0, false);
        let m2 = map_cost(1e6, 20, true);
        assert!(m2.seconds > 10.0 * m1.seconds && m2.memory == 9.0 * m1.memory);
        let s = Cost::ZERO.then(a).then(c);
        assert_eq!(s.seconds, a.seconds + c.seconds);
        assert_eq!(s.memory, a.memory.max(c.memory));
    }

    #[test]
    fn costs_follow_what_the_work_grows_with() {
        // the margins of a stable wall dominate a long filter's check, not its delay
        let filter = check_cost(2003, 2001, true).seconds;
        let delay = check_cost(2003, 3, true).seconds;
        assert!(filter > 100.0 * delay, "{filter} vs {delay}");
        assert!(check_cost(2003, 3, false).seconds < delay);
        // a region grows with the degree of the parts at the same total degree
        assert!(region_cost_of_degree(1003, 1001).seconds > 50.0 * region_cost(1000).seconds);
        // an unstable point costs a small part of a stable one's full test
        let (all, none) = (
            map_cost_of_degree(1e4, 1003, false, 1.0).seconds,
            map_cost_of_degree(1e4, 1003, false, 0.0).seconds,
        );
        assert!(none < 0.1 * all && none > 0.0);
        // the radius map at d = 2000 is minutes, not hours
        let r = map_cost(1e4, 2000, true).seconds;
        assert!(r > MAX_COMMAND_SECONDS && r < 3600.0, "{r}");
    }

    #[test]
    fn messages_use_readable_units() {
        assert_eq!(duration(30.0), "30.00 s");
        assert_eq!(duration(600.0), "10 min");
        assert_eq!(duration(1e20), "more than a century");
        assert_eq!(bytes(3.7e9), "3.7 GB");
        assert_eq!(bytes(2048.0), "2.0 kB");
    }
}
