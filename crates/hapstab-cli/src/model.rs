//! Model arguments shared by the commands: normalized (α, β, γ, δ, d) or physical units.

use anyhow::{Result, bail};
use clap::Args;
use hapstab::model::{Delay, Loop, Plant, PlantModel as LibPlantModel, TwoMass, VelocityEstimator};
use hapstab::params::{Arm, Device, Effective, Normalized, Physical, Sampling, Wall};
use hapstab::{AffineFamily, Param, System};
use serde::Serialize;

use crate::output::{poly_text, sig};
use hapstab::spec::excerpt_list;

pub use hapstab::loop_spec::{DEFAULT_PERIOD, DEFAULT_WALL};

/// The flags that describe a physical plant or its sampling: none of them may be combined
/// with the normalized plant (--gamma/--delta).
pub const PHYSICAL_PLANT_FLAGS: [&str; 11] = [
    "mass",
    "damping",
    "stiffness",
    "device_mass",
    "device_damping",
    "arm_mass",
    "arm_damping",
    "arm_stiffness",
    "no_arm",
    "period",
    "delay_time",
];

/// Plant and sampling: either normalized (γ, δ) or physical units. Without any flag: a
/// PHANToM-like device (m_L = 0.1 kg, b_L = 1.5 Ns/m) held by a typical arm (m_H = 1 kg,
/// b_H = 6 Ns/m, k_H = 350 N/m), T = 1 ms, d = 0.
#[derive(Args, Debug, Clone, Default)]
pub struct PlantArgs {
    /// Normalized physical stiffness γ = kT²/m (normalized mode: the paper's plant only).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = PHYSICAL_PLANT_FLAGS)]
    pub gamma: Option<f64>,
    /// Normalized physical damping δ = bT/m (normalized mode: the paper's plant only).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = PHYSICAL_PLANT_FLAGS)]
    pub delta: Option<f64>,
    /// Effective mass m = m_L + m_H in kg (replaces the device and arm split).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["device_mass", "arm_mass"])]
    pub mass: Option<f64>,
    /// Effective damping b = b_L + b_H in Ns/m.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["device_damping", "arm_damping"])]
    pub damping: Option<f64>,
    /// Effective stiffness k = k_H in N/m.
    #[arg(long, allow_hyphen_values = true, conflicts_with = "arm_stiffness")]
    pub stiffness: Option<f64>,
    /// Device mass m_L in kg [default: 0.1].
    #[arg(long, allow_hyphen_values = true)]
    pub device_mass: Option<f64>,
    /// Device damping b_L in Ns/m [default: 1.5].
    #[arg(long, allow_hyphen_values = true)]
    pub device_damping: Option<f64>,
    /// Arm mass m_H in kg [default: 1.0].
    #[arg(long, allow_hyphen_values = true)]
    pub arm_mass: Option<f64>,
    /// Arm damping b_H in Ns/m [default: 6].
    #[arg(long, allow_hyphen_values = true)]
    pub arm_damping: Option<f64>,
    /// Arm stiffness k_H in N/m [default: 350].
    #[arg(long, allow_hyphen_values = true)]
    pub arm_stiffness: Option<f64>,
    /// No human arm: the ungrabbed device (k_H = b_H = m_H = 0).
    #[arg(long, conflicts_with_all = ["arm_mass", "arm_damping", "arm_stiffness", "mass", "damping", "stiffness"])]
    pub no_arm: bool,
    /// Sampling period T in s, from 1e-7 to 1 [default: 0.001].
    #[arg(long, allow_hyphen_values = true)]
    pub period: Option<f64>,
    /// Delay d in whole samples [default: 0].
    #[arg(long, allow_hyphen_values = true, conflicts_with = "delay_time")]
    pub delay: Option<f64>,
    /// Delay t_d = (d + λ)T in seconds; a fraction λ of a period is discretized exactly
    /// (modified z-transform) by the commands that accept the general loop.
    #[arg(long, allow_hyphen_values = true)]
    pub delay_time: Option<f64>,
    /// A loop saved as JSON: a report's "input" (e.g. `hapstab check --json > my.json`), its
    /// "loop" object, or a whole report. Flags given beside it change its parts: the arm,
    /// device or two-mass flags the matching parts of its plant, the other plant flags
    /// replace the plant; --period, --delay, --velocity, --force-lag and the wall flags
    /// their own part (a new --period keeps the file's delay in samples).
    #[arg(long = "loop", value_name = "FILE")]
    pub loop_file: Option<std::path::PathBuf>,
}

/// The resolved plant: normalized only, or physical with the normalization it implies.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct PlantModel {
    /// γ.
    pub gamma: f64,
    /// δ.
    pub delta: f64,
    /// d.
    pub d: usize,
    /// Physical plant and sampling, when given in physical units.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub physical: Option<(Effective, Sampling)>,
}

/// A delay in whole samples from the --delay flag.
pub fn delay_samples(v: f64) -> Result<usize> {
    if !v.is_finite() {
        bail!("delay d must be a finite whole number of samples (got {v})");
    }
    if v < 0.0 {
        bail!("delay d must be >= 0 (got {v})");
    }
    if v.fract() != 0.0 {
        bail!("delay d must be a whole number of samples (got {v}); use --delay-time for seconds");
    }
    Ok(hapstab::params::check_delay(v as usize)?)
}

impl PlantArgs {
    /// True when the plant is given normalized (--gamma/--delta).
    pub fn normalized_mode(&self) -> bool {
        self.gamma.is_some() || self.delta.is_some()
    }

    /// True when a physical plant or sampling flag is given.
    pub fn any_physical(&self) -> bool {
        self.mass.is_some()
            || self.damping.is_some()
            || self.stiffness.is_some()
            || self.device_mass.is_some()
            || self.device_damping.is_some()
            || self.arm_mass.is_some()
            || self.arm_damping.is_some()
            || self.arm_stiffness.is_some()
            || self.no_arm
            || self.period.is_some()
            || self.delay_time.is_some()
    }

    /// The effective plant of eq. (1) from the physical flags and defaults.
    pub fn effective(&self) -> Result<Effective> {
        if self.mass.is_some() || self.damping.is_some() || self.stiffness.is_some() {
            let m = self.mass.unwrap_or(Device::PHANTOM_LIKE.mass);
            return Ok(Effective::new(
                m,
                self.damping.unwrap_or(Device::PHANTOM_LIKE.damping),
                self.stiffness.unwrap_or(0.0),
            )?);
        }
        let device = Device {
            mass: self.device_mass.unwrap_or(Device::PHANTOM_LIKE.mass),
            damping: self.device_damping.unwrap_or(Device::PHANTOM_LIKE.damping),
        };
        Ok(Effective::combine(device, self.arm())?)
    }

    /// The arm inside the effective plant of eq. (1), when the plant is given as a device and
    /// an arm (not as --mass/--damping/--stiffness, and not with --no-arm).
    pub fn operator(&self) -> Option<Arm> {
        let lumped = self.mass.is_some() || self.damping.is_some() || self.stiffness.is_some();
        let arm = self.arm();
        (!lumped && arm != Arm::NONE).then_some(arm)
    }

    /// The arm from the arm flags: the typical arm by default, none with --no-arm.
    pub fn arm(&self) -> Arm {
        let base = if self.no_arm { Arm::NONE } else { Arm::TYPICAL };
        Arm {
            mass: self.arm_mass.unwrap_or(base.mass),
            damping: self.arm_damping.unwrap_or(base.damping),
            stiffness: self.arm_stiffness.unwrap_or(base.stiffness),
        }
    }

    /// The sampling period and delay.
    pub fn sampling(&self) -> Result<Sampling> {
        let period = self.period.unwrap_or(DEFAULT_PERIOD);
        if let Some(t) = self.delay_time {
            return Ok(Sampling::from_delay_time(period, t)?);
        }
        Ok(Sampling::new(
            period,
            delay_samples(self.delay.unwrap_or(0.0))?,
        )?)
    }

    /// Resolves the plant in either mode.
    pub fn resolve(&self) -> Result<PlantModel> {
        if self.loop_file.is_some() {
            return crate::loop_file::paper_plant(self, "this analysis")?.resolve();
        }
        if self.normalized_mode() {
            if self.any_physical() {
                bail!("give either normalized (--gamma/--delta) or physical parameters, not both");
            }
            let pp =
                hapstab::PlantParams::new(self.gamma.unwrap_or(0.0), self.delta.unwrap_or(0.0))?;
            let d = delay_samples(self.delay.unwrap_or(0.0))?;
            return Ok(PlantModel {
                gamma: pp.gamma,
                delta: pp.delta,
                d,
                physical: None,
            });
        }
        let eff = self.effective()?;
        let s = self.sampling()?;
        let pp = hapstab::PlantParams::from_physical(&eff, s.period)?;
        Ok(PlantModel {
            gamma: pp.gamma,
            delta: pp.delta,
            d: s.delay,
            physical: Some((eff, s)),
        })
    }
}

/// A wall in either unit system.
#[derive(Args, Debug, Clone, Default)]
pub struct WallArgs {
    /// Normalized virtual stiffness α = KT²/m (the paper's plant only).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["wall_stiffness", "wall_damping"])]
    pub alpha: Option<f64>,
    /// Normalized virtual damping β = BT/m (the paper's plant only).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["wall_stiffness", "wall_damping"])]
    pub beta: Option<f64>,
    /// Virtual stiffness K in N/m [default: 10000 in physical mode].
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["gamma", "delta"])]
    pub wall_stiffness: Option<f64>,
    /// Virtual damping B in Ns/m [default: 10 in physical mode].
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["gamma", "delta"])]
    pub wall_damping: Option<f64>,
}

/// A fully resolved model for one parameter point.
#[derive(Debug, Clone, Copy)]
pub struct PointModel {
    /// Normalized parameters.
    pub normalized: Normalized,
    /// Physical description, when given in physical units.
    pub physical: Option<Physical>,
}

/// Resolves plant and wall arguments to one parameter point.
pub fn resolve_point(plant: &PlantArgs, wall: &WallArgs) -> Result<PointModel> {
    let normalized_wall = wall.alpha.is_some() || wall.beta.is_some();
    // --alpha/--beta without any physical flag: normalized mode with γ = δ = 0 by default.
    let pm = if normalized_wall && !plant.any_physical() {
        let mut p = plant.clone();
        p.gamma = Some(p.gamma.unwrap_or(0.0));
        p.resolve()?
    } else {
        plant.resolve()?
    };
    let physical_wall = wall.wall_stiffness.is_some() || wall.wall_damping.is_some();
    match pm.physical {
        None => {
            if physical_wall {
                bail!(
                    "--wall-stiffness/--wall-damping need a physical plant; use --alpha/--beta with --gamma/--delta"
                );
            }
            let (Some(alpha), Some(beta)) = (wall.alpha, wall.beta) else {
                bail!("normalized mode needs both --alpha and --beta");
            };
            Ok(PointModel {
                normalized: Normalized::new(alpha, beta, pm.gamma, pm.delta, pm.d)?,
                physical: None,
            })
        }
        Some((eff, s)) => {
            if normalized_wall {
                if physical_wall {
                    bail!(
                        "give the wall either as --alpha/--beta or as --wall-stiffness/--wall-damping"
                    );
                }
                let (Some(alpha), Some(beta)) = (wall.alpha, wall.beta) else {
                    bail!("give both --alpha and --beta");
                };
                let w = hapstab::params::wall_from_normalized(alpha, beta, eff.mass, s.period);
                let phys = Physical::new(eff, w, s)?;
                return Ok(PointModel {
                    normalized: phys.normalized()?,
                    physical: Some(phys),
                });
            }
            let w = Wall {
                stiffness: wall.wall_stiffness.unwrap_or(DEFAULT_WALL.stiffness),
                damping: wall.wall_damping.unwrap_or(DEFAULT_WALL.damping),
            };
            let phys = Physical::new(eff, w, s)?;
            Ok(PointModel {
                normalized: phys.normalized()?,
                physical: Some(phys),
            })
        }
    }
}

/// A transfer-function plant replaces every other plant description.
const TF_CONFLICTS: [&str; 16] = [
    "gamma",
    "delta",
    "mass",
    "damping",
    "stiffness",
    "device_mass",
    "device_damping",
    "arm_mass",
    "arm_damping",
    "arm_stiffness",
    "no_arm",
    "motor_mass",
    "motor_damping",
    "handle_mass",
    "transmission_stiffness",
    "transmission_damping",
];

/// A two-mass device replaces the normalized plant and the one-mass device with its
/// effective m, b, k; the arm flags stay (the arm holds the handle).
const TWO_MASS_CONFLICTS: [&str; 7] = [
    "gamma",
    "delta",
    "mass",
    "damping",
    "stiffness",
    "device_mass",
    "device_damping",
];

/// Plants without the paper's mass m, which a normalized wall (--alpha/--beta) is scaled by.
pub const NON_PAPER_PLANT_FLAGS: [&str; 7] = [
    "plant_num",
    "plant_den",
    "motor_mass",
    "motor_damping",
    "handle_mass",
    "transmission_stiffness",
    "transmission_damping",
];

/// The flags that go beyond the paper's loop (any of them makes a loop physical).
pub const LOOP_FLAGS: [&str; 9] = [
    "plant_num",
    "plant_den",
    "motor_mass",
    "motor_damping",
    "handle_mass",
    "transmission_stiffness",
    "transmission_damping",
    "force_lag",
    "velocity",
];

/// A comma-separated coefficient list as typed on the command line.
#[derive(Debug, Clone, PartialEq)]
pub struct Coefficients(pub Vec<f64>);

fn plant_numerator(s: &str) -> std::result::Result<Coefficients, String> {
    hapstab::spec::parse_coefficients(Param::PlantNum, s)
        .map(Coefficients)
        .map_err(|e| e.to_string())
}

fn plant_denominator(s: &str) -> std::result::Result<Coefficients, String> {
    hapstab::spec::parse_coefficients(Param::PlantDen, s)
        .map(Coefficients)
        .map_err(|e| e.to_string())
}

fn velocity_estimator(s: &str) -> std::result::Result<VelocityEstimator, String> {
    s.parse::<VelocityEstimator>().map_err(|e| e.to_string())
}

fn time_constant(s: &str) -> std::result::Result<f64, String> {
    let tau: f64 = s
        .trim()
        .parse()
        .map_err(|_| "not a number of seconds".to_string())?;
    if !tau.is_finite() || tau < 0.0 {
        return Err("the actuator time constant must be a finite number >= 0".into());
    }
    Ok(tau)
}

/// The user's loop: the paper's flags ([`PlantArgs`]) plus a plant given as a transfer
/// function or a two-mass device, an actuator lag and a velocity estimator. Without the new
/// flags it is the paper's loop.
#[derive(Args, Debug, Clone, Default)]
pub struct LoopArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Plant P(s) = num(s)/den(s) from wall force (N) to measured position (m): numerator
    /// coefficients, highest power of s first, comma-separated (as MATLAB's and
    /// python-control's tf), e.g. --plant-num 10 --plant-den 1,3,10. Strictly proper,
    /// order <= 12.
    #[arg(long, value_name = "COEFFS", allow_hyphen_values = true,
          value_parser = plant_numerator, conflicts_with_all = TF_CONFLICTS)]
    pub plant_num: Option<Coefficients>,
    /// Denominator of P(s), highest power of s first, comma-separated (with --plant-num).
    #[arg(long, value_name = "COEFFS", allow_hyphen_values = true,
          value_parser = plant_denominator, conflicts_with_all = TF_CONFLICTS)]
    pub plant_den: Option<Coefficients>,
    /// Two-mass device: motor-side mass J in kg, where the actuator pushes and the encoder
    /// measures (needs --transmission-stiffness; the arm flags act on the handle).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = TWO_MASS_CONFLICTS)]
    pub motor_mass: Option<f64>,
    /// Two-mass device: motor-side viscous damping b_m in Ns/m [default: 0].
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = TWO_MASS_CONFLICTS)]
    pub motor_damping: Option<f64>,
    /// Two-mass device: handle mass m_h in kg [default: 0]; the arm's mass adds to it.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = TWO_MASS_CONFLICTS)]
    pub handle_mass: Option<f64>,
    /// Two-mass device: transmission stiffness k_t in N/m between motor and handle.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = TWO_MASS_CONFLICTS)]
    pub transmission_stiffness: Option<f64>,
    /// Two-mass device: transmission damping b_t in Ns/m [default: 0].
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = TWO_MASS_CONFLICTS)]
    pub transmission_damping: Option<f64>,
    /// Actuator lag: the applied force follows the commanded one through 1/(τs + 1), τ in s
    /// (the current loop's time constant) [default: 0: no lag].
    #[arg(long, value_name = "TAU", allow_hyphen_values = true,
          value_parser = time_constant, conflicts_with_all = ["gamma", "delta"])]
    pub force_lag: Option<f64>,
    /// Velocity estimator of the wall's damper [default: backward]:
    ///   backward                v_k = (y_k − y_{k−1})/T  (the paper's)
    ///   lowpass:FC              v_k = a·v_{k−1} + (1 − a)(y_k − y_{k−1})/T,
    ///                           a = exp(−2π·f_c·T), f_c = FC in Hz
    ///   butterworth:N:FC        the backward difference through a digital Butterworth
    ///                           low-pass of order N (1–8), cut-off FC Hz (MATLAB's and
    ///                           scipy's butter(N, FC, fs=1/T))
    ///   bessel:N:FC             the same through a digital Bessel low-pass (scipy's
    ///                           bessel(N, FC, fs=1/T), phase-normalized), N 1–8
    ///   critically-damped:N:FC  the same through N equal real poles (no overshoot),
    ///                           −3 dB at FC Hz, N 1–8 (all three bilinear, pre-warped)
    ///   average:N               v_k = (y_k − y_{k−N})/(N·T)
    ///   iir:b0,b1,…/a0,a1,…     v = (b0 + b1 z⁻¹ + …)/(a0 + a1 z⁻¹ + …) · y in m/s,
    ///                           any proper discrete filter on the position (a0 ≠ 0)
    #[arg(long, value_name = "SPEC", allow_hyphen_values = true, verbatim_doc_comment,
          value_parser = velocity_estimator, conflicts_with_all = ["gamma", "delta"])]
    pub velocity: Option<VelocityEstimator>,
    /// The --loop file's delay (whole samples and a fraction), when no delay flag changes it.
    #[arg(skip)]
    pub file_delay: Option<Delay>,
}

/// A loop resolved from the flags.
#[derive(Debug, Clone)]
pub struct ResolvedLoop {
    /// The loop (for a normalized plant: [`Loop::normalized`], m = T = 1, so K = α, B = β).
    pub lp: Loop,
    /// True when the plant was given normalized (--gamma/--delta, or --alpha/--beta alone).
    pub normalized: bool,
    /// The wall of the --loop file, in the loop's units, when it names one.
    pub wall: Option<Wall>,
}

impl ResolvedLoop {
    /// The loop's analysis object (discretized and closed once).
    pub fn system(&self) -> hapstab::Result<System> {
        System::of(&self.lp)
    }
}

impl LoopArgs {
    /// True when any flag beyond the paper's loop is given.
    pub fn any_loop_flag(&self) -> bool {
        self.plant_num.is_some()
            || self.plant_den.is_some()
            || self.two_mass_given()
            || self.force_lag.is_some()
            || self.velocity.is_some()
    }

    pub(crate) fn two_mass_given(&self) -> bool {
        self.motor_mass.is_some()
            || self.motor_damping.is_some()
            || self.handle_mass.is_some()
            || self.transmission_stiffness.is_some()
            || self.transmission_damping.is_some()
    }

    /// True when some flag describes a physical plant, its sampling or a loop beyond the
    /// paper's (then a lone --alpha/--beta is a wall on that loop, not a normalized plant).
    pub fn any_physical(&self) -> bool {
        self.plant.any_physical() || self.any_loop_flag()
    }

    /// Resolves the loop; `normalized_wall` says whether --alpha/--beta were given (alone
    /// they select the normalized paper loop with γ = δ = 0).
    pub fn resolve(&self, normalized_wall: bool) -> Result<ResolvedLoop> {
        if let Some(path) = &self.plant.loop_file {
            return crate::loop_file::resolve(self, path, normalized_wall);
        }
        self.resolve_over(normalized_wall, None)
    }

    /// [`LoopArgs::resolve`] with the plant `base` (its model and arm; the lag from the
    /// flags) in place of the plant flags, when given.
    pub fn resolve_over(
        &self,
        normalized_wall: bool,
        base: Option<&Plant>,
    ) -> Result<ResolvedLoop> {
        if self.plant.normalized_mode() || (normalized_wall && !self.any_physical()) {
            let pp = hapstab::PlantParams::new(
                self.plant.gamma.unwrap_or(0.0),
                self.plant.delta.unwrap_or(0.0),
            )?;
            let d = delay_samples(self.plant.delay.unwrap_or(0.0))?;
            return Ok(ResolvedLoop {
                lp: Loop::normalized(pp, d)?,
                normalized: true,
                wall: None,
            });
        }
        let period = self.plant.period.unwrap_or(DEFAULT_PERIOD);
        let model = match base {
            Some(p) => p.model.clone(),
            None => self.plant_model()?,
        };
        if let LibPlantModel::MassSpringDamper(eff) = &model {
            // γ = kT²/m and δ = bT/m must be finite: a mass so small (or a stiffness so
            // large) that they overflow is refused here, naming the physical parameter
            hapstab::PlantParams::from_physical(eff, period)?;
        }
        let mut plant =
            Plant::new(model, self.force_lag.unwrap_or(0.0)).map_err(|e| tf_context(self, e))?;
        let operator = match base {
            Some(p) => p.operator,
            None => self.plant.operator(),
        };
        if let (LibPlantModel::MassSpringDamper(_), Some(arm)) = (&plant.model, operator) {
            plant = plant.with_operator(arm)?;
        }
        let velocity = self.velocity.clone().unwrap_or(VelocityEstimator::Backward);
        Ok(ResolvedLoop {
            lp: Loop::new(plant, period, self.delay(period)?, velocity)
                .map_err(|e| self.with_flag(e))?,
            normalized: false,
            wall: None,
        })
    }

    fn delay(&self, period: f64) -> Result<Delay> {
        if let Some(d) = self.file_delay {
            return Ok(d);
        }
        Ok(match self.plant.delay_time {
            Some(t) => Delay::from_time(t, period)?,
            None => Delay::samples(delay_samples(self.plant.delay.unwrap_or(0.0))?)?,
        })
    }

    fn plant_model(&self) -> Result<LibPlantModel> {
        match (&self.plant_num, &self.plant_den) {
            (Some(num), Some(den)) => {
                return Ok(LibPlantModel::TransferFunction {
                    num: num.0.clone(),
                    den: den.0.clone(),
                });
            }
            (Some(_), None) => bail!("--plant-num needs --plant-den (the plant's denominator)"),
            (None, Some(_)) => bail!("--plant-den needs --plant-num (the plant's numerator)"),
            (None, None) => {}
        }
        if self.two_mass_given() {
            return Ok(LibPlantModel::TwoMass(self.two_mass()?));
        }
        Ok(LibPlantModel::MassSpringDamper(self.plant.effective()?))
    }

    fn two_mass(&self) -> Result<TwoMass> {
        let Some(motor_mass) = self.motor_mass else {
            bail!("the two-mass device needs --motor-mass (the motor-side mass in kg)");
        };
        let Some(transmission_stiffness) = self.transmission_stiffness else {
            bail!("the two-mass device needs --transmission-stiffness (k_t in N/m)");
        };
        Ok(TwoMass {
            motor_mass,
            motor_damping: self.motor_damping.unwrap_or(0.0),
            handle_mass: self.handle_mass.unwrap_or(0.0),
            transmission_stiffness,
            transmission_damping: self.transmission_damping.unwrap_or(0.0),
            arm: self.plant.arm(),
        })
    }
}

/// Names the typed coefficient lists in a transfer-function error.
fn tf_context(a: &LoopArgs, e: hapstab::Error) -> anyhow::Error {
    match (&a.plant_num, &a.plant_den, &e) {
        (Some(n), Some(d), hapstab::Error::Invalid { .. } | hapstab::Error::OutOfRange { .. }) => {
            anyhow::anyhow!(
                "--plant-num {} --plant-den {}: {e}",
                excerpt_list(&n.0),
                excerpt_list(&d.0)
            )
        }
        _ => a.with_flag(e),
    }
}

impl LoopArgs {
    /// A library error with the flag that carries the parameter it names in front
    /// ("--motor-mass: motor mass must be in …"); the effective mass, damping and stiffness of
    /// a device and arm given separately are named by those flags.
    fn with_flag(&self, e: hapstab::Error) -> anyhow::Error {
        let flag = match (e.param(), self.plant.mass) {
            (Some(Param::Mass), None) => Some("--device-mass/--arm-mass"),
            (Some(Param::Damping), None) if self.plant.damping.is_none() => {
                Some("--device-damping/--arm-damping")
            }
            (Some(Param::Stiffness), None) if self.plant.stiffness.is_none() => {
                Some("--arm-stiffness")
            }
            (p, _) => p.and_then(Param::flag),
        };
        match flag {
            Some(f) => anyhow::anyhow!("{f}: {e}"),
            None => e.into(),
        }
    }
}

impl WallArgs {
    /// True when the wall is given normalized (--alpha/--beta).
    pub fn normalized(&self) -> bool {
        self.alpha.is_some() || self.beta.is_some()
    }

    /// The wall flags with the --loop file's wall (if any) where they give none: α and β for
    /// a normalized loop, else K and B (unless the flags give a normalized wall).
    pub fn over_file(&self, rl: &ResolvedLoop) -> WallArgs {
        let mut w = self.clone();
        if let Some(f) = rl.wall {
            if rl.normalized {
                w.alpha.get_or_insert(f.stiffness);
                w.beta.get_or_insert(f.damping);
            } else if !self.normalized() {
                w.wall_stiffness.get_or_insert(f.stiffness);
                w.wall_damping.get_or_insert(f.damping);
            }
        }
        w
    }
}

/// The wall of a resolved loop in the loop's units: K in N/m and B in Ns/m, or (α, β) for a
/// normalized loop. --alpha/--beta on a physical mass-spring-damper plant convert by
/// K = α·m/T², B = β·m/T (Table I).
pub fn resolve_loop_wall(rl: &ResolvedLoop, fam: &AffineFamily, wall: &WallArgs) -> Result<Wall> {
    let wall = &wall.over_file(rl);
    if rl.normalized || wall.normalized() {
        let (Some(alpha), Some(beta)) = (wall.alpha, wall.beta) else {
            bail!("a normalized wall needs both --alpha and --beta");
        };
        hapstab::Normalized::new(alpha, beta, 0.0, 0.0, 0)?;
        if rl.normalized {
            let w = Wall {
                stiffness: alpha,
                damping: beta,
            };
            check_wall_range(fam, w, true)?;
            return Ok(w);
        }
        if !matches!(rl.lp.plant.model, LibPlantModel::MassSpringDamper(_)) {
            bail!(
                "--alpha/--beta are normalized by the paper's mass m; give --wall-stiffness/--wall-damping for this plant"
            );
        }
        let (stiffness, damping) = fam.to_physical(alpha, beta);
        let w = Wall { stiffness, damping };
        check_wall_range(fam, w, false)?;
        return Ok(w);
    }
    let w = Wall {
        stiffness: wall.wall_stiffness.unwrap_or(DEFAULT_WALL.stiffness),
        damping: wall.wall_damping.unwrap_or(DEFAULT_WALL.damping),
    };
    if !w.stiffness.is_finite() {
        bail!(
            "wall stiffness K must be a finite number (got {})",
            w.stiffness
        );
    }
    if !w.damping.is_finite() {
        bail!("wall damping B must be a finite number (got {})", w.damping);
    }
    check_wall_range(fam, w, false)?;
    Ok(w)
}

/// Refuses a wall beyond the representable range ([`hapstab::model::check_wall_range`]),
/// naming its flag: --wall-stiffness/--wall-damping, or --alpha/--beta for a normalized loop.
fn check_wall_range(fam: &AffineFamily, w: Wall, normalized: bool) -> Result<()> {
    let units = fam.to_units(w.stiffness, w.damping);
    hapstab::model::check_wall_range(fam, w, units, normalized).map_err(|e| {
        match e.param().and_then(Param::flag) {
            Some(flag) => anyhow::anyhow!("{flag}: {e}"),
            None => e.into(),
        }
    })
}

/// The loop in words, one line per part (for the text output of the commands).
pub fn describe_loop(lp: &Loop) -> Vec<String> {
    let mut out = vec![format!("plant     {}", plant_text(&lp.plant.model))];
    if lp.plant.force_lag > 0.0 {
        out.push(format!(
            "lag       actuator 1/(τs + 1), τ = {} ms",
            sig(lp.plant.force_lag * 1e3, 6)
        ));
    }
    out.push(format!(
        "sampling  T = {} ms, delay {}",
        sig(lp.period * 1e3, 6),
        delay_text(lp)
    ));
    out.push(format!("velocity  {}", lp.velocity));
    out
}

fn delay_text(lp: &Loop) -> String {
    let ms = sig(lp.delay_time() * 1e3, 6);
    if lp.delay.fraction == 0.0 {
        format!("d = {} (t_d = {ms} ms)", lp.delay.samples)
    } else {
        format!(
            "t_d = {ms} ms (d = {}, λ = {})",
            lp.delay.samples,
            sig(lp.delay.fraction, 6)
        )
    }
}

fn plant_text(m: &LibPlantModel) -> String {
    match m {
        LibPlantModel::MassSpringDamper(e) => format!(
            "1/(m s² + b s + k), m = {} kg, b = {} Ns/m, k = {} N/m",
            sig(e.mass, 6),
            sig(e.damping, 6),
            sig(e.stiffness, 6)
        ),
        LibPlantModel::TwoMass(t) => format!(
            "two-mass device: motor J = {} kg, b_m = {} Ns/m; handle m_h = {} kg; transmission k_t = {} N/m, b_t = {} Ns/m; arm m_H = {} kg, b_H = {} Ns/m, k_H = {} N/m",
            sig(t.motor_mass, 6),
            sig(t.motor_damping, 6),
            sig(t.handle_mass, 6),
            sig(t.transmission_stiffness, 6),
            sig(t.transmission_damping, 6),
            sig(t.arm.mass, 6),
            sig(t.arm.damping, 6),
            sig(t.arm.stiffness, 6)
        ),
        LibPlantModel::TransferFunction { num, den } => format!(
            "P(s) = ({}) / ({}) m/N",
            poly_text(num, "s", 6),
            poly_text(den, "s", 6)
        ),
    }
}

pub use hapstab::loop_spec::LoopInput;

impl ResolvedLoop {
    /// The inputs of a command on this loop and an optional wall in the loop's units, echoed
    /// in its JSON under `input` (the form `--loop` reads back).
    pub fn input(&self, wall: Option<Wall>) -> LoopInput {
        LoopInput::new(&self.lp, self.normalized, wall)
    }
}
