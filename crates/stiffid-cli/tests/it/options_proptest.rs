//! Property tests of the command's numeric options: arbitrary and hostile values never panic,
//! end with exit code 0 or 2 (one `error: ` line), and an accepted value gives finite output.
//!
//! Generated cases per run: 4 x 48 = 192 (each runs the binary once).

use crate::common;
use crate::mutate;

use common::stiffid;
use proptest::prelude::*;
use serde_json::Value;

const CASES: u32 = 48;

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

fn list(n: usize) -> impl Strategy<Value = String> {
    prop::collection::vec(value(), n..=n).prop_map(|v| v.join(","))
}

/// Exit 0 with JSON whose numbers are all finite (`null` allowed), or the documented error.
fn assert_clean(args: &[&str]) {
    let out = stiffid(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    match out.status.code() {
        Some(0) => {
            let doc: Value = serde_json::from_slice(&out.stdout).unwrap();
            assert_finite(&doc, args);
        }
        Some(2) => {
            assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
            assert!(stderr.starts_with("error: "), "{stderr}");
            assert!(stderr.len() < 2000, "{} bytes", stderr.len());
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
    #![proptest_config(ProptestConfig::with_cases(CASES))]

    #[test]
    fn kinematics_options(q in list(6), point in list(3), length in value()) {
        let length = format!("--characteristic-length-mm={length}");
        assert_clean(&["kinematics", "--robot", "comau-smart5-nj165-3.0", "--q-deg", &q, "--point-mm", &point, &length, "--json"]);
    }

    #[test]
    fn predict_options(q in list(6), wrench in prop_oneof![list(3), list(6)]) {
        assert_clean(&["predict", "--setup", "zhang2021-comau-nj165", "--q-deg", &q, "--wrench", &wrench, "--json"]);
    }

    #[test]
    fn simulate_runs(runs in prop_oneof![(1u64..4).prop_map(|r| r.to_string()), value()], seed in value()) {
        let (runs, seed) = (format!("--runs={runs}"), format!("--seed={seed}"));
        let dir = common::temp_dir("options-simulate");
        let group = common::write_file(&dir, "g.csv", common::GROUP);
        assert_clean(&["simulate", "--setup", "zhang2021-comau-nj165", "--postures", group.to_str().unwrap(), &runs, &seed, "--json"]);
    }

    #[test]
    fn select_counts(evals in prop_oneof![(1u64..40).prop_map(|r| r.to_string()), value()], postures in value(), starts in value()) {
        let dir = common::temp_dir("options-select");
        let out = dir.join("out.csv");
        let args = [format!("--max-evals={evals}"), format!("--postures={postures}"), format!("--starts={starts}")];
        assert_clean(&["select", "--setup", "zhang2021-comau-nj165", "--criterion", "classical", "--start-random", &args[0], &args[1], "--out", out.to_str().unwrap(), "--json"]);
        // --starts only with --global: anything but a small count is refused before searching.
        if !(1..=3).contains(&starts.parse::<i64>().unwrap_or(0)) {
            assert_clean(&["select", "--setup", "zhang2021-comau-nj165", "--criterion", "classical", "--global", &args[2], "--out", out.to_str().unwrap(), "--json"]);
        }
    }
}
