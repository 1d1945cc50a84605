//! Margins on seeded loops of every kind — transfer functions up to order 6, two-mass devices,
//! every velocity estimator, force lags, whole and fractional delays up to 600 samples, T from
//! 1e-5 to 1e-1 s — checked against independent evaluations, never against the margins
//! module's own numbers:
//! - every gain crossover has |L| = 1 to 1e-9 and every phase crossover L real;
//! - no crossover that a dense independent grid of |L| finds (uniform in θ and log-spaced down
//!   to θ = 1e-7, within 1e-4 of zero frequency) is missing;
//! - every gain and stiffness margin ×(1 ∓ 1e-6), and the delay margin ×(1 ∓ 1e-6), lie on
//!   opposite sides of the boundary by the verdict (walls whose perturbed verdict is marginal,
//!   within 5e-11 of the circle, are counted and skipped, as every front end reports them).
//!
//! `HAPSTAB_MARGIN_LOOPS=N` sets the number of loops (300 by default, the acceptance size);
//! `HAPSTAB_MARGIN_DENSE=M` the dense grid (20 000 angles by default; 10⁶ in the long run:
//! `HAPSTAB_MARGIN_DENSE=1000000 cargo test --release -p hapstab --test engine margins_property::`).

use crate::common;
use common::SplitMix;
use common::loops::{random_loop, stable_wall, verdict};
use hapstab::AffineFamily;
use hapstab::margins::{CrossingKind, loop_value, margins};
use hapstab::model::{Delay, Loop};
use hapstab::params::Wall;
use hapstab::verdict::Verdict;
use rayon::prelude::*;
use std::f64::consts::PI;

fn env(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

/// Outcome of one side check: agreed, marginal (skipped) — a disagreement panics.
fn sides(inside: Verdict, outside: Verdict, what: &str) -> bool {
    if inside == Verdict::Marginal || outside == Verdict::Marginal {
        return false;
    }
    assert_eq!(
        (inside, outside),
        (Verdict::Stable, Verdict::Unstable),
        "{what}"
    );
    true
}

/// The angles of the dense independent grid.
fn dense(m: usize) -> Vec<f64> {
    let mut ts: Vec<f64> = (1..m).map(|i| PI * i as f64 / m as f64).collect();
    let logs = m / 4;
    ts.extend((0..logs).map(|i| 1e-7 * 10f64.powf(6.0 * i as f64 / logs as f64)));
    ts.sort_by(f64::total_cmp);
    ts
}

#[test]
fn margins_agree_with_independent_evaluations() {
    let n = env("HAPSTAB_MARGIN_LOOPS", 300);
    let grid = dense(env("HAPSTAB_MARGIN_DENSE", 20_000));
    let mut rng = SplitMix(0x3A261);
    let mut cases = Vec::new();
    let mut i = 0;
    while cases.len() < n {
        i += 1;
        let Some(lp) = random_loop(&mut rng, i) else {
            continue;
        };
        let fam = AffineFamily::of_loop(&lp).unwrap();
        if let Some(w) = stable_wall(&mut rng, &fam) {
            cases.push((lp, w));
        }
    }
    let counts: Vec<[usize; 3]> = cases
        .par_iter()
        .map(|(lp, (a, b))| check_case(lp, (*a, *b), &grid))
        .collect();
    let total = counts
        .iter()
        .fold([0; 3], |s, c| [s[0] + c[0], s[1] + c[1], s[2] + c[2]]);
    eprintln!(
        "margins property: {n} loops, {total:?} (margins checked, marginal, dense crossings)"
    );
    assert!(total[0] >= 2 * n, "{total:?}");
}

/// Checks one wall; returns [side checks agreed, side checks marginal, dense crossings].
fn check_case(lp: &Loop, (a, b): (f64, f64), grid: &[f64]) -> [usize; 3] {
    let fam = AffineFamily::of_loop(lp).unwrap();
    let (k, bb) = fam.to_physical(a, b);
    let what = format!("{lp:?} K = {k:e}, B = {bb:e}");
    if verdict(lp, a, b) != Verdict::Stable {
        return [0; 3];
    }
    let m = margins(
        lp,
        Wall {
            stiffness: k,
            damping: bb,
        },
    )
    .unwrap();
    assert!(m.stable, "{what}");
    let mut agreed = [0usize; 3];
    let mut tally = |ok: bool| agreed[if ok { 0 } else { 1 }] += 1;
    let l = |t: f64| loop_value(&fam, a, b, t);
    for c in &m.crossings {
        match c.kind {
            CrossingKind::Gain => {
                let g = l(c.theta).norm();
                assert!((g - 1.0).abs() < 1e-9, "{what}: |L| = {g} at {c:?}");
            }
            CrossingKind::Phase if c.theta > 0.0 && c.theta < PI => {
                let v = l(c.theta) * c.value;
                assert!((v + 1.0).norm() < 1e-6, "{what}: t·L = {v} at {c:?}");
            }
            CrossingKind::Phase => {}
        }
    }
    for g in [m.gain, m.gain_lower].into_iter().flatten() {
        let (i, o) = side_factors(g.factor);
        tally(sides(
            verdict(lp, a * i, b * i),
            verdict(lp, a * o, b * o),
            &what,
        ));
    }
    for g in [m.stiffness, m.stiffness_lower].into_iter().flatten() {
        let (i, o) = side_factors(g.factor);
        tally(sides(verdict(lp, a * i, b), verdict(lp, a * o, b), &what));
    }
    if let Some(d) = m.delay {
        let at = |f: f64| {
            let t = lp.delay_time() + d.seconds * f;
            lp.with_delay(Delay::from_time(t, lp.period).unwrap())
                .unwrap()
        };
        tally(sides(
            verdict(&at(1.0 - 1e-6), a, b),
            verdict(&at(1.0 + 1e-6), a, b),
            &what,
        ));
    }
    let gains: Vec<f64> = m
        .crossings
        .iter()
        .filter(|c| c.kind == CrossingKind::Gain)
        .map(|c| c.theta)
        .collect();
    let g: Vec<f64> = grid.iter().map(|&t| l(t).norm().ln()).collect();
    for j in 1..grid.len() {
        if (g[j] > 0.0) != (g[j - 1] > 0.0) && g[j].abs() > 1e-12 && g[j - 1].abs() > 1e-12 {
            agreed[2] += 1;
            let (t0, t1) = (grid[j - 1], grid[j]);
            let found = gains
                .iter()
                .any(|&t| t >= t0 * (1.0 - 1e-9) && t <= t1 * (1.0 + 1e-9));
            assert!(
                found,
                "{what}: crossover in [{t0}, {t1}] missing from {gains:?}"
            );
        }
    }
    agreed
}

/// The factors just inside and just outside a margin (toward the wall, away from it).
fn side_factors(f: f64) -> (f64, f64) {
    if f > 1.0 {
        (f * (1.0 - 1e-6), f * (1.0 + 1e-6))
    } else {
        (f * (1.0 + 1e-6), f * (1.0 - 1e-6))
    }
}
