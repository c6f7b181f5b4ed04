//! The tool and base a generated program selects by number
//! (`stiffid_machining::program::generate::numbered`): when the setup's `[controller] tools` and
//! `bases` hold the program's tool and part frame, KRL, LS and INFORM programs select them by
//! number and read back, with those tables, to the targets written.

use super::arcs::robot_targets;
use nalgebra::{Isometry3, Translation3, Vector3, Vector6};
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::{self, Language, Program};
use stiffid::internal::robot::presets;
use stiffid::Setup;
use stiffid_core::setup::Pulses;
use stiffid_machining::program::generate::numbered::Numbers;
use stiffid_machining::program::generate::{generate, Move, Plan, Settings, Target, Tool};
use stiffid_machining::program::{parse_in, Context, Dialect};

const SETUP: &str = include_str!("../../../../../../examples/milling/fanuc-milling.toml");

/// The milling setup whose controller holds a tool 1 (not the setup's), the setup's tool as 3
/// (`tool`: its values) and the part frame as base 2 (`base`, in the controller's world: FANUC's,
/// 670 mm above the setup's base frame, so the part's origin at z 400 mm is at z -270 mm).
pub(super) fn setup(tool: &str, base: &str) -> Setup {
    let text = format!("{SETUP}\n[controller]\ntools = [{{ number = 1, xyz_mm = [0, 0, 100] }}, {{ number = 3, xyz_mm = {tool} }}]\nbases = [{{ number = 2, xyz_mm = {base} }}]\n");
    stiffid::internal::setup::parse(&text, "fanuc-milling.toml", |n, _| presets::get(n)).unwrap()
}

pub(super) fn plan<'a>(
    s: &Setup,
    dialect: Dialect,
    t: &'a [Target],
    m: &'a [Move],
    p: &'a Pulses,
) -> Plan<'a> {
    let tool = Isometry3::from(Translation3::from(s.tool().tcp));
    let c = s.workcell().controller();
    let work = *s.workpiece().unwrap();
    Plan {
        dialect,
        name: "HELD",
        targets: t,
        moves: m,
        tool: Tool {
            frame: tool,
            payload: Some((10.0, Vector3::new(0.0, 0.0, 0.1))),
        },
        work,
        world: s.program_world(),
        external: None,
        approximation: 1e-5,
        numbers: Numbers::of(
            (&c.tools, &c.bases),
            &tool,
            &s.program_world().inv_mul(&work),
            dialect.controller().descriptor().frame_numbers,
        ),
        pulses: Some(p),
        settings: Settings::default(),
    }
}

/// A square of 50 mm at 4 mm depth in the part frame.
pub(super) fn square(s: &Setup) -> (Vec<Target>, Vec<Move>) {
    let points: Vec<Vector3<f64>> = [(0.0, 0.0), (0.05, 0.0), (0.05, 0.05), (0.0, 0.05)]
        .iter()
        .map(|(x, y)| Vector3::new(*x, *y, -0.004))
        .collect();
    let t = robot_targets(s, &points);
    let mut m = vec![Move::Feed(0.02); t.len()];
    m[0] = Move::Rapid;
    (t, m)
}

/// The axis angles of `text`'s targets (a KRL program with its `.dat`, `data`), read by
/// stiffid and resolved on `s`.
fn read_back(
    s: &Setup,
    dialect: Dialect,
    (text, data): (&str, Option<&str>),
    pulses: &Pulses,
) -> Vec<[f64; 6]> {
    let targets = match dialect {
        Dialect::Inform => {
            let c = s.workcell().controller();
            let tool = Isometry3::from(Translation3::from(s.tool().tcp));
            let context = Context {
                home_deg: None,
                backup: &[],
                pulses: Some(pulses),
                tool: Some((tool, &c.tools)),
                data: None,
                machine: None,
                ..Default::default()
            };
            parse_in(text, dialect, &context).unwrap().targets
        }
        _ => {
            let context = Context {
                data,
                ..Context::default()
            };
            let read = machining::read_in(text, Language::Robot(dialect), 1e-4, &context).unwrap();
            let read = machining::resolve(&read, s, None, &Options::for_setup(s)).unwrap();
            let Program::Robot(r) = read.into_owned() else {
                panic!()
            };
            r.targets
        }
    };
    targets.iter().map(|t| t.q_deg).collect()
}

#[test]
fn a_tool_and_base_the_controller_holds_are_selected_by_number_and_read_back() {
    let s = setup("[6.9, 245.3, 319.3]", "[1300, -700, -270]");
    let (t, m) = square(&s);
    let pulses = Pulses {
        per_deg: [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7],
        external: Vec::new(),
    };
    let cases: [(Dialect, &[&str], f64); 3] = [
        (
            Dialect::Krl,
            &["$TOOL = TOOL_DATA[3]\n", "$BASE = BASE_DATA[2]\n"],
            1e-6,
        ),
        (
            Dialect::FanucLs,
            &["  UFRAME_NUM=2 ;\n", "  UTOOL_NUM=3 ;\n", "UF : 2, UT : 3,"],
            1e-6,
        ),
        (
            Dialect::Inform,
            &["///TOOL 3\r\n", "'set tool file 3 to the tool:"],
            1e-3,
        ),
    ];
    for (dialect, forms, within) in cases {
        let file = generate(&plan(&s, dialect, &t, &m, &pulses))
            .unwrap()
            .files
            .remove(0);
        let text = &file.text;
        for form in forms {
            assert!(text.contains(form), "{dialect:?}: {form} in {text}");
        }
        if dialect == Dialect::FanucLs {
            // The corpus tests' independent LS reader: user frame 2, tool frame 3, each
            // position the target's in user frame 2.
            let base = s.program_world() * s.workcell().controller().bases.get(2).unwrap();
            for (r, w) in crate::ls_corpus::independent(text).iter().zip(&t) {
                assert_eq!(r.frames, (2, 3));
                let p = Vector3::new(r.values[0], r.values[1], r.values[2]) * 1e-3;
                let want = base.inverse() * w.pose;
                assert!((p - want.translation.vector).norm() < 1e-11, "{r:?}");
            }
        }
        let back = read_back(&s, dialect, (text, file.data.as_deref()), &pulses);
        assert_eq!(back.len(), t.len(), "{dialect:?}");
        for (b, w) in back.iter().zip(&t) {
            let off = (Vector6::from(*b) - Vector6::from(w.q_deg)).amax();
            assert!(off <= within, "{dialect:?}: {off} deg");
        }
    }
}

#[test]
fn frames_the_controller_does_not_hold_are_stated() {
    // The tool 0.01 mm and the base 0.01 mm off the setup's: not the same frames.
    let s = setup("[6.91, 245.3, 319.3]", "[1300, -700.01, -270]");
    let (t, m) = square(&s);
    let pulses = Pulses {
        per_deg: [1341.25; 6],
        external: Vec::new(),
    };
    let p = plan(&s, Dialect::Krl, &t, &m, &pulses);
    assert_eq!((p.numbers.tool, p.numbers.base), (None, None));
    // Tool numbers 1 and 3 hold other tools.
    assert_eq!(p.numbers.held_tools, 0b101);
    let krl = generate(&p).unwrap().files.remove(0).text;
    assert!(
        krl.contains("$TOOL = {X 6.9, Y 245.3, Z 319.3, A 0, B 0, C 0}\n"),
        "{krl}"
    );
    assert!(
        krl.contains("$BASE = {X 1300, Y -700, Z -270, A 0, B 0, C 0}\n"),
        "{krl}"
    );
    let ls = generate(&plan(&s, Dialect::FanucLs, &t, &m, &pulses))
        .unwrap()
        .files
        .remove(0)
        .text;
    // Tool frame 1 holds another tool: the lowest free one, 2, is set to the setup's.
    assert!(
        ls.contains("  UFRAME_NUM=0 ;\n")
            && ls.contains("UTOOL_NUM=2 ;")
            && ls.contains("UF : 0, UT : 2,"),
        "{ls}"
    );
    // A table's number beyond the controller's (KSS holds TOOL_DATA[1..16], FANUC UTOOL[1..10]):
    // the frame stated, not selected.
    let text = format!(
        "{SETUP}\n[controller]\ntools = [{{ number = 20, xyz_mm = [6.9, 245.3, 319.3] }}]\n"
    );
    let high = stiffid::internal::setup::parse(&text, "fanuc-milling.toml", |n, _| presets::get(n))
        .unwrap();
    for (dialect, form) in [
        (Dialect::Krl, "$TOOL = {X 6.9,"),
        (Dialect::FanucLs, "UTOOL_NUM=1 ;"),
    ] {
        let p = plan(&high, dialect, &t, &m, &pulses);
        assert_eq!(p.numbers.tool, None, "{dialect:?}");
        let text = generate(&p).unwrap().files.remove(0).text;
        assert!(
            text.contains(form)
                && !text.contains("TOOL_DATA[20]")
                && !text.contains("UTOOL_NUM=20"),
            "{dialect:?}: {text}"
        );
    }
    let jbi = generate(&plan(&s, Dialect::Inform, &t, &m, &pulses));
    assert!(jbi.unwrap().files[0].text.contains("///TOOL 2\r\n"));
    // Every tool number from 1 to 10 holds another tool: refused, naming the table.
    let tools: Vec<String> = (1..=10)
        .map(|n| format!("{{ number = {n}, xyz_mm = [0, 0, {}] }}", 10 * n))
        .collect();
    let text = format!("{SETUP}\n[controller]\ntools = [{}]\n", tools.join(", "));
    let full = stiffid::internal::setup::parse(&text, "fanuc-milling.toml", |n, _| presets::get(n))
        .unwrap();
    for dialect in [Dialect::FanucLs, Dialect::Inform] {
        let e = generate(&plan(&full, dialect, &t, &m, &pulses))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("controller.tools: every tool number from 1 to 10 holds another"),
            "{e}"
        );
    }
}
