//! The free variables' grid refined around the line chosen on it (`Options::refine`): the
//! refined line's peak and sum of the bound never above the grid's, every step within the
//! largest step given, its values on the halved steps; on a smooth case one level reaches the
//! optimum of a uniform grid of the halved step; bad values refused naming the option.

use stiffid::internal::machining::compensate::{
    self, refine, Aggregate, Compensated, Free, FreeVariables, Objective, Options, PathPoint,
};
use stiffid::internal::machining::path;
use stiffid::internal::observation::deflection::Frame;
use stiffid::{Error, JobOption, Setup};

/// The aggregate of the points' bounds, m.
fn total(results: &[Compensated], aggregate: Aggregate) -> f64 {
    let bounds = results.iter().map(|r| r.budget.bound);
    match aggregate {
        Aggregate::Sum => bounds.sum(),
        Aggregate::Max => bounds.fold(0.0, f64::max),
    }
}

/// The free tool axis minimising the bound in `max_step_deg` steps within +-90 deg (a hair
/// more, so that a 2.5 deg grid reaches 90 too).
fn rotation(s: &Setup, max_step_deg: f64, aggregate: Aggregate, refine: usize) -> Options {
    let free = FreeVariables {
        free: vec![Free::ToolRotation(crate::compensate::rotation(
            90.002,
            max_step_deg,
        ))],
        minimise: Objective::Bound,
        aggregate,
    };
    Options {
        free,
        refine,
        ..Options::for_setup(s)
    }
}

/// Whether every value of `values` (rad or m) is a whole number of `step`s.
fn on_steps(values: impl Iterator<Item = f64>, step: f64) -> bool {
    values
        .into_iter()
        .all(|v| ((v / step) - (v / step).round()).abs() < 1e-6)
}

/// The milling example's first 100 path points.
fn contour() -> Vec<PathPoint> {
    let text = include_str!("../../../../examples/milling/path.csv");
    let head: String = text.lines().take(101).map(|l| format!("{l}\n")).collect();
    path::points(&head, Frame::Base, None)
        .unwrap()
        .collect::<stiffid::Result<_>>()
        .unwrap()
}

#[test]
fn the_refined_rotation_never_rises_keeps_the_step_and_reaches_the_fine_grid() {
    let s = crate::lead_tilt::milling();
    let compliance = s.model_compliance("test").unwrap();
    let points = contour();
    let run = |o: &Options| compensate::path(s.arm(), &compliance, &points, o).unwrap();
    let step = 5f64.to_radians();
    for aggregate in [Aggregate::Sum, Aggregate::Max] {
        let coarse = run(&rotation(&s, 5.0, aggregate, 0));
        let mut previous = total(&coarse, aggregate);
        for levels in 1..=2 {
            let refined = run(&rotation(&s, 5.0, aggregate, levels));
            let value = total(&refined, aggregate);
            assert!(
                value <= previous * (1.0 + 1e-6),
                "{levels}: {value} above {previous}"
            );
            previous = value;
            for w in refined.windows(2) {
                let change = (w[1].tool_rotation - w[0].tool_rotation).abs();
                assert!(change <= step * (1.0 + 1e-9), "{change} rad in one step");
            }
            let half = step / (1 << levels) as f64;
            assert!(on_steps(refined.iter().map(|r| r.tool_rotation), half));
            for r in &refined {
                assert!(r.budget.bound <= r.bound_before.unwrap() + 1e-9);
            }
        }
        // A uniform grid of 2.5 deg with the same largest step (5.0001 deg: two cells a step).
        // With either aggregate the sum is minimised (with the worst point's, as its tie-break).
        let one = run(&rotation(&s, 5.0, aggregate, 1));
        let fine = run(&rotation(&s, 5.0001, aggregate, 0));
        let sums = [&coarse, &one, &fine].map(|r| total(r, Aggregate::Sum));
        let peaks = [&coarse, &one, &fine].map(|r| total(r, Aggregate::Max));
        assert!(
            sums[1] < sums[0] * (1.0 - 2e-5),
            "the refinement finds nothing: {sums:?}"
        );
        // Measured: the sums 1.1e-6 apart (the uniform grid's angles are 2.50005 deg apart),
        // against the 3.2e-5 the refinement gains over the 5 deg grid.
        assert!((sums[1] - sums[2]).abs() <= 1e-5 * sums[2], "{sums:?}");
        assert!((peaks[1] - peaks[2]).abs() <= 1e-5 * peaks[2], "{peaks:?}");
    }
}

#[test]
fn the_refined_station_and_rotation_never_rise_and_keep_the_step() {
    let s = crate::free_station::on_track();
    let compliance = s.model_compliance("test").unwrap();
    let points = crate::free_station::line(8);
    for aggregate in [Aggregate::Sum, Aggregate::Max] {
        let options = |refine| {
            let mut o = rotation(&s, 5.0, aggregate, refine);
            o.free
                .set(Free::Station(crate::compensate::station(100.0, 50.0)));
            o
        };
        let run =
            |o: &Options| compensate::path_on_track(s.arm(), &compliance, &points, o).unwrap();
        let coarse = run(&options(0));
        let refined = run(&options(1));
        let (a, b) = (total(&coarse, aggregate), total(&refined, aggregate));
        assert!(b <= a * (1.0 + 1e-6), "{b} above {a}");
        let stations: Vec<f64> = refined.iter().map(|r| r.external.as_slice()[0]).collect();
        for w in stations.windows(2) {
            assert!((w[1] - w[0]).abs() <= 0.05 * (1.0 + 1e-9), "{w:?}");
        }
        assert!(on_steps(stations.iter().map(|e| e - 1.5), 0.025));
        assert!(stations.iter().all(|e| (e - 1.5).abs() <= 0.1 + 1e-12));
    }
}

#[test]
fn bad_refine_values_are_refused() {
    let s = crate::lead_tilt::milling();
    let compliance = s.model_compliance("test").unwrap();
    let points = crate::lead_tilt::line(3);
    let options = rotation(&s, 5.0, Aggregate::Sum, 4 + 1);
    let e = compensate::path(s.arm(), &compliance, &points, &options).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidOption { option: JobOption::Refine, message } if message.starts_with("5: expected 0 to 4")),
        "{e}"
    );
    let plain = Options {
        refine: 1,
        ..Options::for_setup(&s)
    };
    let e = compensate::path(s.arm(), &compliance, &points, &plain).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidOption { option: JobOption::Refine, message } if message.contains("none is free")),
        "{e}"
    );
    assert!(refine::check(4, 1, 1000).is_ok());
    // Six free axes: 5^6 band states, 5^12 transitions a point.
    assert!(matches!(
        refine::check(1, 6, 20),
        Err(Error::InvalidOption {
            option: JobOption::Refine,
            ..
        })
    ));
    assert!(refine::check(0, 6, 20).is_ok());
}
