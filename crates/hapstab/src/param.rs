//! The parameters that errors name.
//!
//! Every [`crate::Error`] about a value names it by a [`Param`]. The message shows its
//! [`Param::label`] ("sampling period T must be > 0 (got 0)"); a front end names the argument
//! the user typed by [`Param::flag`] (the command line), [`Param::keyword`] (the Python
//! package) or [`Param::query`] (the explorer's HTTP API), so that no front end maps error
//! text back to its own names.
//!
//! Most parameters are spelt alike everywhere: `arm_stiffness` in Python and in a query
//! string, `--arm-stiffness` on the command line. Where the front ends differ, the table
//! below says so, e.g. the delay in whole samples is `--delay`, `delay_samples` and `d`.
//! Some parameters are parts of one argument (the cut-off of a velocity estimator is part of
//! `--velocity`), and some are carried by no argument of a front end (None).

use std::fmt;

/// `None` for `-`, else `Some` of the literal.
macro_rules! opt {
    (-) => {
        None
    };
    ($s:literal) => {
        Some($s)
    };
}

/// The enum and its table: `Variant => label, key, flag, keyword, query;`.
macro_rules! params {
    ($($(#[$doc:meta])* $v:ident => $label:literal, $key:literal, $flag:tt, $kw:tt, $query:tt;)*) => {
        /// A parameter of a loop, of a wall or of an analysis, as an error names it.
        ///
        /// See the [module documentation](self) for the names it has in each front end.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Param {
            $($(#[$doc])* $v,)*
        }

        impl Param {
            /// Every parameter, in declaration order.
            pub const ALL: &[Param] = &[$(Param::$v,)*];

            /// The parameter in words, as messages name it: "sampling period T".
            pub const fn label(self) -> &'static str {
                match self {
                    $(Param::$v => $label,)*
                }
            }

            /// A unique identifier in snake_case: the Python keyword and the query parameter
            /// where those name this parameter alone ("arm_stiffness"), else a descriptive
            /// one ("velocity_cutoff", part of `velocity`).
            pub const fn key(self) -> &'static str {
                match self {
                    $(Param::$v => $key,)*
                }
            }

            /// The command-line flag(s) that carry the parameter, as typed ("--arm-stiffness";
            /// "--handle-mass/--arm-mass" for a sum of two), or None.
            pub const fn flag(self) -> Option<&'static str> {
                match self {
                    $(Param::$v => opt!($flag),)*
                }
            }

            /// The Python keyword argument(s) that carry the parameter ("arm_stiffness";
            /// "num, den" for either of two, "handle_mass + arm_mass" for a sum), or None. A
            /// call whose own keyword differs names it itself.
            pub const fn keyword(self) -> Option<&'static str> {
                match self {
                    $(Param::$v => opt!($kw),)*
                }
            }

            /// The query parameter of the explorer's HTTP API that carries the parameter, or
            /// None.
            pub const fn query(self) -> Option<&'static str> {
                match self {
                    $(Param::$v => opt!($query),)*
                }
            }
        }
    };
}

params! {
    // sampling, delay, actuator
    /// Sampling period T in s.
    Period => "sampling period T", "period", "--period", "period", "period";
    /// Delay time t_d = (d + λ)T in s.
    DelayTime => "delay time t_d", "delay_time", "--delay-time", "delay", "delay_time";
    /// Delay d in whole samples (Python: `delay_samples`, or `d` in normalized units; a delay
    /// given in seconds as `delay` sets it too).
    Delay => "delay d", "delay_samples", "--delay", "delay", "d";
    /// Fractional part λ of the delay t_d/T.
    DelayFraction => "delay fraction", "delay_fraction", "--delay-time", "delay", "delay_time";
    /// Actuator time constant τ in s.
    ForceLag => "force lag tau", "force_lag", "--force-lag", "force_lag", "force_lag";

    // the one-mass plant (eq. 1)
    /// Effective mass m = m_L + m_H in kg.
    Mass => "mass m", "mass", "--mass", "mass", -;
    /// Effective damping b = b_L + b_H in Ns/m.
    Damping => "damping b", "damping", "--damping", "damping", -;
    /// Effective stiffness k = k_H in N/m.
    Stiffness => "stiffness k", "stiffness", "--stiffness", "stiffness", -;
    /// Device mass m_L in kg.
    DeviceMass => "device mass m_L", "device_mass", "--device-mass", "device_mass", "device_mass";
    /// Device damping b_L in Ns/m.
    DeviceDamping => "device damping b_L", "device_damping", "--device-damping", "device_damping",
        "device_damping";
    /// Arm mass m_H in kg.
    ArmMass => "arm mass m_H", "arm_mass", "--arm-mass", "arm_mass", "arm_mass";
    /// Arm damping b_H in Ns/m.
    ArmDamping => "arm damping b_H", "arm_damping", "--arm-damping", "arm_damping", "arm_damping";
    /// Arm stiffness k_H in N/m.
    ArmStiffness => "arm stiffness k_H", "arm_stiffness", "--arm-stiffness", "arm_stiffness",
        "arm_stiffness";
    /// An operator given with a plant that cannot include one.
    Operator => "operator", "operator", -, -, -;

    // the two-mass device
    /// Motor-side mass in kg.
    MotorMass => "motor mass", "motor_mass", "--motor-mass", "motor_mass", "motor_mass";
    /// Motor-side damping in Ns/m.
    MotorDamping => "motor damping", "motor_damping", "--motor-damping", "motor_damping",
        "motor_damping";
    /// Handle mass in kg.
    HandleMass => "handle mass", "handle_mass", "--handle-mass", "handle_mass", "handle_mass";
    /// The handle's mass with the arm's, in kg.
    HandleAndArmMass => "handle mass + arm mass", "handle_and_arm_mass",
        "--handle-mass/--arm-mass", "handle_mass + arm_mass", "handle_mass";
    /// Transmission stiffness k_t in N/m.
    TransmissionStiffness => "transmission stiffness", "transmission_stiffness",
        "--transmission-stiffness", "transmission_stiffness", "transmission_stiffness";
    /// Transmission damping b_t in Ns/m.
    TransmissionDamping => "transmission damping", "transmission_damping",
        "--transmission-damping", "transmission_damping", "transmission_damping";

    // a transfer-function plant
    /// The plant's numerator.
    PlantNum => "plant numerator", "plant_num", "--plant-num", "num", "plant_num";
    /// The plant's denominator.
    PlantDen => "plant denominator", "plant_den", "--plant-den", "den", "plant_den";
    /// A coefficient of the plant's numerator.
    PlantNumCoefficient => "plant numerator coefficient", "plant_num_coefficient",
        "--plant-num", "num", "plant_num";
    /// A coefficient of the plant's denominator.
    PlantDenCoefficient => "plant denominator coefficient", "plant_den_coefficient",
        "--plant-den", "den", "plant_den";
    /// The plant's numerator and denominator together.
    PlantTransferFunction => "plant transfer function", "plant_transfer_function",
        "--plant-num/--plant-den", "num, den", -;
    /// The plant's order (its denominator's degree).
    PlantOrder => "plant order", "plant_order", "--plant-den", "den", "plant_den";

    // the velocity estimator
    /// The velocity estimator as a whole.
    Velocity => "velocity estimator", "velocity", "--velocity", "velocity", "estimator";
    /// Cut-off f_c in Hz of the first-order low-pass estimator.
    VelocityCutoff => "velocity low-pass cut-off f_c", "velocity_cutoff", "--velocity",
        "velocity", "estimator";
    /// Window N in samples of the moving-average estimator.
    VelocityWindow => "velocity average window N", "velocity_window", "--velocity", "velocity",
        "estimator";
    /// The estimator's filter, as a discrete system.
    VelocityFilter => "velocity filter", "velocity_filter", "--velocity", "velocity",
        "estimator";
    /// A coefficient of an IIR estimator.
    VelocityFilterCoefficient => "velocity filter coefficient", "velocity_filter_coefficient",
        "--velocity", "velocity", "estimator";
    /// The leading denominator coefficient a0 of an IIR estimator.
    VelocityFilterA0 => "velocity filter a0", "velocity_filter_a0", "--velocity", "velocity",
        "estimator";
    /// The numerator b of an IIR estimator.
    VelocityFilterNumerator => "velocity filter numerator b", "velocity_filter_numerator",
        "--velocity", "velocity", "estimator";
    /// The denominator a of an IIR estimator.
    VelocityFilterDenominator => "velocity filter denominator a", "velocity_filter_denominator",
        "--velocity", "velocity", "estimator";
    /// The length of an IIR estimator's coefficient lists.
    VelocityFilterLength => "velocity filter length", "velocity_filter_length", "--velocity",
        "velocity", "estimator";
    /// Order N of a Butterworth estimator.
    ButterworthOrder => "velocity Butterworth order N", "velocity_butterworth_order",
        "--velocity", "velocity", "estimator";
    /// Cut-off f_c in Hz of a Butterworth estimator.
    ButterworthCutoff => "velocity Butterworth cut-off f_c", "velocity_butterworth_cutoff",
        "--velocity", "velocity", "estimator";
    /// Order N of a Bessel estimator.
    BesselOrder => "velocity Bessel order N", "velocity_bessel_order", "--velocity", "velocity",
        "estimator";
    /// Cut-off f_c in Hz of a Bessel estimator.
    BesselCutoff => "velocity Bessel cut-off f_c", "velocity_bessel_cutoff", "--velocity",
        "velocity", "estimator";
    /// Order N of a critically damped estimator.
    CriticallyDampedOrder => "velocity critically damped order N",
        "velocity_critically_damped_order", "--velocity", "velocity", "estimator";
    /// Cut-off f_c in Hz of a critically damped estimator.
    CriticallyDampedCutoff => "velocity critically damped cut-off f_c",
        "velocity_critically_damped_cutoff", "--velocity", "velocity", "estimator";

    // normalized units (Table I) and the wall
    /// Normalized stiffness γ = kT²/m.
    Gamma => "gamma", "gamma", "--gamma", "gamma", "gamma";
    /// Normalized damping δ = bT/m.
    Delta => "delta", "delta", "--delta", "delta", "delta";
    /// Normalized wall stiffness α = KT²/m.
    Alpha => "alpha", "alpha", "--alpha", "alpha", "alpha";
    /// Normalized wall damping β = BT/m.
    Beta => "beta", "beta", "--beta", "beta", "beta";
    /// Wall stiffness K in N/m.
    WallStiffness => "wall stiffness K", "wall_stiffness", "--wall-stiffness", "wall_stiffness",
        "wall_stiffness";
    /// Wall damping B in Ns/m.
    WallDamping => "wall damping B", "wall_damping", "--wall-damping", "wall_damping",
        "wall_damping";
    /// Wall stiffness a in the loop's wall units.
    WallUnitStiffness => "wall stiffness a", "wall_unit_stiffness", -, -, -;
    /// Wall damping b in the loop's wall units.
    WallUnitDamping => "wall damping b", "wall_unit_damping", -, -, -;
    /// The eq. (11) limit on k_H/m_H in s⁻².
    ArmStiffnessPerMassLimit => "k_H/m_H limit", "arm_stiffness_per_mass_limit", -, -, -;
    /// The eq. (11) limit on b_H/m_H in s⁻¹.
    ArmDampingPerMassLimit => "b_H/m_H limit", "arm_damping_per_mass_limit", -, -, -;
    /// The limit on b_L/m_L in s⁻¹.
    DeviceDampingPerMassLimit => "b_L/m_L limit", "device_damping_per_mass_limit", -, -, -;

    // maps, regions, frequency analyses
    /// The parameter along an axis of a map.
    MapAxis => "axis", "map_axis", "--x/--y", -, -;
    /// The lower end of a map's axis.
    MapAxisStart => "axis lower end", "map_axis_start", "--x/--y", -, -;
    /// The upper end of a map's axis.
    MapAxisEnd => "axis upper end", "map_axis_end", "--x/--y", -, -;
    /// The number of points along a map's axis.
    MapAxisPoints => "axis points", "map_axis_points", "--x/--y", -, -;
    /// The two axes of a map together.
    MapAxes => "map axes", "map_axes", "--x/--y", -, -;
    /// The number of points of a map.
    MapPoints => "map points", "map_points", "--x/--y", "wall_stiffness, wall_damping", -;
    /// The chord tolerance of a stable region, relative to its size.
    RegionTolerance => "region tolerance", "region_tolerance", -, -, -;
    /// The loop as a whole, for an analysis that needs a loop of a certain kind.
    Loop => "loop", "loop", -, "loop", -;
    /// A loop file.
    LoopFile => "loop file", "loop_file", "--loop", "path", "file";
    /// The delay of a loop file.
    LoopFileDelay => "loop.delay", "loop_file_delay", "--loop", "path", "file";
    /// Angular frequencies ω in rad/s.
    Omega => "omega", "omega", -, "omega", -;
    /// An error level of the linear condition, or a probability level.
    Level => "level", "level", "--levels", "levels", -;
    /// Steps of γ of the Nyquist regions.
    Steps => "steps", "steps", "--steps", "steps", -;
    /// The share of γ_N the Nyquist regions span.
    GammaFraction => "gamma fraction", "gamma_fraction", "--gamma-fraction", "gamma_fraction", -;
    /// The lower end of a robust region's γ range.
    GammaLo => "gamma_lo", "gamma_lo", -, -, "gamma_lo";
    /// The upper end of a robust region's γ range.
    GammaHi => "gamma_hi", "gamma_hi", -, -, "gamma_hi";

    // K_max, robust K_max, populations, sweeps
    /// Position resolution Δ at the handle in m (the renderable band).
    PositionResolution => "position resolution", "position_resolution",
        "--position-resolution", "position_resolution", -;
    /// Force noise F_n in N RMS (the renderable band).
    ForceNoise => "force noise", "force_noise", "--force-noise", "force_noise", -;
    /// The box of a robust K_max.
    Box => "box", "box", "--box", "bounds", -;
    /// The lowest mass of a plant box in kg.
    BoxMassMin => "minimum mass", "box_mass_min", "--box-mass", -, -;
    /// The highest mass of a plant box in kg.
    BoxMassMax => "maximum mass", "box_mass_max", "--box-mass", -, -;
    /// The mass range of a plant box.
    BoxMass => "mass range", "box_mass", "--box-mass", -, -;
    /// The lowest damping of a plant box in Ns/m.
    BoxDampingMin => "minimum damping", "box_damping_min", "--box-damping", -, -;
    /// The highest damping of a plant box in Ns/m.
    BoxDampingMax => "maximum damping", "box_damping_max", "--box-damping", -, -;
    /// The damping range of a plant box.
    BoxDamping => "damping range", "box_damping", "--box-damping", -, -;
    /// The lowest stiffness of a plant box in N/m.
    BoxStiffnessMin => "minimum stiffness", "box_stiffness_min", "--box-stiffness", -, -;
    /// The highest stiffness of a plant box in N/m.
    BoxStiffnessMax => "maximum stiffness", "box_stiffness_max", "--box-stiffness", -, -;
    /// The stiffness range of a plant box.
    BoxStiffness => "stiffness range", "box_stiffness", "--box-stiffness", -, -;
    /// The parameter a sweep, a box or a distribution names.
    SweepParameter => "sweep parameter", "sweep_parameter", "--param", "param", -;
    /// A sweep range NAME:START:END:POINTS as a whole.
    SweepRange => "sweep range", "sweep_range", "--param", -, -;
    /// The first value of a sweep.
    SweepStart => "sweep start", "sweep_start", "--param", -, -;
    /// The last value of a sweep.
    SweepEnd => "sweep end", "sweep_end", "--param", -, -;
    /// The number of values of a sweep.
    SweepPoints => "sweep points N", "sweep_points", "--param", -, -;
    /// A population of operators.
    Population => "population", "population", "--dist", "distributions", -;
    /// A parameter's distribution in a population.
    Distribution => "distribution", "distribution", "--dist", "distributions", -;
    /// The number of draws of a population.
    Samples => "samples", "samples", "--samples", "samples", -;

    // simulation
    /// Wall position x_w in m.
    WallPosition => "wall position x_w", "wall_position", "--wall-position", "wall_position", -;
    /// Position quantization q in m (an encoder's step).
    Quantization => "quantization q", "quantization", "--quantization", "quantization", -;
    /// Actuator saturation F_max in N.
    Saturation => "saturation F_max", "saturation", "--saturation", "saturation", -;
    /// Coulomb friction F_c in N.
    CoulombFriction => "Coulomb friction F_c", "coulomb_friction", "--coulomb",
        "coulomb_friction", -;
    /// Static friction F_s in N.
    StaticFriction => "static friction F_s", "static_friction", "--stiction", "static_friction",
        -;
    /// Friction as a whole.
    Friction => "friction", "friction", "--coulomb", "coulomb_friction", -;
    /// A constant human force F_H in N.
    HumanForce => "human force F_H", "human_force", "--push", "human_force", "push";
    /// A human force given sample by sample, in N.
    HumanForceProfile => "human force profile F_H[k]", "human_force_profile", -, "human_force",
        -;
    /// A human force given as a function of time, in N.
    HumanForceFunction => "human force F_H(t)", "human_force_function", -, "human_force", -;
    /// Initial position in m.
    InitialPosition => "initial position", "initial_position", "--initial-position",
        "initial_position", -;
    /// Initial velocity in m/s.
    InitialVelocity => "initial velocity", "initial_velocity", "--initial-velocity",
        "initial_velocity", "velocity";
    /// Duration of a run in s.
    Duration => "duration", "duration", "--duration", "duration", -;
    /// Duration of a run in sampling periods.
    DurationPeriods => "duration / T", "duration_periods", "--duration", "duration", -;
    /// Duration of a run in samples.
    DurationSamples => "duration in samples", "duration_samples", "--duration-samples",
        "samples", "samples";
    /// Longest run in samples (the horizon of a run until it settles).
    MaxSamples => "horizon in samples", "max_samples", "--max-duration-samples", "max_samples",
        -;
    /// Rows of a recorded trace.
    TraceRows => "trace rows", "trace_rows", "--max-rows", "trace_rows", -;
    /// The input that excites a run for identification.
    Excitation => "excitation", "excitation", "--excitation", -, -;
    /// Largest α of the empirical boundary's search.
    AlphaMax => "alpha_max", "alpha_max", "--alpha-max", -, -;
    /// Runs per β of the empirical boundary's grid.
    Grid => "grid", "grid", "--grid", -, -;
    /// Relative tolerance of the empirical boundary's bisection.
    RelTolerance => "rel_tolerance", "rel_tolerance", "--rel-tol", -, -;
    /// Amplitude under which a run counts as stable.
    AmplitudeThreshold => "amplitude threshold", "amplitude_threshold", "--stable-amplitude",
        -, -;
}

impl fmt::Display for Param {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.label())
    }
}

#[cfg(test)]
mod tests {
    use super::Param;
    use std::collections::HashSet;

    #[test]
    fn keys_and_labels_are_unique() {
        let mut keys = HashSet::new();
        let mut labels = HashSet::new();
        for p in Param::ALL {
            assert!(keys.insert(p.key()), "key {} twice", p.key());
            assert!(labels.insert(p.label()), "label {} twice", p.label());
        }
    }

    #[test]
    fn names_are_spelt_as_their_front_ends_spell_them() {
        let snake = |s: &str| {
            s.chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        };
        for p in Param::ALL {
            assert!(snake(p.key()), "{p:?}: key {}", p.key());
            if let Some(q) = p.query() {
                assert!(snake(q), "{p:?}: query {q}");
            }
            if let Some(kw) = p.keyword() {
                for k in kw.split([',', '+']) {
                    assert!(snake(k.trim()), "{p:?}: keyword {kw}");
                }
            }
            if let Some(flag) = p.flag() {
                for f in flag.split('/') {
                    let name = f.strip_prefix("--").unwrap_or_default();
                    assert!(
                        !name.is_empty()
                            && name.chars().all(|c| c.is_ascii_lowercase() || c == '-'),
                        "{p:?}: flag {flag}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_parameter_shows_its_label() {
        assert_eq!(Param::Period.to_string(), "sampling period T");
        assert_eq!(Param::ArmStiffness.flag(), Some("--arm-stiffness"));
        assert_eq!(Param::ArmStiffness.keyword(), Some("arm_stiffness"));
        assert_eq!(Param::Velocity.query(), Some("estimator"));
    }
}
