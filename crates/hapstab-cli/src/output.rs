//! Shared output helpers: JSON printing and number formatting.

use serde::Serialize;

/// Prints a value as pretty JSON on stdout.
pub fn print_json<T: Serialize>(v: &T) -> anyhow::Result<()> {
    println!("{}", serde_json::to_string_pretty(v)?);
    Ok(())
}

/// Formats a number with `sig` significant digits (trailing zeros dropped), switching to
/// scientific notation for very small or large magnitudes.
pub fn sig(x: f64, sig: usize) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    let e = x.abs().log10().floor() as i32;
    if !(-4..=7).contains(&e) {
        let s = format!("{:.*e}", sig.saturating_sub(1), x);
        let (m, ex) = s.split_once('e').unwrap_or((&s, "0"));
        format!("{}e{}", trim(m), ex)
    } else {
        let decimals = (sig as i32 - 1 - e).max(0) as usize;
        trim(&format!("{:.*}", decimals, x)).to_string()
    }
}

fn trim(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}
