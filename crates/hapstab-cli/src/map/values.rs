//! The grid of `hapstab map` computed: over the paper's normalized loop or a loop's wall (K, B).

use anyhow::{Result, bail};
use hapstab::Normalized;
use hapstab::map::{Axis, MapKind, wall_map_physical};
use hapstab::paper::map::{MapSpec, compute_map};

use super::axes::{Grid, Name};
use super::cost::check_budget;
use super::{MapArgs, Values, map_bar};
use crate::model::LoopInput;
use hapstab::map::stable_share;

pub(super) fn normalized_map(a: &MapArgs, x: Grid, y: Grid, kind: MapKind) -> Result<Values> {
    if a.lp.any_physical() {
        bail!(
            "maps over alpha, beta, gamma, delta are of the paper's normalized loop; for a physical loop grid --x K:LO:HI:N --y B:LO:HI:N"
        );
    }
    let p = &crate::loop_file::paper_plant(&a.lp.plant, "a map over alpha, beta, gamma, delta")?;
    if p.any_physical() {
        bail!(
            "maps over alpha, beta, gamma, delta are of the paper's normalized loop; --loop holds a physical loop: grid --x K:LO:HI:N --y B:LO:HI:N"
        );
    }
    let d = crate::model::delay_samples(p.delay.unwrap_or(0.0))?;
    let base = Normalized::new(
        a.alpha.unwrap_or(0.0),
        a.beta.unwrap_or(0.0),
        p.gamma.unwrap_or(0.0),
        p.delta.unwrap_or(0.0),
        d,
    )?;
    let spec = MapSpec::new(x.range, y.range, base)?;
    check_budget(
        a,
        (x, y),
        (d + 3, spec.plants()),
        1.0,
        ("--delay", &d.to_string()),
    )?;
    let bar = map_bar(a, x, y, d + 3);
    let m = compute_map(&spec, kind, &bar.stage(0))?;
    Ok(Values {
        stable: m.stable,
        radius: m.radius,
        loop_line: normalized_line(base, (x.name, y.name))?,
        input: LoopInput::Normalized {
            gamma: base.gamma,
            delta: base.delta,
            d,
            alpha: Some(base.alpha),
            beta: Some(base.beta),
        },
    })
}

/// The fixed parameters of a normalized map (those of α, β, γ, δ that are no axis), then the
/// rest of the paper's loop ([`crate::wall_plot::loop_line_without`] its plant).
pub(super) fn normalized_line(base: Normalized, axes: (Name, Name)) -> Result<String> {
    let on_axis = |a: Axis| axes.0 == Name::Normalized(a) || axes.1 == Name::Normalized(a);
    let mut parts: Vec<String> = [
        (Axis::Alpha, "α", base.alpha),
        (Axis::Beta, "β", base.beta),
        (Axis::Gamma, "γ", base.gamma),
        (Axis::Delta, "δ", base.delta),
    ]
    .into_iter()
    .filter(|(a, _, _)| !on_axis(*a))
    .map(|(_, n, v)| format!("{n} = {}", crate::output::sig(v, 4)))
    .collect();
    let pp = hapstab::PlantParams {
        gamma: base.gamma,
        delta: base.delta,
    };
    let rl = crate::model::ResolvedLoop {
        lp: hapstab::model::Loop::normalized(pp, base.d)?,
        normalized: true,
        wall: None,
    };
    use crate::wall_plot::Part;
    parts.push(crate::wall_plot::loop_line_without(&rl, &[Part::Plant]));
    Ok(parts.join(", "))
}

/// The map of a loop's wall: K along x and B along y, converted to the family's wall units.
pub(super) fn loop_map(a: &MapArgs, x: Grid, y: Grid, kind: MapKind) -> Result<Values> {
    if a.lp.plant.normalized_mode() {
        bail!("K and B axes map a physical loop; with --gamma/--delta grid alpha and beta");
    }
    let rl = a.lp.resolve(false)?;
    let sys = rl.system()?;
    let fam = sys.family();
    let n = fam.degree();
    let degree = crate::budget::degree_drivers(&a.lp, &rl.lp)
        .into_iter()
        .max_by(|p, q| p.factor.total_cmp(&q.factor))
        .map(|d| (d.flag, d.value));
    let (flag, value) = degree.unwrap_or(("--delay", "0".into()));
    let (a_lo, b_lo) = fam.to_units(x.range.lo, y.range.lo);
    let (a_hi, b_hi) = fam.to_units(x.range.hi, y.range.hi);
    let stable = stable_share(fam, (a_lo, a_hi), (b_lo, b_hi));
    check_budget(a, (x, y), (n, 1), stable, (flag, &value))?;
    let bar = map_bar(a, x, y, n);
    let m = wall_map_physical(
        fam,
        ((x.range.lo, x.range.hi), x.range.n),
        ((y.range.lo, y.range.hi), y.range.n),
        kind,
        &bar.stage(0),
    )?;
    Ok(Values {
        stable: m.stable,
        radius: m.radius,
        loop_line: crate::wall_plot::loop_line(&rl),
        input: rl.input(None),
    })
}
