//! Z-width (Colgate & Brown 1994) and K_max sweeps. Expected values come from closed forms
//! (the pure mass's stable interval, eq. 28 and its delayed form, the linear condition 22)
//! and from physical monotonicity, not from the modules under test.

use hapstab::model::{Delay, Loop, Plant, VelocityEstimator};
use hapstab::params::Effective;
use hapstab::passivity::DeviceDamping;
use hapstab::sweep::{KmaxAt, SweepParam, SweepRange, sweep_param};
use hapstab::zwidth::zwidth;

const T: f64 = 1e-3;

fn phantom(v: VelocityEstimator, delay: Delay) -> Loop {
    let plant = Plant::mass_spring_damper(Effective::new(0.1, 1.5, 0.0).unwrap()).unwrap();
    Loop::new(plant, T, delay, v).unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The pure mass without delay: K_max(B) = 2β(2 − β)/(2 + β)·m/T² with β = BT/m (closed form
/// of the paper's boundary, Section V), and no passive region without device damping.
#[test]
fn pure_mass_table_is_closed_form() {
    let m = 0.2;
    let plant = Plant::mass_spring_damper(Effective::new(m, 0.0, 0.0).unwrap()).unwrap();
    let lp = Loop::new(plant, T, Delay::NONE, VelocityEstimator::Backward).unwrap();
    let dampings = [10.0, 50.0, 150.0, 300.0];
    let z = zwidth(&lp, Some(&dampings)).unwrap();
    for row in &z.table {
        let beta = row.damping * T / m;
        let want = 2.0 * beta * (2.0 - beta) / (2.0 + beta) * m / (T * T);
        let got = row.k_max.unwrap();
        assert!(rel(got, want) < 1e-12, "B={}: {got} vs {want}", row.damping);
        assert!(
            row.k_min.unwrap().abs() < 1e-9 * want,
            "K > 0 at the lower end"
        );
        assert!(row.k_max_passive.is_none(), "b = 0: nothing is passive");
    }
    assert!(z.passive.as_ref().unwrap().vertices.is_empty());
}

/// The PHANToM-like device of Remark 4 (m = 0.1 kg, b = 1.5 Ns/m, T = 1 ms): the passive
/// triangle of eq. (28) inside the stable region, the linear condition (22), and K_max where
/// the region says.
#[test]
fn phantom_zwidth() {
    let lp = phantom(VelocityEstimator::Backward, Delay::NONE);
    let z = zwidth(&lp, None).unwrap();
    assert_eq!(z.device_damping, DeviceDamping::Known { damping: 1.5 });
    let p = z.passive.as_ref().unwrap();
    assert!(rel(p.k_max, 2.0 * 1.5 / T) < 1e-12);
    assert_eq!(z.passive_inside_stable, Some(true));
    let k = z.k_max.unwrap();
    // the linear condition (22) bounds K_max from above near the paper's regime and is close
    // to it (Section VII: a few percent)
    let lin = z.linear.unwrap();
    assert!(rel(lin.k_at(k.damping), (1.5 + k.damping) / (T / 2.0)) < 1e-15);
    assert!(z.table.len() == 11 && z.table[0].damping == 0.0);
    for row in &z.table {
        if let (Some(kp), Some(ks)) = (row.k_max_passive, row.k_max) {
            assert!(
                kp < ks,
                "passive K above the stable K at B = {}",
                row.damping
            );
        }
        if let Some(ks) = row.k_max {
            assert!(ks <= k.stiffness * (1.0 + 1e-9), "table above K_max");
        }
    }
    assert!(z.stable_area > p.area);
}

/// Acceptance (library side of `zwidth --compare`): on the PHANToM-like device, a low-pass
/// (100 Hz) and a 15-sample average shrink the stable region and its K_max against the
/// backward difference.
#[test]
fn filters_shrink_the_stable_region() {
    let base = zwidth(&phantom(VelocityEstimator::Backward, Delay::NONE), None).unwrap();
    // the paper's loop: (22) with b = 1.5 Ns/m and t_r = T/2
    let lin = base
        .linear
        .expect("the backward difference has the linear condition");
    assert_eq!((lin.damping, lin.effective_delay), (1.5, T / 2.0));
    for v in [
        VelocityEstimator::LowPass { cutoff_hz: 100.0 },
        VelocityEstimator::Average { samples: 15 },
    ] {
        let z = zwidth(&phantom(v.clone(), Delay::NONE), None).unwrap();
        assert!(z.stable_area < base.stable_area, "{v:?}");
        // the linear condition (22) is the backward difference's; a filtered loop has none
        assert!(z.linear.is_none(), "{v:?}");
        assert!(z.table.iter().all(|r| r.k_linear.is_none()), "{v:?}");
        assert!(
            z.k_max.unwrap().stiffness < base.k_max.unwrap().stiffness,
            "{v:?}"
        );
    }
}

#[test]
fn sweep_ranges_parse_and_refuse() {
    let r: SweepRange = "delay-time:0:0.005:51".parse().unwrap();
    assert_eq!(r.param, SweepParam::DelayTime);
    assert_eq!(r.values().len(), 51);
    assert!((r.value(50) - 0.005).abs() < 1e-18);
    for bad in [
        "delay:0:1:5",
        "period:0:1",
        "period:a:1:5",
        "period:0:1:1",
        "cutoff:0:1:2.5",
    ] {
        let e = bad.parse::<SweepRange>().unwrap_err().to_string();
        assert!(!e.is_empty(), "{bad}");
    }
    let e = "delay:0:1:5".parse::<SweepRange>().unwrap_err().to_string();
    assert!(e.contains("'delay'") && e.contains("delay-time"), "{e}");
    let lp = phantom(VelocityEstimator::Backward, Delay::NONE);
    let e = SweepParam::Cutoff.apply(&lp, 50.0).unwrap_err().to_string();
    assert!(e.contains("cutoff") && e.contains("low-pass"), "{e}");
    let e = SweepParam::ArmMass.apply(&lp, 1.0).unwrap_err().to_string();
    assert!(e.contains("arm-mass"), "{e}");
    let e = SweepParam::DelayTime
        .apply(&lp, -1e-3)
        .unwrap_err()
        .to_string();
    assert!(e.contains("delay time") && e.contains("-0.001"), "{e}");
    // the period keeps the delay time
    let d = phantom(VelocityEstimator::Backward, Delay::samples(2).unwrap());
    let p = SweepParam::Period.apply(&d, 5e-4).unwrap();
    assert_eq!(p.delay, Delay::samples(4).unwrap());
}

/// K_max against the delay: the passive K at B = 0 is b/(T/2 + t_d) at whole samples (the
/// delayed form of eq. 28) and 2b/(T·(s + ½ + √((s + ½)² + λ(1 − λ)))) between them (the
/// fractional-delay condition at θ = 0); the stable K_max falls with the delay and stays
/// above the passive one.
#[test]
fn kmax_against_delay() {
    let lp = phantom(VelocityEstimator::Backward, Delay::NONE);
    let r: SweepRange = "delay-time:0:0.005:41".parse().unwrap();
    let at = KmaxAt::Damping { damping: 0.0 };
    let pts = sweep_param(&lp, &r, at, &|_| {}).unwrap();
    let b = 1.5;
    let mut prev = f64::INFINITY;
    for p in &pts {
        let s = p.value / T;
        let lam = s - s.floor();
        let want = 2.0 * b / (T * (s + 0.5 + ((s + 0.5).powi(2) + lam * (1.0 - lam)).sqrt()));
        let got = p.k_max_passive.unwrap();
        assert!(rel(got, want) < 1e-10, "t_d = {}: {got} vs {want}", p.value);
        let k = p.k_max.unwrap();
        assert!(k < prev, "K_max must fall with the delay");
        assert!(k > got, "stable K_max {k} below passive {got}");
        prev = k;
    }
    let whole = &pts[8]; // t_d = 1 ms
    assert!(rel(whole.k_max_passive.unwrap(), b / (T / 2.0 + 1e-3)) < 1e-12);
}

/// Sweeps of the overall K_max run in parallel, report progress, and agree with single-loop
/// Z-widths; a cut-off sweep shows the low-pass costing stiffness at low cut-off.
#[test]
fn cutoff_sweep_and_progress() {
    let lp = phantom(VelocityEstimator::LowPass { cutoff_hz: 100.0 }, Delay::NONE);
    let r: SweepRange = "cutoff:20:500:12".parse().unwrap();
    let count = std::sync::atomic::AtomicUsize::new(0);
    let pts = sweep_param(&lp, &r, KmaxAt::Overall, &|_| {
        count.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    })
    .unwrap();
    assert_eq!(count.into_inner(), 12);
    for p in &pts {
        let single = zwidth(&SweepParam::Cutoff.apply(&lp, p.value).unwrap(), Some(&[])).unwrap();
        let want = single.k_max.unwrap().stiffness;
        assert!(
            rel(p.k_max.unwrap(), want) < 1e-12,
            "{:?} vs {want}",
            p.k_max
        );
    }
    assert!(pts[0].k_max.unwrap() < pts[11].k_max.unwrap());
}

/// A sweep of an arm parameter shares one passive computation between its points (they have
/// the same sampled wall and device damping): each point's passive K_max equals the one
/// computed for its own loop alone, at every damping constraint, and eq. (28)'s figure with
/// the arm's damping counted follows the arm damping swept.
#[test]
fn shared_passive_kmax_equals_each_points_own() {
    use hapstab::params::Arm;
    use hapstab::passivity::{SampledWall, k_max_passive_at, passive_k_max};
    let device = hapstab::params::Device {
        mass: 0.25,
        damping: 2.0,
    };
    let plant = Plant::held_device(device, Arm::TYPICAL).unwrap();
    let delay = Delay::from_time(4e-4, T).unwrap();
    let lp = Loop::new(plant, T, delay, VelocityEstimator::Backward).unwrap();
    for (range, at) in [
        ("arm-stiffness:0:2000:7", KmaxAt::Overall),
        ("arm-damping:1:9:5", KmaxAt::Overall),
        ("arm-damping:1:9:5", KmaxAt::Damping { damping: 3.0 }),
        ("arm-mass:0.5:3:4", KmaxAt::Band { lo: 0.0, hi: 1.0 }),
    ] {
        let r: SweepRange = range.parse().unwrap();
        let pts = sweep_param(&lp, &r, at, &|_| {}).unwrap();
        for p in &pts {
            let own = r.param.apply(&lp, p.value).unwrap();
            let sw = SampledWall::new(&own).unwrap();
            let b_arm = own.plant.effective_damping().unwrap();
            let want = |b: f64| match at {
                KmaxAt::Damping { damping } => k_max_passive_at(&sw, b, damping),
                _ => passive_k_max(&sw, b).map(|w| w.stiffness),
            };
            if !matches!(at, KmaxAt::Band { .. }) {
                assert_eq!(p.k_max_passive, want(2.0), "{range} at {}", p.value);
                let with_arm = p.k_max_passive_with_arm.unwrap();
                assert!(
                    rel(with_arm, want(b_arm).unwrap()) < 1e-12,
                    "{range} at {}",
                    p.value
                );
            }
            assert_eq!(
                p.k_max_passive, pts[0].k_max_passive,
                "{range}: one device damping"
            );
        }
        if range.starts_with("arm-damping") {
            assert!(pts[0].k_max_passive_with_arm < pts[4].k_max_passive_with_arm);
        }
    }
}

/// Never contradict yourself: Z-width's K_max and its table answer what `kmax` and
/// `boundary` answer for the same loop, bit for bit — the paper's loop (analysed in α, β)
/// and a filtered one.
#[test]
fn zwidth_agrees_with_kmax_and_the_region_bit_for_bit() {
    use hapstab::System;
    use hapstab::kmax::{KmaxQuery, kmax};
    let held = Loop::paper(Effective::new(1.1, 7.5, 350.0).unwrap(), T, 1).unwrap();
    let filtered = phantom(
        VelocityEstimator::LowPass { cutoff_hz: 100.0 },
        Delay::samples(2).unwrap(),
    );
    for lp in [held, filtered] {
        let dampings = [0.0, 3.0, 11.0];
        let z = zwidth(&lp, Some(&dampings)).unwrap();
        let sys = System::of(&lp).unwrap();
        let r = sys.region().unwrap();
        let (k, b) = sys.family().to_physical(r.a_max, r.b_at_a_max);
        let zk = z.k_max.unwrap();
        assert_eq!((zk.stiffness, zk.damping), (k, b), "{lp:?}");
        for row in &z.table {
            let at = kmax(&sys, KmaxQuery::AtDamping(row.damping)).unwrap();
            let interval = at.k_interval.filter(|i| i[1].is_finite());
            assert_eq!(row.k_max, interval.map(|i| i[1]), "B = {}", row.damping);
            assert_eq!(row.k_min, interval.map(|i| i[0]), "B = {}", row.damping);
        }
    }
}

/// Never contradict yourself: every point of a sweep answers what `kmax` answers for the
/// loop at that value, bit for bit — at a damping, over a band and overall, on the paper's
/// loop (analysed in α, β) and on a filtered loop.
#[test]
fn sweep_points_equal_kmax_bit_for_bit() {
    use hapstab::System;
    use hapstab::kmax::{KmaxQuery, kmax};
    let held = Loop::paper(Effective::new(1.1, 7.5, 350.0).unwrap(), T, 1).unwrap();
    let filtered = phantom(
        VelocityEstimator::LowPass { cutoff_hz: 100.0 },
        Delay::samples(1).unwrap(),
    );
    let r: SweepRange = "arm-stiffness:100:1500:3".parse().unwrap();
    let r_delay: SweepRange = "delay-time:0.001:0.004:3".parse().unwrap();
    for (lp, r) in [(held, &r), (filtered, &r_delay)] {
        let ats = [
            (KmaxAt::Damping { damping: 4.0 }, KmaxQuery::AtDamping(4.0)),
            (
                KmaxAt::Band { lo: 0.0, hi: 6.0 },
                KmaxQuery::Band { lo: 0.0, hi: 6.0 },
            ),
        ];
        for (at, q) in ats {
            for p in sweep_param(&lp, r, at, &|_| {}).unwrap() {
                let l = r.param.apply(&lp, p.value).unwrap();
                let want = kmax(&System::of(&l).unwrap(), q).unwrap();
                assert_eq!(p.k_max, want.k_max, "{at:?} at {}", p.value);
                if let KmaxAt::Band { .. } = at {
                    assert_eq!(p.b_at_k_max, want.b_at_k_max, "{at:?} at {}", p.value);
                }
            }
        }
    }
}
