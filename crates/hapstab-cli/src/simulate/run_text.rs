//! The text `hapstab simulate` prints: the loop, the effects, the run, the verdict with its
//! evidence, the contact events and a hint.

use hapstab::Verdict;
use hapstab::simulation::{Contact, Outcome, RunResult};

use super::run::{SimLoop, SimulateOut};
use super::run_args::RunSettings;
use super::{Units, describe_effects};
use crate::model::print_loop_and_wall;
use crate::output::{eng, sig};

/// A frequency in Hz (physical) or cycles per sample (normalized).
fn frequency(hz: f64, units: Units) -> String {
    if units.physical {
        eng(hz, "Hz", 6)
    } else {
        format!("{} cycles/sample", sig(hz, 6))
    }
}

/// A time in s (physical) or a sample count (normalized).
fn time_text(seconds: f64, units: Units) -> String {
    if units.physical {
        eng(seconds, "s", 6)
    } else {
        format!("{} samples", sig(seconds, 6))
    }
}

/// The outcome with its key numbers, e.g. "limit cycle, bouncing: 1.383 mm peak-to-peak, 8.88 Hz".
pub(super) fn outcome_summary(r: &RunResult, units: Units) -> String {
    let v = &r.verdict;
    match (v.outcome, v.limit_cycle) {
        (Outcome::LimitCycle, Some(lc)) => {
            let counts = lc
                .counts
                .map(|c| format!(" ({} counts)", sig(c, 3)))
                .unwrap_or_default();
            format!(
                "limit cycle{}: {} peak-to-peak{counts}, {}",
                if lc.bouncing { ", bouncing" } else { "" },
                eng(lc.peak_to_peak, "m", 6),
                frequency(lc.frequency_hz, units)
            )
        }
        (Outcome::Separated, _) => match v.contact.separations {
            0 => "separated: never touched the wall".to_string(),
            1 => "separated: left the wall after 1 bounce".to_string(),
            n => format!("separated: left the wall after {n} bounces"),
        },
        (o, _) => o.as_str().replace('_', " "),
    }
}

/// The simulated loop in words: the paper's normalized point, or the loop and its wall.
fn print_model(o: &SimulateOut, sl: &SimLoop, units: Units) {
    let normalized = o.normalized.as_ref();
    if units.physical || normalized.is_none() {
        // physical input speaks K, B and the loop
        print_loop_and_wall(&sl.rl.lp, sl.wall);
    }
    // physical input speaks K, B; the paper's normalized view stays in the JSON
    let (Some(n), false) = (normalized, units.physical) else {
        return;
    };
    println!(
        "model       α = {}, β = {}, γ = {}, δ = {}, d = {} (normalized: time in samples, forces as T²F/m)",
        sig(n.alpha, 6),
        sig(n.beta, 6),
        sig(n.gamma, 6),
        sig(n.delta, 6),
        n.d,
    );
}

pub(super) fn print_simulate(o: &SimulateOut, sl: &SimLoop, s: &RunSettings, units: Units) {
    let r = &o.run;
    let v = &r.verdict;
    print_model(o, sl, units);
    println!("effects     {}", describe_effects(s, units.force()));
    println!("run         {}", run_text(o, units));
    let outcome = outcome_summary(r, units);
    match outcome.split_once(':') {
        Some((head, tail)) => println!("verdict     {}:{tail}", head.to_uppercase()),
        None => println!("verdict     {}", outcome.to_uppercase()),
    }
    println!("why         {}", v.reason);
    println!(
        "judged      t = {} … {} (the second half of the run)",
        time_text(o.judged_from, units),
        time_text(o.judged_to, units)
    );
    if let Some(line) = analysis_text(r, s) {
        println!("{line}");
    }
    if s.effects.contact != Contact::Bilateral {
        println!("contact     {}", contact_text(r));
    }
    if let Some(hint) = hint_text(r, s, units, o.period) {
        println!("hint        {hint}");
    }
    if let Some(f) = &o.files {
        let mut names: Vec<String> = Vec::new();
        if let Some(c) = &f.csv {
            names.push(format!("{} ({} rows: t, x, v, F)", c.display(), f.rows));
        }
        names.extend(f.svg.iter().chain(&f.png).map(|p| p.display().to_string()));
        println!("files       {}", names.join(", "));
    }
}

fn run_text(o: &SimulateOut, units: Units) -> String {
    let r = &o.run;
    let mut t = format!(
        "{} samples ({}) from x(0) = {}, ẋ(0) = {} {}",
        r.samples,
        time_text(o.duration, units),
        eng(o.input.initial.position, "m", 6),
        sig(o.input.initial.velocity, 6),
        units.velocity()
    );
    if r.blown_up {
        t += " (stopped: the state blew up)";
    } else if r.verdict.outcome == Outcome::Undecided && r.samples > r.requested_samples {
        t += &format!(
            "; extended from {} samples to the horizon without settling",
            r.requested_samples
        );
    } else if r.samples > r.requested_samples {
        t += &format!(
            "; extended from {} samples until it settled (horizon {} samples)",
            r.requested_samples, r.max_samples
        );
    }
    t
}

/// The measured growth beside the spectral radius, or what the analysis says about a
/// cycle or a separation.
fn analysis_text(r: &RunResult, s: &RunSettings) -> Option<String> {
    let v = &r.verdict;
    let rho = v.spectral_radius?;
    let lin = v.linear_verdict.map_or("", |x| x.as_str());
    let analysis = format!(
        "spectral radius {} ({lin})",
        crate::output::radius_text(rho)
    );
    let in_contact = if v.linear_window {
        ""
    } else {
        " for the loop in linear contact"
    };
    let measured = v.measured_growth_per_sample.filter(|g| match v.outcome {
        Outcome::Growing => *g > 1.0,
        Outcome::Decaying => *g < 1.0,
        _ => true,
    });
    Some(match (v.outcome, measured) {
        (Outcome::Growing | Outcome::Decaying | Outcome::Undecided, Some(g)) => format!(
            "growth      measured {} per sample{}; analysis: {analysis}{in_contact}",
            crate::output::radius_text(g),
            if v.outcome == Outcome::Undecided {
                " (not settled)"
            } else {
                ""
            }
        ),
        (Outcome::LimitCycle, _) => format!(
            "analysis    {analysis}{in_contact}; {}",
            cycle_explanation(r, s)
        ),
        (Outcome::Separated, _) => format!(
            "analysis    {analysis} while in contact; the run ended out of contact, so it does not test the wall"
        ),
        _ => format!("analysis    {analysis}{in_contact}"),
    })
}

fn cycle_explanation(r: &RunResult, s: &RunSettings) -> String {
    let v = &r.verdict;
    let unstable = v.linear_verdict == Some(Verdict::Unstable);
    let bouncing = v.limit_cycle.is_some_and(|c| c.bouncing);
    let e = &s.effects;
    let mut limits: Vec<&str> = Vec::new();
    if e.quantization.is_some() {
        limits.push("quantization");
    }
    if e.friction.is_some() {
        limits.push("friction");
    }
    if e.saturation.is_some() {
        limits.push("saturation");
    }
    match (bouncing, unstable) {
        (true, true) => "in contact the oscillation grows until the device leaves the wall".into(),
        (true, false) => {
            "the contact itself is stable; the device bounces off the wall and returns".into()
        }
        (false, true) => format!(
            "the growth of the unstable loop is limited by {}",
            limits.join(" and ")
        ),
        (false, false) => format!(
            "the linear loop is stable; {} sustains the cycle",
            limits.join(" and ")
        ),
    }
}

fn contact_text(r: &RunResult) -> String {
    let c = &r.verdict.contact;
    format!(
        "contacts {}, separations {} ({} in the judged window, in contact {} % of it); {} at the end",
        c.contacts,
        c.separations,
        c.judged_separations,
        sig(100.0 * c.judged_contact_fraction, 3),
        if c.in_contact_at_end {
            "in contact"
        } else {
            "out of contact"
        }
    )
}

fn hint_text(r: &RunResult, s: &RunSettings, units: Units, period: f64) -> Option<String> {
    let v = &r.verdict;
    match v.outcome {
        Outcome::Separated if s.human_force <= 0.0 => Some(
            "nothing pushes the device into the wall: give --push F to keep it in contact".into(),
        ),
        Outcome::Separated => Some(
            "the push does not hold the device on the wall; a larger --push keeps it in contact"
                .into(),
        ),
        Outcome::Undecided if v.linear_window && v.linear_verdict == Some(Verdict::Marginal) => {
            Some("the loop is marginal (spectral radius 1): a longer run will not settle it".into())
        }
        Outcome::Undecided if r.samples >= r.max_samples => Some(format!(
            "simulate longer with --max-duration{} (the horizon is now {})",
            if units.physical { "" } else { "-samples" },
            time_text(r.max_samples as f64 * period, units)
        )),
        _ => None,
    }
}
