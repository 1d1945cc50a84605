//! `hapstab passivity`: the device damping a wall requires to be passive (Colgate–Schenkel;
//! eq. 28 for the paper's loop, Section VIII), whether the device has it, and the passive
//! region of the device beside the wall's stability.

use anyhow::{Result, bail};

use crate::passivity_quantized::{
    QuantizationArgs, QuantizedInput, QuantizedOut, quantized_section,
};
use clap::Args;
use hapstab::AffineFamily;
use hapstab::params::Wall;
use hapstab::passivity::{
    DeviceDamping, PassiveRegion, Passivity, PassivityVerdict, SampledWall, passive_region,
    passivity_with,
};
use serde::Serialize;

use crate::model::{
    LoopArgs, LoopInput, NON_PAPER_PLANT_FLAGS, ResolvedLoop, WallArgs, describe_loop,
    resolve_loop_wall,
};
use crate::output::{eng, print_json, sig};
use hapstab::loop_analysis::{analysis, wall_units};

/// Arguments of `hapstab passivity`.
#[derive(Args, Debug)]
#[command(mut_arg("alpha", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
#[command(mut_arg("beta", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
pub struct PassivityArgs {
    #[command(flatten)]
    lp: LoopArgs,
    #[command(flatten)]
    wall: WallArgs,
    #[command(flatten)]
    quantized: QuantizationArgs,
    /// Print one JSON object instead of text (b_required in Ns/m; δ for a normalized plant).
    #[arg(long)]
    json: bool,
}

/// The passive region in the output: its largest stiffness and its polygon.
#[derive(Serialize)]
struct RegionOut {
    k_max: f64,
    b_at_k_max: f64,
    area: f64,
    bounded: bool,
    /// Counter-clockwise vertices [K, B].
    vertices: Vec<[f64; 2]>,
}

#[derive(Serialize)]
struct PassivityOut {
    input: LoopInput,
    /// The device damping the wall requires, Ns/m (δ for a normalized plant).
    b_required: f64,
    /// Where the requirement binds, Hz (cycles per sample for a normalized plant).
    binding_frequency_hz: f64,
    /// The same as θ = ωT in [0, π].
    binding_theta: f64,
    /// The wall's static stiffness K + B·V(1), N/m (must be >= 0).
    dc_stiffness: f64,
    /// The device's own damping b_L, the arm's excluded (null when the argument does not
    /// apply): passivity towards any passive operator.
    device_damping: Option<f64>,
    /// The paper's eq. (28) read with the effective damping b = b_L + b_H of eq. (1), the arm
    /// included (null when the plant names no arm): passivity towards this operator only.
    #[serde(skip_serializing_if = "Option::is_none")]
    effective_damping: Option<f64>,
    /// The verdict against the effective damping.
    #[serde(skip_serializing_if = "Option::is_none")]
    effective_verdict: Option<PassivityVerdict>,
    /// True when b > b_required and the static stiffness is >= 0; null when not applicable.
    meets: Option<bool>,
    verdict: PassivityVerdict,
    /// Why the verdict is not applicable.
    #[serde(skip_serializing_if = "Option::is_none")]
    note: Option<String>,
    /// The wall's stability (Schur–Cohn), to read beside the passivity verdict.
    stable: bool,
    /// The passive region for the device's damping (null when not applicable).
    passive_region: Option<RegionOut>,
    /// Abbott & Okamura's quantized-spring conditions (with --quantization and --coulomb).
    #[serde(skip_serializing_if = "Option::is_none")]
    quantized: Option<QuantizedOut>,
}

/// Runs `hapstab passivity`.
pub fn run(a: &PassivityArgs) -> Result<()> {
    let rl = a.lp.resolve(a.wall.normalized())?;
    let fam = AffineFamily::of_loop(&rl.lp)?;
    let w = resolve_loop_wall(&rl, &fam, &a.wall)?;
    let n = fam.degree();
    let cost = hapstab::limits::passivity_cost(n, hapstab::limits::core_degree(&fam))
        .then(hapstab::limits::roots_cost(n));
    crate::budget::check_loop(&a.lp, &rl.lp, cost, "the passive region")?;
    let sw = SampledWall::new(&rl.lp)?;
    let p = passivity_with(&sw, &rl.lp, w);
    let units = wall_units(&rl.lp, &fam, w)?;
    let stable = analysis(&rl.lp, &fam, units)?.verdict == hapstab::stability::Verdict::Stable;
    let region = match &p.device {
        DeviceDamping::Known { damping } => Some(passive_region(&sw, *damping)?),
        DeviceDamping::NotApplicable { .. } => None,
    };
    let quantized = quantized(a, &rl, w, &p)?;
    let mut out = output(&rl, &p, stable, region.as_ref());
    out.quantized = quantized.as_ref().map(|(o, _)| o.clone());
    if a.json {
        return print_json(&out);
    }
    print_text(&rl, w, &out);
    for line in quantized.iter().flat_map(|(_, lines)| lines) {
        println!("quantized   {line}");
    }
    Ok(())
}

/// The quantized-spring section, for a physical loop whose device damping is known.
fn quantized(
    a: &PassivityArgs,
    rl: &ResolvedLoop,
    w: Wall,
    p: &Passivity,
) -> Result<Option<(QuantizedOut, Vec<String>)>> {
    if a.quantized.quantization.is_none() && a.quantized.coulomb.is_none() {
        return Ok(None);
    }
    if rl.normalized {
        bail!("--quantization and --coulomb need a physical loop (Δ in m, f_c in N)");
    }
    let DeviceDamping::Known { damping } = &p.device else {
        bail!("--quantization and --coulomb need a device damper (not applicable to this plant)");
    };
    quantized_section(
        &a.quantized,
        QuantizedInput {
            stiffness: w.stiffness,
            damping: w.damping,
            period: rl.lp.period,
            delay: rl.lp.delay.samples,
            device_damping: *damping,
        },
    )
}

fn output(
    rl: &ResolvedLoop,
    p: &Passivity,
    stable: bool,
    region: Option<&PassiveRegion>,
) -> PassivityOut {
    let (device_damping, note) = match &p.device {
        DeviceDamping::Known { damping } => (Some(*damping), None),
        DeviceDamping::NotApplicable { reason } => (None, Some(reason.clone())),
    };
    PassivityOut {
        input: rl.input(Some(p.wall)),
        b_required: p.requirement.b_required,
        binding_frequency_hz: p.requirement.frequency_hz,
        binding_theta: p.requirement.theta,
        dc_stiffness: p.dc_stiffness,
        device_damping,
        effective_damping: p.with_arm.map(|a| a.damping),
        effective_verdict: p.with_arm.map(|a| a.verdict),
        meets: match p.verdict {
            PassivityVerdict::NotApplicable => None,
            v => Some(v == PassivityVerdict::Passive),
        },
        verdict: p.verdict,
        note,
        stable,
        passive_region: region.map(|r| RegionOut {
            k_max: r.k_max,
            b_at_k_max: r.b_at_k_max,
            area: r.area,
            bounded: r.bounded,
            vertices: r
                .vertices
                .iter()
                .map(|v| [v.stiffness, v.damping])
                .collect(),
        }),
        quantized: None,
    }
}

fn print_text(rl: &ResolvedLoop, w: Wall, o: &PassivityOut) {
    let (k_unit, b_unit, f_unit) = if rl.normalized {
        ("", "", "cycles/sample")
    } else {
        ("N/m", "Ns/m", "Hz")
    };
    let num = |x: f64, unit: &str| {
        if unit.is_empty() {
            sig(x, 6)
        } else {
            eng(x, unit, 6)
        }
    };
    if !rl.normalized {
        for line in describe_loop(&rl.lp) {
            println!("{line}");
        }
    }
    let (what, k, b, area_unit) = if rl.normalized {
        ("δ", "α", "β", "")
    } else {
        ("b", "K", "B", " N²·s/m²")
    };
    println!(
        "wall        {k} = {}, {b} = {}",
        num(w.stiffness, k_unit),
        num(w.damping, b_unit)
    );
    println!(
        "required    {what} > {} (Colgate–Schenkel; binds at {} {f_unit}, ωT = {})",
        num(o.b_required, b_unit),
        sig(o.binding_frequency_hz, 6),
        sig(o.binding_theta, 6)
    );
    println!("passivity   {}", verdict_text(o, what, b_unit, &num));
    if let (Some(b), Some(v)) = (o.effective_damping, o.effective_verdict) {
        println!(
            "with arm    {} by eq. (28) with the arm's damping counted (b = b_L + b_H = {}): \
             towards this operator only, not any passive operator",
            verdict_word(v),
            num(b, b_unit)
        );
    }
    let stable = if o.stable { "STABLE" } else { "NOT STABLE" };
    let both = match (o.stable, o.meets) {
        (true, Some(false)) => " (stable but not passive)",
        (false, Some(true)) => " (passive but not asymptotically stable)",
        _ => "",
    };
    println!("stability   {stable}{both}");
    if let Some(r) = &o.passive_region {
        println!(
            "passive     {k}_max = {} at {b} = {}; region area {}{area_unit} ({} vertices)",
            num(r.k_max, k_unit),
            num(r.b_at_k_max, b_unit),
            sig(r.area, 6),
            r.vertices.len()
        );
    }
}

fn verdict_text(
    o: &PassivityOut,
    what: &str,
    b_unit: &str,
    num: &dyn Fn(f64, &str) -> String,
) -> String {
    let Some(b) = o.device_damping else {
        return format!(
            "not applicable: {}",
            o.note.as_deref().unwrap_or("no device damper")
        );
    };
    let own = if o.effective_damping.is_some() {
        format!("device's own {what}_L")
    } else {
        format!("device {what}")
    };
    let have = format!("{own} = {}", num(b, b_unit));
    match o.verdict {
        PassivityVerdict::Passive => format!("PASSIVE ({have})"),
        PassivityVerdict::Boundary => format!("ON THE BOUNDARY ({have}, equal to the requirement)"),
        PassivityVerdict::NotPassive if o.dc_stiffness < 0.0 => format!(
            "NOT PASSIVE ({have}; the wall's static stiffness {} is negative)",
            sig(o.dc_stiffness, 6)
        ),
        _ => format!(
            "NOT PASSIVE ({have}, {} short)",
            num(o.b_required - b, b_unit)
        ),
    }
}

fn verdict_word(v: PassivityVerdict) -> &'static str {
    match v {
        PassivityVerdict::Passive => "PASSIVE",
        PassivityVerdict::Boundary => "ON THE BOUNDARY",
        PassivityVerdict::NotPassive => "NOT PASSIVE",
        PassivityVerdict::NotApplicable => "NOT APPLICABLE",
    }
}
