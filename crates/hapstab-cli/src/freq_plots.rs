//! `hapstab bode` and `hapstab nyquist-plot`: the open loop L(e^{jωT}) of a wall on any loop
//! ([`hapstab::freqresp`]) as a Bode plot (magnitude in dB and phase in degrees over a log
//! frequency axis in Hz up to the Nyquist frequency) or as a Nyquist plot (L in the complex
//! plane with −1, the unit circle and min |1 + L|), with the margins of `check` marked; a CSV
//! of the curve and a JSON of everything on request.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::freqresp::{Closest, FrequencyResponse, Mark, frequency_response};
use hapstab::margins::CrossingKind;
use hapstab::params::Wall;
use serde::Serialize;

use crate::model::{
    LoopArgs, LoopInput, NON_PAPER_PLANT_FLAGS, ResolvedLoop, WallArgs, print_loop_and_wall,
    resolve_loop_wall,
};
use crate::output::{csv_num, eng, print_json, sig};
use crate::wall_plot::files_text;

/// Arguments of `hapstab bode` and `hapstab nyquist-plot`.
#[derive(Args, Debug)]
#[command(mut_arg("alpha", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
#[command(mut_arg("beta", |a| a.conflicts_with_all(NON_PAPER_PLANT_FLAGS)))]
pub struct FreqArgs {
    #[command(flatten)]
    lp: LoopArgs,
    #[command(flatten)]
    wall: WallArgs,
    /// Draw the plot to FILE: SVG or PNG by its extension, both FILE.svg and FILE.png for
    /// any other name.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Write the curve to FILE as CSV: frequency_hz, omega_rad_s, re, im, magnitude_db,
    /// phase_deg (unwrapped), one row per frequency.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    /// Print one JSON object instead of text (the curve, the crossings and the margins).
    #[arg(long)]
    json: bool,
}

/// The curve as arrays.
#[derive(Serialize)]
struct CurveOut<'a> {
    frequency_hz: &'a [f64],
    omega_rad_s: &'a [f64],
    re: &'a [f64],
    im: &'a [f64],
    magnitude_db: &'a [f64],
    phase_deg: &'a [f64],
}

/// The JSON of both commands.
#[derive(Serialize)]
struct FreqOut<'a> {
    input: LoopInput,
    stable: bool,
    nyquist_hz: f64,
    /// Factor > 1 on (K, B) to the boundary, read at `phase_crossover_hz`.
    gain_margin: Option<f64>,
    /// The same in dB.
    gain_margin_db: Option<f64>,
    phase_crossover_hz: Option<f64>,
    /// The phase margin smallest in magnitude, degrees, read at `gain_crossover_hz`.
    phase_margin_deg: Option<f64>,
    gain_crossover_hz: Option<f64>,
    /// min |1 + L| and where it is reached (any wall).
    closest: Option<Closest>,
    /// Every crossing with its place on the curve.
    marks: &'a [Mark],
    margin_notes: &'a [String],
    curve: CurveOut<'a>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    plot: Vec<PathBuf>,
    #[serde(skip_serializing_if = "Option::is_none")]
    csv: Option<PathBuf>,
}

/// Which plot.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Bode,
    Nyquist,
}

/// Runs `hapstab bode`.
pub fn run_bode(a: &FreqArgs) -> Result<()> {
    run(a, Kind::Bode)
}

/// Runs `hapstab nyquist-plot`.
pub fn run_nyquist_plot(a: &FreqArgs) -> Result<()> {
    run(a, Kind::Nyquist)
}

fn run(a: &FreqArgs, kind: Kind) -> Result<()> {
    let rl = a.lp.resolve(a.wall.normalized())?;
    if rl.normalized {
        bail!(
            "this plot works in physical units (Hz): give the plant in kg, Ns/m, N/m and \
             --period, not --gamma/--delta"
        );
    }
    let sys = rl.system()?;
    let fam = sys.family();
    let w = resolve_loop_wall(&rl, fam, &a.wall)?;
    let n = fam.degree();
    let cost = hapstab::limits::check_cost(n, hapstab::limits::core_degree(fam), true);
    crate::budget::check_loop(&a.lp, &rl.lp, cost, "the frequency response")?;
    let fr = frequency_response(&rl.lp, w, None)?;
    let mut plot = Vec::new();
    if let Some(path) = &a.plot {
        let title = wall_text(w);
        let sub = crate::wall_plot::loop_line(&rl);
        let written = match kind {
            Kind::Bode => hapstab_plot::freq::bode(&fr, &title, &sub).save_as(path),
            Kind::Nyquist => hapstab_plot::freq::nyquist(&fr, &title, &sub).save_as(path),
        };
        plot = written.with_context(|| format!("--plot {}", path.display()))?;
    }
    if let Some(path) = &a.csv {
        write_csv(path, &fr).with_context(|| format!("--csv: cannot write {}", path.display()))?;
    }
    if a.json {
        return print_json(&json_out(&rl, w, &fr, plot, a.csv.clone()));
    }
    print_loop_and_wall(&rl.lp, w);
    print_summary(&fr, kind);
    if !plot.is_empty() {
        println!("plot      {}", files_text(&plot));
    }
    if let Some(p) = &a.csv {
        println!("csv       {}", p.display());
    }
    Ok(())
}

/// "K = … N/m, B = … Ns/m" for titles.
fn wall_text(w: Wall) -> String {
    format!(
        "K = {} N/m, B = {} Ns/m",
        sig(w.stiffness, 4),
        sig(w.damping, 4)
    )
}

fn json_out<'a>(
    rl: &ResolvedLoop,
    w: Wall,
    fr: &'a FrequencyResponse,
    plot: Vec<PathBuf>,
    csv: Option<PathBuf>,
) -> FreqOut<'a> {
    let m = &fr.margins;
    FreqOut {
        input: rl.input(Some(w)),
        stable: m.stable,
        nyquist_hz: fr.nyquist_hz,
        gain_margin: m.gain.map(|g| g.factor),
        gain_margin_db: m.gain.map(|g| 20.0 * g.factor.log10()),
        phase_crossover_hz: m.gain.map(|g| g.frequency_hz),
        phase_margin_deg: m.phase.map(|p| p.degrees),
        gain_crossover_hz: m.phase.map(|p| p.frequency_hz),
        closest: fr.closest,
        marks: &fr.marks,
        margin_notes: &m.notes,
        curve: CurveOut {
            frequency_hz: &fr.frequency_hz,
            omega_rad_s: &fr.omega,
            re: &fr.re,
            im: &fr.im,
            magnitude_db: &fr.magnitude_db,
            phase_deg: &fr.phase_deg,
        },
        plot,
        csv,
    }
}

/// The curve, one row per frequency, shortest round-trip numbers.
fn write_csv(path: &Path, fr: &FrequencyResponse) -> Result<()> {
    let mut w = csv::Writer::from_path(path)?;
    w.write_record([
        "frequency_hz",
        "omega_rad_s",
        "re",
        "im",
        "magnitude_db",
        "phase_deg",
    ])?;
    for i in 0..fr.omega.len() {
        w.write_record([
            csv_num(fr.frequency_hz[i]),
            csv_num(fr.omega[i]),
            csv_num(fr.re[i]),
            csv_num(fr.im[i]),
            csv_num(fr.magnitude_db[i]),
            csv_num(fr.phase_deg[i]),
        ])?;
    }
    w.flush()?;
    Ok(())
}

fn print_summary(fr: &FrequencyResponse, kind: Kind) {
    let m = &fr.margins;
    let hz = |f: f64| eng(f, "Hz", 6);
    println!(
        "verdict   {}",
        if m.stable { "STABLE" } else { "NOT STABLE" }
    );
    let (f0, f1) = (
        fr.frequency_hz.first().copied().unwrap_or(f64::NAN),
        fr.nyquist_hz,
    );
    let what = match kind {
        Kind::Bode => "Bode plot",
        Kind::Nyquist => "Nyquist plot",
    };
    println!(
        "{what:<9} {} frequencies from {} to the Nyquist frequency {}",
        fr.omega.len(),
        hz(f0),
        hz(f1)
    );
    for mk in &fr.marks {
        match mk.kind {
            CrossingKind::Gain => println!(
                "crossing  gain crossover |L| = 1 at {}: phase margin {}°",
                hz(mk.frequency_hz),
                sig(mk.value, 6)
            ),
            CrossingKind::Phase => println!(
                "crossing  phase crossover (L = {}) at {}: gain factor ×{}{}",
                sig(mk.re, 6),
                hz(mk.frequency_hz),
                sig(mk.value, 6),
                if mk.value > 0.0 {
                    format!(" ({} dB)", sig(20.0 * mk.value.log10(), 4))
                } else {
                    String::new()
                }
            ),
        }
    }
    if let Some(g) = m.gain {
        println!(
            "margins   gain ×{} ({} dB) at {}",
            sig(g.factor, 6),
            sig(20.0 * g.factor.log10(), 4),
            hz(g.frequency_hz)
        );
    }
    if let Some(p) = m.phase {
        println!(
            "margins   phase {}° at {}",
            sig(p.degrees, 6),
            hz(p.frequency_hz)
        );
    }
    if let Some(c) = fr.closest {
        println!(
            "closest   min |1 + L| = {} at {} (L = {} {} {}j)",
            sig(c.distance, 6),
            hz(c.frequency_hz),
            sig(c.re, 6),
            if c.im < 0.0 { "−" } else { "+" },
            sig(c.im.abs(), 6)
        );
    }
    for note in &m.notes {
        println!("note      {note}");
    }
}
