//! The free variables' options of `compensate` (`--free lead-tilt=-CONE..CONE/STEP`,
//! `--free tilt=-R..R/STEP`, `--free configuration`, the texts of `--free`, the options of the
//! free variables given without one and the options `--free` replaced) and
//! `place`'s region (`--region-mm`, `--rotation-deg`), given hostile values: one test per class
//! of problem (not finite, negative or zero, too large or too small, empty, combinations that
//! make no sense), each refused with exit code 2 in one line naming the option, no panic,
//! nothing written.

use crate::common::example;
use crate::common::{refused, temp_dir};
use std::path::Path;

/// `compensate` of the milling example's path or of the track's
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

/// One option given hostile values: its base command, what it needs beside it, how a value
/// `v` is written (the arguments) and the names its refusal must hold.
struct Given {
    base: Vec<String>,
    extra: Vec<&'static str>,
    write: fn(&str) -> Vec<String>,
    names: Vec<&'static str>,
}

/// Each value of `values` written by `given` is refused naming its names.
fn each_refused(dir: &Path, given: &Given, values: &[&str]) {
    for v in values {
        let mut args: Vec<String> = given.base.clone();
        args.extend(given.extra.iter().map(|s| s.to_string()));
        args.extend((given.write)(v));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(dir, &args, &given.names);
    }
}

/// A `--free` of `text`.
fn free(text: String) -> Vec<String> {
    vec!["--free".into(), text]
}

/// The lean's cone, the lean's step, the tilt's range and step, the place region and rotation.
fn options() -> Vec<Given> {
    let region = vec!["--region-mm", "500,2000,-1500,500"];
    let lean = ["--free", "lead-tilt"];
    let tilt = ["--free", "tilt"];
    vec![
        Given {
            base: compensate(false),
            extra: vec![],
            write: |v| free(format!("lead-tilt=-{v}..{v}")),
            names: lean.to_vec(),
        },
        Given {
            base: compensate(false),
            extra: vec![],
            write: |v| free(format!("lead-tilt=-5..5/{v}")),
            names: lean.to_vec(),
        },
        Given {
            base: compensate(true),
            extra: vec![],
            write: |v| free(format!("tilt=-{v}..{v}")),
            names: tilt.to_vec(),
        },
        Given {
            base: compensate(true),
            extra: vec![],
            write: |v| free(format!("tilt=-10..10/{v}")),
            names: tilt.to_vec(),
        },
        Given {
            base: place(),
            extra: vec![],
            write: |v| vec![format!("--region-mm={}", [v; 4].join(","))],
            names: vec!["--region-mm"],
        },
        Given {
            base: place(),
            extra: region,
            write: |v| vec![format!("--rotation-deg={}", [v; 2].join(","))],
            names: vec!["--rotation-deg"],
        },
    ]
}

/// Runs `values` through every option.
fn through_every_option(name: &str, values: &[&str]) {
    let dir = temp_dir(name);
    for given in options() {
        each_refused(&dir, &given, values);
    }
}

#[test]
fn values_that_are_not_finite_are_refused_naming_the_option() {
    through_every_option("hostile-not-finite", &["NaN", "inf", "-inf"]);
}

#[test]
fn negative_and_zero_values_are_refused_naming_the_option() {
    let dir = temp_dir("hostile-negative");
    for given in options().into_iter().take(4) {
        each_refused(&dir, &given, &["-1", "0", "-0"]);
    }
    // Zero is a valid coordinate of the region: its ranges are refused reversed instead.
    for (option, value) in [
        ("--region-mm", "0,-1,0,1"),
        ("--region-mm", "0,1,0,-1"),
        ("--rotation-deg", "0,-1"),
    ] {
        let mut args = place();
        if option == "--rotation-deg" {
            args.extend(["--region-mm".into(), "500,2000,-1500,500".into()]);
        }
        args.push(format!("{option}={value}"));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&dir, &args, &[option]);
    }
}

#[test]
fn huge_and_tiny_values_are_refused_naming_the_option() {
    through_every_option("hostile-huge", &["1e308", "1e9"]);
    // A range below the smallest step names the range, not the step it was given.
    let dir = temp_dir("hostile-tiny");
    for given in options().into_iter().take(4) {
        each_refused(&dir, &given, &["1e-300", "0.001"]);
    }
}

#[test]
fn empty_and_malformed_values_are_refused_naming_the_option() {
    let dir = temp_dir("hostile-empty");
    for given in options() {
        each_refused(&dir, &given, &["", " ", "x"]);
    }
    let place_region = &options()[4];
    each_refused(&dir, place_region, &[",", "1,2,3,4,5", "1,,2,3"]);
    // The --free texts themselves.
    let malformed = [
        "tool-rotation=90",
        "tool-rotation=-90..80",
        "tool-rotation=..90",
        "tool-rotation=-90..90/",
        "=-90..90",
        "spindle=-90..90",
        "configuration=each",
    ];
    for text in malformed {
        let mut args = compensate(false);
        args.extend(free(text.into()));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        // A name is checked against the cell's axes: its refusal names the name.
        let named = text
            .strip_prefix("spindle")
            .map_or(text, |_| "spindle: unknown variable");
        refused(&dir, &args, &["--free", named]);
    }
}

/// A command refused: its arguments and the names its refusal must hold.
type Refusal = (Vec<String>, Vec<&'static str>);

/// `base` with `extra` after it, refused naming `names`.
fn case(mut base: Vec<String>, extra: &[&str], names: &[&'static str]) -> Refusal {
    base.extend(extra.iter().map(|s| s.to_string()));
    (base, names.to_vec())
}

/// `compensate` of the milling example's trim program written as FANUC LS, `extra` after it.
fn program(extra: &[&str]) -> Vec<String> {
    let mut args = compensate(false);
    args.truncate(5);
    args.extend(["--program".into(), example("milling/trim.nc")]);
    args.extend(["--process".into(), example("milling/trim.toml")]);
    args.extend(["--out".into(), "{dir}/trim.ls".into()]);
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

/// Free variables that do not go together, or not with the cell, the program or the process.
fn free_variables_that_do_not_fit() -> Vec<Refusal> {
    // The surge minimised by the lean or the configuration.
    let surge = ["--free", "tool-rotation", "--minimise", "surge"];
    let lean_surge: Vec<&str> = ["--free", "lead-tilt=-5..5"]
        .into_iter()
        .chain(surge)
        .collect();
    let config_surge: Vec<&str> = ["--free", "configuration"]
        .into_iter()
        .chain(surge)
        .collect();
    vec![
        // A tilt on a robot without a positioner; a step without its range.
        case(
            compensate(false),
            &["--free", "tilt=-10..10"],
            &["--free tilt", "positioner"],
        ),
        case(
            compensate(true),
            &["--free", "tilt=/5"],
            &["--free", "tilt"],
        ),
        // A cone without the lean; a program's cone given as an option; a process without a cone.
        case(
            program(&["--free", "lead-tilt=-5..5"]),
            &[],
            &["--free lead-tilt range", "process file"],
        ),
        case(
            program(&["--free", "lead-tilt"]),
            &[],
            &["--free lead-tilt range", "allows no lean"],
        ),
        case(compensate(false), &lean_surge, &["--minimise"]),
        case(
            compensate(false),
            &config_surge,
            &["--minimise", "configuration"],
        ),
        case(
            compensate(false),
            &["--free", "configuration", "--free", "configuration=run"],
            &["--free", "configuration", "twice"],
        ),
        // An axis by its name and by its keyword is one variable; a name the cell does not have.
        case(
            compensate(true),
            &["--free", "rotate=-10..10", "--free", "positioner=-10..10"],
            &["--free", "positioner", "twice"],
        ),
        case(
            compensate(true),
            &["--free", "turn=-10..10"],
            &["--free", "turn: unknown variable", "track, tilt, rotate"],
        ),
    ]
}

/// The options of the free variables without one, and the options `--free` replaced, each
/// refused saying how to write it.
fn options_without_free() -> Vec<Refusal> {
    let mut cases: Vec<Refusal> = [
        ["--minimise", "bound"],
        ["--objective", "max"],
        ["--margin-deg", "3"],
        ["--max-condition", "100"],
        ["--refine", "1"],
    ]
    .iter()
    .map(|option| case(compensate(false), option, &[option[0], "only with --free"]))
    .collect();
    for (option, how) in [
        (vec!["--free-tool-axis"], "--free tool-rotation=-90..90/2"),
        (
            vec!["--max-step-deg", "2"],
            "--free tool-rotation=-R..R/STEP",
        ),
        (vec!["--free-station-mm=200"], "--free station=-R..R/STEP"),
        (vec!["--free-tool-axis-objective", "bound"], "--minimise"),
        (
            vec!["--configuration-per", "run"],
            "--free configuration=run",
        ),
        (vec!["--cone-deg", "5"], "--free lead-tilt=-CONE..CONE/STEP"),
    ] {
        let named = option[0].split('=').next().unwrap();
        cases.push(case(compensate(false), &option, &[named, "removed", how]));
    }
    cases
}

/// A map, a grid and a region that cannot be.
fn searches_that_cannot_be() -> Vec<Refusal> {
    // A map of the track on a fixed base, with the lean free.
    let track_map = [
        "--free",
        "lead-tilt=-5..5",
        "--map",
        "track",
        "--report",
        "{dir}/report",
    ];
    // A lean grid beyond the cells a path may take.
    let fine = ["--free", "lead-tilt=-30..30/0.1", "--free", "tool-rotation"];
    vec![
        case(compensate(false), &track_map, &["--map", "carrier"]),
        case(
            compensate(false),
            &fine,
            &["--free lead-tilt step", "at most 5e6"],
        ),
        // A region that holds no feasible placement; the retired --z-mm names the new form.
        case(
            place(),
            &["--region-mm", "-20000,-19000,-20000,-19000"],
            &["--region-mm", "no placement"],
        ),
        case(
            place(),
            &["--region-mm", "500,2000,-1500,500", "--z-mm", "0,10"],
            &["--free"],
        ),
    ]
}

#[test]
fn combinations_that_make_no_sense_are_refused_naming_the_option() {
    let dir = temp_dir("hostile-combinations");
    let cases = [
        free_variables_that_do_not_fit(),
        options_without_free(),
        searches_that_cannot_be(),
    ];
    for (args, names) in cases.concat() {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&dir, &args, &names);
    }
}
