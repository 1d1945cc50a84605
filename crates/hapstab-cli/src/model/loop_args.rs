//! The user's loop flags ([`LoopArgs`]): the paper's plant flags plus a transfer-function
//! or two-mass plant, an actuator lag and a velocity estimator, resolved to a
//! [`ResolvedLoop`].

use anyhow::{Result, bail};
use clap::Args;
use hapstab::Param;
use hapstab::loop_spec::{LoopSpec, VelocitySpec};
use hapstab::model::{Delay, Loop, Plant, PlantModel as LibPlantModel, TwoMass, VelocityEstimator};
use hapstab::spec::excerpt_list;

use super::flags::{TF_CONFLICTS, TWO_MASS_CONFLICTS};
use super::{DEFAULT_PERIOD, PlantArgs, ResolvedLoop, delay_samples};

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
        let force_lag = self.force_lag.unwrap_or(0.0);
        // the plant's own errors name the flag the user typed
        Plant::new(model.clone(), force_lag).map_err(|e| tf_context(self, e))?;
        let operator = match base {
            Some(p) => p.operator,
            None => self.plant.operator(),
        }
        .filter(|_| matches!(model, LibPlantModel::MassSpringDamper(_)));
        // the loop file's form: one set of defaults and checks for every front end
        let velocity = self.velocity.clone().unwrap_or(VelocityEstimator::Backward);
        let spec = LoopSpec {
            delay: Some(self.delay(period)?),
            ..LoopSpec::of_plant(
                model,
                force_lag,
                operator,
                period,
                VelocitySpec::Estimator(velocity),
            )
        };
        Ok(ResolvedLoop {
            lp: spec.resolve().map_err(|e| self.with_flag(e))?,
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
