//! The root locus in the virtual stiffness K at a fixed virtual damping B: the roots of the
//! characteristic polynomial p(z) = P0 + a·PK + b·PB (eq. 9, generalized; through the
//! paper's family for the paper's loop, [`crate::system::System::characteristic`]) as K sweeps
//! from 0 to beyond K_max, with the unit circle as the stability boundary (Section V).
//!
//! The ends of the stable K interval at B are the engine's exact ones
//! ([`crate::system::System::k_max_at_damping`], Section V's D-decomposition), and the sweep
//! holds them exactly: at the sample K = K_max a root lies on the unit circle (to the
//! accuracy of the roots, about 1e-12 for a simple root). The default sweep is
//! [`DEFAULT_SAMPLES`] uniform stiffnesses from 0 to [`OVERSHOOT`]·K_max with both interval
//! ends inserted. Roots are ordered along the sweep so that branch i of one sample continues
//! branch i of the previous (nearest-neighbour matching, for degrees up to
//! [`TRACK_DEGREE`]).

use num_complex::Complex64;
use serde::Serialize;

use crate::error::{Error, Result};
use crate::model::Loop;
use crate::param::Param;
use crate::stability::roots;
use crate::system::System;

/// Uniform samples of the default sweep.
pub const DEFAULT_SAMPLES: usize = 400;

/// The default sweep ends at this multiple of K_max.
pub const OVERSHOOT: f64 = 1.5;

/// Roots are matched branch by branch along the sweep up to this degree of p(z) (above it
/// they are listed as the root finder orders them).
pub const TRACK_DEGREE: usize = 64;

/// The root locus at one damping (module doc).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RootLocus {
    /// The virtual damping B in Ns/m.
    pub damping: f64,
    /// K_max at B in N/m: the upper end of the stable K interval reaching furthest (None when
    /// no K is stable at B).
    pub k_max: Option<f64>,
    /// That stable interval (lo, hi) of K in N/m.
    pub k_interval: Option<[f64; 2]>,
    /// Index of the sample K = K_max in `stiffness` (None without K_max or for a given sweep
    /// that does not hold it).
    pub k_max_index: Option<usize>,
    /// The root of p(z) closest to the unit circle at K = K_max: where the locus crosses it.
    pub crossing: Option<Complex64>,
    /// The frequency of the oscillation at K_max, |arg z|/(2πT) in Hz of that root.
    pub crossing_frequency_hz: Option<f64>,
    /// The virtual stiffnesses K of the sweep in N/m.
    pub stiffness: Vec<f64>,
    /// For each K, the roots of p(z) (degree of p each), branch-ordered.
    pub roots: Vec<Vec<Complex64>>,
    /// For each K, the spectral radius max |z|.
    pub spectral_radius: Vec<f64>,
}

/// The root locus of the loop at damping B (Ns/m) over the stiffnesses `stiffness` (N/m,
/// each finite), or over the default sweep (module doc) when None.
pub fn root_locus(lp: &Loop, damping: f64, stiffness: Option<&[f64]>) -> Result<RootLocus> {
    if !damping.is_finite() {
        return Err(Error::NotFinite {
            param: Param::WallDamping,
            value: damping,
        });
    }
    if let Some(ks) = stiffness {
        check_stiffness(ks)?;
    }
    let sys = System::of(lp)?;
    let fam = sys.family();
    let bu = sys.damping_units(damping)?;
    let iv = sys.k_max_at_damping(bu).filter(|iv| iv.hi.is_finite());
    let phys = |a: f64| fam.to_physical(a, 0.0).0;
    // The sweep in wall units: the interval ends exactly as the engine gives them.
    let (units, k_max_index) = match stiffness {
        Some(ks) => {
            let us: Vec<f64> = ks.iter().map(|&k| fam.to_units(k, 0.0).0).collect();
            let at = iv.and_then(|iv| ks.iter().position(|&k| k == phys(iv.hi)));
            let us = match (at, iv) {
                (Some(i), Some(iv)) => {
                    let mut us = us;
                    us[i] = iv.hi;
                    us
                }
                _ => us,
            };
            (us, at)
        }
        None => default_sweep(iv.map(|iv| (iv.lo, iv.hi))),
    };
    let mut all: Vec<Vec<Complex64>> = Vec::with_capacity(units.len());
    for &a in &units {
        let mut r = roots(&sys.characteristic((a, bu)))?;
        if let Some(prev) = all.last() {
            track(prev, &mut r);
        }
        all.push(r);
    }
    let crossing = k_max_index.and_then(|i| {
        all[i]
            .iter()
            .copied()
            .min_by(|x, y| (x.norm() - 1.0).abs().total_cmp(&(y.norm() - 1.0).abs()))
    });
    Ok(RootLocus {
        damping,
        k_max: iv.map(|iv| phys(iv.hi)),
        k_interval: iv.map(|iv| [phys(iv.lo), phys(iv.hi)]),
        k_max_index,
        crossing,
        crossing_frequency_hz: crossing
            .map(|z| z.arg().abs() / (2.0 * std::f64::consts::PI * lp.period)),
        stiffness: units.iter().map(|&a| phys(a)).collect(),
        spectral_radius: all
            .iter()
            .map(|r| r.iter().map(|z| z.norm()).fold(0.0, f64::max))
            .collect(),
        roots: all,
    })
}

/// Refuses an empty sweep or a stiffness that is not finite.
fn check_stiffness(ks: &[f64]) -> Result<()> {
    if ks.is_empty() {
        return Err(Error::Invalid {
            param: Param::WallStiffness,
            reason: "needs at least one stiffness".into(),
        });
    }
    match ks.iter().find(|k| !k.is_finite()) {
        Some(&k) => Err(Error::NotFinite {
            param: Param::WallStiffness,
            value: k,
        }),
        None => Ok(()),
    }
}

/// The default sweep in wall units and the index of K_max in it: 0 to OVERSHOOT·hi uniform,
/// with the interval's ends inserted (a lower end ≤ 0 is left out); without an interval, 0 to
/// one wall unit of stiffness.
fn default_sweep(iv: Option<(f64, f64)>) -> (Vec<f64>, Option<usize>) {
    let top = match iv {
        Some((_, hi)) if hi > 0.0 => OVERSHOOT * hi,
        _ => 1.0,
    };
    let n = DEFAULT_SAMPLES;
    let mut us: Vec<f64> = (0..=n).map(|i| top * i as f64 / n as f64).collect();
    if let Some((lo, hi)) = iv {
        us.extend([lo, hi].into_iter().filter(|&x| x > 0.0 && x < top));
    }
    us.sort_by(f64::total_cmp);
    us.dedup();
    let at = iv.and_then(|(_, hi)| us.iter().position(|&x| x == hi));
    (us, at)
}

/// Reorders `next` so that its i-th root is the nearest free one to `prev[i]` (greedy, in
/// order of the closest pairs), for degrees up to [`TRACK_DEGREE`].
fn track(prev: &[Complex64], next: &mut [Complex64]) {
    let n = next.len();
    if n != prev.len() || n > TRACK_DEGREE {
        return;
    }
    let mut pairs: Vec<(f64, usize, usize)> = Vec::with_capacity(n * n);
    for (i, p) in prev.iter().enumerate() {
        for (j, q) in next.iter().enumerate() {
            pairs.push(((p - q).norm(), i, j));
        }
    }
    pairs.sort_by(|x, y| x.0.total_cmp(&y.0));
    let (mut used_i, mut used_j) = (vec![false; n], vec![false; n]);
    let mut order = vec![0usize; n];
    for (_, i, j) in pairs {
        if !used_i[i] && !used_j[j] {
            used_i[i] = true;
            used_j[j] = true;
            order[i] = j;
        }
    }
    let taken: Vec<Complex64> = order.iter().map(|&j| next[j]).collect();
    next.copy_from_slice(&taken);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Effective;

    #[test]
    fn the_locus_crosses_the_circle_at_k_max() {
        let lp = Loop::paper(Effective::new(1.1, 7.5, 350.0).unwrap(), 1e-3, 1).unwrap();
        let rl = root_locus(&lp, 3.0, None).unwrap();
        let i = rl.k_max_index.unwrap();
        assert_eq!(rl.stiffness[i], rl.k_max.unwrap());
        assert!(
            (rl.spectral_radius[i] - 1.0).abs() < 1e-9,
            "{}",
            rl.spectral_radius[i]
        );
        assert!(rl.spectral_radius[i - 1] < 1.0 && rl.spectral_radius[i + 1] > 1.0);
        assert!((rl.crossing.unwrap().norm() - 1.0).abs() < 1e-9);
        assert!(root_locus(&lp, f64::NAN, None).is_err());
        assert!(root_locus(&lp, 3.0, Some(&[f64::INFINITY])).is_err());
    }
}
