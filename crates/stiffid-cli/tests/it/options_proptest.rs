//! Property tests of the command's numeric options: arbitrary and hostile values never panic,
//! end with exit code 0 or 2 (one `error: ` line), and an accepted value gives finite output.
//!
//! Generated cases per run: 4 x 48 = 192 (each runs the binary once). Each test counts the
//! inputs the command accepted (`mutate::Tally`), prints the count (`cargo test -- --nocapture`)
//! and fails when fewer than its least were: values are mostly plausible, one in ten hostile, so
//! that the options are exercised past their parsing.

use crate::common;
use crate::mutate;

use common::stiffid;
use mutate::Tally;
use proptest::prelude::*;
use serde_json::Value;

const CASES: u32 = 48;
// The least accepted of each test's inputs (`Tally`): well below what a run accepts (seen: 10-11,
// 8-10, 40-41, 29-36 of 48), so that a random run falls below it with a probability under 1e-3.
const LEAST_KINEMATICS: u32 = 2;
const LEAST_PREDICT: u32 = 1;
const LEAST_SIMULATE: u32 = 25;
const LEAST_SELECT: u32 = 18;

/// A value a hostile user types for a number: hostile numbers, huge integers, junk.
fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        mutate::hostile_number(),
        prop::sample::select(vec![
            "",
            "-1",
            "18446744073709551616",
            "9223372036854775808",
            "3074457345618258603",
            "1e9",
            "0x10",
        ])
        .prop_map(str::to_string),
        (-200.0..200.0f64).prop_map(|v| format!("{v:.3}")),
        any::<u64>().prop_map(|v| v.to_string()),
        "[ -~]{0,20}",
    ]
}

/// A number a user means to type or, one in ten, a hostile value ([`value`]).
fn mostly_valid(valid: impl Strategy<Value = String> + 'static) -> impl Strategy<Value = String> {
    prop_oneof![9 => valid.boxed(), 1 => value().boxed()]
}

/// `n` values, comma-separated: each a plain number within +-`max` or, one in ten, hostile.
fn list(n: usize, max: f64) -> impl Strategy<Value = String> {
    let number = (-max..max).prop_map(|v| format!("{v:.3}"));
    prop::collection::vec(mostly_valid(number), n..=n).prop_map(|v| v.join(","))
}

/// A small count or, one in ten, a hostile value.
fn count(max: u64) -> impl Strategy<Value = String> {
    mostly_valid((1..=max).prop_map(|v| v.to_string()))
}

/// Exit 0 with JSON whose numbers are all finite (`null` allowed), or the documented error;
/// whether the values were accepted (exit 0).
fn assert_clean(args: &[&str]) -> bool {
    let out = stiffid(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    match out.status.code() {
        Some(0) => {
            let doc: Value = serde_json::from_slice(&out.stdout).unwrap();
            assert_finite(&doc, args);
            true
        }
        Some(2) => {
            assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
            assert!(stderr.starts_with("error: "), "{stderr}");
            assert!(stderr.len() < 2000, "{} bytes", stderr.len());
            false
        }
        other => panic!("{args:?}: exit {other:?}: {stderr}"),
    }
}

fn assert_finite(v: &Value, args: &[&str]) {
    match v {
        Value::Number(n) => assert!(n.as_f64().is_some_and(f64::is_finite), "{args:?}"),
        Value::Array(a) => a.iter().for_each(|x| assert_finite(x, args)),
        Value::Object(o) => o.values().for_each(|x| assert_finite(x, args)),
        _ => {}
    }
}

proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig {
        // A fixed seed: every run tries the same cases (set another to explore).
        rng_seed: proptest::test_runner::RngSeed::Fixed(20_211_126),
        ..proptest::prelude::ProptestConfig::with_cases(CASES)
    })]

    #[test]
    fn kinematics_options(q in list(6, 40.0), point in list(3, 500.0), length in mostly_valid((1.0..5000.0f64).prop_map(|v| v.to_string()))) {
        let length = format!("--characteristic-length-mm={length}");
        static TALLY: Tally = Tally::new("kinematics options", CASES, LEAST_KINEMATICS);
        TALLY.count(assert_clean(&["kinematics", "--robot", "comau-smart5-nj165-3.0", "--q-deg", &q, "--point-mm", &point, &length, "--json"]));
    }

    #[test]
    fn predict_options(q in list(6, 40.0), wrench in prop_oneof![list(3, 2000.0), list(6, 2000.0)]) {
        static TALLY: Tally = Tally::new("predict options", CASES, LEAST_PREDICT);
        TALLY.count(assert_clean(&["predict", "--setup", "zhang2021-comau-nj165", "--q-deg", &q, "--wrench", &wrench, "--json"]));
    }

    #[test]
    fn simulate_runs(runs in count(3), seed in mostly_valid(any::<u64>().prop_map(|v| v.to_string()))) {
        let (runs, seed) = (format!("--runs={runs}"), format!("--seed={seed}"));
        let dir = common::temp_dir("options-simulate");
        let group = common::write_file(&dir, "g.csv", common::GROUP);
        static TALLY: Tally = Tally::new("simulate runs and seed", CASES, LEAST_SIMULATE);
        TALLY.count(assert_clean(&["simulate", "--setup", "zhang2021-comau-nj165", "--postures", group.to_str().unwrap(), &runs, &seed, "--json"]));
    }

    #[test]
    fn select_counts(evals in count(40), postures in count(12), starts in value()) {
        let dir = common::temp_dir("options-select");
        let out = dir.join("out.csv");
        let args = [format!("--max-evals={evals}"), format!("--count={postures}"), format!("--starts={starts}")];
        static TALLY: Tally = Tally::new("select counts", CASES, LEAST_SELECT);
        TALLY.count(assert_clean(&["select", "--setup", "zhang2021-comau-nj165", "--criterion", "classical", "--start-random", &args[0], &args[1], "--out", out.to_str().unwrap(), "--json"]));
        // --starts only with --global: anything but a small count is refused before searching.
        if !(1..=3).contains(&starts.parse::<i64>().unwrap_or(0)) {
            assert_clean(&["select", "--setup", "zhang2021-comau-nj165", "--criterion", "classical", "--global", &args[2], "--out", out.to_str().unwrap(), "--json"]);
        }
    }
}
