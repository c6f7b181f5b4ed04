//! `calibrate --gravity auto` on a heavy robot measured in a narrow part of its workspace (the
//! FANUC R-2000iC/165F preset, a simulated true robot sagging under the weight of its links,
//! geometric errors in every joint, 0.015 mm of tracker noise; 36 postures with joints 2 and 3
//! within 12 and 16 deg): the ladder judges the gravity models where the robot is used, picks one, and
//! predicts held-out postures of that region better than the geometry.

use crate::true_robot::{masses, setup_text, Truth};
use nalgebra::Vector6;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Uniform};
use stiffid::app::calibrate::{self, GravitySpec, Report};
use stiffid::internal::metrology::calibration::gravity::Gravity;
use stiffid::internal::metrology::calibration::maps::Spec;
use stiffid::internal::metrology::calibration::Geometry;
use stiffid::Setup;

/// The FANUC preset's robot file, with the link masses of the true robot when `with_masses`.
fn robot_text(with_masses: bool) -> String {
    let preset = include_str!("../../../stiffid-core/presets/fanuc-r2000ic-165f.toml");
    if !with_masses {
        return preset.to_string();
    }
    let mut text = String::new();
    let mut m = masses();
    // The robot file's masses off the truth's (`FILE_MASSES`: a factor per link, comma-separated).
    if let Ok(f) = std::env::var("FILE_MASSES") {
        for (l, v) in f.split(',').enumerate() {
            m[l].mass *= v.parse::<f64>().unwrap();
        }
    }
    for (i, part) in preset.split("[[joint]]\n").enumerate() {
        text += part;
        if i < 6 {
            let c = m[i].centre * 1e3;
            text += &format!(
                "[[joint]]\nmass_kg = {:?}\ncom_mm = [{:?}, {:?}, {:?}]\n",
                m[i].mass, c.x, c.y, c.z
            );
        }
    }
    text
}

/// The heavy robot's setup (the true robot's link masses in its robot file when `with_masses`).
pub(crate) fn heavy_setup(with_masses: bool) -> Setup {
    setup_with(with_masses, false, "")
}

/// [`heavy_setup`], read at one measuring point when `one_point`, with `more` appended (a
/// `[test]` table).
fn setup_with(with_masses: bool, one_point: bool, more: &str) -> Setup {
    let mut text = setup_text("robot.toml", more);
    if one_point {
        let four = text
            .lines()
            .find(|l| l.starts_with("measuring_points_mm"))
            .unwrap();
        text = text.replace(four, "measuring_points_mm = [[80.0, 80.0, 260.0]]");
    }
    let robot = robot_text(with_masses);
    stiffid::internal::setup::parse(&text, "setup.toml", |_, _| {
        stiffid::internal::robot::file::parse(&robot, "robot.toml")
    })
    .unwrap()
}

/// `n` postures in a narrow region in front of the robot (axis angles, rad).
pub(crate) fn narrow(n: usize, rng: &mut ChaCha8Rng) -> Vec<Vector6<f64>> {
    let lo: [f64; 6] = [-15.0, 0.0, -8.0, -20.0, -70.0, -30.0];
    let hi: [f64; 6] = [15.0, 12.0, 8.0, 20.0, -45.0, 30.0];
    (0..n)
        .map(|_| {
            Vector6::from_fn(|i, _| Uniform::new(lo[i], hi[i]).unwrap().sample(rng).to_radians())
        })
        .collect()
}

/// The report of `gravity` fitted to `data`, `held` held out.
pub(crate) fn calibrated(setup: &Setup, data: &str, held: &str, gravity: GravitySpec) -> Report {
    at_level(setup, (data, held), gravity, None)
}

/// [`calibrated`] with the gravity bound `bound` (rad; `None` the default), or why not.
fn try_bounded(
    setup: &Setup,
    readings: (&str, &str),
    gravity: GravitySpec,
    bound: Option<f64>,
) -> stiffid::Result<Report> {
    run(setup, readings, gravity, (None, bound))
}

/// [`calibrated`] with the held-out intervals at `level`.
fn at_level(
    setup: &Setup,
    readings: (&str, &str),
    gravity: GravitySpec,
    level: Option<f64>,
) -> Report {
    with_options(setup, readings, gravity, (level, None))
}

/// [`calibrated`] with the held-out intervals at `level` and the gravity bound `bound`.
fn with_options(
    setup: &Setup,
    (data, held): (&str, &str),
    gravity: GravitySpec,
    options: (Option<f64>, Option<f64>),
) -> Report {
    run(setup, (data, held), gravity, options).unwrap()
}

/// The calibrate job on `data`, `held` held out, with the held-out intervals at `level` and the
/// gravity bound `gravity_bound`.
fn run(
    setup: &Setup,
    (data, held): (&str, &str),
    gravity: GravitySpec,
    (level, gravity_bound): (Option<f64>, Option<f64>),
) -> stiffid::Result<Report> {
    calibrate::run(&calibrate::Request {
        readings: stiffid::app::readings::Request {
            setup_name: "setup".into(),
            setup,
            name: "fit.csv".into(),
            text: data,
            force: false,
        },
        geometry: Geometry::Full,
        gravity,
        gravity_bound,
        validate: Some(("held.csv".into(), held)),
        reregister: false,
        cross_validate: false,
        priors: None,
        progress: &(),
        maps: Spec::None,
        error_motions: Default::default(),
        level,
        update: false,
        refit: Default::default(),
        weight: None,
        urdf: false,
    })
    .map(|o| o.report)
}

/// The readings of 36 narrow postures of the true robot of `seed`, split 24 fitted, 12 held out.
pub(crate) fn split(setup: &Setup, seed: u64) -> (String, String) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let truth = Truth::new(setup, &mut rng);
    let mut qs = narrow(36, &mut rng);
    qs.shuffle(&mut rng);
    let zero = [Vector6::zeros()];
    (
        truth.readings(&qs[..24], &zero, &mut rng),
        truth.readings(&qs[24..], &zero, &mut rng),
    )
}

fn held_out(report: &Report) -> f64 {
    report.validation.as_ref().unwrap().calibrated.rms
}

#[test]
fn a_heavy_robot_measured_where_it_works_gets_gravity_terms() {
    let setup = heavy_setup(false);
    let (data, held) = split(&setup, 31);
    let auto = calibrated(&setup, &data, &held, GravitySpec::Auto);
    let geometry = calibrated(&setup, &data, &held, GravitySpec::Fixed(Gravity::None));
    let ladder = auto.ladder.as_ref().unwrap();
    println!("{ladder:#?}");
    assert_ne!(auto.gravity, Gravity::None, "{ladder:#?}");
    // The arm's three terms are scored on this anthropomorphic arm, not skipped.
    let arm = ladder
        .rungs
        .iter()
        .find(|r| r.gravity == Gravity::Arm)
        .unwrap();
    assert!(arm.rms.is_some() && arm.skipped.is_none(), "{arm:#?}");
    // The region is the narrow one, not the joint limits: joint 2 within 0..12 deg (the box
    // of the postures' hull, within the old box's 5 deg margin on either side).
    assert!(ladder.region.lower[1] >= (-5.0f64 - 1e-9).to_radians());
    assert!(ladder.region.upper[1] <= (17.0f64 + 1e-9).to_radians());
    let (a, g) = (held_out(&auto), held_out(&geometry));
    assert!(a < 0.8 * g, "{a} against {g}");
    // On a robot without link masses too, the model the default chose, given by name
    // (`--gravity <it> --maps none`), is fitted as its rung: one bound, the same fit and the
    // same held-out figure.
    let given = calibrated(&setup, &data, &held, GravitySpec::Fixed(auto.gravity));
    let apart = (&auto.fit.estimate.values - &given.fit.estimate.values).amax();
    assert!(apart <= 1e-12, "{apart:e}");
    assert_eq!(auto.gravity_bound, given.gravity_bound);
    assert!(
        (held_out(&given) - a).abs() <= 1e-12 * a,
        "{} {a}",
        held_out(&given)
    );
    // `masses` named on this robot without link masses: refused for that, not as a model the
    // postures leave undetermined.
    let e = try_bounded(
        &setup,
        (&data, &held),
        GravitySpec::Fixed(Gravity::Masses),
        None,
    );
    let e = e.err().map(|e| e.to_string()).unwrap_or_default();
    assert!(
        e.contains("gives no link masses") && !e.contains("do not determine"),
        "{e}"
    );
}

/// 24 postures read at four points give the jackknife+ 288 held-out values, fewer than the 333
/// a finite 99.7 % end needs: every end comes from the fit's Gaussian bound, finite, and the
/// intervals cover the held-out readings about as the level says, not vacuously.
#[test]
fn a_99_7_bound_from_the_fit_where_the_jackknife_has_none() {
    let setup = heavy_setup(false);
    let (data, held) = split(&setup, 32);
    let report = at_level(&setup, (&data, &held), GravitySpec::Auto, Some(0.997));
    let h = report.validation.as_ref().unwrap();
    let intervals = h.intervals.as_ref().unwrap();
    assert_eq!(h.from_fit, 3 * intervals.len());
    assert!(intervals.iter().flatten().flatten().all(|v| v.is_finite()));
    // Each half-width is at least z = 2.9677 times the held-out RMS per coordinate of the
    // folds (a few times the tracker's 0.015 mm), and far below a millimetre.
    for i in intervals.iter().flatten() {
        assert!(i[1] > 2.9 * 0.015e-3 && i[1] < 1e-3, "{i:?}");
        assert!((i[0] + i[1]).abs() < 1e-15);
    }
    let c = h.coverage.unwrap();
    assert!(c.coverage() >= 0.95, "{c:?}");
    let shown = stiffid::app::calibrate::document::held(h);
    let i = shown.intervals.unwrap();
    assert_eq!(i.method, "the fit's Gaussian bound");
    assert_eq!(i.held_out_needed, 333);
    assert!(i.assumption.is_some());
    // At 95 % the jackknife+ has enough: no end from the fit.
    let report = at_level(&setup, (&data, &held), GravitySpec::Auto, Some(0.95));
    assert_eq!(report.validation.unwrap().from_fit, 0);
}

/// The measure of the default against the geometry and the explicit models on `splits` splits
/// (`cargo test --profile ci -p stiffid --test it ladder_heavy::measure -- --ignored --nocapture`).
#[test]
#[ignore = "a measurement, minutes long"]
fn measure() {
    let splits: u64 = std::env::var("SPLITS").map_or(10, |s| s.parse().unwrap());
    // Test postures at the joint limits' corners: the region spans the joint limits from the
    // postures to those corners (close to the screen before it judged where the robot is used).
    let everywhere = "[test]\npostures_deg = [[-185.0, -60.0, -132.0, -360.0, -125.0, -360.0], [185.0, 76.0, 180.0, 360.0, 125.0, 360.0]]";
    let cases = [
        (false, false, ""),
        (true, false, ""),
        (false, true, ""),
        (true, true, ""),
        (false, false, everywhere),
        (true, false, everywhere),
    ];
    for (with_masses, one_point, more) in cases {
        let setup = setup_with(with_masses, one_point, more);
        let with_masses = format!(
            "{with_masses}, one point {one_point}, limits {}",
            !more.is_empty()
        );
        let mut rows = Vec::new();
        for seed in 0..splits {
            let (data, held) = split(&setup, 1000 + seed);
            let mut row = Vec::new();
            let mut specs = vec![GravitySpec::Auto, GravitySpec::Fixed(Gravity::None)];
            specs.push(GravitySpec::Fixed(Gravity::Arm));
            specs.push(GravitySpec::Fixed(Gravity::Lumped));
            if with_masses.starts_with("true") {
                specs.push(GravitySpec::Fixed(Gravity::Masses));
            }
            let mut chosen = Gravity::None;
            for spec in specs {
                let r = calibrated(&setup, &data, &held, spec);
                if spec == GravitySpec::Auto {
                    chosen = r.gravity;
                    for rung in &r.ladder.as_ref().unwrap().rungs {
                        let why = rung.skipped.as_deref().unwrap_or_default();
                        println!(
                            "  {:?} {:?} {:.70}",
                            rung.gravity,
                            rung.rms.map(|v| v * 1e3),
                            why
                        );
                    }
                }
                row.push(held_out(&r) * 1e3);
            }
            println!("masses {with_masses} seed {seed}: auto ({chosen:?}), none, arm, lumped[, masses] held-out RMS mm {row:.4?}");
            rows.push(row);
        }
        let n = rows.len() as f64;
        let mean: Vec<f64> = (0..rows[0].len())
            .map(|k| rows.iter().map(|r| r[k]).sum::<f64>() / n)
            .collect();
        let worse = rows.iter().filter(|r| r[0] > r[1] + 0.05).count();
        println!("masses {with_masses}: mean {mean:.4?}; auto worse than geometry by > 0.05 mm on {worse}");
    }
}

/// `n` postures drawn at random over the middle 60 % of the robot's axis ranges (at most
/// +-2.6 rad), axis angles, rad.
fn wide(setup: &Setup, n: usize, rng: &mut ChaCha8Rng) -> Vec<Vector6<f64>> {
    let l = setup.robot().limits();
    (0..n)
        .map(|_| {
            Vector6::from_fn(|i, _| {
                let (lo, hi) = (l.lower[i].max(-2.6), l.upper[i].min(2.6));
                let mid = 0.5 * (lo + hi);
                mid + 0.6 * (hi - lo) * (rand::Rng::random::<f64>(rng) - 0.5)
            })
        })
        .collect()
}

/// The measure of every gravity model named on random 24/12 splits of 36 postures over the
/// joint ranges (`cargo test --profile ci -p stiffid --test it ladder_heavy::random_splits --
/// --ignored --nocapture`; `SPLITS`, `ONE_POINT`).
#[test]
#[ignore = "a measurement"]
fn random_splits() {
    let splits: u64 = std::env::var("SPLITS").map_or(10, |s| s.parse().unwrap());
    let setup = setup_with(true, std::env::var("ONE_POINT").is_ok(), "");
    let specs = [
        GravitySpec::Auto,
        GravitySpec::Fixed(Gravity::None),
        GravitySpec::Fixed(Gravity::Arm),
        GravitySpec::Fixed(Gravity::Lumped),
        GravitySpec::Fixed(Gravity::Masses),
    ];
    let mut sums = vec![0.0; specs.len()];
    for seed in 0..splits {
        let mut rng = ChaCha8Rng::seed_from_u64(7000 + seed);
        let truth = Truth::new(&setup, &mut rng);
        let qs = match std::env::var("NARROW") {
            Ok(_) => narrow(36, &mut rng),
            Err(_) => wide(&setup, 36, &mut rng),
        };
        let zero = [Vector6::zeros()];
        let far = wide(&setup, 12, &mut rng);
        let (data, held) = (
            truth.readings(&qs[..24], &zero, &mut rng),
            match std::env::var("HELD_WIDE") {
                Ok(_) => truth.readings(&far, &zero, &mut rng),
                Err(_) => truth.readings(&qs[24..], &zero, &mut rng),
            },
        );
        let mut row = Vec::new();
        let mut chosen = Gravity::None;
        for (i, &spec) in specs.iter().enumerate() {
            let bound = std::env::var("BOUND_MRAD")
                .ok()
                .map(|s| s.parse::<f64>().unwrap() * 1e-3);
            let r = match try_bounded(&setup, (&data, &held), spec, bound) {
                Ok(r) => r,
                Err(e) => {
                    println!("  {spec:?} refused: {e}");
                    row.push(f64::NAN);
                    continue;
                }
            };
            if spec == GravitySpec::Auto {
                chosen = r.gravity;
                for rung in &r.ladder.as_ref().unwrap().rungs {
                    let why = rung.skipped.as_deref().unwrap_or_default();
                    println!(
                        "  {:?} {:?} {:.90}",
                        rung.gravity,
                        rung.rms.map(|v| v * 1e3),
                        why
                    );
                }
            }
            sums[i] += held_out(&r).powi(2);
            row.push(held_out(&r) * 1e3);
        }
        println!(
            "seed {seed}: auto ({chosen:?}), none, arm, lumped, masses held-out RMS mm {row:.4?}"
        );
    }
    let rms: Vec<f64> = sums
        .iter()
        .map(|s| (s / splits as f64).sqrt() * 1e3)
        .collect();
    println!("RMS over splits mm {rms:.4?}");
}
