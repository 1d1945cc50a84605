//! Loop files in the explorer against the real server: "Save loop" (`/api/export?format=loop`)
//! writes a file that `hapstab check --loop` reads to the explorer's own answer, and "Open
//! loop" (`/api/open`) turns a loop the command line echoed into the page's query, whose
//! point is the command line's, bit for bit.

mod serve_support;

use serve_support::{Server, enc, hapstab_json};

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
        let check = hapstab_json(&["check", "--loop", file.to_str().unwrap()]);
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
        let check = hapstab_json(&args);
        let r = s.get(&format!(
            "/api/open?file={}",
            enc(&check["input"].to_string())
        ));
        assert_eq!(r.status, 200, "{}", r.body);
        let query = r.json()["query"].as_str().unwrap().to_string();
        // the page asks for its point by the wall in N/m, as a click on K, B does
        let at = query.split("&alpha=").next().unwrap().to_string();
        let p = s
            .get(&format!(
                "/api/point?{at}&wall_stiffness=300&wall_damping=0.5"
            ))
            .json();
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
