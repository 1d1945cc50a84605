//! Numbers as the figures and the reports write them: a number in significant digits
//! ([`sig`]) and a quantity in engineering notation with an SI prefix ([`eng`]).

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

#[cfg(test)]
mod tests {
    use super::*;

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
}
