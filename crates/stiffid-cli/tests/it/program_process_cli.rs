//! A G-code program written as a robot program with the setup's `[controller]` program
//! settings: the milling example's pocket (`T1 M06`, `S6000 M03`, `M05`, `M30`) on the FANUC
//! cell with a home posture, rapid speeds and `[controller.io]`, written as LS and as KRL.

use crate::common;

use common::{assert_success, assert_usage_error, example, stiffid, temp_dir, write_file};
use std::path::Path;

/// The FANUC milling setup with `controller` appended (a `[controller]` table's lines).
fn setup(dir: &Path, controller: &str) -> String {
    let text = std::fs::read_to_string(example("milling/fanuc-milling.toml")).unwrap();
    let setup = write_file(dir, "cell.toml", &format!("{text}\n{controller}\n"));
    setup.display().to_string()
}

fn compensate(setup: &str, out: &Path, extra: &[&str]) -> std::process::Output {
    let (nc, process) = (
        example("milling/pocket.nc"),
        example("milling/aluminium.toml"),
    );
    let stiffness = example("milling/stiffness.json");
    let mut args = vec![
        "compensate",
        "--setup",
        setup,
        "--stiffness",
        &stiffness,
        "--program",
        &nc,
        "--process",
        &process,
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    stiffid(&args)
}

const CONTROLLER: &str = "[controller]
home_deg = [0, 10, -20, 0, -60, 0]
rapid_joint_pct = 35
[controller.io]
tool_change = \"TOOL_CHANGE({tool})\"
spindle_cw = [\"SPINDLE_ON({rpm})\", \"out[12] = on\"]
spindle_off = \"out[12] = off\"
";

/// The `/MN` lines of an LS program, without their numbers.
fn mn(text: &str) -> Vec<String> {
    let body = text
        .split("/MN\n")
        .nth(1)
        .unwrap()
        .split("/POS\n")
        .next()
        .unwrap();
    (body.lines())
        .map(|l| l.split_once(':').unwrap().1.trim().to_string())
        .collect()
}

#[test]
fn the_pocket_starts_and_ends_at_home_with_its_process_words_mapped() {
    let dir = temp_dir("program-process");
    let setup = setup(&dir, CONTROLLER);
    let ls = dir.join("POCKET.ls");
    let o = compensate(&setup, &ls, &[]);
    assert_success(&o);
    let stderr = String::from_utf8_lossy(&o.stderr);
    // The one word left unmapped, named in one warning.
    let warned: Vec<&str> = stderr
        .lines()
        .filter(|l| l.contains("process word"))
        .collect();
    assert_eq!(warned.len(), 1, "{stderr}");
    assert!(
        warned[0].contains("1 process word(s)")
            && warned[0].ends_with("program_end: M30 (line 190)"),
        "{stderr}"
    );
    let text = std::fs::read_to_string(&ls).unwrap();
    let lines = mn(&text);
    // Every position once: a circular move's via point on its `C` line, its end on the
    // continuation line.
    let moves: Vec<usize> = (lines.iter().enumerate())
        .filter(|(_, l)| {
            ["J P[", "L P[", "C P[", "P["]
                .iter()
                .any(|m| l.starts_with(m))
        })
        .map(|(i, _)| i)
        .collect();
    // The pocket's points (its arcs as circular moves) and the home posture at both ends.
    let n = moves.len();
    let declared = text.split("/POS\n").nth(1).unwrap().matches("\nP[").count() + 1;
    assert_eq!(n, declared, "{text}");
    let (first, last) = (moves[0], *moves.last().unwrap());
    assert_eq!(lines[first], "J P[1] 35% FINE ;");
    assert_eq!(lines[last], format!("J P[{n}] 35% FINE ;"));
    // The G-code's comments, tool change and spindle after moving home, before the path's
    // first point (LS remarks of at most 32 characters); the spindle
    // stop after the path's last point, before going home; the end after it.
    let after_home: Vec<&str> = lines[first + 1..moves[1]]
        .iter()
        .map(String::as_str)
        .collect();
    assert_eq!(
        after_home,
        [
            "! pocket wall: 300 x 200 mm, corne ;",
            "! operation: wall ;",
            "CALL TOOL_CHANGE(1) ;",
            "CALL SPINDLE_ON(6000) ;",
            "DO[12]=ON ;"
        ]
    );
    assert_eq!(lines[last - 1], "DO[12]=OFF ;");
    assert_eq!(lines[last + 1], "! M30 (line 190) ;");
    // Both home positions are the same pose, and carry no bound (they are not compensated);
    // every path position does.
    let pos = format!("\n{}", text.split("/POS\n").nth(1).unwrap());
    let position = |i: usize| {
        let at = |end: &str| pos.find(&format!("\nP[{i}{end}"));
        let start = at("]").or_else(|| at(":")).unwrap() + 1;
        let end = start + pos[start..].find("};").unwrap();
        pos[start..end].to_string()
    };
    let (home, back) = (position(1), position(n));
    assert!(
        home.starts_with("P[1]{") && back.starts_with(&format!("P[{n}]{{")),
        "{home}\n{back}"
    );
    assert_eq!(
        home.replace("P[1]", ""),
        back.replace(&format!("P[{n}]"), "")
    );
    assert!(position(2).starts_with("P[2:\""), "{}", position(2));
    // Joint targets: the home posture as its axis angles.
    let krl = dir.join("POCKET.src");
    let o = compensate(&setup, &krl, &["--targets", "joint"]);
    assert_success(&o);
    let text = std::fs::read_to_string(&krl).unwrap();
    // The points are declared in the .dat beside it, the motions name them.
    let dat = std::fs::read_to_string(dir.join("POCKET.dat")).unwrap();
    let home = "={A1 0.000000000, A2 10.000000000, A3 -20.000000000, A4 0.000000000, A5 -60.000000000, A6 0.000000000}\n";
    assert!(dat.matches(home).count() == 2, "{dat}");
    let named = |l: &str| l.starts_with("PTP XP") && !l.contains('{');
    assert_eq!(
        text.lines().filter(|l| named(l)).count(),
        dat.matches("DECL E6AXIS XP").count()
    );
    assert!(text.contains("BAS(#VEL_PTP, 35)"), "{text}");
    assert!(
        text.contains("TOOL_CHANGE(1)\nSPINDLE_ON(6000)\n$OUT[12]=TRUE\n"),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn program_settings_a_language_cannot_state_are_refused_before_compensating() {
    let dir = temp_dir("program-process-refused");
    let ls = dir.join("POCKET.ls");
    let setup = setup(&dir, "[controller]\nrapid_joint_pct = 12.5\n");
    let o = compensate(&setup, &ls, &[]);
    assert_usage_error(&o, &["controller.rapid_joint_pct", "12.5", "whole percent"]);
    let setup = setup_outside(&dir);
    let o = compensate(&setup, &ls, &[]);
    assert_usage_error(&o, &["controller.home_deg[5]", "the robot's limits"]);
    let setup = self::setup(
        &dir,
        "[controller.io]\nspindle_cw = \"out[doSpindle] = on\"\n",
    );
    let o = compensate(&setup, &ls, &[]);
    assert_usage_error(&o, &["controller.io.spindle_cw", "DO[n]", "line 6"]);
    assert!(!ls.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

fn setup_outside(dir: &Path) -> String {
    setup(dir, "[controller]\nhome_deg = [0, 0, 0, 0, 300, 0]\n")
}
