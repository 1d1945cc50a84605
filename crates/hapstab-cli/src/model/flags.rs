//! The flag-name lists the argument structs conflict on (clap's `conflicts_with_all`).

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

/// A transfer-function plant replaces every other plant description.
pub(super) const TF_CONFLICTS: [&str; 16] = [
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
pub(super) const TWO_MASS_CONFLICTS: [&str; 7] = [
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
