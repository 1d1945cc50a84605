//! Shared helpers of the `hapstab serve` tests: start the real server on an ephemeral loopback
//! port and talk HTTP/1.1 to it with the standard library only.
//!
//! The server is this crate's `hapstab-serve` (the explorer alone, with the flags of
//! `hapstab serve`) in hapstab-serve's tests, and `hapstab serve` itself in hapstab-cli's
//! tests, which include this module to compare the explorer with the command line.

#![allow(dead_code)]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use hapstab::PlantParams;
use hapstab::paper::NormalizedFamily;
use hapstab::region::stable_region;

/// The server's command: this crate's `hapstab-serve`, or `hapstab serve` where the `hapstab`
/// binary is the crate's own (hapstab-cli).
fn server_command() -> Command {
    match (
        option_env!("CARGO_BIN_EXE_hapstab-serve"),
        option_env!("CARGO_BIN_EXE_hapstab"),
    ) {
        (Some(explorer), _) => Command::new(explorer),
        (None, Some(cli)) => {
            let mut c = Command::new(cli);
            c.arg("serve");
            c
        }
        (None, None) => panic!("no server binary: neither hapstab-serve nor hapstab is built"),
    }
}

/// A running `hapstab serve --port 0`; killed on drop.
pub struct Server {
    child: Child,
    pub port: u16,
    /// The line the server printed on startup ("hapstab serve: listening on http://…").
    pub listening: String,
}

/// The server's command with arguments, as [`Server::start`] runs it (to see it refuse).
pub fn server_with(args: &[&str]) -> Command {
    let mut c = server_command();
    c.args(args);
    c
}

impl Server {
    /// Starts the server with extra arguments and waits for its "listening on" line.
    pub fn start(extra: &[&str]) -> Server {
        let mut child = server_command()
            .args(["--port", "0"])
            .args(extra)
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("start hapstab serve");
        let stdout = child.stdout.take().expect("stdout");
        let mut line = String::new();
        BufReader::new(stdout)
            .read_line(&mut line)
            .expect("read the listening line");
        let port = line
            .rsplit(':')
            .next()
            .and_then(|s| s.split('/').next())
            .and_then(|s| s.trim().parse::<u16>().ok())
            .unwrap_or_else(|| panic!("no port in {line:?}"));
        assert!(
            line.contains("http://127.0.0.1:"),
            "binds loopback by default: {line}"
        );
        Server {
            child,
            port,
            listening: line,
        }
    }

    /// The server's process id.
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// The base URL.
    pub fn base(&self) -> String {
        format!("http://127.0.0.1:{}", self.port)
    }

    /// GET a path.
    pub fn get(&self, path: &str) -> Response {
        request(self.port, "GET", path, &[])
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// An HTTP response.
#[derive(Debug)]
pub struct Response {
    pub status: u16,
    pub headers: Vec<(String, String)>,
    pub body: String,
}

impl Response {
    /// A header value (case-insensitive name).
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.as_str())
    }

    /// The body as JSON.
    pub fn json(&self) -> serde_json::Value {
        serde_json::from_str(&self.body).unwrap_or_else(|e| {
            panic!("not JSON ({e}): {}", &self.body[..self.body.len().min(300)])
        })
    }
}

/// One HTTP/1.1 request with `Connection: close`.
pub fn request(port: u16, method: &str, path: &str, headers: &[(&str, &str)]) -> Response {
    let mut s = TcpStream::connect(("127.0.0.1", port)).expect("connect");
    s.set_read_timeout(Some(Duration::from_secs(60))).ok();
    let mut req = format!("{method} {path} HTTP/1.1\r\nConnection: close\r\n");
    if !headers.iter().any(|(k, _)| k.eq_ignore_ascii_case("host")) {
        req.push_str(&format!("Host: 127.0.0.1:{port}\r\n"));
    }
    for (k, v) in headers {
        req.push_str(&format!("{k}: {v}\r\n"));
    }
    req.push_str("\r\n");
    s.write_all(req.as_bytes()).expect("send");
    read_response(s)
}

/// Sends `bytes` as they are and reads the answer.
pub fn raw_request(port: u16, bytes: &[u8]) -> Response {
    let mut s = TcpStream::connect(("127.0.0.1", port)).expect("connect");
    s.set_read_timeout(Some(Duration::from_secs(60))).ok();
    s.write_all(bytes).expect("send");
    read_response(s)
}

/// Reads one HTTP/1.1 response.
fn read_response(mut s: TcpStream) -> Response {
    // Read the headers, then Content-Length bytes if given (some servers keep the
    // connection open), else to the end.
    let mut raw = Vec::new();
    let mut buf = [0u8; 16384];
    let split = loop {
        if let Some(p) = raw.windows(4).position(|w| w == b"\r\n\r\n") {
            break p;
        }
        let n = s.read(&mut buf).expect("read");
        assert!(n > 0, "connection closed before the end of the headers");
        raw.extend_from_slice(&buf[..n]);
    };
    let length = String::from_utf8_lossy(&raw[..split])
        .lines()
        .filter_map(|l| l.split_once(':'))
        .find(|(k, _)| k.trim().eq_ignore_ascii_case("content-length"))
        .and_then(|(_, v)| v.trim().parse::<usize>().ok());
    match length {
        Some(len) => {
            while raw.len() < split + 4 + len {
                let n = s.read(&mut buf).expect("read");
                if n == 0 {
                    break;
                }
                raw.extend_from_slice(&buf[..n]);
            }
        }
        None => {
            s.read_to_end(&mut raw).expect("read");
        }
    }
    let head = String::from_utf8_lossy(&raw[..split]).to_string();
    let mut body = raw[split + 4..].to_vec();
    let mut lines = head.lines();
    let status: u16 = lines
        .next()
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|c| c.parse().ok())
        .expect("status");
    let headers: Vec<(String, String)> = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_string(), v.trim().to_string()))
        .collect();
    let chunked = headers.iter().any(|(k, v)| {
        k.eq_ignore_ascii_case("transfer-encoding") && v.eq_ignore_ascii_case("chunked")
    });
    if chunked {
        body = dechunk(&body);
    }
    Response {
        status,
        headers,
        body: String::from_utf8(body).expect("UTF-8 body"),
    }
}

fn dechunk(mut b: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    while let Some(eol) = b.windows(2).position(|w| w == b"\r\n") {
        let size_str = String::from_utf8_lossy(&b[..eol]);
        let size = usize::from_str_radix(size_str.split(';').next().unwrap_or("0").trim(), 16)
            .unwrap_or(0);
        b = &b[eol + 2..];
        if size == 0 || b.len() < size {
            break;
        }
        out.extend_from_slice(&b[..size]);
        b = &b[(size + 2).min(b.len())..];
    }
    out
}

/// The raw JSON number after the first `"key":` that follows `after` in `text`, parsed exactly
/// by Rust's float parser (serde_json's default parser may be off by one ulp).
pub fn raw_number(text: &str, after: &str, key: &str) -> f64 {
    let start = text.find(after).unwrap_or_else(|| panic!("no {after}"));
    let pat = format!("\"{key}\":");
    let at = text[start..]
        .find(&pat)
        .unwrap_or_else(|| panic!("no {key} after {after}"))
        + start
        + pat.len();
    let tok: String = text[at..]
        .chars()
        .take_while(|c| !matches!(c, ',' | '}' | ']'))
        .collect();
    if tok.trim() == "null" {
        return f64::NAN;
    }
    tok.trim()
        .parse()
        .unwrap_or_else(|_| panic!("not a number: {tok}"))
}

/// Percent-encodes a query value (enough for numbers and words).
pub fn enc(s: &str) -> String {
    s.bytes()
        .map(|b| match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'.' | b'_' | b'~' => {
                (b as char).to_string()
            }
            _ => format!("%{b:02X}"),
        })
        .collect()
}

/// A field of /proc/PID/status in bytes (VmRSS: resident now, VmHWM: peak resident).
pub fn proc_status_bytes(pid: u32, field: &str) -> u64 {
    let text = std::fs::read_to_string(format!("/proc/{pid}/status")).expect("/proc status");
    text.lines()
        .find_map(|l| l.strip_prefix(field)?.strip_prefix(':'))
        .and_then(|v| v.split_whitespace().next()?.parse::<u64>().ok())
        .map(|kb| kb * 1024)
        .unwrap_or_else(|| panic!("no {field} in /proc/{pid}/status"))
}

/// Peak resident memory of a process in bytes.
pub fn peak_rss_bytes(pid: u32) -> u64 {
    proc_status_bytes(pid, "VmHWM")
}

// ---------------------------------------------------------------------------------------
// Shared by the endpoint tests (`tests/serve/api_*.rs`).
// ---------------------------------------------------------------------------------------

/// The paper's plant of most API tests, as a query.
pub const PLANT: &str = "gamma=0.001&delta=0.015&d=1";

/// The library's exact stable region of (γ, δ, d).
pub fn library_region(gamma: f64, delta: f64, d: usize) -> hapstab::region::StableRegion {
    stable_region(&NormalizedFamily::new(PlantParams::new(gamma, delta).unwrap(), d).unwrap())
        .unwrap()
}

/// The paper's loop in physical units with the command line's default device and arm, d = 1.
pub const PAPER_LOOP: &str = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&d=1";

/// A two-mass device held by the default arm, with an actuator lag, a low-pass velocity and a
/// fractional delay (t_d = 1.4 T): a loop beyond the paper's.
pub const TWO_MASS_LOOP: &str = "mode=physical&motor_mass=0.05&handle_mass=0.05&transmission_stiffness=5000&transmission_damping=1&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&delay_time=0.0014&estimator=lowpass%3A150&force_lag=0.0002";
