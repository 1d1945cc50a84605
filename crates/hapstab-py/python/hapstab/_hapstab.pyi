"""Type stubs of the hapstab extension module (see the package docstring and each function's
docstring for the equations). Units are SI: K in N/m, B in Ns/m, masses in kg, times in s."""

import os
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike

__version__: str
Float64Array = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]
Complex128Array = npt.NDArray[np.complex128]

class NumericalError(RuntimeError):
    """A numerical routine did not converge on valid input."""

class MassSpringDamper:
    """The paper's plant 1/(m s² + b s + k) from force (N) to position (m) (eq. 1)."""

    def __init__(self, mass: float, damping: float = 0.0, stiffness: float = 0.0) -> None: ...
    @staticmethod
    def from_device_and_arm(
        *,
        device_mass: float = 0.1,
        device_damping: float = 1.5,
        arm_mass: float = 1.0,
        arm_damping: float = 6.0,
        arm_stiffness: float = 350.0,
    ) -> MassSpringDamper:
        """m = m_L + m_H, b = b_L + b_H, k = k_H (eq. 1); the arm is remembered, so
        passivity counts only the device's own b_L."""
    @property
    def mass(self) -> float:
        """m in kg."""
    @property
    def damping(self) -> float:
        """b in Ns/m."""
    @property
    def device_damping(self) -> float:
        """The device's own b_L = b − b_H in Ns/m (b when given as m, b, k)."""
    @property
    def stiffness(self) -> float:
        """k in N/m."""

class TwoMass:
    """Motor-side mass J (actuator and encoder) coupled to the handle by a compliant
    transmission k_t, b_t; the arm (m_H, b_H, k_H) holds the handle."""

    def __init__(
        self,
        motor_mass: float,
        transmission_stiffness: float,
        *,
        motor_damping: float = 0.0,
        handle_mass: float = 0.0,
        transmission_damping: float = 0.0,
        arm_mass: float = 1.0,
        arm_damping: float = 6.0,
        arm_stiffness: float = 350.0,
    ) -> None: ...
    @property
    def motor_mass(self) -> float: ...
    @property
    def motor_damping(self) -> float: ...
    @property
    def handle_mass(self) -> float: ...
    @property
    def transmission_stiffness(self) -> float: ...
    @property
    def transmission_damping(self) -> float: ...
    @property
    def arm_mass(self) -> float: ...
    @property
    def arm_damping(self) -> float: ...
    @property
    def arm_stiffness(self) -> float: ...

class TransferFunction:
    """A strictly proper P(s) = num(s)/den(s), force (N) to position (m), highest power of s
    first (python-control's tf convention), order <= 12."""

    def __init__(self, num: ArrayLike, den: ArrayLike) -> None: ...
    @property
    def num(self) -> Float64Array: ...
    @property
    def den(self) -> Float64Array: ...

# also a continuous-time python-control TransferFunction or StateSpace (SISO), typed Any here
# because python-control is not a dependency
Plant = Union[MassSpringDamper, TwoMass, TransferFunction, Any]

class Loop:
    """The loop of Fig. 3: plant, sampling period T, delay t_d = (d + λ)T, velocity estimator
    ("backward", "lowpass:FC", "butterworth:N:FC", "bessel:N:FC", "critically-damped:N:FC",
    "average:N", "iir:b0,b1,…/a0,a1,…") and actuator lag τ."""

    def __init__(
        self,
        plant: Plant,
        *,
        period: float = 1e-3,
        delay: Optional[float] = None,
        delay_samples: Optional[int] = None,
        velocity: str = "backward",
        force_lag: float = 0.0,
    ) -> None: ...
    @staticmethod
    def paper(
        *,
        device_mass: float = 0.1,
        device_damping: float = 1.5,
        arm_mass: float = 1.0,
        arm_damping: float = 6.0,
        arm_stiffness: float = 350.0,
        period: float = 1e-3,
        delay: float = 0.0,
    ) -> Loop:
        """The paper's loop in physical units (eq. 1, backward-difference velocity)."""
    @staticmethod
    def normalized(gamma: float = 0.0, delta: float = 0.0, d: int = 0) -> Loop:
        """The paper's loop in normalized units (Table I): m = 1 kg, T = 1 s, so K = α, B = β."""
    @staticmethod
    def load(path: Union[str, "os.PathLike[str]"]) -> Loop:
        """A loop saved as JSON: a report's "input", its "loop" object or a whole report."""
    @staticmethod
    def load_wall(path: Union[str, "os.PathLike[str]"]) -> Optional[Tuple[float, float]]:
        """The wall (K, B) a loop file names (α, β for a normalized loop), or None."""
    @staticmethod
    def from_json(text: str) -> Loop:
        """The loop from the text of a loop file."""
    def to_json(
        self, wall_stiffness: Optional[float] = None, wall_damping: Optional[float] = None
    ) -> str:
        """The loop (and a wall) as the command line echoes it under "input"."""
    def to_control(
        self,
        wall_stiffness: Optional[float] = None,
        wall_damping: Optional[float] = None,
        *,
        alpha: Optional[float] = None,
        beta: Optional[float] = None,
    ) -> Any:
        """The sampled open loop (K·PK + B·PB)/P0 as a python-control TransferFunction, dt = T."""
    def save(
        self,
        path: Union[str, "os.PathLike[str]"],
        wall_stiffness: Optional[float] = None,
        wall_damping: Optional[float] = None,
    ) -> None:
        """Writes to_json(wall_stiffness, wall_damping) to path."""
    @property
    def plant(self) -> Plant: ...
    @property
    def period(self) -> float:
        """T in s."""
    @property
    def delay(self) -> float:
        """t_d in s."""
    @property
    def delay_samples(self) -> float:
        """t_d/T = d + λ."""
    @property
    def velocity(self) -> str: ...
    @property
    def force_lag(self) -> float:
        """τ in s."""
    @property
    def is_normalized(self) -> bool: ...
    @property
    def paper_view(self) -> Optional[Tuple[float, float, int]]:
        """(γ, δ, d) of Table I for the paper's loop, else None."""
    @property
    def reference_mass(self) -> float:
        """The m in kg of α = KT²/m, β = BT/m."""
    @property
    def wall_scale(self) -> Tuple[float, float]:
        """(m/T² N/m per unit α, m/T Ns/m per unit β)."""

class Check:
    stable: bool
    verdict: Literal["stable", "marginal", "unstable"]
    spectral_radius: float
    roots: Complex128Array
    wall_stiffness: float
    wall_damping: float
    k_interval: Optional[Tuple[float, float]]
    alpha: Optional[float]
    beta: Optional[float]
    alpha_interval: Optional[Tuple[float, float]]
    alpha_linear: Optional[float]
    k_linear: Optional[float]
    margins: Margins
    """The wall's margins beside the verdict (as `margins`; none for a wall that is not stable)."""

class Edge:
    start: int
    stop: int
    kind: Literal["z=1", "z=-1", "complex", "window"]
    theta_start: Optional[float]
    theta_end: Optional[float]

class Region:
    polygons: list[Float64Array]
    """(N, 2) arrays of [K in N/m, B in Ns/m], counter-clockwise, first vertex not repeated."""
    thetas: list[Float64Array]
    edges: list[list[Edge]]
    k_max: Optional[float]
    b_at_k_max: Optional[float]
    k_max_attained: Optional[bool]
    b_stable_near_k_max: Optional[float]
    k_stable_near_k_max: Optional[float]
    area: float
    wall_units: dict
    """N/m and Ns/m of one wall unit: {"stiffness", "damping"} (boundary --json's keys)."""
    normalized: Optional[dict]
    """The paper's loop: gamma, delta, d, alpha_max, beta_at_alpha_max, area; else None."""
    def plot(self, ax: Any = None) -> Any:
        """Draws the result (hapstab.plotting; needs matplotlib) and returns the matplotlib Axes."""

class Kmax:
    k_max: Optional[float]
    b_at_k_max: Optional[float]
    k_interval: Optional[Tuple[float, float]]
    k_linear: Optional[float]
    k_max_attained: Optional[bool]
    b_stable_near_k_max: Optional[float]
    k_stable_near_k_max: Optional[float]
    k_max_at_zero_damping: Optional[float]
    renderable: Optional[RenderableBand]
    normalized: Optional[dict]
    """The paper's loop: alpha_max, beta, gamma, delta, d (kmax --json's keys); else None."""

class RenderableBand:
    """The renderable damping band 0 <= B <= b_max (force noise F_n RMS from position steps
    through the velocity estimator) and K_max over it."""

    position_resolution: float
    force_noise: float
    velocity_noise_gain: float
    b_max: float
    k_max: Optional[float]
    b_at_k_max: Optional[float]
    k_max_attained: Optional[bool]

class Identification:
    """A plant identified from a recording (hapstab identify)."""

    model: str
    names: List[str]
    units: List[str]
    values: Float64Array
    standard_errors: Float64Array
    ci_low: Float64Array
    ci_high: Float64Array
    fixed: List[bool]
    position_offset: float
    period: float
    nrmse: float
    fit_percent: float
    residual_rms: float
    whiteness_passes: bool
    cross_correlation_passes: bool
    predicted: Float64Array
    k_max: Optional[float]
    k_max_spread: Optional[Tuple[float, float]]
    k_max_robust: Optional[float]
    k_max_box_range: Optional[Tuple[float, float]]
    k_max_interval: Optional[Tuple[float, float]]
    k_max_standard_error: Optional[float]
    band_b_max: Optional[float]
    k_max_band: Optional[float]
    k_max_band_interval: Optional[Tuple[float, float]]
    position_offsets: List[float]
    fitted_loop: Loop

class RobustKmax:
    """Robust K_max over a box of loop parameters (hapstab kmax --robust --box)."""

    wall_damping: float
    k_max: Optional[float]
    k_min: Optional[float]
    k_max_nominal: Optional[float]
    worst_plant: List[Tuple[str, float]]
    plants_evaluated: int
    plants_verified: int
    verification_found: int

class WallProbability:
    """P(stable) of one wall over a population of operators (hapstab population)."""

    wall_stiffness: float
    wall_damping: float
    samples: int
    stable: int
    probability: float
    interval: Tuple[float, float]
    param_names: List[str]
    draws: Float64Array
    verdicts: BoolArray

class StabilityCurve:
    """P(stable) against K over a population of operators (hapstab population)."""

    wall_damping: float
    samples: int
    k: Float64Array
    probability: Float64Array
    probability_lo: Float64Array
    probability_hi: Float64Array
    levels: List[Tuple[float, Optional[float], Optional[float], Optional[float]]]
    param_names: List[str]
    draws: Float64Array
    intervals: Float64Array

class StabilityMap:
    stable: BoolArray
    spectral_radius: Optional[Float64Array]
    wall_stiffness: Float64Array
    wall_damping: Float64Array
    grid: bool
    def plot(self, ax: Any = None) -> Any:
        """Draws the result (hapstab.plotting; needs matplotlib) and returns the matplotlib Axes."""

class Discretization:
    """Coefficient arrays in descending powers of z."""

    period: float
    plant_num: Float64Array
    plant_den: Float64Array
    plant_delay: int
    velocity_num: Float64Array
    velocity_den: Float64Array
    p0: Float64Array
    pk: Float64Array
    pb: Float64Array
    characteristic: Optional[Float64Array]
    wall_stiffness: Optional[float]
    wall_damping: Optional[float]

class Simulation:
    time: Float64Array
    position: Float64Array
    velocity: Float64Array
    wall_force: Float64Array
    human_force: Float64Array
    outcome: Literal["decaying", "limit_cycle", "growing", "separated", "undecided"]
    reason: str
    linear_window: bool
    measured_growth_per_sample: Optional[float]
    spectral_radius: Optional[float]
    linear_verdict: Optional[Literal["stable", "marginal", "unstable"]]
    limit_cycle: Optional[dict]
    contact: dict
    judged_samples: Tuple[int, int]
    samples: int
    trace_stride: int
    blown_up: bool
    final_position: float
    final_velocity: float
    requested_samples: int
    max_samples: int
    duration: float
    judged_from: float
    judged_to: float
    units: Literal["physical", "normalized"]
    input: dict
    """The loop, its wall, effects, human_force and initial state, as `hapstab simulate --json`
    (duration, judged_from, judged_to in s, or samples for a loop in normalized units)."""
    def plot(self, ax: Any = None) -> Any:
        """Draws the result (hapstab.plotting; needs matplotlib) and returns the matplotlib Axes."""

class PassiveRegion:
    """The walls (K, B) the device renders passively: a convex polygon."""

    k_max: float
    """Largest passive K in N/m (exact; inf when unbounded in K)."""
    b_at_k_max: float
    """B in Ns/m at k_max."""
    area: float
    """Area in (N/m)·(Ns/m)."""
    bounded: bool
    vertices: Float64Array
    """(N, 2) array of [K in N/m, B in Ns/m], counter-clockwise, first vertex not repeated."""

class Passivity:
    """Colgate–Schenkel passivity of the sampled wall (eq. 28, generalized)."""

    wall_stiffness: float
    wall_damping: float
    b_required: float
    """Required device damping in Ns/m: b > b_required for passivity."""
    binding_frequency_hz: float
    binding_theta: float
    """ωT in [0, π] where the requirement binds."""
    dc_stiffness: float
    """K + B·V(1) in N/m (must be >= 0)."""
    device_damping: Optional[float]
    """The device's own damping b_L in Ns/m (passive towards any passive operator)."""
    effective_damping: Optional[float]
    """b = b_L + b_H of eq. (1), for eq. (28) with the arm counted (this operator only)."""
    effective_verdict: Optional[Literal["passive", "boundary", "not_passive", "not_applicable"]]
    meets: Optional[bool]
    verdict: Literal["passive", "boundary", "not_passive", "not_applicable"]
    note: Optional[str]
    stable: bool
    """The wall's stability verdict (as check)."""
    passive_region: Optional[PassiveRegion]

class Margins:
    """Stability margins of a stable wall, named as python-control and MATLAB name them (None
    when not stable or unbounded; see notes)."""

    stable: bool
    gain_margin: Optional[float]
    """Factor > 1 on K and B together to the stability boundary (python-control's gm)."""
    gain_margin_lower: Optional[float]
    """Factor < 1 on K and B together to the boundary."""
    phase_crossover_hz: Optional[float]
    """Where the gain margin is read (L real, negative), Hz."""
    stiffness_margin: Optional[float]
    """Factor > 1 on K alone at the given B."""
    stiffness_margin_lower: Optional[float]
    """Factor < 1 on K alone at the given B."""
    stiffness_crossover_hz: Optional[float]
    phase_margin_deg: Optional[float]
    """The smallest in magnitude over the gain crossovers."""
    gain_crossover_hz: Optional[float]
    """Where the phase margin is read (|L| = 1), Hz."""
    delay_margin: Optional[float]
    """Exact extra delay in s (fractional) to the boundary."""
    delay_margin_frequency_hz: Optional[float]
    delay_margin_pm_over_wc: Optional[float]
    """MATLAB's PM/ω_c, s."""
    delay_margin_at_least: Optional[float]
    stability_margin: Optional[float]
    """min |1 + L| (python-control's sm)."""
    stability_margin_hz: Optional[float]
    peak_gain: Optional[float]
    """max |L| over frequency."""
    peak_gain_hz: Optional[float]
    crossings: list[tuple[str, float, float]]
    """(kind "gain" or "phase", frequency Hz, phase margin deg or gain factor)."""
    notes: list[str]

class Mark:
    """One crossing of the open loop as the Bode and Nyquist plots mark it."""

    kind: Literal["gain", "phase"]
    omega: float
    """rad/s."""
    frequency_hz: float
    value: float
    """Phase margin in degrees (gain crossover) or the factor on (K, B) (phase crossover)."""
    magnitude_db: float
    phase_deg: float
    response: complex
    """L there."""
    primary: bool
    """True where the reported gain or phase margin is read."""

class FrequencyResponse:
    """The open loop L(e^{jωT}) of a wall on the exact discrete loop, with its crossings."""

    period: float
    nyquist_hz: float
    omega: Float64Array
    """rad/s."""
    frequency_hz: Float64Array
    response: Complex128Array
    """L(e^{jωT})."""
    magnitude_db: Float64Array
    phase_deg: Float64Array
    """Unwrapped along the grid."""
    marks: list[Mark]
    """Every gain and phase crossover (none when the wall is not stable)."""
    closest: Optional[Tuple[float, float, complex]]
    """(min |1 + L|, frequency Hz, L there)."""
    margins: Margins
    def plot(self, axes: Any = None) -> Tuple[Any, Any]:
        """Draws the result (hapstab.plotting; needs matplotlib) and returns the (magnitude, phase) matplotlib Axes."""

class RootLocus:
    """The roots of p(z) (eq. 9) as K sweeps at a fixed damping B."""

    wall_damping: float
    k_max: Optional[float]
    k_interval: Optional[Tuple[float, float]]
    k_max_index: Optional[int]
    """Index of the sample K = K_max in wall_stiffness."""
    crossing: Optional[complex]
    """The root closest to the unit circle at K = K_max."""
    crossing_frequency_hz: Optional[float]
    """The frequency of the oscillation at K_max, |arg z|/(2πT) of that root, Hz."""
    wall_stiffness: Float64Array
    roots: Complex128Array
    """Shape (len(wall_stiffness), degree of p), branch-ordered."""
    spectral_radius: Float64Array
    def plot(self, ax: Any = None) -> Any:
        """Draws the result (hapstab.plotting; needs matplotlib) and returns the matplotlib Axes."""

class Sweep:
    """K_max against one parameter of the loop (NaN where a value is missing; see notes)."""

    param: str
    unit: str
    values: Float64Array
    k_max: Float64Array
    b_at_k_max: Float64Array
    k_max_passive: Float64Array
    k_max_passive_with_arm: Float64Array
    notes: list[Optional[str]]
    passive_notes: list[Optional[str]]
    """Why passivity does not apply, per point (the passive K_max are then NaN)."""
    def plot(self, ax: Any = None) -> Any:
        """Draws the result (hapstab.plotting; needs matplotlib) and returns the matplotlib Axes."""

class LinearCondition:
    """The paper's linear condition (22)-(23) and its validity points (eq. 24, Fig. 7)."""

    gamma: float
    delta: float
    d: int
    linear_slope: float
    """1/(d + 1/2): (23) is alpha < linear_slope*beta + linear_intercept."""
    linear_intercept: float
    alpha_lower: float
    """(19): alpha > -gamma."""
    levels: Float64Array
    beta: Float64Array
    """The smallest beta > 0 at which the error (24) reaches each level."""
    alpha: Float64Array
    alpha_linear: Float64Array
    error: Float64Array
    at_start: list[bool]
    wall_stiffness: Optional[Float64Array]
    """alpha in N/m at each point (None for Loop.normalized)."""
    wall_damping: Optional[Float64Array]
    """beta in Ns/m at each point (None for Loop.normalized)."""
    k_linear: Optional[Float64Array]
    """K_lin of (23) in N/m at each point (None for Loop.normalized)."""
    k_linear_slope: Optional[float]
    """(23) in N/m and Ns/m: K < k_linear_slope*B + k_linear_intercept, 1/(T(d + 1/2)) in 1/s."""
    k_linear_intercept: Optional[float]
    k_lower: Optional[float]
    """(19) in N/m: K > k_lower = -k; k_linear_intercept = b/(T(d + 1/2)) in N/m."""

class NyquistRegions:
    """Section VIII: the gamma sweep's regions, the robust region, the passive region."""

    delta: float
    d: int
    gamma_nyquist: float
    """gamma_N = pi^2 + delta^2/4 (eq. 27)."""
    sweep_gamma: Float64Array
    sweep_alpha_max: Float64Array
    sweep_beta_at_alpha_max: Float64Array
    sweep_alpha_min: Float64Array
    sweep_beta_min: Float64Array
    sweep_beta_max: Float64Array
    sweep_area: Float64Array
    sweep_empty: list[bool]
    sweep_degenerate: list[bool]
    robust_polygon: Float64Array
    """(N, 2) array of [alpha, beta], counter-clockwise."""
    robust_alpha_max: float
    robust_beta_at_alpha_max: float
    robust_area: float
    robust_gamma_hi: float
    passive_polygon: Optional[Float64Array]
    passive_area: Optional[float]
    passive_inside_robust: Optional[bool]
    passive_applies: Optional[bool]

class ZWidth:
    """The Z-width of a loop: stable and passive regions, K_max, the K_max table."""

    stable: list[Float64Array]
    """Components as (N, 2) arrays of [K in N/m, B in Ns/m]."""
    stable_area: float
    k_max: Optional[float]
    b_at_k_max: Optional[float]
    k_max_nonnegative_damping: Optional[Tuple[float, float]]
    device_damping: Optional[float]
    passive: Optional[PassiveRegion]
    k_max_passive_with_arm: Optional[Tuple[float, float]]
    passive_inside_stable: Optional[bool]
    linear: Optional[Tuple[float, float]]
    """(b, t_r) of the linear condition K < (b + B)/t_r (22)."""
    table_damping: Float64Array
    table_k_max: Float64Array
    table_k_min: Float64Array
    table_k_max_passive: Float64Array
    table_k_linear: Float64Array

def check(
    loop: Loop,
    wall_stiffness: Optional[float] = None,
    wall_damping: Optional[float] = None,
    *,
    alpha: Optional[float] = None,
    beta: Optional[float] = None,
) -> Check:
    """Verdict, spectral radius and roots of p(z) (eq. 9) at the wall (K N/m, B Ns/m)."""

def region(loop: Loop) -> Region:
    """The exact stable region in the (K, B) plane by D-decomposition (Section V)."""

def kmax(
    loop: Loop,
    *,
    wall_damping: Optional[float] = None,
    damping_range: Optional[Tuple[float, float]] = None,
    position_resolution: Optional[float] = None,
    force_noise: Optional[float] = None,
) -> Kmax:
    """K_max in N/m: at a damping B, over a band of B, or (without either) over B >= 0
    beside K_max at B = 0 and over the renderable band."""

def identify(
    t: Union[ArrayLike, Sequence[ArrayLike]],
    force: Union[ArrayLike, Sequence[ArrayLike]],
    position: Union[ArrayLike, Sequence[ArrayLike]],
    *,
    model: str = "mass-spring-damper",
    fixed: Optional[Dict[str, float]] = None,
    delay: float = 0.0,
    force_lag: float = 0.0,
    fit_delay: bool = False,
    fit_force_lag: bool = False,
    quantization: float = 0.0,
    velocity: str = "backward",
    draws: int = 400,
    seed: int = 1,
) -> Identification:
    """The plant from a recording of time (s), commanded force (N) and measured position (m)
    (or lists of them, one per run), with standard errors, 95 % intervals, and K_max at B = 0
    and over the renderable band with their uncertainty."""

def identify_frequency(
    frequency_hz: ArrayLike,
    response: ArrayLike,
    *,
    period: float = 1e-3,
    model: str = "mass-spring-damper",
    fixed: Optional[Dict[str, float]] = None,
    delay: float = 0.0,
    force_lag: float = 0.0,
    fit_delay: bool = False,
    fit_force_lag: bool = False,
    velocity: str = "backward",
    draws: int = 400,
    seed: int = 1,
) -> Identification:
    """The plant from a measured frequency response (Hz, complex m/N) on a loop of period T,
    by logarithmic least squares on the exact sampled response."""

def robust_kmax(
    loop: Loop,
    bounds: Dict[str, Tuple[float, float]],
    *,
    wall_damping: float = 0.0,
    samples: int = 256,
    verify: int = 10000,
    seed: int = 1,
) -> RobustKmax:
    """Robust K_max at wall_damping over a box {name: (lo, hi)} of the loop's parameters
    (sweep's names): sampled, refined and verified."""

def stability_probability(
    loop: Loop,
    *,
    wall_stiffness: Optional[float] = None,
    wall_damping: float = 0.0,
    samples: int = 10000,
    seed: int = 1,
    levels: Sequence[float] = (0.99, 0.999),
    distributions: Optional[Dict[str, str]] = None,
) -> Union[WallProbability, StabilityCurve]:
    """P(stable) over a population of operators: at the wall (wall_stiffness, wall_damping),
    or against K at wall_damping with the K of each level."""

def stability_map(
    loop: Loop,
    wall_stiffness: ArrayLike,
    wall_damping: ArrayLike,
    *,
    spectral_radius: bool = False,
    grid: Optional[bool] = None,
) -> StabilityMap:
    """The grid method (Section V) over 1-D axes (grid=True, the default for two 1-D arrays:
    result shape (len(B), len(K))) or same-shape arrays of walls (grid=False, the default for
    any other same shape), in parallel with the GIL released."""

def discretize(
    loop: Loop,
    wall_stiffness: Optional[float] = None,
    wall_damping: Optional[float] = None,
    *,
    alpha: Optional[float] = None,
    beta: Optional[float] = None,
) -> Discretization:
    """The exact discrete loop (eq. 2–9) as coefficient arrays, descending powers of z."""

def simulate(
    loop: Loop,
    wall_stiffness: Optional[float] = None,
    wall_damping: Optional[float] = None,
    *,
    alpha: Optional[float] = None,
    beta: Optional[float] = None,
    duration: Optional[float] = None,
    samples: Optional[int] = None,
    max_duration: Optional[float] = None,
    max_samples: Optional[int] = None,
    human_force: Union[float, Sequence[float], Float64Array, None] = None,
    initial_position: float = 1e-3,
    initial_velocity: float = 0.0,
    contact: Literal["bilateral", "unilateral", "unilateral_no_pull"] = "bilateral",
    wall_position: float = 0.0,
    coulomb_friction: Optional[float] = None,
    static_friction: Optional[float] = None,
    quantization: Optional[float] = None,
    saturation: Optional[float] = None,
    trace_rows: int = 200000,
) -> Simulation:
    """The loop in the time domain with nonlinear effects: trace arrays and the verdict."""

def passivity(
    loop: Loop,
    wall_stiffness: Optional[float] = None,
    wall_damping: Optional[float] = None,
    *,
    alpha: Optional[float] = None,
    beta: Optional[float] = None,
    device_damping: Optional[float] = None,
) -> Passivity:
    """The device damping the wall requires to be passive (Colgate–Schenkel),
    b > (T/2)·max Re{(1 − e^{−jωT})H(e^{jωT})}/(1 − cos ωT), eq. (28) b > KT/2 + |B| for the
    paper's loop; the verdict for the device (its own damping, or device_damping in Ns/m), the
    wall's stability and the passive region."""

def margins(
    loop: Loop,
    wall_stiffness: Optional[float] = None,
    wall_damping: Optional[float] = None,
    *,
    alpha: Optional[float] = None,
    beta: Optional[float] = None,
) -> Margins:
    """Gain (on K, on (K, B)), phase and delay margins of a stable wall on the exact discrete
    loop (Section V), and the critical frequency at the gain-margin boundary."""

def frequency_response(
    loop: Loop,
    wall_stiffness: Optional[float] = None,
    wall_damping: Optional[float] = None,
    omega: Optional[ArrayLike] = None,
    *,
    alpha: Optional[float] = None,
    beta: Optional[float] = None,
) -> FrequencyResponse:
    """The open loop L(e^{jωT}) of the wall at omega (rad/s) or on the grid of `hapstab bode`,
    with every crossing and the margins."""

def root_locus(
    loop: Loop,
    wall_damping: float,
    wall_stiffness: Optional[ArrayLike] = None,
) -> RootLocus:
    """The roots of p(z) at each K (N/m) at damping B (Ns/m), or on `hapstab locus`'s sweep."""
def sweep(
    loop: Loop,
    param: str,
    values: ArrayLike,
    *,
    wall_damping: Optional[float] = None,
    damping_range: Optional[Tuple[float, float]] = None,
) -> Sweep:
    """K_max (stable and passive) with `param` ("delay-time", "arm-stiffness", …) at each value."""
def linear_condition(loop: Loop, *, levels: Sequence[float] = (0.02, 0.05)) -> LinearCondition:
    """The linear condition of the paper's loop: the numbers of `hapstab linear --json`."""
def nyquist_regions(
    delta: float = 0.0,
    d: int = 0,
    *,
    gamma_fraction: float = 1.0,
    steps: int = 4,
    beta_samples: int = 201,
    gamma_samples: int = 41,
) -> NyquistRegions:
    """Section VIII in normalized units: the numbers of `hapstab nyquist --json`."""
def zwidth(loop: Loop, *, table_damping: Optional[Sequence[float]] = None) -> ZWidth:
    """The Z-width: the numbers of `hapstab zwidth --json`."""
    def plot(self, ax: Any = None) -> Any:
        """Draws the result (hapstab.plotting; needs matplotlib) and returns the matplotlib Axes."""
