//! The `--json` answer of `hapstab kmax --robust`: the box as given, the worst plant and
//! K_max in physical or normalized units.

use anyhow::Result;
use hapstab::paper::nyquist::RobustKmax;
use serde::Serialize;

use crate::output::print_json;

/// The box as given, after defaults: physical (kg, Ns/m, N/m) or normalized (γ, δ).
#[derive(Serialize)]
#[serde(untagged)]
pub(super) enum BoxInput {
    Physical {
        mass: [f64; 2],
        damping: [f64; 2],
        stiffness: [f64; 2],
        period: f64,
        d: usize,
    },
    Normalized {
        gamma: [f64; 2],
        delta: [f64; 2],
        d: usize,
    },
}

#[derive(Serialize)]
pub(super) struct RobustInput {
    #[serde(rename = "box")]
    pub(super) plant_box: BoxInput,
    pub(super) box_samples: usize,
}

/// The plant of the box that limits K_max.
#[derive(Serialize)]
#[serde(untagged)]
pub(super) enum WorstPlant {
    Physical {
        mass: f64,
        damping: f64,
        stiffness: f64,
    },
    Normalized {
        gamma: f64,
        delta: f64,
    },
}

/// `kmax --robust --json` of a physical box (N/m, Ns/m).
#[derive(Serialize)]
pub(super) struct PhysicalOut {
    pub(super) input: RobustInput,
    pub(super) k_max: f64,
    pub(super) b_at_k_max: f64,
    /// Lower end of the robust K interval at that B.
    pub(super) k_min: f64,
    pub(super) worst_plant: WorstPlant,
    /// Linear condition (22) for the worst plant at the same B.
    pub(super) k_linear_worst: f64,
    /// K_max and its B normalized with the smallest mass of the box: K T²/m, B T/m.
    pub(super) normalized_at_min_mass: hapstab::boundary::WallPoint,
    pub(super) plants_sampled: usize,
}

/// `kmax --robust --json` of a normalized box (α, β).
#[derive(Serialize)]
pub(super) struct NormalizedOut {
    pub(super) input: RobustInput,
    pub(super) alpha_max: f64,
    pub(super) beta_at_alpha_max: f64,
    pub(super) alpha_min: f64,
    pub(super) worst_plant: WorstPlant,
    /// Linear condition (23) for the worst plant at the same β.
    pub(super) alpha_linear_worst: f64,
    pub(super) plants_sampled: usize,
}

pub(super) fn json_out(r: &RobustKmax, samples: usize, normalized: bool) -> Result<()> {
    let pb = &r.plant_box;
    let [m, b, k] = r.worst_plant;
    let k_linear_worst = (b + r.damping_at_max) / ((pb.d as f64 + 0.5) * pb.period);
    if normalized {
        let input = RobustInput {
            plant_box: BoxInput::Normalized {
                gamma: pb.stiffness,
                delta: pb.damping,
                d: pb.d,
            },
            box_samples: samples,
        };
        return print_json(&NormalizedOut {
            input,
            alpha_max: r.stiffness_max,
            beta_at_alpha_max: r.damping_at_max,
            alpha_min: r.stiffness_min,
            worst_plant: WorstPlant::Normalized { gamma: k, delta: b },
            alpha_linear_worst: k_linear_worst,
            plants_sampled: r.plants_sampled,
        });
    }
    let input = RobustInput {
        plant_box: BoxInput::Physical {
            mass: pb.mass,
            damping: pb.damping,
            stiffness: pb.stiffness,
            period: pb.period,
            d: pb.d,
        },
        box_samples: samples,
    };
    print_json(&PhysicalOut {
        input,
        k_max: r.stiffness_max,
        b_at_k_max: r.damping_at_max,
        k_min: r.stiffness_min,
        worst_plant: WorstPlant::Physical {
            mass: m,
            damping: b,
            stiffness: k,
        },
        k_linear_worst,
        normalized_at_min_mass: r.normalized_at_min_mass,
        plants_sampled: r.plants_sampled,
    })
}
