//! Options set in code are checked against their documented limits at the entry points, as
//! argmin's `with_*` setters do: any f64 (NaN, infinite, negative, 0, huge) or count (0, huge) is
//! an error naming the field with the value and the range, never a panic or a hang.

use nalgebra::{Isometry3, Vector3};
use stiffid::internal::design::{self, Criterion, Pool, PoolOptions, SearchOptions};
use stiffid::internal::machining::compensate::{self, Free, FreeRange, Variable};
use stiffid::internal::observation::stiffness::joint_torques;
use stiffid::internal::observation::{point_rows, posture_block};
use stiffid::{
    internal::{robot::ik, setup, study, study::simulate},
    Error, Setup,
};

fn paper() -> Setup {
    setup::builtin("zhang2021-comau-nj165").unwrap()
}

/// The field and message of an [`Error::InvalidField`]; the message must hold `value`.
fn rejected(result: Result<impl std::fmt::Debug, Error>, field: &str, value: &str) {
    match result {
        Err(Error::InvalidField { field: f, message }) => {
            assert_eq!(f, field);
            assert!(message.contains(value), "{field}: {message}");
            assert!(
                message.contains("outside") || message.contains("expected"),
                "{message}"
            );
        }
        other => panic!("{field} = {value}: expected a field error, got {other:?}"),
    }
}

#[test]
fn search_options_out_of_range_are_refused_by_local_and_global() {
    let setup = paper();
    let start = design::random_group(&setup, 6, 1);
    let bad_floats = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1.0, 1e300];
    for v in bad_floats {
        let cases = [
            (
                "ftol",
                SearchOptions {
                    ftol: v,
                    ..Default::default()
                },
            ),
            (
                "xtol",
                SearchOptions {
                    xtol: v,
                    ..Default::default()
                },
            ),
            (
                "fd_step",
                SearchOptions {
                    fd_step: v,
                    ..Default::default()
                },
            ),
        ];
        for (field, o) in cases {
            let field = format!("SearchOptions.{field}");
            let shown = stiffid::internal::common::words::number(v);
            rejected(
                design::local(&setup, Criterion::DOptimal, &start, &o),
                &field,
                &shown,
            );
            let found = design::global(&setup, Criterion::DOptimal, 6, &o, &());
            rejected(found, &field, &shown);
        }
    }
    let zero_step = SearchOptions {
        fd_step: 0.0,
        ..Default::default()
    };
    let e = design::local(&setup, Criterion::DOptimal, &start, &zero_step);
    rejected(e, "SearchOptions.fd_step", "0 is outside [1e-12, 0.01] rad");
    for v in [0, usize::MAX] {
        let cases = [
            (
                "max_evals",
                SearchOptions {
                    max_evals: v,
                    ..Default::default()
                },
            ),
            (
                "starts",
                SearchOptions {
                    starts: v,
                    ..Default::default()
                },
            ),
            (
                "polished",
                SearchOptions {
                    polished: v,
                    ..Default::default()
                },
            ),
        ];
        for (field, o) in cases {
            let found = design::global(&setup, Criterion::DOptimal, 6, &o, &());
            rejected(found, &format!("SearchOptions.{field}"), &v.to_string());
        }
    }
    let o = SearchOptions {
        screen_steps: usize::MAX,
        ..Default::default()
    };
    let e = design::local(&setup, Criterion::DOptimal, &start, &o);
    rejected(
        e,
        "SearchOptions.screen_steps",
        "18446744073709551615 is outside [0, 10000000]",
    );
    // The limits themselves are accepted.
    let edge = SearchOptions {
        ftol: 0.0,
        xtol: 1.0,
        fd_step: 1e-2,
        max_evals: 1,
        ..Default::default()
    };
    assert!(design::local(&setup, Criterion::DOptimal, &start, &edge).is_ok());
}

#[test]
fn pool_options_out_of_range_are_refused() {
    let setup = paper();
    let postures = design::random_group(&setup, 8, 2);
    let pool = Pool::new(&setup, &postures, &[]).unwrap();
    let best = |o: PoolOptions| pool.best(Criterion::DOptimal, 6, &o);
    for v in [0, usize::MAX] {
        let o = PoolOptions {
            restarts: v,
            ..Default::default()
        };
        rejected(best(o), "PoolOptions.restarts", &v.to_string());
    }
    let o = PoolOptions {
        enumeration_limit: u64::MAX,
        ..Default::default()
    };
    rejected(
        best(o),
        "PoolOptions.enumeration_limit",
        "18446744073709551615",
    );
}

#[test]
fn ik_and_compensate_options_out_of_range_are_refused() {
    let setup = paper();
    let robot = setup.robot();
    let q = setup.test_postures()[0];
    let target: Isometry3<f64> = ik::tool_pose(&robot.frames(&q), &setup.tool().tcp);
    let solve = |o: ik::Options| ik::solve(robot, &setup.tool().tcp, &target, &q, &o);
    for v in [f64::NAN, -1e-3, 0.0, f64::INFINITY] {
        let o = ik::Options {
            position_tolerance: v,
            ..Default::default()
        };
        rejected(
            solve(o),
            "ik::Options.position_tolerance",
            &stiffid::internal::common::words::number(v),
        );
        let o = ik::Options {
            rotation_tolerance: v,
            ..Default::default()
        };
        rejected(
            solve(o),
            "ik::Options.rotation_tolerance",
            &stiffid::internal::common::words::number(v),
        );
    }
    let o = ik::Options {
        max_iterations: 0,
        ..Default::default()
    };
    rejected(
        solve(o),
        "ik::Options.max_iterations",
        "0 is outside [1, 100000]",
    );
    let o = ik::Options {
        restarts: usize::MAX,
        ..Default::default()
    };
    rejected(solve(o), "ik::Options.restarts", "18446744073709551615");
    assert!(solve(ik::Options::default()).is_ok());

    let mut options = compensate::Options::for_setup(&setup);
    options.q0[3] = f64::NAN;
    rejected(options.validate(), "compensate::Options.q0[4]", "NaN");
    let mut options = compensate::Options::for_setup(&setup);
    options.free.set(Free::ToolRotation(FreeRange {
        step: 0.0,
        range: 1.0,
    }));
    match options.validate() {
        Err(Error::InvalidOption { option, message }) => {
            assert_eq!(option, stiffid::JobOption::ToolRotationStep);
            assert!(message.starts_with("0: expected a number > 0"), "{message}");
        }
        other => panic!("expected an option error, got {other:?}"),
    }
    // The error budget's options: the force model's error within 0 to 100%, the largest error > 0.
    let mut budget = compensate::Options::for_setup(&setup);
    budget.force_tolerance = 1.5;
    let e = budget.validate().unwrap_err();
    assert!(
        matches!(&e, stiffid::Error::InvalidOption { option: stiffid::JobOption::ForceTolerancePct, message } if message == "150: expected 0 to 100 percent"),
        "{e}"
    );
    let mut budget = compensate::Options::for_setup(&setup);
    budget.max_error = Some(-1e-3);
    let e = budget.validate().unwrap_err();
    assert!(
        matches!(&e, stiffid::Error::InvalidOption { option: stiffid::JobOption::MaxErrorMm, message } if message == "-1: expected a number > 0"),
        "{e}"
    );
    // 5e-324 deg is 0 rad: refused by the degrees' own check, naming the option.
    match FreeRange::checked(&Variable::ToolRotation, 90.0, 5e-324) {
        Err(Error::InvalidOption { option, message }) => {
            assert_eq!(option, stiffid::JobOption::ToolRotationStep);
            assert!(message.contains("5e-324"), "{message}");
        }
        other => panic!("expected an option error, got {other:?}"),
    }
    assert!(matches!(
        FreeRange::checked(&Variable::ToolRotation, 181.0, 10.0),
        Err(Error::InvalidOption {
            option: stiffid::JobOption::ToolRotationRange,
            ..
        })
    ));
    let free = crate::compensate::rotation(180.0, 90.0);
    options.free.set(Free::ToolRotation(free));
    assert!(options.validate().is_ok());
}

#[test]
fn simulation_and_study_counts_out_of_range_are_refused() {
    let setup = paper();
    let group = vec![design::random_group(&setup, 6, 1)];
    for runs in [0, usize::MAX] {
        let o = simulate::Options { runs, seed: 1 };
        rejected(
            simulate::monte_carlo(&setup, &group, &o),
            "runs",
            &runs.to_string(),
        );
    }
    let o = study::Options {
        trials: usize::MAX,
        ..Default::default()
    };
    rejected(
        study::run(&setup, &o, &()),
        "trials",
        "18446744073709551615",
    );
    // The trials' seeds follow the seed: they may not pass u64::MAX (no silent wrap-around).
    let o = study::Options {
        seed: u64::MAX - 1,
        trials: 2,
        ..Default::default()
    };
    rejected(study::run(&setup, &o, &()), "seed", "18446744073709551614");
}

#[test]
fn point_rows_take_the_point_and_match_the_posture_block() {
    let setup = paper();
    let frames = setup.robot().frames(&setup.test_postures()[1]);
    let wrench = setup.rope_wrench(&frames);
    let block = posture_block(setup.arm(), &frames, &wrench);
    let tau = joint_torques(setup.arm(), &frames, &wrench);
    for (k, p) in setup.tool().measuring_points.iter().enumerate() {
        let rows = point_rows(setup.arm(), &frames, p, &tau);
        assert_eq!(rows, block.fixed_view::<3, 6>(3 * k, 0));
    }
    // Any point, not only the setup's: no index to get out of range.
    let far = point_rows(setup.arm(), &frames, &Vector3::new(0.0, 0.0, 1.0), &tau);
    assert!(far.iter().all(|v| v.is_finite()));
}

/// A calibration prior's tolerances outside their limits (a tolerance of 1e-300 mm once hung the
/// fit: its prior rows overflowed) are refused naming both fields.
#[test]
fn calibration_tolerances_out_of_range_are_refused() {
    use stiffid::app::calibrate::Tolerances;
    let refused = |r: Result<Tolerances, Error>| match r {
        Err(Error::InvalidOption { option, message }) => {
            assert_eq!(option, stiffid::JobOption::Tolerances);
            assert!(
                message.contains("expected [1e-6, 1000] mm and [1e-6, 90] deg"),
                "{message}"
            );
        }
        other => panic!("expected an option error, got {other:?}"),
    };
    for v in [f64::NAN, f64::INFINITY, -1.0, 0.0, 1e-300, 1e300] {
        refused(Tolerances::from_mm_deg(v, 0.01));
        refused(Tolerances::from_mm_deg(0.1, v));
    }
    for (mm, deg) in [(1e-6, 1e-6), (0.1, 0.01), (1e3, 90.0)] {
        assert!(
            Tolerances::from_mm_deg(mm, deg).is_ok(),
            "{mm} mm, {deg} deg"
        );
    }
}

/// `--distinct-deg` and `--distinct-mm` out of range are refused as their own options, with the
/// value as given (1e9, not its round trip through radians).
#[test]
fn distinct_distances_out_of_range_are_refused_as_options() {
    use stiffid::internal::design::distinct::Distinctness;
    let cases = [
        (
            Some(1e9),
            None,
            stiffid::JobOption::DistinctDeg,
            "1e9 is outside [0, 180] deg",
        ),
        (
            Some(-1.0),
            None,
            stiffid::JobOption::DistinctDeg,
            "-1 is outside",
        ),
        (
            None,
            Some(f64::NAN),
            stiffid::JobOption::DistinctMm,
            "NaN is outside",
        ),
        (
            None,
            Some(2e4),
            stiffid::JobOption::DistinctMm,
            "20000 is outside [0, 10000] mm",
        ),
    ];
    for (deg, mm, want, text) in cases {
        match Distinctness::try_from_deg_mm(deg, mm) {
            Err(Error::InvalidOption { option, message }) => {
                assert_eq!(option, want);
                assert!(message.contains(text), "{message}");
            }
            other => panic!("{deg:?} deg, {mm:?} mm: expected an option error, got {other:?}"),
        }
    }
    let d = Distinctness::try_from_deg_mm(Some(5.0), Some(20.0)).unwrap();
    assert!((d.joint - 5f64.to_radians()).abs() < 1e-15 && (d.position - 0.02).abs() < 1e-15);
}

/// A margin out of range is refused as the user's option (`--margin-mm`, Python `margin_mm`),
/// not as a library field, with the value in mm in its shortest form.
#[test]
fn a_margin_out_of_range_is_refused_as_an_option() {
    for (margin, text) in [
        (-1e-3, "-1 is outside [0, 1000] mm"),
        (f64::NAN, "NaN is outside"),
        (1e297, "1e300 is outside"),
    ] {
        let options = SearchOptions {
            margin: Some(margin),
            ..SearchOptions::default()
        };
        match options.validate() {
            Err(Error::InvalidOption { option, message }) => {
                assert_eq!(option, stiffid::JobOption::MarginMm);
                assert!(message.contains(text), "{message}");
            }
            other => panic!("{margin}: expected an option error, got {other:?}"),
        }
    }
    let inside = SearchOptions {
        margin: Some(0.02),
        ..SearchOptions::default()
    };
    assert!(inside.validate().is_ok());
}

/// `result` is the option error of `want`, its message holding `text`.
fn refused_option(result: Result<(), Error>, want: stiffid::JobOption, text: &str) {
    match result {
        Err(Error::InvalidOption { option, message }) => {
            assert_eq!(option, want, "{message}");
            assert!(message.contains(text), "{want:?}: {message}");
        }
        other => panic!("{want:?}: expected an option error, got {other:?}"),
    }
}

/// Selections on `setup` with an option that means nothing there: the option and what its
/// refusal says.
fn select_cases(
    setup: &Setup,
) -> Vec<(
    stiffid::app::select::Request<'_>,
    stiffid::JobOption,
    &'static str,
)> {
    use stiffid::app::purpose::{CalibrationOptions, Purpose};
    use stiffid::app::select;
    use stiffid::internal::design::observability::CalibrationCriterion;
    use stiffid::JobOption;
    let search = select::Request {
        setup,
        criterion: Criterion::RelativeA,
        purpose: Purpose::Stiffness,
        calibration: CalibrationOptions::default(),
        method: select::Method::Global,
        start: None,
        pool: None,
        postures: 6,
        target_pct: None,
        options: SearchOptions::default(),
        restarts: None,
        distinct: None,
        for_candidates: false,
        candidates: None,
        stations: Vec::new(),
        progress: &(),
        out: None,
        report_dir: None,
    };
    let weight = CalibrationOptions {
        weight: Some(0.3),
        ..Default::default()
    };
    let o1 = CalibrationOptions {
        criterion: Some(CalibrationCriterion::O1),
        ..Default::default()
    };
    vec![
        (
            select::Request {
                restarts: Some(4),
                ..search.clone()
            },
            JobOption::Restarts,
            "only for a pool choice",
        ),
        (
            select::Request {
                calibration: weight,
                ..search.clone()
            },
            JobOption::Weight,
            "only with for = both",
        ),
        (
            select::Request {
                purpose: Purpose::Calibration,
                calibration: weight,
                ..search.clone()
            },
            JobOption::Weight,
            "only with for = both",
        ),
        (
            select::Request {
                calibration: o1,
                ..search.clone()
            },
            JobOption::CalibrationCriterion,
            "only with for = calibration or both",
        ),
        (
            select::Request {
                options: SearchOptions {
                    margin: Some(0.01),
                    ..SearchOptions::default()
                },
                ..search.clone()
            },
            JobOption::MarginMm,
            "no cell, tracker or constraints",
        ),
    ]
}

/// Options that mean nothing where they are given are refused by the jobs themselves, as typed
/// option errors (the command and Python name them their own way): a pool's restarts for a
/// search, a calibration option for a stiffness design, the weight unless for both, a margin on a
/// setup without a cell, `force` for a registration proposal, a level without prediction data.
#[test]
fn options_that_mean_nothing_where_given_are_refused_by_the_jobs() {
    use stiffid::app::purpose::{CalibrationOptions, Purpose};
    use stiffid::app::{evaluate, predict, register, select, WarningKind};
    use stiffid::internal::metrology::calibration::gravity::Gravity;
    use stiffid::JobOption;
    let setup = paper();
    let cases = select_cases(&setup);
    for (request, option, text) in cases {
        refused_option(select::run(&request).map(drop), option, text);
    }
    let group = design::random_group(&setup, 6, 1);
    let gravity = CalibrationOptions {
        gravity: Some(Gravity::Lumped),
        ..Default::default()
    };
    let evaluate = evaluate::Request {
        purpose: Purpose::Stiffness,
        calibration: gravity,
        setup: &setup,
        postures: &group,
        candidates: None,
    };
    refused_option(
        evaluate::run(&evaluate).map(drop),
        JobOption::Gravity,
        "for = calibration",
    );
    let proposal = register::DesignRequest {
        setup: &setup,
        setup_name: "setup".into(),
        postures: 4,
        options: Default::default(),
        force: true,
    };
    refused_option(
        register::propose(&proposal).map(drop),
        JobOption::Force,
        "only with readings",
    );
    let prediction = |level| predict::Request {
        setup_name: "setup".into(),
        setup: &setup,
        q: group[0],
        wrench: nalgebra::Vector6::new(0.0, 0.0, -500.0, 0.0, 0.0, 0.0),
        frame: stiffid::internal::observation::deflection::Frame::Base,
        at: None,
        compliance: None,
        level,
    };
    refused_option(
        predict::run(&prediction(Some(0.9))).map(drop),
        JobOption::Level,
        "prediction data",
    );
    assert!(predict::run(&prediction(None)).is_ok());
    // 500 N deflects the paper's robot by hundredths of a degree; 1e7 N by degrees, beyond
    // the linear model: said.
    let large = |r: &predict::Report| {
        (r.warnings.iter())
            .any(|w| w.kind == WarningKind::Plausibility && w.message.contains("deflects"))
    };
    assert!(!large(&predict::run(&prediction(None)).unwrap()));
    let heavy = predict::Request {
        wrench: nalgebra::Vector6::new(0.0, 0.0, -1e7, 0.0, 0.0, 0.0),
        ..prediction(None)
    };
    let report = predict::run(&heavy).unwrap();
    let dq = &report.tcp.deflection.joint_deflections;
    assert!(dq.amax() > 1f64.to_radians(), "{dq}");
    assert!(large(&report), "{:?}", report.warnings);
}
