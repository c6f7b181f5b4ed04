//! Programs with external axes compensated on the example track cell (a KUKA KR 210 on a 6 m
//! track, the part on a tilt-rotate positioner) and read back: KRL `E1..E6`, RAPID `extjoint`
//! (`9E9` unused), LS `E1=` with a `GP2` positioner group and INFORM base (`BC`, pulses) and
//! station (`EC`, angles) axes. Every external value written equals the one given (or the
//! station chosen with `--free station`), every target the CSV's compensated axis angles;
//! with the free station, every station within `+-R` of the given and within the travel,
//! consecutive stations at most a step apart, and no point's bound above its bound at the
//! given station.

use crate::common;

use common::{assert_success, example, stiffid, temp_dir, write_file};
use std::path::Path;
use stiffid::internal::machining::program::{self, Dialect};

/// The targets: axis angles (deg, whole hundredths for INFORM's 100 pulses per degree) near the
/// cell's test posture and the external values: track (mm, the first 100 mm from the end of its
/// travel), tilt and rotate (deg).
fn targets() -> Vec<([f64; 6], [f64; 3])> {
    (0..5)
        .map(|i| {
            let i = i as f64;
            (
                [2.5 * i, 30.0 + i, -5.0, 10.0, 60.0 - i, 15.0],
                [100.0 + 60.0 * i, 10.0, 20.0 + 5.0 * i],
            )
        })
        .collect()
}

/// A KRL program: even targets as motions to an aggregate, odd ones to an `E6AXIS` declared
/// before the motion (KUKA's zeros for the axes the cell lacks).
fn krl() -> String {
    let mut text = String::from("DEF cut( )\n");
    for (i, (q, e)) in targets().iter().enumerate() {
        let axes = format!(
            "A1 {}, A2 {}, A3 {}, A4 {}, A5 {}, A6 {}, E1 {}, E2 {}, E3 {}, E4 0, E5 0, E6 0",
            q[0], q[1], q[2], q[3], q[4], q[5], e[0], e[1], e[2]
        );
        match i % 2 {
            0 => text += &format!("PTP {{{axes}}}\n"),
            _ => text += &format!("DECL E6AXIS XP{i}={{{axes}}}\nLIN XP{i} C_DIS\n"),
        }
    }
    text + "END\n"
}

/// A RAPID module: the first target a declared `jointtarget`, the others literal; `9E9` for the
/// three axes the cell lacks.
fn rapid() -> String {
    let target = |(q, e): &([f64; 6], [f64; 3])| {
        format!(
            "[[{},{},{},{},{},{}],[{},{},{},9E9,9E9,9E9]]",
            q[0], q[1], q[2], q[3], q[4], q[5], e[0], e[1], e[2]
        )
    };
    let t = targets();
    let mut text = format!(
        "MODULE Cut\n  CONST jointtarget j0:={};\n  PROC main()\n    MoveAbsJ j0, v100, fine, tool0;\n",
        target(&t[0])
    );
    for x in &t[1..] {
        text += &format!("    MoveAbsJ {}, v100, z10, tool0;\n", target(x));
    }
    text + "  ENDPROC\nENDMODULE\n"
}

/// An LS program: group 1 with the track as `E1` (mm), group 2 the positioner (deg).
fn ls() -> String {
    let t = targets();
    let mut text = String::from("/PROG  CUT\n/MN\n");
    for i in 1..=t.len() {
        text += &format!("{i:>4}:L P[{i}] 50mm/sec FINE ;\n");
    }
    text += "/POS\n";
    for (i, (q, e)) in t.iter().enumerate() {
        text += &format!(
            "P[{}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= {:.3} deg,\tJ2= {:.3} deg,\tJ3= {:.3} deg,\n\tJ4= {:.3} deg,\tJ5= {:.3} deg,\tJ6= {:.3} deg,\n\tE1= {:.3} mm\n   GP2:\n\tUF : 0, UT : 1,\n\tJ1= {:.3} deg,\tJ2= {:.3} deg\n}};\n",
            i + 1, q[0], q[1], q[2], q[3], q[4], q[5], e[0], e[1], e[2]
        );
    }
    text + "/END\n"
}

/// An INFORM job: the robot and the track (base axis) in pulses (100 per degree, 100 per mm),
/// the positioner (station axes) in degrees.
fn inform() -> String {
    let t = targets();
    let n = t.len();
    let mut text = format!(
        "/JOB\r\n//NAME CUT\r\n//POS\r\n///NPOS {n},{n},{n},0,0,0\r\n///TOOL 0\r\n///POSTYPE PULSE\r\n///PULSE\r\n"
    );
    let pulses = |v: f64| format!("{}", (v * 100.0).round() as i64);
    for (i, (q, _)) in t.iter().enumerate() {
        let q: Vec<String> = q.iter().map(|v| pulses(*v)).collect();
        text += &format!("C{i:05}={}\r\n", q.join(","));
    }
    for (i, (_, e)) in t.iter().enumerate() {
        text += &format!("BC{i:05}={}\r\n", pulses(e[0]));
    }
    text += "///POSTYPE ANGLE\r\n///ANGLE\r\n";
    for (i, (_, e)) in t.iter().enumerate() {
        text += &format!("EC{i:05}={:.3},{:.3}\r\n", e[1], e[2]);
    }
    text += "//INST\r\n///DATE 2026/11/25 12:00\r\n///ATTR SC,RW\r\n///GROUP1 RB1,BS1,ST1\r\n'stiffid: pulses_per_deg = 100 100 100 100 100 100\r\n'stiffid: external_pulses = 100\r\nNOP\r\n";
    for i in 0..n {
        text += &format!("MOVL C{i:05} BC{i:05} EC{i:05} V=100.0 PL=0\r\n");
    }
    text + "END\r\n"
}

/// The programs of the four dialects, their file names and the largest difference between a
/// written axis angle and the CSV's (deg: INFORM writes whole pulses, 0.01 deg).
fn programs() -> Vec<(Dialect, &'static str, String, f64)> {
    vec![
        (Dialect::Krl, "cut.src", krl(), 1e-9),
        (Dialect::Rapid, "cut.mod", rapid(), 1e-9),
        (Dialect::FanucLs, "cut.ls", ls(), 1e-9),
        (Dialect::Inform, "cut.jbi", inform(), 0.005 + 1e-9),
    ]
}

/// One row of the CSV: the compensated axis angles (deg), the external values (mm, deg, deg)
/// and the bound (mm).
struct Row {
    qc: [f64; 6],
    e: [f64; 3],
    bound: f64,
}

fn rows(csv: &Path) -> Vec<Row> {
    let text = std::fs::read_to_string(csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at = |name: &str| header.iter().position(|h| *h == name).unwrap();
    lines
        .map(|l| {
            let cells: Vec<f64> = l
                .split(',')
                .map(|c| c.parse().unwrap_or(f64::NAN))
                .collect();
            Row {
                qc: std::array::from_fn(|k| cells[at(&format!("qc{}_deg", k + 1))]),
                e: [cells[at("e1_mm")], cells[at("e2_deg")], cells[at("e3_deg")]],
                bound: cells[at("bound_mm")],
            }
        })
        .collect()
}

/// Compensates `program` (file `name`) on the track cell with `extra` options: the program
/// written, read back, and the CSV's rows.
fn compensate(
    dir: &Path,
    (dialect, name, program): (Dialect, &str, &str),
    tag: &str,
    extra: &[&str],
) -> (program::JointProgram, Vec<Row>) {
    let input = write_file(dir, name, program);
    let out = dir.join(format!("{tag}_{name}"));
    let csv = dir.join(format!("{tag}_{name}.csv"));
    let (setup, stiffness, process) = (
        example("track/track-cell.toml"),
        example("milling/kuka-stiffness.json"),
        example("milling/aluminium.toml"),
    );
    let mut args = vec!["compensate", "--setup", &setup, "--stiffness", &stiffness];
    args.extend(["--program", input.to_str().unwrap(), "--process", &process]);
    args.extend([
        "--out",
        out.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
    ]);
    args.extend(extra);
    assert_success(&stiffid(&args));
    let written = std::fs::read_to_string(&out).unwrap();
    (program::parse(&written, dialect).unwrap(), rows(&csv))
}

#[test]
fn every_dialect_reads_back_its_external_values_and_the_compensated_targets() {
    let dir = temp_dir("readback");
    for (dialect, name, text, tolerance) in programs() {
        let read = program::parse(&text, dialect).unwrap();
        let (written, rows) = compensate(&dir, (dialect, name, &text), "own", &[]);
        assert_eq!(written.targets.len(), targets().len(), "{dialect:?}");
        assert_eq!(rows.len(), targets().len(), "{dialect:?}");
        for (i, ((t, r), (given, e))) in (written.targets.iter().zip(&rows))
            .zip(targets())
            .enumerate()
        {
            assert_eq!(t.external, read.targets[i].external, "{dialect:?} {i}");
            assert_eq!(&t.external[..3], &e.map(Some), "{dialect:?} {i}");
            assert_eq!(r.e, e, "{dialect:?} {i}");
            for k in 0..6 {
                assert!(
                    (t.q_deg[k] - r.qc[k]).abs() <= tolerance,
                    "{dialect:?} {i} axis {}: {} against the CSV's {}",
                    k + 1,
                    t.q_deg[k],
                    r.qc[k]
                );
            }
            let moved = (0..6)
                .map(|k| (r.qc[k] - given[k]).abs())
                .fold(0.0, f64::max);
            assert!(moved > 1e-4, "{dialect:?} {i}: compensated by {moved} deg");
        }
    }
}

/// A free external axis `axis` (0: the track, mm; 1: the tilt, 2: the table, deg) compensated with `free`
/// options of range `range` and step `step`, read back from every dialect.
fn free_axis_is_written(free: &[&str], axis: usize, (range, step): (f64, f64)) {
    // One folder per option (two tests free the table's axis, by its two names).
    let named = free[1].split('=').next().unwrap();
    let dir = temp_dir(&format!("readback-free-{named}"));
    let upper = [6000.0, 95.0, 360.0][axis];
    let lower = [0.0, -95.0, -360.0][axis];
    for (dialect, name, text, tolerance) in programs() {
        let (_, own) = compensate(&dir, (dialect, name, &text), "own", &[]);
        let (written, rows) = compensate(&dir, (dialect, name, &text), "free", free);
        // INFORM writes the track in whole pulses, 0.01 mm (its table in decimals).
        let e_tolerance = match (dialect, axis) {
            (Dialect::Inform, 0) => 0.005 + 1e-9,
            _ => 1e-9,
        };
        let mut moved = false;
        for (i, ((t, r), (_, e))) in (written.targets.iter().zip(&rows))
            .zip(targets())
            .enumerate()
        {
            let value = t.external[axis].unwrap();
            assert!(
                (value - r.e[axis]).abs() <= e_tolerance,
                "{dialect:?} {i}: {value} written, the CSV's {}",
                r.e[axis]
            );
            assert!(
                (value - e[axis]).abs() <= range + e_tolerance,
                "{dialect:?} {i}: {value} from {}",
                e[axis]
            );
            assert!((lower - e_tolerance..=upper).contains(&value), "{value}");
            moved |= (value - e[axis]).abs() > 1e-3;
            for k in (0..3).filter(|k| *k != axis) {
                assert_eq!(t.external[k], Some(e[k]), "{dialect:?} {i}");
                assert_eq!(r.e[k], e[k], "{dialect:?} {i}");
            }
            for k in 0..6 {
                assert!((t.q_deg[k] - r.qc[k]).abs() <= tolerance, "{dialect:?} {i}");
            }
            assert!(
                r.bound <= own[i].bound + 1e-9,
                "{dialect:?} {i}: {} mm against {} mm at the given values",
                r.bound,
                own[i].bound
            );
        }
        assert!(moved, "{dialect:?}: the axis moves somewhere");
        let offsets: Vec<f64> = (rows.iter().zip(targets()))
            .map(|(r, (_, e))| r.e[axis] - e[axis])
            .collect();
        for w in offsets.windows(2) {
            assert!(
                (w[1] - w[0]).abs() <= step + 1e-9,
                "{dialect:?}: offsets {offsets:?}"
            );
        }
    }
}

#[test]
fn a_free_station_is_written_into_every_target_of_a_program() {
    let free = ["--free", "station=-200..200/50"];
    free_axis_is_written(&free, 0, (200.0, 50.0));
}

#[test]
fn a_free_table_angle_is_written_into_every_target_of_a_program() {
    let free = ["--free", "positioner=-20..20/5"];
    free_axis_is_written(&free, 2, (20.0, 5.0));
}

/// The positioner's axes by their names in the cell file: `rotate` is the table's turn, `tilt`
/// its tilt.
#[test]
fn a_free_axis_named_as_the_cell_names_it_is_that_axis() {
    free_axis_is_written(&["--free", "rotate=-20..20/5"], 2, (20.0, 5.0));
}

#[test]
fn a_free_tilt_is_written_into_every_target_of_a_program() {
    let free = ["--free", "tilt=-10..10/5"];
    free_axis_is_written(&free, 1, (10.0, 5.0));
}

/// `--map track` on the trim line along the rail: `map.csv` holds every point at every
/// station's offset of the free station's grid, with the collision distance column (empty: the
/// cell has no floor or obstacles) and one chosen station per point, the CSV's.
#[test]
fn the_track_map_holds_every_station_and_the_one_chosen() {
    let dir = temp_dir("track-map");
    let (setup, stiffness, path) = (
        example("track/track-cell.toml"),
        example("milling/kuka-stiffness.json"),
        example("track/trim.csv"),
    );
    let (out, report) = (dir.join("trim.csv"), dir.join("report"));
    let mut args = vec!["compensate", "--setup", &setup, "--stiffness", &stiffness];
    args.extend(["--path", &path, "--out", out.to_str().unwrap()]);
    args.extend(["--free", "station=-200..200/100"]);
    args.extend(["--map", "track", "--report", report.to_str().unwrap()]);
    assert_success(&stiffid(&args));
    let map = std::fs::read_to_string(report.join("map.csv")).unwrap();
    let mut lines = map.lines();
    assert_eq!(
        lines.next().unwrap(),
        "point,line,station_offset_mm,bound_mm,deflection_mm,condition,limit_distance_deg,collision_distance_mm,chosen"
    );
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    let csv = std::fs::read_to_string(&out).unwrap();
    let points = csv.lines().count() - 1;
    assert_eq!(rows.len(), 5 * points);
    for (i, point) in rows.chunks(5).enumerate() {
        let offsets: Vec<f64> = point.iter().map(|r| r[2].parse().unwrap()).collect();
        assert_eq!(offsets, vec![-200.0, -100.0, 0.0, 100.0, 200.0], "{i}");
        assert!(point.iter().all(|r| r[7].is_empty()), "{i}");
        assert_eq!(point.iter().filter(|r| r[8] == "1").count(), 1, "{i}");
        assert!(
            point.iter().all(|r| r[3].parse::<f64>().unwrap() > 0.0),
            "{i}"
        );
    }
}

/// `--map track` on a robot without a track is refused naming `--map`, nothing written.
#[test]
fn a_track_map_without_a_track_is_refused_naming_the_option() {
    let dir = temp_dir("track-map-none");
    let (setup, stiffness, path) = (
        example("milling/fanuc-milling.toml"),
        example("milling/stiffness.json"),
        example("milling/path.csv"),
    );
    let (out, report) = (dir.join("out.csv"), dir.join("report"));
    let mut args = vec!["compensate", "--setup", &setup, "--stiffness", &stiffness];
    args.extend(["--path", &path, "--out", out.to_str().unwrap()]);
    args.extend(["--map", "track", "--report", report.to_str().unwrap()]);
    common::refused(&dir, &args, &["--map", "no carrier axis"]);
    assert!(!out.exists() && !report.exists());
}
