//! The error budget's model-form part (crate::machining::compensate::budget): the models the data
//! support and their resampled parameter sets written by `identify --compare-models --bootstrap`
//! into the stiffness file, read back, and their spread at a compensated point against a direct
//! computation over the resamples.

use crate::candidates::{measure, paper_with, ELBOW};
use nalgebra::{DVector, Vector3, Vector6};
use std::io::Empty;
use stiffid::app::compensate::ranking::{Ranking, RankingDocument};
use stiffid::app::identify::{run, Options, Report, Request};
use stiffid::app::measurements::Data;
use stiffid::internal::design::random_group;
use stiffid::internal::identify::compare::bootstrap::percentile;
use stiffid::internal::identify::compare::{bootstrap, compare, Resampling};
use stiffid::internal::machining::compensate::{
    self, Options as CompensateOptions, PathPoint, Target,
};
use stiffid::internal::observation::deflection::{Frame, Points};
use stiffid::internal::observation::Measurement;
use stiffid::internal::robot::ik::tool_pose;
use stiffid::internal::setup::Setup;

/// The truth: the drives and an elbow spring 3 times stiffer than `ELBOW`'s, measured with 10
/// times the tracker noise, so that the drives alone and the drives with the elbow fit the data
/// about equally (each is within the one-standard-error margin in about two thirds of the
/// resamples); the setup declaring the elbow as a candidate; measurements of 12 random postures.
fn simulated() -> (Setup, Vec<Measurement>) {
    let stiff = ELBOW.replace("4e6", "1.2e7");
    let truth = paper_with(&stiff);
    let declared = paper_with(&stiff.replace("rotation\"", "rotation\"\ncandidate = true"));
    let h = truth.model_nominal_compliance().unwrap();
    let postures = random_group(&truth, 12, 5);
    let sigma = 10.0 * truth.noise().displacement_sd();
    (declared, measure(&truth, &postures, &h, sigma, 4))
}

/// The 95% percentile of `|t_s - t|` over every supported model of every resample of a
/// bootstrap with `seed`, each set's translation from the observation's forward model
/// ([`Points::deflection`]) on a setup holding that model's springs, `t` the drives' (the
/// data's fit of the setup's model) at `q` under `wrench`.
fn direct(
    s: &Setup,
    data: &[Measurement],
    q: &Vector6<f64>,
    wrench: &Vector6<f64>,
    t: &Vector3<f64>,
    resamples: usize,
    seed: u64,
) -> (f64, usize) {
    let candidates = s.candidate_springs().to_vec();
    let c = compare(s, data, &candidates, false).unwrap();
    let b = bootstrap(
        s,
        data,
        &candidates,
        &c,
        Resampling { resamples, seed },
        &(),
    )
    .unwrap();
    let all = s.model().with(&candidates).unwrap();
    let mut e: Vec<f64> = Vec::new();
    let mut models = std::collections::BTreeSet::new();
    for (indices, h) in b.supported.iter().flatten() {
        models.insert(indices.clone());
        let springs = indices[6..]
            .iter()
            .map(|&j| all.springs()[j - 6].clone())
            .collect();
        let m = s
            .to_builder()
            .with_virtual_springs(springs)
            .with_candidate_springs(Vec::new())
            .build()
            .unwrap();
        let frames = m.robot().frames(q);
        let tcp = m.tool().tcp;
        let points = Points {
            arm: m.arm(),
            frames: &frames,
            loaded: &tcp,
            observed: &tcp,
        };
        let d = points.deflection(wrench, &DVector::from_column_slice(h));
        e.push((d.displacement.fixed_rows::<3>(0) - t).norm());
    }
    e.sort_by(f64::total_cmp);
    (percentile(&e, 0.95), models.len())
}

/// Two models fit the data about equally (the drives alone, the drives with the elbow): the
/// stiffness file `--stiffness-out` writes carries both with their resampled sets, and the
/// compensated point's model-form part is the 95% percentile of their translations' distance
/// from the compensation's, as a direct computation over the same resamples gives it (to
/// rounding) and within 10% over 600 resamples of another seed (Monte Carlo); it is not small
/// against the deflection, and the bound adds it whole.
#[test]
fn the_model_form_part_is_the_spread_over_the_resamples() {
    let (s, data) = simulated();
    let report = run(Request::<Empty> {
        progress: &(),
        setup_name: "setup".into(),
        setup: &s,
        data: Data::Measurements(data.clone()),
        options: Options {
            compare_models: true,
            candidates: Some(vec!["declared".into()]),
            bootstrap: Some(300),
            seed: Some(1),
            ..Options::default()
        },
    })
    .unwrap();
    let Report::Comparison(report) = report.report else {
        panic!("not a comparison")
    };
    let file = report.stiffness_file().unwrap();
    let text = serde_json::to_string(&file.document()).unwrap();
    let compliance = stiffid::internal::io::stiffness::parse(&text)
        .unwrap()
        .compliance(s.model())
        .unwrap();
    let form = compliance.model_form.as_ref().unwrap();
    // A set's value beyond any robot's compliance (or not a number) is refused, naming it.
    let mut bad: serde_json::Value = serde_json::from_str(&text).unwrap();
    bad["model_form"]["models"][0]["compliance_si"][0][0] = serde_json::json!(1e300);
    let error = stiffid::internal::io::stiffness::parse(&bad.to_string())
        .and_then(|f| f.compliance(s.model()))
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("model_form.models[1].compliance_si[1]") && error.contains("at most 1"),
        "{error}"
    );
    // The recommended model fitted to every posture rides along: one set, the comparison's fit.
    let recommended = form.recommended.as_ref().unwrap();
    let fitted = &report.comparison.recommended_fit.compliance;
    assert_eq!(recommended.sets.len(), 1);
    assert!((&recommended.sets[0] - fitted).norm() <= 1e-12 * fitted.norm());
    let two = bad["model_form"]["recommended"]["compliance_si"][0].clone();
    let mut bad: serde_json::Value = serde_json::from_str(&text).unwrap();
    bad["model_form"]["recommended"]["compliance_si"] = serde_json::json!([two.clone(), two]);
    let error = stiffid::internal::io::stiffness::parse(&bad.to_string())
        .and_then(|f| f.compliance(s.model()))
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("model_form.recommended.compliance_si")
            && error.contains("one parameter set"),
        "{error}"
    );
    let counts: Vec<usize> = form.models.iter().map(|m| m.sets.len()).collect();
    println!("sets {counts:?}");
    assert_eq!(form.models.len(), 2, "{counts:?}");
    assert!(counts.iter().all(|&n| n >= 30), "{counts:?}");
    let q = s.test_postures()[0];
    let wrench = Vector6::new(300.0, -100.0, -400.0, 0.0, 0.0, 0.0);
    let point = PathPoint {
        line: 1,
        target: Target::Posture(q),
        wrench,
        frame: Frame::Base,
        external: stiffid::internal::robot::external::ExternalValues::NONE,
    };
    let options = CompensateOptions::for_setup(&s);
    let r =
        &compensate::path(s.arm(), &compliance, std::slice::from_ref(&point), &options).unwrap()[0];
    let part = r.budget.model_form.unwrap();
    let t: Vector3<f64> = r.deflection.fixed_rows::<3>(0).into_owned();
    let (same, models) = direct(&s, &data, &q, &wrench, &t, 300, 1);
    assert_eq!(models, 2);
    assert!((part - same).abs() <= 1e-9 * same, "{part} against {same}");
    let (other, _) = direct(&s, &data, &q, &wrench, &t, 600, 7);
    assert!(
        (part - other).abs() <= 0.1 * other,
        "{part} against {other} over other resamples"
    );
    assert!(part > 0.02 * t.norm(), "{part} of {}", t.norm());
    let b = &r.budget;
    let random = b
        .compensation
        .unwrap_or(0.0)
        .hypot(b.calibration.unwrap_or(0.0));
    assert!((b.bound - (b.left + b.force + part + random)).abs() < 1e-15);
    // Without the section the part is absent, as before.
    let plain = stiffid::internal::model::Compliance {
        model_form: None,
        ..compliance.clone()
    };
    let r = &compensate::path(s.arm(), &plain, &[point], &options).unwrap()[0];
    assert_eq!(r.budget.model_form, None);
}

/// The setup, the drives' compliance, the recommended model's setup and compliance.
type Fanuc = (
    Setup,
    stiffid::internal::model::Compliance,
    Setup,
    stiffid::internal::model::Compliance,
);

/// The FANUC data's identification by the model comparison with 100 bootstrap resamples: the
/// setup, the compliance of the six drives with the `model_form` the stiffness file carries, and
/// the recommended model's setup and compliance (computed once for the tests that read it).
fn fanuc() -> &'static Fanuc {
    static FANUC: std::sync::OnceLock<Fanuc> = std::sync::OnceLock::new();
    FANUC.get_or_init(|| fanuc_with(100))
}

/// As [`fanuc`], with `resamples` bootstrap resamples.
fn fanuc_with(resamples: usize) -> Fanuc {
    let s = stiffid::internal::setup::builtin("fanuc-r2000ic-165f").unwrap();
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/data/fanuc-r2000ic-165f/measurements.csv"
    );
    let report = run(Request {
        progress: &(),
        setup_name: "setup".into(),
        setup: &s,
        data: Data::File {
            name: "measurements.csv".into(),
            reader: std::fs::File::open(path).unwrap(),
        },
        options: Options {
            compare_models: true,
            bootstrap: Some(resamples),
            ..Options::default()
        },
    })
    .unwrap();
    let Report::Comparison(report) = report.report else {
        panic!("not a comparison")
    };
    let text = serde_json::to_string(&report.stiffness_file().unwrap().document()).unwrap();
    let drives = stiffid::internal::io::stiffness::parse(&text)
        .unwrap()
        .compliance(s.model())
        .unwrap();
    let c = &report.comparison;
    let recommended = s
        .to_builder()
        .with_virtual_springs(c.recommended_springs.clone())
        .build()
        .unwrap();
    let h = c.recommended_fit.compliance.clone();
    let compliance = stiffid::internal::model::Compliance {
        h,
        covariance: None,
        prediction: None,
        own_weight: None,
        region: Default::default(),
        model_form: None,
    };
    (s, drives, recommended, compliance)
}

/// Spearman's rank correlation of `a` and `b` (no ties).
fn spearman(a: &[f64], b: &[f64]) -> f64 {
    let rank = |x: &[f64]| -> Vec<f64> {
        let mut i: Vec<usize> = (0..x.len()).collect();
        i.sort_by(|p, q| x[*p].total_cmp(&x[*q]));
        let mut r = vec![0.0; x.len()];
        for (k, j) in i.iter().enumerate() {
            r[*j] = k as f64;
        }
        r
    };
    let (ra, rb) = (rank(a), rank(b));
    let n = a.len() as f64;
    let d2: f64 = ra.iter().zip(&rb).map(|(x, y)| (x - y).powi(2)).sum();
    1.0 - 6.0 * d2 / (n * (n * n - 1.0))
}

/// On the real FANUC data, one drilling hole (600 N of thrust along the tool axis) at seven
/// rotations about the spindle, -90 to 90 deg: the six drives and the recommended model (drives,
/// `tilt3_x`, `tool_y`) rank the rotations in opposite order (Spearman's rho -0.79), and the
/// drives' error bound shows it: at every rotation its model-form part, the spread over the
/// models the data support, is larger than what the drives promise by their best rotation over
/// the recommended model's best (0.21 mm).
#[test]
fn the_drives_and_the_recommended_model_rank_a_holes_postures_in_opposite_order() {
    let (s, drives, rec, rec_c) = fanuc();
    let q = random_group(s, 300, 11)[196];
    let start = tool_pose(&s.robot().frames(&q), &s.tool().tcp);
    let mut options = CompensateOptions::for_setup(s);
    options.q0 = q;
    let at = |setup: &Setup, c: &stiffid::internal::model::Compliance, deg: f64| {
        let rotation =
            nalgebra::UnitQuaternion::from_axis_angle(&Vector3::z_axis(), deg.to_radians());
        let point = PathPoint {
            line: 1 + ((deg + 90.0) / 30.0) as u64,
            target: Target::Pose(start * rotation),
            wrench: Vector6::new(0.0, 0.0, 600.0, 0.0, 0.0, 0.0),
            frame: Frame::Tool,
            external: stiffid::internal::robot::external::ExternalValues::NONE,
        };
        compensate::path(setup.arm(), c, &[point], &options)
            .unwrap()
            .remove(0)
    };
    let angles = [-90.0, -60.0, -30.0, 0.0, 30.0, 60.0, 90.0];
    let a: Vec<_> = angles.iter().map(|&g| at(s, drives, g)).collect();
    let b: Vec<_> = angles.iter().map(|&g| at(rec, rec_c, g)).collect();
    let norm = |r: &compensate::Compensated| r.deflection.fixed_rows::<3>(0).norm() * 1e3;
    let da: Vec<f64> = a.iter().map(norm).collect();
    let db: Vec<f64> = b.iter().map(norm).collect();
    let mf: Vec<f64> = a
        .iter()
        .map(|r| r.budget.model_form.unwrap() * 1e3)
        .collect();
    let bound: Vec<f64> = a.iter().map(|r| r.budget.bound * 1e3).collect();
    let rho = spearman(&da, &db);
    println!("q {:?}\ndrives {da:.4?}\nrecommended {db:.4?}\nmodel form {mf:.4?}\nbound {bound:.4?}\nrho {rho:.3}", q.map(f64::to_degrees).as_slice());
    assert!(rho <= -0.5, "{rho}");
    // The compensation says so: the stiffness file's recommended model, set beside the drives at
    // every point, gives the recommended setup's own deflections and their rho, and a warning.
    let (section, warning) = ranked(s, drives, &a);
    assert!((section.rho.unwrap() - rho).abs() < 1e-12, "{section:?}");
    assert!(!section.agree && section.recommended_springs.len() == 2);
    for p in &section.largest_rank_differences {
        let k = (p.line - 1) as usize;
        assert!(
            (p.recommended_deflection_mm - db[k]).abs() < 1e-9 * db[k],
            "{p:?} against {}",
            db[k]
        );
        assert!((p.deflection_mm - da[k]).abs() < 1e-12 * da[k]);
    }
    let warning = warning.unwrap();
    assert_eq!(warning.kind.code(), "model-form");
    assert!(warning.message.contains("rho -0.79"), "{}", warning.message);
    // What the drives promise by their best rotation over the recommended model's best.
    let best = |x: &[f64]| (0..x.len()).min_by(|i, j| x[*i].total_cmp(&x[*j])).unwrap();
    let promised = da[best(&db)] - da[best(&da)];
    assert!(promised > 0.15, "{promised}");
    assert!(
        mf.iter().all(|&m| m > promised),
        "{mf:?} against {promised}"
    );
}

/// The compensation's `model_ranking` of the points compensated as `results` (lines 1, 2, ...)
/// with `compliance` on `s`, and its warning.
fn ranked(
    s: &Setup,
    compliance: &stiffid::internal::model::Compliance,
    results: &[compensate::Compensated],
) -> (
    RankingDocument,
    Option<stiffid::internal::common::warning::Warning>,
) {
    let mut ranking = Ranking::new(s.arm(), compliance.model_form.as_ref()).unwrap();
    for (k, r) in results.iter().enumerate() {
        ranking.add(s.arm(), k as u64 + 1, r);
    }
    ranking.finish()
}

/// Where the models agree, the compensation says nothing: on the real FANUC data, seven holes
/// 10 mm apart towards the base drilled with a thrust growing from 100 to 700 N along the tool
/// (the deflection growing with it under both models), the drives and the recommended model
/// rank the points alike; a stiffness file without the recommended model, or whose recommended
/// model is its own, gives no ranking.
#[test]
fn the_drives_and_the_recommended_model_rank_growing_thrusts_alike() {
    let (s, drives, _, _) = fanuc();
    let q = random_group(s, 300, 11)[196];
    let start = tool_pose(&s.robot().frames(&q), &s.tool().tcp);
    let mut options = CompensateOptions::for_setup(s);
    options.q0 = q;
    let points: Vec<PathPoint> = (0..7)
        .map(|k| {
            let towards = nalgebra::Translation3::from(
                -start.translation.vector.normalize() * (0.01 * k as f64),
            );
            PathPoint {
                line: k + 1,
                target: Target::Pose(towards * start),
                wrench: Vector6::new(0.0, 0.0, 100.0 * (k + 1) as f64, 0.0, 0.0, 0.0),
                frame: Frame::Tool,
                external: stiffid::internal::robot::external::ExternalValues::NONE,
            }
        })
        .collect();
    let results = compensate::path(s.arm(), drives, &points, &options).unwrap();
    let (section, warning) = ranked(s, drives, &results);
    println!("{section:#?}");
    assert!(section.agree && section.rho.unwrap() >= 0.9, "{section:?}");
    assert_eq!(section.points, 7);
    assert!(warning.is_none());
    let mut form = drives.model_form.clone().unwrap();
    assert!(Ranking::new(s.arm(), Some(&form)).is_some());
    form.recommended = Some(stiffid::internal::model::FormModel {
        model: s.model().clone(),
        sets: vec![drives.h.clone()],
    });
    assert!(Ranking::new(s.arm(), Some(&form)).is_none());
    form.recommended = None;
    assert!(Ranking::new(s.arm(), Some(&form)).is_none());
}
