//! Boxes a positioner carries (`[[cell.obstacle]] carried_by`): a capsule's distance to a turned
//! box against brute force; a carried box turns with the part (the axes up to its own);
//! `at_station` freezes it; the free table angle never drives the arm into a box on the table
//! (checked independently at the chosen angle), the choice changes and no bound rises; bad
//! fields are refused naming the file and the field; a turned box's margin gradient matches
//! central differences.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::cell::{
    bodies, body_box, capsule_box, capsules, Capsule, CheckKind, Checker, Part,
};
use stiffid::internal::machining::compensate::PathPoint;
use stiffid::internal::machining::compensate::{
    self, Compensated, Free, FreeRange, FreeVariables, Options, Variable,
};
use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis, ExternalValues};
use stiffid::internal::robot::presets;
use stiffid::internal::setup::Obstacle;
use stiffid::{internal::setup, Setup};

use crate::track_collisions::{assert_avoided, in_cell, line_at};

/// The distance of point `p` to the box `o` (turned by its pose), exact: `p` in the box's
/// frame, clamped into it.
fn point_box(p: &Vector3<f64>, o: &Obstacle) -> f64 {
    let local = o.pose.inverse_transform_point(&Point3::from(*p)).coords;
    let inside = local.zip_zip_map(&o.min, &o.max, |v, lo, hi| v.clamp(lo, hi));
    (local - inside).norm()
}

/// A capsule's distance to a box by brute force: the smallest point-box distance over 20 001
/// points of the segment (a convex function of the segment's parameter), less the radius.
fn brute(c: &Capsule, o: &Obstacle) -> f64 {
    let n = 20_000;
    (0..=n)
        .map(|k| point_box(&(c.a + (c.b - c.a) * (k as f64 / n as f64)), o))
        .fold(f64::INFINITY, f64::min)
        - c.radius
}

fn turned_box(pose: Isometry3<f64>) -> Obstacle {
    Obstacle {
        pose,
        ..Obstacle::fixed(
            "fixture",
            Vector3::new(-0.2, -0.1, 0.0),
            Vector3::new(0.3, 0.4, 0.25),
        )
    }
}

#[test]
fn a_capsule_and_a_turned_box_match_brute_force() {
    let pose = Isometry3::from_parts(
        Translation3::new(1.2, -0.5, 0.7),
        UnitQuaternion::from_euler_angles(0.4, -0.7, 1.1),
    );
    let o = turned_box(pose);
    let segments = [
        ([0.0, 0.0, 0.0], [2.0, -1.0, 2.0]),
        ([1.9, 0.2, 1.5], [0.3, -1.4, 1.8]),
        ([2.5, 0.5, 0.1], [2.6, -0.8, 0.4]),
        ([0.5, -0.5, 1.6], [0.5, -0.5, 1.6]),
    ];
    let mut apart = 0;
    for (a, b) in segments {
        let c = Capsule {
            part: Part::Tool,
            a: Vector3::from(a),
            b: Vector3::from(b),
            radius: 0.05,
        };
        let (d, reference) = (capsule_box(&c, &o), brute(&c, &o));
        if reference > 0.0 {
            apart += 1;
            assert!((d - reference).abs() < 1e-6, "{d} {reference}");
        } else {
            assert!(d <= 0.0, "{d} {reference}");
        }
    }
    assert!(apart >= 3, "{apart}");
    // A quarter turn about z is the axis-aligned box with x and y swapped (to GJK's tolerance).
    let quarter = Isometry3::rotation(Vector3::z() * std::f64::consts::FRAC_PI_2);
    let swapped = Obstacle::fixed(
        "fixture",
        Vector3::new(-0.4, -0.2, 0.0),
        Vector3::new(0.1, 0.3, 0.25),
    );
    for (a, b) in segments {
        let c = Capsule {
            part: Part::Tool,
            a: Vector3::from(a) * 0.5,
            b: Vector3::from(b) * 0.5,
            radius: 0.02,
        };
        let (d, aligned) = (
            capsule_box(&c, &turned_box(quarter)),
            capsule_box(&c, &swapped),
        );
        assert!((d - aligned).abs() < 1e-7, "{d} {aligned}");
    }
}

/// The track-and-positioner example with `obstacles` appended to its text.
pub(crate) fn track_cell(obstacles: &str) -> stiffid::Result<Setup> {
    let text = include_str!("../../../../examples/track/track-cell.toml").to_string()
        + "\n[cell]\nclearance_mm = 10\n"
        + obstacles;
    setup::parse(&text, "track-cell.toml", |name, _| presets::get(name))
}

pub(crate) const PLATE: &str = "[[cell.obstacle]]\nname = \"plate\"\nmin_mm = [2700, 1500, 850]\n\
                     max_mm = [3300, 2100, 900]\ncarried_by = \"AXIS\"\n";

/// Turning by `angle` about the line through `point` along `direction`.
pub(crate) fn turn(point: [f64; 3], direction: Vector3<f64>, angle: f64) -> Isometry3<f64> {
    let p = Translation3::from(Vector3::from(point) * 1e-3);
    let r = UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(direction), angle);
    p * r * p.inverse()
}

#[test]
fn a_carried_box_turns_with_the_axes_up_to_its_own() {
    let (tilt, rotate) = (20f64.to_radians(), 45f64.to_radians());
    let e = [3.0, tilt, rotate];
    let tilted = turn([3000.0, 1800.0, 700.0], Vector3::x(), tilt);
    let turned = tilted * turn([3000.0, 1800.0, 900.0], Vector3::z(), rotate);
    for (axis, expected) in [("tilt", tilted), ("rotate", turned)] {
        let s = track_cell(&PLATE.replace("AXIS", axis)).unwrap();
        let o = &s.cell().unwrap().obstacles[0];
        let at = o.at(s.robot().external(), &e);
        assert_eq!(at.carried_by, None);
        let corner = Point3::from(o.max);
        let error = (at.pose * corner - expected * corner).norm();
        assert!(error < 1e-12, "{axis}: {error}");
        // At rest (no values: e = 0, no offsets) it stands as given.
        let rest = o.at(s.robot().external(), &[]).pose * corner;
        assert!((rest - corner).norm() < 1e-12, "{axis}: {rest}");
        // A station freezes it where the station's values put it.
        let there = s.at_station(&e).unwrap();
        assert_eq!(there.cell().unwrap().obstacles[0], at);
    }
}

#[test]
fn bad_carriers_are_refused_naming_the_file_and_the_field() {
    for (axis, says) in [
        (
            "table",
            "expected a positioner axis of the cell: tilt, rotate",
        ),
        ("track", "is a carrier axis"),
    ] {
        let error = track_cell(&PLATE.replace("AXIS", axis))
            .unwrap_err()
            .to_string();
        for part in ["track-cell.toml", "cell.obstacle[1].carried_by", says] {
            assert!(error.contains(part), "{part}: {error}");
        }
    }
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml").to_string()
        + "\n[cell]\n"
        + &PLATE.replace("AXIS", "rotate");
    let error = setup::parse(&text, "milling.toml", |name, _| presets::get(name))
        .unwrap_err()
        .to_string();
    assert!(error.contains("the cell has no positioner axis"), "{error}");
}

/// The table's axis: vertical through (2.7, -0.4, 0) m.
const TABLE: [f64; 3] = [2.7, -0.4, 0.0];

/// The FANUC milling example on a track (0 to 6 m), the part on a turntable (-30 to 30 deg),
/// in a cell with `obstacles` (clearance 10 mm).
fn on_table(obstacles: Vec<Obstacle>) -> Setup {
    let limit = 30f64.to_radians();
    let cell = ExternalAxes::new(vec![
        ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0),
        ExternalAxis::rotary("table", TABLE.into(), Vector3::z_axis(), -limit, limit),
    ])
    .unwrap();
    in_cell(cell, obstacles)
}

/// `n` points of a line along x on the part (the tool pointing down), the station 1.5 m, the
/// table at rest.
fn line(n: usize) -> Vec<PathPoint> {
    line_at(n, &[1.5, 0.0])
}

/// The free table +-20 deg in 10 deg steps, the bound summed.
fn options(s: &Setup) -> Options {
    let table = FreeRange::checked(&Variable::Positioner, 20.0, 10.0).ok();
    Options {
        free: FreeVariables {
            free: table.map(Free::Positioner).into_iter().collect(),
            ..FreeVariables::default()
        },
        ..Options::for_setup(s)
    }
}

/// A box of half-size `half` (m) on the table, centred at `centre` when the table is at
/// `angle` (rad).
fn on_the_table(centre: &Vector3<f64>, half: f64, angle: f64) -> Obstacle {
    let back = turn(TABLE.map(|v| v * 1e3), Vector3::z(), -angle) * Point3::from(*centre);
    Obstacle {
        carried_by: Some("table".into()),
        ..Obstacle::fixed(
            "fixture",
            back.coords.add_scalar(-half),
            back.coords.add_scalar(half),
        )
    }
}

/// Whether posture `q` on the carriage at `e` hits an obstacle, by the cell's checker.
fn collides(checker: &Checker, q: &Vector6<f64>, e: &ExternalValues) -> bool {
    (checker.feasibility_at(q, e.as_slice()).checks.iter())
        .any(|c| c.kind == CheckKind::Obstacles && !c.ok)
}

/// The smallest distance of the bodies of `q` (on the carriage at `e`) to box `o` turned by
/// hand to the table's angle in `e`, m.
fn by_hand(s: &Setup, q: &Vector6<f64>, e: &ExternalValues, o: &Obstacle) -> f64 {
    let turned = Obstacle {
        carried_by: None,
        pose: turn(TABLE.map(|v| v * 1e3), Vector3::z(), e.as_slice()[1]),
        ..o.clone()
    };
    arm_to_box(s, q, e, &turned)
}

/// The smallest distance of the bodies of `q` (on the carriage at `e`) to the box `o` where it
/// stands, m.
pub(crate) fn arm_to_box(s: &Setup, q: &Vector6<f64>, e: &ExternalValues, o: &Obstacle) -> f64 {
    let frames = s.robot().frames_at(q, e.as_slice());
    (bodies(s.arm(), &frames).iter())
        .map(|b| body_box(b, o))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn a_table_angle_that_drives_the_arm_into_a_box_on_the_table_is_not_taken() {
    let points = line(4);
    let open = on_table(Vec::new());
    let compliance = open.model_compliance("test").unwrap();
    let unchecked =
        compensate::path_on_track(open.arm(), &compliance, &points, &options(&open)).unwrap();
    let angle = |c: &Compensated| c.external.as_slice()[1];
    let (i, far) = (unchecked.iter().enumerate())
        .max_by(|a, b| angle(a.1).abs().total_cmp(&angle(b.1).abs()))
        .unwrap();
    assert!(angle(far).abs() >= 0.1, "{}", angle(far));
    // A box on the table 5 mm into one of the arm's bodies at the unchecked choice (by hand),
    // clear of every posture of the path's own (the table at rest).
    let frames = open.robot().frames_at(&far.q, far.external.as_slice());
    let sides = [Vector3::x(), Vector3::y(), Vector3::z()]
        .map(|u| [u, -u])
        .concat();
    let boxes: Vec<Obstacle> = (capsules(open.arm(), &frames).iter())
        .flat_map(|c| (0..=10).map(move |k| (c, c.a + (c.b - c.a) * (k as f64 / 10.0))))
        .flat_map(|(c, x)| sides.iter().map(move |u| (c.radius, x, *u)))
        .flat_map(|(r, x, u)| {
            [0.1, 0.05, 0.03]
                .map(|half| on_the_table(&(x + u * (r + half - 0.005)), half, angle(far)))
        })
        .collect();
    let own: Vec<Vector6<f64>> = unchecked.iter().map(|c| c.q_before.unwrap()).collect();
    let rest = ExternalValues::new(&[1.5, 0.0]).unwrap();
    let o = (boxes.into_iter())
        .find(|o| {
            own.iter().all(|q| by_hand(&open, q, &rest, o) >= 0.011)
                && by_hand(&open, &far.q, &far.external, o) < 0.0
        })
        .unwrap_or_else(|| panic!("no box fits: the table at {} rad", angle(far)));
    let s = on_table(vec![o]);
    let checker = Checker::new(&s);
    assert!(own.iter().all(|q| !collides(&checker, q, &rest)));
    assert!(collides(&checker, &far.q, &far.external));
    let o = &s.cell().unwrap().obstacles[0];
    // The same box at the table's rest is clear of that posture's own.
    assert!(by_hand(&s, &own[i], &rest, o) >= 0.01 - 1e-9);
    assert!(by_hand(&s, &far.q, &far.external, o) < 0.01);
    let out = compensate::path_on_track(s.arm(), &compliance, &points, &options(&s)).unwrap();
    assert_avoided(&out, (i, far), |k, c| {
        let clear = by_hand(&s, &c.q, &c.external, o);
        assert!(clear >= 0.01 - 1e-9, "point {k}: {clear} m");
    });
}

/// The gradient of a turned box's margin (from the witness turned back into the cell) equals
/// central differences.
#[test]
fn a_turned_box_margin_gradient_matches_finite_differences() {
    let s = on_table(Vec::new());
    let q = Vector6::new(0.2, 0.3, -0.2, 0.4, -0.6, 0.3);
    let frames = s.robot().frames(&q);
    let c = capsules(s.arm(), &frames)[4];
    let half = 0.08;
    let centre = (c.a + c.b) / 2.0 + Vector3::new(0.0, 1.0, 0.3).normalize() * (c.radius + 0.15);
    let pose = Isometry3::from_parts(
        Translation3::from(centre),
        UnitQuaternion::from_euler_angles(0.3, 0.5, -0.8),
    );
    let o = Obstacle {
        pose,
        ..Obstacle::fixed("turned", Vector3::repeat(-half), Vector3::repeat(half))
    };
    let s = on_table(vec![o]);
    let checker = Checker::new(&s);
    let (margins, gradients) = checker.margins_and_gradients(&q);
    let obstacle = |m: &[stiffid::internal::cell::Margin]| -> Vec<usize> {
        (0..m.len())
            .filter(|&i| m[i].kind == CheckKind::Obstacles && m[i].margin < 0.05)
            .collect()
    };
    let near = obstacle(&margins);
    assert!(!near.is_empty(), "a body within 5 cm of the box");
    let h = 1e-6;
    for &i in &near {
        for a in 0..6 {
            let (mut up, mut down) = (q, q);
            up[a] += h;
            down[a] -= h;
            let fd =
                (checker.margins(&up)[i].margin - checker.margins(&down)[i].margin) / (2.0 * h);
            let g = gradients.gradient(i)[a];
            assert!(
                (g - fd).abs() < 1e-5 * (1.0 + fd.abs()),
                "{i} {a}: {g} {fd}"
            );
        }
    }
}
