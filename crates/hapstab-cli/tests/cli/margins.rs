//! Stability margins through `check`, on loops where a uniform frequency grid loses them:
//! crossovers near θ = 0, fast sampling, long delays, narrow resonances, walls beside the
//! z = 1 line. Expected values come from a 40-digit referee (the exact ZOH by partial
//! fractions in mpmath, `benches/baseline/margins_referee.py`), a dense independent
//! evaluation of |L| (numpy, 2·10⁶ log-spaced angles), or the verdict itself at walls and
//! delays beside each margin (a margin is where the verdict changes).

use crate::common;

use common::{check_json, num, verdict};
use serde_json::Value;

/// Asserts that a margin's frequency list holds a gain crossover within `rel` of `hz`.
fn has_gain_crossover(v: &Value, hz: f64, rel: f64) {
    let found = v["crossings"].as_array().unwrap().iter().any(|c| {
        c["kind"] == "gain" && (c["frequency_hz"].as_f64().unwrap() - hz).abs() <= rel * hz
    });
    assert!(found, "no gain crossover at {hz} Hz in {}", v["crossings"]);
}

/// The slow crossover of 0.5/(s³ + 2s² + s + 0.5) at T = 1 ms (θ = 6.4e-4, inside the first
/// cell of a uniform grid): the 40-digit referee gives ω_gc = 0.640246888881737 rad/s,
/// PM = 49.7315380164089°, the phase crossover 0.999625304395811 rad/s with GM =
/// 3.02727625846462 (python-control's `stability_margins` agrees to 1e-6; its 'poly'
/// method reports PM = 24.7°).
#[test]
fn crossover_near_zero_frequency_is_found_exactly() {
    let lp = ["--plant-num=0.5", "--plant-den=1,2,1,0.5", "--period=1e-3"];
    let v = check_json(&lp, 0.99, 0.0, &[]);
    let two_pi = 2.0 * std::f64::consts::PI;
    let close = |x: f64, want: f64, tol: f64| (x - want).abs() <= tol * want.abs();
    assert!(
        close(num(&v, "phase_margin_deg"), 49.7315380164089, 1e-11),
        "{v}"
    );
    assert!(close(
        num(&v, "gain_crossover_hz") * two_pi,
        0.640246888881737,
        1e-11
    ));
    assert!(close(num(&v, "gain_margin"), 3.02727625846462, 1e-11));
    assert!(close(
        num(&v, "phase_crossover_hz") * two_pi,
        0.999625304395811,
        1e-11
    ));
    assert!(v["gain_margin_lower"].is_null() || num(&v, "gain_margin_lower") < 1.0);
}

/// 25/(s³ + 10s² + 10s + 10) at T = 10 µs, K = 1: the verdict says stable, so every margin is
/// given (every root crowds z = 1; the margins use the verdict's own test), and the stiffness
/// margin is the end of the stable interval `check` prints beside it.
#[test]
fn margins_are_given_at_fast_sampling() {
    let lp = ["--plant-num=25", "--plant-den=1,10,10,10", "--period=1e-5"];
    let v = check_json(&lp, 1.0, 0.0, &[]);
    assert_eq!(v["verdict"], "stable");
    let hi = v["k_interval"][1].as_f64().unwrap();
    assert!(
        (num(&v, "stiffness_margin") - hi).abs() <= 1e-12 * hi,
        "{v}"
    );
    assert!(num(&v, "phase_margin_deg") > 0.0);
    assert!(num(&v, "stability_margin") > 0.0);
}

/// The same plant at T = 0.5 ms: the delay margin (568.9 samples) is the added delay at which
/// `check`'s spectral radius (roots polished in w = z − 1, an independent method) reaches 1,
/// found here by bisection, to 1e-9; the verdict is stable and unstable at ∓1e-6 of it (within
/// ±4e-7 the radius lies inside the marginal band of 5e-11).
#[test]
fn delay_margin_at_long_delay_is_exact() {
    let lp = ["--plant-num=25", "--plant-den=1,10,10,10", "--period=5e-4"];
    let dm = num(&check_json(&lp, 1.0, 0.0, &[]), "delay_margin");
    let flag = |t: f64| format!("{t:e}");
    let radius = |t: f64| {
        num(
            &check_json(&lp, 1.0, 0.0, &["--delay-time", &flag(t)]),
            "spectral_radius",
        )
    };
    let (mut lo, mut hi) = (0.999 * dm, 1.001 * dm);
    assert!(radius(lo) < 1.0 && radius(hi) > 1.0);
    for _ in 0..24 {
        let mid = 0.5 * (lo + hi);
        if radius(mid) < 1.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    assert!(
        (0.5 * (lo + hi) - dm).abs() <= 1e-9 * dm,
        "{dm} vs [{lo}, {hi}]"
    );
    let at = |f: f64| verdict(&lp, 1.0, 0.0, &["--delay-time", &flag(f * dm)]);
    assert_eq!(at(1.0 - 1e-6), "stable");
    assert_eq!(at(1.0 + 1e-6), "unstable");
}

/// A two-mass device held by an arm, 7.4 Hz low-pass, d = 10: |L| peaks at 1.21 near 14.34 Hz
/// between two gain crossovers (the audit's dense evaluation: max |L| ≈ 1.22 at 14.34 Hz), so
/// no small-gain claim is made, and the delay margin is where the verdict changes (the wall is
/// unstable at d = 35, as the audit found).
#[test]
fn a_narrow_resonance_is_not_missed() {
    let lp = [
        "--motor-mass=0.330007898428",
        "--transmission-stiffness=2307.62976172",
        "--handle-mass=0.0966319224952",
        "--arm-mass=2.10661470411",
        "--arm-damping=3.28339902875",
        "--arm-stiffness=1294.00325996",
        "--velocity=lowpass:7.44562256558",
        "--period=0.002304143883",
        "--delay=10",
    ];
    let v = check_json(&lp, 9.347, 0.0, &[]);
    let peak = num(&v, "peak_gain");
    assert!((1.19..1.23).contains(&peak), "{v}");
    assert!((14.3..14.4).contains(&num(&v, "peak_gain_hz")));
    let gains = v["crossings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["kind"] == "gain")
        .count();
    assert!(gains >= 2, "{}", v["crossings"]);
    let notes = v["margin_notes"].to_string();
    assert!(!notes.contains("small gain"), "{notes}");
    let dm = num(&v, "delay_margin");
    let t = 10.0 * 0.002304143883;
    let at = |f: f64| {
        verdict(
            &lp[..8],
            9.347,
            0.0,
            &["--delay-time", &format!("{:e}", t + f * dm)],
        )
    };
    assert_eq!(at(1.0 - 1e-6), "stable");
    assert_eq!(at(1.0 + 1e-6), "unstable");
    assert_eq!(verdict(&lp[..8], 9.347, 0.0, &["--delay=35"]), "unstable");
}

/// A wall near K = −k (|L| ≈ 0.98 at θ = 0): a dense independent evaluation of |L| (numpy on
/// python-control's c2d, 2·10⁶ log-spaced angles, each crossing then refined by Brent's
/// method) finds crossovers at 0.0498324132 and 0.1539208187 Hz and max |L| = 1.04457921.
#[test]
fn crossovers_beside_the_static_stiffness_are_found() {
    let lp = [
        "--mass=1.79499614825",
        "--damping=2.49124876751",
        "--stiffness=2.65620727859",
        "--velocity=average:6",
        "--delay=2",
        "--period=0.000346530517061",
    ];
    let v = check_json(&lp, -2.6, 0.0, &[]);
    has_gain_crossover(&v, 0.0498324132, 1e-6);
    has_gain_crossover(&v, 0.1539208187, 1e-6);
    assert!((num(&v, "peak_gain") - 1.04457921).abs() < 1e-7, "{v}");
}

/// The audit's unsafe delay margin (it printed 3.5e-8 s; the wall is unstable at 1.4e-8 s
/// more): the margin now lies where the verdict changes.
#[test]
fn an_unsafe_delay_margin_is_corrected() {
    let lp = [
        "--plant-num=0.00017931357856,0.26802700468,122.104258549,35740.9702254,23589.1788247",
        "--plant-den=0.444621299113,113.212747661,11241.7778948,715447.126385,35352490.2124,832064414.369",
        "--force-lag=0.00369242554853",
        "--period=0.000398512984122",
    ];
    let (k, t0) = (227.15396510462193, 0.000140373690632);
    let dm = num(
        &check_json(&lp, k, 0.0, &["--delay-time", &format!("{t0:e}")]),
        "delay_margin",
    );
    assert!(dm < 1.4e-8, "{dm}");
    let at = |f: f64| {
        verdict(
            &lp,
            k,
            0.0,
            &["--delay-time", &format!("{:e}", t0 + f * dm)],
        )
    };
    assert_eq!(at(0.9), "stable");
    assert_eq!(at(1.1), "unstable");
}

/// The audit's spurious delay margin (it printed 69.7 samples; every added delay up to the
/// largest modelled one is stable): no finite margin, and the verdict agrees far out.
#[test]
fn a_spurious_delay_margin_is_gone() {
    let lp = [
        "--plant-num=0.0698251904,214.624484102,40475.7343247,3139960.23636",
        "--plant-den=0.171644332161,131.557949678,94437.1970777,21448700.9585,5565927152.12,83811453708.0",
        "--period=0.000132553258407",
    ];
    let (k, t0) = (-26691.85708979062, 0.000194908033432);
    let v = check_json(&lp, k, 0.0, &["--delay-time", &format!("{t0:e}")]);
    assert!(v["delay_margin"].is_null(), "{v}");
    for extra in [69.7, 500.3, 1990.0] {
        let t = t0 + extra * 0.000132553258407;
        assert_ne!(
            verdict(&lp, k, 0.0, &["--delay-time", &format!("{t:e}")]),
            "unstable"
        );
    }
}

/// Both stiffness margins of a wall 0.9 % above the lower end of its stable interval:
/// 9.90961/10 downward, 14.1352/10 upward, each where the verdict changes (±1e-6).
#[test]
fn the_lower_stiffness_margin_is_reported() {
    let lp = ["--no-arm", "--velocity=average:15"];
    let v = check_json(&lp, 10000.0, -40.0, &[]);
    let (lo, hi) = (
        num(&v, "stiffness_margin_lower"),
        num(&v, "stiffness_margin"),
    );
    assert!((lo - 0.990961).abs() < 5e-7, "{v}");
    assert!((hi - 1.41352).abs() < 5e-6, "{v}");
    for (f, inside) in [
        (lo * (1.0 + 1e-6), true),
        (lo * (1.0 - 1e-6), false),
        (hi * (1.0 - 1e-6), true),
        (hi * (1.0 + 1e-6), false),
    ] {
        let want = if inside { "stable" } else { "unstable" };
        assert_eq!(verdict(&lp, 10000.0 * f, -40.0, &[]), want, "factor {f}");
    }
}

/// min |1 + L| where the bracket of the grid's sample minimum misses the true minimum, which
/// lies in the next cell. Expected: the dense independent evaluation of the python-control c2d loop (2·10⁵
/// angles, the best cells resampled 500-fold), 0.22049758763551017 for the IIR-filtered mass
/// (θ = 0.60018) and 0.5603467313987809 for the fourth-order plant with 4 samples of delay
/// (θ = 0.24574); hapstab returned 0.2205949 and 0.5603497, read at grid angles, before.
#[test]
fn the_global_minimum_of_one_plus_l_is_found() {
    let iir = [
        "--mass=1.9931523014162988",
        "--damping=4.948057959610891",
        "--stiffness=292.32713665337724",
        "--period=0.03573622266613576",
        "--velocity=iir:14.237458721930132,-14.237458721930132/1.0,-1.1623587017663588,0.6711516968531707",
    ];
    let v = check_json(&iir, 232.28600320874466, 2.0644756852718333, &[]);
    let sm = num(&v, "stability_margin");
    assert!((sm - 0.22049758763551017).abs() < 1e-11, "{sm}");
    let tf = [
        "--plant-num=0.0067188502058943495,0.056500453061890527,0.16103933740164855,0.15497536091275033",
        "--plant-den=1.0,6.788040256945405,68.16024758042889,255.2944057788163,268.00014556011087",
        "--period=0.019332551255760156",
        "--delay=4",
    ];
    let v = check_json(&tf, 723.1501491931801, 3.980278449334679, &[]);
    let sm = num(&v, "stability_margin");
    assert!((sm - 0.5603467313987809).abs() < 1e-11, "{sm}");
}

/// The default wall of `check` (the paper's device and arm, K = 10 kN/m, B = 10 Ns/m, T = 1 ms,
/// d = 0) against python-control's `stability_margins` on the same sampled loop
/// (`benches/baseline/margins_baseline.py`): gm 74.68108217503872 at 1060.0735292226464 rad/s,
/// pm 6.882606120435042° at 97.29871946463614 rad/s, sm 0.11971349105403406 — equal to 1e-7
/// (python-control's own resolution here is about 1e-9).
#[test]
fn the_default_wall_matches_python_control() {
    let v = common::json(&["check"]);
    let two_pi = 2.0 * std::f64::consts::PI;
    for (got, want) in [
        (num(&v, "gain_margin"), 74.68108217503872),
        (num(&v, "phase_crossover_hz") * two_pi, 1060.0735292226464),
        (num(&v, "phase_margin_deg"), 6.882606120435042),
        (num(&v, "gain_crossover_hz") * two_pi, 97.29871946463614),
        (num(&v, "stability_margin"), 0.11971349105403406),
    ] {
        assert!((got - want).abs() <= 1e-7 * want, "{got} vs {want}");
    }
}
