//! `hapstab linear` in the user's units: for a plant given in physical units the condition
//! (23) α < (β + δ)/(d + 1/2) and the bound (19) α > −γ are K < (B + b)/(T(d + 1/2)) and
//! K > −k (α = KT²/m, β = BT/m, δ = bT/m, γ = kT²/m), checked against that closed form.

use crate::common;

use common::{f, json, text};

const ARGS: [&str; 11] = [
    "linear",
    "--mass",
    "1.1",
    "--damping",
    "7.5",
    "--stiffness",
    "350",
    "--period",
    "0.002",
    "--delay",
    "1",
];

#[test]
fn linear_condition_of_a_physical_plant_is_in_newtons() {
    let (b, k, t, d) = (7.5, 350.0, 0.002, 1.0);
    let tr = t * (d + 0.5);
    let close = |x: f64, want: f64| (x - want).abs() <= 1e-12 * want.abs();
    let v = json(&ARGS);
    assert!(close(f(&v["k_linear_slope"]), 1.0 / tr), "{v}");
    assert!(close(f(&v["k_linear_intercept"]), b / tr), "{v}");
    assert!(close(f(&v["k_lower"]), -k), "{v}");
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 2);
    for p in points {
        let (kb, kk) = (f(&p["wall_damping"]), f(&p["k_linear"]));
        assert!(close(kk, (kb + b) / tr), "{p}");
        // the exact boundary lies below the linear one by the level's relative error (24)
        let ks = f(&p["wall_stiffness"]);
        assert!(ks < kk, "{p}");
    }
    let out = text(&ARGS);
    assert!(
        out.contains("K < (B + b)/(T(d + 1/2)) = 333.333/s · B + 2.5 kN/m"),
        "{out}"
    );
    assert!(out.contains("K > -350 N/m"), "{out}");
    assert!(!out.contains("α < "), "{out}");
}

#[test]
fn linear_condition_of_normalized_input_stays_in_alpha_and_beta() {
    let args = [
        "linear", "--gamma", "0.001", "--delta", "0.015", "--delay", "1",
    ];
    let v = json(&args);
    assert!(v.get("k_linear_slope").is_none(), "{v}");
    assert!(v["points"][0].get("k_linear").is_none(), "{v}");
    // (23) at d = 1: slope 1/(3/2), intercept δ/(3/2)
    assert!((f(&v["linear_slope"]) - 2.0 / 3.0).abs() < 1e-15);
    assert!((f(&v["linear_intercept"]) - 0.01).abs() < 1e-15);
    let out = text(&args);
    assert!(out.contains("α < (β + δ)/(d + 1/2)"), "{out}");
}
