//! Section IV's parameter ranges (`hapstab::paper::ranges`, eq. 14 and 15).
//! Expected values come from closed forms derived by hand, the paper's own formulas and
//! statements, or published examples, never from program output.

use hapstab::paper::ranges::ranges;

/// Eq. (14) for T = 1 ms: γ < 710·10⁻⁶, δ < 13.225·10⁻³, inside the extended range (15);
/// the bounds scale with T² and T.
#[test]
fn parameter_ranges_eq14_eq15() {
    let r = ranges(1e-3).unwrap();
    assert!((r.gamma_max - 7.1e-4).abs() < 1e-15);
    assert!((r.delta_max - 0.013225).abs() < 1e-15);
    assert!(r.within_extended && r.gamma_max < 1e-3 && r.delta_max < 15e-3);
    let h = ranges(0.5e-3).unwrap();
    assert!((h.gamma_max - 710.0 * 0.25e-6).abs() < 1e-15);
    assert!((h.delta_max - 13.225 * 0.5e-3).abs() < 1e-15);
    // at 2 ms the arm range leaves (15): the paper's T ≤ 1 ms assumption matters
    assert!(!ranges(2e-3).unwrap().within_extended);
    assert!(ranges(-1e-3).is_err());
}
