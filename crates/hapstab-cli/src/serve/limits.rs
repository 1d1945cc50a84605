//! The limits of the interactive explorer. They keep one request cheap enough that no request
//! can take the server down; `/api/limits` reports them and the page states them.

use serde::Serialize;

/// Largest delay d in samples (the library allows more; interactive use is bounded).
pub const MAX_D: usize = 200;
/// Largest normalized physical stiffness γ (Section VIII needs up to π² + δ²/4).
pub const MAX_GAMMA: f64 = 1000.0;
/// Largest normalized physical damping δ.
pub const MAX_DELTA: f64 = 100.0;
/// Largest |α| and |β| of a clicked point.
pub const MAX_WALL: f64 = 1e6;
/// Physical mode: largest mass in kg.
pub const MAX_MASS: f64 = 1e4;
/// Physical mode: largest damping in Ns/m.
pub const MAX_PHYS_DAMPING: f64 = 1e7;
/// Physical mode: largest arm stiffness in N/m.
pub const MAX_PHYS_STIFFNESS: f64 = 1e9;
/// Physical mode: smallest sampling period in s.
pub const MIN_PERIOD: f64 = 1e-7;
/// Physical mode: largest sampling period in s.
pub const MAX_PERIOD: f64 = 1.0;
/// Smallest and largest relative simplification tolerance of drawn polygons.
pub const MIN_TOL: f64 = 0.0;
pub const MAX_TOL: f64 = 0.01;
/// Default relative simplification tolerance (0.2 px on a 1000 px plot).
pub const DEFAULT_TOL: f64 = 2e-4;
/// Robust region: γ samples.
pub const MIN_ROBUST_GAMMA_SAMPLES: usize = 2;
pub const MAX_ROBUST_GAMMA_SAMPLES: usize = 64;
pub const DEFAULT_ROBUST_GAMMA_SAMPLES: usize = 17;
/// Robust region: β slices.
pub const MIN_ROBUST_BETA_SAMPLES: usize = 8;
pub const MAX_ROBUST_BETA_SAMPLES: usize = 256;
pub const DEFAULT_ROBUST_BETA_SAMPLES: usize = 64;
/// Robust region: largest d.
pub const MAX_ROBUST_D: usize = 50;
/// Robust region: largest γ-samples × β-slices × (d + 4) (× 4 with γ refinement), about the
/// number of per-β D-decomposition sweeps (each 256 unit-circle evaluations) it costs.
pub const MAX_ROBUST_WORK: usize = 120_000;
/// Simulation: samples.
pub const MIN_SIM_SAMPLES: usize = 10;
pub const MAX_SIM_SAMPLES: usize = 20_000;
/// Simulation: horizon in samples up to which a run is extended until its verdict settles
/// (the library's default, as for `hapstab simulate`).
pub const SIM_HORIZON: usize = hapstab::simulation::DEFAULT_MAX_SAMPLES;
/// Simulation: largest number of trace rows returned.
pub const MAX_TRACE_POINTS: usize = 2000;
/// Simulation: largest |push force| in N and |initial velocity| in m/s.
pub const MAX_PUSH: f64 = 1e6;
pub const MAX_VELOCITY: f64 = 1e3;
/// Export plot size in px.
pub const MIN_EXPORT_PX: usize = 200;
pub const MAX_EXPORT_PX: usize = 4000;
/// Heavy computations running at once; more wait up to [`QUEUE_WAIT_MS`] for a slot.
pub const MAX_JOBS: usize = 4;
/// How long a request waits for a free computation slot before a 503.
pub const QUEUE_WAIT_MS: u64 = 3000;
/// Time limit of one computation before a 503 (the work finishes in the background but
/// keeps its slot, so the number of running computations stays bounded).
pub const COMPUTE_TIMEOUT_MS: u64 = 10_000;

/// The limits as JSON (`GET /api/limits`).
#[derive(Serialize)]
pub struct Limits {
    pub d_max: usize,
    pub gamma_max: f64,
    pub delta_max: f64,
    pub wall_abs_max: f64,
    pub mass_max_kg: f64,
    pub damping_max_ns_per_m: f64,
    pub stiffness_max_n_per_m: f64,
    pub period_min_s: f64,
    pub period_max_s: f64,
    pub tol_max: f64,
    pub tol_default: f64,
    pub robust_gamma_samples: [usize; 2],
    pub robust_beta_samples: [usize; 2],
    pub robust_d_max: usize,
    pub robust_work_max: usize,
    pub sim_samples: [usize; 2],
    pub sim_horizon_samples: usize,
    pub sim_trace_points_max: usize,
    pub export_px: [usize; 2],
    pub concurrent_jobs: usize,
    pub queue_wait_ms: u64,
    pub compute_timeout_ms: u64,
}

/// The current limits.
pub fn limits() -> Limits {
    Limits {
        d_max: MAX_D,
        gamma_max: MAX_GAMMA,
        delta_max: MAX_DELTA,
        wall_abs_max: MAX_WALL,
        mass_max_kg: MAX_MASS,
        damping_max_ns_per_m: MAX_PHYS_DAMPING,
        stiffness_max_n_per_m: MAX_PHYS_STIFFNESS,
        period_min_s: MIN_PERIOD,
        period_max_s: MAX_PERIOD,
        tol_max: MAX_TOL,
        tol_default: DEFAULT_TOL,
        robust_gamma_samples: [MIN_ROBUST_GAMMA_SAMPLES, MAX_ROBUST_GAMMA_SAMPLES],
        robust_beta_samples: [MIN_ROBUST_BETA_SAMPLES, MAX_ROBUST_BETA_SAMPLES],
        robust_d_max: MAX_ROBUST_D,
        robust_work_max: MAX_ROBUST_WORK,
        sim_samples: [MIN_SIM_SAMPLES, MAX_SIM_SAMPLES],
        sim_horizon_samples: SIM_HORIZON,
        sim_trace_points_max: MAX_TRACE_POINTS,
        export_px: [MIN_EXPORT_PX, MAX_EXPORT_PX],
        concurrent_jobs: MAX_JOBS,
        queue_wait_ms: QUEUE_WAIT_MS,
        compute_timeout_ms: COMPUTE_TIMEOUT_MS,
    }
}
