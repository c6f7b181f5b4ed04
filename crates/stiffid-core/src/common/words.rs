//! Words and numbers in messages: a count with its noun and the verb that agrees with it, so that
//! a message reads `1 point is` and `3 points are` whatever the count; a number short enough to
//! read (`1e308`, never 309 digits), and a value told apart from the limit it is compared with.

/// `n` and `noun`, singular for exactly one and plural (the noun and `s`) otherwise:
/// `count(1, "point")` is `1 point`, `count(0, "point")` and `count(3, "point")` are `0 points`
/// and `3 points`.
///
/// # Examples
/// ```
/// use stiffid_core::common::words::{count, is_are};
/// assert_eq!(format!("{} {} rapid", count(1, "point"), is_are(1)), "1 point is rapid");
/// assert_eq!(format!("{} {} rapid", count(2, "point"), is_are(2)), "2 points are rapid");
/// ```
pub fn count(n: usize, noun: &str) -> String {
    match n {
        1 => format!("1 {noun}"),
        _ => format!("{n} {noun}s"),
    }
}

/// `is` for exactly one, `are` otherwise: the verb after [`count`] (or after `k of n ...`,
/// which agrees with `k`).
pub fn is_are(n: usize) -> &'static str {
    match n {
        1 => "is",
        _ => "are",
    }
}

/// A number for messages: plain for moderate magnitudes, shortest round-trip scientific notation
/// otherwise (`1e308`, never 309 digits); rounded to 12 significant digits ([`as_given`]), so a
/// value the user gave in degrees and converted to radians reads as given (`-60`, not
/// `-59.99999999999999`).
pub fn number(v: f64) -> String {
    let v = as_given(v);
    if v == 0.0 || (1e-4..1e9).contains(&v.abs()) || !v.is_finite() {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// `v` rounded to 12 significant digits: a value the user gave, back in the user's unit after a
/// conversion (degrees to radians and back: `(-60f64).to_radians().to_degrees()` is
/// `-59.99999999999999`, and `as_given` of it `-60`), for messages and documents; a value
/// that reads no shorter rounded (one not finite, a subnormal) as it is.
///
/// # Examples
/// ```
/// use stiffid_core::common::words::as_given;
/// assert_eq!(as_given((-60f64).to_radians().to_degrees()), -60.0);
/// assert_eq!(as_given(15f64.to_radians().to_degrees()), 15.0);
/// assert_eq!(as_given(0.123456789012345), 0.123456789012);
/// ```
pub fn as_given(v: f64) -> f64 {
    let rounded: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    // Only when it reads shorter: a subnormal's rounding would read longer.
    match format!("{rounded:e}").len() < format!("{v:e}").len() {
        true => rounded,
        false => v,
    }
}

/// `value` with 2 decimals, or as many more (up to 9) as tell it apart from the nearer end of
/// `[lower, upper]` printed the same way: `35.001` is not shown as `35.00` beside a limit `35.00`
/// (2 decimals if they are equal).
pub(crate) fn distinct(value: f64, lower: f64, upper: f64) -> String {
    let nearer = match (value - lower).abs() < (value - upper).abs() {
        true => lower,
        false => upper,
    };
    (2..=9)
        .map(|p| (format!("{value:.p$}"), format!("{nearer:.p$}")))
        .find(|(v, n)| v != n)
        .map_or_else(|| format!("{value:.2}"), |(v, _)| v)
}

/// `values` each with the fewest significant digits, at least `least` (and at most 17), at which
/// any two that differ read differently: `4009.1` and `4009.4` are `4009.1` and `4009.4` where
/// four digits would show both as `4009`, and no digit more than that. Plain decimals for
/// magnitudes from 1e-4 to 1e9 (as [`number`]), scientific notation otherwise; a value not finite
/// as Rust writes it.
///
/// # Examples
/// ```
/// use stiffid_core::common::words::apart;
/// assert_eq!(apart(&[4009.1, 4009.4], 4), ["4009.1", "4009.4"]);
/// assert_eq!(apart(&[4009.1, 5000.0], 4), ["4009", "5000"]);
/// assert_eq!(apart(&[1.5e-7, 1.6e-7], 2), ["1.5e-7", "1.6e-7"]);
/// ```
pub fn apart(values: &[f64], least: usize) -> Vec<String> {
    let least = least.clamp(1, 17);
    let at =
        |digits: usize| -> Vec<String> { values.iter().map(|v| significant(*v, digits)).collect() };
    for digits in least..17 {
        let texts = at(digits);
        let apart = (0..values.len()).all(|i| {
            (i + 1..values.len())
                .all(|j| as_given(values[i]) == as_given(values[j]) || texts[i] != texts[j])
        });
        if apart {
            return texts;
        }
    }
    at(17)
}

/// `v` with `digits` significant digits (module docs of [`apart`]), trailing zeros of a decimal
/// fraction kept as the digits ask.
fn significant(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 || (1e-4..1e9).contains(&v.abs()) {
        let magnitude = match v {
            0.0 => 0,
            _ => v.abs().log10().floor() as i64,
        };
        let decimals = (digits as i64 - 1 - magnitude).max(0) as usize;
        return format!("{v:.decimals$}");
    }
    format!("{v:.*e}", digits - 1)
}
