//! A G-code path's arcs as circular moves (`stiffid_machining::program::generate::arcs`):
//! pieces of at most 180 deg through the chord point nearest their middle, chords where the
//! compensated points leave the circle (the deviation stated), each language's circular move
//! written and read back to the targets written.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::{self, Language, Program};
use stiffid::internal::robot::{ik, presets};
use stiffid::Setup;
use stiffid_core::setup::Pulses;
use stiffid_machining::gcode::ArcBlock;
use stiffid_machining::program::generate::arcs::{self, Form};
use stiffid_machining::program::generate::{generate, Move, Plan, Settings, Target, Tool};
use stiffid_machining::program::{parse_in, Context, Dialect};

const FEED: f64 = 0.02;

/// A target at `p` (m) of no robot: the planner looks at positions and external values only.
fn bare(p: &Vector3<f64>, external: f64) -> Target {
    Target {
        q_deg: [0.0; 6],
        pose: Isometry3::from(Translation3::from(*p)),
        arm: stiffid::internal::robot::configuration::Configuration {
            q_deg: [0.0; 6],
            front: 1.0,
            elbow: 1.0,
        },
        external: vec![external],
    }
}

/// `m` chords of a circle of radius 50 mm about (10, 20, 5) mm turning `sweep_deg` in a plane
/// tilted 30 deg about x, from angle 15 deg: the start and the `m` chord ends, m.
fn circle(m: usize, sweep_deg: f64) -> Vec<Vector3<f64>> {
    let tilt = UnitQuaternion::from_euler_angles(30f64.to_radians(), 0.0, 0.0);
    (0..=m)
        .map(|i| {
            let a = (15.0 + sweep_deg * i as f64 / m as f64).to_radians();
            Vector3::new(0.01, 0.02, 0.005) + tilt * Vector3::new(a.cos(), a.sin(), 0.0) * 0.05
        })
        .collect()
}

/// The path: a rapid to the arc's start, the arc (line 7) at [`FEED`], one straight move
/// after; its targets, moves and arc.
fn path(points: &[Vector3<f64>]) -> (Vec<Target>, Vec<Move>, Vec<ArcBlock>) {
    let mut p = points.to_vec();
    p.push(points[points.len() - 1] + Vector3::new(0.0, 0.0, 0.01));
    let targets: Vec<Target> = p.iter().map(|p| bare(p, 0.0)).collect();
    let mut moves = vec![Move::Feed(FEED); p.len()];
    moves[0] = Move::Rapid;
    let arc = ArcBlock {
        line: 7,
        points: 0..points.len(),
    };
    (targets, moves, vec![arc])
}

fn positions(t: &[Target]) -> Vec<Vector3<f64>> {
    t.iter().map(|t| t.pose.translation.vector).collect()
}

/// The pieces written: `[start, via, end]` indices of the path.
fn pieces(c: &arcs::Circular) -> Vec<[usize; 3]> {
    (0..c.moves.len())
        .filter(|&i| matches!(c.moves[i], Move::ArcEnd(_)))
        .map(|i| [c.index[i - 2], c.index[i - 1], c.index[i]])
        .collect()
}

#[test]
fn an_arc_is_written_in_circular_moves_of_at_most_half_a_circle_through_its_middle() {
    // 90 deg in one move; 270 deg and a full circle in two.
    for (sweep, m, count) in [(90.0, 9, 1), (270.0, 27, 2), (360.0, 36, 2)] {
        let (t, moves, arcs) = path(&circle(m, sweep));
        let c = arcs::circular(&arcs, (&t, &positions(&t), &moves), 1e-5, Form::ViaEnd);
        assert!(c.warnings.is_empty(), "{:?}", c.warnings);
        let p = pieces(&c);
        assert_eq!(p.len(), count, "{sweep} deg");
        // The pieces follow each other from the arc's start to its end.
        assert_eq!(p[0][0], 0);
        assert_eq!(p[count - 1][2], m);
        for w in p.windows(2) {
            assert_eq!(w[0][2], w[1][0]);
        }
        for [s, v, e] in &p {
            // Each chord turns sweep / m: a piece turns at most 180 deg.
            assert!((e - s) as f64 * sweep / m as f64 <= 180.0 + 1e-9, "{p:?}");
            // The via point is the chord point nearest the piece's middle.
            assert!((2 * v).abs_diff(s + e) <= 1, "{p:?}");
        }
        // The straight move after the arc is kept; the rapid before it too.
        assert_eq!(c.index[0], 0);
        assert_eq!(c.moves[0], Move::Rapid);
        assert_eq!(*c.index.last().unwrap(), m + 1);
        assert_eq!(*c.moves.last().unwrap(), Move::Feed(FEED));
        assert_eq!(c.moves.len(), 2 + 2 * count);
    }
}

#[test]
fn a_compensated_arc_off_its_circle_is_written_as_chords_with_the_deviation_stated() {
    let mut points = circle(9, 90.0);
    // Point 3 (no piece's start, via or end) 0.03 mm out along its radius.
    let tilt = UnitQuaternion::from_euler_angles(30f64.to_radians(), 0.0, 0.0);
    let a = (15.0f64 + 30.0).to_radians();
    points[3] += tilt * Vector3::new(a.cos(), a.sin(), 0.0) * 0.03e-3;
    let (t, moves, arcs) = path(&points);
    let c = arcs::circular(&arcs, (&t, &positions(&t), &moves), 1e-5, Form::ViaEnd);
    assert_eq!(c.index, (0..t.len()).collect::<Vec<_>>());
    assert_eq!(c.moves, moves);
    assert_eq!(c.warnings.len(), 1, "{:?}", c.warnings);
    let w = &c.warnings[0];
    assert!(
        w.contains("1 of 1 arcs written as chords (lines 7)") && w.contains("up to 0.03 mm off"),
        "{w}"
    );
    // Within the tolerance, the circle.
    let c = arcs::circular(&arcs, (&t, &positions(&t), &moves), 0.04e-3, Form::ViaEnd);
    assert!(c.warnings.is_empty() && pieces(&c).len() == 1);
    // The external axes moving along the arc: chords.
    let mut moving = t.clone();
    moving[4].external[0] = 1.0;
    let c = arcs::circular(&arcs, (&moving, &positions(&t), &moves), 1e-3, Form::ViaEnd);
    assert_eq!(c.moves, moves);
    assert!(c.warnings[0].contains("external axes"), "{:?}", c.warnings);
}

#[test]
fn inform_teaches_the_start_and_separates_two_arcs_by_a_linear_step() {
    // The second arc the first turned half a turn about its end (an S curve).
    let first = circle(8, 90.0);
    let end = first[8];
    let mut points = first.clone();
    points.extend((1..=8).map(|i| 2.0 * end - first[8 - i]));
    let (t, moves, _) = path(&points);
    let arcs = vec![
        ArcBlock {
            line: 7,
            points: 0..9,
        },
        ArcBlock {
            line: 8,
            points: 8..17,
        },
    ];
    let c = arcs::circular(&arcs, (&t, &positions(&t), &moves), 1e-5, Form::StartViaEnd);
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
    let f = FEED;
    assert_eq!(
        c.moves,
        [
            Move::Rapid,
            Move::ArcStart(f),
            Move::ArcVia(f),
            Move::ArcEnd(f),
            Move::Feed(f),
            Move::ArcStart(f),
            Move::ArcVia(f),
            Move::ArcEnd(f),
            Move::Feed(f)
        ]
    );
    assert_eq!(c.index, [0, 0, 4, 8, 8, 8, 12, 16, 17]);
    assert!(arcs::whole(&c.moves, Some(Form::StartViaEnd)));
    assert!(!arcs::whole(&c.moves, Some(Form::ViaEnd)));
    assert!(!arcs::whole(&c.moves, None));
    // Each motion's bound: the largest of the points it stands for.
    let bounds: Vec<f64> = (0..t.len()).map(|i| i as f64).collect();
    assert_eq!(
        arcs::motion_bounds(&c, &bounds, Form::StartViaEnd),
        [0.0, 0.0, 7.0, 8.0, 8.0, 8.0, 15.0, 16.0, 17.0]
    );
    let via_end = arcs::circular(&arcs, (&t, &positions(&t), &moves), 1e-5, Form::ViaEnd);
    assert_eq!(via_end.index, [0, 4, 8, 12, 16, 17]);
    assert_eq!(
        arcs::motion_bounds(&via_end, &bounds, Form::ViaEnd),
        [0.0, 8.0, 16.0, 17.0]
    );
}

const SETUP: &str = include_str!("../../../../../../examples/milling/fanuc-milling.toml");

fn setup() -> Setup {
    stiffid::internal::setup::parse(SETUP, "fanuc-milling.toml", |n, _| presets::get(n)).unwrap()
}

/// The targets of the setup's robot at the part-frame points `points` (the tool down), by its
/// inverse kinematics from the start.
pub(super) fn robot_targets(s: &Setup, points: &[Vector3<f64>]) -> Vec<Target> {
    let (robot, tcp, part) = (s.robot(), s.tool().tcp, *s.workpiece().unwrap());
    let down = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    let mut q = Options::for_setup(s).q0;
    (points.iter())
        .map(|p| {
            let pose = part * Isometry3::from_parts(Translation3::from(*p), down);
            q = (ik::solve(robot, &tcp, &pose, &q, &ik::Options::default()).unwrap()).q;
            Target::new(robot, &tcp, &q)
        })
        .collect()
}

fn plan<'a>(
    s: &Setup,
    dialect: Dialect,
    (t, m): (&'a [Target], &'a [Move]),
    pulses: Option<&'a Pulses>,
) -> Plan<'a> {
    Plan {
        dialect,
        name: "ARCS",
        targets: t,
        moves: m,
        tool: Tool {
            frame: Isometry3::from(Translation3::from(s.tool().tcp)),
            payload: Some((10.0, Vector3::new(0.0, 0.0, 0.1))),
        },
        work: *s.workpiece().unwrap(),
        world: s.program_world(),
        external: None,
        approximation: 1e-5,
        numbers: Default::default(),
        pulses,
        settings: Settings::default(),
    }
}

/// Each language's circular moves (a full circle then 90 deg more: three pieces), written and
/// read back by stiffid's own readers to the targets written, in order.
#[test]
fn each_language_writes_its_circular_moves_and_reads_them_back() {
    let s = setup();
    // In the part's plane at z = -4 mm: radius 50 mm about (10, 20) mm from angle 15 deg.
    let points: Vec<Vector3<f64>> = (0..=45)
        .map(|i| {
            let a = (15.0 + 10.0 * i as f64).to_radians();
            Vector3::new(0.01 + 0.05 * a.cos(), 0.02 + 0.05 * a.sin(), -0.004)
        })
        .collect();
    let arcs = vec![
        ArcBlock {
            line: 7,
            points: 0..37,
        },
        ArcBlock {
            line: 8,
            points: 36..46,
        },
    ];
    let targets = robot_targets(&s, &points);
    let mut moves = vec![Move::Feed(FEED); targets.len()];
    moves[0] = Move::Rapid;
    let pulses = Pulses {
        per_deg: [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7],
        external: Vec::new(),
    };
    let cases = [
        (Dialect::Krl, Form::ViaEnd, "CIRC {E6POS:", 3),
        (Dialect::Rapid, Form::ViaEnd, "MoveC [[", 3),
        (Dialect::FanucLs, Form::ViaEnd, ":C P[", 3),
        (Dialect::Inform, Form::StartViaEnd, "MOVC C", 9),
    ];
    for (dialect, form, circular, count) in cases {
        let c = arcs::circular(&arcs, (&targets, &positions(&targets), &moves), 1e-5, form);
        assert!(c.warnings.is_empty(), "{:?}", c.warnings);
        let written: Vec<Target> = c.index.iter().map(|&i| targets[i].clone()).collect();
        let p = plan(&s, dialect, (&written, &c.moves), Some(&pulses));
        let file = generate(&p).unwrap().files.remove(0);
        // A KRL program's points are in its .dat: its literal form, read alone, too.
        let text = crate::common::inlined(&file.text, file.data.as_deref());
        assert_eq!(text.matches(circular).count(), count, "{dialect:?}: {text}");
        if dialect == Dialect::Krl {
            reads_back_with_its_data(&file, &text);
        }
        if dialect == Dialect::FanucLs {
            // The LS reader of the corpus's tests (string searches, not stiffid's): the via
            // point and the end of each `C`, in order, each the written target's position in
            // the controller's world (FANUC's, 670 mm above the base frame).
            let read = crate::ls_corpus::independent(&text);
            assert_eq!(read.len(), written.len());
            let world = s.program_world().translation.vector;
            assert_eq!(world, Vector3::new(0.0, 0.0, 0.670));
            for (r, w) in read.iter().zip(&written) {
                let p = Vector3::new(r.values[0], r.values[1], r.values[2]) * 1e-3;
                assert!(
                    (p + world - w.pose.translation.vector).norm() < 1e-11,
                    "{r:?}"
                );
            }
        }
        let back = match dialect {
            Dialect::Inform => {
                let context = Context {
                    home_deg: None,
                    backup: &[],
                    pulses: Some(&pulses),
                    tool: None,
                    data: None,
                    machine: None,
                    ..Default::default()
                };
                parse_in(&text, dialect, &context).unwrap().targets
            }
            _ => {
                let read = machining::read(&text, Language::Robot(dialect), 1e-4).unwrap();
                let read = machining::resolve(&read, &s, None, &Options::for_setup(&s)).unwrap();
                let Program::Robot(r) = read.into_owned() else {
                    panic!()
                };
                r.targets
            }
        };
        assert_eq!(back.len(), written.len(), "{dialect:?}");
        // INFORM rounds to whole pulses; the others state 9 decimals.
        let within = if dialect == Dialect::Inform {
            1e-3
        } else {
            1e-6
        };
        for (b, w) in back.iter().zip(&written) {
            let off = (Vector6::from(b.q_deg) - Vector6::from(w.q_deg)).amax();
            assert!(off <= within, "{dialect:?}: {off} deg");
        }
    }
}

/// A written KRL program, its `.src` naming the points and its `.dat` declaring them
/// (`krl::data::split`), reads back with the `.dat` to the targets of its literal form `text`
/// (the points put back): the same lines, values (to 1e-9 mm/deg) and motions, each circular
/// move's via and end points named in order.
fn reads_back_with_its_data(file: &stiffid_machining::program::generate::File, text: &str) {
    use stiffid_machining::program::parse_with_data;
    let (src, dat) = (&file.text, file.data.as_deref().unwrap());
    assert!(!src.contains("E6POS") && !src.contains("{A1"), "{src}");
    assert!(
        dat.starts_with("&ACCESS RVP\n&REL 1\nDEFDAT ARCS\n"),
        "{dat}"
    );
    assert!(dat.ends_with("ENDDAT\n"), "{dat}");
    assert!(src.contains("CIRC XP2, XP3"), "{src}");
    // Read alone, a .src naming its points is refused: they are in the .dat.
    assert!(parse_with_data(src, None, Dialect::Krl).is_err());
    let literal = parse_with_data(text, None, Dialect::Krl).unwrap().targets;
    let named = parse_with_data(src, Some(dat), Dialect::Krl)
        .unwrap()
        .targets;
    assert_eq!(named.len(), literal.len());
    assert_eq!(dat.matches("DECL E6POS XP").count(), literal.len(), "{dat}");
    for (n, l) in named.iter().zip(&literal) {
        assert_eq!(n.line, l.line);
        assert_eq!(n.speed, l.speed);
        assert_eq!(n.external, l.external);
        let (Some(a), Some(b)) = (&n.cartesian, &l.cartesian) else {
            panic!("a Cartesian target: {n:?}");
        };
        let dp = (a.position_mm - b.position_mm).norm();
        assert!(dp < 1e-9, "{dp} mm");
        assert!(a.rotation.angle_to(&b.rotation).to_degrees() < 1e-9);
        assert_eq!((&a.flags, &a.frame, &a.tool), (&b.flags, &b.frame, &b.tool));
    }
}
