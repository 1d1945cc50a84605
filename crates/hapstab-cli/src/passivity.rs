//! `hapstab passivity`: the device damping a wall requires to be passive (Colgate–Schenkel;
//! eq. 28 for the paper's loop, Section VIII), whether the device has it, and the passive
//! region of the device beside the wall's stability.

use anyhow::{Result, bail};

use crate::passivity_quantized::{
    QuantizationArgs, QuantizedInput, QuantizedOut, quantized_section,
};
use clap::Args;

use hapstab::answer::{PassivityAnswer, passivity_answer};
use hapstab::params::Wall;
use hapstab::passivity::{DeviceDamping, Passivity, PassivityVerdict};
use serde::Serialize;

use crate::model::{
    LoopArgs, NON_PAPER_PLANT_FLAGS, ResolvedLoop, WallArgs, print_loop, resolve_loop_wall,
};
use crate::output::{eng, print_json, sig};

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

#[derive(Serialize)]
struct PassivityOut {
    /// The passivity answer, as the explorer's `/api/passivity` gives it.
    #[serde(flatten)]
    answer: PassivityAnswer,
    /// Abbott & Okamura's quantized-spring conditions (with --quantization and --coulomb).
    #[serde(skip_serializing_if = "Option::is_none")]
    quantized: Option<QuantizedOut>,
}

/// Runs `hapstab passivity`.
pub fn run(a: &PassivityArgs) -> Result<()> {
    let rl = a.lp.resolve(a.wall.normalized())?;
    let sys = rl.system()?;
    let fam = sys.family();
    let w = resolve_loop_wall(&rl, fam, &a.wall)?;
    let n = fam.degree();
    let cost = hapstab::limits::passivity_cost(n, hapstab::limits::core_degree(fam))
        .then(hapstab::limits::roots_cost(n));
    crate::budget::check_loop(&a.lp, &rl.lp, cost, "the passive region")?;
    let (answer, p) = passivity_answer(&sys, rl.normalized, w)?;
    let quantized = quantized(a, &rl, w, &p)?;
    let out = PassivityOut {
        answer,
        quantized: quantized.as_ref().map(|(o, _)| o.clone()),
    };
    if a.json {
        return print_json(&out);
    }
    print_text(&rl, w, &out.answer);
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

fn print_text(rl: &ResolvedLoop, w: Wall, o: &PassivityAnswer) {
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
        print_loop(&rl.lp);
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
    o: &PassivityAnswer,
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
