//! `hapstab kmax`'s text: K_max at B = 0, over the renderable band and over the damping band
//! asked, in the loop's units.

use hapstab::kmax::{KmaxReport, RenderableBand};

use super::{DampingRange, KmaxOut, band_text};
use crate::model::{ResolvedLoop, print_loop};
use crate::output::eng;
use crate::wall_plot;

/// The human-readable answer of `kmax`: the loop, K_max with where it is reached (or why no
/// stiffness is stable), the plot's files, and over a damping band K_max at B = 0 as well.
pub(super) fn print_text(rl: &ResolvedLoop, out: &KmaxOut, band: DampingRange, over_band: bool) {
    print_loop(&rl.lp);
    let r = &out.answer.report;
    // the pure spring first: the number a device renders without virtual damping
    if over_band {
        match r.k_max_at_zero_damping {
            Some(k) => println!(
                "K_max = {} at B = 0 (no virtual damping, the plant's own damping only)",
                kt(k)
            ),
            None => println!("no stiffness is stable at B = 0"),
        }
    }
    if let Some(rb) = &r.renderable {
        print_renderable(rl, rb);
    }
    print_main(r, out.wall_damping, band);
    if over_band
        && band.lo == 0.0
        && band.hi == f64::INFINITY
        && let Some(b) = r.b_at_k_max.filter(|&b| b > 0.0)
        && r.renderable.as_ref().is_none_or(|rb| b > rb.b_max)
    {
        println!(
            "            (that needs the device to render B = {}; --damping-range LO:HI \
             gives K_max over the dampings yours renders)",
            bt(b)
        );
    }
    if !out.plot.is_empty() {
        println!("plot written to {}", wall_plot::files_text(&out.plot));
    }
}

fn kt(k: f64) -> String {
    eng(k, "N/m", 6)
}

fn bt(b: f64) -> String {
    eng(b, "Ns/m", 6)
}

/// K_max over the renderable band and how the band is set.
fn print_renderable(rl: &ResolvedLoop, rb: &RenderableBand) {
    let band = format!("the renderable band 0 ≤ B ≤ {}", bt(rb.b_max));
    match (rb.k_max, rb.b_at_k_max) {
        (Some(k), Some(b)) => println!(
            "K_max = {}, {} B = {} (largest over {band})",
            kt(k),
            if rb.k_max_attained == Some(false) {
                "approached as"
            } else {
                "reached at"
            },
            bt(b)
        ),
        _ => println!("no stiffness is stable over {band}"),
    }
    println!(
        "            (the damper's force noise stays ≤ {} RMS there: {} position steps through \
         the {} estimator, noise gain {} s⁻¹; --position-resolution, --force-noise)",
        eng(rb.noise.force_noise, "N", 6),
        eng(rb.noise.position_resolution, "m", 6),
        rl.lp.velocity,
        crate::output::sig(rb.velocity_noise_gain, 6),
    );
}

/// K_max at the given B, or over the band with where it is reached.
fn print_main(r: &KmaxReport, wall_damping: Option<f64>, band: DampingRange) {
    let linear = |what: &str| {
        r.k_linear
            .map(|k| format!("; linear condition (22){what}: {}", kt(k)))
            .unwrap_or_default()
    };
    match (r.k_max, wall_damping, r.b_at_k_max) {
        (None, None, _) => println!("no stiffness is stable for {}", band_text(band)),
        (None, Some(b), _) => println!("no stiffness is stable at B = {}", bt(b)),
        (Some(k), Some(b), _) => println!(
            "K_max = {} at B = {} (stable for {} < K < {}){}",
            kt(k),
            bt(b),
            r.k_interval.map_or("—".into(), |i| kt(i[0])),
            kt(k),
            linear("")
        ),
        (Some(k), None, Some(b)) if r.k_max_attained == Some(false) => println!(
            "K_max = {}, approached as B → {} (largest over {}: a supremum, a corner of the \
             region that no stiffness at exactly that B reaches; K = {} is stable at B = {}){}",
            kt(k),
            bt(b),
            band_text(band),
            r.k_stable_near_k_max
                .map_or("—".into(), |k| eng(k, "N/m", 10)),
            r.b_stable_near_k_max
                .map_or("—".into(), |b| eng(b, "Ns/m", 10)),
            linear(" at that B")
        ),
        (Some(k), None, Some(b)) => println!(
            "K_max = {}, reached at B = {} (largest over {}){}",
            kt(k),
            bt(b),
            band_text(band),
            linear(" at that B")
        ),
        _ => {}
    }
}
