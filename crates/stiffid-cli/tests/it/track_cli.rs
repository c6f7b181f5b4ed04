//! `stiffid compensate --free station` on the example trim line along the rail
//! (`examples/track/trim.csv`): the CSV carries the station chosen (`e1_mm`) and the path's own
//! values without it; the redundancy lowers the path's peak bound by at least 30% with no point
//! worse; a robot without a track is refused naming the option, nothing written.

use crate::common;

use common::{assert_success, example, stiffid, temp_dir};
use std::path::Path;

/// The trim line compensated with `extra` options: each row's `bound_mm` and `e1_mm`.
fn trim(out: &Path, extra: &[&str]) -> Vec<(f64, f64)> {
    let (setup, stiffness) = (
        example("track/track-cell.toml"),
        example("milling/kuka-stiffness.json"),
    );
    let path = example("track/trim.csv");
    let mut args = vec!["compensate", "--setup", &setup, "--stiffness", &stiffness];
    args.extend(["--path", &path, "--out", out.to_str().unwrap()]);
    args.extend(extra);
    assert_success(&stiffid(&args));
    let text = std::fs::read_to_string(out).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (bound, e1) = (at("bound_mm"), at("e1_mm"));
    lines
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            (cells[bound].parse().unwrap(), cells[e1].parse().unwrap())
        })
        .collect()
}

#[test]
fn the_free_station_lowers_the_trim_lines_peak_bound_by_30_percent() {
    let dir = temp_dir("track-trim");
    let own = trim(&dir.join("own.csv"), &[]);
    assert!(
        own.iter().all(|(_, e)| *e == 3000.0),
        "the path's own station"
    );
    let free = trim(
        &dir.join("free.csv"),
        &["--free", "station=-1500..1500/50", "--objective", "max"],
    );
    assert_eq!(own.len(), free.len());
    let peak = |rows: &[(f64, f64)]| rows.iter().map(|r| r.0).fold(0.0, f64::max);
    let (before, after) = (peak(&own), peak(&free));
    assert!(after <= 0.7 * before, "peak {after} mm against {before} mm");
    for (i, (a, b)) in own.iter().zip(&free).enumerate() {
        assert!(b.0 <= a.0 + 1e-6, "{i}: {} mm > {} mm", b.0, a.0);
        assert!(
            (b.1 - 3000.0).abs() <= 1500.0 + 1e-6,
            "{i}: station {}",
            b.1
        );
    }
    for w in free.windows(2) {
        assert!(
            (w[1].1 - w[0].1).abs() <= 50.0 + 1e-6,
            "step {} mm",
            w[1].1 - w[0].1
        );
    }
}

#[test]
fn a_free_station_on_a_fixed_base_is_refused_naming_the_option() {
    let dir = temp_dir("track-fixed");
    let out = dir.join("out.csv");
    let setup = example("milling/fanuc-milling.toml");
    let stiffness = example("milling/stiffness.json");
    let path = example("milling/path.csv");
    let o = stiffid(&[
        "compensate",
        "--setup",
        &setup,
        "--stiffness",
        &stiffness,
        "--path",
        &path,
        "--free",
        "station=-100..100",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--free station") && err.contains("carrier"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn a_calibration_campaign_refuses_a_station_given_twice_naming_it() {
    let dir = temp_dir("track-twice");
    let out = dir.join("campaign.csv");
    let setup = example("track/track-cell.toml");
    let o = stiffid(&[
        "select",
        "--setup",
        &setup,
        "--for",
        "calibration",
        "--global",
        "--count",
        "6",
        "--station",
        "500,0,0",
        "--station",
        "3000,0,0",
        "--station",
        "500,0,0",
        "--seed",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--station") && err.contains("station 3 repeats station 1"),
        "{err}"
    );
    assert!(!out.exists());
}
