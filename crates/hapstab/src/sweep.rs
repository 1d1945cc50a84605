//! K_max against one parameter of the loop (delay, sampling period, filter cut-off, any plant
//! parameter): the exact largest stable stiffness of Section V and the largest passive one
//! (Section VIII) at every value, computed in parallel.

use std::str::FromStr;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;
use serde::Serialize;

use crate::closed_loop::AffineFamily;
use crate::error::{Error, Result, finite};
use crate::kmax_band::{BandMax, CurveTop, k_max_band_near};
use crate::model::{Delay, Loop, Plant, PlantModel, VelocityEstimator};
use crate::param::Param;
use crate::params::{Arm, Effective};
use crate::passivity::{
    DeviceDamping, SampledWall, device_damping, k_max_passive_at, passive_k_max,
};
use crate::region::{alpha_max_within, stable_region_with};
use crate::system::System;

/// Chord tolerance of the regions a sweep computes (relative to their size): a sweep reports
/// only K_max, which is refined exactly on its arc (da/dθ = 0) whatever the chords, so the
/// polygon may be 1000 times coarser than a drawn region's (four times faster).
pub const SWEEP_REL_TOL: f64 = 1e-6;

/// A parameter of the loop that a sweep varies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SweepParam {
    /// Delay t_d in s (any fraction of a sample).
    DelayTime,
    /// Sampling period T in s; the delay time t_d is kept.
    Period,
    /// Cut-off f_c in Hz of the low-pass velocity estimator.
    Cutoff,
    /// Window N in samples of the averaging velocity estimator.
    Window,
    /// Actuator lag τ in s.
    ForceLag,
    /// Effective mass m in kg of the one-mass plant (eq. 1).
    Mass,
    /// Effective damping b in Ns/m of the one-mass plant.
    Damping,
    /// Effective stiffness k in N/m of the one-mass plant.
    Stiffness,
    /// Motor-side mass in kg of a two-mass device.
    MotorMass,
    /// Motor-side damping in Ns/m of a two-mass device.
    MotorDamping,
    /// Handle mass in kg of a two-mass device.
    HandleMass,
    /// Transmission stiffness in N/m of a two-mass device.
    TransmissionStiffness,
    /// Transmission damping in Ns/m of a two-mass device.
    TransmissionDamping,
    /// Arm mass m_H in kg (a two-mass device's arm, or the arm of a held device).
    ArmMass,
    /// Arm damping b_H in Ns/m (a two-mass device's arm, or the arm of a held device).
    ArmDamping,
    /// Arm stiffness k_H in N/m (a two-mass device's arm, the arm of a held device; else k of
    /// the one-mass plant).
    ArmStiffness,
}

impl SweepParam {
    /// Every parameter, in the order of the help text.
    pub const ALL: [SweepParam; 16] = [
        SweepParam::DelayTime,
        SweepParam::Period,
        SweepParam::Cutoff,
        SweepParam::Window,
        SweepParam::ForceLag,
        SweepParam::Mass,
        SweepParam::Damping,
        SweepParam::Stiffness,
        SweepParam::MotorMass,
        SweepParam::MotorDamping,
        SweepParam::HandleMass,
        SweepParam::TransmissionStiffness,
        SweepParam::TransmissionDamping,
        SweepParam::ArmMass,
        SweepParam::ArmDamping,
        SweepParam::ArmStiffness,
    ];

    /// The name used on the command line and in CSV/JSON.
    pub fn name(self) -> &'static str {
        match self {
            SweepParam::DelayTime => "delay-time",
            SweepParam::Period => "period",
            SweepParam::Cutoff => "cutoff",
            SweepParam::Window => "window",
            SweepParam::ForceLag => "force-lag",
            SweepParam::Mass => "mass",
            SweepParam::Damping => "damping",
            SweepParam::Stiffness => "stiffness",
            SweepParam::MotorMass => "motor-mass",
            SweepParam::MotorDamping => "motor-damping",
            SweepParam::HandleMass => "handle-mass",
            SweepParam::TransmissionStiffness => "transmission-stiffness",
            SweepParam::TransmissionDamping => "transmission-damping",
            SweepParam::ArmMass => "arm-mass",
            SweepParam::ArmDamping => "arm-damping",
            SweepParam::ArmStiffness => "arm-stiffness",
        }
    }

    /// The loop's parameter it sets, as errors name it.
    pub fn param(self) -> Param {
        match self {
            SweepParam::DelayTime => Param::DelayTime,
            SweepParam::Period => Param::Period,
            SweepParam::Cutoff => Param::VelocityCutoff,
            SweepParam::Window => Param::VelocityWindow,
            SweepParam::ForceLag => Param::ForceLag,
            SweepParam::Mass => Param::Mass,
            SweepParam::Damping => Param::Damping,
            SweepParam::Stiffness => Param::Stiffness,
            SweepParam::MotorMass => Param::MotorMass,
            SweepParam::MotorDamping => Param::MotorDamping,
            SweepParam::HandleMass => Param::HandleMass,
            SweepParam::TransmissionStiffness => Param::TransmissionStiffness,
            SweepParam::TransmissionDamping => Param::TransmissionDamping,
            SweepParam::ArmMass => Param::ArmMass,
            SweepParam::ArmDamping => Param::ArmDamping,
            SweepParam::ArmStiffness => Param::ArmStiffness,
        }
    }

    /// The parameter's SI unit.
    pub fn unit(self) -> &'static str {
        match self {
            SweepParam::DelayTime | SweepParam::Period | SweepParam::ForceLag => "s",
            SweepParam::Cutoff => "Hz",
            SweepParam::Window => "samples",
            SweepParam::Mass
            | SweepParam::MotorMass
            | SweepParam::HandleMass
            | SweepParam::ArmMass => "kg",
            SweepParam::Damping
            | SweepParam::MotorDamping
            | SweepParam::TransmissionDamping
            | SweepParam::ArmDamping => "Ns/m",
            SweepParam::Stiffness
            | SweepParam::TransmissionStiffness
            | SweepParam::ArmStiffness => "N/m",
        }
    }

    /// The loop with this parameter set to `v` (validated like any loop). Fails, naming the
    /// parameter, when the loop has no such parameter (a cut-off without a low-pass estimator,
    /// a motor mass without a two-mass device, …).
    pub fn apply(self, lp: &Loop, v: f64) -> Result<Loop> {
        finite(self.param(), v)?;
        let mut out = lp.clone();
        match self {
            SweepParam::DelayTime => out.delay = Delay::from_time(v, lp.period)?,
            SweepParam::Period => {
                crate::error::positive(Param::Period, v)?;
                out.delay = Delay::from_time(lp.delay_time(), v)?;
                out.period = v;
            }
            SweepParam::Cutoff => match out.velocity {
                VelocityEstimator::LowPass { .. } => {
                    out.velocity = VelocityEstimator::LowPass { cutoff_hz: v };
                }
                _ => {
                    let Some(named) = out.velocity.named_lowpass() else {
                        return Err(missing(
                            self,
                            "a low-pass velocity estimator (lowpass:FC, butterworth:N:FC, \
                             bessel:N:FC or critically-damped:N:FC)",
                        ));
                    };
                    let f = crate::lowpass_design::NamedLowPass {
                        cutoff_hz: v,
                        ..named
                    };
                    out.velocity = f.validated()?.within_nyquist(out.period)?.into();
                }
            },
            SweepParam::Window => match out.velocity {
                VelocityEstimator::Average { .. } => {
                    out.velocity = VelocityEstimator::Average {
                        samples: whole_window(v)?,
                    };
                }
                _ => return Err(missing(self, "an averaging velocity estimator (average:N)")),
            },
            SweepParam::ForceLag => out.plant.force_lag = v,
            _ => out.plant = set_plant(self, &lp.plant, v)?,
        }
        Loop::new(out.plant, out.period, out.delay, out.velocity)
    }
}

fn missing(p: SweepParam, needs: &str) -> Error {
    Error::Invalid {
        param: Param::SweepParameter,
        reason: format!("{} needs {needs}", p.name()),
    }
}

fn whole_window(v: f64) -> Result<usize> {
    if v < 1.0 || v.fract() != 0.0 {
        return Err(Error::OutOfRange {
            param: Param::VelocityWindow,
            value: v,
            range: "whole numbers 1..=2000",
        });
    }
    Ok(v as usize)
}

/// Sets a plant parameter on the plant model that carries it.
fn set_plant(p: SweepParam, plant: &Plant, v: f64) -> Result<Plant> {
    let model = match (&plant.model, p) {
        (PlantModel::MassSpringDamper(e), _) => {
            if let Some(arm) = plant.operator {
                return set_held(p, plant, e, arm, v);
            }
            PlantModel::MassSpringDamper(set_msd(p, e, v)?)
        }
        (PlantModel::TwoMass(t), _) => {
            let mut t = *t;
            match p {
                SweepParam::MotorMass => t.motor_mass = v,
                SweepParam::MotorDamping => t.motor_damping = v,
                SweepParam::HandleMass => t.handle_mass = v,
                SweepParam::TransmissionStiffness => t.transmission_stiffness = v,
                SweepParam::TransmissionDamping => t.transmission_damping = v,
                SweepParam::ArmMass => t.arm.mass = v,
                SweepParam::ArmDamping => t.arm.damping = v,
                SweepParam::ArmStiffness => t.arm.stiffness = v,
                _ => {
                    return Err(missing(
                        p,
                        "the one-mass plant (a two-mass device is given)",
                    ));
                }
            }
            PlantModel::TwoMass(t)
        }
        (PlantModel::TransferFunction { .. }, _) => {
            return Err(missing(
                p,
                "a physical plant (a transfer function is given)",
            ));
        }
    };
    Plant::new(model, plant.force_lag)
}

/// A parameter of a held device (eq. 1 with its operator known): an arm parameter changes
/// the arm and the effective m, b, k with it; m, b, k change the effective plant around the
/// same arm.
fn set_held(p: SweepParam, plant: &Plant, e: &Effective, arm: Arm, v: f64) -> Result<Plant> {
    let mut arm2 = arm;
    match p {
        SweepParam::ArmMass => arm2.mass = v,
        SweepParam::ArmDamping => arm2.damping = v,
        SweepParam::ArmStiffness => arm2.stiffness = v,
        _ => {
            let e = set_msd(p, e, v)?;
            return Plant::new(PlantModel::MassSpringDamper(e), plant.force_lag)?
                .with_operator(arm);
        }
    }
    crate::error::non_negative(p.param(), v)?;
    let e = Effective::new(
        e.mass - arm.mass + arm2.mass,
        e.damping - arm.damping + arm2.damping,
        e.stiffness - arm.stiffness + arm2.stiffness,
    )?;
    Plant::new(PlantModel::MassSpringDamper(e), plant.force_lag)?.with_operator(arm2)
}

fn set_msd(p: SweepParam, e: &Effective, v: f64) -> Result<Effective> {
    match p {
        SweepParam::Mass => Effective::new(v, e.damping, e.stiffness),
        SweepParam::Damping => Effective::new(e.mass, v, e.stiffness),
        SweepParam::Stiffness | SweepParam::ArmStiffness => Effective::new(e.mass, e.damping, v),
        SweepParam::ArmMass | SweepParam::ArmDamping => Err(Error::Invalid {
            param: Param::SweepParameter,
            reason: format!(
                "{} is part of the one-mass plant's effective m = m_L + m_H and b = b_L + b_H; \
                 sweep mass or damping",
                p.name()
            ),
        }),
        _ => Err(missing(p, "a two-mass device")),
    }
}

impl FromStr for SweepParam {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        SweepParam::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| Error::Invalid {
                param: Param::SweepParameter,
                reason: format!(
                    "'{s}' is not one of {}",
                    SweepParam::ALL.map(|p| p.name()).join(", ")
                ),
            })
    }
}

/// Largest number of sweep points.
pub const MAX_SWEEP_POINTS: usize = 100_000;

/// n values from lo to hi inclusive of one parameter: `NAME:LO:HI:N` on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SweepRange {
    /// The parameter.
    pub param: SweepParam,
    /// First value.
    pub lo: f64,
    /// Last value.
    pub hi: f64,
    /// Number of values (>= 2).
    pub n: usize,
}

impl SweepRange {
    /// Validates lo, hi finite and 2 <= n <= [`MAX_SWEEP_POINTS`].
    pub fn new(param: SweepParam, lo: f64, hi: f64, n: usize) -> Result<Self> {
        finite(Param::SweepStart, lo)?;
        finite(Param::SweepEnd, hi)?;
        if !(2..=MAX_SWEEP_POINTS).contains(&n) {
            return Err(Error::OutOfRange {
                param: Param::SweepPoints,
                value: n as f64,
                range: "2..=100000",
            });
        }
        Ok(Self { param, lo, hi, n })
    }

    /// The i-th value.
    pub fn value(&self, i: usize) -> f64 {
        crate::grid::evenly_spaced_at(self.lo, self.hi, self.n, i)
    }

    /// All values.
    pub fn values(&self) -> Vec<f64> {
        (0..self.n).map(|i| self.value(i)).collect()
    }
}

impl FromStr for SweepRange {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        let parts: Vec<&str> = s.split(':').collect();
        let [name, lo, hi, n] = parts[..] else {
            return Err(Error::Invalid {
                param: Param::SweepRange,
                reason: format!("'{s}' must be NAME:START:END:POINTS, e.g. delay-time:0:0.005:50"),
            });
        };
        let num = |param: Param, t: &str| {
            t.trim().parse::<f64>().map_err(|_| Error::Invalid {
                param,
                reason: format!("'{t}' is not a number"),
            })
        };
        let count = n.trim().parse::<usize>().map_err(|_| Error::Invalid {
            param: Param::SweepPoints,
            reason: format!("'{n}' is not a whole number"),
        })?;
        Self::new(
            name.trim().parse()?,
            num(Param::SweepStart, lo)?,
            num(Param::SweepEnd, hi)?,
            count,
        )
    }
}

/// Where K_max is taken.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum KmaxAt {
    /// Over every damping B: the stable region's largest K (Section V).
    Overall,
    /// At one virtual damping B in Ns/m: the top of the exact stable interval.
    Damping {
        /// B in Ns/m.
        damping: f64,
    },
    /// Over a damping band lo <= B <= hi in Ns/m.
    Band {
        /// Lowest B.
        lo: f64,
        /// Highest B.
        hi: f64,
    },
}

/// K_max at one parameter value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepPoint {
    /// The parameter's value.
    pub value: f64,
    /// Largest stable K in N/m (None when none is stable, or undecided: see `note`).
    pub k_max: Option<f64>,
    /// The B in Ns/m where it is reached.
    pub b_at_k_max: Option<f64>,
    /// Largest passive K in N/m under the same damping constraint, for the device's own
    /// damping (None when passivity does not apply or nothing is passive).
    pub k_max_passive: Option<f64>,
    /// The same by the paper's eq. (28) with the arm's damping counted (b = b_L + b_H): towards
    /// this operator only; None when the plant names no operator.
    pub k_max_passive_with_arm: Option<f64>,
    /// Why a value is missing, when the analysis could not decide.
    pub note: Option<String>,
    /// Why passivity does not apply to this loop (then both passive K_max are None): an
    /// actuator lag, a plant without a known device damping, a velocity filter the
    /// passivity condition cannot take. None where it applies.
    pub passive_note: Option<String>,
}

/// K_max (stable and passive) of the loops `loop_at(v)` for every value, in parallel;
/// `progress` is called with the number of points done. Every loop is built (and so
/// validated) before any analysis, so a bad value fails the whole sweep with its message.
/// The passive K_max depends only on the sampled wall (period, delay, velocity estimator) and
/// the damping that counts, so points that share them (a sweep of an arm or plant parameter)
/// share one computation.
pub fn kmax_sweep<F>(
    values: &[f64],
    loop_at: F,
    at: KmaxAt,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<SweepPoint>>
where
    F: Fn(f64) -> Result<Loop>,
{
    let loops: Vec<Loop> = values.iter().map(|&v| loop_at(v)).collect::<Result<_>>()?;
    let keys: Vec<PassiveKey> = loops.iter().map(PassiveKey::of).collect();
    // the first point of each distinct key, and each point's key among them; each key's
    // passive K_max is computed once, by the first worker that needs it
    let mut firsts: Vec<usize> = Vec::new();
    let slot: Vec<usize> = (0..keys.len())
        .map(|i| match firsts.iter().position(|&j| keys[j] == keys[i]) {
            Some(s) => s,
            None => {
                firsts.push(i);
                firsts.len() - 1
            }
        })
        .collect();
    let passive: Vec<OnceLock<PassiveKmax>> = firsts.iter().map(|_| OnceLock::new()).collect();
    let passive_at = |i: usize| -> PassiveKmax {
        let s = slot[i];
        passive[s]
            .get_or_init(|| PassiveKmax::of(&loops[firsts[s]], &keys[firsts[s]], at))
            .clone()
    };
    // Runs of neighbouring points, each computed in order from the previous point's top on
    // the curve (the warm start of `k_max_band_near`, the run's first point cold), the runs
    // with the longest delays (the costliest points: p's degree grows with them) first. The
    // runs, and so every answer to the last bit, depend neither on the number of threads nor
    // on their timing.
    let runs: Vec<std::ops::Range<usize>> = (0..values.len())
        .step_by(SWEEP_RUN)
        .map(|i| i..(i + SWEEP_RUN).min(values.len()))
        .collect();
    let cost = |r: &std::ops::Range<usize>| -> usize {
        r.clone().map(|i| loops[i].delay.samples + 8).sum()
    };
    let mut order: Vec<usize> = (0..runs.len()).collect();
    order.sort_by_key(|&j| std::cmp::Reverse(cost(&runs[j])));
    let done = AtomicUsize::new(0);
    let run = |k: usize| -> Vec<SweepPoint> {
        let mut near = None;
        runs[order[k]]
            .clone()
            .map(|i| {
                let p = sweep_point(values[i], &loops[i], at, passive_at(i), &mut near);
                progress(done.fetch_add(1, Ordering::Relaxed) + 1);
                p
            })
            .collect()
    };
    let mut by_run: Vec<Vec<SweepPoint>> = vec![Vec::new(); runs.len()];
    for (k, points) in list_scheduled(order.len(), &run).into_iter().enumerate() {
        by_run[order[k]] = points;
    }
    Ok(by_run.into_iter().flatten().collect())
}

/// `task(k)` for k = 0 … n − 1 on rayon's pool, one worker per thread, each taking the next
/// k (list scheduling, so that tasks given costliest first balance). The results by k; they
/// do not depend on which thread computed them.
fn list_scheduled<T: Send>(n: usize, task: &(dyn Fn(usize) -> T + Sync)) -> Vec<T> {
    let next = AtomicUsize::new(0);
    let workers = rayon::current_num_threads().clamp(1, n.max(1));
    let mut all: Vec<(usize, T)> = (0..workers)
        .into_par_iter()
        .with_max_len(1)
        .flat_map_iter(|_| {
            let mut mine = Vec::new();
            loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                if k >= n {
                    return mine;
                }
                mine.push((k, task(k)));
            }
        })
        .collect();
    all.sort_by_key(|(k, _)| *k);
    all.into_iter().map(|(_, t)| t).collect()
}

/// Neighbouring points of a sweep computed in order on one thread, each warm-started from the
/// previous one's top on the curve (a point's cost is about d + 8 units for d samples of
/// delay; a run's first point starts cold).
const SWEEP_RUN: usize = 5;

/// The sweep of one parameter of a base loop (see [`SweepParam::apply`]).
pub fn sweep_param(
    base: &Loop,
    range: &SweepRange,
    at: KmaxAt,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<SweepPoint>> {
    kmax_sweep(
        &range.values(),
        |v| range.param.apply(base, v),
        at,
        progress,
    )
}

fn sweep_point(
    value: f64,
    lp: &Loop,
    at: KmaxAt,
    passive: PassiveKmax,
    near: &mut Option<CurveTop>,
) -> SweepPoint {
    let mut p = SweepPoint {
        value,
        k_max: None,
        b_at_k_max: None,
        k_max_passive: passive.device,
        k_max_passive_with_arm: passive.with_arm,
        note: None,
        passive_note: passive.why_not,
    };
    match stable_kmax(lp, at, near) {
        Ok(Some((k, b))) => {
            p.k_max = Some(k);
            p.b_at_k_max = Some(b);
        }
        Ok(None) => {}
        Err(e) => p.note = Some(e.to_string()),
    }
    p
}

/// What a point's passive K_max depends on: the sampled wall and the dampings that count.
#[derive(Debug, Clone, PartialEq)]
struct PassiveKey {
    period: f64,
    delay: Delay,
    velocity: VelocityEstimator,
    /// The device's own damping, or why the passivity condition does not apply.
    device: DeviceDamping,
    /// The device's and the arm's damping together (eq. 28's b).
    with_arm: Option<f64>,
}

impl PassiveKey {
    fn of(lp: &Loop) -> Self {
        let device = device_damping(&lp.plant);
        let with_arm = match device {
            DeviceDamping::Known { .. } => lp.plant.effective_damping(),
            DeviceDamping::NotApplicable { .. } => None,
        };
        Self {
            period: lp.period,
            delay: lp.delay,
            velocity: lp.velocity.clone(),
            device,
            with_arm,
        }
    }
}

/// The passive K_max of a point: for the device's own damping and with the arm's counted,
/// or why passivity does not apply.
#[derive(Debug, Clone, Default)]
struct PassiveKmax {
    device: Option<f64>,
    with_arm: Option<f64>,
    why_not: Option<String>,
}

impl PassiveKmax {
    fn of(lp: &Loop, key: &PassiveKey, at: KmaxAt) -> Self {
        let damping = match &key.device {
            DeviceDamping::Known { damping } => *damping,
            DeviceDamping::NotApplicable { reason } => return Self::not_applicable(reason.clone()),
        };
        let sw = match SampledWall::new(lp) {
            Ok(sw) => sw,
            Err(e) => return Self::not_applicable(e.to_string()),
        };
        let device = passive_kmax(&sw, at, damping);
        let with_arm = key.with_arm.and_then(|b| match at {
            // the passive region scales with the device damping (b_required is positively
            // homogeneous in (K, B)): its largest K too
            KmaxAt::Overall if damping > 0.0 => device.map(|k| k * (b / damping)),
            _ => passive_kmax(&sw, at, b),
        });
        Self {
            device,
            with_arm,
            why_not: None,
        }
    }

    fn not_applicable(why_not: String) -> Self {
        Self {
            why_not: Some(why_not),
            ..Self::default()
        }
    }
}

/// The largest stable K and its B in physical units.
/// `near`: the previous point's top on the curve, the warm start of [`k_max_band_near`], replaced by
/// this point's.
fn stable_kmax(lp: &Loop, at: KmaxAt, near: &mut Option<CurveTop>) -> Result<Option<(f64, f64)>> {
    // through the loop's System: the same family and units as `kmax` and `boundary`
    let sys = System::of(lp)?;
    let units = |b: f64| -> Result<f64> {
        if b.is_finite() {
            sys.damping_units(b)
        } else {
            Ok(b)
        }
    };
    let best = match at {
        KmaxAt::Damping { damping } => {
            let beta = units(damping)?;
            sys.stable_intervals(beta)
                .iter()
                .map(|iv| iv.hi)
                .filter(|h| h.is_finite())
                .reduce(f64::max)
                .map(|a| (a, beta))
        }
        KmaxAt::Overall => band_kmax(
            sys.verdict_family(),
            (f64::NEG_INFINITY, f64::INFINITY),
            near,
        )?,
        KmaxAt::Band { lo, hi } => band_kmax(sys.verdict_family(), (units(lo)?, units(hi)?), near)?,
    };
    Ok(best.map(|(a, b)| sys.family().to_physical(a, b)))
}

/// K_max over a damping band in wall units and its damping: from the D-decomposition's
/// candidates ([`k_max_band`]), else from the region at the sweep's tolerance.
fn band_kmax(
    fam: &AffineFamily,
    (b0, b1): (f64, f64),
    near: &mut Option<CurveTop>,
) -> Result<Option<(f64, f64)>> {
    let (answer, top) = k_max_band_near(fam, b0, b1, *near);
    *near = top;
    Ok(match answer {
        BandMax::Max(p) => Some((p.a, p.b)),
        BandMax::NoneStable => None,
        BandMax::Undecided => {
            let r = stable_region_with(fam, SWEEP_REL_TOL)?;
            alpha_max_within(fam, &r, b0, b1)?.map(|p| (p.a, p.b))
        }
    })
}

/// The largest passive K for a device damping b under the same damping constraint; the
/// passive region is convex, so over a band it is the region's maximum if its B lies in the
/// band, else the band's nearer edge.
fn passive_kmax(sw: &SampledWall, at: KmaxAt, b: f64) -> Option<f64> {
    let best = || passive_k_max(sw, b).filter(|w| w.stiffness.is_finite());
    match at {
        KmaxAt::Damping { damping } => k_max_passive_at(sw, b, damping),
        KmaxAt::Overall => best().map(|w| w.stiffness),
        KmaxAt::Band { lo, hi } => {
            let w = best()?;
            if (lo..=hi).contains(&w.damping) {
                Some(w.stiffness)
            } else {
                let edge = if w.damping < lo { lo } else { hi };
                k_max_passive_at(sw, b, edge)
            }
        }
    }
}
