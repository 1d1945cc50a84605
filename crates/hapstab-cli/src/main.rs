//! `hapstab`: command-line front end of the hapstab library. It only parses arguments, calls
//! the library and formats output; every analysis lives in the `hapstab` crate.

mod boundary;
mod budget;
mod check;
mod discretize;
mod kmax;
mod linear;
mod map;
mod model;
mod nyquist;
mod output;
mod paper;
mod passivity;
mod plot;
mod progress;
mod ranges;
mod robust;
mod serve;
mod simulate;
mod sweep;
mod wall_plot;
mod zwidth;

use clap::{Parser, Subcommand};

/// Exact stability of haptic virtual walls with a human operator (Hulin et al. 2008).
#[derive(Parser)]
#[command(name = "hapstab", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Time-domain simulation with nonlinear effects: verdict, CSV trace and plot (issue 6)
    Simulate(simulate::SimulateArgs),
    /// Empirical stability boundary of a nonlinear setting by simulation (issue 6)
    Simboundary(simulate::SimboundaryArgs),
    /// Is this virtual wall stable, and how stiff may it be? (Sections III and V)
    Check(check::CheckArgs),
    /// The exact discrete loop as coefficients: plant H(z) with its delay, velocity filter V(z), p(z)
    Discretize(discretize::DiscretizeArgs),
    /// The exact stable region in the (α, β)-plane, α_max and area (Section V, Figs. 4–6)
    Boundary(boundary::BoundaryArgs),
    /// Largest stable virtual stiffness K in N/m, beside the linear condition (22)
    Kmax(kmax::KmaxArgs),
    /// Device damping a wall needs to be passive (Colgate–Schenkel, eq. 28) and the passive region
    Passivity(passivity::PassivityArgs),
    /// Z-width: stable and passive (K, B) regions of a device, K_max table; compare loops
    Zwidth(zwidth::ZwidthArgs),
    /// K_max (stable and passive) against delay, period, filter cut-off or a plant parameter
    Sweep(sweep::SweepArgs),
    /// Grid map of stability over two of α, β, γ, δ (the paper's method), in parallel
    Map(map::MapArgs),
    /// Interactive explorer in the browser: local web server with the exact region (issue 7)
    Serve(serve::ServeArgs),
    /// The γ and δ ranges of real haptic systems for a sampling period (Section IV, eq. 11–15)
    Ranges(ranges::RangesArgs),
    /// Linear condition (22)/(23) and where its error (24) reaches 2 % and 5 % (Sections VI–VII)
    Linear(linear::LinearArgs),
    /// Regions up to the Nyquist frequency, robust region, passivity; Remark 4 (Section VIII)
    Nyquist(nyquist::NyquistArgs),
    /// Reproduce the paper: Figs. 4–10 (SVG, PNG), claims C1–C11 with verdicts, α_max table
    Paper(paper::PaperArgs),
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Simulate(a) => simulate::run_simulate(&a),
        Command::Simboundary(a) => simulate::run_simboundary(&a),
        Command::Check(a) => check::run(&a),
        Command::Discretize(a) => discretize::run(&a),
        Command::Boundary(a) => boundary::run(&a),
        Command::Kmax(a) => kmax::run(&a),
        Command::Passivity(a) => passivity::run(&a),
        Command::Zwidth(a) => zwidth::run(&a),
        Command::Sweep(a) => sweep::run(&a),
        Command::Map(a) => map::run(&a),
        Command::Serve(a) => serve::run(&a),
        Command::Ranges(a) => ranges::run(&a),
        Command::Linear(a) => linear::run(&a),
        Command::Nyquist(a) => nyquist::run(&a),
        Command::Paper(a) => paper::run(&a),
    }
}

/// One clear line from clap's message: its first line names the flag and the value; a first
/// line that ends in ':' (a conflict with several flags) is completed by the indented lines
/// that list them.
fn one_line(text: &str) -> String {
    let mut lines = text.lines();
    let first = lines.next().unwrap_or("error: invalid arguments");
    match first.strip_suffix(':') {
        Some(head) => {
            let items: Vec<&str> = lines
                .take_while(|l| l.starts_with(' ') && !l.trim().is_empty())
                .map(str::trim)
                .collect();
            format!("{head} {}", items.join(", "))
        }
        None => first.to_string(),
    }
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
        ] {
            let e = Cli::try_parse_from(&args).err().expect("a parse error");
            let line = one_line(&e.render().to_string());
            assert!(line.contains(flag), "{args:?}: {line}");
            assert!(!line.contains('\n'), "{line}");
        }
    }
}
