//! The map holds every other free variable at the value the compensation chose
//! ([`ChosenValues`]): the cell of the value chosen is the compensated point's bound (the
//! map's bound leaves out the Newton steps' residual, the budget's `left`), with the lean
//! free beside the rotation on a fixed base (through the compensate job) and beside the
//! station and the rotation on a track.

use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use stiffid::app::compensate::{run, Input, Request};
use stiffid::internal::machining::cell::on_carriage;
use stiffid::internal::machining::compensate::{
    self, Aggregate, ChosenValues, Compensated, Free, FreeVariables, LeadTilt, MapVariable,
    Objective, Options, PathPoint, Target,
};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis, ExternalValues};
use stiffid::internal::robot::presets;
use stiffid::{internal::setup, Error, Setup};

/// The FANUC milling example; on a track along x (1.45 to 6 m) when `track`.
fn milling(track: bool) -> Setup {
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let base = setup::parse(text, "milling.toml", |name, _| presets::get(name)).unwrap();
    if !track {
        return base;
    }
    let axis = ExternalAxis::linear("track", Vector3::x_axis(), 1.45, 6.0);
    let robot = (base.robot().clone()).with_external(Some(ExternalAxes::new(vec![axis]).unwrap()));
    base.to_builder().with_robot(robot).build().unwrap()
}

/// The rotation (5 deg steps within +-30 deg) and the lean (a 10 deg cone, 2.5 deg steps)
/// free, minimising the summed bound.
fn free(s: &Setup) -> Options {
    let free = FreeVariables {
        free: vec![
            Free::ToolRotation(crate::compensate::rotation(30.0, 5.0)),
            Free::LeadTilt(LeadTilt::checked(Some(10.0), 2.5).unwrap()),
        ],
        minimise: Objective::Bound,
        aggregate: Aggregate::Sum,
    };
    Options {
        free,
        map: true,
        ..Options::for_setup(s)
    }
}

/// The index of `value` among `grid` (to 1e-12).
fn index(grid: &[f64], value: f64) -> usize {
    grid.iter()
        .position(|g| (g - value).abs() <= 1e-12)
        .unwrap_or_else(|| panic!("{value} not on the grid {grid:?}"))
}

/// Asserts that the map's cell of each point's chosen value is its bound without the residual,
/// to 1e-9 mm.
fn assert_chosen_cells(map: &compensate::Map, grid: &[f64], results: &[Compensated]) {
    assert_eq!(map.chosen.len(), results.len());
    for (i, r) in results.iter().enumerate() {
        let g = index(grid, map.chosen[i]);
        let expected = r.budget.bound - r.budget.left;
        assert!(
            (map.bound[(i, g)] - expected).abs() <= 1e-12,
            "point {i}: the map {} m against the point's {expected} m",
            map.bound[(i, g)]
        );
    }
}

#[test]
fn the_rotation_map_holds_the_chosen_lean_and_its_chosen_cells_are_the_bounds() {
    let s = milling(false);
    let mut text = String::from("x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n\n");
    for i in 0..6 {
        text += &format!("{},-800,400,180,0,0,-300,200,-250\n", 1300 + 50 * i);
    }
    let request = Request {
        names: Default::default(),
        setup: &s,
        compliance: s.model_compliance("test").unwrap(),
        input: Input::Path {
            name: "path.csv".into(),
            text: &text,
            frame: Frame::Base,
        },
        options: free(&s),
    };
    let mut results: Vec<Compensated> = Vec::new();
    let report = run::<Error, _>(request, |_, _, r, _| {
        results.extend_from_slice(r);
        Ok(())
    })
    .unwrap();
    // The lean chosen somewhere: a map at no lean would not hold these bounds.
    assert!(results.iter().any(|r| r.lead != 0.0 || r.tilt != 0.0));
    let map = report.report.map.unwrap();
    assert_eq!(map.variable, MapVariable::Rotation);
    for (c, r) in map.chosen.iter().zip(&results) {
        assert_eq!(*c, r.tool_rotation);
    }
    assert_chosen_cells(&map, &map.angles, &results);
}

#[test]
fn the_track_map_holds_the_chosen_rotation_and_lean_and_its_chosen_cells_are_the_bounds() {
    let s = milling(true);
    let compliance = s.model_compliance("test").unwrap();
    let down = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    let points: Vec<PathPoint> = (0..5)
        .map(|i| PathPoint {
            line: i as u64 + 2,
            target: Target::Pose(Isometry3::from_parts(
                Vector3::new(2.6 + 0.05 * i as f64, -0.8, 0.4).into(),
                down,
            )),
            wrench: Vector6::new(-300.0, 200.0, -250.0, 0.0, 0.0, 0.0),
            frame: Frame::Base,
            external: ExternalValues::new(&[1.5]).unwrap(),
        })
        .collect();
    let mut options = free(&s);
    options
        .free
        .set(Free::Station(crate::compensate::station(100.0, 50.0)));
    options.map_over = MapVariable::Track;
    let results = compensate::path_on_track(s.arm(), &compliance, &points, &options).unwrap();
    assert!(results
        .iter()
        .any(|r| r.tool_rotation != 0.0 || r.lead != 0.0 || r.tilt != 0.0));
    let placed: Vec<PathPoint> = (points.iter())
        .map(|p| on_carriage(s.robot(), p.clone()).unwrap())
        .collect();
    let chosen: Vec<ChosenValues> = (results.iter().zip(&placed))
        .map(|(r, p)| ChosenValues::of(r, &p.external))
        .collect();
    let map = compensate::map(
        s.arm(),
        &compliance,
        &placed,
        (&options, None),
        (&chosen, false),
    );
    let map = map.unwrap();
    for (c, r) in map.chosen.iter().zip(&results) {
        assert!((c - (r.external.as_slice()[0] - 1.5)).abs() <= 1e-15);
    }
    assert_chosen_cells(&map, &map.stations, &results);
}
