//! Mutations of real input files for property tests: hostile numbers, inserted text, deleted
//! spans. Shared by the library's parser tests and the command's (`#[path]` include).
#![allow(dead_code)] // each includer uses its own subset

use proptest::prelude::*;

/// Numbers a hostile user types.
pub fn hostile_number() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(vec![
            "nan",
            "NaN",
            "inf",
            "-inf",
            "1e308",
            "-1e308",
            "1e-320",
            "-0",
            "0",
            "1e5",
            "-1e5",
            "99999999999999999999999",
            "0.0000001",
            "1e-12",
        ])
        .prop_map(str::to_string),
        any::<f64>().prop_map(|v| format!("{v:?}")),
        (-1e6..1e6f64).prop_map(|v| v.to_string()),
    ]
}

/// One edit of a text: at a relative position, replace a number, insert text or delete a span.
#[derive(Debug, Clone)]
pub enum Edit {
    /// Replace the number with this index (modulo their count) by this text.
    Number(usize, String),
    /// Insert text at this relative position.
    Insert(f64, String),
    /// Delete this many bytes from this relative position.
    Delete(f64, usize),
}

pub fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), hostile_number()).prop_map(|(i, n)| Edit::Number(i, n)),
        (0.0..1.0f64, "[ -~\\n]{0,12}").prop_map(|(p, s)| Edit::Insert(p, s)),
        (0.0..1.0f64, 1usize..40).prop_map(|(p, n)| Edit::Delete(p, n)),
    ]
}

/// The byte spans of the numbers in `text` (runs of digits, signs, points and exponents that
/// hold a digit).
pub fn numbers(text: &str) -> Vec<(usize, usize)> {
    let is_num = |c: u8| c.is_ascii_digit() || b".-+eE".contains(&c);
    let b = text.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if is_num(b[i]) && (i == 0 || !b[i - 1].is_ascii_alphanumeric() && b[i - 1] != b'_') {
            let start = i;
            while i < b.len() && is_num(b[i]) {
                i += 1;
            }
            if b[start..i].iter().any(u8::is_ascii_digit) {
                spans.push((start, i));
            }
        } else {
            i += 1;
        }
    }
    spans
}

fn floor_boundary(text: &str, mut i: usize) -> usize {
    i = i.min(text.len());
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

pub fn apply(text: &str, edits: &[Edit]) -> String {
    let mut s = text.to_string();
    for e in edits {
        match e {
            Edit::Number(k, n) => {
                let spans = numbers(&s);
                if let Some(&(a, b)) = spans.get(k % spans.len().max(1)) {
                    s.replace_range(a..b, n);
                }
            }
            Edit::Insert(p, t) => {
                let i = floor_boundary(&s, (p * s.len() as f64) as usize);
                s.insert_str(i, t);
            }
            Edit::Delete(p, n) => {
                let a = floor_boundary(&s, (p * s.len() as f64) as usize);
                let b = floor_boundary(&s, a + n);
                s.replace_range(a..b, "");
            }
        }
    }
    s
}

/// The generated inputs of one property test and how many of them were accepted: a property
/// test whose generator no longer reaches the parser (every input refused at its first line)
/// would pass without testing anything, so each test states the least it must see accepted.
pub struct Tally {
    name: &'static str,
    cases: u32,
    least: u32,
    seen: std::sync::atomic::AtomicU32,
    accepted: std::sync::atomic::AtomicU32,
}

impl Tally {
    /// A tally of `cases` inputs of which at least `least` must be accepted.
    pub const fn new(name: &'static str, cases: u32, least: u32) -> Self {
        Self {
            name,
            cases,
            least,
            seen: std::sync::atomic::AtomicU32::new(0),
            accepted: std::sync::atomic::AtomicU32::new(0),
        }
    }

    /// Counts one input. At the `cases`-th it prints `NAME: A of N generated inputs accepted`
    /// (shown by `cargo test -- --nocapture`) and checks that at least `least` were.
    pub fn count(&self, accepted: bool) {
        use std::sync::atomic::Ordering::SeqCst;
        let a = self.accepted.fetch_add(accepted as u32, SeqCst) + accepted as u32;
        if self.seen.fetch_add(1, SeqCst) + 1 == self.cases {
            eprintln!(
                "{}: {a} of {} generated inputs accepted",
                self.name, self.cases
            );
            assert!(
                a >= self.least,
                "{}: only {a} of {} generated inputs accepted (at least {} expected): the generator no longer exercises the parser",
                self.name,
                self.cases,
                self.least
            );
        }
    }
}
