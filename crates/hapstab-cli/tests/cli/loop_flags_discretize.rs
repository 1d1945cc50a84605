//! Binary tests of `hapstab discretize` with the loop flags: closed forms and published
//! values (MATLAB's c2d documentation).

use crate::common;

use common::{floats, json, text};

/// x rounded to `digits` significant digits, as text (MATLAB's display precision).
fn round_sig(x: f64, digits: usize) -> String {
    format!("{:.*e}", digits - 1, x)
}

/// MATLAB's c2d documentation, "Discretize Model with Fractional Delay Absorbed into
/// Coefficients": h = tf(10,[1 3 10],'IODelay',0.25); hd = c2d(h,0.1) prints
/// z^(-3) * (0.01187 z^2 + 0.06408 z + 0.009721)/(z^2 - 1.655 z + 0.7408).
const MATLAB: [&str; 8] = [
    "discretize",
    "--plant-num",
    "10",
    "--plant-den",
    "1,3,10",
    "--period",
    "0.1",
    "--delay-time=0.25",
];
const MATLAB_NUM: [&str; 3] = ["0.01187", "0.06408", "0.009721"];
const MATLAB_DEN: [&str; 3] = ["1", "-1.655", "0.7408"];

#[test]
fn discretize_reproduces_matlab_c2d_example_json() {
    let v = json(&MATLAB);
    assert_eq!(v["plant"]["delay"], 3);
    let num = floats(&v["plant"]["num"]);
    let den = floats(&v["plant"]["den"]);
    assert_eq!(num.len(), 3);
    assert_eq!(den.len(), 3);
    for (got, want) in num.iter().zip(MATLAB_NUM) {
        assert_eq!(round_sig(*got, 4), round_sig(want.parse().unwrap(), 4));
    }
    for (got, want) in den.iter().zip(MATLAB_DEN) {
        assert_eq!(round_sig(*got, 4), round_sig(want.parse().unwrap(), 4));
    }
    assert_eq!(v["input"]["loop"]["period"], 0.1);
    assert_eq!(v["input"]["delay_time"], 0.25);
    assert_eq!(v["input"]["loop"]["delay"]["samples"], 2);
    assert_eq!(v["input"]["loop"]["delay"]["fraction"], 0.5);
    assert_eq!(
        v["input"]["loop"]["plant"]["model"]["kind"],
        "transfer_function"
    );
}

/// The coefficients of a polynomial as text, e.g. "0.0118732 z^2 + 0.0640836 z + 0.00972066"
/// → [0.0118732, 0.0640836, 0.00972066]; a power of z without a number has coefficient ±1.
fn coefficients_of(line: &str) -> Vec<f64> {
    let mut out = Vec::new();
    let mut sign = 1.0;
    let mut after_number = false;
    for tok in line.split_whitespace() {
        match tok {
            "+" | "-" => {
                sign = if tok == "-" { -1.0 } else { 1.0 };
                after_number = false;
            }
            t if t.starts_with('z') => {
                if !after_number {
                    out.push(sign);
                }
                after_number = false;
            }
            t => {
                out.push(sign * t.parse::<f64>().unwrap());
                after_number = true;
            }
        }
    }
    out
}

#[test]
fn discretize_text_shows_matlab_display_to_its_digits() {
    let s = text(&MATLAB);
    let lines: Vec<&str> = s.lines().collect();
    let rule = lines
        .iter()
        .position(|l| l.trim_start().starts_with("z^(-3) * ---"))
        .unwrap_or_else(|| panic!("no delay line in\n{s}"));
    let num = coefficients_of(lines[rule - 1]);
    // the denominator line starts with the unit leading term "z^2"
    let den_line = lines[rule + 1].trim();
    assert!(den_line.starts_with("z^2 - "), "{den_line}");
    let den = coefficients_of(den_line.trim_start_matches("z^2"));
    assert_eq!(num.len(), 3, "{}", lines[rule - 1]);
    for (got, want) in num.iter().zip(MATLAB_NUM) {
        assert_eq!(round_sig(*got, 4), round_sig(want.parse().unwrap(), 4));
    }
    for (got, want) in den.iter().zip(&MATLAB_DEN[1..]) {
        assert_eq!(round_sig(*got, 4), round_sig(want.parse().unwrap(), 4));
    }
    assert!(s.contains("Sample time: 0.1 seconds"), "{s}");
}

/// A pure mass m behind a zero-order hold: H(z) = T²/(2m)·(z + 1)/(z − 1)²; with the
/// backward difference V(z) = (z − 1)/(T z) the loop closes on
/// z(z − 1)² + g(z + 1)(K z + B(z − 1)/T) = 0, g = T²/(2m).
#[test]
fn discretize_pure_mass_closed_forms() {
    let (m, t, k, b) = (0.7, 1e-3, 3000.0, 4.0);
    let v = json(&[
        "discretize",
        "--mass",
        "0.7",
        "--damping",
        "0",
        "--stiffness",
        "0",
        "--wall-stiffness",
        "3000",
        "--wall-damping",
        "4",
    ]);
    let g = t * t / (2.0 * m);
    let num = floats(&v["plant"]["num"]);
    let den = floats(&v["plant"]["den"]);
    assert_eq!(v["plant"]["delay"], 0);
    for (x, y) in num.iter().zip([g, g]) {
        assert!((x - y).abs() < 1e-14 * g, "{num:?}");
    }
    for (x, y) in den.iter().zip([1.0, -2.0, 1.0]) {
        assert!((x - y).abs() < 4e-16, "{den:?}");
    }
    assert_eq!(floats(&v["velocity"]["num"]), vec![1000.0, -1000.0]);
    assert_eq!(floats(&v["velocity"]["den"]), vec![1.0, 0.0]);
    // z³ − 2z² + z + g[(K + B/T) z² + K z − (B/T) z + (K... ) ]: expand (z + 1)(c1 z − c0)
    let (c1, c0) = (k + b / t, b / t);
    let want = [1.0, -2.0 + g * c1, 1.0 + g * (c1 - c0), -g * c0];
    let p = floats(&v["characteristic"]);
    assert_eq!(p.len(), 4);
    for (x, y) in p.iter().zip(want) {
        assert!((x - y).abs() < 1e-14, "{p:?} vs {want:?}");
    }
}

/// The modified z-transform of a pure mass with a delay of half a sample:
/// N(z) = g((1 − λ)² z² + (1 + 2λ − 2λ²) z + λ²) over z (z − 1)², g = T²/(2m), λ = 1/2.
#[test]
fn discretize_fractional_delay_closed_form() {
    let v = json(&[
        "discretize",
        "--mass",
        "2",
        "--damping",
        "0",
        "--delay-time",
        "0.0005",
    ]);
    let g = 1e-6 / 4.0;
    let want = [0.25 * g, 1.5 * g, 0.25 * g];
    assert_eq!(v["plant"]["delay"], 1);
    let num = floats(&v["plant"]["num"]);
    for (x, y) in num.iter().zip(want) {
        assert!((x - y).abs() < 1e-14 * g, "{num:?}");
    }
}

/// The low-pass estimator is (1 − a)(z − 1)/(T(z − a)), a = exp(−2π f_c T).
#[test]
fn discretize_lowpass_velocity_closed_form() {
    let v = json(&["discretize", "--velocity", "lowpass:50"]);
    let a = (-2.0 * std::f64::consts::PI * 50.0 * 1e-3_f64).exp();
    let num = floats(&v["velocity"]["num"]);
    let den = floats(&v["velocity"]["den"]);
    let c = (1.0 - a) / 1e-3;
    assert!(
        (num[0] - c).abs() < 1e-12 * c && (num[1] + c).abs() < 1e-12 * c,
        "{num:?}"
    );
    assert!(
        (den[0] - 1.0).abs() < 1e-15 && (den[1] + a).abs() < 1e-15,
        "{den:?}"
    );
    // average:N is (z^N − 1)/(N T z^N)
    let v = json(&["discretize", "--velocity", "average:4"]);
    let num = floats(&v["velocity"]["num"]);
    assert_eq!(num.len(), 5);
    assert!(
        (num[0] - 250.0).abs() < 1e-12 && (num[4] + 250.0).abs() < 1e-12,
        "{num:?}"
    );
    assert_eq!(floats(&v["velocity"]["den"]), vec![1.0, 0.0, 0.0, 0.0, 0.0]);
}
