//! Loop files (`hapstab::loop_spec`): a loop written out and read back is the same loop bit
//! for bit on seeded loops of every kind; the defaults are the paper's device, arm and
//! sampling; every malformed file is refused naming the field.

use crate::common;
use common::SplitMix;
use common::loops::random_loop;
use hapstab::loop_spec::{LoopInput, parse};
use hapstab::model::{Delay, Loop, Plant, PlantModel, VelocityEstimator};
use hapstab::paper::PlantParams;
use hapstab::params::{Arm, Device, Effective, Wall};

/// The paper's default loop, built from the published constants (Section IV's device and
/// arm, T = 1 ms, backward difference, no delay).
fn paper_default() -> Loop {
    let eff = Effective::new(
        Device::PHANTOM_LIKE.mass + Arm::TYPICAL.mass,
        Device::PHANTOM_LIKE.damping + Arm::TYPICAL.damping,
        Arm::TYPICAL.stiffness,
    )
    .unwrap();
    let plant = Plant::mass_spring_damper(eff)
        .unwrap()
        .with_operator(Arm::TYPICAL)
        .unwrap();
    Loop::new(plant, 1e-3, Delay::NONE, VelocityEstimator::Backward).unwrap()
}

#[test]
fn saved_loops_load_back_bit_for_bit() {
    let mut rng = SplitMix(0x5EED_F11E);
    let mut tried = 0;
    for i in 0..400 {
        let Some(lp) = random_loop(&mut rng, i) else {
            continue;
        };
        tried += 1;
        let wall = (i % 2 == 0).then_some(Wall {
            stiffness: rng.range(-1e3, 1e5),
            damping: rng.range(-5.0, 50.0),
        });
        let text = LoopInput::new(&lp, false, wall).to_json();
        let back = parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert_eq!(back.lp, lp, "{text}");
        assert_eq!(back.wall, wall);
        assert!(!back.normalized);
        // the loop object alone, and inside a whole report
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(parse(&v["loop"].to_string()).unwrap().lp, lp);
        let report = serde_json::json!({"input": v, "verdict": "stable"});
        assert_eq!(parse(&report.to_string()).unwrap().lp, lp);
        // a sweep's report: its parameter and damping constraint beside the loop
        let mut input = v.clone();
        input["param"] = serde_json::json!({"name": "arm-stiffness", "values": [0.0, 1.0]});
        input["k_max_at"] = serde_json::json!("overall");
        let sweep = serde_json::json!({"input": input, "points": []});
        assert_eq!(parse(&sweep.to_string()).unwrap().lp, lp);
    }
    assert!(tried >= 300, "only {tried} loops");
}

#[test]
fn a_negative_zero_is_written_as_zero_as_every_report_writes_it() {
    let wall = Wall {
        stiffness: 2000.0,
        damping: -0.0,
    };
    let text = LoopInput::new(&paper_default(), false, Some(wall)).to_json();
    assert!(!text.contains("-0"), "{text}");
    assert!(text.contains("\"damping\": 0"), "{text}");
    assert_eq!(parse(&text).unwrap().wall, Some(wall));
}

#[test]
fn an_operator_and_a_force_lag_survive_the_file() {
    let lp = paper_default();
    let lp = Loop::new(
        lp.plant.with_force_lag(4e-4).unwrap(),
        5e-4,
        Delay::from_time(3.7e-4, 5e-4).unwrap(),
        "iir:0.5,0,-0.5/1,-0.2".parse().unwrap(),
    )
    .unwrap();
    let back = parse(&LoopInput::new(&lp, false, None).to_json()).unwrap();
    assert_eq!(back.lp.plant.operator, Some(Arm::TYPICAL));
    assert_eq!(back.lp, lp);
}

#[test]
fn an_empty_loop_is_the_paper_default() {
    assert_eq!(parse("{}").unwrap().lp, paper_default());
    assert_eq!(parse(r#"{"loop": {}}"#).unwrap().lp, paper_default());
    assert_eq!(parse(r#"{"loop": {}}"#).unwrap().wall, None);
}

#[test]
fn velocity_text_and_object_forms_agree() {
    let text = parse(r#"{"velocity": "lowpass:100"}"#).unwrap().lp;
    let object = parse(r#"{"velocity": {"kind": "low_pass", "cutoff_hz": 100}}"#)
        .unwrap()
        .lp;
    assert_eq!(text, object);
    assert_eq!(
        text.velocity,
        VelocityEstimator::LowPass { cutoff_hz: 100.0 }
    );
}

#[test]
fn a_delay_in_seconds_is_the_delay_in_samples() {
    let t = parse(r#"{"period": 0.0005, "delay_time": 0.00037}"#)
        .unwrap()
        .lp;
    assert_eq!(t.delay.samples, 0);
    assert!((t.delay.fraction - 0.74).abs() < 1e-12);
    // the report's delay_time beside a loop without a delay
    let echoed = parse(r#"{"loop": {"period": 0.0005}, "delay_time": 0.001}"#)
        .unwrap()
        .lp;
    assert_eq!(echoed.delay, Delay::samples(2).unwrap());
}

#[test]
fn a_transfer_function_file_as_a_user_writes_it() {
    let f = parse(
        r#"{"loop": {"plant": {"model": {"kind": "transfer_function", "num": [10], "den": [1, 3, 10]},
                              "force_lag": 0.0005},
                    "period": 0.001, "delay_time": 0.0003, "velocity": "average:4"},
            "wall": {"stiffness": 2000, "damping": 5}}"#,
    )
    .unwrap();
    assert_eq!(
        f.lp.plant.model,
        PlantModel::TransferFunction {
            num: vec![10.0],
            den: vec![1.0, 3.0, 10.0]
        }
    );
    assert_eq!(f.lp.plant.force_lag, 5e-4);
    assert_eq!(f.lp.velocity, VelocityEstimator::Average { samples: 4 });
    assert_eq!(
        f.wall,
        Some(Wall {
            stiffness: 2000.0,
            damping: 5.0
        })
    );
}

#[test]
fn a_normalized_loop_round_trips() {
    let lp = Loop::normalized(PlantParams::new(0.3, 0.1).unwrap(), 2).unwrap();
    let wall = Some(Wall {
        stiffness: 0.1,
        damping: 0.05,
    });
    let text = LoopInput::new(&lp, true, wall).to_json();
    assert!(text.contains("\"gamma\": 0.3"), "{text}");
    let back = parse(&text).unwrap();
    assert!(back.normalized);
    assert_eq!(back.lp, lp);
    assert_eq!(back.wall, wall);
}

/// The message of a refused file.
fn refusal(text: &str) -> String {
    parse(text).expect_err(text).to_string()
}

#[test]
fn malformed_files_name_the_field_and_the_value() {
    let m = refusal(r#"{"loop": {"period": "fast"}}"#);
    assert!(m.contains("loop.period") && m.contains("\"fast\""), "{m}");
    let m = refusal(r#"{"loop": {"perod": 0.001}}"#);
    assert!(m.contains("perod"), "{m}");
    let m = refusal(r#"{"loop": {"period": -0.001}}"#);
    assert!(
        m.contains("sampling period T") && m.contains("-0.001"),
        "{m}"
    );
    let m = refusal(
        r#"{"loop": {"plant": {"model": {"kind": "mass_spring_damper", "mass": -1, "damping": 1, "stiffness": 0}}}}"#,
    );
    assert!(m.contains("mass") && m.contains("-1"), "{m}");
    let m = refusal(r#"{"loop": {"velocity": "lowpass:-3"}}"#);
    assert!(m.contains("cut-off") && m.contains("-3"), "{m}");
    let m = refusal(r#"{"loop": {"delay": {"samples": 1, "fraction": 0}, "delay_time": 0.001}}"#);
    assert!(m.contains("delay"), "{m}");
    let m = refusal(r#"{"gamma": 0.3, "alpha": 0.1}"#);
    assert!(m.contains("beta"), "{m}");
    let m = refusal(r#"{"loop": {}, "wall": {"stiffness": 1}}"#);
    assert!(m.contains("wall") && m.contains("damping"), "{m}");
    let m = refusal(r#"{"loop": {}, "extra": 1}"#);
    assert!(m.contains("extra"), "{m}");
    let m = refusal("[1, 2]");
    assert!(m.contains("JSON object"), "{m}");
    let m = refusal("{\"loop\": ");
    assert!(m.contains("not JSON"), "{m}");
    for m in [
        refusal(r#"{"loop": {"period": "fast"}}"#),
        refusal("{\"loop\": "),
    ] {
        assert_eq!(m.lines().count(), 1, "{m}");
    }
}
