//! API tests of `hapstab serve` against the real server on an ephemeral loopback port:
//! `/api/point` gives exactly the library's analysis.

mod serve_support;

use hapstab::Normalized;
use hapstab::stability::Analysis;
use serve_support::{Server, hapstab_json, raw_number};

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
        // the normalized plant's damping is all the device's: passivity applies at any d
        assert!(j["passive"].is_boolean(), "{j}");
    }
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
            let check = hapstab_json(&args);
            assert_eq!(p["verdict"], check["verdict"], "{query} {k} {b}");
            let m = p["margins"].as_object().unwrap();
            assert!(m.len() >= 15, "{m:?}");
            for (key, v) in m {
                assert_eq!(v, &check[key], "{query} K = {k}: {key}");
            }
            args[0] = "passivity";
            let pass = hapstab_json(&args);
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
