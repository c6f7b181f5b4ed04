//! The free tilt ([`Options::free_tilt`]): a two-axis positioner's first axis chosen jointly
//! with the tool rotation; the dynamic programming's optimum equals the shared exhaustive search
//! over every path of states on a small grid (each state's bound computed independently, at the
//! part's point tilted by hand); no point's bound rises; the loaded tool lands on the part's
//! point where the tilt put it; a one-axis positioner is refused naming the option.

use nalgebra::{Isometry3, Rotation3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::machining::compensate::{
    self, Aggregate, Compensated, Free, FreeRange, FreeVariables, Model, Objective, Options,
    PathPoint, Target, Variable,
};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis, ExternalValues};
use stiffid::internal::robot::presets;
use stiffid::{internal::setup, Setup};

/// The positioner's axes' point: (2.7, -0.4, 0) m.
const AXES: [f64; 3] = [2.7, -0.4, 0.0];

/// The tilt's travel, rad: +-30 deg (it ends inside the grid below for the last point).
fn travel() -> f64 {
    30f64.to_radians()
}

/// The FANUC milling example on a track along x (0 to 6 m), the part on a tilt-rotate table:
/// the tilt about x, the table about its own z (the tilt's second axis), both through
/// [`AXES`]; with the tilt alone when `tilt_only` (a one-axis positioner).
fn on_tilt_table(tilt_only: bool) -> Setup {
    let point = Vector3::from(AXES);
    let mut axes = vec![
        ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0),
        ExternalAxis::rotary("tilt", point, Vector3::x_axis(), -travel(), travel()),
    ];
    if !tilt_only {
        let limit = std::f64::consts::PI;
        axes.push(ExternalAxis::rotary(
            "table",
            point,
            Vector3::z_axis(),
            -limit,
            limit,
        ));
    }
    let cell = ExternalAxes::new(axes).unwrap();
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let base = setup::parse(text, "milling.toml", |name, _| presets::get(name)).unwrap();
    let robot = base.robot().clone().with_external(Some(cell));
    base.to_builder().with_robot(robot).build().unwrap()
}

/// The force of every point, cell frame at the tilt's own angle, N.
const FORCE: [f64; 3] = [300.0, -200.0, -400.0];

/// Point `i`'s own tilt, rad: 0, but 25 deg for the last of four.
fn tilt(i: usize) -> f64 {
    match i {
        3 => 25f64.to_radians(),
        _ => 0.0,
    }
}

/// `n` points of a line along x on the part (the tool pointing down), at the station 1.5 m,
/// the tilt at [`tilt`] and the table at 0.
fn line(n: usize) -> Vec<PathPoint> {
    (0..n)
        .map(|i| PathPoint {
            line: i as u64 + 2,
            target: Target::Pose(moved(i, 0.0)),
            wrench: Vector6::new(FORCE[0], FORCE[1], FORCE[2], 0.0, 0.0, 0.0),
            frame: Frame::Base,
            external: ExternalValues::new(&[1.5, tilt(i), 0.0]).unwrap(),
        })
        .collect()
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

/// The free tilt +-10 deg in 10 deg steps and the free tool axis +-10 deg in 5 deg steps.
fn free(s: &Setup, aggregate: Aggregate) -> Options {
    let free = FreeVariables {
        free: vec![
            Free::ToolRotation(crate::compensate::rotation(10.0, 5.0)),
            Free::Tilt(FreeRange::checked(&Variable::Tilt, 10.0, 10.0).unwrap()),
        ],
        minimise: Objective::Bound,
        aggregate,
    };
    Options {
        free,
        ..Options::for_setup(s)
    }
}

/// Point `i`'s bound with the tilt `d` (rad) from its own and the tool turned by `phi`,
/// compensated alone at those values (no free variable): the part's point where the tilt
/// moves it, the force turned with the part (about x); `None` beyond the tilt's travel.
fn bound_at(s: &Setup, points: &[PathPoint], i: usize, (d, phi): (f64, f64)) -> Option<f64> {
    let angle = tilt(i) + d;
    if angle.abs() > travel() + 1e-12 {
        return None;
    }
    let f = Rotation3::from_axis_angle(&Vector3::x_axis(), d) * Vector3::from(FORCE);
    let p = PathPoint {
        target: Target::Pose(moved(i, phi)),
        external: ExternalValues::new(&[1.5, angle, 0.0]).unwrap(),
        wrench: Vector6::new(f.x, f.y, f.z, 0.0, 0.0, 0.0),
        ..points[i].clone()
    };
    let compliance = s.model_compliance("test").unwrap();
    let r = compensate::path_on_track(s.arm(), &compliance, &[p], &Options::for_setup(s)).ok()?;
    Some(r[0].budget.bound)
}

#[test]
fn the_tilt_and_rotation_chosen_equal_the_exhaustive_optimum() {
    let points = line(4);
    let s = on_tilt_table(false);
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
    // The last point cannot tilt 10 deg further (35 deg is beyond the travel).
    assert!(bounds[3][2].iter().all(Option::is_none));
    let compliance = s.model_compliance("test").unwrap();
    for aggregate in [Aggregate::Max, Aggregate::Sum] {
        let options = free(&s, aggregate);
        let results = compensate::path_on_track(s.arm(), &compliance, &points, &options).unwrap();
        let chosen: Vec<f64> = results.iter().map(|r| r.budget.bound).collect();
        crate::free_station::assert_exhaustive_optimum(&chosen, &bounds, aggregate, (1, 2));
    }
}

/// No point's bound rises against the path's own values; the tilt moves at most one step
/// between points within its range and travel, the station and the table stay; the loaded tool
/// at the compensated angles lands on the part's point where the chosen tilt put it, to 0.1
/// micrometre.
#[test]
fn no_point_rises_and_the_tool_lands_on_the_tilted_part() {
    let points = line(4);
    let s = on_tilt_table(false);
    let options = free(&s, Aggregate::Max);
    let compliance = s.model_compliance("test").unwrap();
    let results = compensate::path_on_track(s.arm(), &compliance, &points, &options).unwrap();
    let results: Vec<Compensated> =
        stiffid::internal::machining::cell::path_to_cell(s.robot(), &points, results);
    let cell = s.robot().external().unwrap();
    let model = Model::new(s.arm(), &compliance).unwrap();
    let mut tilted_any = false;
    for (i, (p, r)) in points.iter().zip(&results).enumerate() {
        assert!(
            r.budget.bound <= r.bound_before.unwrap() * (1.0 + 1e-9),
            "{i}"
        );
        let e = r.external.as_slice();
        assert_eq!(
            (e[0], e[2]),
            (1.5, 0.0),
            "{i}: the station and the table stay"
        );
        let d = e[1] - tilt(i);
        assert!(d.abs() <= 10f64.to_radians() + 1e-12, "{i}: {d}");
        assert!(e[1].abs() <= travel() + 1e-12, "{i}: {}", e[1]);
        tilted_any |= d.abs() > 1e-9;
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
        let expected = Rotation3::from_axis_angle(&Vector3::x_axis(), d) * Vector3::from(FORCE);
        assert!(
            (r.wrench.fixed_rows::<3>(0) - expected).norm() < 1e-9,
            "{i}"
        );
    }
    assert!(tilted_any, "the tilt moves somewhere");
    let offsets: Vec<f64> = (results.iter().enumerate())
        .map(|(i, r)| r.external.as_slice()[1] - tilt(i))
        .collect();
    for w in offsets.windows(2) {
        assert!(
            (w[1] - w[0]).abs() <= 10f64.to_radians() + 1e-12,
            "{offsets:?}"
        );
    }
}

/// A one-axis positioner: the free tilt is refused naming the option.
#[test]
fn a_free_tilt_on_a_one_axis_positioner_is_refused() {
    let s = on_tilt_table(true);
    let options = free(&s, Aggregate::Sum);
    let mut points = line(2);
    for p in &mut points {
        p.external = ExternalValues::new(&[1.5, 0.0]).unwrap();
    }
    let compliance = s.model_compliance("test").unwrap();
    let error = compensate::path_on_track(s.arm(), &compliance, &points, &options).unwrap_err();
    assert!(
        matches!(
            error,
            stiffid::Error::InvalidOption {
                option: stiffid::JobOption::TiltRange,
                ..
            }
        ),
        "{error}"
    );
}
