//! The explorer of `hapstab serve`: a local web server drawing the exact stable region live.
//! [`run`] serves until Ctrl-C with the options of [`ServeArgs`] (the command's flags).
//!
//! One self-contained page (inline JavaScript and CSS, no network access, embedded in the
//! binary) and a JSON API backed by the library:
//!
//! | endpoint | answer |
//! |---|---|
//! | `GET /` | the page |
//! | `GET /api/limits` | the limits below |
//! | `GET /api/region` | exact stable region (Section V), α_max, linear condition (23), passive region (28, d = 0), optional robust region over a γ range, or in physical mode over the arm's stiffness k_H (Section VIII); with `box=NAME:LO:HI,…` (physical units, any loop) the robust K_max over that box at `wall_damping`, as `hapstab kmax --robust --box … --json` |
//! | `GET /api/point` | verdict, spectral radius and roots of p(z) at one (α, β) |
//! | `GET /api/simulate` | a short simulated wall contact at one (α, β) |
//! | `GET /api/kmax` | K_max of a physical loop at `wall_damping`, over `damping_lo`..`damping_hi`, or over every damping, as `hapstab kmax --json` |
//! | `GET /api/sweep` | K_max against `param` from `lo` to `hi` in `n` points, as `hapstab sweep --json` |
//! | `GET /api/zwidth` | the Z-width of a physical loop, as `hapstab zwidth --json` |
//! | `GET /api/map` | the grid method over (K, B) of any loop or two of α, β, γ, δ, as `hapstab map --json` with the grid |
//! | `GET /api/passivity` | the passivity of one wall and the passive region, as `hapstab passivity --json` |
//! | `GET /api/export` | the current view as SVG, CSV or JSON |
//!
//! Every parameter is validated; bad input is HTTP 400 with `{"error": ...}` naming the
//! parameter and the value. Each computation's time and memory are estimated before it
//! starts and refused beyond `hapstab::limits::Budget::INTERACTIVE`; computations run on the
//! blocking pool, at most `limits::MAX_JOBS` at once, each under a time limit, so no
//! request can stall the server.
//!
//! The transport is hardened as well (`listen`): a connection limit, a header-read
//! timeout, one request per connection, size limits of the request head (`head`) and body,
//! a time limit per request, and strict Host validation (`host`). Every refusal, at any
//! layer, has a JSON body.
//!
//! What the command line shares with the explorer lives here too: the JSON text of every
//! answer ([`json`]), the robust K_max over a box ([`robust_box`]) and the split of a loop
//! file's plant into device and arm ([`loop_io::remainder`]).

#![deny(missing_docs)]
#![warn(unreachable_pub)]

mod api;
mod export;
mod head;
mod host;
mod limits;
mod listen;
pub mod loop_io;
mod query;
#[cfg(test)]
mod query_props;
pub mod robust_box;

use std::net::{IpAddr, SocketAddr};
use std::sync::Arc;
use std::time::Duration;

use axum::Router;
use axum::extract::rejection::QueryRejection;
use axum::extract::{Query, Request, State};
use axum::http::{HeaderValue, StatusCode, header};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use clap::Args;
use serde::Serialize;
use tokio::sync::Semaphore;
use tower_http::limit::RequestBodyLimitLayer;
use tower_http::timeout::TimeoutLayer;

use query::{ApiError, Params};

/// The page, embedded at build time: index.html with the robust K_max overlay's script
/// inlined at its marker (one self-contained page; the script is kept in its own file).
static INDEX_HTML: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| {
    include_str!("../assets/index.html").replace(
        "/*@robust_kmax.js*/",
        include_str!("../assets/robust_kmax.js"),
    )
});

/// The options of the explorer: the flags of `hapstab serve`.
#[derive(Args, Debug)]
pub struct ServeArgs {
    /// TCP port to listen on (0 picks a free port; the address is printed on startup).
    #[arg(long, default_value_t = 8717)]
    port: u16,
    /// Address to bind. The default serves this machine only; anything else exposes the
    /// explorer to the network.
    #[arg(long, default_value = "127.0.0.1")]
    host: IpAddr,
    /// A loop file (the `input.loop` of any `--json` report, the page's "Save loop", Python's
    /// `Loop.save`): the printed address opens the page on that loop and its wall.
    #[arg(long = "loop", value_name = "FILE")]
    loop_file: Option<std::path::PathBuf>,
    /// Time limit of one computation in milliseconds (503 when exceeded).
    #[arg(long, default_value_t = limits::COMPUTE_TIMEOUT_MS, hide = true)]
    timeout_ms: u64,
    /// Computations running at once.
    #[arg(long, default_value_t = limits::MAX_JOBS, hide = true)]
    jobs: usize,
    /// Connections open at once.
    #[arg(long, default_value_t = limits::MAX_CONNECTIONS, hide = true)]
    connections: usize,
    /// Time to send a whole request head in milliseconds (408 when exceeded).
    #[arg(long, default_value_t = limits::HEADER_READ_TIMEOUT_MS, hide = true)]
    header_timeout_ms: u64,
}

/// Shared server state.
#[derive(Clone)]
struct AppState {
    jobs: Arc<Semaphore>,
    max_jobs: usize,
    timeout: Duration,
    queue_wait: Duration,
    /// Which Host headers and request targets are accepted.
    hosts: host::HostPolicy,
}

/// Niceness of the threads that compute (the blocking pool's jobs and rayon's workers): the
/// threads that accept connections and answer cheap requests run at the normal priority, so
/// that the server stays responsive while its computations use every core.
const COMPUTE_NICENESS: i32 = 10;

/// Lowers the CPU priority of the calling thread to [`COMPUTE_NICENESS`] (Linux: niceness is
/// per thread).
fn lower_priority() {
    #[cfg(target_os = "linux")]
    // SAFETY: setpriority on this thread's own id; failure leaves the priority unchanged.
    unsafe {
        libc::setpriority(
            libc::PRIO_PROCESS as _,
            libc::gettid() as _,
            COMPUTE_NICENESS,
        );
    }
}

/// Why the explorer could not serve.
#[derive(Debug, thiserror::Error)]
pub enum ServeError {
    /// The async runtime could not start.
    #[error("cannot start the async runtime")]
    Runtime(#[source] std::io::Error),
    /// The address could not be bound.
    #[error("cannot listen on {addr}")]
    Listen {
        /// The address asked for.
        addr: SocketAddr,
        /// The system's reason.
        #[source]
        source: std::io::Error,
    },
    /// The bound socket's address could not be read.
    #[error("cannot read the listening address")]
    LocalAddr(#[source] std::io::Error),
    /// The loop file given with `--loop` cannot be read or is not a loop.
    #[error("--loop {path}: {message}")]
    LoopFile {
        /// The file as given.
        path: String,
        /// What is wrong with it, in one line.
        message: String,
    },
}

/// The page's query for the loop file of `--loop`, read before anything is bound.
fn loop_query(path: &std::path::Path) -> Result<String, ServeError> {
    let fail = |message: String| ServeError::LoopFile {
        path: path.display().to_string(),
        message,
    };
    let text = std::fs::read_to_string(path).map_err(|e| fail(e.to_string()))?;
    loop_io::open(&text)
        .map(|o| o.query)
        .map_err(|e| fail(e.message))
}

/// Runs the explorer until Ctrl-C: binds the address, prints the URL on standard output
/// ("hapstab serve: listening on http://…/"), and answers every request.
pub fn run(a: &ServeArgs) -> Result<(), ServeError> {
    let query = a.loop_file.as_deref().map(loop_query).transpose()?;
    // rayon's workers do the parallel part of the computations: lower them too (ignored if
    // the global pool already exists)
    let _ = rayon::ThreadPoolBuilder::new()
        .start_handler(|_| lower_priority())
        .build_global();
    let rt = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .max_blocking_threads(4 * a.jobs.max(1) + 4)
        .build()
        .map_err(ServeError::Runtime)?;
    rt.block_on(serve(a, query.as_deref()))
}

async fn serve(a: &ServeArgs, query: Option<&str>) -> Result<(), ServeError> {
    let addr = SocketAddr::new(a.host, a.port);
    let listener = listen::bind(addr, limits::LISTEN_BACKLOG)
        .map_err(|source| ServeError::Listen { addr, source })?;
    let local = listener.local_addr().map_err(ServeError::LocalAddr)?;
    let state = AppState {
        jobs: Arc::new(Semaphore::new(a.jobs.max(1))),
        max_jobs: a.jobs.max(1),
        timeout: Duration::from_millis(a.timeout_ms.max(1)),
        queue_wait: Duration::from_millis(limits::QUEUE_WAIT_MS),
        hosts: host::HostPolicy {
            loopback_only: a.host.is_loopback(),
            port: local.port(),
        },
    };
    let transport = listen::Transport {
        max_connections: listen::connection_capacity(a.connections),
        header_read_timeout: Duration::from_millis(a.header_timeout_ms.max(1)),
        connection_lifetime: Duration::from_millis(limits::CONNECTION_LIFETIME_MS),
        head: head::HeadLimits {
            max_head_bytes: limits::MAX_HEAD_BYTES,
            max_uri_bytes: limits::MAX_URI_BYTES,
            max_headers: limits::MAX_HEADERS,
        },
        drain_bytes: limits::DRAIN_BYTES,
    };
    let host = match local.ip() {
        IpAddr::V6(ip) => format!("[{ip}]"),
        IpAddr::V4(ip) => ip.to_string(),
    };
    let page = query.map_or(String::new(), |q| format!("?{q}"));
    println!(
        "hapstab serve: listening on http://{host}:{}/{page} (Ctrl-C to stop)",
        local.port()
    );
    if !a.host.is_loopback() {
        eprintln!(
            "warning: bound to {} — the explorer is reachable from the network",
            a.host
        );
    }
    use std::io::Write;
    let _ = std::io::stdout().flush();
    if transport.max_connections < a.connections {
        eprintln!(
            "warning: the open-file limit allows {} connections at once (of {})",
            transport.max_connections, a.connections
        );
    }
    let shutdown = async {
        let _ = tokio::signal::ctrl_c().await;
    };
    listen::serve(
        listener,
        router(state),
        transport,
        shutdown,
        Duration::from_secs(2),
    )
    .await;
    Ok(())
}

fn router(state: AppState) -> Router {
    Router::new()
        .route("/", get(index))
        .route("/index.html", get(index))
        .route("/favicon.ico", get(|| async { StatusCode::NO_CONTENT }))
        .route("/api/limits", get(api_limits))
        .route("/api/region", get(api_region))
        .route("/api/point", get(api_point))
        .route("/api/simulate", get(api_simulate))
        .route("/api/kmax", get(api_kmax))
        .route("/api/sweep", get(api_sweep))
        .route("/api/zwidth", get(api_zwidth))
        .route("/api/map", get(api_map))
        .route("/api/passivity", get(api_passivity))
        .route("/api/export", get(api_export))
        .route("/api/open", get(api_open))
        .fallback(not_found)
        .method_not_allowed_fallback(method_not_allowed)
        // innermost first: body limit (413), then the request time limit (503), both with
        // empty bodies that `json_errors` fills; the Host check runs before all of them
        .layer(RequestBodyLimitLayer::new(limits::MAX_BODY_BYTES))
        .layer(TimeoutLayer::with_status_code(
            StatusCode::SERVICE_UNAVAILABLE,
            Duration::from_millis(limits::REQUEST_TIMEOUT_MS),
        ))
        .layer(middleware::map_response(json_errors))
        .layer(middleware::from_fn_with_state(state.clone(), guard))
        .with_state(state)
}

/// Refuses requests for other hosts (DNS rebinding) and sets the security headers of every
/// answer.
async fn guard(State(st): State<AppState>, req: Request, next: Next) -> Response {
    let mut resp = match host::check(st.hosts, req.headers(), req.uri()) {
        Ok(()) => next.run(req).await,
        Err(e) => e.into_response(),
    };
    let h = resp.headers_mut();
    h.insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    h.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    resp
}

/// Gives the error answers of the middleware (body limit, request time limit), which have
/// empty bodies, a JSON body like every other error.
async fn json_errors(resp: Response) -> Response {
    let status = resp.status();
    let is_json = resp
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|c| c.as_bytes().starts_with(b"application/json"));
    if !(status.is_client_error() || status.is_server_error()) || is_json {
        return resp;
    }
    let message = match status {
        StatusCode::PAYLOAD_TOO_LARGE => format!(
            "request body larger than {} bytes: every endpoint is a GET without a body",
            limits::MAX_BODY_BYTES
        ),
        StatusCode::SERVICE_UNAVAILABLE => format!(
            "request exceeded the time limit of {} ms",
            limits::REQUEST_TIMEOUT_MS
        ),
        s => s.canonical_reason().unwrap_or("error").to_string(),
    };
    ApiError::status(status, message).into_response()
}

async fn index() -> Response {
    (
        [
            (header::CONTENT_TYPE, "text/html; charset=utf-8"),
            (
                header::CONTENT_SECURITY_POLICY,
                "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src data: blob:; connect-src 'self'; base-uri 'none'; form-action 'none'",
            ),
        ],
        INDEX_HTML.as_str(),
    )
        .into_response()
}

async fn not_found(req: Request) -> Response {
    ApiError::status(
        StatusCode::NOT_FOUND,
        format!(
            "no such endpoint: {} (endpoints: /, /api/limits, /api/region, /api/point, /api/simulate, /api/kmax, /api/sweep, /api/zwidth, /api/map, /api/passivity, /api/export)",
            req.uri().path().chars().take(80).collect::<String>()
        ),
    )
    .into_response()
}

async fn method_not_allowed() -> Response {
    ApiError::status(
        StatusCode::METHOD_NOT_ALLOWED,
        "only GET is supported".into(),
    )
    .into_response()
}

async fn api_limits() -> Response {
    axum::Json(limits::limits()).into_response()
}

type RawQuery = Result<Query<Vec<(String, String)>>, QueryRejection>;

/// Parses the query string against the allowed names.
fn params(q: RawQuery, allowed: &[&str]) -> Result<Params, ApiError> {
    let Query(pairs) = q.map_err(|e| ApiError::bad(format!("malformed query string: {e}")))?;
    Params::new(pairs, allowed)
}

/// Runs `f` on the blocking pool: waits at most `queue_wait` for one of the job slots, and
/// answers 503 after `timeout` (the computation keeps its slot until it ends, so the number
/// of running computations stays bounded).
async fn run_job<T, F>(st: &AppState, f: F) -> Result<T, ApiError>
where
    T: Send + 'static,
    F: FnOnce() -> Result<T, ApiError> + Send + 'static,
{
    let permit = tokio::time::timeout(st.queue_wait, st.jobs.clone().acquire_owned())
        .await
        .map_err(|_| {
            ApiError::status(
                StatusCode::SERVICE_UNAVAILABLE,
                format!(
                    "server busy: {} computations are running; try again",
                    st.max_jobs
                ),
            )
        })?
        .map_err(|_| {
            ApiError::status(
                StatusCode::SERVICE_UNAVAILABLE,
                "server shutting down".into(),
            )
        })?;
    let handle = tokio::task::spawn_blocking(move || {
        let _permit = permit;
        lower_priority();
        f()
    });
    match tokio::time::timeout(st.timeout, handle).await {
        Err(_) => Err(ApiError::status(
            StatusCode::SERVICE_UNAVAILABLE,
            format!(
                "computation exceeded the time limit of {} ms",
                st.timeout.as_millis()
            ),
        )),
        Ok(Err(e)) => Err(ApiError::status(
            StatusCode::INTERNAL_SERVER_ERROR,
            format!(
                "internal error: the computation failed ({})",
                if e.is_panic() { "panic" } else { "cancelled" }
            ),
        )),
        Ok(Ok(r)) => r,
    }
}

/// A JSON answer with a Server-Timing header; numbers as the command line writes them (−0
/// as 0).
fn json_timed<T: Serialize>(v: &T, ms: f64) -> Response {
    let mut resp = match hapstab::json::compact(v) {
        Ok(body) => ([(header::CONTENT_TYPE, "application/json")], body).into_response(),
        Err(e) => ApiError::status(
            StatusCode::INTERNAL_SERVER_ERROR,
            format!("internal error: JSON encoding failed ({e})"),
        )
        .into_response(),
    };
    if let Ok(h) = HeaderValue::from_str(&format!("compute;dur={ms:.3}")) {
        resp.headers_mut().insert("server-timing", h);
    }
    resp
}

fn respond<T>(r: Result<T, ApiError>, ok: impl FnOnce(T) -> Response) -> Response {
    match r {
        Ok(v) => ok(v),
        Err(e) => e.into_response(),
    }
}

async fn api_region(State(st): State<AppState>, q: RawQuery) -> Response {
    let r = async {
        let p = params(q, &api::region_names())?;
        let req = api::parse_region(&p)?;
        run_job(&st, move || api::region(&req)).await
    }
    .await;
    respond(r, |v| json_timed(&v, v.server_ms.total))
}

async fn api_point(State(st): State<AppState>, q: RawQuery) -> Response {
    let r = async {
        let p = params(q, &api::point_names())?;
        let spec = query::plant_spec(&p)?;
        let at = api::wall_at(&p, &spec)?;
        api::point_budget(&spec)?;
        run_job(&st, move || api::point(&spec, at)).await
    }
    .await;
    respond(r, |v| json_timed(&v, v.server_ms))
}

async fn api_simulate(State(st): State<AppState>, q: RawQuery) -> Response {
    let r = async {
        let p = params(q, &api::simulate_names())?;
        let req = api::parse_simulate(&p)?;
        run_job(&st, move || api::simulate(&req)).await
    }
    .await;
    respond(r, |v| json_timed(&v, v.server_ms))
}

/// An analysis of the command line behind one endpoint: the query's `names`, its parser and
/// its computation, run on the blocking pool; the answer is the command's `--json` object,
/// with the computing time in the Server-Timing header only.
async fn analysis<R, T>(
    st: AppState,
    q: RawQuery,
    names: Vec<&'static str>,
    parse: fn(&Params) -> Result<R, ApiError>,
    compute: fn(&R) -> Result<T, ApiError>,
) -> Response
where
    R: Send + 'static,
    T: Serialize + Send + 'static,
{
    let r = async {
        let p = params(q, &names)?;
        let req = parse(&p)?;
        run_job(&st, move || {
            let t0 = std::time::Instant::now();
            compute(&req).map(|v| (v, t0.elapsed().as_secs_f64() * 1e3))
        })
        .await
    }
    .await;
    respond(r, |(v, ms)| json_timed(&v, ms))
}

async fn api_kmax(State(st): State<AppState>, q: RawQuery) -> Response {
    analysis(st, q, api::kmax_names(), api::parse_kmax, api::kmax).await
}

async fn api_sweep(State(st): State<AppState>, q: RawQuery) -> Response {
    analysis(st, q, api::sweep_names(), api::parse_sweep, api::sweep).await
}

async fn api_zwidth(State(st): State<AppState>, q: RawQuery) -> Response {
    analysis(st, q, api::zwidth_names(), api::parse_zwidth, api::zwidth).await
}

async fn api_map(State(st): State<AppState>, q: RawQuery) -> Response {
    analysis(st, q, api::map_names(), api::parse_map, api::map).await
}

async fn api_passivity(State(st): State<AppState>, q: RawQuery) -> Response {
    let parse = api::parse_passivity;
    analysis(st, q, api::passivity_names(), parse, api::passivity).await
}

/// `/api/open?file=TEXT`: the page's query for a loop file's text.
async fn api_open(q: RawQuery) -> Response {
    let r = params(q, &["file"]).and_then(|p| {
        let text = p
            .raw("file")
            .ok_or_else(|| ApiError::param("file", "", "missing parameter 'file'".into()))?;
        loop_io::open(text)
    });
    respond(r, |v| axum::Json(v).into_response())
}

async fn api_export(State(st): State<AppState>, q: RawQuery) -> Response {
    let r = async {
        let p = params(q, &export::export_names())?;
        let req = export::parse_export(&p)?;
        run_job(&st, move || export::export(&req)).await
    }
    .await;
    respond(r, |(ctype, name, body)| {
        (
            [
                (header::CONTENT_TYPE, ctype.to_string()),
                (
                    header::CONTENT_DISPOSITION,
                    format!("attachment; filename=\"{name}\""),
                ),
            ],
            body,
        )
            .into_response()
    })
}
