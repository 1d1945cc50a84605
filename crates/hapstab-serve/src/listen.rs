//! The connection loop of `hapstab serve`: hyper's HTTP/1.1 server connection (hyper-util's
//! tokio runtime glue and graceful shutdown) with
//!
//! - a connection limit: at most [`Transport::max_connections`] open at once, each holding
//!   one slot of a semaphore; beyond it new connections wait in the listen queue;
//! - a header-read timeout: a client that has not sent its whole request head within
//!   [`Transport::header_read_timeout`] gets a JSON 408 and is closed, so slow clients
//!   cannot keep slots;
//! - the head check of [`crate::head`] (sizes and syntax, JSON 400/414/431);
//! - one request per connection (no keep-alive: every request passes the head check), and a
//!   cap on a connection's whole life, so a client that never reads its answer cannot keep
//!   a slot either.

use std::future::Future;
use std::io::Cursor;
use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;

use axum::Router;
use axum::http::StatusCode;
use hyper::body::Incoming;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::server::graceful::{GracefulShutdown, Watcher};
use hyper_util::service::TowerToHyperService;
use tokio::io::AsyncReadExt;
use tokio::net::{TcpListener, TcpSocket, TcpStream};
use tokio::sync::Semaphore;
use tower::ServiceExt;

use crate::head::{HeadError, HeadLimits, read_head, refuse};

/// The transport limits of the server.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Transport {
    /// Connections open at once.
    pub max_connections: usize,
    /// Time to send the whole request head.
    pub header_read_timeout: Duration,
    /// Longest life of one connection.
    pub connection_lifetime: Duration,
    /// Sizes of the request head.
    pub head: HeadLimits,
    /// Bytes read and discarded after a refusal before closing.
    pub drain_bytes: u64,
}

/// A listening socket on `addr` with a queue of `backlog` pending connections (address reuse
/// on, so that a restarted server can bind at once).
pub(crate) fn bind(addr: SocketAddr, backlog: u32) -> std::io::Result<TcpListener> {
    let socket = if addr.is_ipv4() {
        TcpSocket::new_v4()?
    } else {
        TcpSocket::new_v6()?
    };
    socket.set_reuseaddr(true)?;
    socket.bind(addr)?;
    socket.listen(backlog)
}

/// Serves `app` on `listener` until `shutdown` resolves; then waits up to `grace` for open
/// connections to finish.
pub(crate) async fn serve(
    listener: TcpListener,
    app: Router,
    t: Transport,
    shutdown: impl Future<Output = ()>,
    grace: Duration,
) {
    let slots = Arc::new(Semaphore::new(t.max_connections.max(1)));
    let graceful = GracefulShutdown::new();
    let mut shutdown = std::pin::pin!(shutdown);
    loop {
        let permit = tokio::select! {
            p = slots.clone().acquire_owned() => match p {
                Ok(p) => p,
                Err(_) => break,
            },
            _ = &mut shutdown => break,
        };
        let stream = tokio::select! {
            r = listener.accept() => match r {
                Ok((s, _)) => s,
                Err(_) => {
                    // out of file descriptors or a connection reset while queued: wait a
                    // moment instead of spinning
                    tokio::time::sleep(Duration::from_millis(20)).await;
                    continue;
                }
            },
            _ = &mut shutdown => break,
        };
        let app = app.clone();
        let watcher = graceful.watcher();
        tokio::spawn(async move {
            let _permit = permit;
            connection(stream, app, t, watcher).await;
        });
    }
    drop(listener);
    let _ = tokio::time::timeout(grace, graceful.shutdown()).await;
}

/// One connection: the head check under the header-read timeout, then hyper with one
/// request, all within the connection's lifetime.
async fn connection(stream: TcpStream, app: Router, t: Transport, watcher: Watcher) {
    let _ = stream.set_nodelay(true);
    let (mut rd, mut wr) = stream.into_split();
    let head = match tokio::time::timeout(t.header_read_timeout, read_head(&mut rd, &t.head)).await
    {
        Ok(Ok(bytes)) => bytes,
        Ok(Err(HeadError::Closed)) => return,
        Ok(Err(HeadError::Refused(status, msg))) => {
            refuse(&mut rd, &mut wr, status, &msg, t.drain_bytes).await;
            return;
        }
        Err(_) => {
            let msg = format!(
                "request head not received within {} ms",
                t.header_read_timeout.as_millis()
            );
            refuse(&mut rd, &mut wr, StatusCode::REQUEST_TIMEOUT, &msg, 0).await;
            return;
        }
    };
    let io = tokio::io::join(Cursor::new(head).chain(rd), wr);
    let service = TowerToHyperService::new(
        app.map_request(|req: axum::http::Request<Incoming>| req.map(axum::body::Body::new)),
    );
    let conn = hyper::server::conn::http1::Builder::new()
        .timer(TokioTimer::new())
        .header_read_timeout(t.header_read_timeout)
        .keep_alive(false)
        .max_buf_size((2 * t.head.max_head_bytes).max(8192))
        .serve_connection(TokioIo::new(io), service);
    let _ = tokio::time::timeout(t.connection_lifetime, watcher.watch(conn)).await;
}

/// Elsewhere than on Unix the connection limit is taken as asked.
#[cfg(not(unix))]
pub fn connection_capacity(wanted: usize) -> usize {
    wanted.max(1)
}

/// Raises the soft limit of open files to the hard limit (connections are files) and
/// returns the number of connections that fit: the soft limit less a reserve for the
/// process's own files, at most `wanted`.
#[cfg(unix)]
pub(crate) fn connection_capacity(wanted: usize) -> usize {
    /// Files kept free for the process itself (binary, libraries, pipes, the listener).
    const RESERVE: u64 = 64;
    let mut lim = libc::rlimit {
        rlim_cur: 0,
        rlim_max: 0,
    };
    // SAFETY: getrlimit/setrlimit with a valid pointer to a local struct.
    let soft = unsafe {
        if libc::getrlimit(libc::RLIMIT_NOFILE, &mut lim) != 0 {
            return wanted.min(1024 - RESERVE as usize);
        }
        let target = lim.rlim_max.min(wanted as u64 + RESERVE);
        if lim.rlim_cur < target {
            let raised = libc::rlimit {
                rlim_cur: target,
                rlim_max: lim.rlim_max,
            };
            if libc::setrlimit(libc::RLIMIT_NOFILE, &raised) == 0 {
                lim.rlim_cur = target;
            }
        }
        lim.rlim_cur
    };
    (soft.saturating_sub(RESERVE) as usize).clamp(1, wanted.max(1))
}
