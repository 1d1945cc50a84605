//! Loopback load test of `hapstab serve` (a test binary of its own, so no other test competes
//! for the CPU): 2 000 slow clients that keep sending partial request heads, and 200 heavy
//! requests within the limits, all at once. The server must keep answering `/api/limits`
//! within 100 ms and stay under 1 GB of resident memory. Bounded: about ten seconds, every
//! connection to 127.0.0.1 only, and everything stops by itself.
//! Run with `--nocapture` to see the figures.

mod serve_support;

use std::io::{ErrorKind, Read, Write};
use std::net::TcpStream;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Barrier};
use std::thread;
use std::time::{Duration, Instant};

use serve_support::{Server, peak_rss_bytes, proc_status_bytes, request};

/// Slow clients held open at once.
const SLOW: usize = 2000;
/// Heavy requests sent at once.
const HEAVY: usize = 200;
/// How long the probes run.
const PROBE_TIME: Duration = Duration::from_secs(8);
/// The acceptance bounds.
const MAX_LATENCY: Duration = Duration::from_millis(100);
const MAX_RSS: u64 = 1 << 30;

/// Raises this process's open-file limit to its hard limit (each client is a file).
fn raise_open_files() {
    let mut lim = libc::rlimit {
        rlim_cur: 0,
        rlim_max: 0,
    };
    // SAFETY: getrlimit/setrlimit with a valid pointer to a local struct.
    unsafe {
        if libc::getrlimit(libc::RLIMIT_NOFILE, &mut lim) == 0 && lim.rlim_cur < lim.rlim_max {
            lim.rlim_cur = lim.rlim_max;
            libc::setrlimit(libc::RLIMIT_NOFILE, &lim);
        }
    }
}

/// A slow client: connected, a partial request head sent, non-blocking.
fn slow_client(port: u16) -> Option<TcpStream> {
    let mut s = TcpStream::connect(("127.0.0.1", port)).ok()?;
    s.write_all(b"GET /api/limits HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ")
        .ok()?;
    s.set_nonblocking(true).ok()?;
    Some(s)
}

/// Keeps `n` slow clients open until `stop`: each sends one more byte of its never-ending
/// header about every half second; one that the server answers or closes is replaced.
/// Returns how many were replaced.
fn slow_clients(port: u16, n: usize, ready: Arc<AtomicUsize>, stop: Arc<AtomicBool>) -> usize {
    let mut clients: Vec<Option<TcpStream>> = Vec::with_capacity(n);
    for _ in 0..n {
        clients.push(slow_client(port));
        ready.fetch_add(1, Ordering::SeqCst);
    }
    let mut replaced = 0;
    let mut buf = [0u8; 1024];
    while !stop.load(Ordering::SeqCst) {
        for c in clients.iter_mut() {
            let alive = match c {
                Some(s) => match s.read(&mut buf) {
                    Err(e) if e.kind() == ErrorKind::WouldBlock => s.write_all(b"a").is_ok(),
                    _ => false, // answered (408), closed or reset
                },
                None => false,
            };
            if !alive {
                *c = slow_client(port);
                replaced += 1;
            }
        }
        thread::sleep(Duration::from_millis(500));
    }
    replaced
}

/// A heavy request within the limits: large delays, robust regions, long simulations and
/// large exports.
fn heavy_path(i: usize) -> String {
    let de = 0.005 + 0.0001 * i as f64;
    match i % 4 {
        0 => format!("/api/region?gamma=0.001&delta={de}&d={}", 150 + i % 50),
        1 => format!(
            "/api/region?gamma=0&delta={}&d=3&robust=1&gamma_lo=0&gamma_hi=9&gamma_samples=32&beta_samples=128",
            0.5 + 0.01 * i as f64
        ),
        2 => format!("/api/simulate?gamma=0.001&delta={de}&d=10&alpha=0.01&beta=0.1&samples=20000"),
        _ => format!("/api/export?gamma=0.001&delta={de}&d=100&format=svg&width=4000&height=4000"),
    }
}

#[test]
fn slow_clients_and_heavy_requests_leave_the_server_responsive_and_small() {
    raise_open_files();
    let s = Server::start(&[]);
    let (port, pid) = (s.port, s.pid());
    let stop = Arc::new(AtomicBool::new(false));
    let ready = Arc::new(AtomicUsize::new(0));
    let slow = {
        let (stop, ready) = (stop.clone(), ready.clone());
        thread::spawn(move || slow_clients(port, SLOW, ready, stop))
    };
    let t = Instant::now();
    while ready.load(Ordering::SeqCst) < SLOW && t.elapsed() < Duration::from_secs(30) {
        thread::sleep(Duration::from_millis(10));
    }
    assert_eq!(
        ready.load(Ordering::SeqCst),
        SLOW,
        "slow clients not connected"
    );
    // the heavy clients' threads exist before the probes start (creating 200 threads is the
    // test's own cost, not the server's); a barrier releases their requests all at once
    let go = Arc::new(Barrier::new(HEAVY + 1));
    let heavy: Vec<_> = (0..HEAVY)
        .map(|i| {
            let go = go.clone();
            thread::spawn(move || {
                go.wait();
                request(port, "GET", &heavy_path(i), &[]).status
            })
        })
        .collect();
    go.wait();
    let mut latencies = Vec::new();
    let mut rss_max = 0;
    let t0 = Instant::now();
    while t0.elapsed() < PROBE_TIME {
        let t = Instant::now();
        let r = request(port, "GET", "/api/limits", &[]);
        latencies.push(t.elapsed());
        if t.elapsed() > MAX_LATENCY / 2 {
            println!(
                "slow probe at {:.2} s: {:?}",
                (t - t0).as_secs_f64(),
                t.elapsed()
            );
        }
        assert_eq!(r.status, 200, "{}", r.body);
        rss_max = rss_max.max(proc_status_bytes(pid, "VmRSS"));
        thread::sleep(Duration::from_millis(50));
    }
    stop.store(true, Ordering::SeqCst);
    let replaced = slow.join().expect("slow clients");
    let statuses: Vec<u16> = heavy
        .into_iter()
        .map(|h| h.join().expect("heavy"))
        .collect();
    let ok = statuses.iter().filter(|&&st| st == 200).count();
    let busy = statuses.iter().filter(|&&st| st == 503).count();
    let hwm = peak_rss_bytes(pid);
    latencies.sort();
    let max = latencies[latencies.len() - 1];
    println!(
        "{SLOW} slow clients ({replaced} cut off by the header timeout and replaced), {HEAVY} heavy requests ({ok} answered, {busy} busy): \
         /api/limits over {} probes: median {:.1} ms, max {:.1} ms; server RSS max {:.0} MB, peak (VmHWM) {:.0} MB",
        latencies.len(),
        latencies[latencies.len() / 2].as_secs_f64() * 1e3,
        max.as_secs_f64() * 1e3,
        rss_max as f64 / 1e6,
        hwm as f64 / 1e6
    );
    assert!(
        statuses.iter().all(|&st| st == 200 || st == 503),
        "{statuses:?}"
    );
    assert!(ok > 0, "no heavy request was answered: {statuses:?}");
    assert!(max < MAX_LATENCY, "slowest /api/limits took {max:?}");
    assert!(hwm < MAX_RSS, "peak RSS {hwm} bytes");
    assert_eq!(s.get("/api/limits").status, 200);
}
