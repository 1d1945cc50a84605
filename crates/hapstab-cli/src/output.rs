//! Shared output helpers: JSON printing and number formatting. The JSON text is the
//! explorer's ([`hapstab::json`]), significant digits and engineering notation are the
//! figures' ([`hapstab_plot::text`]).

use serde::Serialize;

pub use hapstab::json::pretty as json_text;
pub use hapstab_plot::text::{eng, sig};

/// Prints a value as pretty JSON on stdout: shortest round-trip floats, and a negative zero
/// written as 0 (its sign carries no information in any result).
pub fn print_json<T: Serialize>(v: &T) -> anyhow::Result<()> {
    println!("{}", json_text(v)?);
    Ok(())
}

/// Significant digits of the human-readable output.
pub const TEXT_DIGITS: usize = 6;

/// A spectral radius (or growth factor per sample) in 6 significant digits, or in as many
/// more as it takes not to round to 1 (a radius beside a verdict must show on which side of
/// the unit circle it lies).
pub fn radius_text(rho: f64) -> String {
    (TEXT_DIGITS..=17)
        .map(|d| sig(rho, d))
        .find(|t| t != "1" || rho == 1.0)
        .unwrap_or_else(|| format!("{rho:e}"))
}

/// A number for a CSV field: the shortest decimal text that reads back to the same f64
/// ("0.5", "1e-7"), −0 written as "0", and an empty field for NaN (no value).
pub fn csv_num(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if x.is_nan() {
        String::new()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        let mut buf = ryu::Buffer::new();
        buf.format_finite(x).trim_end_matches(".0").to_string()
    }
}

/// [`csv_num`] of an optional value (empty when absent).
pub fn csv_opt(x: Option<f64>) -> String {
    x.map(csv_num).unwrap_or_default()
}

/// A value that may be undefined in a human-readable table: the formatted number, or "—"
/// for NaN.
pub fn or_dash(x: f64, f: impl Fn(f64) -> String) -> String {
    if x.is_nan() { "—".into() } else { f(x) }
}

/// A polynomial with descending coefficients as MATLAB displays it, e.g.
/// `z^2 - 1.655 z + 0.7408`: `digits` significant digits, zero terms left out, a unit
/// coefficient shown only on the constant term.
pub fn poly_text(desc: &[f64], var: &str, digits: usize) -> String {
    let n = desc.len().saturating_sub(1);
    let mut out = String::new();
    for (i, &c) in desc.iter().enumerate() {
        if c == 0.0 {
            continue;
        }
        let power = n - i;
        let sign = if c < 0.0 { "-" } else { "+" };
        if out.is_empty() {
            if c < 0.0 {
                out.push('-');
            }
        } else {
            out.push_str(&format!(" {sign} "));
        }
        let mag = c.abs();
        let number = sig(mag, digits);
        let var_part = match power {
            0 => String::new(),
            1 => var.to_string(),
            p => format!("{var}^{p}"),
        };
        match (power, number.as_str()) {
            (0, _) => out.push_str(&number),
            (_, "1") => out.push_str(&var_part),
            _ => out.push_str(&format!("{number} {var_part}")),
        }
    }
    if out.is_empty() { "0".into() } else { out }
}

/// Ascending coefficients reversed into descending order (MATLAB's and python-control's).
pub fn descending(asc: &[f64]) -> Vec<f64> {
    asc.iter().rev().copied().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radius_text_never_rounds_to_one() {
        assert_eq!(radius_text(0.994314440240548), "0.994314");
        assert_eq!(radius_text(1.0 - 1e-9), "0.999999999");
        assert_eq!(radius_text(1.0 + 2e-12), "1.000000000002");
        assert_eq!(radius_text(1.0), "1");
    }

    #[test]
    fn csv_numbers_are_shortest_round_trip() {
        for x in [0.1, 1.0 / 3.0, -2.5e-300, 1e22, 350.0, 123456.789] {
            assert_eq!(csv_num(x).parse::<f64>().unwrap(), x);
        }
        assert_eq!(csv_num(0.0), "0");
        assert_eq!(csv_num(-0.0), "0");
        assert_eq!(csv_num(350.0), "350");
        assert_eq!(csv_num(1e-7), "1e-7");
        assert_eq!(csv_num(f64::NAN), "");
    }

    #[test]
    fn polynomials_read_like_matlab() {
        assert_eq!(
            poly_text(&[1.0, -1.655, 0.7408], "z", 6),
            "z^2 - 1.655 z + 0.7408"
        );
        assert_eq!(
            poly_text(&[0.01187, 0.06408, 0.009721], "z", 4),
            "0.01187 z^2 + 0.06408 z + 0.009721"
        );
        assert_eq!(poly_text(&[-2.0, 0.0, 1.0], "s", 6), "-2 s^2 + 1");
        assert_eq!(poly_text(&[1.0, 0.0], "z", 6), "z");
        assert_eq!(poly_text(&[0.0, 0.0], "z", 6), "0");
        assert_eq!(poly_text(&[10.0], "s", 6), "10");
    }
}
