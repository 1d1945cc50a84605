//! Evenly spaced values: the grids of maps, sweeps, parameter boxes and scans, formed the one
//! way `lo + (hi − lo)·i/(n − 1)`, so that the same grid gives the same doubles in every
//! analysis and front end (its ends exactly lo and hi).

/// The i-th of n evenly spaced values from lo to hi (n ≥ 2; lo for n ≤ 1).
pub fn evenly_spaced_at(lo: f64, hi: f64, n: usize, i: usize) -> f64 {
    if n <= 1 {
        return lo;
    }
    lo + (hi - lo) * i as f64 / (n - 1) as f64
}

/// n evenly spaced values from lo to hi, both included ([`evenly_spaced_at`]; `[lo]` for
/// n = 1, empty for n = 0).
pub fn evenly_spaced(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n).map(|i| evenly_spaced_at(lo, hi, n, i)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_are_exact_and_steps_even() {
        let v = evenly_spaced(0.1, 0.7, 4);
        assert_eq!(v.len(), 4);
        assert_eq!((v[0], v[3]), (0.1, 0.7));
        assert!((v[1] - 0.3).abs() < 1e-16 && (v[2] - 0.5).abs() < 1e-16);
        assert_eq!(evenly_spaced(2.0, 5.0, 1), vec![2.0]);
        assert!(evenly_spaced(2.0, 5.0, 0).is_empty());
    }
}
