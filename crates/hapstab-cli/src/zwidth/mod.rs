//! `hapstab zwidth`: the Z-width of a device (Colgate & Brown 1994) — its stable and passive
//! (K, B) regions in physical units with the linear condition (22), K_max and a
//! K_max-versus-damping table — for one loop or several compared in one figure.
//!
//! Parts: [`compare`] builds the loops of `--compare`, [`text`] prints the answer, [`csv_file`]
//! writes the `--csv` file, [`plot`] draws the regions.

mod compare;
mod csv_file;
mod plot;
mod text;

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::answer::{ZwidthAnswer, ZwidthInput, ZwidthLoop as LoopOut};
use serde::Serialize;

use crate::model::{LoopArgs, ResolvedLoop};
use crate::output::print_json;
use compare::compared;
use csv_file::write_csv;
use plot::figure;
use text::{print_comparison, print_loop};

/// Arguments of `hapstab zwidth`.
#[derive(Args, Debug)]
pub struct ZwidthArgs {
    #[command(flatten)]
    lp: LoopArgs,
    /// Compare with another loop in the same figure (repeatable): a velocity estimator
    /// (lowpass:100, average:15, …) or loop flags in quotes, e.g.
    /// "--device-mass 0.2 --device-damping 3"; the other flags stay as given.
    #[arg(long, value_name = "SPEC", allow_hyphen_values = true)]
    compare: Vec<String>,
    /// Virtual dampings B in Ns/m of the K_max table, comma-separated [default: 11 from 0 to
    /// the largest stable B].
    #[arg(
        long,
        value_name = "LIST",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    table_damping: Option<Vec<f64>>,
    /// Write the figure as FILE.svg and FILE.png.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Write the K_max tables as CSV (one row per loop and damping).
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct ZwidthOut {
    /// The Z-widths with their inputs, as the explorer's `/api/zwidth` gives them.
    #[serde(flatten)]
    answer: ZwidthAnswer,
    #[serde(skip_serializing_if = "Option::is_none")]
    plot: Option<hapstab_plot::Saved>,
}

fn resolve(lp: &LoopArgs, what: &str) -> Result<ResolvedLoop> {
    let rl = lp.resolve(false)?;
    if rl.normalized {
        bail!("zwidth works in physical units ({what}); give the device, not --gamma/--delta");
    }
    Ok(rl)
}

/// Runs `hapstab zwidth`.
pub fn run(a: &ZwidthArgs) -> Result<()> {
    if let Some(d) = &a.table_damping
        && let Some(bad) = d.iter().find(|x| !x.is_finite())
    {
        bail!("--table-damping values must be finite numbers of Ns/m (got {bad})");
    }
    let mut loops = vec![(label_of(&a.lp, None), resolve(&a.lp, "the base loop")?)];
    for spec in &a.compare {
        let lp = compared(&a.lp, spec)?;
        loops.push((spec.trim().to_string(), resolve(&lp, spec)?));
    }
    let dampings = a.table_damping.as_deref();
    check_budget(a, &loops)?;
    let subtitle = match a.compare.is_empty() {
        true => crate::wall_plot::loop_line(&loops[0].1),
        false => format!("base loop: {}", crate::wall_plot::loop_line(&loops[0].1)),
    };
    // a comparison analyses several loops: one step each
    let bar = crate::progress::Bar::new(loops.len(), "loops", !a.json && !a.compare.is_empty());
    let out: Vec<LoopOut> = loops
        .into_iter()
        .map(|(label, rl)| {
            let z = LoopOut::new(label.clone(), &rl.lp, dampings)
                .with_context(|| format!("loop '{label}'"))?;
            bar.inc();
            Ok(z)
        })
        .collect::<Result<_>>()?;
    bar.finish();
    if let Some(path) = &a.csv {
        write_csv(path, &out)?;
    }
    let plot = a
        .plot
        .as_ref()
        .map(|p| figure(&out, &subtitle).save(p))
        .transpose()?;
    if a.json {
        let input = ZwidthInput {
            compare: a.compare.clone(),
            table_damping: a.table_damping.clone(),
        };
        let answer = ZwidthAnswer { input, loops: out };
        return print_json(&ZwidthOut { answer, plot });
    }
    for (i, o) in out.iter().enumerate() {
        if i > 0 {
            println!();
        }
        print_loop(o, out.len() > 1);
    }
    print_comparison(&out);
    if let Some(s) = &plot {
        println!("plot        {} and {}", s.svg.display(), s.png.display());
    }
    Ok(())
}

/// Refuses the analyses beyond the command-line budget: per loop the stable and passive
/// regions and the table's intervals; blames --compare or the flag that sets most of the
/// heaviest loop's degree.
fn check_budget(a: &ZwidthArgs, loops: &[(String, ResolvedLoop)]) -> Result<()> {
    let rows = a.table_damping.as_ref().map_or(8, Vec::len);
    let mut cost = hapstab::limits::Cost::ZERO;
    let mut heaviest = (0, &loops[0].1);
    for (_, rl) in loops {
        let sys = rl.system()?;
        let fam = sys.family();
        cost = cost.then(hapstab::limits::zwidth_cost(fam, rows));
        if fam.degree() > heaviest.0 {
            heaviest = (fam.degree(), rl);
        }
    }
    let mut drivers = crate::budget::degree_drivers(&a.lp, &heaviest.1.lp);
    drivers.push(crate::budget::Driver::count(
        "--compare",
        a.compare.len(),
        1,
    ));
    crate::budget::check(cost, "the regions of the loops", &drivers)
}

/// The base loop's label: its --loop file, else its velocity estimator.
fn label_of(lp: &LoopArgs, spec: Option<&str>) -> String {
    spec.map(str::to_string)
        .unwrap_or_else(|| match (&lp.plant.loop_file, &lp.velocity) {
            (Some(f), None) => format!("--loop {}", f.display()),
            (_, v) => v
                .as_ref()
                .map_or_else(|| "backward".to_string(), |v| v.to_string()),
        })
}
