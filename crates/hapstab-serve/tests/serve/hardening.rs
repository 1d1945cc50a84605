//! Hostile requests to `hapstab serve`: every Host case and every oversized or malformed
//! request is refused with the right status and a JSON body, slow clients are cut off by
//! the header-read timeout, and requests whose estimated cost is beyond one request's budget
//! are refused before they start.

use crate::serve_support;

use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::{Duration, Instant};

use serve_support::{Response, Server, raw_request, request};

/// The status and the JSON error message of a response (panics when the body is not a JSON
/// object with an "error" string).
fn json_error(r: &Response) -> (u16, String) {
    assert!(
        r.header("content-type")
            .is_some_and(|c| c.starts_with("application/json")),
        "{} without a JSON content type: {:?}",
        r.status,
        r.headers
    );
    let msg = r.json()["error"]
        .as_str()
        .unwrap_or_else(|| panic!("no error string: {}", r.body))
        .to_string();
    (r.status, msg)
}

#[test]
fn host_header_must_be_one_loopback_authority_of_this_server() {
    let s = Server::start(&[]);
    let port = s.port;
    let get = |head: &str| raw_request(port, format!("{head}\r\n\r\n").as_bytes());
    // accepted: loopback names and addresses, with this port or none
    for host in [
        format!("127.0.0.1:{port}"),
        "localhost".to_string(),
        format!("LOCALHOST:{port}"),
        format!("[::1]:{port}"),
        "127.0.0.2".to_string(),
    ] {
        let r = get(&format!(
            "GET /api/limits HTTP/1.1\r\nHost: {host}\r\nConnection: close"
        ));
        assert_eq!(r.status, 200, "{host}: {}", r.body);
    }
    // (head, status, words the message must contain)
    let cases: Vec<(String, u16, &str)> = vec![
        (
            "GET /api/limits HTTP/1.1\r\nConnection: close".into(),
            400,
            "missing Host",
        ),
        ("GET /api/limits HTTP/1.0".into(), 400, "missing Host"),
        (
            format!("GET /api/limits HTTP/1.1\r\nHost: localhost:{port}\r\nHost: evil.example"),
            400,
            "2 Host headers",
        ),
        (
            format!("GET /api/limits HTTP/1.1\r\nHost: localhost:{port}\r\nHost: localhost:{port}"),
            400,
            "exactly one",
        ),
        (
            "GET /api/limits HTTP/1.1\r\nHost: evil.example".into(),
            403,
            "evil.example",
        ),
        (
            "GET /api/limits HTTP/1.1\r\nHost: localhost.evil.example".into(),
            403,
            "localhost.evil.example",
        ),
        (
            "GET /api/limits HTTP/1.1\r\nHost: 192.168.1.1".into(),
            403,
            "192.168.1.1",
        ),
        (
            "GET /api/limits HTTP/1.1\r\nHost: localhost:1".into(),
            403,
            "port 1",
        ),
        (
            "GET /api/limits HTTP/1.1\r\nHost: user@localhost".into(),
            400,
            "malformed Host",
        ),
        (
            format!("GET http://evil.example/api/limits HTTP/1.1\r\nHost: localhost:{port}"),
            403,
            "request target",
        ),
        (
            format!("GET http://localhost:1/api/limits HTTP/1.1\r\nHost: localhost:{port}"),
            403,
            "port 1",
        ),
    ];
    for (head, status, words) in &cases {
        let r = get(head);
        let (st, msg) = json_error(&r);
        assert_eq!(st, *status, "{head:?}: {msg}");
        assert!(msg.contains(words), "{head:?}: '{msg}' lacks '{words}'");
    }
    // the absolute form naming this server is fine
    let r = get(&format!(
        "GET http://127.0.0.1:{port}/api/limits HTTP/1.1\r\nHost: 127.0.0.1:{port}"
    ));
    assert_eq!(r.status, 200, "{}", r.body);
}

#[test]
fn oversized_and_malformed_requests_get_json_errors() {
    let s = Server::start(&[]);
    let port = s.port;
    for (req, status, words) in &oversized_and_malformed_requests(&s) {
        let r = raw_request(port, req.as_bytes());
        let (st, msg) = json_error(&r);
        let shown = &req[..req.len().min(60)];
        assert_eq!(st, *status, "{shown:?}: {msg}");
        assert!(msg.contains(words), "{shown:?}: '{msg}' lacks '{words}'");
    }
    // a body within the limit is fine, and so is the server after all of the above
    let host = host_lines(port);
    let r = raw_request(
        port,
        format!("GET /api/limits HTTP/1.1\r\n{host}Content-Length: 3\r\n\r\nabc").as_bytes(),
    );
    assert_eq!(r.status, 200, "{}", r.body);
    // other methods and paths stay JSON too
    let (st, _) = json_error(&request(port, "DELETE", "/api/region", &[]));
    assert_eq!(st, 405);
}

/// The Host and Connection header lines of a request to this server.
fn host_lines(port: u16) -> String {
    format!("Host: 127.0.0.1:{port}\r\nConnection: close\r\n")
}

/// Requests beyond the server's limits (read from `/api/limits`) or malformed: (request,
/// status, words of the message).
fn oversized_and_malformed_requests(s: &Server) -> Vec<(String, u16, &'static str)> {
    let port = s.port;
    let l = s.get("/api/limits").json();
    let max_uri = l["uri_bytes_max"].as_u64().unwrap() as usize;
    let max_head = l["head_bytes_max"].as_u64().unwrap() as usize;
    let max_headers = l["headers_max"].as_u64().unwrap() as usize;
    let max_body = l["body_bytes_max"].as_u64().unwrap() as usize;
    let host = host_lines(port);
    let pad = |n: usize| "a".repeat(n);
    let many: String = (0..=max_headers)
        .map(|i| format!("X-Field-{i}: 1\r\n"))
        .collect();
    vec![
        (
            format!("GET /api/limits?x={} HTTP/1.1\r\n{host}\r\n", pad(max_uri)),
            414,
            "request target too long",
        ),
        (
            format!("GET /{} HTTP/1.1\r\n{host}\r\n", pad(100_000)),
            414,
            "request target too long",
        ),
        (
            format!(
                "GET /api/limits HTTP/1.1\r\n{host}X-Big: {}\r\n\r\n",
                pad(max_head)
            ),
            431,
            "request head larger",
        ),
        (
            format!(
                "GET /api/limits HTTP/1.1\r\n{host}X-Big: {}\r\n\r\n",
                pad(300_000)
            ),
            431,
            "request head larger",
        ),
        (
            format!("GET /api/limits HTTP/1.1\r\n{host}{many}\r\n"),
            431,
            "too many header fields",
        ),
        (
            format!(
                "GET /api/limits HTTP/1.1\r\n{host}Content-Length: {}\r\n\r\n",
                max_body + 1
            ),
            413,
            "request body larger",
        ),
        (
            format!("GET /api/limits HTTP/1.1\r\n{host}no colon here\r\n\r\n"),
            400,
            "malformed HTTP request",
        ),
        (
            "\u{1}\u{2}\u{3} / HTTP/1.1\r\n\r\n".to_string(),
            400,
            "malformed HTTP request",
        ),
        (
            format!("GET /api/limits HTTP/7.0\r\n{host}\r\n"),
            400,
            "malformed HTTP request",
        ),
    ]
}

#[test]
fn a_slow_client_gets_a_json_408_and_is_closed() {
    let s = Server::start(&["--header-timeout-ms", "300"]);
    let mut c = TcpStream::connect(("127.0.0.1", s.port)).unwrap();
    c.write_all(b"GET /api/limits HTTP/1.1\r\nHost: local")
        .unwrap();
    let t = Instant::now();
    c.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    let mut answer = String::new();
    c.read_to_string(&mut answer).unwrap();
    let waited = t.elapsed();
    assert!(answer.starts_with("HTTP/1.1 408"), "{answer}");
    assert!(answer.contains("\"error\""), "{answer}");
    assert!(
        waited >= Duration::from_millis(250) && waited < Duration::from_secs(3),
        "{waited:?}"
    );
    assert_eq!(s.get("/api/limits").status, 200);
}

#[test]
fn requests_beyond_one_requests_budget_are_refused_naming_the_parameter() {
    let s = Server::start(&[]);
    let l = s.get("/api/limits").json();
    assert_eq!(l["job_seconds_max"], hapstab::limits::MAX_JOB_SECONDS);
    assert_eq!(l["job_memory_max_bytes"], hapstab::limits::MAX_JOB_MEMORY);
    // within every per-parameter range, but the product is too much work for one request
    let r = s.get(
        "/api/region?gamma=0&delta=1&d=50&robust=1&gamma_lo=0&gamma_hi=9&gamma_samples=64&beta_samples=64&refine=1",
    );
    let (st, msg) = json_error(&r);
    assert_eq!(st, 400, "{msg}");
    assert_eq!(r.json()["parameter"], "gamma_samples", "{msg}");
    assert!(msg.contains("64 × 64") && msg.contains("limit"), "{msg}");
    let r = s.get(
        "/api/region?gamma=0&delta=1&d=50&robust=1&gamma_lo=0&gamma_hi=9&gamma_samples=8&beta_samples=256&refine=1",
    );
    assert_eq!(r.json()["parameter"], "beta_samples", "{}", r.body);
    // the estimate is no excuse for refusing ordinary requests
    let r = s.get(
        "/api/region?gamma=0&delta=1&d=2&robust=1&gamma_lo=0&gamma_hi=9&gamma_samples=17&beta_samples=64",
    );
    assert_eq!(r.status, 200, "{}", r.body);
}

#[test]
fn extreme_in_limit_region_is_answered_or_refused_within_memory() {
    // Inside /api/limits (γ ≤ 1000, δ ≤ 100, d ≤ 200), and hard for the region engine, which
    // bounds its own curve sampling: the answer is a 200 or a JSON refusal (the engine's
    // honest error, or the computation's time limit), and the server stays small.
    let s = Server::start(&[]);
    let t = Instant::now();
    let r = s.get("/api/region?mode=normalized&gamma=967.8197089101616&delta=100&d=100");
    assert!(
        r.status == 200 || r.status == 400 || r.status == 503,
        "{}",
        r.body
    );
    assert!(r.json().is_object());
    // the computation's time limit is 10 s
    assert!(t.elapsed() < Duration::from_secs(15), "{:?}", t.elapsed());
    let rss = serve_support::peak_rss_bytes(s.pid());
    assert!(rss < 1 << 30, "peak RSS {rss} bytes");
}
