//! The INFORM generator (`stiffid_machining::program::inform::generate`): jobs in pulses that read back.

use nalgebra::{Isometry3, Vector3, Vector6};
use stiffid_core::robot::external::{ExternalAxes, ExternalAxis};
use stiffid_core::robot::presets;
use stiffid_core::setup::Pulses;
use stiffid_core::Error;
use stiffid_machining::program::generate::{generate, Settings, Tool};
use stiffid_machining::program::generate::{Move, Plan, Target, Targets};
use stiffid_machining::program::inform::generate::speed;
use stiffid_machining::program::speed::Speed;
use stiffid_machining::program::{parse, parse_in, Context, Dialect};

/// What a setup with the controller's pulses `p` tells the reader.
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

/// Pulses per degree that are not whole (S, L, U, R, B, T) and per mm of a track.
fn pulses(external: Vec<f64>) -> Pulses {
    Pulses {
        per_deg: [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7],
        external,
    }
}

/// Targets of a GP-sized robot at these axis angles (deg), with these external values.
fn targets(q_deg: &[[f64; 6]], external: &[f64]) -> Vec<Target> {
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    (q_deg.iter())
        .map(|q| Target {
            external: external.to_vec(),
            ..Target::new(
                &robot,
                &Vector3::new(0.0, 0.0, 0.3),
                &Vector6::from(*q).map(f64::to_radians),
            )
        })
        .collect()
}

fn plan<'a>(t: &'a [Target], m: &'a [Move], pulses: Option<&'a Pulses>) -> Plan<'a> {
    Plan {
        dialect: Dialect::Inform,
        name: "POCKET",
        targets: t,
        moves: m,
        tool: Tool {
            frame: Isometry3::translation(0.01, -0.02, 0.3),
            payload: Some((12.5, Vector3::new(0.0, 0.0, 0.12))),
        },
        work: Isometry3::identity(),
        world: Isometry3::identity(),
        external: None,
        approximation: 1e-5,
        numbers: Default::default(),
        pulses,
        settings: Settings::default(),
    }
}

const Q: [[f64; 6]; 3] = [
    [-23.2, 3.9, -48.1, 10.0, -41.9, 23.2],
    [
        -20.000123, 5.000456, -45.000789, 100.0001, -40.00049, 200.00077,
    ],
    [-18.0, 6.0, -44.0, -95.0, 35.0, -190.0],
];
const MOVES: [Move; 3] = [Move::Rapid, Move::Feed(0.03), Move::Feed(100.0 / 6e4)];

/// A job written from Cartesian targets (the default) states their axis angles in pulses and no
/// `'stiffid:` comment, reads back with the setup's pulses (not without them) to within half a
/// pulse, with its speeds, and is the job of joint targets.
#[test]
fn a_job_reads_back_its_targets_within_half_a_pulse() {
    let (t, p) = (targets(&Q, &[]), pulses(Vec::new()));
    let w = generate(&plan(&t, &MOVES, Some(&p))).unwrap();
    assert_eq!(w.files.len(), 1);
    let text = &w.files[0].text;
    assert!(text.starts_with("/JOB\r\n//NAME POCKET\r\n//POS\r\n///NPOS 3,0,0,0,0,0\r\n///TOOL 1\r\n///POSTYPE PULSE\r\n///PULSE\r\nC00000="), "{text}");
    assert!(text.contains("///GROUP1 RB1\r\nNOP\r\n'set tool file 1 to the tool:\r\n'X = 10 mm\r\n'Y = -20 mm\r\n'Z = 300 mm\r\n"), "{text}");
    assert!(
        text.contains("'W = 12.5 kg\r\n'Xg = 0 mm\r\n'Yg = 0 mm\r\n'Zg = 120 mm\r\n"),
        "{text}"
    );
    // The pulses are the setup's: no comment states them (a pendant keeps 32 characters).
    assert!(!text.contains("'stiffid:"), "{text}");
    assert!(text.contains("MOVJ C00000 VJ=20.00 PL=0\r\nMOVL C00001 V=30.0 PL=1\r\nMOVL C00002 V=1.7 PL=0\r\nEND\r\n"), "{text}");
    assert!(text.lines().all(|l| !l.starts_with('\'') || l.len() <= 32));
    assert_eq!(w.warnings.len(), 1, "{:?}", w.warnings);
    assert!(w.warnings[0].contains("100 mm/min") && w.warnings[0].contains("V=1.7"));
    assert!(parse(text, Dialect::Inform).is_err());
    let read = parse_in(text, Dialect::Inform, &with(&p)).unwrap();
    assert_eq!(read.targets.len(), 3);
    for (r, q) in read.targets.iter().zip(&Q) {
        for ((a, b), per) in r.q_deg.iter().zip(q).zip(&p.per_deg) {
            assert!((a - b).abs() <= 0.5 / per + 1e-12, "{a} {b}");
        }
    }
    // The job is not exact to the decimals: the rounding is the pulse's.
    let off = (read.targets[1].q_deg[0] - Q[1][0]).abs();
    assert!(off > 1e-6, "{off}");
    let speeds: Vec<&Speed> = read.targets.iter().map(|t| &t.speed).collect();
    assert_eq!(speeds[0], &Speed::Joint);
    assert!(matches!(speeds[1], Speed::Path(v) if (v - 0.03).abs() < 1e-12));
    assert!(matches!(speeds[2], Speed::Path(v) if (v - 0.0017).abs() < 1e-12));
    let mut joint = plan(&t, &MOVES, Some(&p));
    joint.settings.targets = Targets::Joint;
    assert_eq!(&generate(&joint).unwrap().files[0].text, text);
}

/// Without the controller's pulses no job is written; a feed below 0.1 mm/s is refused naming
/// its target.
#[test]
fn a_job_without_pulses_or_with_a_feed_it_cannot_state_is_refused() {
    let t = targets(&Q, &[]);
    match generate(&plan(&t, &MOVES, None)) {
        Err(Error::InvalidField { field, message }) => {
            assert_eq!(field, "controller.pulses_per_deg");
            assert!(message.contains("[controller] pulses_per_deg"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(speed(0.03), Some(("V=30.0".into(), true)));
    assert_eq!(speed(0.12345), Some(("V=123.5".into(), false)));
    assert_eq!(speed(0.04e-3), None);
    // F5 and F5.99 (mm/min): below the slowest V=, refused as the reference says, never
    // written as V=0.1 (20 % and 0.2 % fast); F6 is V=0.1 exactly.
    assert_eq!(speed(5.0 / 60e3), None);
    assert_eq!(speed(5.99 / 60e3), None);
    assert_eq!(speed(6.0 / 60e3), Some(("V=0.1".into(), true)));
    let p = pulses(Vec::new());
    let slow = [Move::Rapid, Move::Feed(0.04e-3), Move::Feed(0.03)];
    assert!(matches!(
        generate(&plan(&t, &slow, Some(&p))),
        Err(Error::Program { line: 2, .. })
    ));
}

/// A job of more moves than one file holds calls its sub-jobs, each of which reads back with the
/// setup's pulses with its share of the targets.
#[test]
fn a_split_job_calls_sub_jobs_that_read_back_with_the_setups_pulses() {
    let q: Vec<[f64; 6]> = (0..250)
        .map(|i| [-20.0 + 1e-3 * i as f64, 5.0, -45.0, 10.0, -40.0, 20.0])
        .collect();
    let (t, p) = (targets(&q, &[]), pulses(Vec::new()));
    let m = vec![Move::Feed(0.03); t.len()];
    let mut plan = plan(&t, &m, Some(&p));
    plan.settings.moves_per_file = 100;
    let w = generate(&plan).unwrap();
    assert_eq!(w.files.len(), 4);
    let main = &w.files[0].text;
    assert!(main.contains("NOP\r\n'set tool file 1"), "{main}");
    assert!(
        main.contains("CALL JOB:POCKET_01\r\nCALL JOB:POCKET_02\r\nCALL JOB:POCKET_03\r\nEND\r\n"),
        "{main}"
    );
    assert!(main.contains("///NPOS 0,0,0,0,0,0\r\n//INST"), "{main}");
    let mut read = Vec::new();
    for f in &w.files[1..] {
        assert!(f
            .text
            .starts_with(&format!("/JOB\r\n//NAME {}\r\n", f.name)));
        read.extend(
            parse_in(&f.text, Dialect::Inform, &with(&p))
                .unwrap()
                .targets,
        );
    }
    assert_eq!(read.len(), 250);
    for (r, q) in read.iter().zip(&q) {
        assert!((r.q_deg[0] - q[0]).abs() <= 0.5 / p.per_deg[0] + 1e-12);
    }
}

/// A track's values without `external_pulses` are written in `///ANGLE` form (mm) and read back
/// to the decimals; with them, in whole pulses.
#[test]
fn a_base_axis_is_written_in_angle_form_or_in_pulses() {
    let axes = ExternalAxes::new(vec![ExternalAxis::linear(
        "track",
        Vector3::x_axis(),
        0.0,
        6.0,
    )])
    .unwrap();
    let t = targets(&Q, &[1500.123456789]);
    for (p, tolerance) in [(pulses(Vec::new()), 1e-9), (pulses(vec![1000.0]), 5e-4)] {
        let mut plan = plan(&t, &MOVES, Some(&p));
        plan.external = Some(&axes);
        let text = &generate(&plan).unwrap().files[0].text;
        assert!(text.contains("///NPOS 3,3,0,0,0,0"), "{text}");
        assert!(text.contains("///GROUP1 RB1,BS1\r\n"), "{text}");
        assert!(text.contains("MOVL C00001 BC00001 V=30.0"), "{text}");
        let form = match p.external.is_empty() {
            true => "///ANGLE\r\nBC00000=1500.123456789\r\n",
            false => "///PULSE\r\nBC00000=1500123\r\n",
        };
        assert!(text.contains(form), "{text}");
        let read = parse_in(text, Dialect::Inform, &with(&p)).unwrap();
        for r in &read.targets {
            let e = r.external[0].unwrap();
            assert!((e - 1500.123456789).abs() <= tolerance, "{e}");
        }
    }
}
