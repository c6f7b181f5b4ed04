//! Where a new controller plugs in: one row per controller language (`program::Dialect::ALL`),
//! with a small program and what it must read and write. A new controller adds its folder under
//! `program/` implementing `program::Controller`, its line in the registry of `Dialect`, and a
//! row here (docs/ARCHITECTURE.md, "Adding a controller"); `machining::program::controller`
//! implements the trait for a language with only its required items.

use nalgebra::{Isometry3, Vector3, Vector6};
use stiffid::app::compensate::certify;
use stiffid::internal::machining::program::generate::{
    check_name, generate, Move, Plan, Settings, Target, Targets, Tool,
};
use stiffid::internal::machining::program::{self, rename, Dialect};
use stiffid::internal::machining::Language;
use stiffid::internal::robot::configuration::Configuration;
use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis};
use stiffid::internal::setup::Pulses;

/// One controller and what its small program must give.
struct Row {
    dialect: Dialect,
    /// The name in documents and options, and for people.
    key: &'static str,
    title: &'static str,
    /// The extensions read, the first the one written.
    extensions: &'static [&'static str],
    /// A program with one joint target at axis angles 1, 2, ..., 6 deg.
    program: &'static str,
    /// Axis 3 as the program writes it, then as written back at 3.5 deg (every other byte kept).
    axis_3: (&'static str, &'static str),
    /// The name declaration after renaming the program for a file `cut_c` (`None`: the file
    /// name is not the program's, the text stays).
    renamed: Option<&'static str>,
    /// The text a bound of 0.0123 mm at 95% adds on the motion's target.
    bound: &'static str,
    /// Whether new programs are written in the language from G-code.
    generates: bool,
    /// A generated joint target at 1..6 deg with a track at 1500 mm and a turntable at 45 deg:
    /// the text of the external values (each language's own form).
    external: Option<&'static str>,
}

fn rows() -> [Row; 4] {
    [
        Row {
            dialect: Dialect::Krl,
            key: "krl",
            title: "KUKA KRL",
            extensions: &["src", "dat"],
            program: "DEF cut( )\nPTP {A1 1, A2 2, A3 3, A4 4, A5 5, A6 6}\nEND\n",
            axis_3: ("A3 3,", "A3 3.500000000,"),
            renamed: Some("DEF cut_c( )"),
            bound: "A6 6} ; bound 0.0123 mm at 95%\n",
            generates: true,
            external: Some("A6 6.000000000, E1 1500.000000000, E2 45.000000000}"),
        },
        Row {
            dialect: Dialect::Rapid,
            key: "rapid",
            title: "ABB RAPID",
            extensions: &["mod", "modx", "prg"],
            program: "MODULE Cut\n  PROC main()\n    MoveAbsJ [[1,2,3,4,5,6],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, fine, tool0;\n  ENDPROC\nENDMODULE\n",
            axis_3: ("[[1,2,3,4", "[[1,2,3.500000000,4"),
            renamed: None,
            bound: "tool0; ! bound 0.0123 mm at 95%\n",
            generates: true,
            external: Some("[[1.000000000,2.000000000,3.000000000,4.000000000,5.000000000,6.000000000],[1500.000000000,45.000000000,9E9,9E9,9E9,9E9]]"),
        },
        Row {
            dialect: Dialect::FanucLs,
            key: "ls",
            title: "FANUC LS",
            extensions: &["ls"],
            program: "/PROG  CUT\n/ATTR\nOWNER\t\t= MNEDITOR;\n/MN\n   1:J P[1] 100% FINE    ;\n/POS\nP[1]{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1=     1.000 deg,\tJ2=     2.000 deg,\tJ3=     3.000 deg,\n\tJ4=     4.000 deg,\tJ5=     5.000 deg,\tJ6=     6.000 deg\n};\n/END\n",
            axis_3: ("J3=     3.000 deg", "J3=     3.500000000 deg"),
            renamed: Some("/PROG  CUT_C\n"),
            bound: "P[1:\"0.0123 mm\"]{\n",
            generates: true,
            external: Some("J6= 6.000000000 deg,\n\tE1= 1500.000000000 mm\n   GP2:\n\tUF : 0, UT : 1,\n\tJ1= 45.000000000 deg\n};"),
        },
        Row {
            dialect: Dialect::Inform,
            key: "inform",
            title: "Yaskawa INFORM",
            extensions: &["jbi"],
            program: "/JOB\r\n//NAME CUT\r\n//POS\r\n///NPOS 1,0,0,0,0,0\r\n///TOOL 0\r\n///POSTYPE PULSE\r\n///PULSE\r\nC00000=100,200,300,400,500,600\r\n//INST\r\n///DATE 2026/11/25 12:00\r\n///ATTR SC,RW\r\n///GROUP1 RB1\r\n'stiffid: pulses_per_deg = 100 100 100 100 100 100\r\nNOP\r\nMOVJ C00000 VJ=50.00\r\nEND\r\n",
            axis_3: ("=100,200,300,", "=100,200,350,"),
            renamed: Some("//NAME CUT_C\r\n"),
            bound: "'bound 0.0123 mm at 95%\r\nMOVJ C00000",
            generates: true,
            external: Some("C00000=100,200,300,400,500,600\r\n///POSTYPE PULSE\r\n///PULSE\r\nBC00000=150000\r\n///POSTYPE PULSE\r\n///PULSE\r\nEC00000=4500\r\n"),
        },
    ]
}

#[test]
fn every_controller_has_a_row() {
    let listed: Vec<Dialect> = rows().iter().map(|r| r.dialect).collect();
    assert_eq!(listed, Dialect::ALL);
}

#[test]
fn each_controller_names_its_language_and_files() {
    for row in rows() {
        let (d, c) = (row.dialect, row.dialect.controller());
        assert_eq!((c.key(), c.title()), (row.key, row.title), "{d:?}");
        assert_eq!(c.extensions(), row.extensions, "{d:?}");
        for ext in row.extensions {
            let upper = ext.to_ascii_uppercase();
            for name in [format!("cut.{ext}"), format!("CUT.{upper}")] {
                assert_eq!(
                    Language::of_file(&name).unwrap(),
                    Language::Robot(d),
                    "{name}"
                );
            }
        }
        let refused = Language::of_file("cut.txt").unwrap_err().to_string();
        assert!(refused.contains(&format!("({})", row.title)), "{refused}");
        for ext in row.extensions {
            assert!(refused.contains(&format!(".{ext}")), "{ext}: {refused}");
        }
        let language = Language::Robot(d);
        assert_eq!(language.name(), row.key);
        assert_eq!(language.extension(), row.extensions[0]);
    }
}

#[test]
fn each_controller_reads_its_target_and_writes_it_back() {
    for row in rows() {
        let d = row.dialect;
        let p = program::parse(row.program, d).unwrap();
        assert_eq!(p.targets.len(), 1, "{d:?}");
        assert_eq!(p.targets[0].q_deg, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0], "{d:?}");
        let q = p.targets[0].q_deg;
        assert_eq!(p.write(&[q]).unwrap(), row.program, "{d:?}");
        let moved = [[q[0], q[1], 3.5, q[3], q[4], q[5]]];
        let (read, written) = row.axis_3;
        assert_eq!(row.program.matches(read).count(), 1, "{d:?}");
        assert_eq!(
            p.write(&moved).unwrap(),
            row.program.replace(read, written),
            "{d:?}"
        );
    }
}

/// A program beginning with a byte order mark (a file saved as UTF-8 with one) is renamed as
/// without it, the mark kept: the name it declares on its first line (KRL's `DEF`, LS's
/// `/PROG`, a `.dat`'s `DEFDAT`) follows the file's.
#[test]
fn a_program_with_a_byte_order_mark_is_renamed_as_without_it() {
    for row in rows() {
        let (d, c) = (row.dialect, row.dialect.controller());
        let name = c.program_name("cut_c");
        let name = name.as_deref().unwrap_or("cut_c");
        let marked = format!("\u{feff}{}", row.program);
        assert_eq!(
            rename::renamed(&marked, d, name),
            format!("\u{feff}{}", rename::renamed(row.program, d, name)),
            "{d:?}"
        );
    }
    let dat = "\u{feff}DEFDAT cut\nENDDAT\n";
    assert_eq!(
        rename::renamed_data(dat, "cut_c"),
        "\u{feff}DEFDAT cut_c\nENDDAT\n"
    );
}

#[test]
fn each_controller_renames_and_certifies_its_program() {
    for row in rows() {
        let (d, c) = (row.dialect, row.dialect.controller());
        let name = c.program_name("cut_c");
        let renamed = rename::renamed(row.program, d, name.as_deref().unwrap_or("cut_c"));
        match row.renamed {
            Some(declared) => assert!(renamed.contains(declared), "{d:?}: {renamed}"),
            None => assert_eq!((name, renamed.as_str()), (None, row.program), "{d:?}"),
        }
        let line = program::parse(row.program, d).unwrap().targets[0].line;
        let certified = certify::at_lines(d, row.program, &[(line, 1.23e-5)], 0.95);
        assert!(certified.contains(row.bound), "{d:?}: {certified}");
        let line = program::parse(&certified, d).unwrap().targets[0].line;
        let again = certify::at_lines(d, &certified, &[(line, 1.23e-5)], 0.95);
        assert_eq!(
            again, certified,
            "{d:?}: a bound replaces the one written before"
        );
    }
}

#[test]
fn each_controller_says_whether_and_how_it_writes_new_programs() {
    for row in rows() {
        let (d, c) = (row.dialect, row.dialect.controller());
        assert_eq!(c.generator().is_some(), row.generates, "{d:?}");
        assert!(c.default_name_length() <= c.max_name_length(), "{d:?}");
        let name = c.program_name("cut").unwrap_or_else(|| "cut".into());
        assert!(
            check_name(d, &name, c.default_name_length()).is_ok(),
            "{d:?}"
        );
        for word in c.reserved_words() {
            assert!(check_name(d, word, 64).is_err(), "{d:?}: {word}");
        }
    }
}

/// A track along x (0 to 6 m) and a turntable about z (-360 to 360 deg).
fn track_and_table() -> ExternalAxes {
    let turn = 360f64.to_radians();
    ExternalAxes::new(vec![
        ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0),
        ExternalAxis::rotary(
            "table",
            Vector3::new(2.5, 0.0, 0.0),
            Vector3::z_axis(),
            -turn,
            turn,
        ),
    ])
    .unwrap()
}

/// A controller's 100 pulses per degree and per mm of every axis, the robot's and the cell's.
fn pulses() -> Pulses {
    Pulses {
        per_deg: [100.0; 6],
        external: vec![100.0; 2],
    }
}

/// A one-target plan in `dialect` with `targets` on the cell `axes` (with the controller's
/// `pulses`, which only INFORM reads).
fn plan<'a>(
    dialect: Dialect,
    targets: Targets,
    target: &'a [Target],
    (axes, pulses): (&'a ExternalAxes, &'a Pulses),
) -> Plan<'a> {
    Plan {
        dialect,
        name: "CUT",
        targets: target,
        moves: &[Move::Rapid],
        tool: Tool {
            frame: Isometry3::translation(0.0, 0.0, 0.3),
            payload: Some((10.0, Vector3::zeros())),
        },
        work: Isometry3::identity(),
        world: Isometry3::identity(),
        external: Some(axes),
        approximation: 1e-5,
        numbers: Default::default(),
        pulses: Some(pulses),
        settings: Settings {
            targets,
            ..Settings::default()
        },
    }
}

#[test]
fn each_generating_controller_writes_the_cells_external_axes_in_its_form() {
    let axes = track_and_table();
    let robot = stiffid::internal::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
    let q = Vector6::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0).map(f64::to_radians);
    let target = [Target {
        q_deg: [1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
        pose: Isometry3::translation(1.0, 0.0, 1.0),
        arm: Configuration::of(&robot, &q),
        external: vec![1500.0, 45.0],
    }];
    let pulses = pulses();
    let cell = (&axes, &pulses);
    for row in rows() {
        let d = row.dialect;
        let written = generate(&plan(d, Targets::Joint, &target, cell));
        let Some(form) = row.external else {
            assert!(written.is_err(), "{d:?}");
            continue;
        };
        let file = written.unwrap().files.remove(0);
        // A KRL program's points, with their external axes, are in its .dat.
        let (text, data) = (&file.text, file.data.as_deref());
        assert!(data.unwrap_or(text).contains(form), "{d:?}: {text}");
        // Read back: the six angles and the two external values.
        // INFORM's pulses are the setup's (the job states none).
        let context = program::Context {
            home_deg: None,
            backup: &[],
            pulses: Some(&pulses),
            tool: None,
            data,
            machine: None,
            ..Default::default()
        };
        let p = program::parse_in(text, d, &context).unwrap();
        assert_eq!(p.axes.len(), 2, "{d:?}: {:?}", p.axes);
        assert_eq!(p.targets[0].q_deg, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0], "{d:?}");
        assert_eq!(p.targets[0].external, [Some(1500.0), Some(45.0)], "{d:?}");
        // A Cartesian target on the positioner needs coordinated motion: refused naming it,
        // where the language writes poses (INFORM writes the axis angles, the same job).
        let cartesian = generate(&plan(d, Targets::Cartesian, &target, cell));
        match d
            .controller()
            .generator()
            .is_some_and(|g| g.writes_cartesian())
        {
            true => {
                let e = cartesian.unwrap_err().to_string();
                assert!(e.contains("positioner axis table"), "{d:?}: {e}");
            }
            false => assert_eq!(&cartesian.unwrap().files[0].text, text, "{d:?}"),
        }
        // A target without the cell's values: refused.
        let bare = [Target {
            external: vec![1500.0],
            ..target[0].clone()
        }];
        let e = generate(&plan(d, Targets::Joint, &bare, cell)).unwrap_err();
        assert!(
            e.to_string()
                .contains("expected 2 finite external axis values"),
            "{d:?}: {e}"
        );
    }
}
