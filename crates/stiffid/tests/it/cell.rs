//! The cell model: distances against hand-computed cases, known collisions, the cell tables.

use approx::assert_relative_eq;
use nalgebra::Vector3;
use stiffid::internal::cell::{self, Body, Capsule, CheckKind, Checker, Part};
use stiffid::internal::setup::Obstacle;
use stiffid::Error;

use crate::common;
use common::{deg, paper_with};

fn capsule(a: [f64; 3], b: [f64; 3], radius: f64) -> Capsule {
    Capsule {
        part: Part::Tool,
        a: Vector3::from(a),
        b: Vector3::from(b),
        radius,
    }
}

fn unit_box() -> Obstacle {
    Obstacle::fixed(
        "table",
        Vector3::new(-1.0, -1.0, 0.0),
        Vector3::new(1.0, 1.0, 1.0),
    )
}

#[test]
fn a_capsule_over_the_floor_is_its_lowest_end_minus_its_radius() {
    let c = capsule([0.0, 0.0, 1.0], [1.0, 0.0, 0.5], 0.1);
    assert_relative_eq!(
        cell::body_floor(&Body::Capsule(c), 0.2),
        0.2,
        epsilon = 1e-12
    );
    assert_relative_eq!(
        cell::body_floor(&Body::Capsule(c), 0.7),
        -0.3,
        epsilon = 1e-12
    );
}

#[test]
fn capsule_against_a_box_outside_and_inside() {
    let b = unit_box();
    // Above the top face: 2 - 0.5 - 1.
    let above = capsule([0.0, 0.0, 2.0], [0.0, 0.0, 3.0], 0.5);
    assert_relative_eq!(cell::capsule_box(&above, &b), 0.5, epsilon = 1e-9);
    // Beside the +x face, horizontal: 3 - 1 - 0.25.
    let beside = capsule([3.0, -1.0, 0.5], [3.0, 1.0, 0.5], 0.25);
    assert_relative_eq!(cell::capsule_box(&beside, &b), 1.75, epsilon = 1e-9);
    // Past a corner edge: the edge (1, 1, z) to the axis (2, 2, z) is sqrt(2).
    let corner = capsule([2.0, 2.0, 0.2], [2.0, 2.0, 0.8], 0.1);
    assert_relative_eq!(
        cell::capsule_box(&corner, &b),
        2f64.sqrt() - 0.1,
        epsilon = 1e-6
    );
    // Through the box at mid-height: pushed out through the top face, 0.5 + 0.1 deep.
    let through = capsule([-2.0, 0.0, 0.5], [2.0, 0.0, 0.5], 0.1);
    assert_relative_eq!(cell::capsule_box(&through, &b), -0.6, epsilon = 1e-6);
}

#[test]
fn segment_against_a_capsule() {
    // A segment is a capsule of radius 0; two capsules are measured by their segments. Crossing lines 1 apart.
    let segment = capsule([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], 0.0);
    let c = capsule([1.0, 1.0, -1.0], [1.0, 1.0, 1.0], 0.3);
    assert_relative_eq!(
        cell::body_body(&Body::Capsule(segment), &Body::Capsule(c)),
        0.7,
        epsilon = 1e-12
    );
    // Closest at both ends: (1, 0, 0) and (2, 1, 0).
    let short = capsule([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 0.0);
    let far = capsule([2.0, 1.0, 0.0], [2.0, 3.0, 0.0], 0.5);
    assert_relative_eq!(
        cell::body_body(&Body::Capsule(short), &Body::Capsule(far)),
        2f64.sqrt() - 0.5,
        epsilon = 1e-12
    );
    // Overlapping parallel capsules: axes 0.2 apart, radii 0.3 each.
    let a = capsule([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 0.3);
    let b = capsule([0.5, 0.2, 0.0], [2.0, 0.2, 0.0], 0.3);
    assert_relative_eq!(
        cell::body_body(&Body::Capsule(a), &Body::Capsule(b)),
        -0.4,
        epsilon = 1e-12
    );
}

#[test]
fn capsules_follow_the_comau_kinematics() {
    let setup = paper_with("").unwrap();
    let q = deg(&[0.0, 0.0, -90.0, 0.0, 0.0, 0.0]);
    let bodies = cell::capsules(setup.arm(), &setup.robot().frames(&q));
    let base = bodies[0];
    assert_eq!(base.part, Part::Base);
    assert_relative_eq!(base.a, Vector3::zeros(), epsilon = 1e-12);
    assert_relative_eq!(base.b, Vector3::new(0.0, 0.0, 0.83), epsilon = 1e-12);
    // Link 1 reaches joint 2 at (400, 0, 830) mm; the tool starts at the flange (2074, 0, 2255).
    let link1 = bodies.iter().find(|b| b.part == Part::Link(1)).unwrap();
    assert_relative_eq!(link1.b, Vector3::new(0.4, 0.0, 0.83), epsilon = 1e-9);
    let tool = bodies.last().unwrap();
    assert_eq!(tool.part, Part::Tool);
    assert_relative_eq!(tool.a, Vector3::new(2.074, 0.0, 2.255), epsilon = 1e-9);
    assert_relative_eq!((tool.b - tool.a).norm(), 0.26, epsilon = 1e-9);
    // Default radii: fractions of the summed segment lengths (4.329 m), the tool half as wide as
    // the reflectors are off its axis (80 sqrt 2 mm).
    let size = 0.83 + 0.4 + 1.175 + 0.25 + 1.444 + 0.23;
    assert_relative_eq!(setup.geometry().link_radii[0], 0.08 * size, epsilon = 1e-9);
    assert_relative_eq!(setup.geometry().link_radii[6], 0.02 * size, epsilon = 1e-9);
    assert_relative_eq!(
        setup.geometry().tool_radius,
        0.04 * 2f64.sqrt(),
        epsilon = 1e-12
    );
}

#[test]
fn a_tool_in_the_floor_is_infeasible_naming_the_bodies() {
    let setup = paper_with("\n[cell]\nfloor_z_mm = 0.0\nclearance_mm = 50.0\n").unwrap();
    // Upper arm 40 deg forward, forearm pointing 80 deg below the horizontal: the wrist dips into
    // the floor.
    let f = cell::feasibility(&setup, &deg(&[0.0, 40.0, -170.0, 0.0, 0.0, 0.0]));
    assert!(!f.feasible());
    let floor = f.violations().find(|c| c.kind == CheckKind::Floor).unwrap();
    assert_eq!(floor.between.1, "floor");
    assert!(["tool", "link 6", "link 5"].contains(&floor.between.0.as_str()));
    assert!(floor.clearance.unwrap() < 0.0);
    // The arm stretched up, wrist bent: clear of the floor and of itself.
    let ok = cell::feasibility(&setup, &deg(&[0.0, 0.0, -90.0, 0.0, 45.0, 0.0]));
    assert!(ok.feasible(), "{ok:?}");
    assert!(ok.min_clearance().unwrap() >= 0.05);
}

#[test]
fn a_forearm_down_the_column_is_a_self_collision() {
    let setup = paper_with("\n[cell]\nclearance_mm = 50.0\n").unwrap();
    // Upper arm 50 deg back, forearm pointing 80 deg down: the forearm runs into the column.
    let f = cell::feasibility(&setup, &deg(&[0.0, -50.0, -170.0, 0.0, 0.0, 0.0]));
    let c = f.violations().next().unwrap();
    assert_eq!(c.kind, CheckKind::SelfCollision);
    assert!(["base", "link 1"].contains(&c.between.0.as_str()), "{c:?}");
    assert!(["link 4", "tool"].contains(&c.between.1.as_str()), "{c:?}");
    // The same arm with the forearm level is clear.
    assert!(cell::feasibility(&setup, &deg(&[0.0, -50.0, -90.0, 0.0, 0.0, 0.0])).feasible());
}

#[test]
fn an_obstacle_and_a_tracker_block_and_name() {
    let setup = paper_with(
        "\n[cell]\nclearance_mm = 50.0\n[[cell.obstacle]]\nname = \"table\"\nmin_mm = [1800, -500, 0]\nmax_mm = [2600, 500, 2200]\n[tracker]\nposition_mm = [3000.0, 0.0, 1000.0]\n",
    )
    .unwrap();
    let f = cell::feasibility(&setup, &deg(&[0.0, 0.0, -90.0, 0.0, 0.0, 0.0]));
    let obstacles = f
        .checks
        .iter()
        .find(|c| c.kind == CheckKind::Obstacles)
        .unwrap();
    assert!(!obstacles.ok);
    assert_eq!(obstacles.between.1, "table");
    let sight = f
        .checks
        .iter()
        .find(|c| c.kind == CheckKind::LineOfSight)
        .unwrap();
    assert!(!sight.ok);
    assert_eq!(sight.between.1, "table");
}

#[test]
fn impossible_constraints_are_reported() {
    // 100 m: the highest the limits accept (stiffid::internal::common::limits::LENGTH_MM), far out of reach.
    let setup = paper_with("\n[constraints]\nloading_point_min_z_mm = 1e5\n").unwrap();
    let checker = Checker::new(&setup);
    let f = checker.feasibility(&deg(&[0.0, 0.0, -90.0, 0.0, 0.0, 0.0]));
    let c = f.violations().next().unwrap();
    assert_eq!(c.kind, CheckKind::LoadingPointHeight);
    assert!(c.margin < -90.0);
    assert!(checker.violation(&deg(&[0.0, 0.0, -90.0, 0.0, 0.0, 0.0])) > 90.0);
}

#[test]
fn bad_cell_fields_are_named_with_their_values() {
    let cases = [
        ("[cell]\nclearance_mm = -5\n", "cell.clearance_mm", "-5"),
        ("[cell]\nfloor_z_mm = nan\n", "cell.floor_z_mm", "NaN"),
        (
            "[[cell.obstacle]]\nname = \"t\"\nmin_mm = [0, 0, 0]\nmax_mm = [1, -1, 1]\n",
            "cell.obstacle[1]",
            "[1, -1, 1]",
        ),
        ("[robot_geometry]\ntool_radius_mm = 0\n", "robot_geometry.tool_radius_mm", "0"),
        (
            "[robot_geometry]\nlink_radius_mm = [1, 2, 3, 4, 5, 6, 1e9]\n",
            "link_radius_mm[7]",
            "1e9",
        ),
        ("[tracker]\nposition_mm = [0, 0, 0]\nmax_incidence_deg = 95\n", "max_incidence_deg", "95"),
        (
            "[tracker]\nposition_mm = [0, 0, 0]\nmeasuring_normals = [[0, 0, 1]]\n",
            "measuring_normals",
            "1 given",
        ),
        (
            "[tracker]\nposition_mm = [0, 0, 0]\nmeasuring_normals = [[0, 0, 1], [0, 0, 0], [0, 0, 1], [0, 0, 1]]\n",
            "measuring_normals[2]",
            "[0, 0, 0]",
        ),
    ];
    for (extra, field, value) in cases {
        match paper_with(&format!("\n{extra}")) {
            Err(Error::InvalidField { field: f, message }) => {
                assert!(f.contains(field), "{f} for {extra}");
                assert!(message.contains(value), "{message} for {extra}");
            }
            other => panic!("{extra}: {other:?}"),
        }
    }
    let inside = "\n[[cell.obstacle]]\nname = \"stand\"\nmin_mm = [0, 0, 0]\nmax_mm = [1000, 1000, 1000]\n[tracker]\nposition_mm = [500, 500, 500]\n";
    let e = paper_with(inside).unwrap_err().to_string();
    assert!(e.contains("inside obstacle 'stand'"), "{e}");
}

/// The paper setup in the cell with three reflectors 40 mm off the flange axis, below the loading
/// point, and `extra` appended.
fn close_reflectors(extra: &str) -> stiffid::internal::setup::Setup {
    let text = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165").unwrap();
    let start = text.find("measuring_points_mm = [").unwrap();
    let end = start + text[start..].find("\n]\n").unwrap() + 3;
    let points = "measuring_points_mm = [[40.0, 0.0, 150.0], [-20.0, 34.641, 150.0], [-20.0, -34.641, 150.0]]\n";
    let text = format!(
        "{}{points}{}{}{extra}",
        &text[..start],
        &text[end..],
        common::PAPER_CELL
    );
    stiffid::internal::setup::parse(&text, "close.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap()
}

/// The default tool body is half as wide as the nearest reflector is off the flange axis: no
/// reflector lies inside it, and the tracker sees all three in many postures, where a body that
/// held every tool point (150 mm, the loading point's distance) hides them in every posture.
#[test]
fn the_default_tool_body_leaves_the_reflectors_outside() {
    let setup = close_reflectors("");
    assert_relative_eq!(setup.geometry().tool_radius, 0.02, epsilon = 1e-6);
    let wide = close_reflectors("[robot_geometry]\ntool_radius_mm = 150.0\n");
    let seen = |s: &stiffid::internal::setup::Setup| {
        let checker = Checker::new(s);
        let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(7);
        (0..500)
            .filter(|_| {
                let q = nalgebra::Vector6::from_fn(|a, _| {
                    rand::Rng::random_range(&mut rng, s.bounds().lower[a]..=s.bounds().upper[a])
                });
                let f = checker.feasibility(&q);
                f.checks
                    .iter()
                    .any(|c| c.kind == CheckKind::LineOfSight && c.ok)
            })
            .count()
    };
    let frames = setup.robot().frames(&nalgebra::Vector6::zeros());
    let tool = cell::capsules(setup.arm(), &frames)
        .into_iter()
        .find(|c| c.part == Part::Tool)
        .unwrap();
    for p in &setup.tool().measuring_points {
        let at = frames.point(p);
        assert!(
            distance_to_segment(&at, &tool.a, &tool.b) > tool.radius,
            "{p}"
        );
    }
    let (narrow, hidden) = (seen(&setup), seen(&wide));
    assert!(narrow >= 50, "{narrow} of 500");
    assert_eq!(hidden, 0);
}

fn distance_to_segment(p: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
    (a + ab * t - p).norm()
}
