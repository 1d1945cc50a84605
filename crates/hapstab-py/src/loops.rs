//! Loop description objects: the plants (the paper's mass-spring-damper, the two-mass device,
//! a transfer function) and the loop (plant, sampling period, delay in seconds, velocity
//! estimator, actuator lag), each validated by the library when constructed.

use hapstab::Param;
use hapstab::loop_spec::{LoopSpec, VelocitySpec};
use hapstab::model::{Delay, Loop, Plant, PlantModel, TwoMass};
use hapstab::params::{Arm, Device, Effective};
use hapstab::{PlantParams, System};
use numpy::{AllowTypeChange, PyArray1, PyArrayLike1};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;

use crate::errors::{Context, bad, finite};
use crate::text::{fmt_list, num};

/// The paper's plant 1/(m s² + b s + k) from force (N) to position (m) (eq. 1): the
/// effective mass m in kg (> 0), damping b in Ns/m (>= 0) and stiffness k in N/m (>= 0).
#[pyclass(frozen, module = "hapstab", name = "MassSpringDamper", eq)]
#[derive(Clone, PartialEq)]
pub struct PyMassSpringDamper {
    pub inner: Effective,
    /// The arm that m, b and k include, when built from a device and an arm: its damping is
    /// the operator's, not the device's own (passivity counts only the device's).
    pub operator: Option<Arm>,
}

#[pymethods]
impl PyMassSpringDamper {
    #[new]
    #[pyo3(signature = (mass, damping = 0.0, stiffness = 0.0))]
    fn new(mass: f64, damping: f64, stiffness: f64) -> PyResult<Self> {
        Ok(Self {
            inner: Effective::new(mass, damping, stiffness).py()?,
            operator: None,
        })
    }

    /// The device held by the arm, combined by eq. (1): m = m_L + m_H, b = b_L + b_H,
    /// k = k_H. Defaults: a PHANToM-like device (m_L = 0.1 kg, b_L = 1.5 Ns/m) held by a
    /// typical arm (m_H = 1 kg, b_H = 6 Ns/m, k_H = 350 N/m); arm_mass = arm_damping =
    /// arm_stiffness = 0 is the ungrabbed device.
    #[staticmethod]
    #[pyo3(signature = (*, device_mass = 0.1, device_damping = 1.5, arm_mass = 1.0,
                        arm_damping = 6.0, arm_stiffness = 350.0))]
    fn from_device_and_arm(
        device_mass: f64,
        device_damping: f64,
        arm_mass: f64,
        arm_damping: f64,
        arm_stiffness: f64,
    ) -> PyResult<Self> {
        let device = Device {
            mass: device_mass,
            damping: device_damping,
        };
        let arm = Arm {
            mass: arm_mass,
            damping: arm_damping,
            stiffness: arm_stiffness,
        };
        let inner = Effective::combine(device, arm).py_with(&[
            (Param::Mass, "device_mass + arm_mass"),
            (Param::Damping, "device_damping + arm_damping"),
            (Param::Stiffness, "arm_stiffness"),
        ])?;
        let operator = (arm != Arm::NONE).then_some(arm);
        Ok(Self { inner, operator })
    }

    /// The device's own damping b_L = b − b_H in Ns/m when built from a device and an arm
    /// (what passivity compares with); b itself otherwise.
    #[getter]
    fn device_damping(&self) -> f64 {
        (self.inner.damping - self.operator.map_or(0.0, |a| a.damping)).max(0.0)
    }

    /// Mass m in kg.
    #[getter]
    fn mass(&self) -> f64 {
        self.inner.mass
    }

    /// Damping b in Ns/m.
    #[getter]
    fn damping(&self) -> f64 {
        self.inner.damping
    }

    /// Stiffness k in N/m.
    #[getter]
    fn stiffness(&self) -> f64 {
        self.inner.stiffness
    }

    fn __repr__(&self) -> String {
        let e = &self.inner;
        format!(
            "MassSpringDamper(mass={}, damping={}, stiffness={})",
            num(e.mass),
            num(e.damping),
            num(e.stiffness)
        )
    }
}

/// A two-mass device: the motor-side mass J in kg (> 0, where the actuator pushes and the
/// encoder measures, with damping b_m in Ns/m) coupled to the handle (mass m_h in kg) by a
/// compliant transmission (stiffness k_t in N/m > 0, damping b_t in Ns/m); the arm (m_H kg,
/// b_H Ns/m, k_H N/m; all zero: the ungrabbed device) holds the handle.
#[pyclass(frozen, module = "hapstab", name = "TwoMass", eq)]
#[derive(Clone, PartialEq)]
pub struct PyTwoMass {
    pub inner: TwoMass,
}

#[pymethods]
impl PyTwoMass {
    #[new]
    #[pyo3(signature = (motor_mass, transmission_stiffness, *, motor_damping = 0.0,
                        handle_mass = 0.0, transmission_damping = 0.0, arm_mass = 1.0,
                        arm_damping = 6.0, arm_stiffness = 350.0))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        motor_mass: f64,
        transmission_stiffness: f64,
        motor_damping: f64,
        handle_mass: f64,
        transmission_damping: f64,
        arm_mass: f64,
        arm_damping: f64,
        arm_stiffness: f64,
    ) -> PyResult<Self> {
        let inner = TwoMass {
            motor_mass,
            motor_damping,
            handle_mass,
            transmission_stiffness,
            transmission_damping,
            arm: Arm {
                mass: arm_mass,
                damping: arm_damping,
                stiffness: arm_stiffness,
            },
        };
        Plant::new(PlantModel::TwoMass(inner), 0.0).py()?;
        Ok(Self { inner })
    }

    /// Motor-side mass J in kg.
    #[getter]
    fn motor_mass(&self) -> f64 {
        self.inner.motor_mass
    }
    /// Motor-side damping b_m in Ns/m.
    #[getter]
    fn motor_damping(&self) -> f64 {
        self.inner.motor_damping
    }
    /// Handle mass m_h in kg.
    #[getter]
    fn handle_mass(&self) -> f64 {
        self.inner.handle_mass
    }
    /// Transmission stiffness k_t in N/m.
    #[getter]
    fn transmission_stiffness(&self) -> f64 {
        self.inner.transmission_stiffness
    }
    /// Transmission damping b_t in Ns/m.
    #[getter]
    fn transmission_damping(&self) -> f64 {
        self.inner.transmission_damping
    }
    /// Arm mass m_H in kg.
    #[getter]
    fn arm_mass(&self) -> f64 {
        self.inner.arm.mass
    }
    /// Arm damping b_H in Ns/m.
    #[getter]
    fn arm_damping(&self) -> f64 {
        self.inner.arm.damping
    }
    /// Arm stiffness k_H in N/m.
    #[getter]
    fn arm_stiffness(&self) -> f64 {
        self.inner.arm.stiffness
    }

    fn __repr__(&self) -> String {
        let t = &self.inner;
        format!(
            "TwoMass(motor_mass={}, transmission_stiffness={}, motor_damping={}, handle_mass={}, transmission_damping={}, arm_mass={}, arm_damping={}, arm_stiffness={})",
            num(t.motor_mass),
            num(t.transmission_stiffness),
            num(t.motor_damping),
            num(t.handle_mass),
            num(t.transmission_damping),
            num(t.arm.mass),
            num(t.arm.damping),
            num(t.arm.stiffness)
        )
    }
}

/// A strictly proper plant P(s) = num(s)/den(s) from force (N) to position (m),
/// coefficients in SI units, highest power of s first (as python-control's and MATLAB's
/// `tf`); order <= 12.
#[pyclass(frozen, module = "hapstab", name = "TransferFunction", eq)]
#[derive(Clone, PartialEq)]
pub struct PyTransferFunction {
    pub num: Vec<f64>,
    pub den: Vec<f64>,
}

#[pymethods]
impl PyTransferFunction {
    #[new]
    fn new(
        num: PyArrayLike1<'_, f64, AllowTypeChange>,
        den: PyArrayLike1<'_, f64, AllowTypeChange>,
    ) -> PyResult<Self> {
        let num = num.as_array().to_vec();
        let den = den.as_array().to_vec();
        let model = PlantModel::TransferFunction {
            num: num.clone(),
            den: den.clone(),
        };
        Plant::new(model, 0.0).py()?;
        Ok(Self { num, den })
    }

    /// Numerator coefficients, highest power of s first (float64 array).
    #[getter]
    fn num<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.num)
    }

    /// Denominator coefficients, highest power of s first (float64 array).
    #[getter]
    fn den<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.den)
    }

    fn __repr__(&self) -> String {
        format!(
            "TransferFunction(num={}, den={})",
            fmt_list(&self.num),
            fmt_list(&self.den)
        )
    }
}

/// The plant model of a Python plant object and the arm a mass-spring-damper includes.
fn plant_model(plant: &Bound<'_, PyAny>) -> PyResult<(PlantModel, Option<Arm>)> {
    if let Ok(p) = plant.cast::<PyMassSpringDamper>() {
        let p = p.get();
        return Ok((PlantModel::MassSpringDamper(p.inner), p.operator));
    }
    if let Ok(p) = plant.cast::<PyTwoMass>() {
        return Ok((PlantModel::TwoMass(p.get().inner), None));
    }
    if let Ok(p) = plant.cast::<PyTransferFunction>() {
        let p = p.get();
        let model = PlantModel::TransferFunction {
            num: p.num.clone(),
            den: p.den.clone(),
        };
        return Ok((model, None));
    }
    if let Some(model) = control_plant(plant)? {
        return Ok((model, None));
    }
    Err(PyTypeError::new_err(format!(
        "plant: expected MassSpringDamper, TwoMass, TransferFunction or a python-control \
         TransferFunction/StateSpace (got {})",
        plant.get_type().name()?
    )))
}

/// A python-control system as the plant's transfer function: a `TransferFunction`'s num and
/// den (highest power first, as `control.tf` takes them), a `StateSpace` through
/// `control.ss2tf`; continuous time (dt = 0) and one input, one output. None for any other
/// object.
fn control_plant(plant: &Bound<'_, PyAny>) -> PyResult<Option<PlantModel>> {
    let module = plant.get_type().module()?.to_string();
    if !(module == "control" || module.starts_with("control.")) {
        return Ok(None);
    }
    let dt = plant.getattr("dt")?;
    let continuous = dt.is_none() || dt.extract::<f64>().is_ok_and(|t| t == 0.0);
    if !continuous {
        return Err(bad(
            "plant",
            format!(
                "a python-control plant must be continuous-time (dt = 0), got dt = {}                  (hapstab samples the plant itself)",
                dt.str()?
            ),
        ));
    }
    let (ni, no): (usize, usize) = (
        plant.getattr("ninputs")?.extract()?,
        plant.getattr("noutputs")?.extract()?,
    );
    if (ni, no) != (1, 1) {
        return Err(bad(
            "plant",
            format!("a python-control plant must have one input and one output (got {ni} × {no})"),
        ));
    }
    let tf = if plant.hasattr("A")? {
        plant
            .py()
            .import("control")?
            .getattr("ss2tf")?
            .call1((plant,))?
    } else {
        plant.clone()
    };
    let coeffs = |name: &str| -> PyResult<Vec<f64>> {
        tf.getattr(name)?
            .get_item(0)?
            .get_item(0)?
            .extract::<Vec<f64>>()
    };
    let (num, den) = (coeffs("num")?, coeffs("den")?);
    Ok(Some(PlantModel::TransferFunction { num, den }))
}

/// The Python object of a plant model.
fn plant_object(py: Python<'_>, plant: &Plant) -> PyResult<Py<PyAny>> {
    Ok(match &plant.model {
        PlantModel::MassSpringDamper(e) => {
            let p = PyMassSpringDamper {
                inner: *e,
                operator: plant.operator,
            };
            Py::new(py, p)?.into_any()
        }
        PlantModel::TwoMass(t) => Py::new(py, PyTwoMass { inner: *t })?.into_any(),
        PlantModel::TransferFunction { num, den } => Py::new(
            py,
            PyTransferFunction {
                num: num.clone(),
                den: den.clone(),
            },
        )?
        .into_any(),
    })
}

/// The loop of Fig. 3, generalized: plant, sampling period, delay, velocity estimator.
///
/// plant: MassSpringDamper, TwoMass or TransferFunction (force in N to position in m), or a
/// continuous-time python-control TransferFunction or StateSpace (one input, one output).
/// period: sampling period T in s. delay: t_d = (d + λ)T in s, a fraction λ of a sample
/// discretized exactly (modified z-transform); or delay_samples: whole samples d.
/// velocity: the wall damper's velocity estimator, as the command line's --velocity text:
///   "backward"             v_k = (y_k − y_{k−1})/T (the paper's)
///   "lowpass:FC"           v_k = a·v_{k−1} + (1 − a)(y_k − y_{k−1})/T, a = exp(−2π·f_c·T),
///                          f_c = FC in Hz
///   "butterworth:N:FC"     the backward difference through a digital Butterworth low-pass of
///                          order N, cut-off FC Hz (scipy's butter(N, FC, fs=1/T))
///   "bessel:N:FC"          the same through a digital Bessel low-pass (scipy's
///                          bessel(N, FC, fs=1/T), phase-normalized)
///   "critically-damped:N:FC"  the same through N equal real poles, −3 dB at FC Hz (N = 1–8
///                          for all three; bilinear with pre-warping)
///   "average:N"            v_k = (y_k − y_{k−N})/(N·T)
///   "iir:b0,b1,…/a0,a1,…"  v = (b0 + b1 z⁻¹ + …)/(a0 + a1 z⁻¹ + …)·y in m/s
/// force_lag: actuator time constant τ in s of 1/(τs + 1) between commanded and applied
/// force (0: none).
#[pyclass(frozen, module = "hapstab", name = "Loop")]
#[derive(Clone)]
pub struct PyLoop {
    pub lp: Loop,
    /// Built by `Loop.normalized`: m = 1 kg and T = 1 s, so K is α and B is β (Table I).
    pub normalized: bool,
}

#[pymethods]
impl PyLoop {
    #[new]
    #[pyo3(signature = (plant, *, period = 1e-3, delay = None, delay_samples = None,
                        velocity = "backward", force_lag = 0.0))]
    fn new(
        plant: &Bound<'_, PyAny>,
        period: f64,
        delay: Option<f64>,
        delay_samples: Option<usize>,
        velocity: &str,
        force_lag: f64,
    ) -> PyResult<Self> {
        let (model, operator) = plant_model(plant)?;
        hapstab::params::Sampling::new(period, 0).py()?;
        let (delay, delay_time) = match (delay, delay_samples) {
            (Some(_), Some(_)) => {
                return Err(bad(
                    "delay, delay_samples",
                    "give the delay either in seconds (delay) or in whole samples (delay_samples)",
                ));
            }
            (None, Some(d)) => (
                Some(Delay::samples(d).py_with(&[(Param::Delay, "delay_samples")])?),
                None,
            ),
            (t, None) => (None, t),
        };
        // the loop file's form: one set of defaults and checks for every front end
        let spec = LoopSpec {
            delay,
            delay_time,
            ..LoopSpec::of_plant(
                model,
                force_lag,
                operator,
                period,
                VelocitySpec::Text(velocity.into()),
            )
        };
        let lp = spec.resolve().py_with(&[
            (Param::Mass, "plant.mass"),
            (Param::Damping, "plant.damping"),
            (Param::Stiffness, "plant.stiffness"),
            (Param::MotorMass, "plant.motor_mass"),
            (Param::HandleMass, "plant.handle_mass"),
            (Param::ArmMass, "plant.arm_mass"),
            (
                Param::HandleAndArmMass,
                "plant.handle_mass + plant.arm_mass",
            ),
        ])?;
        Ok(Self {
            lp,
            normalized: false,
        })
    }

    /// The paper's loop in physical units: the device held by the arm (eq. 1, see
    /// MassSpringDamper.from_device_and_arm for the defaults), backward-difference velocity,
    /// sampling period T in s and delay t_d in s.
    #[staticmethod]
    #[pyo3(signature = (*, device_mass = 0.1, device_damping = 1.5, arm_mass = 1.0,
                        arm_damping = 6.0, arm_stiffness = 350.0, period = 1e-3, delay = 0.0))]
    #[allow(clippy::too_many_arguments)]
    fn paper(
        py: Python<'_>,
        device_mass: f64,
        device_damping: f64,
        arm_mass: f64,
        arm_damping: f64,
        arm_stiffness: f64,
        period: f64,
        delay: f64,
    ) -> PyResult<Self> {
        let plant = PyMassSpringDamper::from_device_and_arm(
            device_mass,
            device_damping,
            arm_mass,
            arm_damping,
            arm_stiffness,
        )?;
        let plant = Bound::new(py, plant)?;
        Self::new(plant.as_any(), period, Some(delay), None, "backward", 0.0)
    }

    /// The paper's loop in normalized units (Table I): m = 1 kg, T = 1 s, plant
    /// 1/(s² + δs + γ) with γ = kT²/m >= 0 and δ = bT/m >= 0, d whole samples of delay. Its
    /// wall is K = α = K_phys T²/m and B = β = B_phys T/m.
    #[staticmethod]
    #[pyo3(signature = (gamma = 0.0, delta = 0.0, d = 0))]
    fn normalized(gamma: f64, delta: f64, d: usize) -> PyResult<Self> {
        let pp = PlantParams::new(gamma, delta).py()?;
        Ok(Self {
            lp: Loop::normalized(pp, d).py_with(&[(Param::Delay, "d")])?,
            normalized: true,
        })
    }

    /// A loop saved as JSON (by Loop.save, by the command line's `--json` under "input", or
    /// by the explorer): the report's "input" object, its "loop" object or a whole report.
    /// The file's wall, if any, is Loop.load_wall(path).
    #[staticmethod]
    fn load(path: std::path::PathBuf) -> PyResult<Self> {
        let f = hapstab::loop_spec::load(&path).py_as("path")?;
        Ok(Self {
            lp: f.lp,
            normalized: f.normalized,
        })
    }

    /// The wall (K, B) a loop file names (α, β for a normalized loop), or None.
    #[staticmethod]
    fn load_wall(path: std::path::PathBuf) -> PyResult<Option<(f64, f64)>> {
        let f = hapstab::loop_spec::load(&path).py_as("path")?;
        Ok(f.wall.map(|w| (w.stiffness, w.damping)))
    }

    /// The loop from the text of a loop file (see Loop.load).
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        let f = hapstab::loop_spec::parse(text).py_as("text")?;
        Ok(Self {
            lp: f.lp,
            normalized: f.normalized,
        })
    }

    /// The loop (and a wall K in N/m, B in Ns/m, or α, β for a normalized loop) as the JSON
    /// the command line echoes under "input"; `hapstab check --loop FILE` reads it back.
    #[pyo3(signature = (wall_stiffness = None, wall_damping = None))]
    fn to_json(&self, wall_stiffness: Option<f64>, wall_damping: Option<f64>) -> PyResult<String> {
        let wall = match (wall_stiffness, wall_damping) {
            (None, None) => None,
            (Some(k), Some(b)) => Some(hapstab::Wall {
                stiffness: finite("wall_stiffness", k)?,
                damping: finite("wall_damping", b)?,
            }),
            (None, Some(_)) => return Err(bad("wall_stiffness", "give it with wall_damping")),
            (Some(_), None) => return Err(bad("wall_damping", "give it with wall_stiffness")),
        };
        Ok(hapstab::loop_spec::LoopInput::new(&self.lp, self.normalized, wall).to_json())
    }

    /// Pickling (multiprocessing, joblib, dask): the loop's JSON, read back by Loop.from_json to
    /// the same loop bit for bit.
    fn __reduce__(&self, py: Python<'_>) -> PyResult<(Py<PyAny>, (String,))> {
        let f = py.import("hapstab")?.getattr("_loop_from_json")?;
        Ok((f.unbind(), (self.to_json(None, None)?,)))
    }

    /// Writes Loop.to_json(wall_stiffness, wall_damping) to `path`.
    #[pyo3(signature = (path, wall_stiffness = None, wall_damping = None))]
    fn save(
        &self,
        path: std::path::PathBuf,
        wall_stiffness: Option<f64>,
        wall_damping: Option<f64>,
    ) -> PyResult<()> {
        let text = self.to_json(wall_stiffness, wall_damping)?;
        std::fs::write(&path, text + "\n").map_err(|e| {
            pyo3::exceptions::PyOSError::new_err(format!(
                "path: cannot write '{}': {e}",
                path.display()
            ))
        })
    }

    /// The sampled open loop of a wall (K in N/m, B in Ns/m; alpha, beta on a normalized
    /// loop) as a python-control discrete TransferFunction with dt = T:
    /// L(z) = (K·PK(z) + B·PB(z))/P0(z), so that control.feedback(L, 1) has the closed loop's
    /// poles, the roots of p(z) (eq. 9). Needs python-control.
    #[pyo3(signature = (wall_stiffness = None, wall_damping = None, *, alpha = None, beta = None))]
    fn to_control(
        &self,
        py: Python<'_>,
        wall_stiffness: Option<f64>,
        wall_damping: Option<f64>,
        alpha: Option<f64>,
        beta: Option<f64>,
    ) -> PyResult<Py<PyAny>> {
        let wall = crate::wall::WallArgs {
            stiffness: wall_stiffness,
            damping: wall_damping,
            alpha,
            beta,
        };
        let (num, den) = crate::discretize::open_loop(self, &wall)?;
        let tf = py.import("control")?.getattr("tf")?;
        Ok(tf.call1((num, den, self.lp.period))?.unbind())
    }

    /// The plant object.
    #[getter]
    fn plant(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        plant_object(py, &self.lp.plant)
    }

    /// Sampling period T in s.
    #[getter]
    fn period(&self) -> f64 {
        self.lp.period
    }

    /// Delay t_d in s.
    #[getter]
    fn delay(&self) -> f64 {
        self.lp.delay_time()
    }

    /// Delay t_d/T in samples, d + λ (not necessarily whole).
    #[getter]
    fn delay_samples(&self) -> f64 {
        self.lp.delay.in_samples()
    }

    /// The velocity estimator as its spec text ("backward", "lowpass:FC", …).
    #[getter]
    fn velocity(&self) -> String {
        self.lp.velocity.to_string()
    }

    /// Actuator time constant τ in s (0: no lag).
    #[getter]
    fn force_lag(&self) -> f64 {
        self.lp.plant.force_lag
    }

    /// True for a loop built by Loop.normalized (m = 1 kg, T = 1 s: K is α, B is β).
    #[getter]
    fn is_normalized(&self) -> bool {
        self.normalized
    }

    /// (γ, δ, d) of Table I for the paper's loop (mass-spring-damper plant, backward
    /// difference, whole-sample delay, no lag), else None.
    #[getter]
    fn paper_view(&self) -> Option<(f64, f64, usize)> {
        self.lp
            .paper_view()
            .map(|pp| (pp.gamma, pp.delta, self.lp.delay.samples))
    }

    /// The mass m in kg that normalizes the wall (α = KT²/m, β = BT/m, Table I): m of eq. (1),
    /// a two-mass device's total mass, 1/(ω²|P(jω)|) at ω = 1/T for a transfer function.
    #[getter]
    fn reference_mass(&self) -> f64 {
        self.lp.plant.reference_mass(self.lp.period)
    }

    /// (N/m per unit α, Ns/m per unit β) = (m/T², m/T): the wall's normalized units.
    #[getter]
    fn wall_scale(&self) -> PyResult<(f64, f64)> {
        let s = self.system()?.family().scale;
        Ok((s.stiffness, s.damping))
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        if self.normalized
            && let Some((g, d, n)) = self.paper_view()
        {
            return Ok(format!(
                "Loop.normalized(gamma={}, delta={}, d={n})",
                num(g),
                num(d)
            ));
        }
        let plant = self.plant(py)?.bind(py).repr()?.to_string();
        Ok(format!(
            "Loop({plant}, period={}, delay={}, velocity='{}', force_lag={})",
            num(self.lp.period),
            num(self.lp.delay_time()),
            self.lp.velocity,
            num(self.lp.plant.force_lag)
        ))
    }
}

impl PyLoop {
    /// The loop's analysis object: discretized and closed once ([`System`]).
    pub fn system(&self) -> PyResult<System> {
        System::of(&self.lp).py()
    }
}
