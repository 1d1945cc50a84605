//! API tests of `hapstab serve` against the real server on an ephemeral loopback port: every
//! bad input is HTTP 400 with a JSON error naming the parameter and the value, other errors
//! are JSON too, and the server survives timeouts and bursts of concurrent requests.

use crate::serve_support;

use serve_support::{PLANT, Server, TWO_MASS_LOOP, enc, request};

/// A bad request: (path, parameter the message must name, value the message must show).
type Case = (&'static str, &'static str, &'static str);

/// Missing parameters and values that are not finite numbers.
const MISSING_OR_NOT_FINITE: &[Case] = &[
    // missing
    ("/api/region?delta=0.015&d=0", "gamma", ""),
    ("/api/region?gamma=0.001&d=0", "delta", ""),
    ("/api/region?gamma=0.001&delta=0.015", "'d'", ""),
    ("/api/point?gamma=0&delta=0&d=0&beta=0.5", "alpha", ""),
    ("/api/simulate?gamma=0&delta=0&d=0&alpha=0.1", "beta", ""),
    // NaN and infinities
    ("/api/region?gamma=NaN&delta=0.015&d=0", "gamma", "NaN"),
    ("/api/region?gamma=0&delta=nan&d=0", "delta", "nan"),
    ("/api/region?gamma=inf&delta=0&d=0", "gamma", "inf"),
    (
        "/api/point?gamma=0&delta=0&d=0&alpha=NaN&beta=0.5",
        "alpha",
        "NaN",
    ),
    (
        "/api/point?gamma=0&delta=0&d=0&alpha=0.1&beta=-infinity",
        "beta",
        "-infinity",
    ),
    ("/api/region?gamma=0&delta=0&d=NaN", "'d'", "NaN"),
    // not numbers
    ("/api/region?gamma=abc&delta=0&d=0", "gamma", "abc"),
    ("/api/region?gamma=&delta=0&d=0", "gamma", ""),
];

/// Values out of their ranges.
const OUT_OF_RANGE: &[Case] = &[
    // negative
    ("/api/region?gamma=-1&delta=0.015&d=0", "gamma", "-1"),
    ("/api/region?gamma=0&delta=-0.5&d=0", "delta", "-0.5"),
    ("/api/region?gamma=0&delta=0&d=-1", "'d'", "-1"),
    // huge
    ("/api/region?gamma=0&delta=0&d=201", "'d'", "201"),
    ("/api/region?gamma=0&delta=0&d=100000", "'d'", "100000"),
    ("/api/region?gamma=0&delta=0&d=1e300", "'d'", "1e300"),
    (
        "/api/point?gamma=0&delta=0&d=5000&alpha=0.1&beta=0.1",
        "'d'",
        "5000",
    ),
    ("/api/region?gamma=1e9&delta=0&d=0", "gamma", "1e9"),
    (
        "/api/point?gamma=0&delta=0&d=0&alpha=1e300&beta=0.5",
        "alpha",
        "1e300",
    ),
    // fractional delay
    ("/api/region?gamma=0&delta=0&d=1.5", "'d'", "1.5"),
];

/// Unknown and repeated names, oversized grids and sizes.
const NAMES_GRIDS_AND_SIZES: &[Case] = &[
    // unknown and duplicate names
    ("/api/region?gamma=0&delta=0&d=0&gama=1", "gama", "1"),
    ("/api/region?gamma=0&gamma=1&delta=0&d=0", "gamma", "1"),
    // oversized grids and sizes
    (
        "/api/region?gamma=0&delta=1&d=0&robust=1&gamma_lo=0&gamma_hi=9&gamma_samples=100000",
        "gamma_samples",
        "100000",
    ),
    (
        "/api/region?gamma=0&delta=1&d=20&robust=1&gamma_lo=0&gamma_hi=9&gamma_samples=64&beta_samples=256",
        "gamma_samples",
        "64",
    ),
    (
        "/api/region?gamma=0&delta=1&d=60&robust=1&gamma_lo=0&gamma_hi=9",
        "'d'",
        "60",
    ),
    (
        "/api/region?gamma=0&delta=1&d=0&robust=1&gamma_lo=5&gamma_hi=1",
        "gamma_hi",
        "1",
    ),
    (
        "/api/region?gamma=0&delta=1&d=0&gamma_lo=0",
        "gamma_lo",
        "0",
    ),
    ("/api/region?gamma=0&delta=0&d=0&tol=5", "tol", "5"),
    (
        "/api/simulate?gamma=0&delta=0&d=0&alpha=0.1&beta=0.5&samples=10000000",
        "samples",
        "10000000",
    ),
    (
        "/api/simulate?gamma=0&delta=0&d=0&alpha=0.1&beta=0.5&contact=sticky",
        "contact",
        "sticky",
    ),
    (
        "/api/export?gamma=0&delta=0&d=0&format=pdf",
        "format",
        "pdf",
    ),
    (
        "/api/export?gamma=0&delta=0&d=0&view=1,0,0,1",
        "view",
        "1,0,0,1",
    ),
    (
        "/api/export?gamma=0&delta=0&d=0&width=100000",
        "width",
        "100000",
    ),
];

/// The physical mode's parameters, an unknown mode, and a physical parameter in normalized
/// mode.
const MODES: &[Case] = &[
    (
        "/api/region?mode=physical&device_mass=0&device_damping=1&arm_mass=0&arm_damping=1&arm_stiffness=0&period=0.001&d=0",
        "device_mass",
        "0",
    ),
    (
        "/api/region?mode=physical&device_mass=0.1&device_damping=1&arm_mass=1&arm_damping=-1&arm_stiffness=0&period=0.001&d=0",
        "arm_damping",
        "-1",
    ),
    (
        "/api/region?mode=physical&device_mass=0.1&device_damping=1&arm_mass=1&arm_damping=1&arm_stiffness=0&period=0&d=0",
        "period",
        "0",
    ),
    (
        "/api/region?mode=hybrid&gamma=0&delta=0&d=0",
        "mode",
        "hybrid",
    ),
    (
        "/api/region?gamma=0&delta=0&d=0&period=0.001",
        "period",
        "0.001",
    ),
];

#[test]
fn bad_input_is_400_with_a_json_error_naming_parameter_and_value() {
    let s = Server::start(&[]);
    for cases in [
        MISSING_OR_NOT_FINITE,
        OUT_OF_RANGE,
        NAMES_GRIDS_AND_SIZES,
        MODES,
    ] {
        assert_400_naming_parameter_and_value(&s, cases);
    }
    // a malformed query string is a 400 too, and the server is still alive afterwards
    let r = s.get("/api/region?gamma=%ZZ&delta=0&d=0");
    assert_eq!(r.status, 400, "{}", r.body);
    assert!(r.json()["error"].is_string());
    assert_eq!(s.get(&format!("/api/region?{PLANT}")).status, 200);
}

/// Each case is a 400 with a JSON error whose message names the parameter and shows the value.
fn assert_400_naming_parameter_and_value(s: &Server, cases: &[Case]) {
    for (path, name, value) in cases {
        let r = s.get(path);
        assert_eq!(r.status, 400, "{path}: {}", r.body);
        assert!(
            r.header("content-type")
                .is_some_and(|c| c.starts_with("application/json")),
            "{path}: {:?}",
            r.headers
        );
        let j = r.json();
        let msg = j["error"]
            .as_str()
            .unwrap_or_else(|| panic!("{path}: no error string in {}", r.body));
        assert!(msg.contains(name), "{path}: '{msg}' does not name {name}");
        assert!(
            msg.contains(value),
            "{path}: '{msg}' does not show the value {value}"
        );
    }
}

#[test]
fn other_errors_are_json_too() {
    let s = Server::start(&[]);
    let r = s.get("/api/nowhere");
    assert_eq!(r.status, 404);
    assert!(r.json()["error"].as_str().unwrap().contains("/api/nowhere"));
    let r = request(s.port, "POST", "/api/region", &[("Content-Length", "0")]);
    assert_eq!(r.status, 405);
    assert!(r.json()["error"].is_string());
    // DNS-rebinding guard: a foreign Host header is refused on a loopback server
    let r = request(s.port, "GET", "/", &[("Host", "attacker.example:80")]);
    assert_eq!(r.status, 403);
    assert!(
        r.json()["error"]
            .as_str()
            .unwrap()
            .contains("attacker.example")
    );
    let r = request(s.port, "GET", "/api/limits", &[("Host", "localhost")]);
    assert_eq!(r.status, 200);
}

/// Bad loop input is a 400 naming the parameter and the value; a fractional delay time is
/// a loop, discretized exactly (λ = 0.5 here).
#[test]
fn bad_loop_input_is_400_naming_the_parameter() {
    let s = Server::start(&[]);
    let r = s.get("/api/region?mode=physical&device_mass=0.1&device_damping=1&arm_mass=1&arm_damping=1&arm_stiffness=0&period=0.001&delay_time=0.0015");
    assert_eq!(r.status, 200, "{}", r.body);
    assert_eq!(r.json()["loop"]["delay"]["fraction"], 0.5);
    let tf = "mode=physical&period=0.001&d=0&alpha=1&beta=1";
    let cases: &[(String, &str, &str)] = &[
        (
            format!("/api/point?{tf}&plant_num=1&plant_den=0.001%2Cx"),
            "plant_den",
            "0.001,x",
        ),
        (
            format!("/api/point?{tf}&plant_num=1,2,3&plant_den=1,2"),
            "plant_den",
            "1,2",
        ),
        (
            format!("/api/point?{tf}&plant_num=1&plant_den=1,0,0&device_mass=1"),
            "device_mass",
            "1",
        ),
        (
            format!("/api/region?{TWO_MASS_LOOP}&robust=1"),
            "robust",
            "1",
        ),
        (
            format!(
                "/api/region?{}",
                TWO_MASS_LOOP.replace("lowpass%3A150", "bogus")
            ),
            "estimator",
            "bogus",
        ),
        (
            format!(
                "/api/region?{}",
                TWO_MASS_LOOP.replace("force_lag=0.0002", "force_lag=-1")
            ),
            "force_lag",
            "-1",
        ),
        (
            format!(
                "/api/region?{}",
                TWO_MASS_LOOP.replace("delay_time=0.0014", "delay_time=0.5")
            ),
            "delay_time",
            "0.5",
        ),
        (
            "/api/region?gamma=0&delta=0&d=0&estimator=backward".to_string(),
            "estimator",
            "backward",
        ),
    ];
    for (path, name, value) in cases {
        let r = s.get(path);
        assert_eq!(r.status, 400, "{path}: {}", r.body);
        let j = r.json();
        assert_eq!(j["parameter"], *name, "{path}: {j}");
        let msg = j["error"].as_str().unwrap();
        assert!(msg.contains(name) && msg.contains(value), "{path}: {msg}");
    }
}

#[test]
fn timeouts_and_bursts_do_not_take_the_server_down() {
    // A 1 ms time limit: a robust region cannot finish, the request gets a 503 JSON error,
    // and the server goes on answering.
    let s = Server::start(&["--timeout-ms", "1", "--jobs", "2"]);
    let r =
        s.get("/api/region?gamma=0&delta=1&d=2&robust=1&gamma_lo=0&gamma_hi=9&gamma_samples=32");
    assert_eq!(r.status, 503, "{}", r.body);
    assert!(r.json()["error"].as_str().unwrap().contains("time limit"));
    assert_eq!(s.get("/api/limits").status, 200);
    drop(s);
    // A burst of concurrent heavy requests: each is answered (200 or 503 busy), none hangs,
    // and the server still answers afterwards.
    let s = Server::start(&["--jobs", "2"]);
    let port = s.port;
    let handles: Vec<_> = (0..12)
        .map(|i| {
            std::thread::spawn(move || {
                let path = format!(
                    "/api/region?gamma=0&delta={}&d={}&robust=1&gamma_lo=0&gamma_hi=1&gamma_samples=8&beta_samples=32",
                    enc(&format!("{}", 0.1 + 0.01 * i as f64)),
                    i % 3
                );
                request(port, "GET", &path, &[]).status
            })
        })
        .collect();
    for h in handles {
        let st = h.join().unwrap();
        assert!(st == 200 || st == 503, "{st}");
    }
    assert_eq!(s.get(&format!("/api/region?{PLANT}")).status, 200);
}
