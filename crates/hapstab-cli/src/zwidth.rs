//! `hapstab zwidth`: the Z-width of a device (Colgate & Brown 1994) — its stable and passive
//! (K, B) regions in physical units with the linear condition (22), K_max and a
//! K_max-versus-damping table — for one loop or several compared in one figure.

use std::path::PathBuf;

use anyhow::{Context, Result, anyhow, bail};
use clap::parser::ValueSource;
use clap::{ArgAction, Args, CommandFactory, FromArgMatches, Parser};
use hapstab::answer::{ZwidthAnswer, ZwidthInput, ZwidthLoop as LoopOut};
use hapstab::params::Wall;
use hapstab::zwidth::ZWidth;
use serde::Serialize;

use crate::model::{LoopArgs, LoopInput, ResolvedLoop, describe_loop};
use crate::output::{csv_num, csv_opt, eng, print_json, sig};
use hapstab_plot::{Figure, Grid, Legend, Marker, Series, palette};

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

/// Re-parses loop flags on top of the base loop's (for --compare).
#[derive(Parser)]
#[command(no_binary_name = true)]
struct Override {
    #[command(flatten)]
    lp: LoopArgs,
}

#[derive(Serialize)]
struct ZwidthOut {
    /// The Z-widths with their inputs, as the explorer's `/api/zwidth` gives them.
    #[serde(flatten)]
    answer: ZwidthAnswer,
    #[serde(skip_serializing_if = "Option::is_none")]
    plot: Option<hapstab_plot::Saved>,
}

/// The loop flags of a --compare spec applied over the base flags.
fn compared(base: &LoopArgs, spec: &str) -> Result<LoopArgs> {
    let tokens: Vec<String> = if spec.trim_start().starts_with("--") {
        spec.split_whitespace().map(String::from).collect()
    } else {
        vec!["--velocity".into(), spec.trim().into()]
    };
    let err = |e: clap::Error| {
        let text = e.render().to_string();
        let line = text.lines().next().unwrap_or("invalid flags").to_string();
        anyhow!("--compare '{spec}': {}", line.trim_start_matches("error: "))
    };
    let matches = Override::command()
        .try_get_matches_from(&tokens)
        .map_err(err)?;
    let mut o = Override { lp: base.clone() };
    o.update_from_arg_matches(&matches).map_err(err)?;
    // clap updates an on/off flag even when it is absent (its default "false" counts as
    // given): keep the base loop's value of every flag the spec does not name.
    for id in switch_ids() {
        if matches.value_source(id.as_str()) != Some(ValueSource::CommandLine) {
            restore_switch(&mut o.lp, base, id.as_str())?;
        }
    }
    Ok(o.lp)
}

/// The ids of the on/off flags of the loop flags.
fn switch_ids() -> Vec<clap::Id> {
    Override::command()
        .get_arguments()
        .filter(|a| matches!(a.get_action(), ArgAction::SetTrue | ArgAction::SetFalse))
        .map(|a| a.get_id().clone())
        .collect()
}

/// Copies one on/off flag from the base loop flags.
fn restore_switch(lp: &mut LoopArgs, base: &LoopArgs, id: &str) -> Result<()> {
    match id {
        "no_arm" => lp.plant.no_arm = base.plant.no_arm,
        _ => bail!("internal: the loop flag --{id} is not handled by --compare"),
    }
    Ok(())
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

fn kn(x: f64) -> String {
    eng(x, "N/m", 6)
}

fn ns(x: f64) -> String {
    eng(x, "Ns/m", 6)
}

fn print_loop(o: &LoopOut, titled: bool) {
    if titled {
        println!("== {} ==", o.label);
    }
    if let LoopInput::Physical { lp, .. } = &o.input {
        for line in describe_loop(lp) {
            println!("{line}");
        }
    }
    let z = &o.zwidth;
    match z.k_max {
        Some(k) => {
            let nonneg = z
                .k_max_nonnegative_damping
                .map(|w| format!("; with B ≥ 0: {} at B = {}", kn(w.stiffness), ns(w.damping)))
                .unwrap_or_else(|| "; nothing stable with B ≥ 0".into());
            println!(
                "stable      K_max = {} at B = {}{nonneg}; area {} N²·s/m²",
                kn(k.stiffness),
                ns(k.damping),
                sig(z.stable_area, 5)
            );
        }
        None => println!("stable      no stable wall"),
    }
    print_passive(z);
    if let Some(l) = z.linear {
        println!(
            "linear (22) K < (b + B)/(t_d + T/2) = ({} + B)/{}",
            ns(l.damping),
            eng(l.effective_delay, "s", 6)
        );
    }
    print_table(z);
}

fn print_passive(z: &ZWidth) {
    match (&z.passive, &z.device_damping) {
        (Some(p), _) if p.vertices.is_empty() => {
            println!("passive     none: the device has no damping (b = 0)");
        }
        (Some(p), _) => {
            let inside = match z.passive_inside_stable {
                Some(true) => "inside the stable region",
                Some(false) => "NOT inside the stable region",
                None => "",
            };
            println!(
                "passive     b = {}: K_max = {} at B = {}; area {} N²·s/m²; {inside}",
                ns(p.device_damping),
                kn(p.k_max),
                ns(p.b_at_k_max),
                sig(p.area, 5)
            );
        }
        (None, hapstab::passivity::DeviceDamping::NotApplicable { reason }) => {
            println!("passive     not applicable: {reason}");
        }
        (None, _) => {}
    }
    if let Some(w) = z.k_max_passive_with_arm {
        println!(
            "with arm    K_max = {} at B = {} by eq. (28) with the arm's damping counted \
             (b = b_L + b_H): towards this operator only",
            kn(w.stiffness),
            ns(w.damping)
        );
    }
}

fn opt(x: Option<f64>) -> String {
    x.map_or_else(|| "—".into(), kn)
}

fn print_table(z: &ZWidth) {
    println!(
        "  {:>12}  {:>14}  {:>14}  {:>14}  {:>14}",
        "B", "K_max stable", "K_min stable", "K_max passive", "linear (22)"
    );
    for r in &z.table {
        println!(
            "  {:>12}  {:>14}  {:>14}  {:>14}  {:>14}",
            ns(r.damping),
            opt(r.k_max),
            opt(r.k_min),
            opt(r.k_max_passive),
            opt(r.k_linear)
        );
    }
}

fn print_comparison(out: &[LoopOut]) {
    let Some(base) = out.first().filter(|_| out.len() > 1) else {
        return;
    };
    println!();
    println!("compared with '{}':", base.label);
    let bk = base.zwidth.k_max.map(|w| w.stiffness);
    for o in &out[1..] {
        let k = o.zwidth.k_max.map(|w| w.stiffness);
        let ratio = match (k, bk) {
            (Some(k), Some(b)) => format!("K_max ×{}", sig(k / b, 4)),
            _ => "K_max —".into(),
        };
        println!(
            "  {:<24} stable area ×{}, {ratio}",
            o.label,
            sig(o.zwidth.stable_area / base.zwidth.stable_area, 4)
        );
    }
}

fn write_csv(path: &std::path::Path, out: &[LoopOut]) -> Result<()> {
    let mut w =
        csv::Writer::from_path(path).with_context(|| format!("cannot write {}", path.display()))?;
    w.write_record([
        "loop",
        "damping",
        "k_max",
        "k_min",
        "k_max_passive",
        "k_linear",
    ])?;
    let cell = csv_opt;
    for o in out {
        for r in &o.zwidth.table {
            w.write_record([
                o.label.clone(),
                csv_num(r.damping),
                cell(r.k_max),
                cell(r.k_min),
                cell(r.k_max_passive),
                cell(r.k_linear),
            ])?;
        }
    }
    w.flush()?;
    Ok(())
}

fn points(v: &[Wall]) -> Vec<(f64, f64)> {
    v.iter().map(|w| (w.stiffness, w.damping)).collect()
}

/// The extent (K0, K1, B0, B1) of a set of polygons.
type Extent = (f64, f64, f64, f64);

fn extent<'a>(polys: impl IntoIterator<Item = &'a Vec<Wall>>) -> Option<Extent> {
    let mut e: Option<Extent> = None;
    for w in polys.into_iter().flatten() {
        let (k0, k1, b0, b1) = e.unwrap_or((w.stiffness, w.stiffness, w.damping, w.damping));
        e = Some((
            k0.min(w.stiffness),
            k1.max(w.stiffness),
            b0.min(w.damping),
            b1.max(w.damping),
        ));
    }
    e
}

/// Two panels: every loop's stable region (light) and passive region (dark) with K_max marked
/// and the linear condition (22) of the first loop dashed; then the same zoomed onto the
/// passive regions, which are small beside the stable ones.
fn figure(out: &[LoopOut], subtitle: &str) -> Grid {
    let stable = extent(out.iter().flat_map(|o| o.zwidth.stable.iter()));
    let passive = extent(
        out.iter()
            .filter_map(|o| o.zwidth.passive.as_ref())
            .map(|p| &p.vertices)
            .filter(|v| !v.is_empty()),
    );
    let mut g = Grid::new("Z-width: stable (light) and passive (dark) walls", 2).subtitle(subtitle);
    let whole = stable.or(passive).unwrap_or((0.0, 1.0, -1.0, 1.0));
    g.push(panel(out, "all stable walls", pad(whole), Legend::Below));
    if let Some(p) = passive {
        let (k0, k1, b0, b1) = p;
        let (w, h) = (k1 - k0, b1 - b0);
        let zoom = (k0 - 0.1 * w, k1 + 0.6 * w, b0 - 0.3 * h, b1 + 0.3 * h);
        g.push(panel(
            out,
            "zoom: the passive regions",
            zoom,
            Legend::Hidden,
        ));
    }
    g
}

fn pad((k0, k1, b0, b1): Extent) -> Extent {
    let (w, h) = ((k1 - k0).max(1e-9), (b1 - b0).max(1e-9));
    (k0 - 0.03 * w, k1 + 0.06 * w, b0 - 0.05 * h, b1 + 0.05 * h)
}

fn panel(out: &[LoopOut], title: &str, (k0, k1, b0, b1): Extent, legend: Legend) -> Figure {
    let mut f = Figure::new(title)
        .x_label("virtual stiffness K (N/m)")
        .y_label("virtual damping B (Ns/m)")
        .legend(legend)
        .x_range(k0, k1)
        .y_range(b0, b1);
    let mut rings = Vec::new();
    // the zoom shows the passive regions: the stable fills behind them are fainter
    let stable_alpha = if legend == Legend::Hidden { 0.05 } else { 0.12 };
    for (i, o) in out.iter().enumerate() {
        let c = palette::CYCLE[i % palette::CYCLE.len()];
        for (j, poly) in o.zwidth.stable.iter().enumerate() {
            let s = Series::polygon(points(poly))
                .color(c)
                .alpha(stable_alpha)
                .width(2);
            f.add(if j == 0 {
                s.label(format!("stable: {}", o.label))
            } else {
                s
            });
        }
        if let Some(p) = o.zwidth.passive.as_ref().filter(|p| !p.vertices.is_empty()) {
            f.add(
                Series::polygon(points(&p.vertices))
                    .color(c)
                    .alpha(0.22)
                    .width(3)
                    .label(format!("passive: {}", o.label)),
            );
            let mut ring = points(&p.vertices);
            ring.extend(ring.first().copied());
            rings.push(Series::line(ring).color(c).width(3));
        }
        if let Some(k) = o.zwidth.k_max {
            f.add(Series::scatter([(k.stiffness, k.damping)], Marker::Circle).color(c));
        }
    }
    // each passive region's outline over every fill, so that overlapping ones stay apart
    for r in rings {
        f.add(r);
    }
    if let Some(l) = out.first().and_then(|o| o.zwidth.linear) {
        let line = [b0, b1].map(|b| (l.k_at(b), b));
        f.add(
            Series::dashed(line)
                .color(palette::BLACK)
                .width(2)
                .label("linear condition (22)"),
        );
    }
    f
}
