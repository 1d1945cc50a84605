//! Where a decaying run comes to rest and when: the rest position and the settling time of a
//! [`Trace`] (the time after which the position stays within a band of its largest excursion
//! from rest; the 2 % band is the control textbooks' settling time, e.g. Ogata, *Modern
//! Control Engineering*, 5th ed., §5-3).

use super::Trace;

/// The band of the usual settling time: 2 % of the largest excursion from rest.
pub const SETTLING_BAND: f64 = 0.02;

/// A last position within this fraction of the largest |x| counts as rest at 0.
const REST_AT_ZERO: f64 = 1e-6;

impl Trace {
    /// The position the run settles at: 0, or the last position when that is not within
    /// 10⁻⁶ of the largest |x| (a push held against the wall settles inside it).
    pub fn rest_position(&self) -> f64 {
        let last = self.position.last().copied().unwrap_or(0.0);
        let peak = self.position.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if last.abs() <= REST_AT_ZERO * peak {
            0.0
        } else {
            last
        }
    }

    /// The settling time in s: the last recorded time at which the distance from
    /// [`Trace::rest_position`] exceeds `band` times its largest value (0 when it never does).
    pub fn settling_time(&self, band: f64) -> f64 {
        let x0 = self.rest_position();
        let peak = self
            .position
            .iter()
            .fold(0.0f64, |m, x| m.max((x - x0).abs()));
        self.time
            .iter()
            .zip(&self.position)
            .filter(|(_, x)| (**x - x0).abs() > band * peak)
            .map(|(t, _)| *t)
            .fold(0.0, f64::max)
    }
}
