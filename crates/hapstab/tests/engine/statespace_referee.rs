//! Independent check against a state-space referee: the loops of
//! `tests/fixtures/statespace_loops.json` were refereed by `benches/baseline/statespace_referee.py`
//! (numpy/scipy, and mpmath at 40 digits where double precision is doubtful), which builds
//! each loop as a closed-loop state matrix (continuous plant and actuator lag, exact
//! zero-order hold by the matrix exponential with the held interval split at the fractional
//! delay, delay states, the velocity estimator's states, the wall F = −(K·y + B·v)) and takes
//! its eigenvalues. No polynomial in z is formed there, and nothing of hapstab's is used.
//! The referee was itself checked against python-control's fixture and the paper's closed form
//! (`benches/baseline/statespace_validate.py`). Regenerate with
//! `bash benches/baseline/statespace_fixture.sh`.
//!
//! hapstab builds the same loops from the same numbers (plants in its serde form, estimators
//! in the `--velocity` text form, delays as `Delay::from_time` reads `--delay-time`) and is
//! checked, every disagreement collected and counted per category before the test fails:
//! (a) the point analysis (`loop_analysis::analysis`, i.e. `Analysis::of_family`): spectral
//!     radius and verdict; (b) the wall map at the same walls (`map::wall_map_points`), in
//!     both kinds: stability flags, and spectral radii with their flags; (c) the exact region
//!     (`loop_analysis::region`): a wall inside a polygon iff it is stable; (d) the stable
//!     stiffness intervals at the fixture's dampings (`loop_analysis::stable_intervals`).
//!
//! Every loop of the committed fixture is checked (about 20 s). A larger run: make a bigger
//! fixture elsewhere, `STATESPACE_FIXTURE=/tmp/big.json bash benches/baseline/statespace_fixture.sh
//! --loops 3000`, and point the test at it, `HAPSTAB_REFEREE_FIXTURE=/tmp/big.json cargo test
//! -p hapstab --test engine statespace_referee::`. `HAPSTAB_REFEREE_REPORT=FILE` writes every
//! disagreement to FILE.

use hapstab::AffineFamily;
use hapstab::System;
use hapstab::boundary::WallPoint;
use hapstab::map::{MapKind, wall_map_points};
use hapstab::model::{Delay, Loop, Plant, PlantModel, VelocityEstimator};
use hapstab::params::Wall;
use hapstab::region::{DEFAULT_REL_TOL, StableRegion};
use hapstab::stability::{MARGINAL_BAND, Verdict};
use rayon::prelude::*;
use serde::Deserialize;
use std::collections::BTreeMap;

/// Spectral radii must agree to this relative difference: the referee's radii are good to
/// about 1e-14 (to the nearest double on its 40-digit path), so 1e-9 leaves hapstab room for
/// the conditioning of its roots but none for a modelling difference.
const RADIUS_REL_TOL: f64 = 1e-9;
/// Verdicts are compared where the reference radius is at least hapstab's documented marginal
/// band away from 1 ([`MARGINAL_BAND`]); closer, "marginal" or either side is an answer.
const VERDICT_BAND: f64 = MARGINAL_BAND;
/// Interval ends must agree to this relative difference (of the end, or of the interval's
/// width for an end at K ≈ 0): the referee bisects its ends to 1e-12, hapstab finds them as
/// boundary crossings to near machine precision.
const INTERVAL_REL_TOL: f64 = 1e-6;

#[derive(Deserialize)]
struct Fixture {
    near_offset: f64,
    /// The referee's K scan covers |K| from 10^lo to 10^hi times each loop's `wall_scale`.
    scan_decades: [f64; 2],
    loops: Vec<Case>,
}

#[derive(Deserialize)]
struct Case {
    id: usize,
    category: String,
    cli: String,
    audit: bool,
    plant: PlantModel,
    force_lag: f64,
    period: f64,
    delay: Delay,
    delay_time: Option<f64>,
    velocity: String,
    wall_scale: Wall,
    intervals: Vec<Level>,
    walls: Vec<RefWall>,
}

/// The referee's stable stiffness intervals (N/m) at one damping (Ns/m); a missing end is
/// beyond the referee's scan (unbounded).
#[derive(Deserialize)]
struct Level {
    damping: f64,
    stiffness: Vec<[Option<f64>; 2]>,
}

#[derive(Deserialize)]
struct RefWall {
    kind: String,
    stiffness: f64,
    damping: f64,
    radius: f64,
    verdict: String,
    precise: bool,
}

/// The committed fixture, or the one `HAPSTAB_REFEREE_FIXTURE` names.
fn fixture() -> Fixture {
    let committed = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/statespace_loops.json"
    );
    let path = std::env::var("HAPSTAB_REFEREE_FIXTURE").unwrap_or_else(|_| committed.into());
    let text = std::fs::read_to_string(&path).expect("fixture statespace_loops.json");
    serde_json::from_str(&text).expect("fixture schema")
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The check categories, in the order of the summary table.
const CATEGORIES: [&str; 12] = [
    "loop refused",
    "delay form",
    "(a) analysis error",
    "(a) analysis radius",
    "(a) analysis verdict",
    "(b) map stability verdict",
    "(b) map radius",
    "(b) map radius verdict",
    "(c) region refused",
    "(c) region contains",
    "(d) interval count",
    "(d) interval ends",
];

/// Counts of checks and disagreements per category, with the disagreements described.
#[derive(Default)]
struct Tally {
    checked: BTreeMap<&'static str, usize>,
    failed: BTreeMap<&'static str, Vec<String>>,
    /// Walls excepted from the region check: within its chord tolerance of the boundary.
    region_excepted: usize,
    /// hapstab's intervals wholly within the referee's unscanned gap around K = 0.
    below_scan: usize,
}

impl Tally {
    fn check(&mut self, category: &'static str, ok: bool, what: impl FnOnce() -> String) {
        *self.checked.entry(category).or_default() += 1;
        if !ok {
            self.failed.entry(category).or_default().push(what());
        }
    }

    fn merge(mut self, other: Tally) -> Tally {
        for (k, v) in other.checked {
            *self.checked.entry(k).or_default() += v;
        }
        for (k, v) in other.failed {
            self.failed.entry(k).or_default().extend(v);
        }
        self.region_excepted += other.region_excepted;
        self.below_scan += other.below_scan;
        self
    }

    fn disagreements(&self) -> usize {
        self.failed.values().map(Vec::len).sum()
    }

    fn table(&self) -> String {
        let mut out = format!("{:<28} {:>8} {:>10}\n", "check", "checked", "disagree");
        for c in CATEGORIES {
            let n = self.checked.get(c).copied().unwrap_or(0);
            let f = self.failed.get(c).map_or(0, Vec::len);
            out += &format!("{c:<28} {n:>8} {f:>10}\n");
        }
        out += &format!(
            "(walls within the region's chord tolerance of its boundary, not region-checked: {})\n",
            self.region_excepted
        );
        out += &format!(
            "(hapstab intervals within the referee's unscanned |K| below its scan, not compared: {})\n",
            self.below_scan
        );
        out
    }
}

/// The loop as hapstab builds it from the fixture's numbers.
fn build(c: &Case) -> hapstab::Result<Loop> {
    let velocity: VelocityEstimator = c.velocity.parse()?;
    let plant = Plant::new(c.plant.clone(), c.force_lag)?;
    let delay = match c.delay_time {
        Some(t) => Delay::from_time(t, c.period)?,
        None => c.delay,
    };
    Loop::new(plant, c.period, delay, velocity)
}

fn describe(c: &Case, w: &RefWall) -> String {
    format!(
        "loop {} ({}, {} wall): {} --wall-stiffness {:?} --wall-damping {:?}: reference ρ = {:.15} ({}{})",
        c.id,
        c.category,
        w.kind,
        c.cli,
        w.stiffness,
        w.damping,
        w.radius,
        w.verdict,
        if w.precise { ", 40 digits" } else { "" }
    )
}

fn decidable(w: &RefWall) -> bool {
    (w.radius - 1.0).abs() >= VERDICT_BAND
}

fn verdict_agrees(w: &RefWall, v: Verdict) -> bool {
    !decidable(w) || v.as_str() == w.verdict
}

/// (a) The point analysis at every wall.
fn check_analysis(t: &mut Tally, c: &Case, sys: &System) {
    for w in &c.walls {
        let wall = Wall {
            stiffness: w.stiffness,
            damping: w.damping,
        };
        let an = sys.wall_units(wall).and_then(|ab| sys.analysis(ab));
        let an = match an {
            Ok(an) => an,
            Err(e) => {
                t.check("(a) analysis error", false, || {
                    format!("{}: {e}", describe(c, w))
                });
                continue;
            }
        };
        t.check("(a) analysis error", true, String::new);
        let rho = an.spectral_radius;
        t.check(
            "(a) analysis radius",
            rel(rho, w.radius) <= RADIUS_REL_TOL,
            || {
                format!(
                    "{}; hapstab ρ = {rho:.15} (rel {:.1e})",
                    describe(c, w),
                    rel(rho, w.radius)
                )
            },
        );
        t.check(
            "(a) analysis verdict",
            verdict_agrees(w, an.verdict),
            || {
                format!(
                    "{}; hapstab says {} (ρ = {rho:.15})",
                    describe(c, w),
                    an.verdict.as_str()
                )
            },
        );
    }
}

/// (b) The map at the fixture's walls, in both kinds.
fn check_map(t: &mut Tally, c: &Case, fam: &AffineFamily) {
    let (a, b): (Vec<f64>, Vec<f64>) = c
        .walls
        .iter()
        .map(|w| fam.to_units(w.stiffness, w.damping))
        .unzip();
    let flags = wall_map_points(fam, &a, &b, MapKind::Stability).expect("map points");
    let radii = wall_map_points(fam, &a, &b, MapKind::SpectralRadius).expect("map points");
    let rho = radii.radius.expect("radius map");
    for (i, w) in c.walls.iter().enumerate() {
        let want_stable = w.verdict == "stable";
        t.check(
            "(b) map stability verdict",
            !decidable(w) || flags.stable[i] == want_stable,
            || format!("{}; map says stable = {}", describe(c, w), flags.stable[i]),
        );
        t.check(
            "(b) map radius",
            rel(rho[i], w.radius) <= RADIUS_REL_TOL,
            || {
                format!(
                    "{}; map ρ = {:.15} (rel {:.1e})",
                    describe(c, w),
                    rho[i],
                    rel(rho[i], w.radius)
                )
            },
        );
        t.check(
            "(b) map radius verdict",
            !decidable(w) || radii.stable[i] == want_stable,
            || {
                format!(
                    "{}; radius map says stable = {} (ρ = {:.15})",
                    describe(c, w),
                    radii.stable[i],
                    rho[i]
                )
            },
        );
    }
}

/// (c) The exact region against every wall further than its chord tolerance from its edges.
fn check_region(t: &mut Tally, c: &Case, sys: &System) {
    let r: StableRegion = match sys.region() {
        Ok(r) => r,
        Err(e) => {
            t.check("(c) region refused", false, || {
                format!("loop {} ({}): {}: {e}", c.id, c.category, c.cli)
            });
            return;
        }
    };
    t.check("(c) region refused", true, String::new);
    let tol = DEFAULT_REL_TOL * r.size();
    for w in c.walls.iter().filter(|w| decidable(w)) {
        let wall = Wall {
            stiffness: w.stiffness,
            damping: w.damping,
        };
        let Ok((alpha, beta)) = sys.wall_units(wall) else {
            continue;
        };
        let p = WallPoint { a: alpha, b: beta };
        if r.boundary_distance(p) <= tol {
            t.region_excepted += 1;
            continue;
        }
        let inside = r.contains(p);
        t.check("(c) region contains", inside == (w.verdict == "stable"), || {
            format!(
                "{}; region ({} polygons, a_max = {:e} at b = {:e}) {} it, boundary distance {:.2e} (tolerance {tol:.2e})",
                describe(c, w),
                r.polygons.len(),
                r.a_max,
                r.b_at_a_max,
                if inside { "contains" } else { "excludes" },
                r.boundary_distance(p)
            )
        });
    }
}

/// True when an end (N/m; None unbounded) matches the referee's, within
/// [`INTERVAL_REL_TOL`] of the larger of its size and the interval's width.
fn end_matches(got: f64, want: Option<f64>, width: f64) -> bool {
    match want {
        None => got.is_infinite(),
        Some(k) => (got - k).abs() <= INTERVAL_REL_TOL * k.abs().max(width),
    }
}

fn interval_text(ivs: &[(f64, f64)]) -> String {
    let parts: Vec<String> = ivs
        .iter()
        .map(|(lo, hi)| format!("({lo:.10e}, {hi:.10e})"))
        .collect();
    format!("[{}]", parts.join(", "))
}

/// Stable stiffness intervals (lo, hi) in N/m.
type Ends = Vec<(f64, f64)>;

/// (d) The stable stiffness intervals at the fixture's dampings; hapstab's intervals wholly
/// within 0 < |K| < `scan_floor` (N/m), where the referee's grid has no point (it has K = 0),
/// are set aside.
fn check_intervals(t: &mut Tally, c: &Case, sys: &System, scan_floor: f64) {
    for level in &c.intervals {
        let all: Vec<(f64, f64)> = sys
            .damping_units(level.damping)
            .map(|b| sys.stable_intervals(b))
            .map(|ivs| {
                let k = |a: f64| sys.family().to_physical(a, 0.0).0;
                ivs.iter().map(|iv| (k(iv.lo), k(iv.hi))).collect()
            })
            .unwrap_or_default();
        let (got, below): (Ends, Ends) = all
            .into_iter()
            .partition(|&(lo, hi)| lo.abs().max(hi.abs()) >= scan_floor || (lo < 0.0 && 0.0 < hi));
        t.below_scan += below.len();
        let want = &level.stiffness;
        let what = || {
            let w: Vec<(f64, f64)> = want
                .iter()
                .map(|[lo, hi]| (lo.unwrap_or(f64::NEG_INFINITY), hi.unwrap_or(f64::INFINITY)))
                .collect();
            format!(
                "loop {} ({}): {} --wall-damping {:?}: hapstab K intervals {}, referee {}",
                c.id,
                c.category,
                c.cli,
                level.damping,
                interval_text(&got),
                interval_text(&w)
            )
        };
        t.check("(d) interval count", got.len() == want.len(), what);
        if got.len() != want.len() {
            continue;
        }
        let ok = got.iter().zip(want).all(|(&(lo, hi), [wlo, whi])| {
            let width = match (wlo, whi) {
                (Some(a), Some(b)) => b - a,
                _ => 0.0,
            };
            end_matches(lo, *wlo, width) && end_matches(hi, *whi, width)
        });
        t.check("(d) interval ends", ok, what);
    }
}

/// Every check on one loop; `scan_decades` as in the fixture.
fn check_loop(c: &Case, scan_decades: [f64; 2]) -> Tally {
    let mut t = Tally::default();
    let lp = match build(c) {
        Ok(lp) => lp,
        Err(e) => {
            t.check("loop refused", false, || {
                format!("loop {}: {}: {e}", c.id, c.cli)
            });
            return t;
        }
    };
    t.check("loop refused", true, String::new);
    if c.delay_time.is_some() {
        t.check("delay form", lp.delay == c.delay, || {
            format!(
                "loop {}: {}: hapstab reads {:?}, the referee {:?}",
                c.id, c.cli, lp.delay, c.delay
            )
        });
    }
    let sys = match System::new(lp) {
        Ok(f) => f,
        Err(e) => {
            t.check("loop refused", false, || {
                format!("loop {}: {}: family: {e}", c.id, c.cli)
            });
            return t;
        }
    };
    check_analysis(&mut t, c, &sys);
    check_map(&mut t, c, sys.family());
    check_region(&mut t, c, &sys);
    let scan_floor = c.wall_scale.stiffness * 10f64.powf(scan_decades[0]);
    check_intervals(&mut t, c, &sys, scan_floor);
    t
}

#[test]
fn fixture_covers_every_kind_of_loop_and_wall() {
    let fx = fixture();
    let walls: Vec<&RefWall> = fx.loops.iter().flat_map(|c| &c.walls).collect();
    assert!(fx.loops.len() >= 300, "{} loops", fx.loops.len());
    assert!(walls.len() >= 3000, "{} walls", walls.len());
    assert_eq!(fx.near_offset, 1e-6);
    assert_eq!(fx.loops.iter().filter(|c| c.audit).count(), 5);
    for kind in ["mass_spring_damper", "two_mass", "transfer_function"] {
        assert!(fx.loops.iter().any(|c| c.category == kind), "{kind}");
    }
    let undamped = |c: &&Case| match &c.plant {
        PlantModel::TwoMass(t) => {
            t.motor_damping == 0.0 && t.transmission_damping == 0.0 && t.arm.damping == 0.0
        }
        _ => false,
    };
    assert!(fx.loops.iter().filter(undamped).count() >= 10);
    let tf_order = |c: &Case| match &c.plant {
        PlantModel::TransferFunction { den, .. } => den.len() - 1,
        _ => 0,
    };
    assert_eq!(fx.loops.iter().map(tf_order).max(), Some(6));
    assert!(fx.loops.iter().any(|c| c.force_lag > 0.0));
    assert!(fx.loops.iter().any(|c| c.force_lag == 0.0));
    for v in ["backward", "lowpass:", "average:", "iir:"] {
        assert!(fx.loops.iter().any(|c| c.velocity.starts_with(v)), "{v}");
    }
    assert!(fx.loops.iter().any(|c| c.delay.fraction > 0.0));
    assert!(fx.loops.iter().any(|c| c.delay.samples > 20));
    assert!((0..=20).all(|d| fx.loops.iter().any(|c| c.delay.samples == d)));
    let (t_lo, t_hi) = fx.loops.iter().fold((1.0_f64, 0.0_f64), |(lo, hi), c| {
        (lo.min(c.period), hi.max(c.period))
    });
    assert!(t_lo < 1.2e-4 && t_hi > 0.8e-2, "periods {t_lo} .. {t_hi}");
    for kind in ["near", "far", "zero_k", "zero_b", "negative_k", "audit"] {
        assert!(walls.iter().any(|w| w.kind == kind), "{kind}");
    }
    assert!(walls.iter().any(|w| w.precise) && walls.iter().any(|w| !w.precise));
    assert!(walls.iter().any(|w| w.verdict == "stable"));
    assert!(walls.iter().any(|w| w.verdict == "unstable"));
}

#[test]
fn hapstab_agrees_with_the_state_space_referee() {
    let fx = fixture();
    let tally = fx
        .loops
        .par_iter()
        .map(|c| check_loop(c, fx.scan_decades))
        .reduce(Tally::default, Tally::merge);
    println!("{}", tally.table());
    let mut report = String::new();
    for c in CATEGORIES {
        for line in tally.failed.get(c).into_iter().flatten() {
            report += &format!("[{c}] {line}\n");
        }
    }
    if let Ok(path) = std::env::var("HAPSTAB_REFEREE_REPORT") {
        std::fs::write(path, &report).expect("report file");
    }
    assert!(
        tally.disagreements() == 0,
        "{} disagreements with the state-space referee:\n{}\n{report}",
        tally.disagreements(),
        tally.table()
    );
}
