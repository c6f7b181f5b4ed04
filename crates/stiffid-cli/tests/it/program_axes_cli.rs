//! `stiffid compensate --program` with a Yaskawa INFORM job and with programs that move external
//! axes: the job written back in pulses with its name following the file's; an external axis the
//! robot lacks refused naming the file, line and axis, nothing written.

use crate::common;

use common::{assert_success, assert_usage_error, example, json, stiffid, temp_dir, write_file};
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
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `compensate --program pocket.nc --out POCKET.jbi` with the command's arguments.
fn pocket_as_job(setup: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args: Vec<String> = vec![
        "compensate".into(),
        "--setup".into(),
        setup.to_str().unwrap().into(),
        "--stiffness".into(),
        example("milling/stiffness.json"),
        "--program".into(),
        example("milling/pocket.nc"),
        "--process".into(),
        example("milling/aluminium.toml"),
        "--out".into(),
        out.to_str().unwrap().into(),
    ];
    args.extend(extra.iter().map(|a| a.to_string()));
    stiffid(&args.iter().map(String::as_str).collect::<Vec<_>>())
}

/// A G-code pocket written as a Yaskawa job: in pulses at the setup's `[controller]
/// pulses_per_deg`, each position the compensated axis angles to half a pulse, no comment longer
/// than the pendant keeps, a warning of joint targets only when Cartesian ones are asked for;
/// refused without the pulses or with the wrong count, nothing written.
#[test]
fn a_gcode_pocket_becomes_a_job_in_the_controllers_pulses() {
    let dir = temp_dir("pocket-jbi");
    let out = dir.join("POCKET.jbi");
    let plain = Path::new(&example("milling/fanuc-milling.toml")).to_path_buf();
    let o = pocket_as_job(&plain, &out, &[]);
    assert_usage_error(
        &o,
        &["controller.pulses_per_deg", "missing", "[controller]"],
    );
    assert!(!out.exists());
    let text = std::fs::read_to_string(&plain).unwrap();
    let pulses = [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7];
    let written = std::cell::Cell::new(0);
    let with = |controller: &str| {
        written.set(written.get() + 1);
        let name = format!("setup{}.toml", written.get());
        write_file(
            &dir,
            &name,
            &format!("{text}\n[controller]\n{controller}\n"),
        )
    };
    for (bad, words) in [
        (
            "pulses_per_deg = [1000, 1000, 1000]",
            &["pulses_per_deg = [1000, 1000, 1000]", "length 6"][..],
        ),
        (
            "pulses_per_deg = [1000, 1000, 1000, 1000, 1000, 0]",
            &["controller.pulses_per_deg[6]", "outside"][..],
        ),
        (
            "pulses_per_deg = [1000, 1000, 1000, 1000, 1000, nan]",
            &["controller.pulses_per_deg[6]"][..],
        ),
        (
            "pulses_per_deg = [1000, 1000, 1000, 1000, 1000, 1000]\nexternal_pulses = [1000]",
            &[
                "controller.external_pulses",
                "1 numbers for 0 external axes",
            ][..],
        ),
        (
            "external_pulses = [1000]",
            &["controller.external_pulses", "without pulses_per_deg"][..],
        ),
    ] {
        let o = pocket_as_job(&with(bad), &out, &[]);
        assert_usage_error(&o, words);
        assert!(!out.exists(), "{bad}");
    }
    let list: Vec<String> = pulses.iter().map(f64::to_string).collect();
    let setup = with(&format!("pulses_per_deg = [{}]", list.join(", ")));
    let o = pocket_as_job(&setup, &out, &["--json"]);
    let document = json(&o);
    // Nobody asked for Cartesian targets: no word of them.
    let warned = String::from_utf8_lossy(&o.stderr);
    assert!(
        !warned.contains("joint targets (the compensated"),
        "{warned}"
    );
    let job = std::fs::read_to_string(&out).unwrap();
    assert!(job.starts_with("/JOB\r\n//NAME POCKET\r\n"), "{job}");
    // The pulses are the setup's; every comment fits the pendant's 32 characters.
    assert!(!job.contains("'stiffid:"), "{job}");
    assert!(
        job.lines().all(|l| !l.starts_with('\'') || l.len() <= 32),
        "{job}"
    );
    let points = document["points"].as_array().unwrap();
    let positions: Vec<Vec<f64>> = (job.split("\r\n"))
        .filter_map(|l| l.strip_prefix('C').and_then(|l| l.split_once('=')))
        .map(|(_, v)| v.split(',').map(|p| p.parse::<f64>().unwrap()).collect())
        .collect();
    // One motion per position; the arcs written as `MOVC` (start, via, end) leave their other
    // chord points out, and each position is a point's, in path order.
    assert!(positions.len() <= points.len() + job.matches("\r\nMOVC C").count());
    assert_eq!(
        job.matches("\r\nMOVL C").count()
            + job.matches("\r\nMOVJ C").count()
            + job.matches("\r\nMOVC C").count(),
        positions.len()
    );
    let largest = largest_off(&positions, points, &pulses);
    // Half a pulse, and the document's own rounding of its angles.
    assert!(largest <= 0.5 + 0.01, "{largest} pulses");
    // `--targets cartesian` asked for: the same job, with the warning.
    let o = pocket_as_job(&setup, &dir.join("CART.jbi"), &["--targets", "cartesian"]);
    let warned = String::from_utf8_lossy(&o.stderr);
    assert!(warned.contains("targets = cartesian: INFORM programs are written with joint targets"));
    // `--targets joint` writes the same job, without the warning.
    let joint = dir.join("JOINT.jbi");
    let o = pocket_as_job(&setup, &joint, &["--targets", "joint"]);
    assert_success(&o);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("joint targets (the compensated"));
    let same = std::fs::read_to_string(&joint).unwrap();
    assert_eq!(same.replace("//NAME JOINT", "//NAME POCKET"), job);
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

/// The largest distance, in pulses, of each of a job's `positions` from the document's `points`
/// it is (in path order; a taught arc start repeats the point before it).
fn largest_off(positions: &[Vec<f64>], points: &[serde_json::Value], pulses: &[f64]) -> f64 {
    let off = |p: &[f64], point: &serde_json::Value| {
        (0..6)
            .map(|k| {
                let want = point[format!("qc{}_deg", k + 1)].as_f64().unwrap();
                (p[k] / pulses[k] - want).abs() * pulses[k]
            })
            .fold(0.0, f64::max)
    };
    let (mut largest, mut at): (f64, usize) = (0.0, 0);
    for p in positions {
        let found = (at.saturating_sub(1)..points.len())
            .find(|&i| off(p, &points[i]) <= 0.51)
            .unwrap_or_else(|| panic!("a position off the path: {p:?}"));
        largest = largest.max(off(p, &points[found]));
        at = found + 1;
    }
    largest
}
