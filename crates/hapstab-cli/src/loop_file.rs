//! `--loop FILE`: a saved loop ([`hapstab::loop_spec`]) with the flags given beside it
//! changing its parts.
//!
//! The flags fill in over the file part by part: `--period`, `--delay`/`--delay-time`,
//! `--velocity`, `--force-lag` and the wall flags replace their own part; arm flags
//! (`--arm-*`, `--no-arm`) change the arm of a device held by an arm (a mass-spring-damper
//! that names its operator, or a two-mass device), device flags its device, two-mass flags
//! the two-mass device's parts; any other plant flag (a transfer function, a plant of
//! another kind) replaces the file's plant. Without plant flags the file's plant is taken
//! as it is, bit for bit.

use std::path::Path;

use anyhow::{Context, Result, bail};
use hapstab::Loop;
use hapstab::model::{Plant, PlantModel};
use hapstab::params::{Arm, Effective};
use hapstab_serve::loop_io::remainder;

use crate::model::{LoopArgs, PlantArgs, ResolvedLoop};

/// The loop of `--loop FILE` under the flags of `args` (module doc).
pub fn resolve(args: &LoopArgs, path: &Path, normalized_wall: bool) -> Result<ResolvedLoop> {
    let file = hapstab::loop_spec::load(path)?;
    let mut over = args.clone();
    over.plant.loop_file = None;
    if file.normalized {
        return normalized(&over, &file.lp, file.wall, path);
    }
    if args.plant.normalized_mode() {
        bail!(
            "--gamma/--delta: '{}' holds a physical loop; change its plant with physical flags",
            path.display()
        );
    }
    fill_sampling(&mut over, &file.lp);
    let plant_flags = plant_flags_given(args);
    if plant_flags {
        fill_plant(&mut over, &file.lp.plant);
    }
    let base = (!plant_flags).then_some(&file.lp.plant);
    let mut rl = over
        .resolve_over(normalized_wall, base)
        .with_context(|| format!("--loop {}", path.display()))?;
    rl.wall = file.wall;
    Ok(rl)
}

/// A normalized paper loop from the file: --gamma, --delta and --delay change it.
fn normalized(
    over: &LoopArgs,
    lp: &Loop,
    wall: Option<hapstab::Wall>,
    path: &Path,
) -> Result<ResolvedLoop> {
    if over.any_physical() {
        bail!(
            "--loop {}: the file holds the paper's normalized loop (γ, δ, d); change it with --gamma, --delta, --delay",
            path.display()
        );
    }
    let Some(pp) = lp.paper_view() else {
        bail!("--loop {}: not the paper's normalized loop", path.display());
    };
    let mut o = over.clone();
    o.plant.gamma = Some(o.plant.gamma.unwrap_or(pp.gamma));
    o.plant.delta = Some(o.plant.delta.unwrap_or(pp.delta));
    o.plant.delay = Some(o.plant.delay.unwrap_or(lp.delay.samples as f64));
    let mut rl = o.resolve_over(true, None)?;
    rl.wall = wall;
    Ok(rl)
}

/// Period, delay, velocity and lag from the file where no flag gives them.
fn fill_sampling(o: &mut LoopArgs, lp: &Loop) {
    o.plant.period.get_or_insert(lp.period);
    if o.plant.delay.is_none() && o.plant.delay_time.is_none() {
        o.file_delay = Some(lp.delay);
    }
    o.velocity.get_or_insert_with(|| lp.velocity.clone());
    o.force_lag.get_or_insert(lp.plant.force_lag);
}

/// True when a flag describes the plant (its model, device or arm).
fn plant_flags_given(a: &LoopArgs) -> bool {
    let p = &a.plant;
    a.plant_num.is_some()
        || a.plant_den.is_some()
        || a.two_mass_given()
        || p.mass.is_some()
        || p.damping.is_some()
        || p.stiffness.is_some()
        || device_or_arm_given(p)
}

fn device_or_arm_given(p: &PlantArgs) -> bool {
    p.device_mass.is_some()
        || p.device_damping.is_some()
        || p.arm_mass.is_some()
        || p.arm_damping.is_some()
        || p.arm_stiffness.is_some()
        || p.no_arm
}

/// The file's plant as defaults of the plant flags of its own kind (module doc).
fn fill_plant(o: &mut LoopArgs, plant: &Plant) {
    let tf = o.plant_num.is_some() || o.plant_den.is_some();
    let lumped = o.plant.mass.is_some() || o.plant.damping.is_some() || o.plant.stiffness.is_some();
    match (&plant.model, plant.operator) {
        (PlantModel::TwoMass(t), _)
            if !tf
                && !lumped
                && o.plant.device_mass.is_none()
                && o.plant.device_damping.is_none() =>
        {
            o.motor_mass.get_or_insert(t.motor_mass);
            o.motor_damping.get_or_insert(t.motor_damping);
            o.handle_mass.get_or_insert(t.handle_mass);
            o.transmission_stiffness
                .get_or_insert(t.transmission_stiffness);
            o.transmission_damping.get_or_insert(t.transmission_damping);
            fill_arm(&mut o.plant, t.arm);
        }
        (PlantModel::MassSpringDamper(e), arm) if !tf && !o.two_mass_given() => {
            fill_mass_spring_damper(&mut o.plant, e, arm)
        }
        _ => {}
    }
}

/// A mass-spring-damper as defaults of the paper's plant flags: a device and its arm, or
/// (without a named arm, or with --mass/--damping/--stiffness) m, b and k.
fn fill_mass_spring_damper(p: &mut PlantArgs, e: &Effective, arm: Option<Arm>) {
    let lumped = p.mass.is_some() || p.damping.is_some() || p.stiffness.is_some();
    match arm {
        Some(arm) if !lumped => {
            // the device is what the arm leaves of eq. (1)'s m and b
            p.device_mass.get_or_insert(remainder(e.mass, arm.mass));
            p.device_damping
                .get_or_insert(remainder(e.damping, arm.damping));
            fill_arm(p, arm);
        }
        _ => fill_lumped(p, e),
    }
}

/// The file's arm where no arm flag (and no --no-arm) changes it.
fn fill_arm(p: &mut PlantArgs, arm: Arm) {
    if p.no_arm {
        return;
    }
    p.arm_mass.get_or_insert(arm.mass);
    p.arm_damping.get_or_insert(arm.damping);
    p.arm_stiffness.get_or_insert(arm.stiffness);
}

/// A mass-spring-damper without a named arm: its m, b, k as --mass, --damping, --stiffness,
/// unless device or arm flags split it (then its m and b are the device's).
fn fill_lumped(p: &mut PlantArgs, e: &Effective) {
    let lumped = p.mass.is_some() || p.damping.is_some() || p.stiffness.is_some();
    if lumped || !device_or_arm_given(p) {
        p.mass.get_or_insert(e.mass);
        p.damping.get_or_insert(e.damping);
        p.stiffness.get_or_insert(e.stiffness);
        return;
    }
    p.device_mass.get_or_insert(e.mass);
    p.device_damping.get_or_insert(e.damping);
    // the file has no arm: arm flags add one, the rest of it zero
    fill_arm(p, Arm::NONE);
}

/// The paper's plant flags with a --loop file's loop filled in, for the commands defined on
/// the paper's loop only (a mass-spring-damper, backward difference, whole-sample delay, no
/// lag); other loops are refused in one line.
pub fn paper_plant(p: &PlantArgs, what: &str) -> Result<PlantArgs> {
    let Some(path) = &p.loop_file else {
        return Ok(p.clone());
    };
    let file = hapstab::loop_spec::load(path)?;
    let mut o = p.clone();
    o.loop_file = None;
    let Some(pp) = file.lp.paper_view() else {
        bail!(
            "--loop {}: {what} is defined for the paper's loop only (a mass-spring-damper, backward-difference velocity, whole-sample delay, no actuator lag)",
            path.display()
        );
    };
    if o.delay.is_none() && o.delay_time.is_none() {
        o.delay = Some(file.lp.delay.samples as f64);
    }
    if file.normalized {
        o.gamma.get_or_insert(pp.gamma);
        o.delta.get_or_insert(pp.delta);
        return Ok(o);
    }
    o.period.get_or_insert(file.lp.period);
    if let PlantModel::MassSpringDamper(e) = &file.lp.plant.model {
        fill_mass_spring_damper(&mut o, e, file.lp.plant.operator);
    }
    Ok(o)
}
