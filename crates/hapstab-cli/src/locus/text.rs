//! The text summary of `hapstab locus`: the crossing at K_max and the roots there.

use hapstab::locus::RootLocus;

use super::CrossingOut;
use crate::output::{eng, radius_text, sig};

pub(super) fn print_summary(l: &RootLocus, crossing: Option<&CrossingOut>) {
    let kt = |k: f64| eng(k, "N/m", 6);
    let (k0, k1) = (
        l.stiffness.first().copied().unwrap_or(f64::NAN),
        l.stiffness.last().copied().unwrap_or(f64::NAN),
    );
    println!(
        "locus     {} stiffnesses from {} to {} at B = {}, {} roots each",
        l.stiffness.len(),
        kt(k0),
        kt(k1),
        eng(l.damping, "Ns/m", 6),
        l.roots.first().map_or(0, Vec::len)
    );
    match (l.k_interval, crossing) {
        (Some([lo, hi]), Some(c)) => {
            println!("stiffness stable for {} < K < {}", kt(lo), kt(hi));
            println!(
                "crossing  at K_max = {} a root reaches the unit circle at z = {} {} {}j \
                 (|z| = {}, {})",
                kt(hi),
                sig(c.re, 6),
                if c.im < 0.0 { "−" } else { "+" },
                sig(c.im.abs(), 6),
                radius_text(c.modulus),
                eng(c.frequency_hz, "Hz", 6)
            );
        }
        _ => println!("stiffness no stable K at this B"),
    }
}
