//! API tests of `hapstab serve` against the real server on an ephemeral loopback port:
//! every bad input is HTTP 400 with a JSON error naming the parameter and the value; good
//! input gives exactly the library's numbers; the page is self-contained; the server
//! survives timeouts and bursts of concurrent requests.

mod serve_support;

use hapstab::region::stable_region;
use hapstab::stability::Analysis;
use hapstab::{Normalized, PlantParams, PolyFamily};
use serve_support::{Server, enc, raw_number, request};

const PLANT: &str = "gamma=0.001&delta=0.015&d=1";

#[test]
fn bad_input_is_400_with_a_json_error_naming_parameter_and_value() {
    let s = Server::start(&[]);
    // (path, parameter the message must name, value the message must show)
    let cases: &[(&str, &str, &str)] = &[
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
        // physical mode
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
    // a malformed query string is a 400 too, and the server is still alive afterwards
    let r = s.get("/api/region?gamma=%ZZ&delta=0&d=0");
    assert_eq!(r.status, 400, "{}", r.body);
    assert!(r.json()["error"].is_string());
    assert_eq!(s.get(&format!("/api/region?{PLANT}")).status, 200);
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

fn library_region(gamma: f64, delta: f64, d: usize) -> hapstab::region::StableRegion {
    stable_region(&PolyFamily::new(PlantParams::new(gamma, delta).unwrap(), d).unwrap()).unwrap()
}

#[test]
fn region_alpha_max_equals_the_library() {
    let s = Server::start(&[]);
    for (g, de, d) in [
        (0.001, 0.015, 0),
        (0.001, 0.015, 1),
        (0.0, 0.0, 2),
        (0.0005, 0.005, 5),
        (0.001, 0.0, 10),
        (5.0, 1.0, 3),
        (0.0, 0.015, 50),
    ] {
        let path = format!("/api/region?gamma={g}&delta={de}&d={d}");
        let r = s.get(&path);
        assert_eq!(r.status, 200, "{path}: {}", r.body);
        let lib = library_region(g, de, d);
        let am = raw_number(&r.body, "\"region\":", "alpha_max");
        let bm = raw_number(&r.body, "\"region\":", "beta_at_alpha_max");
        let area = raw_number(&r.body, "\"region\":", "area");
        assert_eq!(am, lib.alpha_max, "{path}");
        assert_eq!(bm, lib.beta_at_alpha_max, "{path}");
        assert_eq!(area, lib.area, "{path}");
        let j = r.json();
        assert_eq!(j["params"]["d"], d);
        let polys = j["region"]["polygons"].as_array().unwrap();
        assert_eq!(polys.len(), lib.polygons.len(), "{path}");
        // simplified for drawing, corners kept, never more vertices than the exact polygons
        let sent = j["region"]["vertices_sent"].as_u64().unwrap() as usize;
        let exact: usize = lib.polygons.iter().map(|p| p.vertices.len()).sum();
        assert_eq!(
            j["region"]["vertices_exact"].as_u64().unwrap() as usize,
            exact
        );
        assert!(
            sent <= exact && sent >= 3 * lib.polygons.len(),
            "{sent} of {exact}"
        );
        // every drawn vertex lies on the exact boundary: its neighbourhood straddles it
        // (checked cheaply: the drawn polygon's α extent is the exact one within tolerance)
        let amax_drawn = polys
            .iter()
            .flat_map(|p| p.as_array().unwrap())
            .map(|v| v[0].as_f64().unwrap())
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(amax_drawn <= lib.alpha_max + 1e-12);
        assert!(amax_drawn >= lib.alpha_max - 1e-3 * lib.alpha_max.abs().max(1e-9));
        // overlays
        let lin = &j["linear"];
        assert!((lin["slope"].as_f64().unwrap() - 1.0 / (d as f64 + 0.5)).abs() < 1e-15);
        assert!((lin["alpha_at_beta0"].as_f64().unwrap() - de / (d as f64 + 0.5)).abs() < 1e-15);
        if d == 0 {
            let v = &j["passive"]["vertices"];
            assert_eq!(v[1][0].as_f64().unwrap(), 2.0 * de);
            assert_eq!(v[2][1].as_f64().unwrap(), de);
        } else {
            assert!(j["passive"].is_null());
        }
    }
}

#[test]
fn physical_mode_matches_the_library() {
    let s = Server::start(&[]);
    let path = "/api/region?mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&delay_time=0.002";
    let r = s.get(path);
    assert_eq!(r.status, 200, "{}", r.body);
    let eff = hapstab::Effective::new(1.1, 7.5, 350.0).unwrap();
    let pp = PlantParams::from_physical(&eff, 0.001).unwrap();
    let lib = library_region(pp.gamma, pp.delta, 2);
    assert_eq!(
        raw_number(&r.body, "\"region\":", "alpha_max"),
        lib.alpha_max
    );
    let j = r.json();
    assert_eq!(j["params"]["d"], 2);
    let kpa = j["physical"]["k_per_alpha"].as_f64().unwrap();
    assert!((kpa - 1.1 / 1e-6).abs() < 1e-6);
    assert!((j["physical"]["b_per_beta"].as_f64().unwrap() - 1100.0).abs() < 1e-9);
}

#[test]
fn robust_region_is_inside_the_nominal_one() {
    let s = Server::start(&[]);
    let r = s.get("/api/region?gamma=0&delta=1&d=0&robust=1&gamma_lo=0&gamma_hi=9.8696");
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    let rob = &j["robust"];
    assert_eq!(rob["empty"], false);
    let ram = rob["alpha_max"].as_f64().unwrap();
    for g in [0.0, 9.8696] {
        assert!(ram <= library_region(g, 1.0, 0).alpha_max + 1e-9);
    }
    // Colgate's passive triangle (0, −1), (2, 0), (0, 1) lies inside the robust region
    // (Section VIII-A): its tip α = 2δ = 2 at β = 0 is below the robust α_max.
    assert!(ram > 2.0, "{ram}");
    assert!(rob["method"].as_str().unwrap().contains("robust_region"));
}

#[test]
fn point_matches_the_library_analysis() {
    let s = Server::start(&[]);
    for (a, b, g, de, d) in [
        (0.3, 0.5, 0.001, 0.015, 0),
        (0.75, 0.5, 0.001, 0.015, 0),
        (0.05, 0.3, 0.0, 0.0, 3),
    ] {
        let path = format!("/api/point?alpha={a}&beta={b}&gamma={g}&delta={de}&d={d}");
        let r = s.get(&path);
        assert_eq!(r.status, 200, "{}", r.body);
        let lib = Analysis::new(Normalized::new(a, b, g, de, d).unwrap()).unwrap();
        let j = r.json();
        assert_eq!(j["verdict"], lib.verdict.as_str(), "{path}");
        assert_eq!(
            raw_number(&r.body, "\"verdict\"", "spectral_radius"),
            lib.spectral_radius
        );
        let roots = j["roots"].as_array().unwrap();
        assert_eq!(roots.len(), d + 3);
        assert_eq!(j["passive"].is_null(), d != 0);
    }
}

#[test]
fn simulate_returns_a_short_contact_trace() {
    let s = Server::start(&[]);
    let r = s.get("/api/simulate?gamma=0.001&delta=0.015&d=0&alpha=0.3&beta=0.5&push=100");
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    assert_eq!(j["outcome"], "decaying", "{j}");
    assert_eq!(j["linear_verdict"], "stable");
    assert_eq!(j["contact_mode"], "unilateral");
    assert_eq!(j["linear_window"], true);
    assert!(j["measured_growth_per_sample"].as_f64().unwrap() < 1.0);
    let n = j["trace"]["time"].as_array().unwrap().len();
    assert!((10..=2000).contains(&n), "{n}");
    assert_eq!(j["trace"]["position"].as_array().unwrap().len(), n);
    // beyond α_max the bilateral loop grows
    let r = s.get(
        "/api/simulate?gamma=0.001&delta=0.015&d=0&alpha=0.75&beta=0.5&contact=bilateral&samples=400",
    );
    let j = r.json();
    assert_eq!(j["linear_verdict"], "unstable");
    assert_eq!(j["outcome"], "growing");
    assert!(j["measured_growth_per_sample"].as_f64().unwrap() > 1.0);
    // long runs are decimated to at most 2000 rows
    let r = s.get("/api/simulate?gamma=0&delta=0.01&d=1&alpha=0.05&beta=0.2&samples=20000");
    assert_eq!(r.status, 200, "{}", r.body);
    assert!(r.json()["trace"]["time"].as_array().unwrap().len() <= 2000);
}

/// The device of the reproduction in the explorer's physical mode: 0.2 kg, 2 Ns/m, the
/// default arm (1 kg, 6 Ns/m, 350 N/m), T = 1 ms, d = 1, K = 20 kN/m, B = 5 Ns/m.
const REPRO_WALL: &str = "mode=physical&device_mass=0.2&device_damping=2&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&d=1&wall_stiffness=20000&wall_damping=5";

/// Reproduction: the selected wall is unstable (spectral radius 1.00702); the simulated
/// contact (unilateral, push 1 N, 10 mm/s) must not be called decaying beside its growing
/// trace. It is a bouncing limit cycle whose peak-to-peak amplitude is that of the returned
/// trace over the judged window; the bilateral contact grows. The same setting gives the same
/// verdict in `hapstab simulate` (one library function).
#[test]
fn simulated_contact_agrees_with_the_analysis_and_with_simulate() {
    let s = Server::start(&[]);
    let point = s.get(&format!("/api/point?{REPRO_WALL}")).json();
    assert_eq!(point["verdict"], "unstable");
    let j = s.get(&format!("/api/simulate?{REPRO_WALL}")).json();
    assert_eq!(j["linear_verdict"], "unstable", "{j}");
    assert_eq!(j["spectral_radius"], point["spectral_radius"]);
    assert_eq!(j["outcome"], "limit_cycle", "{j}");
    let lc = &j["limit_cycle"];
    assert_eq!(lc["bouncing"], true);
    assert!(
        j["reason"]
            .as_str()
            .unwrap()
            .contains("contact is lost and regained")
    );
    // The trace covers the judged window; its extremes there are the cycle's.
    let (t, x) = (&j["trace"]["time"], &j["trace"]["position"]);
    let from = j["judged_from_sample"].as_f64().unwrap() * 1e-3;
    let tail: Vec<f64> = (0..t.as_array().unwrap().len())
        .filter(|&i| t[i].as_f64().unwrap() >= from)
        .map(|i| x[i].as_f64().unwrap())
        .collect();
    assert!(tail.len() > 100, "{}", tail.len());
    let pp = tail.iter().cloned().fold(f64::MIN, f64::max)
        - tail.iter().cloned().fold(f64::MAX, f64::min);
    let lpp = lc["peak_to_peak"].as_f64().unwrap();
    assert!(pp <= lpp * (1.0 + 1e-12) && pp > 0.8 * lpp, "{pp} vs {lpp}");
    let bil = s
        .get(&format!("/api/simulate?{REPRO_WALL}&contact=bilateral"))
        .json();
    assert_eq!(bil["outcome"], "growing", "{bil}");

    // hapstab simulate with the same setting and run length: the same verdict.
    let samples = j["requested_samples"].as_u64().unwrap().to_string();
    let out = assert_cmd::Command::cargo_bin("hapstab")
        .unwrap()
        .args([
            "simulate",
            "--device-mass",
            "0.2",
            "--device-damping",
            "2",
            "--delay",
            "1",
            "--wall-stiffness",
            "20000",
            "--wall-damping",
            "5",
            "--unilateral",
            "--push",
            "1",
            "--initial-position",
            "0",
            "--initial-velocity",
            "0.01",
            "--duration-samples",
            &samples,
            "--json",
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    let cli: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "outcome",
        "reason",
        "limit_cycle",
        "contact",
        "samples",
        "judged_from_sample",
        "measured_growth_per_sample",
        "spectral_radius",
        "linear_verdict",
        "linear_window",
    ] {
        assert_eq!(cli[key], j[key], "{key}");
    }
}

#[test]
fn export_svg_csv_json() {
    let s = Server::start(&[]);
    let base = format!("/api/export?{PLANT}&alpha=0.05&beta=0.3");
    let lib = library_region(0.001, 0.015, 1);
    let r = s.get(&format!("{base}&format=svg"));
    assert_eq!(r.status, 200);
    assert_eq!(r.header("content-type"), Some("image/svg+xml"));
    assert!(r.header("content-disposition").unwrap().contains(".svg"));
    assert!(r.body.starts_with("<svg") && r.body.trim_end().ends_with("</svg>"));
    assert!(r.body.contains("class=\"region\"") && r.body.contains("class=\"point\""));
    let r = s.get(&format!("{base}&format=csv"));
    assert_eq!(r.status, 200);
    let mut lines = r.body.lines();
    assert_eq!(
        lines.next(),
        Some("layer,polygon,vertex,alpha,beta,K_N_per_m,B_Ns_per_m")
    );
    let amax_row = r
        .body
        .lines()
        .find(|l| l.starts_with("alpha_max,"))
        .unwrap();
    let am: f64 = amax_row.split(',').nth(3).unwrap().parse().unwrap();
    assert_eq!(am, lib.alpha_max);
    assert!(r.body.lines().any(|l| l.starts_with("point,")));
    assert!(r.body.lines().filter(|l| l.starts_with("region,")).count() > 10);
    let r = s.get(&format!("{base}&format=json&view=-0.01,0.2,-0.1,1.2"));
    assert_eq!(r.status, 200);
    assert_eq!(
        raw_number(&r.body, "\"region\":", "alpha_max"),
        lib.alpha_max
    );
    let j = r.json();
    assert_eq!(j["view"][1].as_f64(), Some(0.2));
    assert_eq!(j["point"]["verdict"], "stable");
}

#[test]
fn page_is_self_contained() {
    let s = Server::start(&[]);
    let r = s.get("/");
    assert_eq!(r.status, 200);
    assert!(r.header("content-type").unwrap().starts_with("text/html"));
    let csp = r.header("content-security-policy").unwrap();
    assert!(csp.contains("default-src 'none'") && csp.contains("connect-src 'self'"));
    // no external resource: the only URL is the SVG namespace
    let urls: Vec<&str> = r
        .body
        .match_indices("http")
        .map(|(i, _)| &r.body[i..(i + 40).min(r.body.len())])
        .filter(|u| !u.starts_with("http://www.w3.org/2000/svg"))
        .collect();
    assert!(urls.is_empty(), "{urls:?}");
    assert!(!r.body.contains("<script src") && !r.body.contains("<link "));
    // the limits are stated on the page and served as JSON
    assert!(r.body.contains("d ≤ 200"));
    let l = s.get("/api/limits").json();
    assert_eq!(l["d_max"], 200);
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

/// A two-mass device held by the default arm, with an actuator lag, a low-pass velocity and a
/// fractional delay (t_d = 1.4 T): a loop beyond the paper's.
const TWO_MASS_LOOP: &str = "mode=physical&motor_mass=0.05&handle_mass=0.05&transmission_stiffness=5000&transmission_damping=1&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&delay_time=0.0014&estimator=lowpass%3A150&force_lag=0.0002";

/// The same loop's flags for `hapstab`.
const TWO_MASS_FLAGS: [&str; 14] = [
    "--motor-mass",
    "0.05",
    "--handle-mass",
    "0.05",
    "--transmission-stiffness",
    "5000",
    "--transmission-damping",
    "1",
    "--force-lag",
    "0.0002",
    "--velocity",
    "lowpass:150",
    "--delay-time",
    "0.0014",
];

/// The library's [`hapstab::Loop`] of [`TWO_MASS_LOOP`].
fn two_mass_loop() -> hapstab::Loop {
    let plant = hapstab::Plant::new(
        hapstab::PlantModel::TwoMass(hapstab::TwoMass {
            motor_mass: 0.05,
            motor_damping: 0.0,
            handle_mass: 0.05,
            transmission_stiffness: 5000.0,
            transmission_damping: 1.0,
            arm: hapstab::Arm::TYPICAL,
        }),
        0.0002,
    )
    .unwrap();
    let delay = hapstab::Delay::from_time(0.0014, 0.001).unwrap();
    hapstab::Loop::new(plant, 0.001, delay, "lowpass:150".parse().unwrap()).unwrap()
}

fn hapstab_json(args: &[&str]) -> serde_json::Value {
    let out = assert_cmd::Command::cargo_bin("hapstab")
        .unwrap()
        .args(args)
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// A loop beyond the paper's in the explorer: the region is the loop's (its vertices, given
/// back as walls, have a root on the unit circle), the point is `hapstab check`'s, and the
/// simulated contact is `hapstab simulate`'s, key for key; the paper's overlays are absent.
#[test]
fn general_loop_region_point_and_simulation_match_the_cli() {
    let s = Server::start(&[]);
    let r = s.get(&format!("/api/region?{TWO_MASS_LOOP}"));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    assert!(j["linear"].is_null() && j["passive"].is_null(), "{j}");
    assert_eq!(j["loop"]["velocity"]["kind"], "low_pass");
    let (kpa, bpb) = (
        j["physical"]["k_per_alpha"].as_f64().unwrap(),
        j["physical"]["b_per_beta"].as_f64().unwrap(),
    );
    let poly = j["region"]["polygons"][0].as_array().unwrap();
    assert!(poly.len() > 10, "{j}");
    // Vertices on the z = 1 line a = −γ are double roots at z = 1 amid the plant's cluster
    // of roots near 1, where roots of the z-coefficients are ill-conditioned: sample the rest.
    let gamma = j["params"]["gamma"].as_f64().unwrap();
    let lp = two_mass_loop();
    let fam = hapstab::AffineFamily::of_loop(&lp).unwrap();
    let arcs: Vec<&serde_json::Value> = poly
        .iter()
        .filter(|v| (v[0].as_f64().unwrap() + gamma).abs() > 1e-6 * gamma)
        .collect();
    assert!(arcs.len() > 8, "{j}");
    for v in arcs.iter().step_by(arcs.len() / 8) {
        let (a, b) = (v[0].as_f64().unwrap(), v[1].as_f64().unwrap());
        let p = s
            .get(&format!("/api/point?{TWO_MASS_LOOP}&alpha={a}&beta={b}"))
            .json();
        let rho = p["spectral_radius"].as_f64().unwrap();
        assert!((rho - 1.0).abs() < 1e-6, "vertex ({a}, {b}): rho {rho}");
        // on the boundary too, the verdict is check's (`hapstab::loop_analysis::analysis`)
        let an = hapstab::loop_analysis::analysis(&lp, &fam, (a, b)).unwrap();
        assert_eq!(p["verdict"], an.verdict.as_str(), "vertex ({a}, {b})");
        // (serde_json's float parser may be an ulp off the server's shortest form)
        assert!(
            (rho - an.spectral_radius).abs() <= 1e-15,
            "vertex ({a}, {b})"
        );
    }
    // A wall inside: the explorer's point is check's.
    let (k, b) = (
        0.5 * j["region"]["alpha_max"].as_f64().unwrap() * kpa,
        0.5 * j["region"]["beta_at_alpha_max"].as_f64().unwrap() * bpb,
    );
    let (ks, bs) = (k.to_string(), b.to_string());
    let p = s
        .get(&format!(
            "/api/point?{TWO_MASS_LOOP}&wall_stiffness={ks}&wall_damping={bs}"
        ))
        .json();
    let mut args = vec!["check"];
    args.extend(TWO_MASS_FLAGS);
    args.extend(["--wall-stiffness", &ks, "--wall-damping", &bs]);
    let check = hapstab_json(&args);
    assert_eq!(p["verdict"], check["verdict"]);
    let (r1, r2) = (
        p["spectral_radius"].as_f64().unwrap(),
        check["spectral_radius"].as_f64().unwrap(),
    );
    assert!((r1 - r2).abs() <= 1e-12, "{r1} vs {r2}");
    assert!(p["linear"].is_null());
    // The simulated contact: the explorer's run is hapstab simulate's.
    let sim = s
        .get(&format!(
            "/api/simulate?{TWO_MASS_LOOP}&wall_stiffness={ks}&wall_damping={bs}"
        ))
        .json();
    let samples = sim["requested_samples"].as_u64().unwrap().to_string();
    let mut args = vec!["simulate"];
    args.extend(TWO_MASS_FLAGS);
    args.extend([
        "--wall-stiffness",
        &ks,
        "--wall-damping",
        &bs,
        "--unilateral",
        "--push",
        "1",
    ]);
    args.extend(["--initial-position", "0", "--initial-velocity", "0.01"]);
    args.extend(["--duration-samples", &samples]);
    let cli = hapstab_json(&args);
    for key in [
        "outcome",
        "reason",
        "limit_cycle",
        "contact",
        "samples",
        "judged_from_sample",
        "measured_growth_per_sample",
        "spectral_radius",
        "linear_verdict",
        "linear_window",
    ] {
        assert_eq!(cli[key], sim[key], "{key}");
    }
    assert_eq!(sim["linear_verdict"], "stable");
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

/// The paper's plant given as a loop (an explicit backward velocity estimator makes it a
/// loop request): the explorer analyses it as `hapstab check` does
/// (`hapstab::loop_analysis`, through the paper's family in (α, β)), so its region is the
/// paper's region exactly and every point's verdict and radius are `Analysis::new`'s, on the
/// boundary too.
#[test]
fn a_loop_with_the_papers_view_is_analysed_as_check_does() {
    let s = Server::start(&[]);
    let lp = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&d=1&estimator=backward";
    let r = s.get(&format!("/api/region?{lp}"));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    assert_eq!(j["loop"]["velocity"]["kind"], "backward", "{j}");
    let eff =
        hapstab::Effective::combine(hapstab::Device::PHANTOM_LIKE, hapstab::Arm::TYPICAL).unwrap();
    let pp = PlantParams::from_physical(&eff, 1e-3).unwrap();
    let lib = library_region(pp.gamma, pp.delta, 1);
    assert_eq!(j["region"]["alpha_max"].as_f64().unwrap(), lib.alpha_max);
    let vertices = &lib.polygons[0].vertices;
    for v in vertices.iter().step_by(vertices.len() / 12 + 1) {
        let p = s
            .get(&format!(
                "/api/point?{lp}&alpha={}&beta={}",
                v.alpha, v.beta
            ))
            .json();
        let an = Analysis::new(Normalized::new(v.alpha, v.beta, pp.gamma, pp.delta, 1).unwrap())
            .unwrap();
        assert_eq!(
            p["verdict"],
            an.verdict.as_str(),
            "({}, {})",
            v.alpha,
            v.beta
        );
        let rho = p["spectral_radius"].as_f64().unwrap();
        // (serde_json's float parser may be an ulp off the server's shortest form)
        assert!(
            (rho - an.spectral_radius).abs() <= 1e-15,
            "{rho} vs {}",
            an.spectral_radius
        );
    }
}

/// The robust region in physical mode over the arm's stiffness k_H ∈ [lo, hi] N/m: the same
/// region as the γ range γ = k_H T²/m, and its K_max agrees with `hapstab kmax --robust` on
/// the same box (mass and damping fixed, stiffness ranged).
#[test]
fn robust_range_in_arm_stiffness_is_the_gamma_range_and_kmax_robust() {
    let s = Server::start(&[]);
    let phys = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&d=0";
    let r = s.get(&format!(
        "/api/region?{phys}&robust=1&arm_stiffness_lo=0&arm_stiffness_hi=350"
    ));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    let rob = &j["robust"];
    // m = 1.1 kg, T = 1 ms: γ = k_H T²/m
    let g_hi = 350.0 * 1e-6 / 1.1;
    assert_eq!(rob["gamma_lo"].as_f64().unwrap(), 0.0);
    assert!((rob["gamma_hi"].as_f64().unwrap() - g_hi).abs() <= 1e-15 * g_hi);
    assert_eq!(rob["arm_stiffness_hi"].as_f64().unwrap(), 350.0);
    let (gamma, delta) = (
        j["params"]["gamma"].as_f64().unwrap(),
        j["params"]["delta"].as_f64().unwrap(),
    );
    let norm = s
        .get(&format!(
            "/api/region?gamma={}&delta={}&d=0&robust=1&gamma_lo=0&gamma_hi={}",
            gamma,
            delta,
            rob["gamma_hi"].as_f64().unwrap()
        ))
        .json();
    assert_eq!(norm["robust"]["polygon"], rob["polygon"]);
    let kpa = j["physical"]["k_per_alpha"].as_f64().unwrap();
    let k_max = rob["alpha_max"].as_f64().unwrap() * kpa;
    let cli = hapstab_json(&[
        "kmax",
        "--robust",
        "--box-mass",
        "1.1,1.1",
        "--box-damping",
        "7.5:7.5",
        "--box-stiffness",
        "0,350",
    ]);
    let k_cli = cli["k_max"].as_f64().unwrap();
    // The explorer's 64 β slices find the peak of a smooth boundary from below; the CLI
    // refines the slices near it: a relative gap of order (slice spacing)² ≈ 1e-4 at most.
    assert!(
        k_max <= k_cli * (1.0 + 1e-12) && k_max >= k_cli * (1.0 - 1e-4),
        "explorer {k_max} vs kmax --robust {k_cli}"
    );
    // γ and k_H ranges together, or k_H in normalized mode: 400 naming the parameter.
    for (path, name) in [
        (
            format!(
                "/api/region?{phys}&robust=1&arm_stiffness_lo=0&arm_stiffness_hi=350&gamma_lo=0"
            ),
            "gamma_lo",
        ),
        (
            format!("/api/region?{PLANT}&robust=1&arm_stiffness_lo=0&arm_stiffness_hi=350"),
            "arm_stiffness_lo",
        ),
        (
            format!("/api/region?{phys}&robust=1&arm_stiffness_lo=400&arm_stiffness_hi=350"),
            "arm_stiffness_hi",
        ),
    ] {
        let r = s.get(&path);
        assert_eq!(r.status, 400, "{path}: {}", r.body);
        assert_eq!(r.json()["parameter"], name, "{path}");
    }
}

/// Physical mode, d = 0: the passive triangle is the device's own δ_L = b_L·T/m (passive for
/// any operator); eq. (28) with the arm's damping counted, δ = (b_L + b_H)·T/m, is the second.
#[test]
fn physical_passive_region_counts_the_devices_own_damping() {
    let s = Server::start(&[]);
    let lp = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&d=0";
    let r = s.get(&format!("/api/region?{lp}"));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    let (own, eff) = (1.5e-3 / 1.1, 7.5e-3 / 1.1);
    let v = &j["passive"]["vertices"];
    assert!(
        (v[1][0].as_f64().unwrap() - 2.0 * own).abs() < 1e-15,
        "{}",
        j["passive"]
    );
    let w = &j["passive_with_arm"]["vertices"];
    assert!(
        (w[1][0].as_f64().unwrap() - 2.0 * eff).abs() < 1e-15,
        "{}",
        j["passive_with_arm"]
    );
    // a spring wall α = 3δ_L lies outside the device's own triangle, inside eq. (28)'s
    let alpha = 3.0 * own;
    let r = s.get(&format!("/api/point?{lp}&alpha={alpha}&beta=0"));
    assert_eq!(r.status, 200, "{}", r.body);
    let p = r.json();
    assert_eq!(p["passive"], false, "{p}");
    assert_eq!(p["passive_with_arm"], true, "{p}");
    // without an arm there is one triangle, the device's own
    let bare = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=0&arm_damping=0&arm_stiffness=0&period=0.001&d=0";
    let j = s.get(&format!("/api/region?{bare}")).json();
    assert!(j["passive_with_arm"].is_null(), "{j}");
    let v = &j["passive"]["vertices"];
    assert!((v[1][0].as_f64().unwrap() - 2.0 * 1.5e-3 / 0.1).abs() < 1e-15);
}
