//! `hapstab population`: the probability that a wall is stable over a population of
//! operators, P(stable) against K at a damping, the K of each level, and P(stable) at one
//! wall ([`hapstab::population::stability_probability`]).

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::population::{
    Dist, Population, StabilityProbability, WallProbability, stability_probability,
    wall_probability,
};
use hapstab::sweep::SweepParam;
use serde::Serialize;
use std::path::PathBuf;

use crate::model::{LoopArgs, LoopInput, print_loop};
use crate::output::{csv_num, eng, print_json, sig};

/// Arguments of `hapstab population`.
#[derive(Args, Debug)]
pub struct PopulationArgs {
    #[command(flatten)]
    lp: LoopArgs,
    /// Virtual damping B in Ns/m at which P(stable) is taken.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    wall_damping: f64,
    /// A wall stiffness K in N/m: P(stable) of that wall with its 95 % interval, each
    /// operator by the exact verdict alone (instead of the curve against K).
    #[arg(long, allow_hyphen_values = true)]
    wall_stiffness: Option<f64>,
    /// A parameter's distribution NAME=KIND:A:B (`sweep --param`'s names; uniform:LO:HI,
    /// normal:MEAN:SD, lognormal:MEDIAN:SIGMA), repeatable; without any, the paper's
    /// Section IV population: m_H uniform in 0.5..2 kg, k_H/m_H in 0..710 s⁻², b_H/m_H in
    /// 0..12.6 s⁻¹.
    #[arg(long = "dist", value_name = "NAME=DIST", value_parser = parse_dist)]
    dists: Vec<(SweepParam, Dist)>,
    /// Operators drawn (each an exact stable interval at B).
    #[arg(long, default_value_t = 10_000)]
    samples: usize,
    /// Seed of the draw (the same seed draws the same operators).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Levels q whose stiffness (the largest K with P(stable) ≥ q) is reported.
    #[arg(long, value_delimiter = ',', default_values_t = [0.99, 0.999])]
    levels: Vec<f64>,
    /// Write the curve K, P(stable), Wilson's interval to FILE (CSV).
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    /// Draw P(stable) against K (with Wilson's band) and 1 − P(stable) on a log scale with
    /// the levels' K marked: STEM.svg and STEM.png (the curve; not with --wall-stiffness).
    #[arg(long, value_name = "STEM", conflicts_with = "wall_stiffness")]
    plot: Option<PathBuf>,
    /// Write each operator's drawn parameters and stable K interval to FILE (CSV).
    #[arg(long, value_name = "FILE")]
    samples_csv: Option<PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// Parses NAME=KIND:A:B.
fn parse_dist(s: &str) -> Result<(SweepParam, Dist), String> {
    let (name, dist) = s.split_once('=').ok_or_else(|| {
        format!("expected NAME=KIND:A:B, e.g. arm-mass=uniform:0.5:2 (got '{s}')")
    })?;
    let p: SweepParam = name.parse().map_err(|e| format!("{e} (in '{s}')"))?;
    Ok((p, Dist::parse(dist).map_err(|e| e.to_string())?))
}

#[derive(Serialize)]
struct PopulationOut<'a, R: Serialize> {
    input: PopulationInput<'a>,
    #[serde(flatten)]
    report: &'a R,
    /// Files written by --plot.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    plot: Vec<PathBuf>,
}

#[derive(Serialize)]
struct PopulationInput<'a> {
    #[serde(flatten)]
    lp: LoopInput,
    population: &'a Population,
}

/// Runs `hapstab population`.
pub fn run(a: &PopulationArgs) -> Result<()> {
    let rl = a.lp.resolve(false)?;
    if rl.normalized {
        bail!("population works in physical units");
    }
    let pop = if a.dists.is_empty() {
        Population::SectionIv
    } else {
        Population::Independent {
            params: a.dists.clone(),
        }
    };
    let sys = rl.system()?;
    let fam = sys.family();
    let cost = hapstab::limits::population_cost(fam.degree(), a.samples);
    crate::budget::check_loop(&a.lp, &rl.lp, cost, "the population")?;
    let input = PopulationInput {
        lp: rl.input(None),
        population: &pop,
    };
    if let Some(k) = a.wall_stiffness {
        let wall = hapstab::params::Wall {
            stiffness: k,
            damping: a.wall_damping,
        };
        let r = wall_probability(&rl.lp, &pop, wall, a.samples, a.seed)?;
        if let Some(path) = &a.samples_csv {
            let flags: Vec<[f64; 2]> = r
                .verdicts
                .iter()
                .map(|&s| [f64::from(u8::from(s)), 0.0])
                .collect();
            write_samples(path, &r.param_names, &r.draws, &flags, ["stable", "_"])?;
        }
        if a.json {
            return print_json(&PopulationOut {
                input,
                report: &r,
                plot: Vec::new(),
            });
        }
        print_loop_and_population(&rl, &pop, r.samples, r.seed);
        print_wall(&r);
        return Ok(());
    }
    run_curve(a, &rl, &pop, input)
}

/// The curve against K: CSV, samples, plot, then JSON or text.
fn run_curve(
    a: &PopulationArgs,
    rl: &crate::model::ResolvedLoop,
    pop: &Population,
    input: PopulationInput<'_>,
) -> Result<()> {
    let r = stability_probability(&rl.lp, pop, a.wall_damping, a.samples, a.seed, &a.levels)?;
    if let Some(path) = &a.csv {
        write_curve(path, &r)?;
    }
    if let Some(path) = &a.samples_csv {
        let names = ["k_lo", "k_hi"];
        write_samples(path, &r.param_names, &r.draws, &r.intervals, names)?;
    }
    let plot = match &a.plot {
        Some(stem) => Some(
            hapstab_plot::population::figure(&r, &crate::wall_plot::loop_line(rl))
                .save(stem)
                .with_context(|| format!("--plot {}", stem.display()))?,
        ),
        None => None,
    };
    if a.json {
        return print_json(&PopulationOut {
            input,
            report: &r,
            plot: plot.map_or(Vec::new(), |p| vec![p.svg, p.png]),
        });
    }
    print_loop_and_population(rl, pop, r.samples, r.seed);
    print_levels(&r);
    if let Some(p) = plot {
        println!(
            "plot written to {} and {}",
            p.svg.display(),
            p.png.display()
        );
    }
    Ok(())
}

fn print_loop_and_population(
    rl: &crate::model::ResolvedLoop,
    pop: &Population,
    n: usize,
    seed: u64,
) {
    print_loop(&rl.lp);
    let who = match pop {
        Population::SectionIv => {
            "Section IV: m_H ∈ [0.5, 2] kg, k_H/m_H ∈ [0, 710] s⁻², b_H/m_H ∈ [0, 12.6] s⁻¹"
                .to_string()
        }
        Population::Independent { params } => params
            .iter()
            .map(|(p, d)| format!("{} ~ {}", p.name(), dist_text(*d)))
            .collect::<Vec<_>>()
            .join(", "),
    };
    println!("operators {n} drawn (seed {seed}), {who}");
}

fn dist_text(d: Dist) -> String {
    match d {
        Dist::Uniform { lo, hi } => format!("uniform({}, {})", sig(lo, 6), sig(hi, 6)),
        Dist::Normal { mean, sd } => format!("normal({}, {})", sig(mean, 6), sig(sd, 6)),
        Dist::LogNormal { median, sigma } => {
            format!("lognormal(median {}, σ {})", sig(median, 6), sig(sigma, 6))
        }
    }
}

fn print_wall(w: &WallProbability) {
    println!(
        "P(stable) = {} at K = {}, B = {} ({} of {}; 95 % interval {} … {})",
        sig(w.probability, 6),
        eng(w.wall_stiffness, "N/m", 6),
        eng(w.wall_damping, "Ns/m", 6),
        w.stable,
        w.samples,
        sig(w.interval[0], 4),
        sig(w.interval[1], 4)
    );
}

fn print_levels(r: &StabilityProbability) {
    let bt = eng(r.wall_damping, "Ns/m", 6);
    for l in &r.levels {
        let k = |x: Option<f64>| x.map_or("—".into(), |v| eng(v, "N/m", 6));
        match l.k {
            Some(_) => println!(
                "P(stable) ≥ {} up to K = {} at B = {bt} (95 %: {} … {})",
                l.level,
                k(l.k),
                k(l.k_lo),
                k(l.k_hi)
            ),
            None => println!("P(stable) ≥ {} is reached at no K at B = {bt}", l.level),
        }
    }
}

fn write_curve(path: &std::path::Path, r: &StabilityProbability) -> Result<()> {
    let mut w =
        csv::Writer::from_path(path).with_context(|| format!("cannot write {}", path.display()))?;
    w.write_record(["k", "probability", "probability_lo", "probability_hi"])?;
    for i in 0..r.k.len() {
        w.write_record([
            csv_num(r.k[i]),
            csv_num(r.probability[i]),
            csv_num(r.probability_lo[i]),
            csv_num(r.probability_hi[i]),
        ])?;
    }
    w.flush()?;
    Ok(())
}

fn write_samples(
    path: &std::path::Path,
    names: &[&str],
    draws: &[Vec<f64>],
    tail: &[[f64; 2]],
    tail_names: [&str; 2],
) -> Result<()> {
    let mut w =
        csv::Writer::from_path(path).with_context(|| format!("cannot write {}", path.display()))?;
    let keep = if tail_names[1] == "_" { 1 } else { 2 };
    let mut head: Vec<&str> = names.to_vec();
    head.extend(&tail_names[..keep]);
    w.write_record(&head)?;
    for (d, t) in draws.iter().zip(tail) {
        let mut row: Vec<String> = d.iter().map(|&x| csv_num(x)).collect();
        row.extend(t[..keep].iter().map(|&x| csv_num(x)));
        w.write_record(&row)?;
    }
    w.flush()?;
    Ok(())
}
