//! `hapstab simulate --identification-log FILE`: instead of a wall contact, the recording an
//! identification experiment would make on the loop's plant — the force excitation and the
//! measured position with noise and quantization ([`hapstab::identify::excitation`]) — as the
//! CSV `hapstab identify --data` reads (time, force, position).

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use hapstab::identify::excitation::{Excitation, force, measured_position};
use hapstab::model::Loop;
use serde::Serialize;

use crate::output::{csv_num, print_json};

/// Most samples of an identification log (10⁷: 400 MB of CSV at most).
const MAX_LOG_SAMPLES: usize = 10_000_000;

/// The identification-log flags of `simulate`.
#[derive(Args, Debug, Clone)]
pub struct LogArgs {
    /// Write an identification log instead of simulating a wall: time (s), commanded force (N)
    /// and measured position (m) of the loop's plant alone, as `hapstab identify --data` reads
    /// it (--quantization rounds its position)
    #[arg(long, value_name = "FILE")]
    pub identification_log: Option<PathBuf>,
    /// The log's force: chirp:F0:F1 (a linear sweep in Hz), prbs:HOLD (random ±amplitude
    /// levels held HOLD samples) or step
    #[arg(long, default_value = "chirp:0.5:50", requires = "identification_log")]
    pub excitation: Excitation,
    /// The log's force amplitude in N
    #[arg(long, default_value_t = 1.0, requires = "identification_log")]
    pub excitation_amplitude: f64,
    /// The log's length in samples
    #[arg(long, default_value_t = 4000, requires = "identification_log")]
    pub log_samples: usize,
    /// Noise on the log's position: signal-to-noise ratio in dB (none without it)
    #[arg(long, value_name = "DB", requires = "identification_log")]
    pub log_snr: Option<f64>,
    /// Seed of the log's noise and PRBS
    #[arg(long, default_value_t = 1, requires = "identification_log")]
    pub log_seed: u64,
}

/// The log's settings as echoed under `input`.
#[derive(Serialize)]
struct LogInput<'a> {
    #[serde(rename = "loop")]
    lp: &'a Loop,
    excitation: Excitation,
    amplitude: f64,
    samples: usize,
    snr_db: Option<f64>,
    quantization: Option<f64>,
    seed: u64,
}

/// The JSON report: the settings and the file written with its position's RMS.
#[derive(Serialize)]
struct LogOut<'a> {
    input: LogInput<'a>,
    identification_log: &'a PathBuf,
    position_rms: f64,
}

/// Writes the log of `a` for the loop `lp` (module doc), with quantization `q` in m.
pub fn run(a: &LogArgs, lp: &Loop, q: Option<f64>, json: bool) -> Result<()> {
    let Some(path) = &a.identification_log else {
        return Ok(());
    };
    if !(2..=MAX_LOG_SAMPLES).contains(&a.log_samples) {
        bail!(
            "--log-samples: {} is outside [2, {MAX_LOG_SAMPLES}]",
            a.log_samples
        );
    }
    if !a.excitation_amplitude.is_finite() || a.excitation_amplitude <= 0.0 {
        bail!(
            "--excitation-amplitude: {} must be a force > 0 in N",
            a.excitation_amplitude
        );
    }
    if let Some(s) = a.log_snr.filter(|s| !s.is_finite()) {
        bail!("--log-snr: {s} must be a finite number of dB");
    }
    let f = force(
        a.excitation,
        a.excitation_amplitude,
        a.log_samples,
        lp.period,
        a.log_seed,
    );
    let y = measured_position(lp, &f, a.log_snr, q.unwrap_or(0.0), a.log_seed)?;
    let mut text = String::from("time,force,position\n");
    for (k, (fk, yk)) in f.iter().zip(&y).enumerate() {
        let t = k as f64 * lp.period;
        let _ = writeln!(text, "{},{},{}", csv_num(t), csv_num(*fk), csv_num(*yk));
    }
    std::fs::write(path, text)
        .with_context(|| format!("--identification-log '{}': cannot write", path.display()))?;
    if json {
        let rms = (y.iter().map(|v| v * v).sum::<f64>() / y.len() as f64).sqrt();
        return print_json(&LogOut {
            input: LogInput {
                lp,
                excitation: a.excitation,
                amplitude: a.excitation_amplitude,
                samples: a.log_samples,
                snr_db: a.log_snr,
                quantization: q,
                seed: a.log_seed,
            },
            identification_log: path,
            position_rms: rms,
        });
    }
    println!(
        "identification log {}: {} samples at T = {} s of the loop's plant under {}, amplitude {} N",
        path.display(),
        a.log_samples,
        csv_num(lp.period),
        a.excitation,
        csv_num(a.excitation_amplitude)
    );
    Ok(())
}
