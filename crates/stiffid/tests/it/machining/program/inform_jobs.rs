//! INFORM jobs as the controllers store them (`stiffid_machining::program::inform`): pulses from
//! the setup, tool files, `MOVC`, what real jobs write around their motions, and the real jobs
//! of `tests/data/programs/inform` (SOURCES.md there), each read point by point against an
//! independent reading or refused naming its line and construct.

use nalgebra::Isometry3;
use stiffid_core::setup::{NumberedFrames, Pulses};
use stiffid_core::Error;
use stiffid_machining::program::{parse, parse_in, Context, Dialect, JointProgram};

/// A GP-sized robot's pulses per degree (S, L, U, R, B, T), not whole.
const PER_DEG: [f64; 6] = [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7];

fn pulses() -> Pulses {
    Pulses {
        per_deg: PER_DEG,
        external: Vec::new(),
    }
}

fn with(p: &Pulses) -> Context<'_> {
    Context {
        home_deg: None,
        backup: &[],
        pulses: Some(p),
        tool: None,
        data: None,
        machine: None,
        ..Default::default()
    }
}

/// A job as a YRC1000 stores it: no `///POSTYPE` line, tool file 1, no `'stiffid:` comment,
/// I/O, timers, arc welding, a label and a circle around its motions.
const STORED: &str = "/JOB\r\n//NAME WELD\r\n//POS\r\n///NPOS 5,0,0,0,0,0\r\n///TOOL 1\r\nC00000=-48629,112084,69901,4161,-52375,-4796\r\nC00001=-46969,105372,61036,4871,-50464,-5567\r\nC00002=-45969,104372,60036,4871,-50464,-5567\r\nC00003=-44969,105372,61036,4871,-50464,-5567\r\nC00004=-43969,106372,62036,4871,-50464,-5567\r\n//INST\r\n///DATE 2023/02/07 09:03\r\n///ATTR SC,RW\r\n///GROUP1 RB1\r\nNOP\r\n*START\r\nDOUT OT#(12) ON\r\nTIMER T=0.50\r\nMOVJ C00000 VJ=25.00 PL=0\r\nWAIT IN#(3)=ON\r\nARCON ASF#(1)\r\nMOVL C00001 V=10.0 PL=0 NWAIT\r\nMOVC C00002 V=10.0\r\nMOVC C00003 V=10.0\r\nMOVC C00004 V=10.0 PL=0\r\nARCOF AEF#(1)\r\nSET B000 1\r\nEND\r\n";

/// The `C` positions of `text` read independently: each `Cnnnnn=` line's numbers divided by
/// `per_deg`, by position number.
fn independent(text: &str, per_deg: &[f64; 6]) -> Vec<(u32, Vec<f64>)> {
    text.lines()
        .filter(|l| l.starts_with('C') && l.contains('='))
        .map(|l| {
            let (name, values) = l.split_once('=').unwrap();
            let values = (values.trim().split(',').zip(per_deg))
                .map(|(v, per)| v.parse::<i64>().unwrap() as f64 / per)
                .collect();
            (name[1..].parse().unwrap(), values)
        })
        .collect()
}

/// The position numbers the motion lines of `text` name, in order.
fn moved_to(text: &str) -> Vec<u32> {
    text.lines()
        .filter(|l| {
            ["MOVJ C", "MOVL C", "MOVC C"]
                .iter()
                .any(|m| l.starts_with(m))
        })
        .map(|l| l[6..11].parse().unwrap())
        .collect()
}

fn refused(result: stiffid_core::Result<JointProgram>) -> (u64, String) {
    match result {
        Err(Error::Program { line, message }) => (line, message),
        other => panic!("{other:?}"),
    }
}

/// A job stored as the controller stores it is read with the setup's pulses, every target equal
/// to the independent reading, MOVC a path motion; written back, the MOVC lines stay MOVC and
/// only the positions change, in whole pulses.
#[test]
fn a_stored_job_is_read_with_the_setups_pulses() {
    let p = pulses();
    let (line, message) = refused(parse(STORED, Dialect::Inform));
    assert_eq!(line, 19);
    assert!(message.contains("[controller] pulses_per_deg"), "{message}");
    let read = parse_in(STORED, Dialect::Inform, &with(&p)).unwrap();
    let positions = independent(STORED, &PER_DEG);
    let order = moved_to(STORED);
    assert_eq!(read.targets.len(), 5);
    for (t, n) in read.targets.iter().zip(&order) {
        let (_, want) = positions.iter().find(|(k, _)| k == n).unwrap();
        for (a, b) in t.q_deg.iter().zip(want) {
            assert!((a - b).abs() < 1e-12, "{a} {b}");
        }
    }
    let lines: Vec<u64> = read.targets.iter().map(|t| t.line).collect();
    assert_eq!(lines, [19, 22, 23, 24, 25]);
    assert!(
        matches!(read.targets[3].speed, stiffid_machining::program::speed::Speed::Path(v) if (v - 0.01).abs() < 1e-12)
    );
    let mut q: Vec<[f64; 6]> = read.targets.iter().map(|t| t.q_deg).collect();
    q[3][1] += 0.01;
    let written = read.write(&q).unwrap();
    let changed = (written.lines().zip(STORED.lines())).filter(|(a, b)| a != b);
    let changed: Vec<(&str, &str)> = changed.collect();
    assert_eq!(changed.len(), 1, "{changed:?}");
    let l = ((105372.0 / PER_DEG[1] + 0.01) * PER_DEG[1]).round() as i64;
    assert_eq!(
        changed[0].0,
        format!("C00003=-44969,{l},61036,4871,-50464,-5567")
    );
    assert!(written.contains("MOVC C00003 V=10.0\r\n"));
}

/// What a YRC1000 backup holds around its motions and moves nothing: an instruction's comment
/// after `//` (`MOVJ C00000 VJ=65.00  //FROM LEFT`), a line commented out on the pendant
/// (`COMM CALL JOB:..`, `COMM MOVL C..`), a user alarm, a message with `//` inside its quotes:
/// the job reads as without them, and written back keeps every one of those lines.
#[test]
fn comments_commented_out_lines_and_alarms_move_nothing() {
    let p = pulses();
    let plain = parse_in(STORED, Dialect::Inform, &with(&p)).unwrap();
    let commented = STORED
        .replace("VJ=25.00 PL=0\r\n", "VJ=25.00 PL=0  //FROM LEFT\r\n")
        .replace("V=10.0 PL=0 NWAIT", "V=10.0 PL=0 NWAIT  //INTO")
        .replace(
            "SET B000 1\r\n",
            "SET B000 1\r\nCOMM CALL JOB:SPINDLE_STOP\r\nCOMM MOVL C00004 V=15.0\r\nSETUALM 8000 \"CHECK\" 0\r\nMSG \"SEE http://a\"\r\n",
        );
    let read = parse_in(&commented, Dialect::Inform, &with(&p)).unwrap();
    let q = |r: &JointProgram| r.targets.iter().map(|t| t.q_deg).collect::<Vec<_>>();
    assert_eq!(q(&read), q(&plain));
    let lines: Vec<u64> = read.targets.iter().map(|t| t.line).collect();
    assert_eq!(lines, [19, 22, 23, 24, 25]);
    let mut moved = q(&read);
    moved[0][0] += 0.5;
    let written = read.write(&moved).unwrap();
    for kept in [
        "MOVJ C00000 VJ=25.00 PL=0  //FROM LEFT\r\n",
        "COMM CALL JOB:SPINDLE_STOP\r\nCOMM MOVL C00004 V=15.0\r\n",
        "SETUALM 8000 \"CHECK\" 0\r\n",
    ] {
        assert!(written.contains(kept), "{written}");
    }
    // A `//` that does not follow a space is no comment: the tag is refused as before.
    let glued = STORED.replace("VJ=25.00 PL=0", "VJ=25.00 PL=0//X");
    let (line, message) = refused(parse_in(&glued, Dialect::Inform, &with(&p)));
    assert_eq!(line, 19);
    assert!(message.contains("PL=0//X"), "{message}");
}

/// A `TOOL.CND` as a YRC1000 backup writes it: per tool file its number, name, frame (X, Y, Z
/// mm, Rx, Ry, Rz deg), centre of gravity, weight and inertia; tool file 1 at `frame`.
fn tool_cnd(frame: &str) -> String {
    let rest = "0.000,0.000,0.000\r\n0.000\r\n0.000,0.000,0.000\r\n0.000,0,1\r\n";
    format!("//TOOL 0\r\n///NAME STANDARD TOOL\r\n0.000,0.000,0.000,0.0000,0.0000,0.0000\r\n{rest}//TOOL 1\r\n///NAME SPINDLE\r\n{frame}\r\n{rest}//TOOL 2\r\n///NAME\r\n0.000,0.000,250.000,0.0000,0.0000,0.0000\r\n{rest}")
}

/// The tool files of a backup's `TOOL.CND` take the place of the setup's `[controller] tools`:
/// one at the setup's tool centre point reads (turned or not: pulse positions do not depend on
/// it), a job changing between two such files reads, one elsewhere is refused, one the setup's
/// table gives otherwise is refused naming both, a frame line cut off names the file's line.
#[test]
fn tool_cnd_gives_the_tool_files() {
    let p = pulses();
    let tool = Isometry3::translation(0.0, 0.0, 0.25);
    let empty = NumberedFrames::default();
    let other = NumberedFrames::new(
        "controller.tools",
        &[(1, Isometry3::translation(0.0, 0.0, 0.26))],
    )
    .unwrap();
    let read = |text: &str, cnd: String, tools: &NumberedFrames| {
        let backup = vec![("backup/TOOL.CND".to_string(), cnd)];
        let context = Context {
            tool: Some((tool, tools)),
            ..with(&p)
        };
        parse_in(text, Dialect::Inform, &context.with_backup(&backup))
    };
    let turned = tool_cnd("0.000,0.000,250.000,0.0000,90.0000,0.0000");
    assert!(read(STORED, turned.clone(), &empty).is_ok());
    let changes = STORED.replace("MOVC C00003 V=10.0", "MOVC C00003 V=10.0 TOOL#(2)");
    let (line, message) = refused(parse_in(
        &changes,
        Dialect::Inform,
        &Context {
            tool: Some((tool, &empty)),
            ..with(&p)
        },
    ));
    assert_eq!(line, 24, "{message}");
    assert_eq!(
        read(&changes, turned.clone(), &empty)
            .unwrap()
            .targets
            .len(),
        5
    );
    let (line, message) = refused(read(
        STORED,
        tool_cnd("0.000,0.000,260.000,0.0000,0.0000,0.0000"),
        &empty,
    ));
    assert_eq!(line, 5);
    assert!(
        message.contains("tool file 1, which the backup's backup/TOOL.CND line 10 (tool file 1) gives as X 0 mm, Y 0 mm, Z 260 mm")
            && message.contains("is not the setup's tool"),
        "{message}"
    );
    let (line, message) = refused(read(STORED, turned.clone(), &other));
    assert_eq!(line, 5);
    assert!(
        message.contains("tool file 1: the backup's backup/TOOL.CND line 10 (tool file 1) gives X 0 mm, Y 0 mm, Z 250 mm")
            && message.contains("the setup's [controller] tools X 0 mm, Y 0 mm, Z 260 mm"),
        "{message}"
    );
    // A frame line cut short, a tool file given twice otherwise, a file ending inside a line.
    let twice = format!("{turned}//TOOL 1\r\n///NAME\r\n0.000,0.000,251.000,0,0,0\r\n");
    let cases = [
        (
            tool_cnd("0.000,0.000,250.000,0.0000"),
            "line 10: tool file 1 (line 8): expected its frame",
        ),
        (
            twice,
            "line 24: tool file 1 again, another frame than backup/TOOL.CND line 10",
        ),
        (
            turned[..turned.len() - 2].to_string(),
            "line 21: the file ends inside this line",
        ),
        // Empty, headers only, a tool file with no frame line.
        (String::new(), "no tool file: the file is empty"),
        (
            "///NAME SPINDLE\r\n".into(),
            "no tool file: the file is empty",
        ),
        (
            "//TOOL 1\r\n///NAME SPINDLE\r\n".into(),
            "line 1: tool file 1 with no frame line",
        ),
    ];
    for (file, says) in cases {
        match read(STORED, file, &empty) {
            Err(Error::Parse {
                source_name,
                message,
            }) => {
                assert_eq!(source_name, "backup/TOOL.CND");
                assert!(message.starts_with(says), "{says}: {message}");
            }
            other => panic!("{says}: {other:?}"),
        }
    }
}

/// A job that moves nothing as a controller stores it: I/O, a wait, and `then` (its last
/// instructions before `END`).
fn io_job(name: &str, then: &str) -> String {
    format!("/JOB\r\n//NAME {name}\r\n//POS\r\n///NPOS 0,0,0,0,0,0\r\n//INST\r\n///DATE 2021/12/03 12:01\r\n///ATTR SC,RW\r\n///GROUP1 RB1\r\nNOP\r\nDOUT OT#(5) ON\r\nWAIT IN#(5)=ON T=5.00\r\n{then}END\r\n")
}

/// A `CALL JOB:` between motions is passed over when the backup holds the job called and it
/// (and every job it calls) moves nothing; refused naming the line without the backup, and for
/// a chain of calls that loops; a called job that moves is read (its refusal named).
#[test]
fn a_call_of_a_job_that_moves_nothing_is_passed_over() {
    let p = pulses();
    let calling = STORED.replace("SET B000 1", "CALL JOB:SPINDLE_ON");
    let read = |backup: &[(String, String)]| {
        parse_in(&calling, Dialect::Inform, &with(&p).with_backup(backup))
    };
    let (line, message) = refused(read(&[]));
    assert_eq!(line, 27);
    assert!(
        message.contains("give the controller's backup holding SPINDLE_ON.JBI"),
        "{message}"
    );
    let lamp = (
        "JOBS/LAMP.JBI".to_string(),
        io_job("LAMP", "TIMER T=0.50\r\n"),
    );
    let on = |then: &str| {
        (
            "JOBS/SPINDLE_ON.JBI".to_string(),
            io_job("SPINDLE_ON", then),
        )
    };
    let backup = [on("CALL JOB:LAMP IF IN#(2)=ON\r\n"), lamp.clone()];
    let ok = read(&backup).unwrap();
    assert_eq!(ok.targets.len(), 5);
    let plain = parse_in(STORED, Dialect::Inform, &with(&p)).unwrap();
    assert_eq!(ok.targets, plain.targets);
    let moving = io_job("SPINDLE_ON", "").replace("NOP\r\n", "NOP\r\nMOVJ C00000 VJ=10.00\r\n");
    let (line, message) = refused(read(&[
        ("SPINDLE_ON.JBI".to_string(), moving),
        lamp.clone(),
    ]));
    // A called job that moves is read where it is called: this one names a position it does not
    // hold.
    assert_eq!(line, 27);
    assert!(
        message
            .contains("CALL JOB:SPINDLE_ON: SPINDLE_ON.JBI line 10: MOVJ C00000: no such position"),
        "{message}"
    );
    let looping = (
        "LAMP.JBI".to_string(),
        io_job("LAMP", "CALL JOB:SPINDLE_ON\r\n"),
    );
    let (_, message) = refused(read(&[on("CALL JOB:LAMP\r\n"), looping]));
    assert!(
        message.contains("CALL JOB:LAMP: LAMP.JBI line 12: CALL JOB:SPINDLE_ON: the job calls itself through SPINDLE_ON, LAMP"),
        "{message}"
    );
}

/// A station's own motion beside the robot's (`+MOVJ EC00000 VJ=10.00`, as a YRC1000 welding
/// cell's job moves its positioner) is read as the station's values of the target, as `EC` in
/// the robot's motion; another group's motion or a tag the station's motion does not take is
/// refused naming the line.
#[test]
fn a_stations_own_motion_gives_the_targets_station_values() {
    let p = Pulses {
        per_deg: PER_DEG,
        external: vec![100.0, 200.0],
    };
    let station = STORED.replace("///NPOS 5,0,0", "///NPOS 5,0,1").replace(
        "//INST",
        "///POSTYPE PULSE\r\n///PULSE\r\nEC00000=1000,-2000\r\n//INST",
    );
    let own = station.replace(
        "VJ=25.00 PL=0",
        "VJ=25.00 PL=0  +MOVJ EC00000 VJ=10.00 DEC=20",
    );
    let inline = station.replace("MOVJ C00000 VJ=25.00", "MOVJ C00000 EC00000 VJ=25.00");
    let read = |text: &str| parse_in(text, Dialect::Inform, &with(&p));
    let (a, b) = (read(&own).unwrap(), read(&inline).unwrap());
    assert_eq!(a.axes, ["EC1", "EC2"]);
    assert_eq!(a.targets[0].external, [Some(10.0), Some(-10.0)]);
    assert_eq!(a.targets, b.targets);
    // A coordinated motion (`SMOVL .. +MOVJ EC..`, as RoboDK's Motoman post writes it) reads as
    // the same motion with the station's values, and is written back as such; one without the
    // station's position is refused on its line.
    let linear = "MOVL C00001 V=10.0 PL=0 NWAIT";
    let with_station = |word: &str| {
        own.replace(
            linear,
            &format!("{word} C00001 V=10.0 PL=0 NWAIT  +MOVJ EC00000"),
        )
    };
    let (smovl, movl) = (
        read(&with_station("SMOVL")).unwrap(),
        read(&with_station("MOVL")).unwrap(),
    );
    assert_eq!(smovl.targets, movl.targets);
    assert_eq!(smovl.targets[1].external, [Some(10.0), Some(-10.0)]);
    let q: Vec<[f64; 6]> = smovl.targets.iter().map(|t| t.q_deg).collect();
    assert!(smovl
        .write(&q)
        .unwrap()
        .contains("\r\nSMOVL C00001 V=10.0 PL=0 NWAIT  +MOVJ EC00000\r\n"));
    // Three coordinated circle points are a circle's, as three MOVC points: its via point fed
    // along the circle.
    let circle = |word: &str| {
        (2..=4).fold(own.clone(), |text, k| {
            text.replace(
                &format!("MOVC C0000{k} V=10.0"),
                &format!("{word} C0000{k} V=10.0  +MOVJ EC00000"),
            )
        })
    };
    let (smovc, movc) = (
        read(&circle("SMOVC")).unwrap(),
        read(&circle("MOVC")).unwrap(),
    );
    assert_eq!(smovc.targets, movc.targets);
    let (line, message) = refused(read(&own.replace(linear, "SMOVL C00001 V=10.0")));
    assert_eq!(line, 25, "{message}");
    assert!(
        message
            .contains("SMOVL C00001 V=10.0: a coordinated motion without the station's position"),
        "{message}"
    );
    for (tags, words) in [
        ("+MOVL EC00000 V=10.0", "another group's own motion"),
        (
            "+MOVJ EC00000 V=10.0",
            "V=10.0: a tag of the station's motion",
        ),
        ("+MOVJ C00001 VJ=10.00", "another group's own motion"),
    ] {
        let text = station.replace("VJ=25.00 PL=0", &format!("VJ=25.00 PL=0  {tags}"));
        let (line, message) = refused(read(&text));
        assert_eq!(line, 22, "{message}");
        assert!(message.contains(words), "{message}");
    }
}

/// The job's `'stiffid:` pulses are used when the setup gives none and refused, naming both,
/// when they contradict the setup's or each other.
#[test]
fn contradicting_pulses_are_refused_naming_both() {
    let comment = |v: &str| {
        STORED.replace(
            "NOP\r\n",
            &format!("NOP\r\n'stiffid: pulses_per_deg = {v}\r\n"),
        )
    };
    let same = comment("1341.25 1341.25 1150.5 873.4 873.4 532.7");
    let alone = parse(&same, Dialect::Inform).unwrap();
    let p = pulses();
    let both = parse_in(&same, Dialect::Inform, &with(&p)).unwrap();
    assert_eq!(alone.targets, both.targets);
    let other = comment("1000 1000 1000 1000 1000 1000");
    let (line, message) = refused(parse_in(&other, Dialect::Inform, &with(&p)));
    assert_eq!(line, 16);
    assert!(
        message.contains("contradicts the setup's [controller] pulses_per_deg = [1341.25"),
        "{message}"
    );
    let twice = other.replace(
        "NOP\r\n",
        "NOP\r\n'stiffid: pulses_per_deg = 1000 1000 1000 1000 1000 999\r\n",
    );
    let (line, message) = refused(parse(&twice, Dialect::Inform));
    assert_eq!(line, 17);
    assert!(
        message.contains("stated twice with other values (lines 16 and 17)"),
        "{message}"
    );
}

/// A tool file the setup's `[controller] tools` gives is checked against the setup's tool; one it
/// does not give is the setup's only in a job that never changes it.
#[test]
fn tool_files_are_checked_against_the_setups_tool() {
    let p = pulses();
    let tool = Isometry3::translation(0.0, 0.0, 0.3);
    let held = NumberedFrames::new("controller.tools", &[(1, tool)]).unwrap();
    let other = NumberedFrames::new(
        "controller.tools",
        &[(1, Isometry3::translation(0.0, 0.0, 0.25))],
    )
    .unwrap();
    let context = |tools| Context {
        home_deg: None,
        backup: &[],
        pulses: Some(&p),
        tool: Some((tool, tools)),
        data: None,
        machine: None,
        ..Default::default()
    };
    assert!(parse_in(STORED, Dialect::Inform, &context(&held)).is_ok());
    let (line, message) = refused(parse_in(STORED, Dialect::Inform, &context(&other)));
    assert_eq!(line, 5);
    assert!(
        message.contains("tool file 1") && message.contains("is not the setup's tool"),
        "{message}"
    );
    let empty = NumberedFrames::default();
    assert!(parse_in(STORED, Dialect::Inform, &context(&empty)).is_ok());
    let changes = STORED.replace("MOVC C00003 V=10.0", "MOVC C00003 V=10.0 TOOL#(2)");
    let (line, message) = refused(parse_in(&changes, Dialect::Inform, &context(&empty)));
    assert_eq!(line, 24);
    assert!(
        message.contains("tool file 2 after tool file 1 (line 5)"),
        "{message}"
    );
    // A joint motion to pulses does not use its tool file: another one there is not checked.
    let joint = STORED.replace("VJ=25.00 PL=0", "VJ=25.00 PL=0 TOOL#(2)");
    assert!(parse_in(&joint, Dialect::Inform, &context(&empty)).is_ok());
}

/// What changes the path or cannot be known is refused naming its line: a shift, weaving, a
/// position variable, a jump, an unknown instruction, a speed that is not a number, a job cut off, a NUL.
#[test]
fn what_can_change_the_path_is_refused_naming_the_line() {
    let p = pulses();
    let cases: Vec<(String, u64, &str)> = vec![
        (
            STORED.replace("ARCOF AEF#(1)", "SFTON P001 TF"),
            26,
            "SFTON P001 TF: a shift in tool coordinates (TF)",
        ),
        (
            STORED
                .replace("ARCON ASF#(1)", "SFTON P001")
                .replace("ARCOF", "SFTOF\r\nARCOF"),
            21,
            "SFTON P001: the shift amount P001 holds its value on the controller",
        ),
        (
            STORED.replace("ARCON ASF#(1)", "ARCON ASF#(1)\r\nWVON WEV#(1)"),
            22,
            "WVON WEV#(1): weaving (WVON) moves the tool across the path",
        ),
        (
            STORED.replace("MOVL C00001", "MOVL P001"),
            22,
            "MOVL P001: a position variable",
        ),
        (
            STORED.replace("SET B000 1", "JUMP *FINISH"),
            27,
            "JUMP *FINISH: a jump to a label the job does not hold (*FINISH)",
        ),
        (
            STORED.replace("SET B000 1", "JUMP JOB:OTHER"),
            27,
            "a jump to another job, which does not come back",
        ),
        (
            STORED.replace("SET B000 1", "JUMP *START IF IN#(1)=ON\r\n*START"),
            28,
            "*START: the label is also on line 16",
        ),
        (
            STORED.replace(
                "ARCON ASF#(1)",
                "ARCON ASF#(1)\r\nWVON WEV#(1)\r\nWVOF\r\n*A\r\nJUMP *A IF IN#(2)=ON",
            ),
            22,
            "WVON: weaving in a job with jumps, loops or branches (line 25)",
        ),
        (
            STORED.replace("SET B000 1", "FROBNICATE 3"),
            27,
            "an instruction stiffid does not know",
        ),
        (
            STORED.replace("SET B000 1", "FORMCUT FCF#(9)"),
            27,
            "FORMCUT: a form cut",
        ),
        (
            STORED.replace("V=10.0 PL=0 NWAIT", "V=nan PL=0"),
            22,
            "V=nan: expected a number",
        ),
        (
            STORED
                .replace("MOVS", "")
                .replace("MOVC C00002", "MOVS C00002"),
            23,
            "MOVS: a spline",
        ),
        (
            STORED.replace("SET B000 1\r\nEND\r\n", "SET B000 1\r\nMOVL C000"),
            28,
            "without END",
        ),
        (
            STORED.replace("MOVL C00001 V=10.0", "MOVL C00001 V=10.0\0"),
            22,
            "a control character",
        ),
        (
            STORED.replace("///GROUP1 RB1", "///GROUP1 RB1,RB2"),
            14,
            "a job of robot RB2",
        ),
        (
            STORED.replace("///NPOS 5,", "///NPOS 6,"),
            4,
            "///NPOS declares 6 C positions, //POS holds 5",
        ),
    ];
    for (text, line, words) in cases {
        let (at, message) = refused(parse_in(&text, Dialect::Inform, &with(&p)));
        assert_eq!(at, line, "{words}: {message}");
        assert!(message.contains(words), "{words}: {message}");
    }
    // Weaving switched on and off with no motion between moves nothing: the job reads.
    let idle = STORED.replace("ARCON ASF#(1)", "ARCON ASF#(1)\r\nWVON WEV#(1)\r\nWVOF");
    let read = parse_in(&idle, Dialect::Inform, &with(&p)).unwrap();
    assert_eq!(read.targets.len(), 5);
}

/// A `CALL JOB:NAME` of a job of the backup that moves: its motions read after the caller's,
/// compensated in place in its own file; every other byte of both as read.
#[test]
fn a_call_of_a_job_that_moves_is_compensated_in_its_own_file() {
    let p = pulses();
    let main = STORED.replace("SET B000 1", "CALL JOB:PICK IF IN#(1)=ON");
    let pick = STORED.replace("//NAME WELD", "//NAME PICK");
    let backup = [("backup/PICK.JBI".to_string(), pick.clone())];
    let read = parse_in(&main, Dialect::Inform, &with(&p).with_backup(&backup)).unwrap();
    assert_eq!(read.targets.len(), 10);
    let q: Vec<[f64; 6]> = read.targets.iter().map(|t| t.q_deg).collect();
    assert_eq!(q[..5], q[5..]);
    assert_eq!(read.called_in(4), None);
    assert_eq!(read.called_in(5), Some("backup/PICK.JBI"));
    let mut moved = q.clone();
    moved[5][0] += 1.0;
    let (written, _, called) = read.write_files(&moved, &vec![Vec::new(); 10]).unwrap();
    assert_eq!(written, main);
    // 1 deg of axis S is 1341.25 pulses: -48629 + 1341.25, to the nearest whole pulse.
    let expected = pick.replacen("C00000=-48629,", "C00000=-47288,", 1);
    assert_eq!(called, [("backup/PICK.JBI".to_string(), expected)]);
    // A job that calls itself is refused naming the call.
    let looped = [(
        "backup/PICK.JBI".to_string(),
        pick.replace("SET B000 1", "CALL JOB:PICK"),
    )];
    let (line, message) = refused(parse_in(
        &main,
        Dialect::Inform,
        &with(&p).with_backup(&looped),
    ));
    assert_eq!(line, 27, "{message}");
    assert!(
        message.contains("the job calls itself through PICK"),
        "{message}"
    );
}

/// A job's jumps, branches and loops are followed: each motion read where it is, to the very
/// target it has in the straight job (pulses change with no path).
#[test]
fn motions_inside_jumps_branches_and_loops_are_read_where_they_are() {
    let p = pulses();
    let straight = parse_in(STORED, Dialect::Inform, &with(&p)).unwrap();
    let looped = STORED
        .replacen("MOVL C00001", "*TOP\r\nIFTHEN IN#(1)=ON\r\nMOVL C00001", 1)
        .replace(
            "SET B000 1",
            "ELSE\r\nTIMER T=1.00\r\nENDIF\r\nJUMP *TOP IF IN#(2)=ON\r\nSET B000 1",
        );
    let read = parse_in(&looped, Dialect::Inform, &with(&p)).unwrap();
    let q = |r: &stiffid_machining::program::JointProgram| -> Vec<[f64; 6]> {
        r.targets.iter().map(|t| t.q_deg).collect()
    };
    assert_eq!(read.targets.len(), 5);
    assert_eq!(q(&read), q(&straight));
    assert_eq!(read.targets[1].line, straight.targets[1].line + 2);
}

/// The real jobs of the corpus (tests/data/programs/inform, SOURCES.md): each refused naming
/// its line and construct, with the setup's pulses given (a GP-sized robot's), never read wrong.
#[test]
fn the_real_jobs_are_refused_naming_line_and_construct() {
    let p = pulses();
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/programs/inform/");
    let expected: [(&str, u64, &str); 8] = [
        (
            "MQCIA_DROP01.JBI",
            45,
            "CALL: a jump, call, macro, loop or branch",
        ),
        (
            "MQCIA_ROBOT_CELL_000.JBI",
            79,
            "WVON WEV#(25): weaving (WVON) moves the tool across the path",
        ),
        ("TSHIKINA_TEST1.JBI", 32, "IMOV: an increment"),
        (
            "MOTOROS2_INIT_ROS_SINGLE_ARM.JBI",
            1,
            "no motion to a target found",
        ),
        (
            "MOTOROS2_INIT_ROS_TWO_ARMS.JBI",
            9,
            "///GROUP2 RB2: a job of robot RB2",
        ),
        ("ROSI_ROS_R1B1.JBI", 1, "no motion to a target found"),
        ("ROSI_ROS_S1.JBI", 8, "///GROUP1 ST1: a job of ST1 alone"),
        (
            "ROSI_INIT_ROS_CALL_JOB_MAIN.JBI",
            1,
            "no motion to a target found",
        ),
    ];
    let files = std::fs::read_dir(dir).unwrap();
    let jobs = files.filter(|f| {
        f.as_ref()
            .unwrap()
            .path()
            .extension()
            .is_some_and(|e| e == "JBI")
    });
    assert_eq!(jobs.count(), expected.len());
    for (name, line, words) in expected {
        let text = std::fs::read_to_string(format!("{dir}{name}")).unwrap();
        let (at, message) = refused(parse_in(&text, Dialect::Inform, &with(&p)));
        assert_eq!(at, line, "{name}: {message}");
        assert!(message.contains(words), "{name}: {message}");
    }
}

/// A base axis in pulses: the setup's `external_pulses`, or the job's comment, never two that
/// differ.
#[test]
fn a_base_axis_takes_the_setups_external_pulses() {
    let job = "/JOB\r\n//NAME T\r\n//POS\r\n///NPOS 1,1,0,0,0,0\r\n///POSTYPE PULSE\r\n///PULSE\r\nC00000=1000,2000,3000,0,-4500,500\r\nBC00000=150000\r\n//INST\r\n///ATTR SC,RW\r\n///GROUP1 RB1,BS1\r\n'stiffid: external_pulses = 100\r\nNOP\r\nMOVJ C00000 BC00000 VJ=10.00\r\nEND\r\n";
    let with_external = |external: Vec<f64>| Pulses {
        per_deg: PER_DEG,
        external,
    };
    let (same, other, none) = (
        with_external(vec![100.0]),
        with_external(vec![1000.0]),
        with_external(Vec::new()),
    );
    for p in [&same, &none] {
        let read = parse_in(job, Dialect::Inform, &with(p)).unwrap();
        assert_eq!(read.targets[0].external, vec![Some(1500.0)]);
    }
    let (line, message) = refused(parse_in(job, Dialect::Inform, &with(&other)));
    assert_eq!(line, 12);
    assert!(
        message.contains(
            "external_pulses = 100 contradicts the setup's [controller] external_pulses = [1000]"
        ),
        "{message}"
    );
    let bare = job.replace("'stiffid: external_pulses = 100\r\n", "");
    let read = parse_in(&bare, Dialect::Inform, &with(&other)).unwrap();
    assert_eq!(read.targets[0].external, vec![Some(150.0)]);
    let (line, message) = refused(parse_in(&bare, Dialect::Inform, &with(&none)));
    assert_eq!(line, 13);
    assert!(
        message.contains("[controller] external_pulses"),
        "{message}"
    );
}

/// A job whose motions move the station alone (`MOVJ EC00000`, no robot position `C`) is refused
/// saying so, on the motion's line, not as a position of another form.
#[test]
fn a_station_only_job_is_refused_saying_what_it_is() {
    let job = "/JOB\r\n//NAME T\r\n//POS\r\n///NPOS 0,0,1,0,0,0\r\n///POSTYPE PULSE\r\n///PULSE\r\nEC00000=1500\r\n//INST\r\n///ATTR SC,RW\r\n///GROUP1 ST1\r\nNOP\r\nMOVJ EC00000 VJ=10.00\r\nEND\r\n";
    let p = Pulses {
        per_deg: PER_DEG,
        external: vec![100.0],
    };
    let (line, message) = refused(parse_in(job, Dialect::Inform, &with(&p)));
    assert_eq!(line, 10, "{message}");
    assert!(
        message.contains("///GROUP1 ST1: a job of ST1 alone, no robot (RB)"),
        "{message}"
    );
    // In a job of the robot, a motion of the station alone is refused on its line.
    let robot = job.replace("GROUP1 ST1", "GROUP1 RB1\r\n///GROUP2 ST1");
    let (line, message) = refused(parse_in(&robot, Dialect::Inform, &with(&p)));
    assert_eq!(line, 13, "{message}");
    assert!(
        message.contains("the station alone, without the robot's position C"),
        "{message}"
    );
    // A group line among the instructions: which groups the job moves is not certain.
    let late = robot.replace("NOP\r\n", "NOP\r\n///GROUP3 ST2\r\n");
    let (line, message) = refused(parse_in(&late, Dialect::Inform, &with(&p)));
    assert_eq!(line, 13, "{message}");
    assert!(
        message.contains("///GROUP3 ST2: a control group line after an instruction (line 12)"),
        "{message}"
    );
}
