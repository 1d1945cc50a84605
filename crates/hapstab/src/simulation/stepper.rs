//! Exact stepping of the plant from sample to sample and within a sample (friction events).
//!
//! # One sample
//!
//! With the matrices of [`crate::zoh::DiscreteLoop`] (E = Φ − I, Γ0, Γ1) and the columns
//! Ψ(1)·b of the human force and of friction (see [`crate::zoh::PlantPorts`]):
//!
//! ```text
//! x_{k+1} = x_k + E x_k + Γ0 u_{k−d} + Γ1 u_{k−d−1} + Ψ(1)b_h u_h + Ψ(1)b_f u_f,
//! ```
//!
//! exact for inputs held over the sample (the wall force switching at λT); the kernel steps
//! it as Φ x + Σ columns·inputs with Φ = I + E, as the paper's 2×2 plant was stepped. A
//! [`Kernel`] has a fixed state size N, so small plants run on unrolled loops; a plant of
//! order n < N is padded with zero states, which stays exact.
//!
//! # Within a sample
//!
//! A sub-step of length h with constant inputs is x(h) = x + E(h)x + Ψ(h)·f, with E(h) and
//! Ψ(h) from [`crate::zoh::exp_and_integral`] and f = B u_a + b_h u_h + b_f u_f the forcing.
//! Friction acts on one velocity state i (the friction point, [`FrictionPoint`]):
//!
//! - *slipping* in direction s, u_f = −F_c·s until the velocity x_i changes sign; the instant
//!   is located by safeguarded Newton steps on the exact sub-step solution;
//! - *stuck* (x_i = 0): the friction holds x_i at zero with the force the rest of the plant
//!   puts on that point, net = (A x + B u_a + b_h u_h)_i / gain, as long as |net| ≤ F_s. The
//!   stuck plant is the plant with row i of A and of the forcing removed (the friction point
//!   does not accelerate); the breakaway instant, where |net| reaches F_s, is located by
//!   bisection. At a reversal the stick rule decides: stick if |net| ≤ F_s, otherwise slip in
//!   the direction of net.
//!
//! A whole sample is first tried with the one-sample matrices (slipping in the direction of
//! the velocity, or stuck); it is redone in sub-steps only when the velocity changed sign or
//! the holding force exceeded F_s at a checked instant (the start, λT and the end of the
//! sample). Two reversals within one sample with equal end signs, and a holding force that
//! exceeds F_s only between the checked instants, are missed; both need dynamics faster
//! than the sampling (a plant half-period shorter than one sample).

use crate::poly::{self, Mat};
use crate::zoh::{FrictionPoint, exp_and_integral, split_hold};

/// The input channels of one sample, in wall units: the wall force applied from λT
/// (computed d samples ago), the one before it (applied on [0, λT)), the human force and
/// the friction force.
pub(super) const CHANNELS: usize = 4;
/// Channel of u_{k−d}, the wall's force held on [λT, T).
pub(super) const WALL_NOW: usize = 0;
/// Channel of u_{k−d−1}, the wall's force held on [0, λT).
pub(super) const WALL_PREV: usize = 1;
/// Channel of the human force.
pub(super) const HUMAN: usize = 2;
/// Channel of the friction force.
pub(super) const FRICTION: usize = 3;

/// Most friction events (reversals, breakaways) handled within one sample: more would need
/// dynamics far faster than the sampling.
pub(super) const MAX_EVENTS: usize = 16;
/// An event is located to this fraction of a sample: τ ∈ [0, 1] is resolved to a few ulps.
const LOCATE_TOL: f64 = 1e-15;
/// Most iterations of an event location (Newton converges in a handful; bisection to
/// [`LOCATE_TOL`] takes 50).
const LOCATE_STEPS: usize = 200;

/// The one-sample map x ↦ Φ x + Σ columns·inputs for a state of size N (Φ = I + E).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Kernel<const N: usize> {
    phi: [[f64; N]; N],
    cols: [[f64; N]; CHANNELS],
}

impl<const N: usize> Kernel<N> {
    /// The kernel of E = Φ − I and the input column of each channel (zero-padded to N).
    pub(super) fn new(e: &Mat, channels: [&[f64]; CHANNELS]) -> Self {
        let mut k = Self {
            phi: [[0.0; N]; N],
            cols: [[0.0; N]; CHANNELS],
        };
        for (i, (row, src)) in k.phi.iter_mut().zip(e).enumerate() {
            row[..src.len()].copy_from_slice(src);
            row[i] += 1.0;
        }
        for (col, src) in k.cols.iter_mut().zip(channels) {
            col[..src.len()].copy_from_slice(src);
        }
        k
    }

    /// One sample with the inputs of each channel held. The inputs are summed first, off
    /// the state's dependency chain from sample to sample; zero columns add exact zeros.
    #[inline(always)]
    pub(super) fn step(&self, x: &[f64; N], u: [f64; CHANNELS]) -> [f64; N] {
        let mut out = [0.0; N];
        for (i, o) in out.iter_mut().enumerate() {
            let c = &self.cols;
            let mut s = c[WALL_PREV][i] * u[WALL_PREV]
                + c[HUMAN][i] * u[HUMAN]
                + c[FRICTION][i] * u[FRICTION]
                + c[WALL_NOW][i] * u[WALL_NOW];
            for (p, xj) in self.phi[i].iter().zip(x) {
                s += p * xj;
            }
            *o = s;
        }
        out
    }
}

/// Inner product of equal-length slices.
#[inline(always)]
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut s = 0.0;
    for (x, y) in a.iter().zip(b) {
        s += x * y;
    }
    s
}

/// The continuous plant with its inputs, for sub-sample steps and the stuck plant.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Continuous {
    /// State matrix A (normalized time).
    a: Mat,
    /// A with the friction point's row removed (the stuck plant).
    stuck_a: Mat,
    /// Actuator input B.
    actuator: Vec<f64>,
    /// Human input column.
    human: Vec<f64>,
    /// Where friction acts.
    point: FrictionPoint,
    /// Fraction λ of the delay (the wall force switches at λT).
    lambda: f64,
}

/// The stuck plant's one-sample kernels (see [`Continuous::stuck_kernels`]).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct StuckKernels<const N: usize> {
    /// Over the whole sample.
    pub whole: Kernel<N>,
    /// Over [0, λT), with the wall force u_{k−d−1}.
    pub to_lambda: Kernel<N>,
}

/// Slipping in a direction (±1) or stuck.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    Slip(f64),
    Stuck,
}

/// Coulomb and static friction in wall units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct FrictionForces {
    /// Coulomb force u_c.
    pub coulomb: f64,
    /// Static force u_s ≥ u_c.
    pub stiction: f64,
}

impl Continuous {
    /// The plant ẋ = A x + B u_a + b_h u_h with friction at `point`, wall force delayed by λ.
    pub(super) fn new(
        a: Mat,
        actuator: Vec<f64>,
        human: Vec<f64>,
        point: FrictionPoint,
        lambda: f64,
    ) -> Self {
        let mut stuck_a = a.clone();
        stuck_a[point.state].iter_mut().for_each(|v| *v = 0.0);
        Self {
            a,
            stuck_a,
            actuator,
            human,
            point,
            lambda,
        }
    }

    /// The stuck plant's kernels over the whole sample and over [0, λT) (friction absent;
    /// channels as [`Kernel`]).
    pub(super) fn stuck_kernels<const N: usize>(&self) -> StuckKernels<N> {
        let (e, psi) = exp_and_integral(&self.stuck_a, 1.0);
        let b = self.stuck(&self.actuator);
        let bh = self.stuck(&self.human);
        let (g0, g1) = split_hold(&self.stuck_a, &psi, &b, self.lambda);
        let gh = poly::mat_vec(&psi, &bh);
        let none = vec![0.0; self.a.len()];
        let (el, psil) = exp_and_integral(&self.stuck_a, self.lambda);
        let (bl, bhl) = (poly::mat_vec(&psil, &b), poly::mat_vec(&psil, &bh));
        StuckKernels {
            whole: Kernel::new(&e, [&g0, &g1, &gh, &none]),
            to_lambda: Kernel::new(&el, [&none, &bl, &bhl, &none]),
        }
    }

    /// A forcing vector with the friction point's row removed.
    fn stuck(&self, f: &[f64]) -> Vec<f64> {
        let mut f = f.to_vec();
        f[self.point.state] = 0.0;
        f
    }

    /// f = B u_a + b_h u_h + b_f u_f.
    fn forcing(&self, ua: f64, uh: f64, uf: f64) -> Vec<f64> {
        let mut f: Vec<f64> = self
            .actuator
            .iter()
            .zip(&self.human)
            .map(|(b, h)| b * ua + h * uh)
            .collect();
        f[self.point.state] += self.point.gain * uf;
        f
    }

    /// The force (wall units) the rest of the plant puts on the friction point:
    /// (A x + B u_a + b_h u_h)_i / gain.
    fn net(&self, x: &[f64], ua: f64, uh: f64) -> f64 {
        let i = self.point.state;
        let accel = dot(&self.a[i], x) + self.actuator[i] * ua + self.human[i] * uh;
        accel / self.point.gain
    }

    /// x(h) = x + E(h)x + Ψ(h)f of the free (or, if `stuck`, the stuck) plant.
    fn propagate(&self, stuck: bool, x: &[f64], f: &[f64], h: f64) -> Vec<f64> {
        let a = if stuck { &self.stuck_a } else { &self.a };
        let (e, psi) = exp_and_integral(a, h);
        let ex = poly::mat_vec(&e, x);
        let pf = poly::mat_vec(&psi, f);
        let mut out: Vec<f64> = x
            .iter()
            .zip(ex.iter().zip(&pf))
            .map(|(x, (e, p))| x + e + p)
            .collect();
        if stuck {
            out[self.point.state] = 0.0;
        }
        out
    }

    /// The velocity state's rate (A x + f)_i at a state.
    fn rate(&self, x: &[f64], f: &[f64]) -> f64 {
        let i = self.point.state;
        dot(&self.a[i], x) + f[i]
    }

    fn mode_at(&self, x: &[f64], ua: f64, uh: f64, fr: FrictionForces) -> Mode {
        let v = x[self.point.state];
        if v != 0.0 {
            return Mode::Slip(v.signum());
        }
        let net = self.net(x, ua, uh);
        if net.abs() <= fr.stiction {
            Mode::Stuck
        } else {
            Mode::Slip(net.signum())
        }
    }

    /// The actuator input at a sample's start: u_{k−d−1} when the delay has a fraction.
    pub(super) fn actuator_at_start(&self, u: &[f64; CHANNELS]) -> f64 {
        if self.lambda > 0.0 {
            u[WALL_PREV]
        } else {
            u[WALL_NOW]
        }
    }

    /// One sample with friction (module doc): the whole-sample kernels when no event
    /// happens, sub-steps otherwise. Returns the number of velocity reversals located.
    pub(super) fn friction_sample<const N: usize>(
        &self,
        free: &Kernel<N>,
        stuck: &StuckKernels<N>,
        x: &mut [f64; N],
        u: [f64; CHANNELS],
        fr: FrictionForces,
    ) -> usize {
        let n = self.a.len();
        let i = self.point.state;
        let ua0 = self.actuator_at_start(&u);
        match self.mode_at(&x[..n], ua0, u[HUMAN], fr) {
            Mode::Slip(s) => {
                let mut us = u;
                us[FRICTION] = -fr.coulomb * s;
                let x1 = free.step(x, us);
                if x1[i] * s > 0.0 {
                    *x = x1;
                    return 0;
                }
            }
            Mode::Stuck => {
                let mut x1 = stuck.whole.step(x, u);
                x1[i] = 0.0;
                if self.holds_over_sample(stuck, x, &x1, &u, fr) {
                    *x = x1;
                    return 0;
                }
            }
        }
        let mut v = x[..n].to_vec();
        let events = self.sample_in_steps(&mut v, &u, fr);
        x[..n].copy_from_slice(&v);
        events
    }

    /// The holding force of a stuck sample stays within F_s at its end and on both sides of
    /// λT (its start was checked by the stick rule).
    fn holds_over_sample<const N: usize>(
        &self,
        stuck: &StuckKernels<N>,
        x0: &[f64; N],
        x1: &[f64; N],
        u: &[f64; CHANNELS],
        fr: FrictionForces,
    ) -> bool {
        let n = self.a.len();
        let uh = u[HUMAN];
        let ok = |x: &[f64], ua: f64| self.net(&x[..n], ua, uh).abs() <= fr.stiction;
        if !ok(x1, u[WALL_NOW]) {
            return false;
        }
        if self.lambda == 0.0 {
            return true;
        }
        let mut xl = stuck.to_lambda.step(x0, *u);
        xl[self.point.state] = 0.0;
        ok(&xl, u[WALL_PREV]) && ok(&xl, u[WALL_NOW])
    }

    /// One sample in sub-steps: the pieces [0, λ) and [λ, 1) with their actuator inputs,
    /// each advanced event by event. Returns the number of reversals.
    fn sample_in_steps(&self, x: &mut Vec<f64>, u: &[f64; CHANNELS], fr: FrictionForces) -> usize {
        let mut pieces = vec![];
        if self.lambda > 0.0 {
            pieces.push((self.lambda, u[WALL_PREV]));
        }
        pieces.push((1.0, u[WALL_NOW]));
        let (mut t, mut events, mut reversals) = (0.0, 0, 0);
        let mut forced: Option<Mode> = None;
        for (end, ua) in pieces {
            while end - t > LOCATE_TOL {
                let mode = forced
                    .take()
                    .unwrap_or_else(|| self.mode_at(x, ua, u[HUMAN], fr));
                let last = events >= MAX_EVENTS;
                let step = self.sub_step(x, mode, ua, u[HUMAN], fr, end - t, last);
                t = if step.elapsed >= end - t {
                    end
                } else {
                    t + step.elapsed
                };
                events += usize::from(step.event.is_some());
                reversals += usize::from(matches!(step.event, Some(Event::Reversal)));
                if let Some(Event::Breakaway(s)) = step.event {
                    forced = Some(Mode::Slip(s));
                }
            }
        }
        reversals
    }

    /// Advances by up to h in one mode; stops early at an event (unless `ignore_events`).
    #[allow(clippy::too_many_arguments)]
    fn sub_step(
        &self,
        x: &mut Vec<f64>,
        mode: Mode,
        ua: f64,
        uh: f64,
        fr: FrictionForces,
        h: f64,
        ignore_events: bool,
    ) -> SubStep {
        let i = self.point.state;
        match mode {
            Mode::Slip(s) => {
                let f = self.forcing(ua, uh, -fr.coulomb * s);
                let x1 = self.propagate(false, x, &f, h);
                if x1[i] * s > 0.0 || ignore_events {
                    *x = x1;
                    return SubStep::whole(h);
                }
                let (tau, mut xt) = self.locate_reversal(x, &f, s, h);
                xt[i] = 0.0;
                *x = xt;
                SubStep::at(tau, Event::Reversal)
            }
            Mode::Stuck => {
                let f = self.stuck(&self.forcing(ua, uh, 0.0));
                let x1 = self.propagate(true, x, &f, h);
                if self.net(&x1, ua, uh).abs() <= fr.stiction || ignore_events {
                    *x = x1;
                    return SubStep::whole(h);
                }
                let (tau, xt) = self.locate_breakaway(x, &f, ua, uh, fr.stiction, h);
                let net = self.net(&xt, ua, uh);
                *x = xt;
                SubStep::at(tau, Event::Breakaway(net.signum()))
            }
        }
    }

    /// The first τ ∈ (0, h] where the velocity s·x_i(τ) (positive just after 0, not positive
    /// at h) reaches zero: safeguarded Newton on the exact solution, with bisection whenever
    /// a Newton step leaves the bracket.
    fn locate_reversal(&self, x: &[f64], f: &[f64], s: f64, h: f64) -> (f64, Vec<f64>) {
        let i = self.point.state;
        let (mut lo, mut hi) = (0.0_f64, h);
        let f_lo = s * x[i];
        let f_hi = s * self.propagate(false, x, f, h)[i];
        let mut t = if f_lo > 0.0 && f_hi < f_lo {
            h * f_lo / (f_lo - f_hi)
        } else {
            0.5 * h
        };
        for _ in 0..LOCATE_STEPS {
            let xt = self.propagate(false, x, f, t);
            let v = s * xt[i];
            if v > 0.0 {
                lo = t;
            } else {
                hi = t;
            }
            let newton = t - v / (s * self.rate(&xt, f));
            let next = if newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if (next - t).abs() <= LOCATE_TOL || hi - lo <= LOCATE_TOL {
                return (next, self.propagate(false, x, f, next));
            }
            t = next;
        }
        (t, self.propagate(false, x, f, t))
    }

    /// The first τ ∈ (0, h] where the holding force of the stuck plant exceeds F_s
    /// (bisection on the exact stuck solution).
    fn locate_breakaway(
        &self,
        x: &[f64],
        f: &[f64],
        ua: f64,
        uh: f64,
        stiction: f64,
        h: f64,
    ) -> (f64, Vec<f64>) {
        let (mut lo, mut hi) = (0.0_f64, h);
        for _ in 0..LOCATE_STEPS {
            let mid = 0.5 * (lo + hi);
            if hi - lo <= LOCATE_TOL || mid <= lo || mid >= hi {
                break;
            }
            let xm = self.propagate(true, x, f, mid);
            if self.net(&xm, ua, uh).abs() <= stiction {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        (hi, self.propagate(true, x, f, hi))
    }
}

/// A friction event within a sample.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Event {
    /// The friction point's velocity reached zero.
    Reversal,
    /// A stuck point broke away, slipping in this direction.
    Breakaway(f64),
}

/// How far a sub-step went and what stopped it.
#[derive(Debug, Clone, Copy)]
struct SubStep {
    elapsed: f64,
    event: Option<Event>,
}

impl SubStep {
    fn whole(h: f64) -> Self {
        Self {
            elapsed: h,
            event: None,
        }
    }

    fn at(tau: f64, event: Event) -> Self {
        Self {
            elapsed: tau,
            event: Some(event),
        }
    }
}
