//! P(stable) over a population of operators (`hapstab::population`): Wilson's interval
//! against published values, the curve (each operator's exact stable interval) against the
//! verdict-only count at walls (two independent methods on the same seeded operators), the
//! level stiffness against the curve on both sides, and the distributions' moments.

use hapstab::model::{Delay, Loop, Plant, VelocityEstimator};
use hapstab::params::{Arm, Device, Wall};
use hapstab::population::{
    Dist, Population, Z95, count_at, stability_probability, wall_probability, wilson,
};
use hapstab::sweep::SweepParam;

fn held_device() -> Loop {
    let plant = Plant::held_device(Device::PHANTOM_LIKE, Arm::TYPICAL).unwrap();
    Loop::new(
        plant,
        1e-3,
        Delay::samples(1).unwrap(),
        VelocityEstimator::Backward,
    )
    .unwrap()
}

#[test]
fn wilson_matches_published_intervals() {
    // Newcombe, Stat. Med. 17 (1998), Table I: 0/10 → [0, 0.2775], 1/29 → [0.0061, 0.1718],
    // 81/263 → [0.2553, 0.3662] (95 %, method 3)
    for (k, n, lo, hi) in [
        (0, 10, 0.0, 0.2775),
        (1, 29, 0.0061, 0.1718),
        (81, 263, 0.2553, 0.3662),
    ] {
        let [a, b] = wilson(k, n, Z95);
        assert!(
            (a - lo).abs() < 5e-5 && (b - hi).abs() < 5e-5,
            "{k}/{n}: {a} {b}"
        );
    }
}

#[test]
fn the_curve_counts_what_the_verdict_counts() {
    let lp = held_device();
    let pop = Population::SectionIv;
    let b = 5.0;
    let curve = stability_probability(&lp, &pop, b, 3000, 7, &[0.99, 0.999]).unwrap();
    for k in [0.0, 2e3, 8e3, 1.2e4, 1.5e4, 3e4] {
        let w = Wall {
            stiffness: k,
            damping: b,
        };
        let by_verdict = wall_probability(&lp, &pop, w, 3000, 7).unwrap();
        assert_eq!(by_verdict.draws, curve.draws);
        let by_interval = count_at(&curve.intervals, k);
        assert_eq!(by_verdict.stable, by_interval, "K = {k}");
    }
}

#[test]
fn level_stiffness_is_where_the_curve_crosses_the_level() {
    let lp = held_device();
    let n = 4000;
    let levels = [0.9, 0.99, 0.999];
    let r = stability_probability(&lp, &Population::SectionIv, 2.0, n, 3, &levels).unwrap();
    assert_eq!(r.levels.len(), levels.len());
    for l in &r.levels {
        let k = l.k.unwrap();
        let below = count_at(&r.intervals, k * (1.0 - 1e-9));
        let above = count_at(&r.intervals, k * (1.0 + 1e-9));
        assert!(below as f64 >= l.level * n as f64, "{l:?}: {below}");
        assert!((above as f64) < l.level * n as f64, "{l:?}: {above}");
        let (lo, hi) = (l.k_lo.unwrap(), l.k_hi.unwrap());
        assert!(lo <= k && k <= hi, "{l:?}");
    }
}

#[test]
fn independent_distributions_have_their_moments() {
    let lp = held_device();
    let pop = Population::Independent {
        params: vec![
            (SweepParam::ArmMass, Dist::parse("uniform:0.5:1.5").unwrap()),
            (
                SweepParam::ArmStiffness,
                Dist::parse("normal:400:50").unwrap(),
            ),
            (
                SweepParam::ArmDamping,
                Dist::parse("lognormal:5:0.3").unwrap(),
            ),
        ],
    };
    let w = Wall {
        stiffness: 1e4,
        damping: 5.0,
    };
    let r = wall_probability(&lp, &pop, w, 20_000, 11).unwrap();
    let col = |j: usize| r.draws.iter().map(|d| d[j]).collect::<Vec<f64>>();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let (m, k, c) = (col(0), col(1), col(2));
    assert!((mean(&m) - 1.0).abs() < 0.01, "{}", mean(&m));
    assert!((mean(&k) - 400.0).abs() < 1.5, "{}", mean(&k));
    let sd = (k.iter().map(|x| (x - 400.0).powi(2)).sum::<f64>() / k.len() as f64).sqrt();
    assert!((sd - 50.0).abs() < 1.5, "{sd}");
    let mut logs: Vec<f64> = c.iter().map(|x| x.ln()).collect();
    logs.sort_by(f64::total_cmp);
    assert!((logs[logs.len() / 2] - 5f64.ln()).abs() < 0.02);
}

#[test]
fn bad_input_names_the_parameter() {
    let lp = held_device();
    assert!(
        Dist::parse("uniform:2:1")
            .unwrap_err()
            .to_string()
            .contains("distribution")
    );
    assert!(
        Dist::parse("gamma:1:2")
            .unwrap_err()
            .to_string()
            .contains("unknown kind")
    );
    let e = stability_probability(&lp, &Population::SectionIv, 0.0, 10, 1, &[1.5]);
    assert!(e.unwrap_err().to_string().contains("level"));
    let e = stability_probability(&lp, &Population::SectionIv, 0.0, 0, 1, &[0.9]);
    assert!(e.unwrap_err().to_string().contains("samples"));
    // a device without an arm cannot take the default population of arms
    let bare = Plant::mass_spring_damper(hapstab::Effective::new(0.1, 1.5, 0.0).unwrap()).unwrap();
    let bare = Loop::new(
        bare,
        1e-3,
        Delay::samples(0).unwrap(),
        VelocityEstimator::Backward,
    );
    let e = stability_probability(&bare.unwrap(), &Population::SectionIv, 0.0, 10, 1, &[0.9]);
    assert!(
        e.unwrap_err()
            .to_string()
            .contains("population of Section IV draws the arm")
    );
}
