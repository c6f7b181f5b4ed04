//! A KRL program with its controller's backup: the module's `.dat` and `$config.dat`'s tool and
//! base tables read from it; a table entry the setup gives otherwise refused naming both.

use nalgebra::{Isometry3, Vector3};
use stiffid::internal::machining::program::{self, cartesian::Frame, Dialect};
use stiffid::internal::setup::NumberedFrames;
use stiffid::Error;

const SRC: &str = "DEF cell( )\nFDAT_ACT = FP1\nBAS(#PTP_PARAMS, 100)\nPTP XP1\nEND\n";
const DAT: &str = "DEFDAT cell\nDECL FDAT FP1={TOOL_NO 1,BASE_NO 2,IPO_FRAME #BASE}\nDECL E6POS XP1={X 10,Y 20,Z 30,A 0,B 0,C 0,S 2,T 0}\nENDDAT\n";
const CONFIG: &str = "DEFDAT $CONFIG PUBLIC\n;tables\nTOOL_DATA[1]={X 0.0,Y 0.0,Z 250.0,A 0.0,B 0.0,C 0.0}\nBASE_DATA[2]={X 680.0,Y 1000.0,Z 0.0,A 90.0,B 0.0,C 0.0}\nENDDAT\n";

fn backup() -> Vec<(String, String)> {
    vec![
        ("KRC/R1/Program/CELL.DAT".to_string(), DAT.to_string()),
        ("KRC/R1/System/$config.dat".to_string(), CONFIG.to_string()),
    ]
}

#[test]
fn the_module_dat_and_config_tables_come_from_the_backup() {
    // Alone: the point is in no file given.
    assert!(matches!(
        program::parse(SRC, Dialect::Krl),
        Err(Error::Program { line: 4, .. })
    ));
    let files = backup();
    let context = program::Context::default().with_backup(&files);
    let p = program::parse_in(SRC, Dialect::Krl, &context).unwrap();
    let c = p.targets[0].cartesian.as_deref().unwrap();
    assert!((c.position_mm - Vector3::new(10.0, 20.0, 30.0)).norm() < 1e-12);
    // TOOL_DATA[1] and BASE_DATA[2] of $config.dat, its lines 3 and 4.
    match (&c.tool, &c.frame) {
        (Frame::Stated(3, t), Frame::Stated(4, b)) => {
            assert!((t.translation.vector - Vector3::new(0.0, 0.0, 0.25)).norm() < 1e-12);
            assert!((b.translation.vector - Vector3::new(0.68, 1.0, 0.0)).norm() < 1e-12);
            assert!((b.rotation.angle() - 90f64.to_radians()).abs() < 1e-12);
        }
        other => panic!("{other:?}"),
    }
    // The setup's table agreeing: read; disagreeing: refused naming both.
    let agree =
        NumberedFrames::new("tools", &[(1, Isometry3::translation(0.0, 0.0, 0.25))]).unwrap();
    let other =
        NumberedFrames::new("tools", &[(1, Isometry3::translation(0.0, 0.0, 0.3))]).unwrap();
    let with = |tools| program::Context {
        tool: Some((Isometry3::translation(0.0, 0.0, 0.25), tools)),
        ..context
    };
    assert!(program::parse_in(SRC, Dialect::Krl, &with(&agree)).is_ok());
    match program::parse_in(SRC, Dialect::Krl, &with(&other)) {
        Err(Error::InvalidField { field, message }) => {
            assert_eq!(field, "controller.tools");
            assert!(
                message.contains("$config.dat line 3") && message.contains("TOOL_DATA[1]"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}

/// A milling program whose cut starts at a point of `$config.dat` (a global `E6POS`), with its
/// module's `.dat`.
const MILL_SRC: &str = "DEF mill( )\n$TOOL = {X 0, Y 0, Z 250, A 0, B 0, C 0}\n$BASE = {X 2000, Y 0, Z 550, A 0, B 0, C 0}\nPTP XP1\n$VEL.CP = 0.03\nLIN XCUT C_DIS\nLIN XP2 C_DIS\nLIN XSAFE\nEND\n";
const MILL_DAT: &str = "DEFDAT mill\nDECL E6POS XP1={X 0, Y -100, Z 5, A 0, B 0, C 180, S 'B010', T 'B101001'}\nDECL E6POS XP2={X 60, Y -100, Z -4, A 0, B 0, C 180, S 'B010', T 'B101001'}\nENDDAT\n";
const MILL_CONFIG: &str = "DEFDAT $CONFIG PUBLIC\n;FOLD USER GLOBALS\nDECL GLOBAL E6POS XCUT={X 0, Y -100, Z -4, A 0, B 0, C 180, S 'B010', T 'B101001', E1 0}\nDECL E6POS XSAFE={X 60, Y -100, Z -4, A 0, B 0, C 180, S 'B010', T 'B101001'}\n;ENDFOLD\nENDDAT\n";

/// Compensates [`MILL_SRC`] with its `.dat` and the backup `files` on the KR 210 milling
/// setup: the program and its `.dat`.
fn mill(files: &[(String, String)]) -> stiffid::Result<(String, Option<String>)> {
    let p = run((MILL_SRC, Some(MILL_DAT)), files)?;
    Ok((p.text, p.data))
}

/// Compensates the program `src` with its `.dat` and the backup `files` on the KR 210 milling
/// setup, written as `mill_c.src`.
pub(super) fn run(
    program: (&str, Option<&str>),
    files: &[(String, String)],
) -> stiffid::Result<stiffid::app::compensate::ProgramReport> {
    run_with(&|setup| setup.to_string(), program, files)
}

/// [`run`] on the milling setup as `edit` changes its text.
pub(super) fn run_with(
    edit: &dyn Fn(&str) -> String,
    (src, dat): (&str, Option<&str>),
    files: &[(String, String)],
) -> stiffid::Result<stiffid::app::compensate::ProgramReport> {
    use stiffid::app::compensate::{self, Input};
    use stiffid::internal::machining::{compensate::Options, Language};
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/milling");
    let text = edit(&std::fs::read_to_string(format!("{dir}/kuka-milling.toml")).unwrap());
    let setup = stiffid::internal::setup::parse(&text, "kuka-milling.toml", |name, _| {
        stiffid::internal::robot::presets::get(name)
    })
    .unwrap();
    let stiffness = std::fs::read_to_string(format!("{dir}/kuka-stiffness.json")).unwrap();
    let compliance = (stiffid::internal::io::stiffness::parse(&stiffness).unwrap())
        .compliance(setup.model())
        .unwrap();
    let process = std::fs::read_to_string(format!("{dir}/aluminium.toml")).unwrap();
    let process = stiffid::internal::machining::process::file::parse(&process, "p.toml").unwrap();
    let request = compensate::Request {
        names: Default::default(),
        setup: &setup,
        compliance,
        input: Input::Program {
            encoding: Default::default(),
            reading: program::Reading {
                backup: files,
                leave_refused: false,
            },
            name: "mill.src".into(),
            text: src,
            data: dat,
            language: Language::Robot(Dialect::Krl),
            process_name: "aluminium.toml".into(),
            process,
            chord_tolerance: 1e-5,
            output: Language::Robot(Dialect::Krl),
            out_name: "mill_c.src".into(),
            settings: Default::default(),
        },
        options: Options::for_setup(&setup),
    };
    let report = compensate::run::<stiffid::Error, _>(request, |_, _, _, _| Ok(()))?;
    Ok(report.report.program.unwrap())
}

/// The members `X` to `C` of the `E6POS` declared as `name` in `text`.
pub(super) fn members(text: &str, name: &str) -> Vec<f64> {
    let l = text
        .lines()
        .find(|l| l.contains(&format!(" {name}={{")))
        .unwrap();
    let end = (l.find(", S").or_else(|| l.find(",S"))).unwrap_or(l.len() - 1);
    let inner = &l[l.find('{').unwrap() + 1..end];
    inner
        .split(',')
        .map(|m| m.split_whitespace().nth(1).unwrap().parse().unwrap())
        .collect()
}

#[test]
fn points_of_config_dat_are_read_from_the_backup_and_written_into_the_module_dat() {
    // Without $config.dat, XCUT is declared nowhere the program gives: refused on its line.
    match mill(&[]) {
        Err(Error::Input { error, .. }) => match *error {
            Error::Program { line, message } => {
                assert_eq!(line, 6);
                assert!(
                    message.contains("XCUT") && message.contains("--backup"),
                    "{message}"
                );
            }
            other => panic!("{other:?}"),
        },
        other => panic!("{other:?}"),
    }
    let files = vec![(
        "KRC/R1/System/$config.dat".to_string(),
        MILL_CONFIG.to_string(),
    )];
    let (src, dat) = mill(&files).unwrap();
    let dat = dat.unwrap();
    // The .src as read; the global points compensated as local declarations of the module's
    // .dat, on the lines after DEFDAT, GLOBAL dropped, in the order they are visited.
    let unbound: Vec<&str> = src
        .lines()
        .map(|l| l.split(" ; bound").next().unwrap())
        .collect();
    assert_eq!(
        unbound.join("\n") + "\n",
        MILL_SRC.replace("DEF mill( )", "DEF mill_c( )")
    );
    let lines: Vec<&str> = dat.lines().collect();
    assert_eq!(lines[0], "DEFDAT mill_c");
    assert!(lines[1].starts_with("DECL E6POS XCUT={X "), "{dat}");
    assert!(lines[1].contains(", S 'B010', T 'B101001', E1 0"), "{dat}");
    assert!(lines[2].starts_with("DECL E6POS XSAFE={X "), "{dat}");
    assert_eq!(lines.len(), MILL_DAT.lines().count() + 2);
    // Compensated: moved by the deflection under the cut and the spindle, not by more than 5 mm.
    for (name, read) in [
        ("XCUT", [0.0, -100.0, -4.0]),
        ("XSAFE", [60.0, -100.0, -4.0]),
    ] {
        let m = members(&dat, name);
        let moved = (0..3).map(|k| (m[k] - read[k]).powi(2)).sum::<f64>().sqrt();
        assert!(moved > 1e-3 && moved < 5.0, "{name}: {moved} mm");
    }
    // The module's own points written in place.
    assert_ne!(
        members(&dat, "XP2"),
        vec![60.0, -100.0, -4.0, 0.0, 0.0, 180.0]
    );
}

#[test]
fn global_points_of_another_modules_public_data_list_are_read_its_local_ones_not() {
    let points = "&ACCESS RV\nDEFDAT  XPOINTS PUBLIC\nDECL GLOBAL E6AXIS XAPP={A1 10,A2 -80,A3 100,A4 0,A5 30,A6 0}\nDECL E6AXIS XLOCAL={A1 20,A2 -80,A3 100,A4 0,A5 30,A6 0}\nENDDAT\n";
    let private =
        "DEFDAT OTHER\nDECL GLOBAL E6AXIS XOTHER={A1 30,A2 -80,A3 100,A4 0,A5 30,A6 0}\nENDDAT\n";
    let files = vec![
        (
            "KRC/R1/Program/Dat/xPoints.dat".to_string(),
            points.to_string(),
        ),
        ("KRC/R1/Program/other.dat".to_string(), private.to_string()),
    ];
    let context = program::Context::default().with_backup(&files);
    let src = |name: &str| format!("DEF move( )\nPTP {name}\nEND\n");
    let p = program::parse_in(&src("XAPP"), Dialect::Krl, &context).unwrap();
    assert_eq!(p.targets[0].q_deg, [10.0, -80.0, 100.0, 0.0, 30.0, 0.0]);
    // A declaration without GLOBAL is its module's; a data list without PUBLIC is its module's.
    for name in ["XLOCAL", "XOTHER"] {
        match program::parse_in(&src(name), Dialect::Krl, &context) {
            Err(Error::Program { line: 2, message }) => {
                assert!(
                    message.contains(name) && message.contains("PUBLIC"),
                    "{message}"
                )
            }
            other => panic!("{name}: {other:?}"),
        }
    }
}

/// A point two public data lists of the backup declare GLOBAL is refused where a motion uses it,
/// naming both (the controller refuses the name declared twice; it was the first list's, exit
/// 0); the program's own declaration of it hides both.
#[test]
fn a_global_point_two_public_lists_declare_is_refused_naming_both() {
    let list = |name: &str, a1: u32| {
        format!("DEFDAT {name} PUBLIC\nDECL GLOBAL E6AXIS XAPP={{A1 {a1},A2 -80,A3 100,A4 0,A5 30,A6 0}}\nENDDAT\n")
    };
    let files = vec![
        ("KRC/R1/Program/a.dat".to_string(), list("A", 10)),
        ("KRC/R1/Program/b.dat".to_string(), list("B", 12)),
    ];
    let context = program::Context::default().with_backup(&files);
    match program::parse_in("DEF move( )\nPTP XAPP\nEND\n", Dialect::Krl, &context) {
        Err(Error::Program { line: 2, message }) => assert!(
            message.contains("GLOBAL twice")
                && message.contains("a.dat")
                && message.contains("b.dat"),
            "{message}"
        ),
        other => panic!("{other:?}"),
    }
    let own =
        "DEF move( )\nDECL E6AXIS XAPP={A1 20,A2 -80,A3 100,A4 0,A5 30,A6 0}\nPTP XAPP\nEND\n";
    let p = program::parse_in(own, Dialect::Krl, &context).unwrap();
    assert_eq!(p.targets[0].q_deg[0], 20.0);
}

/// A KSS backup's folder with a module that is no text (a KR C4 milling cell's `HoldersPos.src`
/// holds a control byte, 0x05, in a comment): it is passed over and the folder's other files read;
/// the same file given by name is refused naming it.
#[test]
fn a_folder_module_that_is_no_text_is_passed_over() {
    let dir = std::env::temp_dir().join(format!("stiffid-krl-backup-{}", std::process::id()));
    let program = dir.join("R1/Program");
    std::fs::create_dir_all(&program).unwrap();
    std::fs::write(program.join("cell.dat"), DAT).unwrap();
    std::fs::write(
        program.join("holders.src"),
        b"DEF holders( )\n; lapy\x05\nEND\n",
    )
    .unwrap();
    let read = |p: &std::path::Path| {
        std::fs::read(p).map_err(|e| Error::Parse {
            source_name: p.display().to_string(),
            message: e.to_string(),
        })
    };
    let files = program::read_backup(std::slice::from_ref(&dir), Dialect::Krl, read, |e| e);
    let names: Vec<String> = files.unwrap().into_iter().map(|(n, _)| n).collect();
    assert_eq!(names.len(), 1);
    assert!(names[0].ends_with("cell.dat"), "{names:?}");
    let named = program::read_backup(&[program.join("holders.src")], Dialect::Krl, read, |e| e);
    match named {
        Err(Error::Parse {
            source_name,
            message,
        }) => {
            assert!(source_name.ends_with("holders.src"), "{source_name}");
            assert!(message.contains("control byte 0x05"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
