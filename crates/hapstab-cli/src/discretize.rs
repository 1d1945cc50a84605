//! `hapstab discretize`: the exact discrete loop as coefficients (Section III, eq. 2–9,
//! generalized): the plant H(z) = z^(−k)·num(z)/den(z) behind a zero-order hold with its
//! delay (MATLAB's and python-control's `c2d(sys, T, 'zoh')` with an input delay), the
//! velocity estimator V(z) and the characteristic polynomial p(z) for a wall (K, B).

use anyhow::Result;
use clap::Args;
use hapstab::AffineFamily;
use hapstab::params::Wall;
use hapstab::stability::Analysis;
use hapstab::zoh::DiscreteTf;
use serde::Serialize;

use crate::model::{
    LoopArgs, LoopInput, NON_PAPER_PLANT_FLAGS, ResolvedLoop, WallArgs, print_loop,
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
    /// The same polynomial in w = z − 1, p(1 + w) (descending powers of w), built from the
    /// loop's shifted form; null for a velocity filter too long to shift.
    characteristic_shifted: Option<Vec<f64>>,
    /// The loop's spectral radius (as `check` prints it: roots polished in w = z − 1).
    spectral_radius: f64,
    /// The largest root modulus of `characteristic` itself, as a user's root finder sees it.
    spectral_radius_of_coefficients: Option<f64>,
    /// True when the two radii differ by more than 1e-9: the roots crowd z = 1 and the
    /// z-coefficients have lost digits of them; use `characteristic_shifted`.
    ill_conditioned: bool,
}

/// Radii of the loop and of its z-coefficients further apart than this mark p(z) as
/// ill-conditioned.
const CONDITIONING_TOL: f64 = 1e-9;

/// Runs `hapstab discretize`.
pub fn run(a: &DiscretizeArgs) -> Result<()> {
    let rl = a.lp.resolve(a.wall.normalized())?;
    let dl = rl.lp.discretize()?;
    let fam = AffineFamily::new(&dl);
    let w = resolve_loop_wall(&rl, &fam, &a.wall)?;
    let (wa, wb) = fam.to_units(w.stiffness, w.damping);
    let v = dl.velocity_tf_physical();
    let coeffs = fam.coefficients(wa, wb);
    let radius = Analysis::of_family(&fam, wa, wb)?.spectral_radius;
    let of_coefficients = Analysis::of_poly(&coeffs).ok().map(|an| an.spectral_radius);
    let out = DiscretizeOut {
        input: rl.input(Some(w)),
        plant: dl.plant_tf_physical().into(),
        velocity: VelocityOut {
            num: descending(&v.num),
            den: descending(&v.den),
        },
        characteristic: descending(&coeffs),
        characteristic_shifted: fam.coefficients_shifted(wa, wb).map(|c| descending(&c)),
        spectral_radius: radius,
        spectral_radius_of_coefficients: of_coefficients,
        ill_conditioned: of_coefficients.is_none_or(|r| (r - radius).abs() > CONDITIONING_TOL),
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
        print_loop(&rl.lp);
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
    if o.ill_conditioned {
        print_conditioning(o);
    }
    if units {
        println!("\nSample time: {} seconds", sig(rl.lp.period, TEXT_DIGITS));
    } else {
        println!("\nSample time: 1 (normalized time t/T, Table I)");
    }
}

/// The note printed where the z-coefficients have lost digits of the roots, with p(1 + w).
fn print_conditioning(o: &DiscretizeOut) {
    let shown = |r: Option<f64>| r.map_or("none (the root finder failed)".into(), |r| sig(r, 12));
    println!(
        "\nnote: the roots of these coefficients (rounded to double precision) have spectral \
         radius {}, the loop's is {}: its roots crowd z = 1, where the coefficients in z \
         are ill-conditioned.",
        shown(o.spectral_radius_of_coefficients),
        sig(o.spectral_radius, 12)
    );
    if let Some(w) = &o.characteristic_shifted {
        println!("In w = z − 1 the polynomial keeps them (full precision with --json):\n");
        println!("  p(1 + w) = {}", poly_text(w, "w", TEXT_DIGITS));
    }
}
