//! `stiffid compensate --program` with a Yaskawa INFORM job and with programs that move external
//! axes: the job written back in pulses with its name following the file's; an external axis the
//! robot lacks refused naming the file, line and axis, nothing written.

use crate::common;

use common::{assert_success, assert_usage_error, example, stiffid, temp_dir, write_file};
use std::path::Path;

/// Two teaching positions near the milling example's posture, 1000 pulses per degree.
const JOB: &str = "/JOB\r\n//NAME CUT\r\n//POS\r\n///NPOS 2,0,0,0,0,0\r\n///TOOL 0\r\n///POSTYPE PULSE\r\n///PULSE\r\nC00000=-59991,-16693,-28930,3788,-62930,144919\r\nC00001=-58991,-16693,-28930,3788,-62930,144919\r\n//INST\r\n///DATE 2026/11/25 12:00\r\n///ATTR SC,RW\r\n///GROUP1 RB1\r\n'stiffid: pulses_per_deg = 1000 1000 1000 1000 1000 1000\r\nNOP\r\nMOVJ C00000 VJ=10.00\r\nMOVL C00001 V=20.0\r\nEND\r\n";

fn run(program: &Path, out: &Path) -> std::process::Output {
    stiffid(&[
        "compensate",
        "--setup",
        &example("milling/fanuc-milling.toml"),
        "--stiffness",
        &example("milling/stiffness.json"),
        "--program",
        program.to_str().unwrap(),
        "--process",
        &example("milling/aluminium.toml"),
        "--out",
        out.to_str().unwrap(),
    ])
}

#[test]
fn an_inform_job_is_written_back_in_pulses_under_its_new_name() {
    let dir = temp_dir("inform");
    let job = write_file(&dir, "cut.jbi", JOB);
    let out = dir.join("cut_c.jbi");
    assert_success(&run(&job, &out));
    let written = std::fs::read_to_string(&out).unwrap();
    // Each motion is certified by a comment line before it naming its error bound.
    let is_bound = |l: &str| l.trim_start().starts_with("'bound ") && l.ends_with(" mm at 95%");
    let lines: Vec<&str> = written.split("\r\n").collect();
    let motions = JOB.split("\r\n").filter(|l| l.starts_with("MOV")).count();
    assert_eq!(
        lines.iter().filter(|l| is_bound(l)).count(),
        motions,
        "{written}"
    );
    let (old, new): (Vec<&str>, Vec<&str>) = (
        JOB.split("\r\n").collect(),
        lines.into_iter().filter(|l| !is_bound(l)).collect(),
    );
    assert_eq!(old.len(), new.len());
    for (k, (a, b)) in old.iter().zip(&new).enumerate() {
        match k {
            // The job is named as its file; the positions are compensated, in whole pulses.
            1 => assert_eq!(*b, "//NAME CUT_C"),
            // C00000 is reached by a joint move (MOVJ): the tool cuts nothing there.
            7 => assert_eq!(a, b),
            8 => {
                let before: Vec<i64> = a[7..].split(',').map(|v| v.parse().unwrap()).collect();
                let after: Vec<i64> = b[7..].split(',').map(|v| v.parse().unwrap()).collect();
                assert_eq!(&a[..7], &b[..7]);
                let moved = before
                    .iter()
                    .zip(&after)
                    .map(|(x, y)| (x - y).abs())
                    .max()
                    .unwrap();
                // Compensation moves an axis by thousandths to tenths of a degree.
                assert!((2..1000).contains(&moved), "{a} -> {b}");
            }
            _ => assert_eq!(a, b),
        }
    }
    // A G-code path is not generated as a job.
    let o = stiffid(&[
        "compensate",
        "--setup",
        &example("milling/fanuc-milling.toml"),
        "--stiffness",
        &example("milling/stiffness.json"),
        "--program",
        &example("milling/pocket.nc"),
        "--process",
        &example("milling/aluminium.toml"),
        "--out",
        dir.join("pocket.jbi").to_str().unwrap(),
    ]);
    assert_usage_error(&o, &["not generated"]);
    assert!(!dir.join("pocket.jbi").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_external_axis_the_robot_lacks_is_refused_naming_file_line_and_axis() {
    let dir = temp_dir("noaxis");
    let ls = write_file(
        &dir,
        "track.ls",
        "/PROG TRACK\n/MN\n   1:J P[1] 10% FINE ;\n/POS\nP[1]{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= -60 deg,\tJ2= -17 deg,\tJ3= -29 deg,\n\tJ4= 4 deg,\tJ5= -63 deg,\tJ6= 145 deg,\n\tE1= 1500.000 mm\n};\n/END\n",
    );
    let out = dir.join("o.ls");
    assert_usage_error(
        &run(&ls, &out),
        &["track.ls", "line 3", "E1 1500", "no external axes"],
    );
    // INFORM: the base axis of a job for a robot without one.
    let job = JOB
        .replace("///NPOS 2,0,0", "///NPOS 2,2,0")
        .replace("//INST", "BC00000=150000\r\nBC00001=150000\r\n//INST")
        .replace("MOVJ C00000", "MOVJ C00000 BC00000")
        .replace("MOVL C00001", "MOVL C00001 BC00001")
        .replace(
            "1000\r\nNOP",
            "1000\r\n'stiffid: external_pulses = 100\r\nNOP",
        );
    let job = write_file(&dir, "track.jbi", &job);
    let out_jbi = dir.join("o.jbi");
    assert_usage_error(&run(&job, &out_jbi), &["track.jbi", "line 19", "BC1 1500"]);
    assert!(!out.exists() && !out_jbi.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
