//! The text report of `hapstab identify`: the fit, the parameter table with standard errors
//! and 95 % intervals in engineering notation, the residual tests, and K_max at B = 0 with
//! its uncertainty.

use hapstab::identify::{CorrelationTest, Estimate, Identification, StiffnessLimit};
use hapstab::model::Loop;

use super::IdentifyArgs;
use crate::output::{eng, sig};
use hapstab_plot::Saved;

/// Significant digits of the estimates.
const DIGITS: usize = 6;

/// A value in its unit: engineering notation for the physical units, plain significant
/// digits for a transfer function's coefficients.
fn value(x: f64, unit: &str, digits: usize) -> String {
    match unit {
        "kg" | "Ns/m" | "N/m" | "m" | "s" => eng(x, unit, digits),
        _ => format!("{} {unit}", sig(x, digits)),
    }
}

fn row(e: &Estimate) -> String {
    let est = value(e.value, &e.unit, DIGITS);
    match (e.standard_error, e.ci95) {
        (Some(se), Some([lo, hi])) => format!(
            "  {:<24} {:<16} {:<14} [{}, {}]",
            e.name,
            est,
            value(se, &e.unit, 3),
            value(lo, &e.unit, DIGITS),
            value(hi, &e.unit, DIGITS)
        ),
        _ => format!("  {:<24} {:<16} (held)", e.name, est),
    }
}

fn test_line(what: &str, t: &CorrelationTest, stat: &str) -> String {
    format!(
        "{what}: {} ({stat} = {} {} {} at {} lags, 95 %)",
        if t.passes { "yes" } else { "NO" },
        sig(t.statistic, 4),
        if t.passes { "<" } else { "≥" },
        sig(t.threshold, 4),
        t.lags
    )
}

fn k_max_lines(lim: &StiffnessLimit) -> Vec<String> {
    let k = |x: Option<f64>| x.map_or("none stable".to_string(), |k| eng(k, "N/m", DIGITS));
    let range =
        |[lo, hi]: [f64; 2]| format!("[{}, {}]", eng(lo, "N/m", DIGITS), eng(hi, "N/m", DIGITS));
    let mut out = vec![format!("K_max at B = 0    {}", k(lim.k_max))];
    if let Some(p) = &lim.interval {
        out.push(format!(
            "  95 % interval   {} (delta method, standard error {})",
            range(p.ci95),
            eng(p.standard_error, "N/m", 3)
        ));
    }
    if let Some(r) = lim.spread {
        out.push(format!(
            "  95 % spread     {} over {} loops drawn from the parameters' covariance",
            range(r),
            lim.valid_draws
        ));
    }
    if let Some(r) = lim.box_range {
        out.push(format!(
            "  over the box    {}: K_max over the parameters' 95 % box",
            range(r)
        ));
    }
    if let Some(r) = &lim.robust {
        let worst: Vec<String> = r
            .worst_plant
            .iter()
            .map(|p| format!("{} = {}", p.param, value(p.value, p.unit, DIGITS)))
            .collect();
        out.push(format!(
            "  robust          {} for every plant in the parameters' 95 % box (worst: {})",
            k(r.k_max),
            worst.join(", ")
        ));
    }
    if let Some(b) = &lim.renderable {
        out.push(format!(
            "K_max, B ≤ B_r    {} over the renderable band 0 ≤ B ≤ {} (Δ = {}, F_n = {})",
            k(b.band.k_max),
            eng(b.band.b_max, "Ns/m", DIGITS),
            eng(b.band.noise.position_resolution, "m", DIGITS),
            eng(b.band.noise.force_noise, "N", DIGITS)
        ));
        if let Some(p) = &b.interval {
            out.push(format!(
                "  95 % interval   {} (delta method, standard error {})",
                range(p.ci95),
                eng(p.standard_error, "N/m", 3)
            ));
        }
    }
    out
}

/// The model, the data and the fit in two lines.
fn header(id: &Identification) {
    let lag = if id.force_lag > 0.0 {
        format!(", force lag τ = {}", eng(id.force_lag, "s", DIGITS))
    } else {
        String::new()
    };
    let (what, residual) = if id.source == "time" {
        ("samples", eng(id.fit.residual_rms, "m", 3))
    } else {
        (
            "frequencies",
            format!("{} Np/rad (ln Ĥ/H)", sig(id.fit.residual_rms, 3)),
        )
    };
    println!(
        "model     {}, {} {what} at T = {}, t_d = {}{lag}",
        id.model,
        id.fit.samples,
        eng(id.period, "s", DIGITS),
        eng(id.delay_time, "s", DIGITS),
    );
    println!(
        "fit       {} % (NRMSE {}), residual RMS {residual}, {} evaluations",
        sig(id.fit.fit_percent, 4),
        sig(id.fit.nrmse, 3),
        id.evaluations
    );
}

/// Prints the report.
pub fn print(
    id: &Identification,
    lim: &StiffnessLimit,
    lp: &Loop,
    args: &IdentifyArgs,
    saved: Option<&Saved>,
) {
    header(id);
    println!();
    println!(
        "  {:<24} {:<16} {:<14} 95 % interval",
        "parameter", "estimate", "std. error"
    );
    for e in &id.parameters {
        println!("{}", row(e));
    }
    for (i, e) in id.position_offsets.iter().enumerate() {
        let mut e = e.clone();
        if id.position_offsets.len() > 1 {
            e.name = format!("offset of run {}", i + 1);
        }
        println!("{}", row(&e));
    }
    if id.runs.len() > 1 {
        for (i, q) in id.runs.iter().enumerate() {
            println!(
                "  run {:<20} fit {} % (NRMSE {}), residual RMS {}",
                i + 1,
                sig(q.fit_percent, 4),
                sig(q.nrmse, 3),
                eng(q.residual_rms, "m", 3)
            );
        }
    }
    println!();
    println!(
        "{}",
        test_line("residuals white", &id.whiteness, "Ljung–Box Q")
    );
    if let Some(t) = &id.cross_correlation {
        println!(
            "{}",
            test_line("residuals uncorrelated with the force", t, "S")
        );
    }
    println!();
    for l in k_max_lines(lim) {
        println!("{l}");
    }
    println!(
        "  velocity        {} (the wall's estimator, --velocity)",
        lp.velocity
    );
    if let Some(p) = &args.write_loop {
        println!(
            "loop file         {} (use it as --loop {})",
            p.display(),
            p.display()
        );
    }
    if let Some(s) = saved {
        println!("plot              {}, {}", s.svg.display(), s.png.display());
    }
}

/// Prints the bootstrap's intervals beside the Jacobian's.
pub fn print_bootstrap(id: &Identification, b: &hapstab::identify::bootstrap::Bootstrap) {
    println!(
        "bootstrap         95 % intervals from {} of {} residual-resampled refits:",
        b.converged, b.replicates
    );
    for p in &b.parameters {
        let unit = id.parameter(&p.name).map_or("", |e| e.unit.as_str());
        println!(
            "  {:<24} [{}, {}]",
            p.name,
            value(p.ci95[0], unit, DIGITS),
            value(p.ci95[1], unit, DIGITS)
        );
    }
}
