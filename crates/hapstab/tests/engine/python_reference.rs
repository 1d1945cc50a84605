//! Reference values for the Python package's acceptance tests, computed here by the library
//! alone: seeded loops of every kind (the paper's normalized and physical loops, two-mass
//! devices, transfer functions, actuator lag, fractional delays, every velocity estimator)
//! with their regions, K_max, checks at seeded walls, maps and discretizations, written to
//! `$CARGO_TARGET_TMPDIR/python_reference.json`. `crates/hapstab-py/tests/test_reference.py`
//! builds the same loops from the same numbers through the Python API and must get the same
//! results (α_max bit-equal, spectral radii to 1e-12).
//!
//! The test also checks the results against each other (so that it can fail by itself): the
//! map agrees with the checks where a check's wall lies on the map, and K_max at a damping is
//! the upper end of the stable interval the check reports there.

use hapstab::System;
use hapstab::boundary::Interval;
use hapstab::map::{Axis, AxisRange, MapKind, wall_map};
use hapstab::model::{Delay, Loop, Plant, PlantModel, TwoMass, VelocityEstimator};
use hapstab::params::{Arm, Device, Effective, Wall};
use hapstab::system::pick_interval;
use hapstab::{AffineFamily, PlantParams};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use serde_json::{Value, json};

/// The seed of the loops (fixed: the Python test reads whatever this test wrote).
const SEED: u64 = 20_081_022;
/// Loops of each kind.
const PER_KIND: usize = 3;
/// Map axes: points along K and along B.
const MAP_K: usize = 9;
const MAP_B: usize = 6;

/// How the Python side builds a loop: the constructor and its arguments.
fn description(kind: &str, lp: &Loop, extra: Value) -> Value {
    let mut v = json!({
        "kind": kind,
        "plant": lp.plant.model,
        "period": lp.period,
        "delay_time": lp.delay_time(),
        "velocity": lp.velocity.to_string(),
        "force_lag": lp.plant.force_lag,
    });
    if let (Value::Object(m), Value::Object(e)) = (&mut v, extra) {
        m.extend(e);
    }
    v
}

fn arm(rng: &mut StdRng) -> Arm {
    Arm {
        mass: rng.random_range(0.3..2.0),
        damping: rng.random_range(1.0..12.0),
        stiffness: rng.random_range(0.0..700.0),
    }
}

fn velocity(rng: &mut StdRng, i: usize) -> VelocityEstimator {
    match i % 4 {
        0 => VelocityEstimator::Backward,
        1 => VelocityEstimator::LowPass {
            cutoff_hz: rng.random_range(20.0..300.0),
        },
        2 => VelocityEstimator::Average {
            samples: rng.random_range(2..6),
        },
        _ => {
            let r: f64 = rng.random_range(0.2..0.8);
            let g = 1.0 - r;
            VelocityEstimator::Iir {
                b: vec![g * 1e3, -g * 1e3],
                a: vec![1.0, -r],
            }
        }
    }
}

/// (kind, loop, extra constructor arguments) for every seeded loop.
fn loops() -> Vec<(String, Loop, Value)> {
    let mut rng = StdRng::seed_from_u64(SEED);
    let mut out = Vec::new();
    for i in 0..PER_KIND {
        let gamma = rng.random_range(0.0..1e-3);
        let delta = rng.random_range(0.0..15e-3);
        let d = [0, 1, 3][i];
        let lp = Loop::normalized(PlantParams::new(gamma, delta).unwrap(), d).unwrap();
        let extra = json!({"gamma": gamma, "delta": delta, "d": d});
        out.push(("normalized".into(), lp, extra));
    }
    for i in 0..PER_KIND {
        let device = Device {
            mass: rng.random_range(0.05..0.5),
            damping: rng.random_range(0.0..3.0),
        };
        let a = arm(&mut rng);
        let period = [1e-3, 5e-4, 2e-3][i];
        let delay = [0.0, 1e-3, 4e-3][i];
        let e = Effective::combine(device, a).unwrap();
        let lp = Loop::new(
            Plant::mass_spring_damper(e).unwrap(),
            period,
            Delay::from_time(delay, period).unwrap(),
            VelocityEstimator::Backward,
        )
        .unwrap();
        let extra = json!({"device": device, "arm": a, "delay": delay});
        out.push(("paper".into(), lp, extra));
    }
    for i in 0..3 * PER_KIND {
        let period = [1e-3, 5e-4, 2.5e-4][i % 3];
        let model = match i % 3 {
            0 => PlantModel::MassSpringDamper(
                Effective::new(rng.random_range(0.3..2.0), rng.random_range(0.0..10.0), 0.0)
                    .unwrap(),
            ),
            1 => PlantModel::TwoMass(TwoMass {
                motor_mass: rng.random_range(0.02..0.3),
                motor_damping: rng.random_range(0.0..2.0),
                handle_mass: rng.random_range(0.02..0.3),
                transmission_stiffness: rng.random_range(5e3..5e5),
                transmission_damping: rng.random_range(0.0..10.0),
                arm: arm(&mut rng),
            }),
            _ => {
                let w: f64 = rng.random_range(20.0..200.0);
                let m: f64 = rng.random_range(0.2..2.0);
                PlantModel::TransferFunction {
                    num: vec![w],
                    den: vec![m, m * (w + 5.0), m * 5.0 * w, 0.0],
                }
            }
        };
        let lag = if i % 2 == 1 {
            rng.random_range(1e-4..1e-3)
        } else {
            0.0
        };
        let delay_time = period * rng.random_range(0.0..3.0);
        let lp = Loop::new(
            Plant::new(model, lag).unwrap(),
            period,
            Delay::from_time(delay_time, period).unwrap(),
            velocity(&mut rng, i),
        )
        .unwrap();
        out.push(("loop".into(), lp, json!({})));
    }
    out
}

fn pair(iv: Option<Interval>, fam: &AffineFamily) -> Value {
    iv.map_or(Value::Null, |iv| {
        json!([fam.to_physical(iv.lo, 0.0).0, fam.to_physical(iv.hi, 0.0).0])
    })
}

/// One check at a wall, as `hapstab.check` reports it.
fn check_at(sys: &System, w: Wall) -> Value {
    let fam = sys.family();
    let (a, b) = sys.wall_units(w).unwrap();
    let an = sys.analysis((a, b)).unwrap();
    let iv = pick_interval(&sys.stable_intervals(b), a);
    json!({
        "wall": [w.stiffness, w.damping],
        "spectral_radius": an.spectral_radius,
        "verdict": an.verdict.as_str(),
        "k_interval": pair(iv, fam),
    })
}

/// The region's α_max, K_max and sizes, as `hapstab.region` reports them.
fn region_of(sys: &System) -> Value {
    let fam = sys.family();
    let r = sys.region().unwrap();
    let (k, b) = fam.to_physical(r.a_max, r.b_at_a_max);
    json!({
        "alpha_max": r.a_max,
        "beta_at_alpha_max": r.b_at_a_max,
        "k_max": k,
        "b_at_k_max": b,
        "vertices": r.polygons.iter().map(|p| p.vertices.len()).collect::<Vec<_>>(),
        "area": r.area,
    })
}

/// A map over a uniform grid around the region, in N/m and Ns/m, with its axis values.
fn map_of(fam: &AffineFamily, k_max: f64, b_at: f64) -> (Value, AxisRange, AxisRange) {
    let (a0, b0) = fam.to_units(-0.1 * k_max, -0.2 * b_at.abs());
    let (a1, b1) = fam.to_units(1.2 * k_max, 2.0 * b_at.abs());
    let x = AxisRange::new(Axis::Alpha, a0, a1, MAP_K).unwrap();
    let y = AxisRange::new(Axis::Beta, b0, b1, MAP_B).unwrap();
    let m = wall_map(fam, x, y, MapKind::SpectralRadius, &|_| {}).unwrap();
    let ks: Vec<f64> = (0..MAP_K)
        .map(|i| fam.to_physical(x.value(i), 0.0).0)
        .collect();
    let bs: Vec<f64> = (0..MAP_B)
        .map(|i| fam.to_physical(0.0, y.value(i)).1)
        .collect();
    let v = json!({
        "wall_stiffness": ks,
        "wall_damping": bs,
        "stable": m.stable,
        "spectral_radius": m.radius,
    });
    (v, x, y)
}

fn descending(v: &[f64]) -> Vec<f64> {
    v.iter().rev().copied().collect()
}

/// The discretization, as `hapstab.discretize` reports it, at a wall.
fn discretization(lp: &Loop, w: Wall) -> Value {
    let dl = lp.discretize().unwrap();
    let fam = AffineFamily::new(&dl);
    let (a, b) = fam.to_units(w.stiffness, w.damping);
    let h = dl.plant_tf_physical();
    let v = dl.velocity_tf_physical();
    json!({
        "wall": [w.stiffness, w.damping],
        "plant_num": descending(&h.num),
        "plant_den": descending(&h.den),
        "plant_delay": h.delay,
        "velocity_num": descending(&v.num),
        "velocity_den": descending(&v.den),
        "characteristic": descending(&fam.coefficients(a, b)),
    })
}

/// Everything the Python side compares for one loop, and the internal cross-checks.
fn reference(rng: &mut StdRng, id: usize, kind: &str, lp: &Loop, extra: Value) -> Value {
    let sys = System::of(lp).unwrap();
    let fam = sys.family();
    let reg = region_of(&sys);
    let (k_max, b_at) = (
        reg["k_max"].as_f64().unwrap(),
        reg["b_at_k_max"].as_f64().unwrap(),
    );
    let (map, x, y) = map_of(fam, k_max, b_at);
    let mut checks = Vec::new();
    let mut kmax_at = Vec::new();
    for _ in 0..4 {
        let (ix, iy) = (rng.random_range(0..MAP_K), rng.random_range(0..MAP_B));
        let w = Wall {
            stiffness: map["wall_stiffness"][ix].as_f64().unwrap(),
            damping: map["wall_damping"][iy].as_f64().unwrap(),
        };
        let c = check_at(&sys, w);
        let bu = sys.damping_units(w.damping).unwrap();
        let best = sys.k_max_at_damping(bu);
        assert_map_agrees(&map, &c, ix, iy, x, y);
        kmax_at.push(json!({"wall_damping": w.damping, "k_max": best.map(|iv| fam.to_physical(iv.hi, 0.0).0), "k_interval": pair(best, fam)}));
        checks.push(c);
    }
    let band = (0.0, 0.5 * b_at.abs());
    let blo = sys.damping_units(band.0).unwrap();
    let bhi = sys.damping_units(band.1).unwrap();
    let within = sys.k_max_within(blo, bhi).unwrap().map(|p| {
        let (k, b) = fam.to_physical(p.a, p.b);
        json!({"alpha_max": p.a, "k_max": k, "b_at_k_max": b})
    });
    json!({
        "id": id,
        "loop": description(kind, lp, extra),
        "region": reg,
        "checks": checks,
        "kmax_at": kmax_at,
        "kmax_within": {"damping_range": [band.0, band.1], "result": within},
        "map": map,
        "discretize": discretization(lp, Wall { stiffness: 0.5 * k_max, damping: b_at }),
    })
}

/// A check's verdict must match the map's at the same wall (the same polynomial up to the
/// rounding of the wall's units; only far from the circle, where rounding cannot flip it).
fn assert_map_agrees(map: &Value, c: &Value, ix: usize, iy: usize, x: AxisRange, y: AxisRange) {
    let k = iy * x.n + ix;
    let rho_map = map["spectral_radius"][k].as_f64().unwrap();
    let rho = c["spectral_radius"].as_f64().unwrap();
    assert!(
        (rho_map - rho).abs() <= 1e-9 * rho,
        "map ρ {rho_map} vs check ρ {rho} at {ix},{iy} of {}x{}",
        x.n,
        y.n
    );
    if (rho - 1.0).abs() > 1e-9 {
        assert_eq!(map["stable"][k].as_bool().unwrap(), rho < 1.0);
    }
}

#[test]
fn python_reference_values() {
    let mut rng = StdRng::seed_from_u64(SEED + 1);
    let cases: Vec<Value> = loops()
        .into_iter()
        .enumerate()
        .map(|(id, (kind, lp, extra))| reference(&mut rng, id, &kind, &lp, extra))
        .collect();
    for c in &cases {
        for (check, at) in c["checks"]
            .as_array()
            .unwrap()
            .iter()
            .zip(c["kmax_at"].as_array().unwrap())
        {
            // K_max at a damping is the top of the highest stable interval there; the check's
            // interval is that one unless the wall sits in a lower stable interval.
            if let (Some(k), Some(iv)) = (at["k_max"].as_f64(), check["k_interval"].as_array()) {
                assert!(iv[1].as_f64().unwrap() <= k, "{check} vs {at}");
            }
        }
    }
    let doc = json!({"generator": "crates/hapstab/tests/engine/python_reference.rs", "seed": SEED, "cases": cases});
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("python_reference.json");
    std::fs::write(&path, serde_json::to_string_pretty(&doc).unwrap()).unwrap();
}
