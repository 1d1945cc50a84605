//! The loop in words, one line per part, for the text output of the commands.

use hapstab::model::{Loop, PlantModel as LibPlantModel};
use hapstab::params::Wall;

use crate::output::{eng, poly_text, sig};

/// Prints the loop in words ([`describe_loop`]), one line per part.
pub fn print_loop(lp: &Loop) {
    for line in describe_loop(lp) {
        println!("{line}");
    }
}

/// Prints the loop in words and the wall's K and B ([`print_loop`]).
pub fn print_loop_and_wall(lp: &Loop, w: Wall) {
    print_loop(lp);
    println!(
        "wall      K = {}, B = {}",
        eng(w.stiffness, "N/m", 6),
        eng(w.damping, "Ns/m", 6)
    );
}

/// The loop in words, one line per part (for the text output of the commands).
fn describe_loop(lp: &Loop) -> Vec<String> {
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
