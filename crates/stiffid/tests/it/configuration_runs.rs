//! One configuration per run (`--free configuration=run`): a path of two runs whose best
//! configurations differ, the runs' choice equal to the exhaustive best over every pair of
//! configurations compensated alone and better than one configuration for the whole path; a
//! G-code program's runs (its rapid moves), its robot program written with each run's
//! configuration, and its G-code refused naming the first run in another configuration.

use crate::common::on_robot;
use crate::compensate::{line_path, options};
use crate::free_configuration::{fanuc, WIDE};
use nalgebra::{Translation3, Vector6};
use stiffid::app::compensate::configurations::ConfigurationsDocument;
use stiffid::app::compensate::{self as job, Input};
use stiffid::internal::common::limits::JointBox;
use stiffid::internal::machining::compensate::{
    self, path_runs, Aggregate, Compensated, Free, FreeVariables, Objective, Options, PathPoint,
    Scope, Target,
};
use stiffid::internal::machining::program::generate::Settings;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::robot::presets;
use stiffid::{Error, JobOption, Setup};

/// Two runs: `line_path`'s six points, then the same line moved by 0.3, -0.5, 0.2 m under
/// 400 N along tool z, from line 20.
fn two_runs(s: &Setup) -> Vec<PathPoint> {
    let a = line_path(s, 6);
    let t = Translation3::new(0.3, -0.5, 0.2);
    let b: Vec<PathPoint> = (a.iter().enumerate())
        .map(|(i, p)| {
            let Target::Pose(pose) = &p.target else {
                unreachable!()
            };
            PathPoint {
                line: 20 + i as u64,
                target: Target::Pose(t * pose),
                wrench: Vector6::new(0.0, 0.0, 400.0, 0.0, 0.0, 0.0),
                ..p.clone()
            }
        })
        .collect();
    a.into_iter().chain(b).collect()
}

/// The options of `s` with the free configuration held per `per`.
fn per(s: &Setup, aggregate: Aggregate, per: Scope) -> Options {
    Options {
        free: FreeVariables {
            free: vec![Free::Configuration(per)],
            minimise: Objective::Bound,
            aggregate,
        },
        ..options(s, None)
    }
}

/// The objective of compensated points and its tie-break for `aggregate` (of the bound), m.
fn value(results: &[Compensated], aggregate: Aggregate) -> (f64, f64) {
    let bounds = results.iter().map(|r| r.budget.bound);
    let (peak, sum) = (bounds.clone().fold(0.0, f64::max), bounds.sum());
    match aggregate {
        Aggregate::Sum => (sum, peak),
        Aggregate::Max => (peak, sum),
    }
}

/// Whether `a` is better than `b` by more than 1e-6 (the objective, then the tie-break).
fn better(a: (f64, f64), b: (f64, f64)) -> bool {
    let below = |x: f64, y: f64| x < y * (1.0 - 1e-6);
    below(a.0, b.0) || (!below(b.0, a.0) && below(a.1, b.1))
}

#[test]
fn each_run_takes_the_exhaustive_best_pair_of_configurations_and_beats_one_for_the_path() {
    let s = fanuc(WIDE);
    let compliance = s.model_compliance("test").unwrap();
    let path = two_runs(&s);
    let ranges = [0..6, 6..12];
    for aggregate in [Aggregate::Sum, Aggregate::Max] {
        let o = per(&s, aggregate, Scope::Run);
        let (results, c) = path_runs(s.arm(), &compliance, (&path, &[0, 6]), &o).unwrap();
        assert_eq!(c.runs.len(), 2);
        assert_eq!((c.runs[1].first_line, c.runs[1].last_line), (20, 25));
        assert_eq!(c.runs[1].points, 6..12);
        // Every configuration of each run compensated alone from its first posture.
        let alone: Vec<Vec<Vec<Compensated>>> = (c.runs.iter().zip(&ranges))
            .map(|(run, r)| {
                assert!(run.branches.len() >= 4);
                (run.branches.iter())
                    .map(|b| {
                        assert!(b.refused.is_none(), "{:?}", b.refused);
                        let q0 = Vector6::from(b.configuration.q_deg).map(f64::to_radians);
                        let o = Options {
                            q0,
                            ..options(&s, None)
                        };
                        compensate::path(s.arm(), &compliance, &path[r.clone()], &o).unwrap()
                    })
                    .collect()
            })
            .collect();
        let mut best: Option<((usize, usize), (f64, f64))> = None;
        for (i, a) in alone[0].iter().enumerate() {
            for (j, b) in alone[1].iter().enumerate() {
                let pair: Vec<Compensated> = a.iter().chain(b).cloned().collect();
                let v = value(&pair, aggregate);
                if best.is_none_or(|(_, w)| better(v, w)) {
                    best = Some(((i, j), v));
                }
            }
        }
        let ((i, j), v) = best.unwrap();
        let got = value(&results, aggregate);
        assert!(
            (got.0 - v.0).abs() <= 1e-8 * v.0,
            "{aggregate:?}: {got:?} {v:?}"
        );
        assert!(
            (got.1 - v.1).abs() <= 1e-6 * v.1,
            "{aggregate:?}: {got:?} {v:?}"
        );
        let chosen = (c.runs[0].chosen, c.runs[1].chosen);
        let key = |k: usize, b: usize| {
            let a = &c.runs[k].branches[b].configuration;
            (a.behind(), a.elbow_down(), a.wrist_negative())
        };
        assert_eq!((key(0, chosen.0), key(1, chosen.1)), (key(0, i), key(1, j)));
        assert_ne!(key(0, chosen.0), key(1, chosen.1), "the runs' best differ");
        let expected = alone[0][chosen.0].iter().chain(&alone[1][chosen.1]);
        for (r, e) in results.iter().zip(expected) {
            assert!((r.q_compensated - e.q_compensated).amax() < 1e-9);
        }
        // One configuration for the whole path: worse.
        let whole = per(&s, aggregate, Scope::Program);
        let (program, p) = path_runs(s.arm(), &compliance, (&path, &[0, 6]), &whole).unwrap();
        assert!(p.runs.is_empty());
        let one = value(&program, aggregate);
        println!(
            "{aggregate:?}: per run {:.6} mm, per program {:.6} mm",
            got.0 * 1e3,
            one.0 * 1e3
        );
        assert!(got.0 < 0.995 * one.0, "{got:?} against {one:?}");
        // The document states each run and the program's objective.
        let doc = ConfigurationsDocument::new(&c);
        assert_eq!((doc.per, doc.runs.len()), ("run", 2));
        assert!((doc.objective_mm.unwrap() - got.0 * 1e3).abs() < 1e-9 * got.0 * 1e3);
        assert_eq!(doc.runs[1].first_line, 20);
    }
}

/// The FANUC milling example with every axis within +-300 deg.
fn wide_milling() -> Setup {
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let s = stiffid::internal::setup::parse(text, "fanuc-milling.toml", |n, _| presets::get(n))
        .unwrap();
    let wide = Vector6::repeat(300f64.to_radians());
    let robot = (s.robot().clone()).with_limits(JointBox::new(-wide, wide));
    on_robot(&s, robot.unwrap(), s.springs())
}

/// The drilling panel compensated per run on `s`, written in `output`.
fn panel(s: &Setup, output: Language) -> Result<job::Report, Error> {
    drill(
        s,
        include_str!("../../../../examples/milling/panel.nc"),
        output,
    )
}

/// Two holes, the second at `d` (mm, part frame) from the first.
fn two_holes(d: [f64; 3]) -> String {
    let hole = |x: f64, y: f64, z: f64| {
        format!(
            "G0 X{x} Y{y} Z{}\nG1 X{x} Y{y} Z{} F450\nG0 X{x} Y{y} Z{}\n",
            z + 5.0,
            z - 10.0,
            z + 5.0
        )
    };
    format!(
        "(stiffid: tool_rpy_deg = 180 0 0)\n(operation: drill)\nG21 G90 G17\nT2 M06\nS3000 M03\n{}{}",
        hole(0.0, 0.0, 0.0),
        hole(d[0], d[1], d[2])
    )
}

/// A drilling program `text` compensated per run on `s`, written in `output`.
fn drill(s: &Setup, text: &str, output: Language) -> Result<job::Report, Error> {
    drill_with(s, text, output, per(s, Aggregate::Sum, Scope::Run))
}

/// A drilling program `text` compensated with `options` on `s`, written in `output`.
fn drill_with(
    s: &Setup,
    text: &str,
    output: Language,
    options: Options,
) -> Result<job::Report, Error> {
    let compliance = stiffid::internal::io::stiffness::parse(include_str!(
        "../../../../examples/milling/stiffness.json"
    ))
    .unwrap()
    .compliance(s.model())
    .unwrap();
    let process = stiffid::internal::machining::process::file::parse(
        include_str!("../../../../examples/milling/drilling.toml"),
        "drilling.toml",
    )
    .unwrap();
    let request = job::Request {
        names: Default::default(),
        setup: s,
        compliance,
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "drill.nc".into(),
            text,
            data: None,
            language: Language::GCode,
            process_name: "drilling.toml".into(),
            process,
            chord_tolerance: 1e-5,
            output,
            out_name: format!("drill.{}", output.extension()),
            settings: Settings::default(),
        },
        options,
    };
    job::run::<Error, _>(request, |_, _, _, _| Ok(())).map(|o| o.report)
}

#[test]
fn a_gcode_program_runs_between_rapid_moves_and_its_gcode_is_refused_naming_the_run() {
    let s = wide_milling();
    let report = panel(&s, Language::Robot(Dialect::FanucLs)).unwrap();
    let c = report.configurations.as_ref().unwrap();
    let doc = ConfigurationsDocument::new(c);
    // 20 holes: each run the retract of the hole before, the approach and the drilling feed;
    // the last retract ends the last run.
    assert_eq!(doc.runs.len(), 20);
    let g = stiffid::internal::machining::gcode::parse(
        include_str!("../../../../examples/milling/panel.nc"),
        1e-5,
    )
    .unwrap();
    let lines: Vec<u64> = g.points.iter().map(|p| p.line).collect();
    assert_eq!(doc.runs[0].first_line, lines[0]);
    assert_eq!(doc.runs[1].first_line, lines[2], "the first hole's retract");
    assert_eq!(doc.runs[19].last_line, *lines.last().unwrap());
    let own: f64 = doc.runs.iter().filter_map(|r| r.own_objective_mm).sum();
    println!("panel: per run {:?} mm, own {own} mm", doc.objective_mm);
    for r in &doc.runs {
        println!(
            "run {} lines {}-{}: {} sum {:?} own {:?}",
            r.run, r.first_line, r.last_line, r.chosen, r.sum_mm, r.own_objective_mm
        );
        // No run is worse than in the program's own configuration.
        if let (Some(v), Some(own)) = (r.objective_mm, r.own_objective_mm) {
            assert!(v <= own * (1.0 + 1e-9), "{}", r.run);
        }
    }
    // Every hole is best in one configuration here (elbow down), so one for the program gives
    // the same; two holes far apart are not.
    assert!(doc.runs.iter().all(|r| r.chosen == doc.runs[0].chosen));
    let whole = per(&s, Aggregate::Sum, Scope::Program);
    let text = include_str!("../../../../examples/milling/panel.nc");
    let program = drill_with(&s, text, Language::GCode, whole).unwrap();
    let one = ConfigurationsDocument::new(program.configurations.as_ref().unwrap());
    assert_eq!(one.chosen, doc.runs[0].chosen);
    let (a, b) = (one.objective_mm.unwrap(), doc.objective_mm.unwrap());
    assert!((a - b).abs() < 1e-9 * a, "{a} {b}");
    let far = two_holes([-1300.0, 700.0, 800.0]);
    let report = drill(&s, &far, Language::Robot(Dialect::FanucLs)).unwrap();
    let doc = ConfigurationsDocument::new(report.configurations.as_ref().unwrap());
    assert_eq!(doc.runs.len(), 2);
    let (first, other) = (&doc.runs[0], &doc.runs[1]);
    assert_ne!(first.chosen, other.chosen);
    assert_eq!((other.first_line, other.last_line), (8, 11));
    // The robot program moves to each run with its configuration.
    let text = &report.program.as_ref().unwrap().text;
    for r in [first, other] {
        assert!(
            text.contains(&format!("CONFIG : {}", r.configuration_data["ls"])),
            "{:?}",
            r.configuration_data
        );
    }
    match drill(&s, &far, Language::GCode).unwrap_err() {
        Error::InvalidOption { option, message } => {
            assert_eq!(option, JobOption::ConfigurationScope);
            assert!(message.contains("run 2 (lines 8 to 11)"), "{message}");
        }
        e => panic!("{e}"),
    }
    // One configuration per program: written as G-code.
    let whole = per(&s, Aggregate::Sum, Scope::Program);
    assert!(drill_with(&s, &far, Language::GCode, whole).is_ok());
}

#[test]
fn one_configuration_per_run_is_refused_with_a_map() {
    let s = fanuc(WIDE);
    let o = Options {
        map: true,
        ..per(&s, Aggregate::Sum, Scope::Run)
    };
    match o.validate().unwrap_err() {
        Error::OptionCombination { option, with, .. } => {
            assert_eq!(option, JobOption::ConfigurationScope);
            assert_eq!(with, vec![JobOption::Map]);
        }
        e => panic!("{e}"),
    }
}
