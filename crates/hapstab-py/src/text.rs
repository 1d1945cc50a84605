//! Numbers in `repr` texts: shortest round-trip, as Python writes floats.

/// A float as `repr` would show it (shortest round-trip digits).
pub fn num(x: f64) -> String {
    format!("{x:?}")
}

/// A list of floats as `[a, b, …]`.
pub fn fmt_list(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|&x| num(x)).collect();
    format!("[{}]", items.join(", "))
}
