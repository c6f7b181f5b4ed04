//! INFORM motions to robot position variables (`MOVJ P005`), read from the backup's `VAR.DAT`
//! and written as the job's own new positions, the variables left as they are; and the bad
//! backups a hostile user gives (a file cut off, a variable beyond it, two files).

use stiffid_core::setup::Pulses;
use stiffid_core::Error;
use stiffid_machining::program::{parse_in, Context, Dialect, JointProgram};

/// A GP-sized robot's pulses per degree (S, L, U, R, B, T), not whole.
const PER_DEG: [f64; 6] = [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7];

fn pulses() -> Pulses {
    Pulses {
        per_deg: PER_DEG,
        external: Vec::new(),
    }
}

/// A job that moves to its own position and to two variables, as a YRC1000 stores one (it
/// lists the variables it uses with their values when saved).
const JOB: &str = "/JOB\r\n//NAME PICK\r\n//POS\r\n///NPOS 1,0,0,2,0,0\r\n///TOOL 1\r\n///POSTYPE PULSE\r\n///PULSE\r\nC00000=-48629,112084,69901,4161,-52375,-4796\r\nP00003=-46969,105372,61036,4871,-50464,-5567\r\nP00005=-45969,104372,60036,4871,-50464,-5567\r\n//INST\r\n///DATE 2023/09/11 14:51\r\n///ATTR SC,RW\r\n///GROUP1 RB1\r\nNOP\r\nMOVJ C00000 VJ=25.00\r\nMOVL P005 V=100.0 PL=0\r\nDOUT OT#(2) ON\r\nMOVL P003 V=50.0\r\nMOVL P005 V=100.0\r\nEND\r\n";

/// The same job with the variables' values taught as its own positions.
const INLINE: &str = "/JOB\r\n//NAME PICK\r\n//POS\r\n///NPOS 4,0,0,0,0,0\r\n///TOOL 1\r\n///POSTYPE PULSE\r\n///PULSE\r\nC00000=-48629,112084,69901,4161,-52375,-4796\r\nC00001=-45969,104372,60036,4871,-50464,-5567\r\nC00002=-46969,105372,61036,4871,-50464,-5567\r\nC00003=-45969,104372,60036,4871,-50464,-5567\r\n//INST\r\n///DATE 2023/09/11 14:51\r\n///ATTR SC,RW\r\n///GROUP1 RB1\r\nNOP\r\nMOVJ C00000 VJ=25.00\r\nMOVL C00001 V=100.0 PL=0\r\nDOUT OT#(2) ON\r\nMOVL C00002 V=50.0\r\nMOVL C00003 V=100.0\r\nEND\r\n";

/// A `VAR.DAT` as a YRC1000 backup writes it (the layout of public backups): P000 to P005,
/// P003 and P005 in pulses with tool file 1, P004 in Cartesian form.
fn var_dat(p3: &str, p5: &str) -> String {
    let head = "//VAR\r\n///PFNUM 6,0,0,0\r\n///SHARE 250,250,250,250,250,250,0,0\r\n///B\r\n0,0,0,0,0,0,0,0,0,0\r\n///P\r\n";
    let pulse = |v: &str| format!("\"PULSE\"0,0,1,000000000000000000000000,0,0,{v},0,0\r\n");
    let rectan = "\"RECTAN\"0,0,4,000000000000000000000000,0,16,-863.111,979.613,492.219,178.9297,-0.1487,123.0482,0.0000,0.0000\r\n";
    format!(
        "{head}\"UNUSED\"\r\n\"UNUSED\"\r\n\"UNUSED\"\r\n{}{rectan}{}///BP\r\n///EX\r\n",
        pulse(p3),
        pulse(p5)
    )
}

const P3: &str = "-46969,105372,61036,4871,-50464,-5567";
const P5: &str = "-45969,104372,60036,4871,-50464,-5567";

/// A backup's files: each name and text.
type Backup = Vec<(String, String)>;

fn backup(var: String) -> Backup {
    vec![("backup/VAR.DAT".to_string(), var)]
}

fn read(job: &str, p: &Pulses, backup: &[(String, String)]) -> stiffid_core::Result<JointProgram> {
    let context = Context {
        pulses: Some(p),
        ..Default::default()
    };
    parse_in(job, Dialect::Inform, &context.with_backup(backup))
}

fn refused(result: stiffid_core::Result<JointProgram>) -> (u64, String) {
    match result {
        Err(Error::Program { line, message }) => (line, message),
        other => panic!("{other:?}"),
    }
}

/// Each motion to a variable is read as `VAR.DAT` holds it, equal to the same job with the
/// values taught inline; written compensated, each motion goes to a new position of the job
/// whose values are the inline job's compensated ones, `///NPOS` counts them, the variable
/// stays; a target that does not move keeps its variable.
#[test]
fn a_position_variable_is_read_from_var_dat_and_copied_into_the_job() {
    let p = pulses();
    let files = backup(var_dat(P3, P5));
    let job = read(JOB, &p, &files).unwrap();
    let inline = read(INLINE, &p, &[]).unwrap();
    let q = |r: &JointProgram| -> Vec<[f64; 6]> { r.targets.iter().map(|t| t.q_deg).collect() };
    assert_eq!(q(&job), q(&inline));
    assert_eq!(job.copied.len(), 3, "{:?}", job.copied);
    assert!(
        job.copied[0].starts_with("line 17: MOVL P005 read as backup/VAR.DAT line 12 holds it")
            && job.copied[0].contains("new position C00001"),
        "{}",
        job.copied[0]
    );
    // Unchanged: written as read, every variable kept.
    assert_eq!(job.write(&q(&job)).unwrap(), JOB);
    // Moved: the copies are the inline job's compensated positions.
    let mut moved = q(&job);
    for (k, row) in moved.iter_mut().enumerate() {
        row[0] += 0.5 + 0.1 * k as f64;
        row[4] -= 0.25;
    }
    let written = job.write(&moved).unwrap();
    let expected = inline.write(&moved).unwrap();
    let positions = |t: &str| -> Vec<String> {
        t.lines()
            .filter(|l| l.starts_with("C0"))
            .map(|l| l.to_string())
            .collect()
    };
    let mut ours = positions(&written);
    ours.sort();
    assert_eq!(ours, positions(&expected), "{written}");
    assert!(written.contains("///NPOS 4,0,0,2,0,0\r\n"), "{written}");
    assert!(written.contains("P00005=-45969,104372,60036,4871,-50464,-5567\r\n"));
    assert!(written.contains("MOVL C00001 V=100.0 PL=0\r\nDOUT OT#(2) ON\r\nMOVL C00002 V=50.0\r\nMOVL C00003 V=100.0\r\n"), "{written}");
    assert!(written.contains("///TOOL 1\r\n///POSTYPE PULSE\r\n///PULSE\r\nC00001="));
    // Read back without the backup: the very targets written, to half a pulse.
    let back = read(&written, &p, &[]).unwrap();
    for (a, b) in q(&back).iter().zip(&moved) {
        for k in 0..6 {
            assert!(
                (a[k] - b[k]).abs() <= 0.5 / PER_DEG[k] + 1e-12,
                "{a:?} {b:?}"
            );
        }
    }
    // Only the second motion moves: its copy is C00001 (no gap), the others keep P005, P003.
    let mut one = q(&job);
    one[2][0] += 1.0;
    let written = job.write(&one).unwrap();
    assert!(written.contains("///NPOS 2,0,0,2,0,0\r\n"), "{written}");
    assert!(
        written.contains("MOVL P005 V=100.0 PL=0\r\nDOUT OT#(2) ON\r\nMOVL C00001 V=50.0\r\nMOVL P005 V=100.0\r\n"),
        "{written}"
    );
    assert!(written.contains("C00001=-45628,105372,"), "{written}");
}

/// What a backup or a job does not say of a variable is refused naming the motion's line (or
/// the file and its line), never read wrong: no `VAR.DAT`, one cut off or beyond the variable,
/// two that differ, a variable unused, Cartesian, set by the job or by a job it calls, listed
/// by the job with other values, a local or indexed variable.
#[test]
fn what_the_backup_does_not_say_of_a_variable_is_refused() {
    let p = pulses();
    let good = var_dat(P3, P5);
    let cases: Vec<(String, Backup, u64, &str)> = vec![
        (JOB.into(), Vec::new(), 17, "give the controller's backup holding its VAR.DAT"),
        (JOB.into(), backup(format!("{}///BP\r\n///EX\r\n", good.split("\"PULSE\"0,0,1,000000000000000000000000,0,0,-45969").next().unwrap())), 17, "backup/VAR.DAT holds 5 position variables (P000 to P004)"),
        (JOB.replace("MOVL P003", "MOVL P004"), backup(good.replace(",0,16,", ",0,18,")), 19, "a \"RECTAN\" variable in tool coordinates (18)"),
        (JOB.replace("MOVL P003", "MOVL P001"), backup(good.clone()), 19, "line 8: the variable is UNUSED"),
        (JOB.replace("DOUT OT#(2) ON", "ADD P005 P003"), backup(good.clone()), 17, "set as the jobs run (line 18: ADD P005 P003)"),
        (JOB.replace("DOUT OT#(2) ON", "SET P[I000] P003"), backup(good.clone()), 17, "set as the jobs run (line 18: SET P[I000] P003)"),
        (JOB.replace("DOUT OT#(2) ON", "CALL JOB:SHIFT"), [backup(good.clone()), vec![("backup/SHIFT.JBI".into(), "/JOB\r\n//NAME SHIFT\r\n//POS\r\n///NPOS 0,0,0,0,0,0\r\n//INST\r\n///DATE 2023/09/11 14:51\r\n///ATTR SC,RW\r\n///GROUP1 RB1\r\nNOP\r\nSETE P003 (1) D000\r\nEND\r\n".into())]].concat(), 19, "(backup/SHIFT.JBI line 10: SETE P003 (1) D000)"),
        (JOB.replace("P00005=-45969", "P00005=-45970"), backup(good.clone()), 17, "the job lists the variable (line 10"),
        (JOB.replace("MOVL P003", "MOVL LP003"), backup(good.clone()), 19, "a local position variable"),
        (JOB.replace("MOVL P003", "MOVL P[I001]"), backup(good.clone()), 19, "an index the job computes as it runs"),
        (JOB.replace("MOVL P003 V=50.0", "MOVL P003 BC00000 V=50.0"), backup(good.clone()), 19, "beside base or station positions"),
        (JOB.replace("MOVL P003", "MOVL P4294967296"), backup(good.clone()), 19, "holds 6 position variables (P000 to P005)"),
    ];
    for (job, files, line, words) in cases {
        let (l, message) = refused(read(&job, &p, &files));
        assert_eq!(l, line, "{message}");
        assert!(message.contains(words), "{words}: {message}");
    }
    // A file cut off inside a line, two files that differ, a seven-axis robot's: the file.
    let bad = [
        backup(good[..good.len() - 40].to_string()),
        [backup(good.clone()), backup(var_dat(P5, P3))].concat(),
        backup(good.replace("PFNUM 6,", "PFNUM 7,")),
        backup(good.replace("///P\r\n", "///Q\r\n")),
        backup(good.replace("0,0,-45969", "0,0,-45969.5")),
        backup(good.replace("\r\n", "\r")),
        backup(good.replace("///BP\r\n///EX\r\n", "")),
    ];
    let says = [
        "line 12: the file ends inside this line",
        "two VAR.DAT files that differ",
        "a robot with 7 axes",
        "no ///P section",
        "'-45969.5': expected a whole number of pulses",
        "no ///P section",
        "the file ends in its ///P section",
    ];
    for (files, words) in bad.iter().zip(says) {
        match read(JOB, &p, files) {
            Err(Error::Parse {
                source_name,
                message,
            }) => {
                assert_eq!(source_name, "backup/VAR.DAT");
                assert!(message.contains(words), "{words}: {message}");
            }
            other => panic!("{words}: {other:?}"),
        }
    }
}

/// The job as its controller's second robot runs it (`///GROUP1 RB2`), on ROS-Industrial's
/// Motoman GP25 (tests/data/robots, SOURCES.md) with `[controller] robot_number = 2`: every
/// motion (its own position and the variables of `VAR.DAT`) compensated, each target the
/// file's pulses over the setup's pulses per degree, each result the very one of the job as
/// the first robot's on a setup of that robot; the first robot's setup refuses the second's job
/// naming its `///GROUP1` line.
#[test]
fn a_second_robots_job_runs_on_a_motoman_gp25_as_a_first_robots_does() {
    use super::rapid::robots::{cell, inner, run};
    use stiffid::internal::machining::compensate::Target;
    let controller = |more: &str| {
        let per: Vec<String> = PER_DEG.iter().map(f64::to_string).collect();
        format!(
            "[controller]\npulses_per_deg = [{}]\n{more}",
            per.join(", ")
        )
    };
    let gp25 = |more: &str| {
        cell(
            "motoman_gp25.urdf",
            "tool0",
            &controller(more),
            [0.0, 0.0, 150.0],
            3.0,
        )
    };
    let (rb1, rb2) = (gp25(""), gp25("robot_number = 2\n"));
    let files = backup(var_dat(P3, P5));
    let second = JOB.replace("///GROUP1 RB1", "///GROUP1 RB2");
    let one = run(&rb1, ("PICK.JBI", JOB, Dialect::Inform), &files, false).unwrap();
    let two = run(&rb2, ("PICK.JBI", &second, Dialect::Inform), &files, false).unwrap();
    let stated = [
        (16, "-48629,112084,69901,4161,-52375,-4796"),
        (17, P5),
        (19, P3),
        (20, P5),
    ];
    assert_eq!(two.len(), stated.len());
    for (((p, c), (p1, c1)), (line, pulses)) in two.iter().zip(&one).zip(stated) {
        assert_eq!(p.line, line);
        let q: Vec<f64> = (pulses.split(',').zip(PER_DEG))
            .map(|(v, per)| (v.parse::<f64>().unwrap() / per).to_radians())
            .collect();
        let Target::Posture(read) = &p.target else {
            panic!("line {line}: {:?}", p.target)
        };
        let d = read
            .iter()
            .zip(&q)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(d < 1e-12, "line {line}: {d} rad");
        assert_eq!((p, c), (p1, c1), "line {line}");
        assert!((c.q_compensated - c.q).norm() > 1e-6, "line {line}");
    }
    match inner(run(&rb1, ("PICK.JBI", &second, Dialect::Inform), &files, false).unwrap_err()) {
        Error::Program { line, message } => {
            assert_eq!(line, 14, "{message}");
            assert!(message.contains("a job of robot RB2"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

/// A backup folder's `VAR.DAT` that is no text (a NUL byte) is refused naming it, not passed over
/// as a folder's stray binary file is (its variables would then be asked for as not given).
#[test]
fn a_var_dat_that_is_no_text_is_refused_naming_it() {
    use stiffid::internal::machining::program::read_backup;
    let dir = std::env::temp_dir().join(format!("stiffid-inform-var-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("VAR.DAT"), b"//VAR\r\n\0\r\n").unwrap();
    std::fs::write(dir.join("ALMHIST.DAT"), b"\0\0").unwrap();
    let read = |p: &std::path::Path| std::fs::read(p);
    let wrap = |e: Error| std::io::Error::other(e.to_string());
    let result = read_backup(std::slice::from_ref(&dir), Dialect::Inform, read, wrap);
    std::fs::remove_dir_all(&dir).unwrap();
    let e = result.unwrap_err().to_string();
    assert!(e.contains("VAR.DAT"), "{e}");
}
