//! API tests of `hapstab serve` against the real server on an ephemeral loopback port:
//! loops beyond the paper's (and the paper's plant given as a loop) are analysed and
//! simulated as `hapstab check` and `hapstab simulate` do.

mod serve_support;

use hapstab::stability::Analysis;
use hapstab::{Normalized, PlantParams};
use serve_support::{Server, TWO_MASS_LOOP, hapstab_json, library_region};

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
        j["physical"]["k_per_alpha"].as_f64().unwrap(),
        j["physical"]["b_per_beta"].as_f64().unwrap(),
    );
    let (k, b) = (
        0.5 * j["region"]["alpha_max"].as_f64().unwrap() * kpa,
        0.5 * j["region"]["beta_at_alpha_max"].as_f64().unwrap() * bpb,
    );
    let (ks, bs) = (k.to_string(), b.to_string());
    assert_point_is_checks(&s, &ks, &bs);
    assert_simulation_is_simulates(&s, &ks, &bs);
}

/// The region's vertices, given back as walls, have a root on the unit circle and the
/// verdict and radius of `hapstab::loop_analysis::analysis`.
fn assert_vertices_are_on_the_boundary(s: &Server, j: &serde_json::Value) {
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
    let check = hapstab_json(&args);
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
