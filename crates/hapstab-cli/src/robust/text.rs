//! The text answer of `hapstab kmax --robust`.

use hapstab::paper::nyquist::RobustKmax;

use crate::output::{eng, sig};

pub(super) fn print_text(r: &RobustKmax, normalized: bool) {
    let pb = &r.plant_box;
    let [m, b, k] = r.worst_plant;
    let k_linear_worst = (b + r.damping_at_max) / ((pb.d as f64 + 0.5) * pb.period);
    if normalized {
        println!(
            "box         γ ∈ [{}, {}], δ ∈ [{}, {}], d = {} ({} plants sampled)",
            sig(pb.stiffness[0], 6),
            sig(pb.stiffness[1], 6),
            sig(pb.damping[0], 6),
            sig(pb.damping[1], 6),
            pb.d,
            r.plants_sampled
        );
        println!(
            "robust      α_max = {} at β = {} (limited by γ = {}, δ = {})",
            sig(r.stiffness_max, 6),
            sig(r.damping_at_max, 6),
            sig(k, 6),
            sig(b, 6)
        );
        println!(
            "linear      (23) for that plant at the same β: α < {}",
            sig(k_linear_worst, 6)
        );
    } else {
        println!(
            "box         m ∈ [{}, {}], b ∈ [{}, {}], k ∈ [{}, {}]; T = {}, d = {} ({} plants sampled)",
            eng(pb.mass[0], "kg", 6),
            eng(pb.mass[1], "kg", 6),
            eng(pb.damping[0], "Ns/m", 6),
            eng(pb.damping[1], "Ns/m", 6),
            eng(pb.stiffness[0], "N/m", 6),
            eng(pb.stiffness[1], "N/m", 6),
            eng(pb.period, "s", 6),
            pb.d,
            r.plants_sampled
        );
        println!(
            "robust      K_max = {} at B = {}, stable for every plant of the box",
            eng(r.stiffness_max, "N/m", 6),
            eng(r.damping_at_max, "Ns/m", 6)
        );
        println!(
            "            limited by m = {}, b = {}, k = {}",
            eng(m, "kg", 6),
            eng(b, "Ns/m", 6),
            eng(k, "N/m", 6)
        );
        println!(
            "linear      (22) for that plant at the same B: K < {}",
            eng(k_linear_worst, "N/m", 6)
        );
    }
}
