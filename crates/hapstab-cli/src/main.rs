//! `hapstab`: command-line front end of the hapstab library. It only parses arguments, calls
//! the library and formats output; every analysis lives in the `hapstab` crate, the figures'
//! machinery in `hapstab-plot` and the explorer of `hapstab serve` in `hapstab-serve`.

mod boundary;
mod budget;
mod check;
mod check_plot;
mod discretize;
mod freq_plots;
mod identify;
mod kmax;
mod linear;
mod locus;
mod loop_file;
mod map;
mod model;
mod nyquist;
mod output;
mod paper;
mod passivity;
mod passivity_quantized;
mod population;
mod progress;
mod ranges;
mod robust;
mod robust_box;
mod simulate;
mod sweep;
mod wall_plot;
mod zwidth;

use clap::{Parser, Subcommand};

/// Exact stability of haptic virtual walls held by a human (Hulin et al. 2008): is a wall
/// stable, how stiff may it be, which (K, B) are stable or passive, for the paper's loop or
/// the loop you run.
#[derive(Parser)]
#[command(name = "hapstab", version, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The commands, in the order a user needs them: the verdict on one wall, the stiffness
/// limit and the regions, their conditions, the design tools, then simulation, the paper and
/// the explorer.
#[derive(Subcommand)]
enum Command {
    /// Is this virtual wall stable, and how stiff may it be? (Sections III and V)
    Check(check::CheckArgs),
    /// Largest stable virtual stiffness K in N/m, beside the linear condition (22)
    Kmax(kmax::KmaxArgs),
    /// The exact stable region in the wall plane, K_max (α_max) and area (Section V, Figs. 4–6)
    Boundary(boundary::BoundaryArgs),
    /// Grid map of stability over two of α, β, γ, δ or over (K, B), in parallel (Section V)
    Map(map::MapArgs),
    /// Linear condition (22)/(23) and where its error (24) reaches 2 % and 5 % (Sections VI–VII)
    Linear(linear::LinearArgs),
    /// Regions up to the Nyquist frequency, robust region, passivity; Remark 4 (Section VIII;
    /// not the Nyquist plot of a wall's open loop, which is `nyquist-plot`)
    Nyquist(nyquist::NyquistArgs),
    /// Bode plot of the wall's open loop L(e^{jωT}) up to the Nyquist frequency, margins marked
    Bode(freq_plots::FreqArgs),
    /// Nyquist plot of the wall's open loop L with −1 and min |1 + L| (not `nyquist`, Section VIII)
    NyquistPlot(freq_plots::FreqArgs),
    /// Root locus in K at a given B: the roots of p(z) crossing the unit circle at K_max
    Locus(locus::LocusArgs),
    /// Device damping a wall needs to be passive (Colgate–Schenkel, eq. 28) and the passive region
    Passivity(passivity::PassivityArgs),
    /// Z-width: stable and passive (K, B) regions of a device, K_max table; compare loops
    Zwidth(zwidth::ZwidthArgs),
    /// K_max (stable and passive) against delay, period, filter cut-off or a plant parameter
    Sweep(sweep::SweepArgs),
    /// P(stable) over a population of operators: against K at a damping, the K of 99 % and
    /// 99.9 %, and at one wall
    Population(population::PopulationArgs),
    /// The γ and δ ranges of real haptic systems for a sampling period (Section IV, eq. 11–15)
    Ranges(ranges::RangesArgs),
    /// The exact discrete loop as coefficients: plant H(z) with its delay, velocity filter V(z), p(z)
    Discretize(discretize::DiscretizeArgs),
    /// The plant from a recording of force and position, with its uncertainty and K_max
    Identify(identify::IdentifyArgs),
    /// Time-domain simulation with nonlinear effects: verdict, and on request a CSV trace and plot
    Simulate(simulate::SimulateArgs),
    /// Empirical stability boundary of a nonlinear setting by simulation
    Simboundary(simulate::SimboundaryArgs),
    /// Reproduce the paper: Figs. 4–10 (SVG, PNG), claims C1–C11 with verdicts, α_max table
    Paper(paper::PaperArgs),
    /// Interactive explorer in the browser: a local web server drawing the exact region live
    Serve(hapstab_serve::ServeArgs),
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Simulate(a) => simulate::run_simulate(&a),
        Command::Identify(a) => identify::run(&a),
        Command::Simboundary(a) => simulate::run_simboundary(&a),
        Command::Check(a) => check::run(&a),
        Command::Discretize(a) => discretize::run(&a),
        Command::Boundary(a) => boundary::run(&a),
        Command::Kmax(a) => kmax::run(&a),
        Command::Passivity(a) => passivity::run(&a),
        Command::Zwidth(a) => zwidth::run(&a),
        Command::Sweep(a) => sweep::run(&a),
        Command::Population(a) => population::run(&a),
        Command::Map(a) => map::run(&a),
        Command::Serve(a) => Ok(hapstab_serve::run(&a)?),
        Command::Ranges(a) => ranges::run(&a),
        Command::Linear(a) => linear::run(&a),
        Command::Nyquist(a) => nyquist::run(&a),
        Command::Bode(a) => freq_plots::run_bode(&a),
        Command::NyquistPlot(a) => freq_plots::run_nyquist_plot(&a),
        Command::Locus(a) => locus::run(&a),
        Command::Paper(a) => paper::run(&a),
    }
}

/// One clear line from clap's message: its first line names the flag and the value; a first
/// line that ends in ':' (a conflict with several flags) is completed by the indented lines
/// that list them, and clap's suggestion ("tip: a similar subcommand exists: 'check'") is
/// kept after a semicolon.
fn one_line(text: &str) -> String {
    let mut lines = text.lines();
    let first = lines.next().unwrap_or("error: invalid arguments");
    let mut line = match first.strip_suffix(':') {
        Some(head) => {
            let items: Vec<&str> = lines
                .clone()
                .take_while(|l| l.starts_with(' ') && !l.trim().is_empty())
                .map(str::trim)
                .collect();
            format!("{head} {}", items.join(", "))
        }
        None => first.to_string(),
    };
    if let Some(tip) = lines.find_map(|l| l.trim().strip_prefix("tip: a similar")) {
        line.push_str(&format!("; a similar{tip}"));
    }
    shorten_value(&line)
}

/// Clap's "invalid value 'VALUE' for '--flag'" with a long VALUE (a list of thousands of
/// coefficients) shown by its excerpt ([`hapstab::spec::excerpt`]).
fn shorten_value(line: &str) -> String {
    let Some((head, rest)) = line.split_once("invalid value '") else {
        return line.to_string();
    };
    let Some((value, tail)) = rest.split_once("' for '") else {
        return line.to_string();
    };
    format!(
        "{head}invalid value '{}' for '{tail}",
        hapstab::spec::excerpt(value)
    )
}

fn main() {
    // Die quietly like other Unix tools when stdout is closed (`hapstab ... | head`), instead
    // of panicking in println!.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of SIGPIPE before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    exit_2_when_stdout_fails();
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion)
                || matches!(
                    e.kind(),
                    ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
                )
            {
                let _ = e.print();
                std::process::exit(
                    if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                        2
                    } else {
                        0
                    },
                );
            }
            eprintln!("{}", one_line(&e.render().to_string()));
            std::process::exit(2);
        }
    };
    if let Err(e) = run(cli) {
        eprintln!("error: {e:#}");
        std::process::exit(2);
    }
}

/// `println!` panics when standard output cannot be written (a full disk, `> /dev/full`):
/// report that as one line and exit 2 like every other output error; any other panic keeps
/// the default report.
fn exit_2_when_stdout_fails() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let msg = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if let Some(why) = msg.strip_prefix("failed printing to stdout: ") {
            eprintln!("error: cannot write to standard output: {why}");
            std::process::exit(2);
        }
        default(info);
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_required_flags_are_named_on_one_line() {
        for (args, flag) in [
            (vec!["hapstab", "map", "--x", "alpha:0:1:10"], "--y"),
            (vec!["hapstab", "paper"], "--out"),
            (vec!["hapstab", "chek"], "'check'"),
        ] {
            let e = Cli::try_parse_from(&args).err().expect("a parse error");
            let line = one_line(&e.render().to_string());
            assert!(line.contains(flag), "{args:?}: {line}");
            assert!(!line.contains('\n'), "{line}");
        }
    }

    /// Every flag a library error can name is a flag of some command.
    #[test]
    fn parameters_name_real_flags() {
        use clap::CommandFactory;
        fn longs(c: &clap::Command, out: &mut std::collections::HashSet<String>) {
            out.extend(
                c.get_arguments()
                    .filter_map(|a| a.get_long().map(str::to_string)),
            );
            c.get_subcommands().for_each(|s| longs(s, out));
        }
        let mut flags = std::collections::HashSet::new();
        longs(&Cli::command(), &mut flags);
        for p in hapstab::Param::ALL {
            for f in p.flag().into_iter().flat_map(|f| f.split('/')) {
                let name = f.strip_prefix("--").unwrap_or(f);
                assert!(flags.contains(name), "{p:?}: no command has {f}");
            }
        }
    }
}
