//! Decimal numbers of a measurement row: the usual `-123.4567` read directly, the same bits as
//! `str::parse::<f64>` (which reads everything else).
//!
//! A number of at most 15 digits with a point and no exponent is `w / 10^e` with `w < 2^53` and
//! `e <= 22`: both exact in `f64`, so the one division is correctly rounded, as `str::parse` is
//! (Clinger's fast path, W. D. Clinger, "How to read floating point numbers accurately", PLDI 1990).

/// Exact powers of ten in `f64`.
const POWERS: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// `field` as a number, as `field.parse::<f64>().ok()`.
pub(super) fn parse(field: &str) -> Option<f64> {
    fast(field.as_bytes()).or_else(|| field.parse().ok())
}

/// `[+-]digits[.digits]` with 1 to 15 digits, or `None`.
fn fast(bytes: &[u8]) -> Option<f64> {
    let (negative, rest) = match bytes.first()? {
        b'-' => (true, &bytes[1..]),
        b'+' => (false, &bytes[1..]),
        _ => (false, bytes),
    };
    let (mut w, integer) = digits(rest, 0);
    let (mut digits_total, mut fraction) = (integer, 0);
    if let Some(after) = rest[integer..].strip_prefix(b".") {
        let (v, n) = digits(after, w);
        (w, fraction) = (v, n);
        digits_total += n;
        if n + 1 != rest.len() - integer {
            return None;
        }
    } else if integer != rest.len() {
        return None;
    }
    if digits_total == 0 || digits_total > 15 {
        return None;
    }
    let value = w as f64 / POWERS[fraction];
    Some(if negative { -value } else { value })
}

/// `w` followed by the leading decimal digits of `bytes` (wrapping beyond `u64`: the caller
/// refuses more than 15 digits), and how many there are.
fn digits(bytes: &[u8], mut w: u64) -> (u64, usize) {
    let mut n = 0;
    for &b in bytes {
        let d = b.wrapping_sub(b'0');
        if d > 9 {
            break;
        }
        w = w.wrapping_mul(10).wrapping_add(u64::from(d));
        n += 1;
    }
    (w, n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The bits of `str::parse`, or `None` where it fails.
    fn std_bits(s: &str) -> Option<u64> {
        s.parse::<f64>().ok().map(f64::to_bits)
    }

    #[test]
    fn table_matches_std() {
        for s in [
            "0",
            "-0",
            "+0",
            "0.0",
            "-0.000",
            "1.",
            ".5",
            "-.5",
            "+.5",
            "-120.2110768",
            "999999999999999",
            "0.000000000000001",
            "123456789012345",
            "1234567890123456",
            "0.1",
            "0.3",
            "-62.9300",
            "144.9190",
            "007.50",
            ".",
            "-",
            "+",
            "",
            "1..2",
            "1.2.3",
            "--1",
            "+-1",
            "1e5",
            "1E-3",
            "inf",
            "-inf",
            "nan",
            "NaN",
            "infinity",
            "1_0",
            " 1",
            "1 ",
            "0x10",
            "١",
        ] {
            assert_eq!(parse(s).map(f64::to_bits), std_bits(s), "{s:?}");
            if let Some(v) = fast(s.as_bytes()) {
                assert_eq!(Some(v.to_bits()), std_bits(s), "fast path {s:?}");
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20000))]
        #[test]
        fn fast_path_is_std(s in "[-+]?[0-9]{0,9}\\.?[0-9]{0,9}") {
            prop_assert_eq!(parse(&s).map(f64::to_bits), std_bits(&s));
        }

        #[test]
        fn any_text_is_std(s in "[-+.0-9eE a-z]{0,20}") {
            prop_assert_eq!(parse(&s).map(f64::to_bits), std_bits(&s));
        }
    }
}
