//! The named low-pass velocity estimators (`butterworth:N:FC`, `bessel:N:FC`,
//! `critically-damped:N:FC`) through the binary: the spec is echoed as its loop-file object and
//! read back from a loop file (object or text form) to the same answer, and
//! `sweep --param cutoff` varies FC of the family and order given, each point equal to
//! `kmax` of the loop with that cut-off.

use crate::common;

use common::{f, json, num};
use serde_json::{Value, json as js};

const FAMILIES: [(&str, &str); 3] = [
    ("butterworth", "butterworth"),
    ("bessel", "bessel"),
    ("critically-damped", "critically_damped"),
];

/// A command's JSON without its timing.
fn answer(args: &[&str]) -> Value {
    let mut v = json(args);
    if let Some(o) = v.as_object_mut() {
        o.remove("seconds");
    }
    v
}

/// `--velocity FAMILY:3:80` is echoed as {"kind", "order", "cutoff_hz"}; that loop saved as a
/// file, and the same file with the velocity as its spec text, give `kmax` the same answer
/// (the whole report, K_max and the echoed input alike).
#[test]
fn the_spec_round_trips_through_a_loop_file() {
    let dir = tempfile::tempdir().unwrap();
    for (family, kind) in FAMILIES {
        let spec = format!("{family}:3:80");
        let flags = ["kmax", "--velocity", &spec, "--wall-damping", "2"];
        let from_flags = answer(&flags);
        let velocity = &from_flags["input"]["loop"]["velocity"];
        assert_eq!(
            velocity,
            &js!({"kind": kind, "order": 3, "cutoff_hz": 80.0}),
            "{spec}"
        );
        let object = dir.path().join(format!("{kind}.json"));
        std::fs::write(&object, from_flags["input"]["loop"].to_string()).unwrap();
        let mut text_form = from_flags["input"]["loop"].clone();
        text_form["velocity"] = Value::String(spec.clone());
        let text = dir.path().join(format!("{kind}-text.json"));
        std::fs::write(&text, text_form.to_string()).unwrap();
        for file in [&object, &text] {
            let file = file.to_str().unwrap();
            let again = answer(&["kmax", "--loop", file, "--wall-damping", "2"]);
            assert_eq!(again, from_flags, "{spec}: {file}");
        }
        assert!(num(&from_flags, "k_max") > 0.0, "{from_flags}");
    }
}

/// `sweep --param cutoff:20:320:4` over a Bessel and a critically damped estimator of order 3:
/// four points, each K_max at B = 2 Ns/m that of `kmax` with `--velocity FAMILY:3:FC`.
#[test]
fn sweeping_the_cutoff_keeps_the_family_and_order() {
    for family in ["bessel", "critically-damped"] {
        let spec = format!("{family}:3:100");
        let v = json(&[
            "sweep",
            "--velocity",
            &spec,
            "--param",
            "cutoff:20:320:4",
            "--wall-damping",
            "2",
        ]);
        assert_eq!(v["unit"], "Hz", "{v}");
        let points = v["points"].as_array().unwrap();
        assert_eq!(points.len(), 4, "{v}");
        for p in points {
            let fc = f(&p["value"]);
            let one = format!("{family}:3:{fc}");
            let want = num(
                &json(&["kmax", "--velocity", &one, "--wall-damping", "2"]),
                "k_max",
            );
            let got = f(&p["k_max"]);
            assert!((got - want).abs() <= 1e-9 * want, "{one}: {got} vs {want}");
        }
    }
}
