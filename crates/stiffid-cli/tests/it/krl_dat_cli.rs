//! `stiffid compensate --program X.SRC` reads the `.dat` beside it (same folder and stem, any
//! case) and writes the compensated `.dat` beside `--out`, both files together; a `.src` whose
//! point lives in a `.dat` that is not there is refused naming the line and the point, nothing
//! written.

use crate::common;

use common::{assert_usage_error, example, stiffid, temp_dir};
use std::path::Path;

const SRC: &str = "DEF CUT( )\r\nPTP XP1\r\nPTP XP2\r\nEND\r\n";
const DAT: &str = "DEFDAT  CUT\r\nDECL E6AXIS XP1={A1 0.0,A2 30.0,A3 0.0,A4 0.0,A5 60.0,A6 0.0}\r\nDECL E6AXIS XP2={A1 5.0,A2 35.0,A3 -5.0,A4 0.0,A5 60.0,A6 0.0}\r\nENDDAT\r\n";

fn run(src: &Path, out: &Path) -> std::process::Output {
    let (setup, stiffness, process) = (
        example("milling/kuka-milling.toml"),
        example("milling/kuka-stiffness.json"),
        example("milling/aluminium.toml"),
    );
    stiffid(&[
        "compensate",
        "--setup",
        &setup,
        "--stiffness",
        &stiffness,
        "--program",
        src.to_str().unwrap(),
        "--process",
        &process,
        "--out",
        out.to_str().unwrap(),
    ])
}

#[test]
fn a_krl_program_and_its_dat_are_compensated_together() {
    let dir = temp_dir("krl-dat");
    std::fs::write(dir.join("CUT.SRC"), SRC).unwrap();
    std::fs::write(dir.join("CUT.DAT"), DAT).unwrap();
    std::fs::create_dir(dir.join("out")).unwrap();
    let o = run(&dir.join("CUT.SRC"), &dir.join("out/C2.SRC"));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let src = std::fs::read_to_string(dir.join("out/C2.SRC")).unwrap();
    let dat = std::fs::read_to_string(dir.join("out/C2.DAT")).unwrap();
    // The .src: renamed, bounds in comments, its motions as read.
    let kept: Vec<&str> = src
        .lines()
        .map(|l| l.split(" ; bound").next().unwrap())
        .collect();
    assert_eq!(kept, ["DEF C2( )", "PTP XP1", "PTP XP2", "END"]);
    // The .dat: renamed, the points moved by the spindle's weight, every other byte kept.
    assert!(dat.starts_with("DEFDAT  C2\r\n"), "{dat}");
    let skeleton = |t: &str| t.replace(|c: char| c.is_ascii_digit() || c == '.' || c == '-', "");
    assert_eq!(skeleton(&dat), skeleton(&DAT.replace("CUT", "C2")));
    assert_ne!(dat.replace("C2", "CUT"), DAT);
    // The inputs are as they were.
    assert_eq!(std::fs::read_to_string(dir.join("CUT.DAT")).unwrap(), DAT);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_point_in_a_missing_dat_is_refused_naming_the_line_and_the_point() {
    let dir = temp_dir("krl-no-dat");
    std::fs::write(dir.join("cut.src"), SRC).unwrap();
    let o = run(&dir.join("cut.src"), &dir.join("c2.src"));
    assert_usage_error(&o, &["cut.src", "line 2", "XP1", ".dat"]);
    assert!(!dir.join("c2.src").exists() && !dir.join("c2.dat").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
