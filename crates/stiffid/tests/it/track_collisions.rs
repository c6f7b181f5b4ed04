//! Collisions of the moved postures of an arm on a track: the free station's states are checked
//! with the arm on its carriage at the state's station. A box placed where the unchecked
//! optimum's arm stands at one point is never hit by a chosen posture (the cell's checker,
//! independently, at the chosen station), that point's choice changes and no point's bound rises
//! above its own.

use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::cell::{capsules, CheckKind, Checker};
use stiffid::internal::machining::compensate::{
    self, Aggregate, Compensated, Free, FreeVariables, Options, PathPoint, Target,
};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis, ExternalValues};
use stiffid::internal::robot::presets;
use stiffid::internal::setup::{Cell, Obstacle};
use stiffid::{internal::setup, Setup};

/// The FANUC milling example on a track along x (0 to 6 m) in a cell with `obstacles` and a
/// clearance of 10 mm.
fn on_track(obstacles: Vec<Obstacle>) -> Setup {
    let track = ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0);
    in_cell(ExternalAxes::new(vec![track]).unwrap(), obstacles)
}

/// The FANUC milling example with the external axes `cell` in a cell with `obstacles` and a
/// clearance of 10 mm.
pub(crate) fn in_cell(cell: ExternalAxes, obstacles: Vec<Obstacle>) -> Setup {
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let base = setup::parse(text, "milling.toml", |name, _| presets::get(name)).unwrap();
    let robot = base.robot().clone().with_external(Some(cell));
    let cell = Cell {
        floor_z: None,
        clearance: 0.01,
        obstacles,
    };
    (base.to_builder().with_robot(robot))
        .with_cell(cell)
        .build()
        .unwrap()
}

/// `n` points of a line along x in the cell (the tool pointing down, a base-frame force), at
/// the station 1.5 m.
fn line(n: usize) -> Vec<PathPoint> {
    line_at(n, &[1.5])
}

/// [`line`] with the external axes at `e` (SI, the cell's order).
pub(crate) fn line_at(n: usize, e: &[f64]) -> Vec<PathPoint> {
    let down = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    (0..n)
        .map(|i| PathPoint {
            line: i as u64 + 2,
            target: Target::Pose(Isometry3::from_parts(
                Vector3::new(2.6 + 0.05 * i as f64, -0.4, 0.5).into(),
                down,
            )),
            wrench: Vector6::new(300.0, -200.0, -400.0, 0.0, 0.0, 0.0),
            frame: Frame::Base,
            external: ExternalValues::new(e).unwrap(),
        })
        .collect()
}

/// The free station +-500 mm in 100 mm steps, the bound summed.
fn options(s: &Setup) -> Options {
    let free = FreeVariables {
        free: vec![Free::Station(crate::compensate::station(500.0, 100.0))],
        aggregate: Aggregate::Sum,
        ..FreeVariables::default()
    };
    Options {
        free,
        ..Options::for_setup(s)
    }
}

/// Whether posture `q` on the carriage at `e` hits an obstacle or itself, by the cell's checker.
fn collides(checker: &Checker, q: &Vector6<f64>, e: &ExternalValues) -> bool {
    let kinds = [CheckKind::Obstacles, CheckKind::SelfCollision];
    (checker.feasibility_at(q, e.as_slice()).checks.iter())
        .any(|c| kinds.contains(&c.kind) && !c.ok)
}

/// A box of half-size `half` (m) centred at `centre` (cell frame, m).
fn boxed(centre: &Vector3<f64>, half: f64) -> Obstacle {
    Obstacle::fixed("fixture", centre.add_scalar(-half), centre.add_scalar(half))
}

#[test]
fn a_station_that_drives_the_arm_into_a_box_is_not_taken() {
    let points = line(6);
    let open = on_track(Vec::new());
    let compliance = open.model_compliance("test").unwrap();
    let unchecked =
        compensate::path_on_track(open.arm(), &compliance, &points, &options(&open)).unwrap();
    // The point whose station moved farthest from its own.
    let station = |c: &Compensated| c.external.as_slice()[0];
    let (i, far) = (unchecked.iter().enumerate())
        .max_by(|a, b| {
            (station(a.1) - 1.5)
                .abs()
                .total_cmp(&(station(b.1) - 1.5).abs())
        })
        .unwrap();
    assert!((station(far) - 1.5).abs() >= 0.1, "{}", station(far));
    // A box at an end of one of the arm's bodies there (cell frame, on its carriage), as small
    // as it must be to leave every posture of the path's own clear.
    let frames = open.robot().frames_at(&far.q, far.external.as_slice());
    let ends: Vec<Vector3<f64>> = (capsules(open.arm(), &frames).iter())
        .flat_map(|c| [c.a, c.b])
        .collect();
    let own: Vec<Vector6<f64>> = unchecked.iter().map(|c| c.q_before.unwrap()).collect();
    let own_station = ExternalValues::new(&[1.5]).unwrap();
    let s = (ends.iter())
        .flat_map(|e| [0.1, 0.05].map(|half| on_track(vec![boxed(e, half)])))
        .find(|s| {
            let checker = Checker::new(s);
            own.iter().all(|q| !collides(&checker, q, &own_station))
                && collides(&checker, &far.q, &far.external)
        })
        .expect("a box clear of the path's own postures that the unchecked choice hits");
    let checker = Checker::new(&s);
    let out = compensate::path_on_track(s.arm(), &compliance, &points, &options(&s)).unwrap();
    assert_avoided(&out, (i, far), |k, c| {
        assert!(!collides(&checker, &c.q, &c.external), "point {k} collides");
    });
}

/// The checked choice `out` avoids the obstacle the unchecked choice `far` at point `i` hits:
/// every point passes `clear` (its index and its result), no bound rises above the path's own, the checks removed some
/// states and point `i`'s choice changes.
pub(crate) fn assert_avoided(
    out: &[Compensated],
    (i, far): (usize, &Compensated),
    clear: impl Fn(usize, &Compensated),
) {
    let mut removed = 0;
    for (k, c) in out.iter().enumerate() {
        clear(k, c);
        assert!(
            c.budget.bound <= c.bound_before.unwrap() * (1.0 + 1e-9),
            "{k}"
        );
        removed += c.removed.collision;
    }
    assert!(removed > 0, "{removed}");
    assert!(
        out[i].external != far.external || out[i].q != far.q,
        "point {i}'s choice changes"
    );
}
