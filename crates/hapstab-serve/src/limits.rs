//! The limits of the interactive explorer. They keep one request cheap enough that no request
//! can take the server down; `/api/limits` reports them and the page states them. The
//! estimated time and memory of each computation are checked against
//! `hapstab::limits::Budget::INTERACTIVE`, shared with the library; the transport limits
//! below (connections, timeouts, sizes) belong to the HTTP server alone.

use serde::Serialize;

/// Largest delay d in samples (the library allows more; interactive use is bounded).
pub(crate) const MAX_D: usize = 200;
/// Largest normalized physical stiffness γ (Section VIII needs up to π² + δ²/4).
pub(crate) const MAX_GAMMA: f64 = 1000.0;
/// Largest normalized physical damping δ.
pub(crate) const MAX_DELTA: f64 = 100.0;
/// Largest |α| and |β| of a clicked point.
pub(crate) const MAX_WALL: f64 = 1e6;
/// Physical mode: largest mass in kg.
pub(crate) const MAX_MASS: f64 = 1e4;
/// Physical mode: largest damping in Ns/m.
pub(crate) const MAX_PHYS_DAMPING: f64 = 1e7;
/// Physical mode: largest arm stiffness in N/m.
pub(crate) const MAX_PHYS_STIFFNESS: f64 = 1e9;
/// Physical mode: the sampling periods the library accepts, in s.
pub(crate) use hapstab::model::{MAX_PERIOD, MIN_PERIOD};
/// Smallest and largest relative simplification tolerance of drawn polygons.
pub(crate) const MIN_TOL: f64 = 0.0;
pub(crate) const MAX_TOL: f64 = 0.01;
/// Default relative simplification tolerance (0.2 px on a 1000 px plot).
pub(crate) const DEFAULT_TOL: f64 = 2e-4;
/// Robust region: γ samples.
pub(crate) const MIN_ROBUST_GAMMA_SAMPLES: usize = 2;
pub(crate) const MAX_ROBUST_GAMMA_SAMPLES: usize = 64;
pub(crate) const DEFAULT_ROBUST_GAMMA_SAMPLES: usize = 17;
/// Robust region: β slices.
pub(crate) const MIN_ROBUST_BETA_SAMPLES: usize = 8;
pub(crate) const MAX_ROBUST_BETA_SAMPLES: usize = 256;
pub(crate) const DEFAULT_ROBUST_BETA_SAMPLES: usize = 64;
/// Robust region: largest d.
pub(crate) const MAX_ROBUST_D: usize = 50;
/// Robust region: rounds of adaptive β refinement of the outline.
pub(crate) const ROBUST_REFINE_BETA_ROUNDS: usize = 2;
/// Robust K_max over a box: largest uniform samples and verified plants (the estimated
/// cost refuses most requests before these).
pub(crate) const MAX_BOX_SAMPLES: usize = 100_000;
pub(crate) const MAX_BOX_VERIFY: usize = 1_000_000;
/// Simulation: samples.
pub(crate) const MIN_SIM_SAMPLES: usize = 10;
pub(crate) const MAX_SIM_SAMPLES: usize = 20_000;
/// Simulation: horizon in samples up to which a run is extended until its verdict settles
/// (the library's default, as for `hapstab simulate`).
pub(crate) const SIM_HORIZON: usize = hapstab::simulation::DEFAULT_MAX_SAMPLES;
/// Simulation: largest number of trace rows returned.
pub(crate) const MAX_TRACE_POINTS: usize = 2000;
/// Simulation: largest |push force| in N and |initial velocity| in m/s.
pub(crate) const MAX_PUSH: f64 = 1e6;
pub(crate) const MAX_VELOCITY: f64 = 1e3;
/// Sweep (`/api/sweep`): largest number of points.
pub(crate) const MAX_SWEEP_POINTS: usize = 1000;
/// Map (`/api/map`): largest number of points along one axis.
pub(crate) const MAX_MAP_AXIS_POINTS: usize = 1000;
/// Z-width (`/api/zwidth`): largest number of dampings in the K_max table.
pub(crate) const MAX_TABLE_DAMPINGS: usize = 200;
/// Export plot size in px.
pub(crate) const MIN_EXPORT_PX: usize = 200;
pub(crate) const MAX_EXPORT_PX: usize = 4000;
/// Heavy computations running at once; more wait up to [`QUEUE_WAIT_MS`] for a slot.
pub(crate) const MAX_JOBS: usize = 4;
/// How long a request waits for a free computation slot before a 503.
pub(crate) const QUEUE_WAIT_MS: u64 = 3000;
/// Time limit of one computation before a 503 (the work finishes in the background but
/// keeps its slot, so the number of running computations stays bounded).
pub(crate) const COMPUTE_TIMEOUT_MS: u64 = 10_000;

/// Connections open at once; more wait in the listen queue until one closes (bounded also
/// by the open-file limit of the process, which the server raises to its hard limit).
pub(crate) const MAX_CONNECTIONS: usize = 4096;
/// Connections the kernel queues before the server accepts them: enough for a burst of
/// clients reconnecting at once (a full queue drops connection attempts, which clients
/// retry only after a second); Linux caps it at `net.core.somaxconn`.
pub(crate) const LISTEN_BACKLOG: u32 = 4096;
/// Time a client has to send its whole request head before a 408 and closing: slow or idle
/// clients cannot keep connection slots for longer.
pub(crate) const HEADER_READ_TIMEOUT_MS: u64 = 5000;
/// Time limit of a whole request, from its head to its answer (503 beyond): the wait for a
/// computation slot plus the computation's own limit, with 2 s to spare.
pub(crate) const REQUEST_TIMEOUT_MS: u64 = QUEUE_WAIT_MS + COMPUTE_TIMEOUT_MS + 2000;
/// Longest life of one connection (one request): the request's limit plus 15 s to send the
/// answer to a slow reader.
pub(crate) const CONNECTION_LIFETIME_MS: u64 = REQUEST_TIMEOUT_MS + 15_000;
/// Largest request target (path and query) in bytes (414 beyond); the longest query the page
/// sends is under 600 bytes.
pub(crate) const MAX_URI_BYTES: usize = 4096;
/// Largest request head (request line and header fields) in bytes (431 beyond).
pub(crate) const MAX_HEAD_BYTES: usize = 16 * 1024;
/// Most header fields of a request (431 beyond).
pub(crate) const MAX_HEADERS: usize = 64;
/// Largest request body in bytes (413 beyond): every endpoint is a GET without a body.
pub(crate) const MAX_BODY_BYTES: usize = 1024;
/// Bytes read and discarded after refusing a request head before the connection is closed,
/// so that the client reads the refusal instead of a reset.
pub(crate) const DRAIN_BYTES: u64 = 1 << 20;

/// A parameter of a robust K_max box.
#[derive(Serialize)]
pub(crate) struct BoxParam {
    pub name: &'static str,
    pub unit: &'static str,
}

/// The limits as JSON (`GET /api/limits`).
#[derive(Serialize)]
pub(crate) struct Limits {
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
    pub robust_refine_beta_rounds: usize,
    /// The parameters a robust K_max box may range over (`sweep --param`'s names) and
    /// their units.
    pub robust_box_params: Vec<BoxParam>,
    pub robust_box_samples: [usize; 2],
    pub robust_box_verify: [usize; 2],
    pub sim_samples: [usize; 2],
    /// Points of a sweep (`/api/sweep`'s `n`).
    pub sweep_points: [usize; 2],
    /// Points along one axis of a map (`/api/map`'s `x` and `y`).
    pub map_axis_points: [usize; 2],
    /// Dampings of a Z-width's K_max table (`/api/zwidth`'s `table_damping`).
    pub zwidth_table_dampings_max: usize,
    pub sim_horizon_samples: usize,
    pub sim_trace_points_max: usize,
    pub export_px: [usize; 2],
    pub concurrent_jobs: usize,
    pub queue_wait_ms: u64,
    pub compute_timeout_ms: u64,
    /// Largest estimated computing time of one request, core-seconds
    /// (`hapstab::limits::MAX_JOB_SECONDS`).
    pub job_seconds_max: f64,
    /// Largest estimated memory of one request, bytes (`hapstab::limits::MAX_JOB_MEMORY`).
    pub job_memory_max_bytes: f64,
    pub connections_max: usize,
    pub header_read_timeout_ms: u64,
    pub request_timeout_ms: u64,
    pub connection_lifetime_ms: u64,
    pub uri_bytes_max: usize,
    pub head_bytes_max: usize,
    pub headers_max: usize,
    pub body_bytes_max: usize,
}

/// The current limits.
pub(crate) fn limits() -> Limits {
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
        robust_refine_beta_rounds: ROBUST_REFINE_BETA_ROUNDS,
        robust_box_params: hapstab::sweep::SweepParam::ALL
            .iter()
            .map(|p| BoxParam {
                name: p.name(),
                unit: p.unit(),
            })
            .collect(),
        robust_box_samples: [0, MAX_BOX_SAMPLES],
        robust_box_verify: [0, MAX_BOX_VERIFY],
        sim_samples: [MIN_SIM_SAMPLES, MAX_SIM_SAMPLES],
        sweep_points: [2, MAX_SWEEP_POINTS],
        map_axis_points: [2, MAX_MAP_AXIS_POINTS],
        zwidth_table_dampings_max: MAX_TABLE_DAMPINGS,
        sim_horizon_samples: SIM_HORIZON,
        sim_trace_points_max: MAX_TRACE_POINTS,
        export_px: [MIN_EXPORT_PX, MAX_EXPORT_PX],
        concurrent_jobs: MAX_JOBS,
        queue_wait_ms: QUEUE_WAIT_MS,
        compute_timeout_ms: COMPUTE_TIMEOUT_MS,
        job_seconds_max: hapstab::limits::MAX_JOB_SECONDS,
        job_memory_max_bytes: hapstab::limits::MAX_JOB_MEMORY,
        connections_max: MAX_CONNECTIONS,
        header_read_timeout_ms: HEADER_READ_TIMEOUT_MS,
        request_timeout_ms: REQUEST_TIMEOUT_MS,
        connection_lifetime_ms: CONNECTION_LIFETIME_MS,
        uri_bytes_max: MAX_URI_BYTES,
        head_bytes_max: MAX_HEAD_BYTES,
        headers_max: MAX_HEADERS,
        body_bytes_max: MAX_BODY_BYTES,
    }
}
