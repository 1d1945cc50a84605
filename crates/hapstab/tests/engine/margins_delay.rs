//! The exact delay margin against the certified delay scan, an independent method: the scan
//! steps the total delay upward by a bound on how far the Nyquist curve can move, tests every
//! step with the Schur–Cohn verdict on the exact fractional-delay discretization and bisects
//! the first change — no crossover, no seed, no Newton step. On seeded loops of every kind
//! (`common::loops`) the two agree:
//! - a crossing of the scan is the exact margin to 1e-9 (relative) at the same frequency, or
//!   lies just below it with the verdict marginal between the two (the verdict calls a root
//!   within 5e-11 of the circle marginal, so the scan stops where a slow root enters that
//!   band, a hair before it reaches the circle);
//! - where the scan finds none up to the largest modelled delay, the exact search reports none;
//! - where the scan stops at its work bound, the exact margin is not below the scan's bound.
//!
//! `HAPSTAB_DELAY_LOOPS=N` sets the number of loops (120 by default).

use crate::common;
use common::SplitMix;
use common::loops::{random_loop, stable_wall, verdict};
use hapstab::AffineFamily;
use hapstab::margins::{DelayScan, delay_margin, delay_scan};
use hapstab::model::{Delay, Loop};
use hapstab::params::Wall;
use hapstab::verdict::Verdict;
use rayon::prelude::*;

fn loops(n: usize) -> Vec<(Loop, Wall)> {
    let mut rng = SplitMix(0xD31A7);
    let mut out = Vec::new();
    let mut i = 0;
    while out.len() < n {
        i += 1;
        let Some(lp) = random_loop(&mut rng, i) else {
            continue;
        };
        // the scan's work grows with the delay: the long delays are left to the other tests
        if lp.delay.samples > 70 {
            continue;
        }
        let fam = AffineFamily::of_loop(&lp).unwrap();
        if let Some((a, b)) = stable_wall(&mut rng, &fam)
            && verdict(&lp, a, b) == Verdict::Stable
        {
            let (k, bb) = fam.to_physical(a, b);
            out.push((
                lp,
                Wall {
                    stiffness: k,
                    damping: bb,
                },
            ));
        }
    }
    out
}

/// Compares the two on one wall; returns whether the scan found a crossing.
fn agree(lp: &Loop, wall: Wall) -> bool {
    let what = format!("{lp:?} {wall:?}");
    let (exact, _) = delay_margin(lp, wall).unwrap();
    let scan = delay_scan(lp, wall).unwrap();
    match (exact, scan) {
        (DelayScan::Crossing(e), DelayScan::Crossing(s)) => {
            // the same crossing: equal to 1e-9, or the scan's stop explained by the verdict's
            // marginal band (a slow root enters the band before it reaches the circle)
            let rel = (e.seconds - s.seconds).abs() / e.seconds;
            let between = verdict_at(lp, wall, 0.5 * (e.seconds + s.seconds));
            assert!(
                rel < 1e-9 || (s.seconds < e.seconds && between == Verdict::Marginal),
                "{what}: exact {e:?}, scan {s:?} ({rel:e}, {between:?} between)"
            );
            assert!(
                (e.theta - s.theta).abs() < 1e-4 * e.theta,
                "{what}: exact {e:?}, scan {s:?}"
            );
            true
        }
        (DelayScan::Crossing(e), DelayScan::AtLeast(t)) => {
            assert!(
                e.seconds >= t * (1.0 - 1e-9),
                "{what}: exact {e:?}, scan ≥ {t}"
            );
            false
        }
        (DelayScan::SmallGain(_) | DelayScan::StableUpToMax, DelayScan::StableUpToMax)
        | (_, DelayScan::AtLeast(_)) => false,
        (e, s) => panic!("{what}: exact {e:?}, scan {s:?}"),
    }
}

/// The verdict with the delay added (seconds).
fn verdict_at(lp: &Loop, wall: Wall, added: f64) -> Verdict {
    let lp = lp
        .with_delay(Delay::from_time(lp.delay_time() + added, lp.period).unwrap())
        .unwrap();
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let (a, b) = fam.to_units(wall.stiffness, wall.damping);
    verdict(&lp, a, b)
}

#[test]
fn the_exact_delay_margin_is_the_certified_scans_first_crossing() {
    let n = std::env::var("HAPSTAB_DELAY_LOOPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(120);
    let cases = loops(n);
    let crossings = cases.par_iter().filter(|(lp, w)| agree(lp, *w)).count();
    eprintln!("delay margins: {n} walls, {crossings} crossings found by the scan");
    assert!(crossings >= n / 2, "{crossings} of {n}");
}
