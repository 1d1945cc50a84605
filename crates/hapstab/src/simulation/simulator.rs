//! The simulator of [`super`]: the loop's memory (plant state, delay line of sensed
//! positions, velocity estimator, last wall force) stepped sample by sample with the exact
//! matrices of [`crate::DiscreteLoop`] (see [`super::stepper`]), feeding the run's log.

use super::filter::VelocityFilter;
use super::stepper::{
    Continuous, FrictionForces, HUMAN, Kernel, StuckKernels, WALL_NOW, WALL_PREV, dot,
};
use super::{BLOW_UP, Config, Contact, HumanForce, LoopFacts, RunLog, RunVerdict, SampleFacts};
use super::{Trace, verdict};
use crate::error::{Result, finite};
use crate::model::MAX_PLANT_ORDER;
use crate::param::Param;
use crate::poly;
use crate::zoh::{PlantPorts, StateSpace, exp_and_integral, initial_state};

/// Largest state the simulator steps: the largest plant and its actuator lag.
const MAX_STATE: usize = MAX_PLANT_ORDER + 1;

/// The wall's force on one sample (wall units) and how it relates to the linear law.
#[derive(Debug, Clone, Copy)]
struct WallSample {
    force: f64,
    in_contact: bool,
    linear: bool,
}

/// The one-sample maps of a loop whose state has at most N components (padded with zeros).
#[derive(Debug, Clone)]
struct Engine<const N: usize> {
    free: Kernel<N>,
    stuck: Option<StuckKernels<N>>,
    output: Row<N>,
    velocity: Row<N>,
}

/// A row read from the state: one state itself (the mechanical models' position and
/// velocity) or a combination of states (a transfer function's realization).
#[derive(Debug, Clone, Copy)]
enum Row<const N: usize> {
    State(usize),
    Combination([f64; N]),
}

impl<const N: usize> Row<N> {
    fn new(row: &[f64]) -> Self {
        let ones: Vec<usize> = (0..row.len()).filter(|&i| row[i] != 0.0).collect();
        match ones.as_slice() {
            &[i] if row[i] == 1.0 => Row::State(i),
            _ => {
                let mut a = [0.0; N];
                a[..row.len()].copy_from_slice(row);
                Row::Combination(a)
            }
        }
    }

    #[inline(always)]
    fn read(&self, x: &[f64; N]) -> f64 {
        match self {
            Row::State(i) => x[*i],
            Row::Combination(c) => dot(c, x),
        }
    }
}

impl<const N: usize> Engine<N> {
    fn new(parts: &Parts, continuous: Option<&Continuous>) -> Self {
        let dl = &parts.dl;
        Self {
            free: Kernel::new(
                &dl.phi_minus_identity,
                [&dl.gamma0, &dl.gamma1, &parts.human, &parts.friction],
            ),
            stuck: continuous.map(Continuous::stuck_kernels),
            output: Row::new(&dl.c),
            velocity: Row::new(&parts.ports.velocity),
        }
    }
}

/// The engine for the loop's state size: unrolled for small sizes, zero-padded above.
/// One lives on the stack per simulation and is matched once per run, not per step, so its
/// size (a few KiB for the largest state) costs nothing that boxing would save.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
enum Engines {
    E2(Engine<2>),
    E3(Engine<3>),
    E4(Engine<4>),
    E5(Engine<5>),
    E8(Engine<8>),
    E13(Engine<MAX_STATE>),
}

impl Engines {
    fn new(parts: &Parts, continuous: Option<&Continuous>) -> Self {
        match parts.dl.order() {
            0..=2 => Engines::E2(Engine::new(parts, continuous)),
            3 => Engines::E3(Engine::new(parts, continuous)),
            4 => Engines::E4(Engine::new(parts, continuous)),
            5 => Engines::E5(Engine::new(parts, continuous)),
            6..=8 => Engines::E8(Engine::new(parts, continuous)),
            _ => Engines::E13(Engine::new(parts, continuous)),
        }
    }
}

/// The discrete loop and the plant's ports, with the one-sample columns of the human force
/// and of friction.
struct Parts {
    dl: crate::DiscreteLoop,
    ss: StateSpace,
    ports: PlantPorts,
    human: Vec<f64>,
    friction: Vec<f64>,
}

impl Parts {
    fn new(lp: &crate::Loop) -> Result<Self> {
        let dl = lp.discretize()?;
        let ss = StateSpace::of_plant(&lp.plant, lp.period)?;
        let ports = PlantPorts::of_plant(&lp.plant, lp.period)?;
        let (_, psi1) = exp_and_integral(&ss.a, 1.0);
        let human = poly::mat_vec(&psi1, &ports.human);
        let friction = match ports.friction {
            Some(f) => {
                let mut b = vec![0.0; ss.order()];
                b[f.state] = f.gain;
                poly::mat_vec(&psi1, &b)
            }
            None => vec![0.0; ss.order()],
        };
        Ok(Self {
            dl,
            ss,
            ports,
            human,
            friction,
        })
    }
}

/// Everything fixed during a run: the laws of the loop and its effects, in wall units.
#[derive(Debug, Clone)]
struct Laws {
    order: usize,
    d: usize,
    fractional: bool,
    filter: VelocityFilter,
    a: f64,
    b: f64,
    xw: f64,
    contact: Contact,
    quant: Option<f64>,
    u_max: f64,
    friction: Option<FrictionForces>,
    continuous: Option<Continuous>,
    linear: bool,
    direct_actuator: f64,
    direct_human: f64,
    output: Vec<f64>,
    velocity: Vec<f64>,
    human: HumanForce,
    scale: f64,
    period: f64,
}

impl Laws {
    #[inline(always)]
    fn sense(&self, x: f64) -> f64 {
        match self.quant {
            Some(q) => (x / q).round() * q,
            None => x,
        }
    }

    /// The wall force on one sample: the linear law a (y − x_w) + b v while the sensed,
    /// delayed position penetrates a unilateral wall (never pulling if so configured),
    /// limited to ±F_max.
    #[inline(always)]
    fn wall(&self, yd: f64, v: f64) -> WallSample {
        let law = self.a * (yd - self.xw) + self.b * v;
        let in_contact = self.contact == Contact::Bilateral || yd > self.xw;
        let acting = match self.contact {
            _ if !in_contact => 0.0,
            Contact::UnilateralNoPull => law.max(0.0),
            _ => law,
        };
        let force = acting.clamp(-self.u_max, self.u_max);
        WallSample {
            force,
            in_contact,
            linear: force == law,
        }
    }

    /// Human force at sample k in wall units.
    #[inline(always)]
    fn human_at(&self, k: usize) -> Result<f64> {
        Ok(match &self.human {
            HumanForce::Constant(f) => *f * self.scale,
            HumanForce::Samples(v) => v.get(k).or(v.last()).copied().unwrap_or(0.0) * self.scale,
            HumanForce::Function(f) => {
                let v = f(k as f64 * self.period);
                finite(Param::HumanForceFunction, v)? * self.scale
            }
        })
    }
}

/// The loop's memory and the run's records.
#[derive(Debug, Clone)]
struct Memory {
    k: usize,
    x: [f64; MAX_STATE],
    /// Sensed positions, y_j at index j & mask.
    ring: Vec<f64>,
    mask: usize,
    /// Velocity estimates, v_j at index j & vmask (recursive estimators only).
    vring: Vec<f64>,
    vmask: usize,
    /// The wall force computed on the previous sample, u_{k−d−1}.
    prev_force: f64,
    log: RunLog,
    recorder: Option<Recorder>,
    blown_up: bool,
    friction_events: usize,
}

/// The time-domain simulator of Fig. 3 for any loop (see the module documentation).
/// Stepping is allocation-free except when a block of the run's log closes or a friction
/// event is located within a sample: the delay line is a ring buffer of sensed positions,
/// the log ([`RunLog`]) and the trace have bounded size whatever the run length.
#[derive(Debug, Clone)]
pub struct Simulator {
    laws: Laws,
    engines: Engines,
    mem: Memory,
}

impl Simulator {
    /// Builds a simulator from a validated configuration (Fig. 3, Section III).
    pub fn new(config: &Config) -> Result<Self> {
        config.validate()?;
        let lp = config.model.stepped_loop()?;
        let parts = Parts::new(&lp)?;
        let laws = Self::laws(config, &parts)?;
        let engines = Engines::new(&parts, laws.continuous.as_ref());
        let mem = Self::memory(config, &lp, &laws)?;
        Ok(Self { laws, engines, mem })
    }

    fn laws(config: &Config, parts: &Parts) -> Result<Laws> {
        let scale = config.model.force_scale();
        let (a, b) = config.model.wall_units();
        let e = &config.effects;
        let friction = e.friction.map(|f| FrictionForces {
            coulomb: f.coulomb * scale,
            stiction: f.stiction * scale,
        });
        let continuous = match (friction, parts.ports.friction) {
            (Some(_), Some(point)) => Some(Continuous::new(
                parts.ss.a.clone(),
                parts.ss.b.clone(),
                parts.ports.human.clone(),
                point,
                parts.dl.delay.fraction,
            )),
            _ => None,
        };
        Ok(Laws {
            order: parts.dl.order(),
            d: parts.dl.delay.samples,
            fractional: parts.dl.delay.fraction > 0.0,
            filter: VelocityFilter::new(&parts.dl.velocity_num, &parts.dl.velocity_den),
            a,
            b,
            xw: e.wall_position,
            contact: e.contact,
            quant: e.quantization,
            u_max: e.saturation.map_or(f64::INFINITY, |f| f * scale),
            friction,
            continuous,
            linear: e.is_linear(),
            direct_actuator: parts.ports.direct_actuator,
            direct_human: parts.ports.direct_human,
            output: parts.dl.c.clone(),
            velocity: parts.ports.velocity.clone(),
            human: config.human.clone(),
            scale,
            period: config.model.period(),
        })
    }

    /// The memory of a loop that has rested at the sensed initial position (the delay line
    /// and the estimator's history hold it, the previous wall force is the one at rest), with
    /// the plant at the initial position and velocity.
    fn memory(config: &Config, lp: &crate::Loop, laws: &Laws) -> Result<Memory> {
        let m = laws.filter.order();
        let cap = (laws.d + m + 1).next_power_of_two();
        let vcap = (m + 1).next_power_of_two();
        let x0 = config.initial.position;
        let y0 = laws.sense(x0);
        let rest = laws.wall(y0, 0.0).force;
        let tv0 = config.initial.velocity * laws.period;
        let start = initial_state(&lp.plant, lp.period, x0, tv0, -rest)?;
        let mut x = [0.0; MAX_STATE];
        x[..start.len()].copy_from_slice(&start);
        Ok(Memory {
            k: 0,
            x,
            ring: vec![y0; cap],
            mask: cap - 1,
            vring: vec![0.0; vcap],
            vmask: vcap - 1,
            prev_force: rest,
            log: RunLog::new(config.samples),
            recorder: (config.trace_rows > 0)
                .then(|| Recorder::new(config.trace_rows, config.samples)),
            blown_up: false,
            friction_events: 0,
        })
    }

    /// Index k of the next sample.
    pub fn sample_index(&self) -> usize {
        self.mem.k
    }

    /// Current time kT in s.
    pub fn time(&self) -> f64 {
        self.mem.k as f64 * self.laws.period
    }

    /// Current (unquantized) measured position y = C x in m.
    pub fn position(&self) -> f64 {
        dot(&self.laws.output, &self.mem.x[..self.laws.order])
    }

    /// Current velocity of the measured point in m/s (for a transfer function of relative
    /// degree 1, without the force's direct effect).
    pub fn velocity(&self) -> f64 {
        dot(&self.laws.velocity, &self.mem.x[..self.laws.order]) / self.laws.period
    }

    /// True once the state exceeded [`BLOW_UP`] (the run has stopped).
    pub fn blown_up(&self) -> bool {
        self.mem.blown_up
    }

    /// Number of friction velocity reversals located so far.
    pub fn friction_events(&self) -> usize {
        self.mem.friction_events
    }

    /// The recorded trace so far, if recording.
    pub fn trace(&self) -> Option<&Trace> {
        self.mem.recorder.as_ref().map(|r| &r.trace)
    }

    /// Trace rows are every n-th sample (0 without a trace).
    pub fn trace_stride(&self) -> usize {
        self.mem.recorder.as_ref().map_or(0, |r| r.stride)
    }

    /// Takes the recorded trace out of the simulator.
    pub fn take_trace(&mut self) -> Option<Trace> {
        self.mem.recorder.take().map(|r| r.trace)
    }

    /// The run's log so far.
    pub fn log(&self) -> &RunLog {
        &self.mem.log
    }

    /// Judges the run so far ([`verdict::judge`]); `last_chance` reports growth that contact
    /// loss or a force limit could still bound as growing.
    pub fn verdict(&self, facts: &LoopFacts, last_chance: bool) -> RunVerdict {
        verdict::judge(&self.mem.log, facts, self.mem.blown_up, last_chance)
    }

    /// Simulates up to `n` more samples and returns how many were simulated (fewer only if
    /// the state blew up). Errors only if a human force function returns a non-finite value.
    pub fn advance(&mut self, n: usize) -> Result<usize> {
        let Simulator { laws, engines, mem } = self;
        match engines {
            Engines::E2(e) => run(laws, e, mem, n),
            Engines::E3(e) => run(laws, e, mem, n),
            Engines::E4(e) => run(laws, e, mem, n),
            Engines::E5(e) => run(laws, e, mem, n),
            Engines::E8(e) => run(laws, e, mem, n),
            Engines::E13(e) => run(laws, e, mem, n),
        }
    }
}

fn run<const N: usize>(laws: &Laws, e: &Engine<N>, mem: &mut Memory, n: usize) -> Result<usize> {
    if laws.linear {
        run_loop::<true, N>(laws, e, mem, n)
    } else {
        run_loop::<false, N>(laws, e, mem, n)
    }
}

/// Samples of the loop (module doc of [`super`]): sense, delay, estimate the velocity, apply
/// the wall law, log, and step the plant exactly over the sample.
fn run_loop<const LINEAR: bool, const N: usize>(
    laws: &Laws,
    e: &Engine<N>,
    mem: &mut Memory,
    n: usize,
) -> Result<usize> {
    if mem.blown_up {
        return Ok(0);
    }
    let Memory {
        k: mem_k,
        x: mem_x,
        ring,
        mask,
        vring,
        vmask,
        prev_force,
        log,
        recorder,
        blown_up,
        friction_events,
    } = mem;
    let (d, mask, vmask) = (laws.d, *mask, *vmask);
    let (ring, vring) = (&mut ring[..], &mut vring[..]);
    let recursive = laws.filter.recursive();
    let direct = laws.direct_actuator != 0.0 || laws.direct_human != 0.0;
    let mut x: [f64; N] = std::array::from_fn(|i| mem_x[i]);
    let (mut k, mut prev) = (*mem_k, *prev_force);
    let mut done = 0;
    let mut result = Ok(());
    while done < n {
        let pos = e.output.read(&x);
        let y = if LINEAR { pos } else { laws.sense(pos) };
        ring[k & mask] = y;
        let j = k.wrapping_sub(d);
        let yd = ring[j & mask];
        let v = laws.filter.output(
            |lag| ring[j.wrapping_sub(lag) & mask],
            |lag| vring[j.wrapping_sub(lag) & vmask],
        );
        if recursive {
            vring[j & vmask] = v;
        }
        let wall = wall_law::<LINEAR>(laws, yd, v);
        let uh = match laws.human_at(k) {
            Ok(uh) => uh,
            Err(err) => {
                result = Err(err);
                break;
            }
        };
        let u = [-wall.force, -prev, uh, 0.0];
        let vel = sensed_velocity(laws, e, &x, u, direct);
        if let Some(r) = recorder.as_mut()
            && r.next == k
        {
            let (t, s) = (laws.period, laws.scale);
            r.push([k as f64 * t, pos, vel / t, wall.force / s, uh / s]);
        }
        log.push(SampleFacts {
            position: pos,
            velocity: vel,
            in_contact: wall.in_contact,
            linear: wall.linear,
        });
        x = plant_step::<LINEAR, N>(laws, e, x, u, friction_events);
        prev = wall.force;
        k += 1;
        done += 1;
        if !x.iter().all(|v| v.abs() < BLOW_UP) {
            *blown_up = true;
            break;
        }
    }
    mem_x[..N].copy_from_slice(&x);
    (*mem_k, *prev_force) = (k, prev);
    result.map(|()| done)
}

/// The wall's force on the delayed position `yd` and the velocity estimate `v`: the linear
/// spring-damper a·(yd − x_w) + b·v in contact throughout, or the wall's own law
/// ([`Laws::wall`]: unilateral contact, saturation).
#[inline(always)]
fn wall_law<const LINEAR: bool>(laws: &Laws, yd: f64, v: f64) -> WallSample {
    if LINEAR {
        WallSample {
            force: laws.a * (yd - laws.xw) + laws.b * v,
            in_contact: true,
            linear: true,
        }
    } else {
        laws.wall(yd, v)
    }
}

/// The plant's velocity output at state x, with the inputs' direct feed-through (a plant
/// whose velocity responds at once to the actuator's force, the current or, under a
/// fractional delay, the previous one, and to the human's).
#[inline(always)]
fn sensed_velocity<const N: usize>(
    laws: &Laws,
    e: &Engine<N>,
    x: &[f64; N],
    u: [f64; 4],
    direct: bool,
) -> f64 {
    let mut vel = e.velocity.read(x);
    if direct {
        let ua = if laws.fractional {
            u[WALL_PREV]
        } else {
            u[WALL_NOW]
        };
        vel += laws.direct_actuator * ua + laws.direct_human * u[HUMAN];
    }
    vel
}

/// The plant's state one sample on under the held inputs u: the exact step, or, with Coulomb
/// friction on a nonlinear run, the step that sticks and slips (the stepper's friction sample, counted
/// in `friction_events`).
#[inline(always)]
fn plant_step<const LINEAR: bool, const N: usize>(
    laws: &Laws,
    e: &Engine<N>,
    mut x: [f64; N],
    u: [f64; 4],
    friction_events: &mut usize,
) -> [f64; N] {
    match (&laws.continuous, &e.stuck, laws.friction) {
        (Some(c), Some(stuck), Some(fr)) if !LINEAR => {
            *friction_events += c.friction_sample(&e.free, stuck, &mut x, u, fr);
            x
        }
        _ => e.free.step(&x, u),
    }
}

/// The loop's state as one vector, for measuring its growth ([`super::growth`]): plant
/// state, the delay line's positions, the estimator's past estimates (recursive estimators)
/// and the previous wall force (fractional delays), newest first.
impl Simulator {
    fn history(&self) -> (usize, usize, usize) {
        let m = self.laws.filter.order();
        let positions = self.laws.d + m;
        let estimates = if self.laws.filter.recursive() { m } else { 0 };
        (positions, estimates, usize::from(self.laws.fractional))
    }

    /// Length of the state vector.
    pub(super) fn state_len(&self) -> usize {
        let (p, e, f) = self.history();
        self.laws.order + p + e + f
    }

    /// Sets the loop's memory from a state vector (at the current sample index).
    pub(super) fn load_state(&mut self, s: &[f64]) {
        let (p, e, f) = self.history();
        let (n, k, d) = (self.laws.order, self.mem.k, self.laws.d);
        let mem = &mut self.mem;
        mem.x[..n].copy_from_slice(&s[..n]);
        for i in 1..=p {
            mem.ring[k.wrapping_sub(i) & mem.mask] = s[n + i - 1];
        }
        for i in 1..=e {
            mem.vring[k.wrapping_sub(d + i) & mem.vmask] = s[n + p + i - 1];
        }
        if f == 1 {
            mem.prev_force = s[n + p + e];
        }
    }

    /// Reads the loop's memory into a state vector (at the current sample index).
    pub(super) fn store_state(&self, s: &mut [f64]) {
        let (p, e, f) = self.history();
        let (n, k, d) = (self.laws.order, self.mem.k, self.laws.d);
        let mem = &self.mem;
        s[..n].copy_from_slice(&mem.x[..n]);
        for i in 1..=p {
            s[n + i - 1] = mem.ring[k.wrapping_sub(i) & mem.mask];
        }
        for i in 1..=e {
            s[n + p + i - 1] = mem.vring[k.wrapping_sub(d + i) & mem.vmask];
        }
        if f == 1 {
            s[n + p + e] = mem.prev_force;
        }
    }
}

/// A trace that keeps at most `cap` rows: every `stride`-th sample from k = 0, thinned by
/// half (stride doubled) whenever it fills up, so an extended run never exceeds `cap`.
#[derive(Debug, Clone)]
struct Recorder {
    trace: Trace,
    cap: usize,
    stride: usize,
    next: usize,
}

impl Recorder {
    fn new(cap: usize, planned: usize) -> Self {
        let stride = planned.div_ceil(cap - 1).max(1);
        let rows = (planned / stride + 1).min(cap);
        Self {
            trace: Trace {
                time: Vec::with_capacity(rows),
                position: Vec::with_capacity(rows),
                velocity: Vec::with_capacity(rows),
                wall_force: Vec::with_capacity(rows),
                human_force: Vec::with_capacity(rows),
            },
            cap,
            stride,
            next: 0,
        }
    }

    fn push(&mut self, row: [f64; 5]) {
        let t = &mut self.trace;
        let cols = [
            &mut t.time,
            &mut t.position,
            &mut t.velocity,
            &mut t.wall_force,
            &mut t.human_force,
        ];
        for (col, v) in cols.into_iter().zip(row) {
            col.push(v);
        }
        self.next += self.stride;
        if self.trace.time.len() == self.cap {
            self.thin();
        }
    }

    /// Keeps every other row (those at multiples of the doubled stride).
    fn thin(&mut self) {
        let t = &mut self.trace;
        for col in [
            &mut t.time,
            &mut t.position,
            &mut t.velocity,
            &mut t.wall_force,
            &mut t.human_force,
        ] {
            let kept: Vec<f64> = col.iter().step_by(2).copied().collect();
            *col = kept;
        }
        self.stride *= 2;
        self.next = self.next.div_ceil(self.stride) * self.stride;
    }
}
