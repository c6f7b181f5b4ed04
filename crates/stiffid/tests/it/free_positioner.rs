//! The free positioner ([`Options::free_positioner`]): the turntable's angle chosen jointly with
//! the tool rotation; the dynamic programming's optimum equals an exhaustive search over every
//! path of states on a small grid (each state's bound computed independently, at the part's
//! point turned by hand); no point's bound rises; the loaded tool lands on the part's point
//! where the table turned it; a cell without a positioner is refused naming the option.

use nalgebra::{Isometry3, Rotation3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::machining::compensate::{
    self, Aggregate, Compensated, Free, FreeRange, FreeVariables, Model, Objective, Options,
    PathPoint, Target, Variable,
};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis, ExternalValues};
use stiffid::internal::robot::presets;
use stiffid::{internal::setup, Setup};

/// The table's axis: vertical through (2.7, -0.4, 0) m.
const TABLE: [f64; 3] = [2.7, -0.4, 0.0];

/// The FANUC milling example on a track along x (0 to 6 m), the part on a turntable (-30 to 30
/// deg; a travel that ends inside the grid below for the points at its end).
fn on_table() -> Setup {
    let limit = 30f64.to_radians();
    let cell = ExternalAxes::new(vec![
        ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0),
        ExternalAxis::rotary(
            "table",
            Vector3::from(TABLE),
            Vector3::z_axis(),
            -limit,
            limit,
        ),
    ])
    .unwrap();
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let base = setup::parse(text, "milling.toml", |name, _| presets::get(name)).unwrap();
    let robot = base.robot().clone().with_external(Some(cell));
    base.to_builder().with_robot(robot).build().unwrap()
}

/// The force of every point, cell frame at the table's own angle, N.
const FORCE: [f64; 3] = [300.0, -200.0, -400.0];

/// `n` points of a line along x on the part (the tool pointing down), at the station 1.5 m and
/// the table at [`table`].
fn line(n: usize) -> Vec<PathPoint> {
    (0..n)
        .map(|i| PathPoint {
            line: i as u64 + 2,
            target: Target::Pose(moved(i, 0.0)),
            wrench: Vector6::new(FORCE[0], FORCE[1], FORCE[2], 0.0, 0.0, 0.0),
            frame: Frame::Base,
            external: ExternalValues::new(&[1.5, table(i)]).unwrap(),
        })
        .collect()
}

/// Point `i`'s own table angle, rad: 0, but 25 deg for the last of four.
fn table(i: usize) -> f64 {
    match i {
        3 => 25f64.to_radians(),
        _ => 0.0,
    }
}

/// Point `i`'s pose (the part's frame at e = 0, cell coordinates) turned by `phi` about its
/// tool z.
fn moved(i: usize, phi: f64) -> Isometry3<f64> {
    let down = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    Isometry3::from_parts(
        Vector3::new(2.6 + 0.05 * i as f64, -0.4, 0.5).into(),
        down * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), phi),
    )
}

/// The free positioner +-10 deg in 10 deg steps and the free tool axis +-10 deg in 5 deg steps.
fn free(aggregate: Aggregate) -> (Options, Setup) {
    let s = on_table();
    let free = FreeVariables {
        free: vec![
            Free::ToolRotation(crate::compensate::rotation(10.0, 5.0)),
            Free::Positioner(FreeRange::checked(&Variable::Positioner, 10.0, 10.0).unwrap()),
        ],
        minimise: Objective::Bound,
        aggregate,
    };
    let options = Options {
        free,
        ..Options::for_setup(&s)
    };
    (options, s)
}

/// Point `i`'s bound with the table `d` (rad) from its own and the tool turned by `phi`,
/// compensated alone at those values (no free variable): the part's point where the table
/// turns it, the force turned with the part; `None` outside the table's travel.
fn bound_at(s: &Setup, points: &[PathPoint], i: usize, (d, phi): (f64, f64)) -> Option<f64> {
    let angle = table(i) + d;
    if angle.abs() > 30f64.to_radians() + 1e-12 {
        return None;
    }
    let turn = Rotation3::from_axis_angle(&Vector3::z_axis(), d);
    let f = turn * Vector3::from(FORCE);
    let p = PathPoint {
        target: Target::Pose(moved(i, phi)),
        external: ExternalValues::new(&[1.5, angle]).unwrap(),
        wrench: Vector6::new(f.x, f.y, f.z, 0.0, 0.0, 0.0),
        ..points[i].clone()
    };
    let compliance = s.model_compliance("test").unwrap();
    let options = Options::for_setup(s);
    let r = compensate::path_on_track(s.arm(), &compliance, &[p], &options).ok()?;
    Some(r[0].budget.bound)
}

/// The optimum by enumeration: [`crate::free_station::exhaustive`] over (table angle index,
/// rotation index) states.
#[test]
fn the_table_angle_and_rotation_chosen_equal_the_exhaustive_optimum() {
    let points = line(4);
    let (_, s) = free(Aggregate::Max);
    let bounds: Vec<Vec<Vec<Option<f64>>>> = (0..points.len())
        .map(|i| {
            (-1..=1)
                .map(|k| {
                    (-2..=2)
                        .map(|g| {
                            let d = (10.0 * k as f64).to_radians();
                            bound_at(&s, &points, i, (d, (5.0 * g as f64).to_radians()))
                        })
                        .collect()
                })
                .collect()
        })
        .collect();
    // The last point's table cannot turn 10 deg further (35 deg is beyond its travel).
    assert!(bounds[3][2].iter().all(Option::is_none));
    let compliance = s.model_compliance("test").unwrap();
    for aggregate in [Aggregate::Max, Aggregate::Sum] {
        let (options, s) = free(aggregate);
        let results = compensate::path_on_track(s.arm(), &compliance, &points, &options).unwrap();
        let chosen: Vec<f64> = results.iter().map(|r| r.budget.bound).collect();
        crate::free_station::assert_exhaustive_optimum(&chosen, &bounds, aggregate, (1, 2));
    }
}

/// No point's bound rises against the path's own values; the table turns at most one step
/// between points and stays within its range and travel; the loaded tool at the compensated
/// angles lands on the part's point where the chosen angle turned it, to 0.1 micrometre.
#[test]
fn no_point_rises_and_the_tool_lands_on_the_turned_part() {
    let points = line(4);
    let (options, s) = free(Aggregate::Max);
    let compliance = s.model_compliance("test").unwrap();
    let results = compensate::path_on_track(s.arm(), &compliance, &points, &options).unwrap();
    let results: Vec<Compensated> =
        stiffid::internal::machining::cell::path_to_cell(s.robot(), &points, results);
    let cell = s.robot().external().unwrap();
    let model = Model::new(s.arm(), &compliance).unwrap();
    let mut turned_any = false;
    for (i, (p, r)) in points.iter().zip(&results).enumerate() {
        let before = r.bound_before.unwrap();
        assert!(r.budget.bound <= before * (1.0 + 1e-9), "{i}");
        let e = r.external.as_slice();
        assert_eq!(e[0], 1.5, "{i}: the station is not free");
        let d = e[1] - table(i);
        assert!(d.abs() <= 10f64.to_radians() + 1e-12, "{i}: {d}");
        assert!(e[1].abs() <= 30f64.to_radians() + 1e-12, "{i}: {}", e[1]);
        turned_any |= d.abs() > 1e-9;
        let carrier = cell.carrier_pose(e);
        let f = carrier.rotation.inverse() * r.wrench.fixed_rows::<3>(0).into_owned();
        let w = Vector6::new(f.x, f.y, f.z, 0.0, 0.0, 0.0);
        let loaded = carrier * model.loaded_pose(&r.q_compensated, &w);
        let Target::Pose(target) = &p.target else {
            unreachable!()
        };
        let on_part = cell.positioner_pose(e) * target;
        let error = (loaded.translation.vector - on_part.translation.vector).norm();
        assert!(error < 1e-7, "{i}: {error} m");
        // The force turned with the part: the table's change about z.
        let turn = Rotation3::from_axis_angle(&Vector3::z_axis(), d);
        let expected = turn * Vector3::from(FORCE);
        assert!(
            (r.wrench.fixed_rows::<3>(0) - expected).norm() < 1e-9,
            "{i}"
        );
    }
    assert!(turned_any, "the table turns somewhere");
    let offsets: Vec<f64> = (results.iter().enumerate())
        .map(|(i, r)| r.external.as_slice()[1] - table(i))
        .collect();
    for w in offsets.windows(2) {
        assert!(
            (w[1] - w[0]).abs() <= 10f64.to_radians() + 1e-12,
            "{offsets:?}"
        );
    }
}

/// A cell without a positioner: the free positioner is refused naming the option.
#[test]
fn a_free_positioner_without_a_positioner_is_refused() {
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let s = setup::parse(text, "milling.toml", |name, _| presets::get(name)).unwrap();
    let (options, _) = free(Aggregate::Sum);
    let mut points = line(2);
    for p in &mut points {
        p.external = ExternalValues::NONE;
    }
    let compliance = s.model_compliance("test").unwrap();
    let error = compensate::path_on_track(s.arm(), &compliance, &points, &options).unwrap_err();
    assert!(
        matches!(
            error,
            stiffid::Error::InvalidOption {
                option: stiffid::JobOption::PositionerRange,
                ..
            }
        ),
        "{error}"
    );
}
