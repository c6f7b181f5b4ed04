//! The free track station ([`compensate::path_on_track`]): jointly with the tool rotation, the
//! dynamic programming's optimum equals an exhaustive search over every path of states on a
//! small grid (each state's bound computed independently, at the point moved by hand); no
//! point's bound rises; the loaded tool lands on the part from the chosen station.

use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::machining::compensate::{
    self, Aggregate, Compensated, Free, FreeRange, FreeVariables, Model, Objective, Options,
    PathPoint, Target, Variable,
};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::external::{
    ErrorMotions, ExternalAxes, ExternalAxis, ExternalValues,
};
use stiffid::internal::robot::presets;
use stiffid::{internal::setup, Setup};

/// The FANUC milling example on a track along x (0 to 6 m, pitching 0.2 mrad at its end).
pub(crate) fn on_track() -> Setup {
    let mut track = ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0);
    track.errors = ErrorMotions::new(vec![[0.0, 0.0, 0.0, 0.0, 2e-4, 0.0]]).unwrap();
    let cell = ExternalAxes::new(vec![track]).unwrap();
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let base = setup::parse(text, "milling.toml", |name, _| presets::get(name)).unwrap();
    let robot = base.robot().clone().with_external(Some(cell));
    base.to_builder().with_robot(robot).build().unwrap()
}

/// `n` points of a line along x in the cell (the tool pointing down, a base-frame force), at
/// the station 1.5 m.
pub(crate) fn line(n: usize) -> Vec<PathPoint> {
    (0..n)
        .map(|i| PathPoint {
            line: i as u64 + 2,
            target: Target::Pose(moved(i, 0.0)),
            wrench: Vector6::new(300.0, -200.0, -400.0, 0.0, 0.0, 0.0),
            frame: Frame::Base,
            external: ExternalValues::new(&[1.5]).unwrap(),
        })
        .collect()
}

/// Point `i`'s pose (cell frame) turned by `phi` about its tool z.
fn moved(i: usize, phi: f64) -> Isometry3<f64> {
    let down = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    Isometry3::from_parts(
        Vector3::new(2.6 + 0.05 * i as f64, -0.4, 0.5).into(),
        down * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), phi),
    )
}

/// The free station +-100 mm in 100 mm steps and the free tool axis +-10 deg in 5 deg steps.
fn free(aggregate: Aggregate) -> (Options, Setup) {
    let s = on_track();
    let free = FreeVariables {
        free: vec![
            Free::ToolRotation(crate::compensate::rotation(10.0, 5.0)),
            Free::Station(FreeRange::checked(&Variable::Station, 100.0, 100.0).unwrap()),
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

/// Point `i`'s bound at the station offset `d` (m) and the rotation `phi`, compensated alone at
/// those values (no free variable).
fn bound_at(s: &Setup, points: &[PathPoint], i: usize, (d, phi): (f64, f64)) -> Option<f64> {
    let station = points[i].external.as_slice()[0] + d;
    let p = PathPoint {
        target: Target::Pose(moved(i, phi)),
        external: ExternalValues::new(&[station]).unwrap(),
        ..points[i].clone()
    };
    let compliance = s.model_compliance("test").unwrap();
    let options = Options::for_setup(s);
    let r = compensate::path_on_track(s.arm(), &compliance, &[p], &options).ok()?;
    Some(r[0].budget.bound)
}

/// The least aggregate of the bounds over every path of states (index on the first free axis, a
/// station offset, a table angle or a lead; index on the second, a rotation or a tilt) whose
/// indices change by at most one per point, each point no worse than at its own values (the
/// middle state of each axis: (1, 2) on 3 x 5 states).
pub(crate) fn exhaustive(bounds: &[Vec<Vec<Option<f64>>>], aggregate: Aggregate) -> f64 {
    let n = bounds.len();
    let (first, second) = (bounds[0].len(), bounds[0][0].len());
    let states: Vec<(usize, usize)> = (0..first)
        .flat_map(|k| (0..second).map(move |g| (k, g)))
        .collect();
    let mut best = f64::INFINITY;
    for code in 0..states.len().pow(n as u32) {
        let path: Vec<(usize, usize)> = (0..n)
            .map(|i| states[code / states.len().pow(i as u32) % states.len()])
            .collect();
        let near = |a: usize, b: usize| a.abs_diff(b) <= 1;
        if (path.windows(2)).any(|w| !near(w[0].0, w[1].0) || !near(w[0].1, w[1].1)) {
            continue;
        }
        let values: Option<Vec<f64>> = (0..n)
            .map(|i| {
                let own = bounds[i][first / 2][second / 2]?;
                bounds[i][path[i].0][path[i].1].filter(|b| *b <= own)
            })
            .collect();
        let Some(values) = values else { continue };
        let value = match aggregate {
            Aggregate::Sum => values.iter().sum(),
            Aggregate::Max => values.iter().copied().fold(0.0, f64::max),
        };
        best = best.min(value);
    }
    best
}

/// Asserts the dynamic programming's choice is the exhaustive optimum: the path's value of the
/// `chosen` bounds (m) by `aggregate` equals [`exhaustive`]'s over `bounds` (up to the
/// tie-breaking cost, 1e-6 of a bound per point and variable), and the grid gains over the
/// path's own state `own` (indices into each point's `bounds`).
pub(crate) fn assert_exhaustive_optimum(
    chosen: &[f64],
    bounds: &[Vec<Vec<Option<f64>>>],
    aggregate: Aggregate,
    own: (usize, usize),
) {
    let add = |v: &mut dyn Iterator<Item = f64>| match aggregate {
        Aggregate::Sum => v.sum(),
        Aggregate::Max => v.fold(0.0, f64::max),
    };
    let value = add(&mut chosen.iter().copied());
    let best = exhaustive(bounds, aggregate);
    assert!(
        (value - best).abs() <= 1e-5 * best,
        "{aggregate:?}: {value} against {best}"
    );
    let own_value = add(&mut bounds.iter().map(|b| b[own.0][own.1].unwrap()));
    assert!(
        best < own_value * 0.999,
        "the grid gains: {best} against {own_value}"
    );
}

#[test]
fn the_station_and_rotation_chosen_equal_the_exhaustive_optimum() {
    let points = line(4);
    let (_, s) = free(Aggregate::Max);
    let bounds: Vec<Vec<Vec<Option<f64>>>> = (0..points.len())
        .map(|i| {
            (-1..=1)
                .map(|k| {
                    (-2..=2)
                        .map(|g| {
                            bound_at(
                                &s,
                                &points,
                                i,
                                (0.1 * k as f64, (5.0 * g as f64).to_radians()),
                            )
                        })
                        .collect()
                })
                .collect()
        })
        .collect();
    let compliance = s.model_compliance("test").unwrap();
    for aggregate in [Aggregate::Max, Aggregate::Sum] {
        let (options, s) = free(aggregate);
        let results = compensate::path_on_track(s.arm(), &compliance, &points, &options).unwrap();
        let chosen: Vec<f64> = results.iter().map(|r| r.budget.bound).collect();
        assert_exhaustive_optimum(&chosen, &bounds, aggregate, (1, 2));
    }
}

/// No point's bound rises against the path's own values; the station moves at most one step
/// between points and stays within its range; the loaded tool at the compensated angles, on the
/// carriage at the chosen station, lands on the part's point to 0.1 micrometre.
#[test]
fn no_point_rises_and_the_tool_lands_from_the_chosen_station() {
    let points = line(12);
    let (options, s) = free(Aggregate::Max);
    let compliance = s.model_compliance("test").unwrap();
    let results = compensate::path_on_track(s.arm(), &compliance, &points, &options).unwrap();
    let results: Vec<Compensated> =
        stiffid::internal::machining::cell::path_to_cell(s.robot(), &points, results);
    let cell = s.robot().external().unwrap();
    let model = Model::new(s.arm(), &compliance).unwrap();
    let mut moved_any = false;
    for (i, (p, r)) in points.iter().zip(&results).enumerate() {
        let before = r.bound_before.unwrap();
        assert!(
            r.budget.bound <= before * (1.0 + 1e-9),
            "{i}: {} > {before}",
            r.budget.bound
        );
        let e = r.external.as_slice()[0];
        assert!((e - 1.5).abs() <= 0.1 + 1e-12, "{i}: station {e}");
        moved_any |= (e - 1.5).abs() > 1e-9;
        let carrier = cell.carrier_pose(r.external.as_slice());
        let rotate = carrier.rotation.inverse();
        let f = rotate * r.wrench.fixed_rows::<3>(0).into_owned();
        let w = Vector6::new(f.x, f.y, f.z, 0.0, 0.0, 0.0);
        let loaded = carrier * model.loaded_pose(&r.q_compensated, &w);
        let Target::Pose(target) = &p.target else {
            unreachable!()
        };
        let error = (loaded.translation.vector - target.translation.vector).norm();
        assert!(error < 1e-7, "{i}: {error} m");
    }
    assert!(moved_any, "the station moves somewhere");
    for w in results.windows(2) {
        let step = (w[1].external.as_slice()[0] - w[0].external.as_slice()[0]).abs();
        assert!(step <= 0.1 + 1e-12, "step {step}");
    }
}

/// A robot without a track: the free station is refused naming the option.
#[test]
fn a_free_station_without_a_track_is_refused() {
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
                option: stiffid::JobOption::StationRange,
                ..
            }
        ),
        "{error}"
    );
}

/// The compensate CSV's external columns carry the chosen station, in mm, named as path files
/// name them.
#[test]
fn the_csv_carries_the_chosen_station_in_mm() {
    use stiffid::app::compensate::document::{external_header, external_values};
    let points = line(3);
    let (options, s) = free(Aggregate::Sum);
    let compliance = s.model_compliance("test").unwrap();
    let results = compensate::path_on_track(s.arm(), &compliance, &points, &options).unwrap();
    let cell = s.robot().external();
    assert_eq!(external_header(cell), vec!["e1_mm".to_string()]);
    for r in &results {
        let e = external_values(cell, r);
        assert_eq!(e, vec![Some(r.external.as_slice()[0] * 1e3)]);
    }
    assert!(external_header(None).is_empty());
}
