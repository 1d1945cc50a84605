//! The explorer and the command line give the same answers: `hapstab serve` (started on an
//! ephemeral loopback port, with hapstab-serve's test helpers) against `hapstab check`,
//! `passivity`, `kmax`, `kmax --robust --box` and `simulate` on the same loop and wall, and
//! loop files passed between them. The explorer's own behaviour is tested in hapstab-serve.

use crate::serve_support;

use crate::common;

use serve_support::{PAPER_LOOP, PLANT, Server, TWO_MASS_LOOP, enc, raw_number};

// ---------------------------------------------------------------------------------------
// Loop files: "Save loop" (`/api/export?format=loop`) writes a file that `hapstab check
// --loop` reads to the explorer's own answer, and "Open loop" (`/api/open`) turns a loop the
// command line echoed into the page's query, whose point is the command line's, bit for bit.
// ---------------------------------------------------------------------------------------

const PAPER: &str = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001";

#[test]
fn a_saved_loop_loads_in_the_command_line() {
    let s = Server::start(&[]);
    let dir = tempfile::tempdir().unwrap();
    for query in [
        format!("{PAPER}&d=2"),
        format!("{PAPER}&delay_time=0.00037&estimator=lowpass%3A100"),
        "mode=physical&plant_num=10&plant_den=1,3,10&period=0.001&d=1".to_string(),
        "mode=normalized&gamma=0.001&delta=0.015&d=1".to_string(),
    ] {
        let point = format!("{query}&alpha=0.02&beta=0.02");
        let saved = s.get(&format!("/api/export?{point}&format=loop"));
        assert_eq!(saved.status, 200, "{}", saved.body);
        let file = dir.path().join("loop.json");
        std::fs::write(&file, &saved.body).unwrap();
        let check = common::json(&["check", "--loop", file.to_str().unwrap()]);
        let p = s.get(&format!("/api/point?{point}")).json();
        assert_eq!(p["verdict"], check["verdict"], "{query}");
        assert_eq!(p["spectral_radius"], check["spectral_radius"], "{query}");
        if check["gain_margin"].is_number() {
            assert_eq!(p["margins"]["gain_margin"], check["gain_margin"], "{query}");
        }
    }
}

#[test]
fn an_echoed_loop_opens_in_the_page() {
    let s = Server::start(&[]);
    let cases: [&[&str]; 4] = [
        &["--delay-time", "0.00037", "--velocity", "lowpass:100"],
        &[
            "--motor-mass",
            "0.3",
            "--transmission-stiffness",
            "2300",
            "--handle-mass",
            "0.1",
            "--velocity",
            "average:3",
            "--period",
            "0.002",
        ],
        &[
            "--plant-num",
            "10",
            "--plant-den",
            "1,3,10",
            "--force-lag",
            "0.0004",
            "--delay",
            "2",
        ],
        &["--no-arm", "--device-mass", "0.25", "--device-damping", "2"],
    ];
    for flags in cases {
        let mut args = vec!["check"];
        args.extend(flags);
        args.extend(["--wall-stiffness", "300", "--wall-damping", "0.5"]);
        let check = common::json(&args);
        let r = s.get(&format!(
            "/api/open?file={}",
            enc(&check["input"].to_string())
        ));
        assert_eq!(r.status, 200, "{}", r.body);
        let query = r.json()["query"].as_str().unwrap().to_string();
        // the page asks for its point by the wall in N/m, as a click on K, B does: the file's
        // wall as written
        assert!(
            query.ends_with("&wall_stiffness=300.0&wall_damping=0.5"),
            "{query}"
        );
        let p = s.get(&format!("/api/point?{query}")).json();
        assert_eq!(p["verdict"], check["verdict"], "{flags:?}: {query}");
        assert_eq!(
            p["spectral_radius"], check["spectral_radius"],
            "{flags:?}: {query}"
        );
        assert_eq!(
            p["margins"]["delay_margin"], check["delay_margin"],
            "{flags:?}"
        );
    }
    let bad = s.get("/api/open?file=%7B%22loop%22%3A%7B%22period%22%3A%22x%22%7D%7D");
    assert_eq!(bad.status, 400);
    assert_eq!(bad.json()["parameter"], "file");
    assert!(bad.body.contains("loop.period"), "{}", bad.body);
}

// ---------------------------------------------------------------------------------------
// A loop beyond the paper's: analysed and simulated as `hapstab check` and `hapstab
// simulate` do; a clicked wall's margins and passivity are the command line's.
// ---------------------------------------------------------------------------------------

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
    assert_vertices_are_on_the_boundary(&s, &j);
    // A wall inside: half way to α_max, in N/m and Ns/m.
    let (kpa, bpb) = (
        j["physical"]["k_per_unit"].as_f64().unwrap(),
        j["physical"]["b_per_unit"].as_f64().unwrap(),
    );
    // the region of a physical loop is sent in N/m and Ns/m
    assert!(j["region"]["alpha_max"].is_null(), "{j}");
    let (k, b) = (
        0.5 * j["region"]["k_max"].as_f64().unwrap(),
        0.5 * j["region"]["b_at_k_max"].as_f64().unwrap(),
    );
    let wall_units = &j["region"]["wall_units"];
    assert_eq!(wall_units["stiffness"].as_f64(), Some(kpa));
    assert_eq!(wall_units["damping"].as_f64(), Some(bpb));
    let (ks, bs) = (k.to_string(), b.to_string());
    assert_point_is_checks(&s, &ks, &bs);
    assert_simulation_is_simulates(&s, &ks, &bs);
}

/// The region's vertices, given back as walls, have a root on the unit circle and the
/// verdict and radius of `hapstab::System::analysis`.
fn assert_vertices_are_on_the_boundary(s: &Server, j: &serde_json::Value) {
    // vertices [K, B] in N/m and Ns/m, asked back in the loop's wall units
    let (kpa, bpb) = (
        j["physical"]["k_per_unit"].as_f64().unwrap(),
        j["physical"]["b_per_unit"].as_f64().unwrap(),
    );
    let poly: Vec<[f64; 2]> = j["region"]["polygons"][0]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| [v[0].as_f64().unwrap() / kpa, v[1].as_f64().unwrap() / bpb])
        .collect();
    assert!(poly.len() > 10, "{j}");
    // Vertices on the z = 1 line a = −γ are double roots at z = 1 amid the plant's cluster
    // of roots near 1, where roots of the z-coefficients are ill-conditioned: sample the rest.
    let lp = two_mass_loop();
    let sys = hapstab::System::of(&lp).unwrap();
    // the z = 1 line lies at a = −(static stiffness in wall units); the loop has no (γ, δ, d)
    assert!(j["params"].is_null(), "{j}");
    let gamma = lp.plant.dc_stiffness().unwrap() / sys.family().scale.stiffness;
    let arcs: Vec<&[f64; 2]> = poly
        .iter()
        .filter(|v| (v[0] + gamma).abs() > 1e-6 * gamma)
        .collect();
    assert!(arcs.len() > 8, "{j}");
    for v in arcs.iter().step_by(arcs.len() / 8) {
        let [a, b] = **v;
        let p = s
            .get(&format!("/api/point?{TWO_MASS_LOOP}&alpha={a}&beta={b}"))
            .json();
        let rho = p["spectral_radius"].as_f64().unwrap();
        assert!((rho - 1.0).abs() < 1e-6, "vertex ({a}, {b}): rho {rho}");
        // on the boundary too, the verdict is check's (`hapstab::loop_analysis::analysis`)
        let an = sys.analysis((a, b)).unwrap();
        assert_eq!(p["verdict"], an.verdict.as_str(), "vertex ({a}, {b})");
        // (serde_json's float parser may be an ulp off the server's shortest form)
        assert!(
            (rho - an.spectral_radius).abs() <= 1e-15,
            "vertex ({a}, {b})"
        );
    }
}

/// The explorer's point at the wall (K, B) = (`ks`, `bs`) is `hapstab check`'s.
fn assert_point_is_checks(s: &Server, ks: &str, bs: &str) {
    let p = s
        .get(&format!(
            "/api/point?{TWO_MASS_LOOP}&wall_stiffness={ks}&wall_damping={bs}"
        ))
        .json();
    let mut args = vec!["check"];
    args.extend(TWO_MASS_FLAGS);
    args.extend(["--wall-stiffness", ks, "--wall-damping", bs]);
    let check = common::json(&args);
    assert_eq!(p["verdict"], check["verdict"]);
    let (r1, r2) = (
        p["spectral_radius"].as_f64().unwrap(),
        check["spectral_radius"].as_f64().unwrap(),
    );
    assert!((r1 - r2).abs() <= 1e-12, "{r1} vs {r2}");
    assert!(p["linear"].is_null());
}

/// The explorer's simulated contact with the wall (`ks`, `bs`) is `hapstab simulate`'s.
fn assert_simulation_is_simulates(s: &Server, ks: &str, bs: &str) {
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
        ks,
        "--wall-damping",
        bs,
        "--unilateral",
        "--push",
        "1",
    ]);
    args.extend(["--initial-position", "0", "--initial-velocity", "0.01"]);
    args.extend(["--duration-samples", &samples]);
    let cli = common::json(&args);
    assert_same_simulation(&cli, &sim);
    assert_eq!(sim["linear_verdict"], "stable");
}

/// The margins and the passivity of a clicked wall, on every kind of loop, are those of
/// `hapstab check --json` and `hapstab passivity --json` on the same loop and wall, bit for
/// bit (the margins under the same keys).
#[test]
fn point_margins_and_passivity_are_the_cli_s() {
    let s = Server::start(&[]);
    const ARM: &str = "arm_mass=1&arm_damping=6&arm_stiffness=350";
    let paper = format!("mode=physical&device_mass=0.1&device_damping=1.5&{ARM}&period=0.001");
    let cases: Vec<(String, Vec<&str>)> = vec![
        (format!("{paper}&d=1"), vec!["--delay", "1"]),
        (
            format!("{paper}&delay_time=0.00037&estimator=lowpass%3A100"),
            vec!["--delay-time", "0.00037", "--velocity", "lowpass:100"],
        ),
        (
            format!(
                "mode=physical&motor_mass=0.05&handle_mass=0.05&transmission_stiffness=5000&{ARM}&period=0.001&force_lag=0.0002&d=0"
            ),
            vec![
                "--motor-mass",
                "0.05",
                "--handle-mass",
                "0.05",
                "--transmission-stiffness",
                "5000",
                "--force-lag",
                "0.0002",
            ],
        ),
        (
            "mode=physical&plant_num=10&plant_den=1,3,10&period=0.001&d=2".into(),
            vec!["--plant-num", "10", "--plant-den", "1,3,10", "--delay", "2"],
        ),
    ];
    for (query, flags) in &cases {
        for (k, b) in [("300", "0.5"), ("3000", "2")] {
            let p = s
                .get(&format!(
                    "/api/point?{query}&wall_stiffness={k}&wall_damping={b}"
                ))
                .json();
            let mut args = vec!["check"];
            args.extend(flags);
            args.extend(["--wall-stiffness", k, "--wall-damping", b]);
            let check = common::json(&args);
            assert_eq!(p["verdict"], check["verdict"], "{query} {k} {b}");
            let m = p["margins"].as_object().unwrap();
            assert!(m.len() >= 15, "{m:?}");
            for (key, v) in m {
                assert_eq!(v, &check[key], "{query} K = {k}: {key}");
            }
            args[0] = "passivity";
            let pass = common::json(&args);
            assert_eq!(p["passivity"]["verdict"], pass["verdict"], "{query}");
            assert_eq!(
                p["passivity"]["requirement"]["b_required"], pass["b_required"],
                "{query}"
            );
            assert_eq!(
                p["passivity"]["device"]["damping"], pass["device_damping"],
                "{query}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------
// K_max: the region's K_max and the robust region over the arm's stiffness are `hapstab
// kmax`'s; the robust K_max over a box is `hapstab kmax --robust --box … --json`'s bit for
// bit (same loop, box, damping, samples, verification and seed), with the same text.
// ---------------------------------------------------------------------------------------

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
    let kpa = j["physical"]["k_per_unit"].as_f64().unwrap();
    let k_max = rob["alpha_max"].as_f64().unwrap() * kpa;
    let cli = common::json(&[
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

/// The region's K_max at B = 0, over the renderable band and over B ≥ 0 are `hapstab kmax`'s,
/// bit for bit, for the paper's loop in physical units and for a loop beyond it.
#[test]
fn region_carries_the_kmax_of_the_command_line() {
    let s = Server::start(&[]);
    for (query, flags) in [
        (
            "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&delay_time=0.001",
            vec!["kmax", "--delay", "1"],
        ),
        (
            "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&delay_time=0&estimator=lowpass:100",
            vec!["kmax", "--velocity", "lowpass:100"],
        ),
    ] {
        let r = s.get(&format!("/api/region?{query}"));
        assert_eq!(r.status, 200, "{}", r.body);
        let api = &r.json()["kmax"];
        let cli = common::json(&flags);
        for key in ["k_max", "b_at_k_max", "k_max_at_zero_damping"] {
            assert_eq!(api[key], cli[key], "{query}: {key}");
        }
        assert_eq!(api["renderable"], cli["renderable"], "{query}");
    }
    // normalized mode has no physical K_max
    let r = s.get("/api/region?gamma=0.001&delta=0.015&d=1");
    assert!(r.json()["kmax"].is_null());
}

/// [`TWO_MASS_LOOP`]'s flags for `hapstab`, the arm and the period spelled out.
const TWO_MASS_FLAGS_IN_FULL: [&str; 22] = [
    "--motor-mass",
    "0.05",
    "--handle-mass",
    "0.05",
    "--transmission-stiffness",
    "5000",
    "--transmission-damping",
    "1",
    "--arm-mass",
    "1",
    "--arm-damping",
    "6",
    "--arm-stiffness",
    "350",
    "--period",
    "0.001",
    "--delay-time",
    "0.0014",
    "--velocity",
    "lowpass:150",
    "--force-lag",
    "0.0002",
];

/// The explorer's answer for `loop_query` + `box_query` equals `hapstab kmax --robust` with
/// `flags`: the whole JSON object, the numbers' exact decimals, and the text's lines.
fn assert_same_as_the_command_line(s: &Server, loop_query: &str, box_query: &str, flags: &[&str]) {
    let r = s.get(&format!("/api/region?{loop_query}&{box_query}"));
    assert_eq!(r.status, 200, "{box_query}: {}", r.body);
    let api = r.json();
    let mut args = vec!["kmax", "--robust"];
    args.extend_from_slice(flags);
    let mut json_args = args.clone();
    json_args.push("--json");
    let cli_text = common::text(&json_args);
    let cli: serde_json::Value = serde_json::from_str(&cli_text).unwrap();
    assert_eq!(api["robust_kmax"], cli, "{box_query}");
    let api_text = &r.body[r.body.find("\"robust_kmax\":").unwrap()..];
    for key in ["k_max", "k_min", "k_max_nominal"] {
        let (a, c) = (
            raw_number(api_text, "\"wall_damping\"", key),
            raw_number(&cli_text, "\"wall_damping\"", key),
        );
        assert_eq!(a.to_bits(), c.to_bits(), "{box_query}: {key}");
    }
    assert!(cli["k_max"].as_f64().is_some(), "a robust K_max: {cli}");
    // the same words: the command line's text ends with the explorer's lines
    let text = common::text(&args);
    let lines: Vec<&str> = text.lines().collect();
    let api_lines: Vec<&str> = api["robust_kmax_text"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap())
        .collect();
    assert_eq!(lines[lines.len() - api_lines.len()..], api_lines[..]);
    assert!(
        api_lines
            .iter()
            .any(|l| l.contains("random plants verified"))
    );
}

#[test]
fn the_explorer_robust_k_max_is_the_command_line_s() {
    let s = Server::start(&[]);
    assert_same_as_the_command_line(
        &s,
        PAPER_LOOP,
        &format!(
            "box={}&wall_damping=5",
            enc("arm-stiffness:0:2000,arm-mass:0.2:2")
        ),
        &[
            "--delay",
            "1",
            "--box",
            "arm-stiffness:0:2000",
            "--box",
            "arm-mass:0.2:2",
            "--wall-damping",
            "5",
        ],
    );
    let mut flags = TWO_MASS_FLAGS_IN_FULL.to_vec();
    flags.extend([
        "--box",
        "transmission-stiffness:3000:8000",
        "--box",
        "cutoff:100:200",
        "--wall-damping",
        "2",
        "--samples",
        "64",
        "--verify",
        "2000",
        "--seed",
        "7",
    ]);
    assert_same_as_the_command_line(
        &s,
        TWO_MASS_LOOP,
        &format!(
            "box={}&wall_damping=2&samples=64&verify=2000&seed=7",
            enc("transmission-stiffness:3000:8000,cutoff:100:200")
        ),
        &flags,
    );
}

// ---------------------------------------------------------------------------------------
// A simulated contact: the explorer's verdict is the analysis's and `hapstab simulate`'s.
// ---------------------------------------------------------------------------------------

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
    assert!(j["trace_clipped"].is_null(), "a limit cycle is not cut");
    // the flags of `hapstab simulate` the answer names for this run (unilateral, 1 N push,
    // entered at x = 0 with 10 mm/s) are the ones used below
    let samples = j["requested_samples"].as_u64().unwrap();
    let flags = j["simulate_flags"].as_str().unwrap();
    assert_eq!(
        flags,
        format!(
            "--unilateral --push 1 --initial-position 0 --initial-velocity 0.01 --duration-samples {samples}"
        )
    );

    // hapstab simulate with the same setting and run length: the same verdict.
    let mut args = vec!["simulate", "--device-mass", "0.2", "--device-damping", "2"];
    args.extend([
        "--delay",
        "1",
        "--wall-stiffness",
        "20000",
        "--wall-damping",
        "5",
    ]);
    args.extend(flags.split(' '));
    assert_same_simulation(&common::json(&args), &j);
}

/// `hapstab simulate --json`'s answer and the explorer's agree on the run and its verdict,
/// key for key.
fn assert_same_simulation(cli: &serde_json::Value, api: &serde_json::Value) {
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
        assert_eq!(cli[key], api[key], "{key}");
    }
}
