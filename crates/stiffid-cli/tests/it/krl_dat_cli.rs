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

/// Where a case-sensitive file system holds `cut.dat` and `cut.DAT` (a program
/// and the pair compensate wrote as `cut.SRC`), `cut.src` reads `cut.dat` and `cut.SRC` reads
/// `cut.DAT`, as the compensated `.dat` is named after `--out`: the program is never read with
/// the points of another.
#[test]
fn a_src_reads_the_dat_whose_case_follows_its_own() {
    let dir = temp_dir("krl-dat-case");
    std::fs::write(dir.join("cut.src"), SRC).unwrap();
    std::fs::write(dir.join("cut.dat"), DAT).unwrap();
    // The other .dat, as sorted before cut.dat: its points 10 deg further on axis 1.
    let other = DAT
        .replace("A1 0.0", "A1 10.0")
        .replace("A1 5.0", "A1 15.0");
    std::fs::write(dir.join("cut.DAT"), &other).unwrap();
    std::fs::write(dir.join("cut.SRC"), SRC).unwrap();
    let first_axis = |program: &str, out: &str| {
        let csv = dir.join(format!("{out}.csv"));
        let o = stiffid(&[
            "compensate",
            "--setup",
            &example("milling/kuka-milling.toml"),
            "--stiffness",
            &example("milling/kuka-stiffness.json"),
            "--program",
            dir.join(program).to_str().unwrap(),
            "--process",
            &example("milling/aluminium.toml"),
            "--out",
            dir.join(out).to_str().unwrap(),
            "--csv",
            csv.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let csv = std::fs::read_to_string(csv).unwrap();
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        let q1 = header.iter().position(|h| *h == "q1_deg").unwrap();
        let rows = csv.lines().skip(1);
        rows.map(|r| r.split(',').nth(q1).unwrap().parse::<f64>().unwrap())
            .collect::<Vec<f64>>()
    };
    // Axis 1 is read as declared (joint motions: no force, compensated by the tool's weight
    // alone, which does not turn axis 1 of an upright arm).
    let lower = first_axis("cut.src", "a.src");
    assert!(
        (lower[0] - 0.0).abs() < 1e-6 && (lower[1] - 5.0).abs() < 1e-6,
        "{lower:?}"
    );
    let upper = first_axis("cut.SRC", "b.src");
    assert!(
        (upper[0] - 10.0).abs() < 1e-6 && (upper[1] - 15.0).abs() < 1e-6,
        "{upper:?}"
    );
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

/// `PTP XHOME` (KUKA's home position, which the controller's `$config.dat` holds) passes through
/// as the controller holds it: no point of the path, its line written back as read and named in
/// a warning, with or without the setup's `[controller] home_deg`.
#[test]
fn ptp_xhome_passes_through_as_the_controller_holds_it() {
    let dir = temp_dir("krl-xhome");
    std::fs::write(
        dir.join("CUT.SRC"),
        SRC.replace("PTP XP1", "PTP XHOME\r\nPTP XP1"),
    )
    .unwrap();
    std::fs::write(dir.join("CUT.DAT"), DAT).unwrap();
    let setup = std::fs::read_to_string(example("milling/kuka-milling.toml")).unwrap();
    std::fs::write(
        dir.join("home.toml"),
        format!("{setup}\n[controller]\nhome_deg = [0, 20, 10, 0, 60, 0]\n"),
    )
    .unwrap();
    let run_on = |setup: &Path, out: &str| {
        stiffid(&[
            "compensate",
            "--setup",
            setup.to_str().unwrap(),
            "--stiffness",
            &example("milling/kuka-stiffness.json"),
            "--program",
            dir.join("CUT.SRC").to_str().unwrap(),
            "--process",
            &example("milling/aluminium.toml"),
            "--out",
            dir.join(out).to_str().unwrap(),
            "--csv",
            dir.join(format!("{out}.csv")).to_str().unwrap(),
        ])
    };
    let o = run_on(&dir.join("home.toml"), "C2.SRC");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let src = std::fs::read_to_string(dir.join("C2.SRC")).unwrap();
    let kept: Vec<&str> = src
        .lines()
        .map(|l| l.split(" ; bound").next().unwrap())
        .collect();
    assert_eq!(
        kept,
        ["DEF C2( )", "PTP XHOME", "PTP XP1", "PTP XP2", "END"]
    );
    // Not compensated (the controller holds it): no bound, and a warning naming its line.
    assert!(src.contains("\nPTP XHOME\r\n"), "{src}");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("line 2: PTP XHOME: the home position, passed through"),
        "{stderr}"
    );
    // The path's first point is the motion after it, on line 3.
    let csv = std::fs::read_to_string(dir.join("C2.SRC.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let row: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
    let col = |name: &str| row[header.iter().position(|h| *h == name).unwrap()];
    assert_eq!(col("line"), "3");
    let plain = run_on(Path::new(&example("milling/kuka-milling.toml")), "C3.SRC");
    assert!(
        plain.status.success(),
        "{}",
        String::from_utf8_lossy(&plain.stderr)
    );
    // A path motion there (under the process's force) would not be compensated: refused.
    let lin = SRC.replace("PTP XP1", "LIN XHOME\r\nPTP XP1");
    std::fs::write(dir.join("CUT.SRC"), lin).unwrap();
    let refused = run_on(&dir.join("home.toml"), "C4.SRC");
    assert_usage_error(&refused, &["line 2", "LIN XHOME", "move there with PTP"]);
    std::fs::remove_dir_all(&dir).unwrap();
}
