//! The headers the controllers expect in a generated program: KRL's `&ACCESS`, `&REL` and
//! `&PARAM` lines, LS's whole `/ATTR`, INFORM's `///DATE` and `///COMM`; the dates reproducible
//! (`SOURCE_DATE_EPOCH`, else 1970-01-01).

use super::arcs::robot_targets;
use nalgebra::{Isometry3, Translation3, Vector3};
use stiffid::internal::robot::presets;
use stiffid_core::setup::Pulses;
use stiffid_machining::program::generate::{generate, Move, Plan, Settings, Tool};
use stiffid_machining::program::{parse_in, Context, Dialect};

const SETUP: &str = include_str!("../../../../../../examples/milling/fanuc-milling.toml");

/// Each language's program of two targets and, for KRL, its `.dat`.
fn texts() -> Vec<(Dialect, String, Option<String>)> {
    let s = stiffid::internal::setup::parse(SETUP, "fanuc-milling.toml", |n, _| presets::get(n))
        .unwrap();
    let points = [
        Vector3::new(0.0, 0.0, -0.004),
        Vector3::new(0.05, 0.0, -0.004),
    ];
    let t = robot_targets(&s, &points);
    let m = [Move::Rapid, Move::Feed(0.02)];
    let pulses = Pulses {
        per_deg: [1341.25; 6],
        external: Vec::new(),
    };
    [Dialect::Krl, Dialect::FanucLs, Dialect::Inform]
        .into_iter()
        .map(|dialect| {
            let plan = Plan {
                dialect,
                name: "HEAD",
                targets: &t,
                moves: &m,
                tool: Tool {
                    frame: Isometry3::from(Translation3::from(s.tool().tcp)),
                    payload: None,
                },
                work: *s.workpiece().unwrap(),
                world: Isometry3::identity(),
                external: None,
                approximation: 1e-5,
                numbers: Default::default(),
                pulses: Some(&pulses),
                settings: Settings::default(),
            };
            {
                let f = generate(&plan).unwrap().files.remove(0);
                (dialect, f.text, f.data)
            }
        })
        .collect()
}

#[test]
fn generated_programs_carry_the_headers_their_controllers_write() {
    // The test process leaves SOURCE_DATE_EPOCH unset: the dates are 1970-01-01.
    assert!(std::env::var("SOURCE_DATE_EPOCH").is_err());
    let texts = texts();
    let krl = &texts[0].1;
    let dat = texts[0].2.as_deref().unwrap();
    // The .dat as KSS writes one: its attributes, DEFDAT of the program's name, its points.
    assert!(
        dat.starts_with("&ACCESS RVP\n&REL 1\nDEFDAT HEAD\nDECL E6POS XP1={X "),
        "{dat}"
    );
    assert!(
        dat.ends_with("}\nENDDAT\n") && dat.matches("DECL").count() == 2,
        "{dat}"
    );
    assert!(krl.starts_with("&ACCESS RVP\n&REL 1\n&PARAM TEMPLATE = C:\\KRC\\Roboter\\Template\\vorgabe\n&PARAM EDITMASK = *\nDEF HEAD( )\n"), "{krl}");
    let ls = &texts[1].1;
    let numbered = ls
        .lines()
        .filter(|l| l.len() > 5 && l[..4].trim().parse::<u32>().is_ok() && &l[4..5] == ":")
        .count();
    let attr = format!("/PROG  HEAD\n/ATTR\nOWNER\t\t= MNEDITOR;\nCOMMENT\t\t= \"stiffid\";\nPROG_SIZE\t= 0;\nCREATE\t\t= DATE 70-01-01  TIME 00:00:00;\nMODIFIED\t= DATE 70-01-01  TIME 00:00:00;\nFILE_NAME\t= ;\nVERSION\t\t= 0;\nLINE_COUNT\t= {numbered};\nMEMORY_SIZE\t= 0;\nPROTECT\t\t= READ_WRITE;\nTCD:  STACK_SIZE\t= 0,\n      TASK_PRIORITY\t= 50,\n      TIME_SLICE\t= 0,\n      BUSY_LAMP_OFF\t= 0,\n      ABORT_REQUEST\t= 0,\n      PAUSE_REQUEST\t= 0;\nDEFAULT_GROUP\t= 1,*,*,*,*;\nCONTROL_CODE\t= 00000000 00000000;\n/MN\n");
    assert!(ls.starts_with(&attr), "{ls}");
    assert_eq!(numbered, 11, "{ls}");
    let jbi = &texts[2].1;
    assert!(
        jbi.contains("//INST\r\n///DATE 1970/01/01 00:00\r\n///COMM stiffid\r\n///ATTR SC,RW\r\n"),
        "{jbi}"
    );
    // Each still reads (the LS and KRL readers the headers of real files; INFORM with the
    // setup's pulses).
    for (text, data, d) in [(krl, Some(dat), Dialect::Krl), (ls, None, Dialect::FanucLs)] {
        let context = Context {
            data,
            ..Context::default()
        };
        assert_eq!(
            parse_in(text, d, &context).unwrap().targets.len(),
            2,
            "{d:?}"
        );
    }
    let pulses = Pulses {
        per_deg: [1341.25; 6],
        external: Vec::new(),
    };
    let context = Context {
        home_deg: None,
        backup: &[],
        pulses: Some(&pulses),
        tool: None,
        data: None,
        machine: None,
        ..Default::default()
    };
    assert_eq!(
        parse_in(jbi, Dialect::Inform, &context)
            .unwrap()
            .targets
            .len(),
        2
    );
}
