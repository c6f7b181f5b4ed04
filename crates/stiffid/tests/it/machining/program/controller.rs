//! The least a controller language gives: a test-only language, laid out as Stäubli VAL3's
//! files are (a program `.pgx` and its data `.dtx`; its names, limits and words are this test's
//! own, not the controller's), implementing `program::Controller` with its required items only
//! (its descriptor, its configuration data's type, `read`, `rotation`, `pose_numbers`), and
//! everything else from the trait's defaults. In the library it would take its folder
//! `program/val3/` and one registry line, `/// Stäubli VAL3 (.pgx, .dtx).` then
//! `Val3 => val3::Val3,`.

use nalgebra::{UnitQuaternion, Vector3, Vector6};
use stiffid::internal::machining::program::cartesian::flags::{ConfigurationData, Posture};
use stiffid::internal::machining::program::{
    AxisNames, BoundComment, Controller, Descriptor, DynController, FileName, NameRules, Read,
};
use stiffid::internal::robot::configuration::Configuration;
use stiffid::{Error, Result};

/// The test's language.
struct Val3;

impl Controller for Val3 {
    type Flags = Posture;
    const LANGUAGE: &'static Descriptor = &Descriptor {
        key: "val3",
        title: "Staubli VAL3",
        extensions: &["pgx", "dtx"],
        data_files: &[(
            "dtx",
            "a VAL3 program is written to a .pgx; its .dtx holds data",
        )],
        motions: "movej or movel to a jointRx",
        joint_forms: "jointRx",
        part_forms: None,
        external_axes: AxisNames::Numbered("ext"),
        unused_axis: "",
        zero_is_no_axis: false,
        names: NameRules {
            declared_by: Some("<Program name="),
            file: FileName::Stem,
            max_length: 15,
            default_length: 12,
            reserved: &["start", "stop"],
        },
        bound_comment: BoundComment::EndOfLine {
            marker: '/',
            statement: None,
        },
        motion_words: &["movej(", "movel("],
        frame_numbers: (0, 0),
        axis_3_from_horizontal: false,
    };

    /// Refuses every program naming its first line: the test reads none.
    fn read(&self, _text: &str) -> Result<Read> {
        Err(Error::Program {
            line: 1,
            message: "the test's language reads no program".into(),
        })
    }
    /// A rotation vector, rad, after the position.
    fn rotation(&self, n: &[f64]) -> UnitQuaternion<f64> {
        UnitQuaternion::from_scaled_axis(Vector3::new(n[3], n[4], n[5]))
    }
    fn pose_numbers(&self, p: &Vector3<f64>, r: &UnitQuaternion<f64>) -> Vec<f64> {
        let v = r.scaled_axis();
        vec![p.x, p.y, p.z, v.x, v.y, v.z]
    }
}

#[test]
fn a_language_with_only_the_required_items_has_every_method() {
    let c: &dyn DynController = &Val3;
    assert_eq!((c.key(), c.title()), ("val3", "Staubli VAL3"));
    assert_eq!(c.extensions(), ["pgx", "dtx"]);
    assert!(c.refuses_output("dtx").unwrap().contains(".pgx"));
    assert_eq!(c.refuses_output("pgx"), None);
    assert_eq!(
        (c.motions(), c.joint_forms(), c.part_forms()),
        ("movej or movel to a jointRx", "jointRx", None)
    );
    assert_eq!(
        (c.external_axis(0), c.external_axis(2)),
        ("ext1".into(), "ext3".into())
    );
    assert_eq!((c.unused_axis(), c.zero_is_no_axis()), ("", false));
    assert_eq!(c.program_name("Cut_c"), Some("Cut_c".into()));
    assert_eq!((c.max_name_length(), c.default_name_length()), (15, 12));
    assert_eq!(c.reserved_words(), ["start", "stop"]);
    let line = "<Program name=\"cut\">";
    assert_eq!(c.declares_name(line), Some("<Program name=".len()));
    assert_eq!(c.declares_name("movej(p1)"), None);
    assert_eq!(
        c.motion_lines("begin\n  movej(j1)\n  movel(p2)\nend\n"),
        [2, 3]
    );
    assert!(c.generator().is_none());
    let e = c.read("begin\nend\n").unwrap_err().to_string();
    assert!(e.contains("line 1"), "{e}");
    // Its poses: the numbers it writes read back to the rotation.
    let r = UnitQuaternion::from_euler_angles(0.1, -0.2, 0.3);
    let n = c.pose_numbers(&Vector3::new(1.0, 2.0, 3.0), &r);
    assert!(c.rotation(&n).angle_to(&r) < 1e-12);
    // Its configuration data: the posture's shoulder, elbow and wrist.
    let robot = stiffid::internal::robot::presets::get("fanuc-r2000ic-165f").unwrap();
    let q = Vector6::new(-23.2, 3.9, -48.1, 0.0, -41.9, 23.2).map(f64::to_radians);
    let arm = Configuration::of(&robot, &q);
    assert_eq!(c.flags(&arm).branch(), (false, false, true));
    assert_eq!(c.flags_name(), <Posture as ConfigurationData>::NAME);
}

/// The items of `pub trait <name>` in `source` that have no default: `(methods, others)`.
fn required(source: &str, name: &str) -> (Vec<String>, Vec<String>) {
    let code: String = (source.lines())
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n");
    let start = code.find(&format!("pub trait {name}:")).expect("the trait");
    let body = &code[start + code[start..].find('{').unwrap() + 1..];
    let (mut methods, mut others) = (Vec::new(), Vec::new());
    let (mut depth, mut item) = (0usize, String::new());
    for ch in body.chars() {
        match ch {
            '{' => depth += 1,
            '}' if depth == 0 => break,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    item.clear();
                }
            }
            ';' if depth == 0 => {
                let it = item.split_whitespace().collect::<Vec<_>>().join(" ");
                if it.starts_with("fn ") {
                    methods.push(it);
                } else if it.starts_with("type ") || it.starts_with("const ") {
                    others.push(it);
                }
                item.clear();
            }
            c if depth == 0 => item.push(c),
            _ => {}
        }
    }
    (methods, others)
}

#[test]
fn the_controller_trait_requires_at_most_ten_methods() {
    let source = include_str!("../../../../../stiffid-machining/src/program/controller.rs");
    let (methods, others) = required(source, "Controller");
    // The test's language implements exactly these (it compiles with nothing else).
    let names: Vec<&str> = (methods.iter())
        .map(|m| m[3..].split('(').next().unwrap())
        .collect();
    assert_eq!(names, ["read", "rotation", "pose_numbers"], "{methods:?}");
    assert!(methods.len() <= 10);
    assert_eq!(others.len(), 2, "{others:?}");
    assert!(others[0].starts_with("type Flags") && others[1].starts_with("const LANGUAGE"));
}

#[test]
fn the_generator_trait_requires_the_writing_and_its_data() {
    let source = include_str!("../../../../../stiffid-machining/src/program/controller.rs");
    let (methods, others) = required(source, "Generator");
    let names: Vec<&str> = (methods.iter())
        .map(|m| m[3..].split('(').next().unwrap())
        .collect();
    assert_eq!(
        names,
        ["header", "body", "calls", "wrap", "writing"],
        "{methods:?}"
    );
    assert!(others.is_empty(), "{others:?}");
}

/// Each language's generator as its data say, through the trait's defaults: the most lines of a
/// file, the routines' prefix, whether the tool's mass is stated, Cartesian targets, pulses, the
/// arcs with Cartesian and joint targets, the external axes of each role and where they are
/// written (each from its controller's manual, as the language's `WRITING` says).
#[test]
fn each_generator_reads_its_writing() {
    use stiffid::internal::machining::program::generate::arcs::Form;
    use stiffid::internal::machining::program::generate::Targets;
    use stiffid::internal::machining::program::Dialect;
    use stiffid::internal::robot::external::Role;
    type Row = (
        Dialect,
        Option<usize>,
        &'static str,
        [bool; 3],
        [Option<Form>; 2],
        (usize, &'static str),
        (usize, &'static str),
    );
    let via = Some(Form::ViaEnd);
    let rows: [Row; 4] = [
        (
            Dialect::Krl,
            None,
            "",
            [false, true, false],
            [via, None],
            (6, "E1 to E6"),
            (6, "E1 to E6"),
        ),
        (
            Dialect::Rapid,
            None,
            "r",
            [true, true, false],
            [via, None],
            (6, "eax_a to eax_f"),
            (6, "eax_a to eax_f"),
        ),
        (
            Dialect::FanucLs,
            Some(9999 - 9),
            "",
            [false, true, false],
            [via, None],
            (3, "group 1's extended axes E1 to E3"),
            (6, "group 2's J1 to J6"),
        ),
        (
            Dialect::Inform,
            Some(100_000),
            "",
            [false, false, true],
            [Some(Form::StartViaEnd); 2],
            (3, "a base axis group BC of 3 axes"),
            (6, "a station group EC of 6 axes"),
        ),
    ];
    for (dialect, lines, prefix, [mass, cartesian, pulses], arcs, carrier, positioner) in rows {
        let g = dialect.controller().generator().expect("a generator");
        assert_eq!(g.lines_per_file(), lines, "{dialect:?}");
        assert_eq!(g.routine_prefix(), prefix, "{dialect:?}");
        for targets in Targets::ALL {
            assert_eq!(g.needs_mass(targets), mass, "{dialect:?}");
        }
        assert_eq!(
            (g.writes_cartesian(), g.needs_pulses()),
            (cartesian, pulses),
            "{dialect:?}"
        );
        assert_eq!(
            [g.circular(Targets::Cartesian), g.circular(Targets::Joint)],
            arcs,
            "{dialect:?}"
        );
        for (role, (most, form)) in [(Role::Carrier, carrier), (Role::Positioner, positioner)] {
            assert_eq!(
                (g.most_external(role), g.external_form(role)),
                (most, form),
                "{dialect:?}"
            );
        }
        assert!(g.process_form().is_some(), "{dialect:?}");
    }
}
