//! The loops of an independent audit, through the command line: every K_max, region and
//! radius the commands print agrees with `check`'s verdict at the walls beside it, and the
//! discretized coefficients say when they have lost digits of the loop's roots.
//!
//! Expected values come from the verdict itself at neighbouring walls (a K_max is the end of
//! a stable interval: stable just below, unstable just above), from the exact intervals at
//! fixed damping, and from the audit's state-space referee (radius 0.99999217 of the
//! crowded-roots loop, 40-digit eigenvalues).

use crate::common;

use common::{hapstab, json};
use serde_json::Value;

fn num(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing in {v}"))
}

/// `check`'s verdict with the loop flags after the command name.
fn check(lp: &[&str], k: f64, b: f64) -> String {
    common::verdict(lp, k, b, &[])
}

/// `kmax` over every damping: K_max is confirmed by the verdict, stable just below it at a
/// damping where that is reached, unstable just above it at its own damping, and never below
/// the exact interval's end at any damping tried.
fn assert_k_max_confirmed(lp: &[&str], dampings: &[f64]) {
    let mut args = vec!["kmax"];
    args.extend(lp);
    let v = json(&args);
    let k = num(&v, "k_max");
    let b = num(&v, "b_at_k_max");
    let attained = v["k_max_attained"].as_bool().unwrap();
    let (k_stable, b_stable) = if attained {
        (k * (1.0 - 1e-6), b)
    } else {
        let ks = num(&v, "k_stable_near_k_max");
        assert!(ks <= k && ks >= k - 1e-6 * k.abs().max(1.0), "{ks} vs {k}");
        (ks, num(&v, "b_stable_near_k_max"))
    };
    assert_eq!(check(lp, k_stable, b_stable), "stable", "{lp:?}");
    assert_eq!(check(lp, k * (1.0 + 1e-6), b), "unstable", "{lp:?}");
    for &d in dampings {
        let bs = format!("--wall-damping={d:e}");
        let mut args = vec!["kmax"];
        args.extend(lp);
        args.push(&bs);
        let at = json(&args);
        if let Some(end) = at["k_max"].as_f64() {
            assert!(
                end <= k * (1.0 + 1e-9),
                "{lp:?}: K_max {k} below {end} at B = {d}"
            );
        }
    }
}

const UNDAMPED_TWO_MASS: [&str; 8] = [
    "--motor-mass=0.804655568232",
    "--transmission-stiffness=21962.7190042",
    "--handle-mass=0.417894852263",
    "--no-arm",
    "--period=0.000117311337797",
    "--force-lag=0.000175330026909",
    "--velocity=lowpass:176.784120008",
    "--motor-damping=0",
];

#[test]
fn undamped_two_mass_k_max_is_confirmed() {
    assert_k_max_confirmed(&UNDAMPED_TWO_MASS, &[1.0, 10.0, 100.0, 1000.0, 38541.107]);
}

#[test]
fn undamped_two_mass_k_max_within_a_band_is_an_interval_end() {
    let mut lp = UNDAMPED_TWO_MASS.to_vec();
    lp.push("--damping-range=0:100");
    let mut args = vec!["kmax"];
    args.extend(&lp);
    let v = json(&args);
    let (k, b) = (num(&v, "k_max"), num(&v, "b_at_k_max"));
    assert!((0.0..=100.0).contains(&b), "{b}");
    let bs = format!("--wall-damping={b:e}");
    let mut at = vec!["kmax"];
    at.extend(&UNDAMPED_TWO_MASS);
    at.push(&bs);
    let end = num(&json(&at), "k_max");
    // the band's maximum is the exact interval's end at its damping (a smooth maximum) or a
    // supremum beside it
    assert!(end <= k * (1.0 + 1e-9), "{k} vs {end}");
    assert_eq!(check(&UNDAMPED_TWO_MASS, k * (1.0 + 1e-6), b), "unstable");
}

#[test]
fn undamped_two_mass_with_a_fractional_delay_has_a_region() {
    let mut lp = UNDAMPED_TWO_MASS.to_vec();
    lp.push("--delay-time=0.000208330779878");
    // the audit's stable wall (referee ρ = 0.999992306)
    assert_eq!(check(&lp, 689.65, 0.67492), "stable");
    let mut args = vec!["boundary"];
    args.extend(&lp);
    let v = json(&args);
    assert!(num(&v, "area") > 0.0, "{}", v["area"]);
    assert_k_max_confirmed(&lp, &[0.675]);
}

#[test]
fn one_sample_delay_undamped_two_mass_is_bounded() {
    let lp = [
        "--motor-mass=0.804655568232",
        "--transmission-stiffness=21962.7190042",
        "--handle-mass=0.417894852263",
        "--no-arm",
        "--period=0.0001",
        "--delay=1",
    ];
    let mut args = vec!["boundary"];
    args.extend(lp);
    let v = json(&args);
    let area = num(&v, "area");
    assert!(area > 0.0 && area < 1e12, "area {area}");
    assert_k_max_confirmed(&lp, &[1.0, 100.0]);
}

/// A 20 kHz servo with a 10 Hz velocity filter and 0.4 ms delay: a thin region.
const THIN: [&str; 5] = [
    "--device-mass=0.25",
    "--device-damping=2",
    "--period=0.00005",
    "--velocity=lowpass:10",
    "--delay-time=0.0004",
];

#[test]
fn thin_region_answers_kmax_boundary_and_sweep() {
    assert_k_max_confirmed(&THIN, &[0.0, 20.0, 50.0, 500.0]);
    let mut band = vec!["kmax"];
    band.extend(THIN);
    band.push("--damping-range=0:50");
    let v = json(&band);
    let (k, b) = (num(&v, "k_max"), num(&v, "b_at_k_max"));
    assert!((0.0..=50.0).contains(&b));
    assert_eq!(check(&THIN, k * (1.0 + 1e-6), b), "unstable");
    let mut bd = vec!["boundary"];
    bd.extend(THIN);
    assert!(num(&json(&bd), "area") > 0.0);
    let mut sw = vec!["sweep"];
    sw.extend(THIN);
    sw.push("--param=period:0.00004:0.00006:3");
    let s = json(&sw);
    assert!(s.to_string().contains("k_max"), "{s}");
}

#[test]
fn discretize_flags_crowded_roots_and_gives_the_shifted_form() {
    let lp = [
        "--plant-num=1",
        "--plant-den=0.01,0.5,20,100,1000",
        "--period=1e-4",
        "--delay=3",
        "--velocity=lowpass:50",
        "--force-lag=1e-3",
        "--wall-stiffness=2400",
        "--wall-damping=0",
    ];
    let mut args = vec!["discretize"];
    args.extend(lp);
    let v = json(&args);
    // the referee's radius, to its 8 digits
    let rho = num(&v, "spectral_radius");
    assert!((rho - 0.99999217).abs() < 5e-9, "{rho}");
    assert!(v["ill_conditioned"].as_bool().unwrap());
    assert!((num(&v, "spectral_radius_of_coefficients") - rho).abs() > 1e-9);
    // p(1 + w) is the same polynomial: compare at z = 2 (w = 1) and z = 0 (w = −1)
    let coeffs = |key: &str| -> Vec<f64> {
        v[key]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let horner = |c: &[f64], x: f64| c.iter().fold(0.0, |acc, &ci| acc * x + ci);
    let (pz, pw) = (coeffs("characteristic"), coeffs("characteristic_shifted"));
    for (z, w) in [(2.0, 1.0), (0.0, -1.0), (1.5, 0.5)] {
        let (a, b) = (horner(&pz, z), horner(&pw, w));
        assert!(
            (a - b).abs() <= 1e-9 * a.abs().max(1.0),
            "p({z}) = {a} vs {b}"
        );
    }
    let text = hapstab().args(&args).output().unwrap();
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains("ill-conditioned") && text.contains("p(1 + w)"),
        "{text}"
    );
}

#[test]
fn discretize_of_a_well_conditioned_loop_prints_no_note() {
    let args = ["discretize", "--wall-stiffness=100", "--wall-damping=1"];
    let v = json(&args);
    assert!(!v["ill_conditioned"].as_bool().unwrap());
    let out = hapstab().args(args).output().unwrap();
    assert!(!String::from_utf8_lossy(&out.stdout).contains("ill-conditioned"));
}

#[test]
fn a_free_mass_without_wall_stiffness_is_marginal_not_a_failure() {
    // K = 0 leaves the free mass's root at z = 1 exactly: marginal, whatever the estimator
    for v in [
        "--velocity=iir:600,-500,-100/1,-0.4,0.05",
        "--velocity=lowpass:100",
    ] {
        let args = [
            "check",
            "--no-arm",
            v,
            "--wall-stiffness=0",
            "--wall-damping=10",
        ];
        let out = json(&args);
        assert_eq!(out["verdict"], "marginal", "{v}: {out}");
        assert!((num(&out, "spectral_radius") - 1.0).abs() < 1e-12, "{v}");
    }
}

#[test]
fn no_polygon_covers_an_unstable_wall_between_close_branches() {
    let lp = [
        "--plant-num=0.000551340607085,0.00831936581947",
        "--plant-den=0.334778171044,1.02955059894,4.04532782511",
        "--delay=6",
        "--period=0.00011424717289",
    ];
    let mut args = vec!["boundary"];
    args.extend(lp);
    let v = json(&args);
    let (k, b) = (20_866.99, 606.01);
    assert_eq!(check(&lp, k, b), "unstable");
    for poly in v["polygons"].as_array().unwrap() {
        let pts: Vec<(f64, f64)> = poly
            .as_array()
            .unwrap()
            .iter()
            .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
            .collect();
        // every polygon counter-clockwise (positive shoelace area)
        let n = pts.len();
        let area: f64 = (0..n)
            .map(|i| {
                let (p, q) = (pts[i], pts[(i + 1) % n]);
                p.0 * q.1 - q.0 * p.1
            })
            .sum();
        assert!(area > 0.0, "a clockwise polygon");
        // the unstable wall lies in none (even-odd rule)
        let mut inside = false;
        for i in 0..n {
            let (p, q) = (pts[i], pts[(i + 1) % n]);
            if (p.1 > b) != (q.1 > b) && k < p.0 + (b - p.1) / (q.1 - p.1) * (q.0 - p.0) {
                inside = !inside;
            }
        }
        assert!(!inside, "the unstable wall is inside a polygon");
    }
}
