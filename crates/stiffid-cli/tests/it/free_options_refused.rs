//! The free variables' options of `compensate` (`--free-lead-tilt`, `--cone-deg`,
//! `--lead-tilt-step-deg`, `--free-tilt-deg`, `--tilt-step-deg`, `--free-configuration`) and
//! `place`'s region (`--region-mm`, `--rotation-deg`), given hostile values: one test per class
//! of problem (not finite, negative or zero, too large or too small, empty, combinations that
//! make no sense), each refused with exit code 2 in one line naming the option, no panic,
//! nothing written.

use crate::common::example;
use crate::common::{refused, temp_dir};
use std::path::Path;

/// `compensate` of the milling example's path (`--free-lead-tilt` given) or of the track's
/// table cut (a two-axis positioner), output into `{dir}`.
fn compensate(track: bool) -> Vec<String> {
    let (setup, stiffness, path) = match track {
        false => (
            "milling/fanuc-milling.toml",
            "milling/stiffness.json",
            "milling/path.csv",
        ),
        true => (
            "track/track-cell.toml",
            "milling/kuka-stiffness.json",
            "track/table.csv",
        ),
    };
    let mut args: Vec<String> = ["compensate", "--setup", &example(setup), "--stiffness"]
        .map(String::from)
        .into();
    args.extend([example(stiffness), "--path".into(), example(path)]);
    args.extend(["--out".into(), "{dir}/out.csv".into()]);
    args
}

/// `place` of the trim line, output into `{dir}`, the search as small as it goes.
fn place() -> Vec<String> {
    let mut args: Vec<String> = vec!["place".into(), "--setup".into()];
    args.push(example("milling/fanuc-milling.toml"));
    args.extend(["--stiffness".into(), example("milling/stiffness.json")]);
    args.extend(["--program".into(), example("milling/trim.nc")]);
    args.extend(["--process".into(), example("milling/trim.toml")]);
    let small = ["--grid", "2", "--samples", "0", "--starts", "1"];
    args.extend(small.map(String::from));
    args.extend(["--out".into(), "{dir}/placed.toml".into()]);
    args
}

/// Each value of `values` given to `option` (after `base` and `extra`) is refused naming
/// `names` (the option by default).
fn each_refused(dir: &Path, (base, extra): (&[String], &[&str]), option: &str, values: &[&str]) {
    for v in values {
        let mut args: Vec<&str> = base.iter().map(String::as_str).collect();
        args.extend(extra);
        let given = format!("{option}={v}");
        args.push(&given);
        refused(dir, &args, &[option]);
    }
}

/// Every option with its base command and what it needs beside it.
fn options() -> Vec<(Vec<String>, Vec<&'static str>, &'static str)> {
    let lean = vec!["--free-lead-tilt"];
    let cone = vec!["--free-lead-tilt", "--cone-deg", "5"];
    let tilt = vec!["--free-tilt-deg", "10"];
    let region = vec!["--region-mm", "500,2000,-1500,500"];
    vec![
        (compensate(false), lean, "--cone-deg"),
        (compensate(false), cone, "--lead-tilt-step-deg"),
        (compensate(true), vec![], "--free-tilt-deg"),
        (compensate(true), tilt, "--tilt-step-deg"),
        (place(), vec![], "--region-mm"),
        (place(), region, "--rotation-deg"),
    ]
}

/// The value `v` repeated as many times as `option` takes numbers.
fn spread(option: &str, v: &str) -> String {
    let n = match option {
        "--region-mm" => 4,
        "--rotation-deg" => 2,
        _ => 1,
    };
    vec![v; n].join(",")
}

/// Runs `values` (each spread over the option's numbers) through every option.
fn through_every_option(name: &str, values: &[&str]) {
    let dir = temp_dir(name);
    for (base, extra, option) in options() {
        let values: Vec<String> = values.iter().map(|v| spread(option, v)).collect();
        let values: Vec<&str> = values.iter().map(String::as_str).collect();
        each_refused(&dir, (&base, &extra), option, &values);
    }
}

#[test]
fn values_that_are_not_finite_are_refused_naming_the_option() {
    through_every_option("hostile-not-finite", &["NaN", "inf", "-inf"]);
}

#[test]
fn negative_and_zero_values_are_refused_naming_the_option() {
    // Zero is a valid coordinate of the region: its ranges are refused reversed instead.
    let dir = temp_dir("hostile-negative");
    for (base, extra, option) in options() {
        let values: Vec<String> = match option {
            "--region-mm" => vec!["0,-1,0,1".into(), "0,1,0,-1".into()],
            "--rotation-deg" => vec!["0,-1".into()],
            _ => vec!["-1".into(), "0".into(), "-0".into()],
        };
        let values: Vec<&str> = values.iter().map(String::as_str).collect();
        each_refused(&dir, (&base, &extra), option, &values);
    }
}

#[test]
fn huge_and_tiny_values_are_refused_naming_the_option() {
    through_every_option("hostile-huge", &["1e308", "1e9"]);
    // A range below the smallest step names the range, not the step it was given.
    let dir = temp_dir("hostile-tiny");
    let tiny = [
        (compensate(false), vec!["--free-lead-tilt"], "--cone-deg"),
        (compensate(true), vec![], "--free-tilt-deg"),
    ];
    for (base, extra, option) in tiny {
        each_refused(&dir, (&base, &extra), option, &["1e-300", "0.001"]);
    }
    let steps = [
        (
            compensate(false),
            vec!["--free-lead-tilt", "--cone-deg", "5"],
            "--lead-tilt-step-deg",
        ),
        (
            compensate(true),
            vec!["--free-tilt-deg", "10"],
            "--tilt-step-deg",
        ),
    ];
    for (base, extra, option) in steps {
        each_refused(&dir, (&base, &extra), option, &["1e-300", "0.001"]);
    }
}

#[test]
fn empty_and_malformed_values_are_refused_naming_the_option() {
    let dir = temp_dir("hostile-empty");
    for (base, extra, option) in options() {
        let mut values = vec!["", " ", "x"];
        if matches!(option, "--region-mm" | "--rotation-deg") {
            values.extend([",", "1,2,3,4,5", "1,,2,3"]);
        }
        each_refused(&dir, (&base, &extra), option, &values);
    }
}

#[test]
fn combinations_that_make_no_sense_are_refused_naming_the_option() {
    let dir = temp_dir("hostile-combinations");
    let run = |base: Vec<String>, extra: &[&str], names: &[&str]| {
        let mut args: Vec<&str> = base.iter().map(String::as_str).collect();
        args.extend(extra);
        refused(&dir, &args, names);
    };
    let program = |extra: &[&str]| {
        let mut args = compensate(false);
        args.truncate(5);
        args.extend(["--program".into(), example("milling/trim.nc")]);
        args.extend(["--process".into(), example("milling/trim.toml")]);
        args.extend(["--out".into(), "{dir}/trim.ls".into()]);
        args.extend(extra.iter().map(|s| s.to_string()));
        args
    };
    // A tilt on a robot without a positioner; a step without its range.
    run(
        compensate(false),
        &["--free-tilt-deg", "10"],
        &["--free-tilt-deg", "positioner"],
    );
    run(
        compensate(true),
        &["--tilt-step-deg", "5"],
        &["--free-tilt-deg"],
    );
    // A cone without the lean; a program's cone given as an option; a process without a cone.
    run(
        compensate(false),
        &["--cone-deg", "5"],
        &["--free-lead-tilt"],
    );
    run(
        program(&["--free-lead-tilt", "--cone-deg", "5"]),
        &[],
        &["--cone-deg", "process file"],
    );
    run(
        program(&["--free-lead-tilt"]),
        &[],
        &["--cone-deg", "allows no lean"],
    );
    // The surge minimised by the lean or the configuration.
    let surge = ["--free-tool-axis", "--free-tool-axis-objective", "surge"];
    let lean_surge: Vec<&str> = ["--free-lead-tilt", "--cone-deg", "5"]
        .into_iter()
        .chain(surge)
        .collect();
    run(
        compensate(false),
        &lean_surge,
        &["--free-tool-axis-objective"],
    );
    let config_surge: Vec<&str> = ["--free-configuration"].into_iter().chain(surge).collect();
    run(compensate(false), &config_surge, &["--free-configuration"]);
    run(
        compensate(false),
        &["--free-configuration", "--free-configuration"],
        &["--free-configuration"],
    );
    // A map of the track on a fixed base, with the lean free.
    let track_map = [
        "--free-lead-tilt",
        "--cone-deg",
        "5",
        "--map",
        "track",
        "--report",
        "{dir}/report",
    ];
    run(compensate(false), &track_map, &["--map", "carrier"]);
    // A lean grid beyond the cells a path may take.
    let fine = [
        "--free-lead-tilt",
        "--cone-deg",
        "30",
        "--lead-tilt-step-deg",
        "0.1",
        "--free-tool-axis",
    ];
    run(
        compensate(false),
        &fine,
        &["--lead-tilt-step-deg", "at most 5e6"],
    );
    // A region that holds no feasible placement; --z-mm without --free.
    run(
        place(),
        &["--region-mm", "-20000,-19000,-20000,-19000"],
        &["--region-mm", "no placement"],
    );
    run(
        place(),
        &["--region-mm", "500,2000,-1500,500", "--z-mm", "0,10"],
        &["--free"],
    );
}
