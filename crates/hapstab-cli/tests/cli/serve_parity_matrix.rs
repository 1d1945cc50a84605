//! The parity matrix of the command line and the explorer: for every kind of loop (the
//! paper's loop in physical and in normalized units, a device without an arm, a two-mass
//! device, a transfer function of order 5, the velocity estimators average, low-pass,
//! Butterworth and IIR, an actuator lag and a fractional delay), every analysis both front
//! ends have — check with its margins, K_max at one damping, over a band and overall, the
//! stable region, the map, passivity, the sweep, the Z-width and the simulated contact —
//! gives the same numbers, bit for bit: `hapstab … --json` against `hapstab serve`'s API on
//! the same loop.
//!
//! Numbers are compared as f64 with `==` after parsing both texts exactly (serde_json's
//! `float_roundtrip`, which the library turns on); the only keys skipped are wall-clock times
//! (`seconds`) and the files the command line writes (`out`, `plot`). The analyses of the
//! paper's normalized loop alone (a map over α, β, γ, δ) and of physical loops alone (K_max,
//! sweep, Z-width) are refused by both front ends in one line.

use crate::serve_support;

use crate::common;

use std::cell::Cell;

use serde_json::Value;
use serve_support::{Server, enc};

thread_local! {
    /// Numbers compared bit for bit by the test running on this thread.
    static COMPARED: Cell<usize> = const { Cell::new(0) };
}

/// Counts `n` numbers compared.
fn counted(n: usize) {
    COMPARED.with(|c| c.set(c.get() + n));
}

/// Reports (with `--nocapture`) how many numbers a test compared, and that it compared some.
fn report(test: &str) {
    let n = COMPARED.with(Cell::get);
    eprintln!("serve_parity_matrix::{test}: {n} numbers equal bit for bit");
    assert!(n > 0, "{test} compared nothing");
}

/// A kind of loop: its command-line flags and the explorer's query of the same loop.
struct Kind {
    name: &'static str,
    flags: Vec<String>,
    query: String,
    /// The paper's normalized loop (γ, δ, d; walls as α, β).
    normalized: bool,
    /// The sweep of this kind, as `--param` (NAME:LO:HI:N), and where K_max is taken
    /// (`--wall-damping B`, `--damping-range LO:HI` or over every damping).
    sweep: &'static str,
    at: At,
}

#[derive(Clone, Copy)]
enum At {
    Damping(&'static str),
    Band(&'static str, &'static str),
    Overall,
}

const ARM: &str = "arm_mass=1&arm_damping=6&arm_stiffness=350";
const DEVICE: &str = "device_mass=0.1&device_damping=1.5";

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

/// A transfer function of order 5: the paper's device and arm (1.1 s² + 7.5 s + 350) behind
/// a lightly damped 80 Hz mode and a 0.5 ms first-order lag, as descending coefficients.
fn order_5() -> (String, String) {
    let w = 2.0 * std::f64::consts::PI * 80.0;
    let mul = |p: &[f64], q: &[f64]| {
        let mut r = vec![0.0; p.len() + q.len() - 1];
        for (i, a) in p.iter().enumerate() {
            for (j, b) in q.iter().enumerate() {
                r[i + j] += a * b;
            }
        }
        r
    };
    let den = mul(
        &mul(&[1.1, 7.5, 350.0], &[1.0, 2.0 * 0.05 * w, w * w]),
        &[5e-4, 1.0],
    );
    let text = |c: &[f64]| {
        c.iter()
            .map(|x| format!("{x}"))
            .collect::<Vec<_>>()
            .join(",")
    };
    (text(&[w * w]), text(&den))
}

/// A physical kind of loop.
fn kind(name: &'static str, flags: &[&str], query: String, sweep: &'static str, at: At) -> Kind {
    Kind {
        name,
        flags: strings(flags),
        query,
        normalized: false,
        sweep,
        at,
    }
}

/// Every kind of loop: the paper's (physical and normalized), other plants, then the
/// paper's device behind each estimator, an actuator lag and a fractional delay.
fn kinds() -> Vec<Kind> {
    let mut v = plants();
    let paper = format!("mode=physical&{DEVICE}&{ARM}&period=0.001");
    let with = |extra: &str| format!("{paper}&{extra}");
    let b2 = At::Damping("2");
    v.extend([
        kind(
            "estimator average:3",
            &["--velocity", "average:3", "--delay", "1"],
            with(&format!("d=1&estimator={}", enc("average:3"))),
            "window:1:5:5",
            b2,
        ),
        kind(
            "estimator lowpass:100",
            &["--velocity", "lowpass:100"],
            with(&format!("d=0&estimator={}", enc("lowpass:100"))),
            "cutoff:50:250:5",
            b2,
        ),
        kind(
            "estimator butterworth:2:150",
            &["--velocity", "butterworth:2:150"],
            with(&format!("d=0&estimator={}", enc("butterworth:2:150"))),
            "cutoff:50:250:5",
            b2,
        ),
        kind(
            "estimator iir",
            &["--velocity", "iir:0.5,0,-0.5/1,-0.2"],
            with(&format!("d=0&estimator={}", enc("iir:0.5,0,-0.5/1,-0.2"))),
            "period:0.0005:0.0015:5",
            b2,
        ),
        kind(
            "force lag",
            &["--force-lag", "0.0004", "--delay", "1"],
            with("d=1&force_lag=0.0004"),
            "force-lag:0:0.0008:5",
            b2,
        ),
        kind(
            "fractional delay",
            &["--delay-time", "0.00037"],
            with("delay_time=0.00037"),
            "delay-time:0.0002:0.0006:5",
            b2,
        ),
    ]);
    v
}

/// The paper's loop (physical with the default device and arm, and normalized), the device
/// without an arm, a two-mass device and a transfer function of order 5.
fn plants() -> Vec<Kind> {
    let (num, den) = order_5();
    let tf_flags = ["--plant-num", &num, "--plant-den", &den, "--delay", "1"];
    vec![
        kind(
            "paper loop, physical",
            &["--period", "0.001", "--delay", "1"],
            format!("mode=physical&{DEVICE}&{ARM}&period=0.001&d=1"),
            "arm-stiffness:0:700:5",
            At::Overall,
        ),
        Kind {
            name: "paper loop, normalized",
            flags: strings(&["--gamma", "0.001", "--delta", "0.015", "--delay", "1"]),
            query: "mode=normalized&gamma=0.001&delta=0.015&d=1".into(),
            normalized: true,
            sweep: "",
            at: At::Overall,
        },
        kind(
            "mass-spring-damper without arm",
            &[
                "--no-arm",
                "--device-mass",
                "0.25",
                "--device-damping",
                "2",
                "--period",
                "0.0005",
            ],
            "mode=physical&device_mass=0.25&device_damping=2&arm_mass=0&arm_damping=0&arm_stiffness=0&period=0.0005&d=0".into(),
            "mass:0.2:0.3:5",
            At::Band("0", "20"),
        ),
        kind(
            "two-mass device",
            &[
                "--motor-mass",
                "0.3",
                "--transmission-stiffness",
                "2300",
                "--handle-mass",
                "0.1",
                "--period",
                "0.002",
            ],
            format!(
                "mode=physical&motor_mass=0.3&transmission_stiffness=2300&handle_mass=0.1&{ARM}&period=0.002&d=0"
            ),
            "transmission-stiffness:2000:3000:5",
            At::Damping("2"),
        ),
        kind(
            "transfer function of order 5",
            &tf_flags,
            format!(
                "mode=physical&plant_num={}&plant_den={}&period=0.001&d=1",
                enc(&num),
                enc(&den)
            ),
            "delay-time:0:0.002:5",
            At::Damping("2"),
        ),
    ]
}

/// `hapstab ARGS FLAGS --json` of a kind.
fn cli(args: &[&str], k: &Kind, extra: &[&str]) -> Value {
    let mut v: Vec<&str> = args.to_vec();
    v.extend(k.flags.iter().map(String::as_str));
    v.extend(extra);
    common::json(&v)
}

/// The explorer's answer (200 required).
fn api(s: &Server, path: &str, k: &Kind, extra: &str) -> Value {
    let r = s.get(&format!("{path}?{}{extra}", k.query));
    assert_eq!(r.status, 200, "{}: {path}{extra}: {}", k.name, r.body);
    r.json()
}

/// Asserts that `api` and `cli` hold the same keys (but `skip`, at any depth) and the same
/// values, numbers equal as f64; counts the numbers compared.
fn same(api: &Value, cli: &Value, skip: &[&str], at: &str) {
    match (api, cli) {
        (Value::Object(a), Value::Object(c)) => {
            let keys = |m: &serde_json::Map<String, Value>| -> Vec<String> {
                m.keys()
                    .filter(|k| !skip.contains(&k.as_str()))
                    .cloned()
                    .collect()
            };
            let (mut ka, mut kc) = (keys(a), keys(c));
            ka.sort();
            kc.sort();
            assert_eq!(ka, kc, "{at}: keys");
            for key in kc {
                same(&a[&key], &c[&key], skip, &format!("{at}.{key}"));
            }
        }
        (Value::Array(a), Value::Array(c)) => {
            assert_eq!(a.len(), c.len(), "{at}: length");
            for (i, (x, y)) in a.iter().zip(c).enumerate() {
                same(x, y, skip, &format!("{at}[{i}]"));
            }
        }
        (Value::Number(a), Value::Number(c)) => {
            let (x, y) = (a.as_f64().unwrap(), c.as_f64().unwrap());
            assert!(x == y, "{at}: explorer {x:e} vs command line {y:e}");
            counted(1);
        }
        _ => assert_eq!(api, cli, "{at}"),
    }
}

/// A wall inside the stable region of a kind, as the text both front ends read: half K_max
/// at the damping that reaches it (the command line's K_max over every damping), or
/// (α, β) = (0.02, 0.02) for the normalized loop.
fn wall(k: &Kind) -> (String, String) {
    if k.normalized {
        return ("0.02".into(), "0.02".into());
    }
    let j = cli(&["kmax"], k, &[]);
    let kmax = j["k_max"].as_f64().unwrap();
    let b = j["b_at_k_max"].as_f64().unwrap();
    (format!("{}", 0.5 * kmax), format!("{b}"))
}

/// The wall as flags and as query parameters.
fn wall_args(k: &Kind, (ks, bs): &(String, String)) -> (Vec<String>, String) {
    if k.normalized {
        (
            strings(&["--alpha", ks, "--beta", bs]),
            format!("&alpha={ks}&beta={bs}"),
        )
    } else {
        (
            strings(&["--wall-stiffness", ks, "--wall-damping", bs]),
            format!("&wall_stiffness={ks}&wall_damping={bs}"),
        )
    }
}

fn refs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

/// check: the verdict, the spectral radius and every margin of `hapstab check` are the
/// explorer's `/api/point` at the same wall (the margins under the same keys).
#[test]
fn check_and_margins() {
    let s = Server::start(&[]);
    for k in kinds() {
        let w = wall(&k);
        let (flags, query) = wall_args(&k, &w);
        let c = cli(&["check"], &k, &refs(&flags));
        let p = api(&s, "/api/point", &k, &query);
        let at = format!("{}: check", k.name);
        assert_eq!(c["verdict"], "stable", "{at}");
        same(&p["verdict"], &c["verdict"], &[], &at);
        same(&p["spectral_radius"], &c["spectral_radius"], &[], &at);
        let m = p["margins"].as_object().unwrap();
        assert!(m.len() >= 15, "{at}: {m:?}");
        for (key, v) in m {
            same(v, &c[key], &[], &format!("{at}.{key}"));
        }
    }
    report("check_and_margins");
}

/// K_max at one damping, over a band and over every damping: the whole answers are equal.
#[test]
fn kmax_three_ways() {
    let s = Server::start(&[]);
    for k in kinds().iter().filter(|k| !k.normalized) {
        let at = format!("{}: kmax", k.name);
        let c = cli(&["kmax"], k, &["--wall-damping", "2"]);
        same(&api(&s, "/api/kmax", k, "&wall_damping=2"), &c, &[], &at);
        let c = cli(&["kmax"], k, &["--damping-range", "0:20"]);
        let a = api(&s, "/api/kmax", k, "&damping_lo=0&damping_hi=20");
        same(&a, &c, &[], &format!("{at} over 0..20"));
        let c = cli(&["kmax"], k, &["--damping-range", "1:inf"]);
        let a = api(&s, "/api/kmax", k, "&damping_lo=1");
        same(&a, &c, &[], &format!("{at} over 1..inf"));
        let c = cli(&["kmax"], k, &[]);
        same(
            &api(&s, "/api/kmax", k, ""),
            &c,
            &[],
            &format!("{at} overall"),
        );
    }
    report("kmax_three_ways");
}

/// The stable region: the explorer's region answer has the keys of `hapstab boundary --json`
/// (K_max, its B, the area and the paper's normalized view in physical mode; α_max, β and
/// the area for normalized input) with the same numbers, and the same input; only its
/// polygons are simplified for drawing.
#[test]
fn region() {
    let s = Server::start(&[]);
    for k in kinds() {
        let at = format!("{}: region", k.name);
        let c = cli(&["boundary"], &k, &[]);
        let a = api(&s, "/api/region", &k, "");
        let r = &a["region"];
        let keys = c.as_object().unwrap().keys();
        for key in keys.filter(|k| !["polygons", "edges"].contains(&k.as_str())) {
            same(&r[key], &c[key], &[], &format!("{at}.{key}"));
        }
        let drawn = r["polygons"].as_array().unwrap();
        assert_eq!(drawn.len(), c["polygons"].as_array().unwrap().len(), "{at}");
    }
    report("region");
}

/// The raw numbers of the JSON array after `"key":[` in `text`, parsed exactly.
fn raw_array(text: &str, key: &str) -> Vec<f64> {
    let pat = format!("\"{key}\":[");
    let start = text.find(&pat).unwrap_or_else(|| panic!("no {key}")) + pat.len();
    let end = start + text[start..].find(']').unwrap();
    text[start..end]
        .split(',')
        .map(|t| {
            if t == "null" {
                f64::NAN
            } else {
                t.parse().unwrap()
            }
        })
        .collect()
}

/// The map: the summaries are equal and every grid point's verdict and spectral radius are
/// those of the command line's `--out` file (parsed exactly from both texts).
#[test]
fn map() {
    let s = Server::start(&[]);
    let dir = tempfile::tempdir().unwrap();
    for (i, k) in kinds().iter().enumerate() {
        let at = format!("{}: map", k.name);
        let (x, y) = if k.normalized {
            ("alpha:0:0.1:5".to_string(), "beta:0:0.4:5".to_string())
        } else {
            let j = cli(&["kmax"], k, &[]);
            let kmax = j["k_max"].as_f64().unwrap();
            let b = j["b_at_k_max"].as_f64().unwrap().abs().max(1.0);
            (
                format!("K:0:{}:5", 1.2 * kmax),
                format!("B:0:{}:5", 2.0 * b),
            )
        };
        let file = dir.path().join(format!("map{i}.csv"));
        let f = file.to_str().unwrap();
        let c = cli(&["map"], k, &["--x", &x, "--y", &y, "--radius", "--out", f]);
        let r = s.get(&format!(
            "/api/map?{}&x={}&y={}&radius=1",
            k.query,
            enc(&x),
            enc(&y)
        ));
        assert_eq!(r.status, 200, "{at}: {}", r.body);
        let a = r.json();
        // the wall-clock time differs; the command line names its --out file
        let skip = ["seconds", "out", "stable", "spectral_radius"];
        same(&a, &c, &skip, &at);
        let csv = std::fs::read_to_string(&file).unwrap();
        let rows: Vec<Vec<&str>> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').collect())
            .collect();
        let radius = raw_array(&r.body, "spectral_radius");
        let stable = a["stable"].as_array().unwrap();
        assert_eq!(rows.len(), 25, "{at}");
        for (j, row) in rows.iter().enumerate() {
            assert_eq!(stable[j].as_bool().unwrap(), row[2] == "1", "{at}[{j}]");
            let rho: f64 = row[3].parse().unwrap();
            assert!(
                rho.to_bits() == radius[j].to_bits(),
                "{at}[{j}]: {rho} vs {}",
                radius[j]
            );
            counted(2);
        }
    }
    report("map");
}

/// Passivity of one wall and the device's passive region: the whole answers are equal.
#[test]
fn passivity() {
    let s = Server::start(&[]);
    for k in kinds() {
        let w = wall(&k);
        let (flags, query) = wall_args(&k, &w);
        let c = cli(&["passivity"], &k, &refs(&flags));
        let a = api(&s, "/api/passivity", &k, &query);
        same(&a, &c, &[], &format!("{}: passivity", k.name));
    }
    report("passivity");
}

/// The sweep of one parameter per kind (5 points): equal but for the wall-clock time.
#[test]
fn sweep() {
    let s = Server::start(&[]);
    for k in kinds().iter().filter(|k| !k.normalized) {
        let mut parts = k.sweep.split(':');
        let (name, lo, hi, n) = (
            parts.next().unwrap(),
            parts.next().unwrap(),
            parts.next().unwrap(),
            parts.next().unwrap(),
        );
        let (flags, query): (Vec<String>, String) = match k.at {
            At::Damping(b) => (
                strings(&["--wall-damping", b]),
                format!("&wall_damping={b}"),
            ),
            At::Band(lo, hi) => (
                vec!["--damping-range".into(), format!("{lo}:{hi}")],
                format!("&damping_lo={lo}&damping_hi={hi}"),
            ),
            At::Overall => (vec![], String::new()),
        };
        let mut extra = vec!["--param", k.sweep];
        extra.extend(refs(&flags));
        let c = cli(&["sweep"], k, &extra);
        let a = api(
            &s,
            "/api/sweep",
            k,
            &format!("&param={name}&lo={lo}&hi={hi}&n={n}{query}"),
        );
        // the wall-clock time of the analysis differs from run to run
        same(&a, &c, &["seconds"], &format!("{}: sweep", k.name));
    }
    report("sweep");
}

/// The Z-width with a table at B = 0 and 2 Ns/m, and with the default table.
#[test]
fn zwidth() {
    let s = Server::start(&[]);
    for k in kinds().iter().filter(|k| !k.normalized) {
        let at = format!("{}: zwidth", k.name);
        let c = cli(&["zwidth"], k, &["--table-damping", "0,2"]);
        same(
            &api(&s, "/api/zwidth", k, "&table_damping=0,2"),
            &c,
            &[],
            &at,
        );
        let c = cli(&["zwidth"], k, &[]);
        same(
            &api(&s, "/api/zwidth", k, ""),
            &c,
            &[],
            &format!("{at}, default table"),
        );
    }
    report("zwidth");
}

/// The simulated contact the explorer runs (unilateral, 1 N push, entered at x = 0 with
/// 10 mm/s, its run length) is `hapstab simulate`'s with those flags.
#[test]
fn simulate() {
    let s = Server::start(&[]);
    for k in kinds() {
        let w = wall(&k);
        let (mut flags, query) = wall_args(&k, &w);
        let a = api(&s, "/api/simulate", &k, &query);
        let samples = a["requested_samples"].as_u64().unwrap().to_string();
        flags.extend(strings(&[
            "--unilateral",
            "--push",
            "1",
            "--initial-position",
            "0",
            "--initial-velocity",
            "0.01",
            "--duration-samples",
            &samples,
        ]));
        let c = cli(&["simulate"], &k, &refs(&flags));
        if k.normalized {
            // the explorer draws a normalized loop's contact at m = 1 kg and T = 1 ms, `hapstab
            // simulate` in normalized units (m = 1, T = 1): the same push and approach speed
            // are another contact; the linear analysis beside it is the same
            for key in ["spectral_radius", "linear_verdict"] {
                same(
                    &a[key],
                    &c[key],
                    &[],
                    &format!("{}: simulate.{key}", k.name),
                );
            }
            continue;
        }
        // One answer schema: every key of `hapstab simulate --json` (the run, its time
        // window, units and the echoed loop, wall, effects, push and initial state) is the
        // explorer's, with the same value; the explorer adds only its trace and notes (and
        // records a trace, every `trace_stride`-th sample, where the command line keeps none).
        let cli_keys = c.as_object().unwrap();
        assert!(cli_keys.len() > 20, "{c}");
        for (key, value) in cli_keys.iter().filter(|(key, _)| *key != "trace_stride") {
            same(
                &a[key.as_str()],
                value,
                &[],
                &format!("{}: simulate.{key}", k.name),
            );
        }
        let extra: Vec<&String> = a
            .as_object()
            .unwrap()
            .keys()
            .filter(|key| !cli_keys.contains_key(*key))
            .collect();
        assert_eq!(
            extra,
            [
                "server_ms",
                "simulate_flags",
                "trace",
                "trace_clipped",
                "units_note"
            ],
            "{}: the explorer's own keys",
            k.name
        );
    }
    report("simulate");
}

/// The command line's refusal: exit 2 and one line on standard error.
fn cli_refuses(args: &[&str]) -> String {
    let out = common::hapstab().args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).trim().to_string();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    err
}

/// The explorer's refusal: 400 with a one-line message naming `name`.
fn api_refuses(s: &Server, path: &str, name: &str) {
    let r = s.get(path);
    assert_eq!(r.status, 400, "{path}: {}", r.body);
    let j = r.json();
    assert_eq!(j["parameter"], name, "{path}: {j}");
    assert_eq!(j["error"].as_str().unwrap().lines().count(), 1, "{path}");
}

/// What only the paper's normalized loop has (a map over α, β, γ, δ) is refused for every
/// physical loop, and what only a physical loop has (K_max in N/m, the sweep, the Z-width,
/// a map over K and B) is refused for the normalized loop, by both front ends, in one line.
#[test]
fn refusals() {
    let s = Server::start(&[]);
    for k in kinds() {
        let mut args: Vec<&str> = vec!["map"];
        args.extend(refs(&k.flags));
        if k.normalized {
            args.extend(["--x", "K:0:1000:5", "--y", "B:0:10:5"]);
            cli_refuses(&args);
            api_refuses(
                &s,
                &format!("/api/map?{}&x=K:0:1000:5&y=B:0:10:5", k.query),
                "x",
            );
            for (cmd, path, extra) in [
                ("kmax", "/api/kmax", ""),
                ("zwidth", "/api/zwidth", ""),
                ("sweep", "/api/sweep", "&param=period&lo=0.001&hi=0.002&n=5"),
            ] {
                let mut a = vec![cmd];
                a.extend(refs(&k.flags));
                if cmd == "sweep" {
                    a.extend(["--param", "period:0.001:0.002:5"]);
                }
                cli_refuses(&a);
                api_refuses(&s, &format!("{path}?{}{extra}", k.query), "mode");
            }
        } else {
            args.extend(["--x", "gamma:0:1:5", "--y", "beta:0:1:5"]);
            let err = cli_refuses(&args);
            assert!(err.contains("normalized"), "{}: {err}", k.name);
            api_refuses(
                &s,
                &format!("/api/map?{}&x=gamma:0:1:5&y=beta:0:1:5", k.query),
                "x",
            );
        }
    }
}

/// The linear condition (22)/(23) is defined for the paper's loop only: where the explorer's
/// point has it (`linear` not null) `hapstab linear` computes it for the same loop (saved as a
/// loop file by `check --json`), and its α interval at the wall is the explorer's bit for bit;
/// elsewhere both refuse it (the explorer with null, the command line in one line).
#[test]
fn linear_condition() {
    let s = Server::start(&[]);
    let dir = tempfile::tempdir().unwrap();
    for (i, k) in kinds().iter().enumerate() {
        let w = wall(k);
        let (flags, query) = wall_args(k, &w);
        let p = api(&s, "/api/point", k, &query);
        let c = cli(&["check"], k, &refs(&flags));
        let file = dir.path().join(format!("loop{i}.json"));
        std::fs::write(&file, c["input"].to_string()).unwrap();
        let args = ["linear", "--loop", file.to_str().unwrap()];
        if p["linear"].is_null() {
            let err = cli_refuses(&args);
            assert!(err.contains("paper"), "{}: {err}", k.name);
            continue;
        }
        common::json(&args);
        // the linear condition (23) at the wall's β and the wall in normalized units
        let at = format!("{}: linear", k.name);
        same(&p["linear"]["alpha_upper"], &c["alpha_linear"], &[], &at);
        if !k.normalized {
            same(
                &p["params"],
                &c["normalized"],
                &[],
                &format!("{at}: (α, β, γ, δ, d)"),
            );
        }
    }
    report("linear_condition");
}
