//! The map over the track station ([`MapVariable::Track`]): every cell equals a compensation of
//! that point alone at that station (its bound and deflection); stations beyond the travel are
//! empty; the collision distance equals the feasibility checker's clearance to the floor and the
//! obstacles of a fixed-base robot whose cell is moved by the station (the arm on its carriage
//! sees the cell move the other way), and the checker's of the robot on its track at the
//! station.

use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::cell::{CheckKind, Checker};
use stiffid::internal::machining::cell::on_carriage;
use stiffid::internal::machining::compensate::{
    self, ChosenValues, Free, FreeVariables, MapVariable, Options, PathPoint, Target,
};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis, ExternalValues};
use stiffid::internal::robot::presets;
use stiffid::internal::setup::{Cell, Obstacle};
use stiffid::{internal::setup, Setup};

/// A floor 0.3 m below the base and a box beside the path, in the cell frame.
fn cell_at(shift: f64) -> Cell {
    Cell {
        floor_z: Some(-0.3),
        clearance: 0.0,
        obstacles: vec![Obstacle::fixed(
            "fixture",
            Vector3::new(2.0 - shift, 0.4, -0.3),
            Vector3::new(2.3 - shift, 0.9, 0.6),
        )],
    }
}

/// The FANUC milling example with the cell of [`cell_at`]; on a track along x (1.45 to 6 m)
/// when `track`.
fn milling(track: bool, shift: f64) -> Setup {
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let base = setup::parse(text, "milling.toml", |name, _| presets::get(name)).unwrap();
    let cell = ExternalAxes::new(vec![ExternalAxis::linear(
        "track",
        Vector3::x_axis(),
        1.45,
        6.0,
    )])
    .unwrap();
    let robot = base.robot().clone().with_external(track.then_some(cell));
    (base.to_builder().with_robot(robot))
        .with_cell(cell_at(shift))
        .build()
        .unwrap()
}

/// `n` points of a line along x in the cell (the tool pointing down, a base-frame force), at the
/// station 1.5 m.
fn line(n: usize) -> Vec<PathPoint> {
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
            external: ExternalValues::new(&[1.5]).unwrap(),
        })
        .collect()
}

/// Every point at its own values: the path's own rotation, lean and external values.
fn own_values(points: &[PathPoint]) -> Vec<ChosenValues> {
    (points.iter())
        .map(|p| ChosenValues {
            external: p.external,
            ..Default::default()
        })
        .collect()
}

#[test]
fn every_cell_of_the_track_map_is_a_compensation_at_its_station() {
    let s = milling(true, 0.0);
    let compliance = s.model_compliance("test").unwrap();
    let points = line(3);
    let placed: Vec<PathPoint> = (points.iter())
        .map(|p| on_carriage(s.robot(), p.clone()).unwrap())
        .collect();
    let options = Options {
        map: true,
        map_over: MapVariable::Track,
        free: FreeVariables {
            free: vec![Free::Station(crate::compensate::station(100.0, 50.0))],
            ..FreeVariables::default()
        },
        ..Options::for_setup(&s)
    };
    let own = own_values(&placed);
    let m = compensate::map(
        s.arm(),
        &compliance,
        &placed,
        (&options, s.cell()),
        (&own, false),
    );
    let m = m.unwrap();
    assert_eq!(m.variable, MapVariable::Track);
    assert!(m.angles.is_empty());
    let expected = [-0.1, -0.05, 0.0, 0.05, 0.1];
    assert_eq!(m.stations.len(), expected.len());
    for (a, b) in m.stations.iter().zip(expected) {
        assert!((a - b).abs() < 1e-15);
    }
    assert_eq!((m.bound.nrows(), m.bound.ncols()), (3, 5));
    let collision = m.collision_distance.as_ref().unwrap();
    let plain = Options::for_setup(&s);
    for (i, p) in points.iter().enumerate() {
        for (k, d) in m.stations.iter().enumerate() {
            let station = 1.5 + d;
            if station < 1.45 {
                // Beyond the travel: empty.
                assert!(m.bound[(i, k)].is_nan() && collision[(i, k)].is_nan());
                continue;
            }
            let alone = PathPoint {
                external: ExternalValues::new(&[station]).unwrap(),
                ..p.clone()
            };
            let r = compensate::path_on_track(s.arm(), &compliance, &[alone], &plain).unwrap();
            let r = &r[0];
            // The map's bound leaves out the Newton steps' residual (below 0.1 um).
            assert!(
                (m.bound[(i, k)] - r.budget.bound).abs() <= 1e-7,
                "{i} {d}: {} against {}",
                m.bound[(i, k)],
                r.budget.bound
            );
            let deflection = r.deflection.fixed_rows::<3>(0).norm();
            assert!((m.deflection[(i, k)] - deflection).abs() <= 1e-12 + 1e-9 * deflection);
            // The checker of a fixed-base robot, its cell moved back by the station.
            let fixed = milling(false, station);
            let f = stiffid::internal::cell::feasibility(&fixed, &r.q);
            let clearance = (f.checks.iter())
                .filter(|c| matches!(c.kind, CheckKind::Floor | CheckKind::Obstacles))
                .filter_map(|c| c.clearance)
                .fold(f64::INFINITY, f64::min);
            assert!(
                (collision[(i, k)] - clearance).abs() <= 1e-9,
                "{i} {d}: {} against the checker's {clearance}",
                collision[(i, k)]
            );
            // The checker of the robot on its track, the arm on its carriage at the station.
            let at = Checker::new(&s).feasibility_at(&r.q, &[station]);
            let on_track = (at.checks.iter())
                .filter(|c| matches!(c.kind, CheckKind::Floor | CheckKind::Obstacles))
                .filter_map(|c| c.clearance)
                .fold(f64::INFINITY, f64::min);
            assert!((collision[(i, k)] - on_track).abs() <= 1e-9, "{i} {d}");
        }
    }
    // The stations differ: the map is not one column repeated.
    let spread = (0..5)
        .filter_map(|k| Some(collision[(2, k)]).filter(|v| v.is_finite()))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    assert!(spread.1 - spread.0 > 1e-3, "{spread:?}");
}

/// A robot without a track: the track map is refused naming `--map` (not the free station,
/// which was not given).
#[test]
fn a_track_map_without_a_track_is_refused() {
    let s = milling(false, 0.0);
    let compliance = s.model_compliance("test").unwrap();
    let mut points = line(2);
    for p in &mut points {
        p.external = ExternalValues::NONE;
    }
    let options = Options {
        map: true,
        map_over: MapVariable::Track,
        ..Options::for_setup(&s)
    };
    let own = own_values(&points);
    let at = (&options, s.cell());
    let error = compensate::map(s.arm(), &compliance, &points, at, (&own, false)).unwrap_err();
    assert!(
        matches!(
            error,
            stiffid::Error::InvalidOption {
                option: stiffid::JobOption::Map,
                ..
            }
        ),
        "{error}"
    );
}
