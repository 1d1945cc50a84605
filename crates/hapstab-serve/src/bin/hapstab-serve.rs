//! `hapstab-serve`: the explorer alone, with the flags of `hapstab serve` — the server process
//! of this crate's integration tests (built with the `test-server` feature, which `cargo test`
//! turns on). Users run `hapstab serve`.

use clap::Parser;

/// The explorer with the flags of `hapstab serve`.
#[derive(Parser)]
#[command(name = "hapstab-serve", version)]
struct Cli {
    #[command(flatten)]
    args: hapstab_serve::ServeArgs,
}

fn main() -> std::process::ExitCode {
    match hapstab_serve::run(&Cli::parse().args) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            let mut text = e.to_string();
            let mut source = std::error::Error::source(&e);
            while let Some(s) = source {
                text.push_str(&format!(": {s}"));
                source = s.source();
            }
            eprintln!("error: {text}");
            std::process::ExitCode::from(2)
        }
    }
}
