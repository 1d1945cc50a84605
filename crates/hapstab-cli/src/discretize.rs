//! `hapstab discretize`: the exact discrete loop as coefficients (Section III, eq. 2–9,
//! generalized): the plant H(z) = z^(−k)·num(z)/den(z) behind a zero-order hold with its
//! delay (MATLAB's and python-control's `c2d(sys, T, 'zoh')` with an input delay), the
//! velocity estimator V(z) and the characteristic polynomial p(z) for a wall (K, B).

use anyhow::Result;
use clap::Args;
use hapstab::AffineFamily;
use hapstab::params::Wall;
use hapstab::zoh::DiscreteTf;
use serde::Serialize;

use crate::model::{
    LoopArgs, LoopInput, NON_PAPER_PLANT_FLAGS, ResolvedLoop, WallArgs, describe_loop,
    resolve_loop_wall,
};
use crate::output::{descending, poly_text, print_json, sig};

/// Significant digits of the coefficients in the text output.
const TEXT_DIGITS: usize = 6;

/// Arguments of `hapstab discretize`.
#[derive(Args, Debug)]
#[command(mut_arg("alpha", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
#[command(mut_arg("beta", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
pub struct DiscretizeArgs {
    #[command(flatten)]
    lp: LoopArgs,
    #[command(flatten)]
    wall: WallArgs,
    /// Print one JSON object instead of text (coefficients in descending powers of z).
    #[arg(long)]
    json: bool,
}

/// A discrete transfer function z^(−delay)·num(z)/den(z), descending powers of z.
#[derive(Serialize)]
struct TfOut {
    num: Vec<f64>,
    den: Vec<f64>,
    delay: usize,
}

impl From<DiscreteTf> for TfOut {
    fn from(tf: DiscreteTf) -> Self {
        Self {
            num: descending(&tf.num),
            den: descending(&tf.den),
            delay: tf.delay,
        }
    }
}

/// The velocity filter V(z) = num(z)/den(z), descending powers of z.
#[derive(Serialize)]
struct VelocityOut {
    num: Vec<f64>,
    den: Vec<f64>,
}

#[derive(Serialize)]
struct DiscretizeOut {
    input: LoopInput,
    /// H(z) from force (N) to position (m).
    plant: TfOut,
    /// V(z) from position (m) to velocity (m/s).
    velocity: VelocityOut,
    /// Monic p(z) = z^k·den·Vd + num·(K·Vd + B·Vn) of the closed loop (descending).
    characteristic: Vec<f64>,
}

/// Runs `hapstab discretize`.
pub fn run(a: &DiscretizeArgs) -> Result<()> {
    let rl = a.lp.resolve(a.wall.normalized())?;
    let dl = rl.lp.discretize()?;
    let fam = AffineFamily::new(&dl);
    let w = resolve_loop_wall(&rl, &fam, &a.wall)?;
    let (wa, wb) = fam.to_units(w.stiffness, w.damping);
    let v = dl.velocity_tf_physical();
    let out = DiscretizeOut {
        input: LoopInput::new(&rl, Some(w)),
        plant: dl.plant_tf_physical().into(),
        velocity: VelocityOut {
            num: descending(&v.num),
            den: descending(&v.den),
        },
        characteristic: descending(&fam.coefficients(wa, wb)),
    };
    if a.json {
        return print_json(&out);
    }
    print_text(&rl, w, &out);
    Ok(())
}

/// MATLAB's display of a ratio: numerator over a rule over denominator, centred, with an
/// optional prefix (the delay) on the rule's line.
fn fraction(prefix: &str, num: &str, den: &str) -> [String; 3] {
    let width = num.chars().count().max(den.chars().count());
    let pad = " ".repeat(prefix.chars().count());
    let centre = |s: &str| {
        let left = (width - s.chars().count()) / 2;
        format!("{pad}{}{s}", " ".repeat(left))
    };
    [
        centre(num),
        format!("{prefix}{}", "-".repeat(width)),
        centre(den),
    ]
}

fn print_text(rl: &ResolvedLoop, w: Wall, o: &DiscretizeOut) {
    let units = !rl.normalized;
    if units {
        for line in describe_loop(&rl.lp) {
            println!("{line}");
        }
    }
    let p = &o.plant;
    let prefix = if p.delay > 0 {
        format!("  z^(-{}) * ", p.delay)
    } else {
        "  ".into()
    };
    let (force, position) = if units { (" (N)", " (m)") } else { ("", "") };
    println!("\nplant H(z) from force{force} to position{position}:\n");
    let num = poly_text(&p.num, "z", TEXT_DIGITS);
    let den = poly_text(&p.den, "z", TEXT_DIGITS);
    for line in fraction(&prefix, &num, &den) {
        println!("{line}");
    }
    let speed = if units { " (m/s)" } else { "" };
    println!("\nvelocity estimator V(z) from position{position} to velocity{speed}:\n");
    let vnum = poly_text(&o.velocity.num, "z", TEXT_DIGITS);
    let vden = poly_text(&o.velocity.den, "z", TEXT_DIGITS);
    for line in fraction("  ", &vnum, &vden) {
        println!("{line}");
    }
    let (k, b) = if units {
        (
            format!("K = {} N/m", sig(w.stiffness, TEXT_DIGITS)),
            format!("B = {} Ns/m", sig(w.damping, TEXT_DIGITS)),
        )
    } else {
        (
            format!("α = {}", sig(w.stiffness, TEXT_DIGITS)),
            format!("β = {}", sig(w.damping, TEXT_DIGITS)),
        )
    };
    println!("\ncharacteristic polynomial for {k}, {b}:\n");
    println!(
        "  p(z) = {}",
        poly_text(&o.characteristic, "z", TEXT_DIGITS)
    );
    if units {
        println!("\nSample time: {} seconds", sig(rl.lp.period, TEXT_DIGITS));
    } else {
        println!("\nSample time: 1 (normalized time t/T, Table I)");
    }
}
