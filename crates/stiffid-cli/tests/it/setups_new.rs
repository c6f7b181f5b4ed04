//! `stiffid setups new`: a commented setup for the user's own robot that the other commands accept
//! as written.

use crate::common;
use common::{assert_success, assert_usage_error, stiffid, temp_dir};
use std::path::Path;

/// The test URDF with two leaf links (`tool0` and a sensor link).
fn two_leaves_urdf() -> String {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../stiffid/tests/data");
    dir.join("comau-nj165-two-leaves.urdf")
        .display()
        .to_string()
}

/// Writes a new setup for `robot` (with `extra` options) into a fresh directory; runs `select
/// --start-random`, `evaluate` on its postures and a small `reproduce` on it.
fn new_setup_is_accepted_unchanged(name: &str, robot: &str, extra: &[&str]) {
    let dir = temp_dir(&format!("setups-new-{name}"));
    let setup = dir.join("cell").join("my setup.toml");
    std::fs::create_dir_all(setup.parent().unwrap()).unwrap();
    let s = setup.to_str().unwrap();
    let mut args = vec!["setups", "new", "--robot", robot, "--out", s];
    args.extend(extra);
    assert_success(&stiffid(&args));
    let text = std::fs::read_to_string(&setup).unwrap();
    assert!(text.contains("characteristic_length_mm = ") && text.contains("ROUGH PRIOR"));
    let postures = dir.join("p.csv");
    let p = postures.to_str().unwrap();
    let select = [
        "select",
        "--setup",
        s,
        "--criterion",
        "relative-a",
        "--start-random",
    ];
    assert_success(&stiffid(
        &[&select[..], &["--out", p, "--max-evals", "300"]].concat(),
    ));
    let evaluated = common::json(&stiffid(&[
        "evaluate",
        "--setup",
        s,
        "--postures",
        p,
        "--json",
    ]));
    for key in [
        "classical",
        "zhang2021",
        "d_optimal",
        "relative_a",
        "cond_psi",
    ] {
        assert!(evaluated[key].as_f64().is_some_and(f64::is_finite), "{key}");
    }
    every_optional_section_loads(&text, &setup.with_file_name("all.toml"), p);
    let report = dir.join("report");
    let r = report.to_str().unwrap();
    let quick = ["--runs", "5", "--starts", "2", "--trials", "1"];
    assert_success(&stiffid(
        &[&["reproduce", "--setup", s, "--out", r][..], &quick].concat(),
    ));
    assert!(report.join("summary.json").is_file());
    assert_eq!(
        std::fs::read_to_string(&setup).unwrap(),
        text,
        "setup changed"
    );
}

/// The commented-out fields of a new setup (`# key = ...` and `# [table]` lines) uncommented.
fn uncommented(text: &str) -> String {
    let lines: Vec<&str> = text.lines().map(|l| field(l).unwrap_or(l)).collect();
    lines.join("\n") + "\n"
}

/// The field in a commented-out line `# key = ...` or `# [table]`, if it is one.
fn field(line: &str) -> Option<&str> {
    let rest = line.strip_prefix("# ")?;
    let key = rest.split_once(" = ").map_or("", |(k, _)| k);
    let is_key = !key.is_empty() && key.chars().all(|c| c.is_ascii_lowercase() || c == '_');
    (rest.starts_with('[') || is_key).then_some(rest)
}

/// The setup `text` with every optional field and section uncommented, written to `all`, loads,
/// and `evaluate` checks `postures` against every check of the cell, the tracker and the
/// constraints.
fn every_optional_section_loads(text: &str, all: &Path, postures: &str) {
    let uncommented = uncommented(text);
    for section in [
        "\n[test]",
        "\n[constraints]",
        "\n[cell]",
        "\n[[cell.obstacle]]",
        "\n[robot_geometry]",
        "\n[tracker]",
        "\nrobot_base = {",
        "\nrobot_flange = {",
        "\ntcp_mm = [",
        "\nbase_from_tracker = {",
    ] {
        assert!(uncommented.contains(section), "{section} missing");
    }
    std::fs::write(all, &uncommented).unwrap();
    let a = all.to_str().unwrap();
    let out = stiffid(&["evaluate", "--setup", a, "--postures", postures]);
    assert_success(&out);
    let checks = "checks: bounds, floor, obstacles, self-collision, rope, line-of-sight, incidence, loading-point-min-z, anchor-below-loading-point";
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains(checks), "{stdout}");
}

#[test]
fn new_setups_of_every_preset_are_accepted_unchanged() {
    for preset in [
        "comau-smart5-nj165-3.0",
        "fanuc-r2000ic-165f",
        "kuka-kr210-robond",
    ] {
        new_setup_is_accepted_unchanged(preset, preset, &[]);
    }
}

#[test]
fn a_new_setup_of_a_urdf_names_it_relative_to_the_setup_file() {
    let urdf = two_leaves_urdf();
    // Two leaf links: the tip is found (tool0, the end of the six revolute joints).
    new_setup_is_accepted_unchanged("urdf", &urdf, &["--payload-kg", "165"]);
    let dir = temp_dir("setups-new-urdf-text");
    let out = stiffid(&["setups", "new", "--robot", &urdf, "--tip", "tool0"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("robot_tip = \"tool0\""), "{text}");
    assert!(!text.contains(dir.to_str().unwrap()));
}

#[test]
fn the_payload_scales_the_stiffness_prior() {
    let stiffness = |kg: &str| -> f64 {
        let out = stiffid(&[
            "setups",
            "new",
            "--robot",
            "kuka-kr210-robond",
            "--payload-kg",
            kg,
        ]);
        let text = String::from_utf8(out.stdout).unwrap();
        let line = text
            .lines()
            .find(|l| l.starts_with("nominal_stiffness"))
            .unwrap();
        let list = line.split('[').nth(1).unwrap().trim_end_matches(']');
        list.split(',').next().unwrap().trim().parse().unwrap()
    };
    assert_eq!(stiffness("165"), 950_000.0);
    assert!((stiffness("330") / stiffness("165") - 2.0).abs() < 1e-6);
}

#[test]
fn setups_new_never_replaces_a_file_and_refuses_bad_payloads() {
    let dir = temp_dir("setups-new-refusals");
    let existing = common::write_file(&dir, "mine.toml", "name = \"mine\"\n");
    let e = existing.to_str().unwrap();
    let out = stiffid(&["setups", "new", "--robot", "kuka-kr210-robond", "--out", e]);
    assert_usage_error(&out, &["--out", "exists"]);
    assert_eq!(
        std::fs::read_to_string(&existing).unwrap(),
        "name = \"mine\"\n"
    );
    let bad = [
        ("0", "0"),
        ("-5", "-5"),
        ("nan", "NaN"),
        ("1e308", "1e308"),
        ("1e-4", "0.0001"),
    ];
    for (bad, shown) in bad {
        let payload = format!("--payload-kg={bad}");
        let out = stiffid(&["setups", "new", "--robot", "kuka-kr210-robond", &payload]);
        let message =
            format!("error: --payload-kg: expected a payload in [0.1, 2500] kg, got {shown}\n");
        assert_usage_error(&out, &[&message]);
    }
}
