//! The exact discrete-time equivalent of any loop's plant behind a zero-order hold with a
//! fractional delay (Section III, eq. 2–6 and 10, generalized).
//!
//! # Continuous plant
//!
//! Every [`Plant`] becomes a state-space model ẋ = A x + B u, y = C x in *normalized time*
//! τ = t/T (one unit per sample) with the force in *wall units* u = F/k_u, k_u = m/T²
//! (Table I with m the plant's [`Plant::reference_mass`]). For the paper's plant this is
//! A = [[0, 1], [−γ, −δ]], B = [0, 1]ᵀ, C = [1, 0] in the state (x, T·ẋ), so the wall's
//! (K/k_u, B/(k_u T)) are the paper's (α, β).
//!
//! # Zero-order hold with a fractional delay (modified z-transform)
//!
//! A force computed at sample j is applied from jT + t_d to (j + 1)T + t_d with
//! t_d = (d + λ)T. Over one sample the input is F_{k−d−1} on [0, λ) and F_{k−d} on [λ, 1), so
//!
//! ```text
//! x_{k+1} = Φ x_k + Γ0 u_{k−d} + Γ1 u_{k−d−1},
//! Φ = e^A,  Γ0 = Ψ(1 − λ) B,  Γ1 = e^{A(1−λ)} Ψ(λ) B,  Ψ(h) = ∫₀ʰ e^{As} ds,
//! ```
//!
//! exact for every λ ∈ [0, 1), continuous as λ → 0 (Γ1 → 0) and λ → 1 (Γ0 → 0, one more
//! sample of delay). No Padé or Thiran approximation is involved.
//!
//! # Accuracy
//!
//! Ψ(h) is summed as a Taylor series at h/2^k with ‖A‖h/2^k ≤ 1/2 and doubled exactly:
//! Ψ(2h) = (2I + E(h))Ψ(h), E(2h) = E(h)(2I + E(h)) with E = e^{Ah} − I = AΨ(h). Carrying
//! E = Φ − I instead of Φ keeps the information that fast sampling puts into 1 − Φ (every
//! eigenvalue of Φ near z = 1): the characteristic polynomials are formed in the shifted
//! variable w = z − 1 from E, where they do not cancel, and only then expanded in z. The same
//! doubling is valid for integrating (A singular), undamped (imaginary eigenvalues) and stiff
//! (‖A‖ ≫ 1, e.g. a fast actuator lag) plants; no step divides by an eigenvalue.

use serde::Serialize;

use crate::error::{Error, Result};
pub use crate::matrix_exp::exp_and_integral;
use crate::model::{Delay, Loop, Plant, PlantModel, VelocityEstimator, strip_leading_zeros};
use crate::param::Param;
use crate::params::Effective;
use crate::poly::{self, Mat};

/// A continuous state-space model in normalized time and wall units (see the module doc).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StateSpace {
    /// State matrix A (n × n).
    pub a: Mat,
    /// Input vector B (n).
    pub b: Vec<f64>,
    /// Output row C (n).
    pub c: Vec<f64>,
}

/// The wall's unit conversion: K = a·stiffness, B = b·damping, where (a, b) are the
/// coordinates the affine family is computed in (for the paper's plant, (α, β) of Table I).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WallScale {
    /// k_u = m/T² in N/m per unit of a.
    pub stiffness: f64,
    /// k_u·T = m/T in Ns/m per unit of b.
    pub damping: f64,
}

impl WallScale {
    /// The identity scale (normalized loops: K = α, B = β).
    pub const UNIT: WallScale = WallScale {
        stiffness: 1.0,
        damping: 1.0,
    };
}

fn add_identity(e: &Mat, c: f64) -> Mat {
    let mut m = e.clone();
    for (i, row) in m.iter_mut().enumerate() {
        row[i] += c;
    }
    m
}

impl StateSpace {
    /// The plant of a loop in normalized time and wall units, with the actuator lag.
    pub fn of_plant(plant: &Plant, period: f64) -> Result<Self> {
        let base = Self::mechanical(plant, period)?;
        Ok(if plant.force_lag > 0.0 {
            base.with_lag(period / plant.force_lag)
        } else {
            base
        })
    }

    /// The plant without its actuator lag: the mechanics from force to measured position.
    fn mechanical(plant: &Plant, period: f64) -> Result<Self> {
        let m_ref = plant.reference_mass(period);
        Ok(match &plant.model {
            PlantModel::MassSpringDamper(e) => mass_spring_damper(e, period),
            PlantModel::TwoMass(t) => two_mass(t, period, m_ref),
            PlantModel::TransferFunction { num, den } => {
                transfer_function(num, den, period, m_ref)?
            }
        })
    }

    /// State dimension n.
    pub fn order(&self) -> usize {
        self.a.len()
    }

    /// Appends a first-order lag u_a' = r(u − u_a) in front of the input (r = T/τ).
    fn with_lag(self, r: f64) -> Self {
        let n = self.order();
        let mut a = vec![vec![0.0; n + 1]; n + 1];
        for ((row, src), bi) in a.iter_mut().zip(&self.a).zip(&self.b) {
            row[..n].copy_from_slice(src);
            row[n] = *bi;
        }
        a[n][n] = -r;
        let mut b = vec![0.0; n + 1];
        b[n] = r;
        let mut c = self.c;
        c.push(0.0);
        Self { a, b, c }
    }
}

/// The paper's plant in the state (x, T·ẋ): A = [[0, 1], [−γ, −δ]], B = [0, 1]ᵀ (eq. 1, 4).
fn mass_spring_damper(e: &Effective, period: f64) -> StateSpace {
    let gamma = e.stiffness * period * period / e.mass;
    let delta = e.damping * period / e.mass;
    StateSpace {
        a: vec![vec![0.0, 1.0], vec![-gamma, -delta]],
        b: vec![0.0, 1.0],
        c: vec![1.0, 0.0],
    }
}

/// The two-mass device in the state (x_m, T·v_m, x_h, T·v_h); the force acts on the motor
/// side, the encoder reads x_m, the arm holds the handle.
fn two_mass(t: &crate::model::TwoMass, period: f64, m_ref: f64) -> StateSpace {
    let (tt, t2) = (period, period * period);
    let j = t.motor_mass;
    let mh = t.handle_mass + t.arm.mass;
    let (kt, bt) = (t.transmission_stiffness * t2, t.transmission_damping * tt);
    let a = vec![
        vec![0.0, 1.0, 0.0, 0.0],
        vec![-kt / j, -(t.motor_damping * tt + bt) / j, kt / j, bt / j],
        vec![0.0, 0.0, 0.0, 1.0],
        vec![
            kt / mh,
            bt / mh,
            -(kt + t.arm.stiffness * t2) / mh,
            -(bt + t.arm.damping * tt) / mh,
        ],
    ];
    StateSpace {
        a,
        b: vec![0.0, m_ref / j, 0.0, 0.0],
        c: vec![1.0, 0.0, 0.0, 0.0],
    }
}

/// A strictly proper num(s)/den(s) in controllable canonical form after the substitution
/// s = σ/T and the force scale k_u = m_ref/T², balanced by powers of two.
fn transfer_function(num: &[f64], den: &[f64], period: f64, m_ref: f64) -> Result<StateSpace> {
    let den = strip_leading_zeros(den);
    let num = strip_leading_zeros(num);
    let n = den.len() - 1;
    if n == 0 || num.len() > n {
        return Err(Error::Invalid {
            param: Param::PlantTransferFunction,
            reason: "must be strictly proper".into(),
        });
    }
    // Ascending: den(s) = Σ a_k s^k; σ-form coefficients a_k T^{n−k} / a_n (monic).
    let lead = den[0];
    let k_u = m_ref / (period * period);
    let asc_den: Vec<f64> = den.iter().rev().copied().collect();
    let asc_num: Vec<f64> = num.iter().rev().copied().collect();
    let a_sig: Vec<f64> = (0..n)
        .map(|k| asc_den[k] * period.powi((n - k) as i32) / lead)
        .collect();
    let b_sig: Vec<f64> = (0..n)
        .map(|k| asc_num.get(k).copied().unwrap_or(0.0) * k_u * period.powi((n - k) as i32) / lead)
        .collect();
    let mut a = vec![vec![0.0; n]; n];
    for i in 0..n - 1 {
        a[i][i + 1] = 1.0;
    }
    for k in 0..n {
        a[n - 1][k] = -a_sig[k];
    }
    let mut b = vec![0.0; n];
    b[n - 1] = 1.0;
    Ok(balance(StateSpace { a, b, c: b_sig }))
}

/// Diagonal similarity D⁻¹AD by powers of two (Parlett–Reinsch) so that rows and columns
/// of A have comparable norms; exact in floating point, the transfer function is unchanged.
fn balance(mut ss: StateSpace) -> StateSpace {
    let n = ss.order();
    for _ in 0..100 {
        let mut done = true;
        for i in 0..n {
            let c: f64 = (0..n).filter(|&j| j != i).map(|j| ss.a[j][i].abs()).sum();
            let r: f64 = (0..n).filter(|&j| j != i).map(|j| ss.a[i][j].abs()).sum();
            if c == 0.0 || r == 0.0 {
                continue;
            }
            let mut f = 1.0;
            let (mut cc, mut rr) = (c, r);
            while cc < rr / 2.0 {
                cc *= 2.0;
                rr /= 2.0;
                f *= 2.0;
            }
            while cc > rr * 2.0 {
                cc /= 2.0;
                rr *= 2.0;
                f /= 2.0;
            }
            if (cc + rr) < 0.95 * (c + r) {
                done = false;
                // column i × f, row i ÷ f
                for j in 0..n {
                    ss.a[j][i] *= f;
                    ss.a[i][j] /= f;
                }
                ss.b[i] /= f;
                ss.c[i] *= f;
            }
        }
        if done {
            break;
        }
    }
    ss
}

/// The exact discrete loop: the plant's ZOH matrices with the fractional delay split, the
/// whole-sample delay, the velocity estimator and the wall's unit conversion. One set of
/// matrices shared by the analysis ([`crate::closed_loop`]) and the simulation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiscreteLoop {
    /// E = Φ − I, Φ = e^A the one-sample transition (n × n).
    pub phi_minus_identity: Mat,
    /// Γ0 = Ψ(1 − λ)B: input of the force delayed by d samples.
    pub gamma0: Vec<f64>,
    /// Γ1 = e^{A(1−λ)}Ψ(λ)B: input of the force delayed by d + 1 samples (zero when λ = 0).
    pub gamma1: Vec<f64>,
    /// Output row C.
    pub c: Vec<f64>,
    /// The delay t_d = (d + λ)T.
    pub delay: Delay,
    /// The velocity estimator as T·V(z) = num/den (ascending powers of z, den monic).
    pub velocity_num: Vec<f64>,
    /// Denominator of the velocity estimator (ascending, monic).
    pub velocity_den: Vec<f64>,
    /// The estimator's DC gain T·V(1) = num(1)/den(1), exact (0 for every differentiator;
    /// [`crate::model::VelocityEstimator::per_sample_dc_gain`]).
    pub velocity_dc: f64,
    /// Wall units.
    pub scale: WallScale,
    /// Sampling period T in s.
    pub period: f64,
    /// The plant's static stiffness 1/P(0) in wall units (a-coordinate): the zero-order hold
    /// keeps the DC gain exactly, so H(1) = P(0) and the z = 1 line is a = −this when the
    /// velocity estimate of a constant position is zero (Section V: α = −γ). None when
    /// P(0) = 0.
    pub dc_stiffness: Option<f64>,
}

/// A discrete transfer function z^{−delay}·num(z)/den(z) (ascending coefficients).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiscreteTf {
    /// Numerator, ascending powers of z.
    pub num: Vec<f64>,
    /// Denominator, ascending powers of z (monic).
    pub den: Vec<f64>,
    /// Pure delay in samples (the factor z^{−delay}).
    pub delay: usize,
}

impl DiscreteLoop {
    /// Discretizes a loop exactly (see the module doc).
    pub fn new(lp: &Loop) -> Result<Self> {
        let ss = StateSpace::of_plant(&lp.plant, lp.period)?;
        let (e1, gamma0, gamma1) = held_over_sample(&ss.a, &ss.b, lp.delay.fraction);
        let (velocity_num, velocity_den) = lp.velocity.per_sample_filter(lp.period);
        let scale = lp.wall_scale();
        let dl = Self {
            phi_minus_identity: e1,
            gamma0,
            gamma1,
            c: ss.c,
            delay: lp.delay,
            velocity_num,
            velocity_den,
            velocity_dc: lp.velocity.per_sample_dc_gain(lp.period),
            scale,
            period: lp.period,
            dc_stiffness: lp.plant.dc_stiffness().map(|k| k / scale.stiffness),
        };
        dl.check_finite()?;
        Ok(dl)
    }

    fn check_finite(&self) -> Result<()> {
        let all = self
            .phi_minus_identity
            .iter()
            .flatten()
            .chain(&self.gamma0)
            .chain(&self.gamma1)
            .chain(&self.c);
        for &x in all {
            if !x.is_finite() {
                return Err(Error::Numerical(
                    "the plant's discretization overflowed: its time constants are too far from the sampling period".into(),
                ));
            }
        }
        Ok(())
    }

    /// State dimension of the plant.
    pub fn order(&self) -> usize {
        self.c.len()
    }

    /// Φ = I + E.
    pub fn phi(&self) -> Mat {
        add_identity(&self.phi_minus_identity, 1.0)
    }

    /// The plant's denominator D(w) = det(wI − E) in the shifted variable w = z − 1.
    pub fn denominator_shifted(&self) -> Vec<f64> {
        poly::char_poly(&self.phi_minus_identity)
    }

    /// C adj(wI − E) g in the shifted variable w = z − 1, by det(wI − E + s·gC) − det(wI − E)
    /// = s·C adj(wI − E) g with s balancing s·gC against E.
    pub(crate) fn numerator_shifted_for(&self, g: &[f64], den: &[f64]) -> Vec<f64> {
        let gn: f64 = g.iter().map(|x| x.abs()).sum();
        let cn: f64 = self.c.iter().map(|x| x.abs()).sum();
        if gn == 0.0 || cn == 0.0 {
            return vec![0.0];
        }
        let s = poly::norm1(&self.phi_minus_identity).max(1.0) / (gn * cn);
        let entry = |i: usize, j: usize| self.phi_minus_identity[i][j] - s * g[i] * self.c[j];
        let mut num = self.char_poly_of(entry);
        num.truncate(den.len());
        for (f, d) in num.iter_mut().zip(den) {
            *f = (*f - d) / s;
        }
        num.pop(); // the monic leading terms cancel exactly
        num
    }

    /// det(wI − M) of the n × n matrix with entries `entry(i, j)` ([`poly::char_poly`]),
    /// formed in a stack buffer for the plants' usual orders.
    fn char_poly_of(&self, entry: impl Fn(usize, usize) -> f64) -> Vec<f64> {
        const SMALL: usize = poly::SMALL_ORDER;
        let n = self.order();
        if n > SMALL {
            let m: Mat = (0..n)
                .map(|i| (0..n).map(|j| entry(i, j)).collect())
                .collect();
            return poly::char_poly(&m);
        }
        let mut buf = [[0.0; SMALL]; SMALL];
        for (i, row) in buf.iter_mut().enumerate().take(n) {
            for (j, x) in row.iter_mut().enumerate().take(n) {
                *x = entry(i, j);
            }
        }
        let mut rows: [&[f64]; SMALL] = [&[]; SMALL];
        for (r, row) in rows.iter_mut().zip(&buf).take(n) {
            *r = &row[..n];
        }
        poly::char_poly(&rows[..n])
    }

    /// The plant's numerator N(w) in the shifted variable: C adj(wI − E)Γ0 when λ = 0,
    /// otherwise C adj(wI − E)((1 + w)Γ0 + Γ1), and the power k of the plant's pure delay
    /// (H(z) = N/(z^k D), k = d or d + 1).
    pub fn numerator_shifted(&self, den: &[f64]) -> (Vec<f64>, usize) {
        let d = self.delay.samples;
        if self.delay.fraction == 0.0 {
            return (self.numerator_shifted_for(&self.gamma0, den), d);
        }
        let sum: Vec<f64> = self
            .gamma0
            .iter()
            .zip(&self.gamma1)
            .map(|(a, b)| a + b)
            .collect();
        let n_sum = self.numerator_shifted_for(&sum, den);
        let n0 = self.numerator_shifted_for(&self.gamma0, den);
        (
            poly::add_scaled(&n_sum, 1.0, &poly::shift_up(&n0, 1)),
            d + 1,
        )
    }

    /// The plant H(z) = z^{−k} N(z)/D(z) in wall units (normalized: multiply the numerator by
    /// 1/k_u for metres per newton), ascending coefficients in z.
    pub fn plant_tf(&self) -> DiscreteTf {
        let den_w = self.denominator_shifted();
        let (num_w, k) = self.numerator_shifted(&den_w);
        DiscreteTf {
            num: poly::taylor_shift(&num_w, -1.0),
            den: poly::taylor_shift(&den_w, -1.0),
            delay: k,
        }
    }

    /// The plant H(z) in physical units, metres per newton (the `c2d` of MATLAB and
    /// python-control with the input delay).
    pub fn plant_tf_physical(&self) -> DiscreteTf {
        let mut tf = self.plant_tf();
        for x in tf.num.iter_mut() {
            *x /= self.scale.stiffness;
        }
        tf
    }

    /// The velocity estimator V(z) in physical units (m/s per m of position).
    pub fn velocity_tf_physical(&self) -> DiscreteTf {
        DiscreteTf {
            num: self.velocity_num.iter().map(|x| x / self.period).collect(),
            den: self.velocity_den.clone(),
            delay: 0,
        }
    }
}

/// Where a friction force acts: on one velocity state of the plant (the state holds T·v of
/// that point in normalized time), with its input gain in wall units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FrictionPoint {
    /// Index of the state T·v of the point where friction acts.
    pub state: usize,
    /// A force u (wall units) there adds gain·u to the derivative of that state.
    pub gain: f64,
}

/// What the time-domain simulation needs of a plant beyond the wall's input B and the
/// measured position C (same state, normalized time and wall units as [`StateSpace`]): where
/// the human operator pushes, the velocity of the measured point, and where friction acts.
/// Neither the human force nor friction passes through the actuator lag.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlantPorts {
    /// Input column of the human force: on the device mass (the paper's plant, eq. 1), on the
    /// handle (two-mass device), at the plant's input (transfer function).
    pub human: Vec<f64>,
    /// T·ẏ = velocity·x + direct_actuator·u_a + direct_human·u_h: the velocity of the
    /// measured point just after a sample instant (u_a the actuator input, u_h the human
    /// force then; the direct terms vanish unless a transfer function has relative degree 1).
    pub velocity: Vec<f64>,
    /// See `velocity`.
    pub direct_actuator: f64,
    /// See `velocity`.
    pub direct_human: f64,
    /// The friction point: the device mass of the paper's plant, the motor side of a two-mass
    /// device. None for a transfer function, which names no mass.
    pub friction: Option<FrictionPoint>,
}

fn padded(mut v: Vec<f64>, n: usize) -> Vec<f64> {
    v.resize(n, 0.0);
    v
}

fn unit(i: usize, n: usize) -> Vec<f64> {
    let mut v = vec![0.0; n];
    v[i] = 1.0;
    v
}

impl PlantPorts {
    /// The ports of a plant (see the type's doc).
    pub fn of_plant(plant: &Plant, period: f64) -> Result<Self> {
        let base = StateSpace::mechanical(plant, period)?;
        let full = StateSpace::of_plant(plant, period)?;
        let n = full.order();
        let lagged = n > base.order();
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        Ok(match &plant.model {
            PlantModel::MassSpringDamper(_) => Self::on_mass(padded(base.b.clone(), n), &base, n),
            PlantModel::TwoMass(t) => {
                let on_handle = plant.reference_mass(period) / (t.handle_mass + t.arm.mass);
                let human = (0..n)
                    .map(|i| if i == 3 { on_handle } else { 0.0 })
                    .collect();
                Self::on_mass(human, &base, n)
            }
            PlantModel::TransferFunction { .. } => {
                let velocity: Vec<f64> = (0..n)
                    .map(|j| (0..n).map(|i| full.c[i] * full.a[i][j]).sum())
                    .collect();
                let cb = dot(&base.c, &base.b);
                Self {
                    human: padded(base.b.clone(), n),
                    velocity,
                    direct_actuator: if lagged { 0.0 } else { cb },
                    direct_human: cb,
                    friction: None,
                }
            }
        })
    }

    /// Ports of a plant whose state 1 is T·v of the mass that the actuator drives (the
    /// paper's device, the motor side of a two-mass device): velocity and friction there.
    fn on_mass(human: Vec<f64>, base: &StateSpace, n: usize) -> Self {
        Self {
            human,
            velocity: unit(1, n),
            direct_actuator: 0.0,
            direct_human: 0.0,
            friction: Some(FrictionPoint {
                state: 1,
                gain: base.b[1],
            }),
        }
    }
}

/// The state at rest-like start: the measured point at `position` (m) moving at T·ẏ =
/// `velocity` (m per sample), with `held` the actuator input (wall units) held before t = 0.
/// The paper's plant: (x, T·ẋ). A two-mass device: motor and handle together at the
/// position, moving together. A transfer function: the state whose free motion starts with
/// y = position, T·ẏ = velocity and zero higher derivatives (least squares if the
/// realization is not observable). An actuator lag has settled on the held input.
pub fn initial_state(
    plant: &Plant,
    period: f64,
    position: f64,
    velocity: f64,
    held: f64,
) -> Result<Vec<f64>> {
    let base = StateSpace::mechanical(plant, period)?;
    let mut x = match &plant.model {
        PlantModel::MassSpringDamper(_) => vec![position, velocity],
        PlantModel::TwoMass(_) => vec![position, velocity, position, velocity],
        PlantModel::TransferFunction { .. } => observable_start(&base, position, velocity),
    };
    if plant.force_lag > 0.0 {
        x.push(held);
    }
    Ok(x)
}

/// Solves [C; CA; …; CA^{n−1}]·x = (position, velocity, 0, …) by SVD (least squares).
fn observable_start(ss: &StateSpace, position: f64, velocity: f64) -> Vec<f64> {
    let n = ss.order();
    let mut rows = Vec::with_capacity(n);
    let mut row = ss.c.clone();
    for _ in 0..n {
        let next = (0..n)
            .map(|j| (0..n).map(|i| row[i] * ss.a[i][j]).sum())
            .collect();
        rows.push(std::mem::replace(&mut row, next));
    }
    let o = nalgebra::DMatrix::from_fn(n, n, |i, j| rows[i][j]);
    let mut rhs = nalgebra::DVector::zeros(n);
    rhs[0] = position;
    if n > 1 {
        rhs[1] = velocity;
    }
    let svd = o.svd(true, true);
    let eps = f64::EPSILON * n as f64 * svd.singular_values.max();
    match svd.solve(&rhs, eps) {
        Ok(x) => x.iter().copied().collect(),
        Err(_) => vec![0.0; n],
    }
}

/// Φ − I = E(1) and the inputs (Γ0, Γ1) of [`split_hold`] over one sample delayed by a
/// fraction λ: for λ > 0 from the two parts of the sample alone, E(1) joining E(1 − λ) and
/// E(λ) ([`crate::matrix_exp::exp_joined`]), so that two exponentials serve where three did.
fn held_over_sample(a: &Mat, b: &[f64], lambda: f64) -> (Mat, Vec<f64>, Vec<f64>) {
    if lambda == 0.0 {
        let (e1, gamma0) = crate::matrix_exp::exp_and_input(a, 1.0, b);
        return (e1, gamma0, vec![0.0; b.len()]);
    }
    let ([e_rest, e_l], g0, g1) = split_parts(a, b, lambda);
    (crate::matrix_exp::exp_joined(&e_rest, &e_l), g0, g1)
}

/// The inputs (Γ0, Γ1) of a force held over one sample and delayed by a fraction λ of it
/// (module doc): Γ0 = Ψ(1 − λ)b, Γ1 = e^{A(1−λ)}Ψ(λ)b; for λ = 0, Γ0 = Ψ(1)b (given as
/// `psi1`) and Γ1 = 0.
pub fn split_hold(a: &Mat, psi1: &Mat, b: &[f64], lambda: f64) -> (Vec<f64>, Vec<f64>) {
    if lambda == 0.0 {
        return (poly::mat_vec(psi1, b), vec![0.0; b.len()]);
    }
    let (_, g0, g1) = split_parts(a, b, lambda);
    (g0, g1)
}

/// For 0 < λ < 1: [E(1 − λ), E(λ)] and the inputs (Γ0, Γ1) of [`split_hold`].
fn split_parts(a: &Mat, b: &[f64], lambda: f64) -> ([Mat; 2], Vec<f64>, Vec<f64>) {
    let (e_rest, g0) = crate::matrix_exp::exp_and_input(a, 1.0 - lambda, b);
    let (e_l, psi_l_b) = crate::matrix_exp::exp_and_input(a, lambda, b);
    let g1 = poly::mat_vec(&add_identity(&e_rest, 1.0), &psi_l_b);
    ([e_rest, e_l], g0, g1)
}

impl Loop {
    /// The exact discrete loop (see [`DiscreteLoop`]).
    pub fn discretize(&self) -> Result<DiscreteLoop> {
        DiscreteLoop::new(self)
    }

    /// The wall's units (Table I generalized): k_u = m/T² per unit of a, k_u·T per unit of
    /// b, with m the plant's [`Plant::reference_mass`].
    pub fn wall_scale(&self) -> WallScale {
        let m = self.plant.reference_mass(self.period);
        let k_u = m / (self.period * self.period);
        WallScale {
            stiffness: k_u,
            damping: k_u * self.period,
        }
    }
}

impl VelocityEstimator {
    /// True for the paper's backward difference.
    pub fn is_backward(&self) -> bool {
        matches!(self, VelocityEstimator::Backward)
    }
}
