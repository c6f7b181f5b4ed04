//! Counts in sentences: a number with its noun and the verb that agrees with it, so that a
//! message reads `1 point is` and `3 points are` whatever the count.

/// `n` and `noun`, singular for exactly one and plural (the noun and `s`) otherwise:
/// `count(1, "point")` is `1 point`, `count(0, "point")` and `count(3, "point")` are `0 points`
/// and `3 points`.
///
/// # Examples
/// ```
/// use stiffid::common::words::{count, is_are};
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_is_singular_and_every_other_count_plural() {
        assert_eq!(count(1, "posture"), "1 posture");
        for n in [0, 2, 11, usize::MAX] {
            assert_eq!(count(n, "posture"), format!("{n} postures"));
            assert_eq!(is_are(n), "are");
        }
        assert_eq!(is_are(1), "is");
    }
}
