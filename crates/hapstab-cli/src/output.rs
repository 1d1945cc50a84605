//! Shared output helpers: JSON printing and number formatting.

use std::io;

use serde::Serialize;
use serde_json::ser::{CompactFormatter, Formatter, PrettyFormatter};

/// Prints a value as pretty JSON on stdout: shortest round-trip floats, and a negative zero
/// written as 0 (its sign carries no information in any result).
pub fn print_json<T: Serialize>(v: &T) -> anyhow::Result<()> {
    println!("{}", json_text(v)?);
    Ok(())
}

/// The pretty JSON text of a value as [`print_json`] writes it.
pub fn json_text<T: Serialize>(v: &T) -> anyhow::Result<String> {
    let mut bytes = Vec::new();
    let mut ser = serde_json::Serializer::with_formatter(&mut bytes, Clean(PrettyFormatter::new()));
    v.serialize(&mut ser)?;
    Ok(String::from_utf8(bytes)?)
}

/// The compact JSON text of a value (the explorer's answers): shortest round-trip floats and
/// −0 written as 0, as [`print_json`] writes them.
pub fn json_compact<T: Serialize>(v: &T) -> serde_json::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    let mut ser = serde_json::Serializer::with_formatter(&mut bytes, Clean(CompactFormatter));
    v.serialize(&mut ser)?;
    Ok(bytes)
}

/// A serde_json formatter (pretty or compact) with −0 written as 0.
struct Clean<F>(F);

/// Delegates a formatter method to the pretty formatter.
macro_rules! delegate {
    ($($name:ident$(($arg:ident: $t:ty))?),* $(,)?) => {$(
        fn $name<W: ?Sized + io::Write>(&mut self, w: &mut W $(, $arg: $t)?) -> io::Result<()> {
            self.0.$name(w $(, $arg)?)
        }
    )*};
}

impl<F: Formatter> Formatter for Clean<F> {
    delegate!(
        begin_array,
        end_array,
        begin_array_value(first: bool),
        end_array_value,
        begin_object,
        end_object,
        begin_object_key(first: bool),
        begin_object_value,
        end_object_value,
    );

    fn write_f64<W: ?Sized + io::Write>(&mut self, w: &mut W, v: f64) -> io::Result<()> {
        self.0.write_f64(w, if v == 0.0 { 0.0 } else { v })
    }

    fn write_f32<W: ?Sized + io::Write>(&mut self, w: &mut W, v: f32) -> io::Result<()> {
        self.0.write_f32(w, if v == 0.0 { 0.0 } else { v })
    }
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
    // scientific below 1e-4, and from 1e6 on where the integer part alone would show more
    // digits than asked (axis ticks of 4 digits keep "20000")
    if !(-4..=7).contains(&e) || e >= (sig as i32).max(6) {
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

/// Engineering notation with an SI prefix: `eng(2.5e-5, "m", 4)` is "25 µm". The mantissa lies
/// in [1, 1000) from pico to giga; outside that range (and for 0) the number stays unprefixed.
pub fn eng(x: f64, unit: &str, digits: usize) -> String {
    if unit == "kg" {
        // the prefix goes on the gram: 100 g, 1.1 kg
        return eng(x * 1e3, "g", digits);
    }
    const PREFIXES: [(i32, &str); 7] = [
        (-12, "p"),
        (-9, "n"),
        (-6, "µ"),
        (-3, "m"),
        (0, ""),
        (3, "k"),
        (6, "M"),
    ];
    let e3 = if x == 0.0 || !x.is_finite() {
        0
    } else {
        (x.abs().log10() / 3.0).floor() as i32 * 3
    };
    match PREFIXES.iter().find(|(e, _)| *e == e3) {
        Some((e, p)) => format!("{} {p}{unit}", sig(x / 10f64.powi(*e), digits)),
        None => format!("{} {unit}", sig(x, digits)),
    }
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
    fn json_writes_negative_zero_as_zero_and_keeps_key_order() {
        #[derive(Serialize)]
        struct T {
            z: f64,
            a: [f64; 2],
        }
        let text = json_text(&T {
            z: -0.0,
            a: [-0.0, -1.5e-7],
        })
        .unwrap();
        assert!(!text.contains("-0.0"), "{text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["a"][1].as_f64(), Some(-1.5e-7));
        assert!(text.find("\"z\"") < text.find("\"a\""), "{text}");
    }

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
    fn engineering_notation_picks_the_prefix() {
        assert_eq!(eng(2.5e-5, "m", 4), "25 µm");
        assert_eq!(eng(0.0013832, "m", 4), "1.383 mm");
        assert_eq!(eng(8.88, "Hz", 3), "8.88 Hz");
        assert_eq!(eng(20_000.0, "N/m", 3), "20 kN/m");
        assert_eq!(eng(0.0, "s", 3), "0 s");
        assert_eq!(eng(1e-20, "m", 3), "1e-20 m");
        assert_eq!(eng(0.1, "kg", 6), "100 g");
        assert_eq!(eng(1.1, "kg", 6), "1.1 kg");
        assert_eq!(sig(9526042.3, 6), "9.52604e6");
        assert_eq!(sig(986960.44, 6), "986960");
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
