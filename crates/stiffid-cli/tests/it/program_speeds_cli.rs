//! A robot program's programmed speeds in `stiffid compensate`: the milling example's LS pocket
//! on the FANUC cell with every joint's largest speed given. Its moves are checked at their
//! `mm/sec` (the text's speed line), a move at a register's speed is counted and warned about,
//! and a speed of 0 mm/sec is refused naming the file and the line.

use crate::common;

use common::{assert_success, assert_usage_error, example, stiffid, temp_dir, write_file};
use std::path::Path;

/// The pocket's move on `line` of the file at `speed` instead of 30mm/sec, compensated with the
/// tool rotation free on the FANUC cell whose joints move at most 50 deg/s.
fn compensated(dir: &Path, speed: &str) -> std::process::Output {
    let setup = std::fs::read_to_string(example("milling/fanuc-milling.toml")).unwrap();
    let setup = setup.replacen(
        "\nrobot = ",
        "\nmax_speed_deg_s = [50, 50, 50, 50, 50, 50]\nrobot = ",
        1,
    );
    let setup = write_file(dir, "limited.toml", &setup);
    let pocket = std::fs::read_to_string(example("milling/pocket.ls")).unwrap();
    let pocket = pocket.replacen("  16:L P[3] 30mm/sec", &format!("  16:L P[3] {speed}"), 1);
    let pocket = write_file(dir, "pocket.ls", &pocket);
    let out = dir.join("OUT.ls");
    let _ = std::fs::remove_file(&out);
    stiffid(&[
        "compensate",
        "--setup",
        setup.to_str().unwrap(),
        "--stiffness",
        &example("milling/stiffness.json"),
        "--program",
        pocket.to_str().unwrap(),
        "--process",
        &example("milling/aluminium.toml"),
        "--out",
        out.to_str().unwrap(),
        "--free",
        "tool-rotation",
    ])
}

#[test]
fn a_robot_programs_speeds_are_checked_counted_or_refused() {
    let dir = temp_dir("program-speeds");
    let o = compensated(&dir, "30mm/sec");
    assert_success(&o);
    let text = String::from_utf8_lossy(&o.stdout);
    let line = text.lines().find(|l| l.starts_with("axis speeds")).unwrap();
    assert!(
        line.contains("along those chosen") && !line.contains("not checked"),
        "{line}"
    );
    let o = compensated(&dir, "R[1]mm/sec");
    assert_success(&o);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("; 1 linear move not checked"), "{text}");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("warning: the programmed speed of 1 linear move is not read")
            && stderr.contains("line 37: R[1]mm/sec: the speed is held in a register"),
        "{stderr}"
    );
    let o = compensated(&dir, "0mm/sec");
    assert_usage_error(&o, &["pocket.ls", "line 37", "0mm/sec", "(0, 10000] mm/s"]);
    assert!(!dir.join("OUT.ls").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
