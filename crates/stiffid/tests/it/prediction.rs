//! Prediction intervals (jackknife+ over the postures, `stiffid::internal::identify::prediction`) on seeded
//! simulations: with a compliance the fitted model lacks they still cover at their level, and
//! with the true model the parameter intervals and the prediction intervals both cover at 95%.
//!
//! Every data set draws its postures uniformly in the paper setup's bounds and a force of 200 to
//! 1000 N in a random direction per posture (exchangeable postures), the tracker noise of the
//! setup on every coordinate; 12 postures are identified (leave one posture out) and 4 others
//! validated.

use nalgebra::{DVector, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::internal::identify::compare::pool_by_name;
use stiffid::internal::identify::cross_validation::{cross_validate, cross_validate_model, Method};
use stiffid::internal::identify::prediction::calibrate;
use stiffid::internal::identify::svd::fit;
use stiffid::internal::identify::validate::compare_at;
use stiffid::internal::identify::Identify;
use stiffid::internal::model::prediction::{inside, Calibration};
use stiffid::internal::model::{Compliance, Family};
use stiffid::internal::observation::{posture_block, Measurement, Observations};
use stiffid::internal::setup::Setup;

const DATA_SETS: u64 = 200;
const TRAIN: usize = 12;
const TEST: usize = 4;

/// The paper's cell with an elbow spring about x of joint 3's frame (lateral bending) of
/// `k` Nm/rad.
fn with_elbow(k: f64) -> Setup {
    let paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut springs = Family::Tilt
        .springs(paper.robot(), &[3], Some(k), None, "test")
        .unwrap();
    springs.truncate(1);
    paper
        .to_builder()
        .with_virtual_springs(springs)
        .build()
        .unwrap()
}

/// `n` postures of data set `rng` under random forces, displaced by `truth` (the compliance of
/// every parameter of `s`) plus the tracker noise; postures numbered from `first`.
fn data(s: &Setup, truth: &DVector<f64>, n: usize, rng: &mut ChaCha8Rng) -> Vec<Measurement> {
    let noise = Normal::new(0.0, s.noise().displacement_sd()).unwrap();
    let b = s.bounds();
    let mut out = Vec::new();
    for posture in 0..n {
        let q = Vector6::from_fn(|i, _| rng.random_range(b.lower[i]..b.upper[i]));
        let direction = Vector3::from_fn(|_, _| noise.sample(rng)).normalize();
        let f = direction * rng.random_range(200.0..1000.0);
        let wrench = Vector6::new(f.x, f.y, f.z, 0.0, 0.0, 0.0);
        let frames = s.robot().frames(&q);
        let d = posture_block(s.arm(), &frames, &wrench) * truth;
        for point in 0..s.tool().measuring_points.len() {
            let e = Vector3::from_fn(|_, _| noise.sample(rng));
            out.push(Measurement {
                posture,
                point,
                q,
                e: Default::default(),
                wrench,
                displacement: d.fixed_rows::<3>(3 * point) + e,
            });
        }
    }
    out
}

/// Coverage counts `[inside, coordinates]` of `compliance` at `level` on `test`, by validation.
fn covered(s: &Setup, c: &Compliance, test: &[Measurement], level: f64) -> [usize; 2] {
    let p = compare_at(s.arm(), c, test, level)
        .unwrap()
        .prediction
        .unwrap();
    [p.covered, p.coordinates]
}

/// [`covered`] by hand from the intervals (a fit whose compliance is not all positive, which
/// validation refuses, still predicts).
fn covered_by_hand(s: &Setup, p: &Calibration, test: &[Measurement], level: f64) -> [usize; 2] {
    let obs = Observations::from_measurements(s.arm(), test).unwrap();
    let inside = (0..test.len())
        .map(|i| {
            let interval = p.interval(&obs.psi.rows(3 * i, 3).into_owned(), level);
            let d = test[i].displacement;
            inside(&interval, &[d.x, d.y, d.z])
                .iter()
                .filter(|b| **b)
                .count()
        })
        .sum();
    [inside, 3 * test.len()]
}

/// The paper's setup with the candidates `names` of the default pool in its model, and the
/// compliance of every parameter: the drives' nominal, then `values` (rad/Nm, m/N, or rad for a
/// lost motion).
fn with_candidates(names: &[&str], values: &[f64]) -> (Setup, DVector<f64>) {
    let paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let names: Vec<String> = names.iter().map(|n| n.to_string()).collect();
    let springs = pool_by_name(&paper, &names).unwrap().candidates;
    assert_eq!(springs.len(), values.len());
    let truth = paper
        .to_builder()
        .with_virtual_springs(springs)
        .build()
        .unwrap();
    let mut h = DVector::zeros(6 + values.len());
    h.rows_mut(0, 6)
        .copy_from(&paper.model_nominal_compliance().unwrap());
    h.rows_mut(6, values.len()).copy_from_slice(values);
    (truth, h)
}

/// The drives-only model fitted to data with compliances it lacks, each about a tenth to a fifth
/// of the deflection: an elbow spring about x of joint 3's frame, the forearm bending at its
/// mid-length, a lost motion of joint 2 (the deflection `b sign(tau)`, smoothed), and all three
/// at once. Held out on postures the fit has not seen, the 90% intervals cover at least 88% of
/// the coordinates in every case, while the drives' parameter intervals miss.
#[test]
fn prediction_intervals_cover_compliances_the_model_lacks() {
    let drives = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let cases: [(&[&str], &[f64]); 4] = [
        (&["tilt3_x"], &[1.0 / 1.5e6]),
        (&["bend3_x"], &[1.0 / 1.5e6]),
        (&["lost2"], &[100e-6]),
        (
            &["tilt3_x", "bend3_x", "lost2"],
            &[1.0 / 3e6, 1.0 / 3e6, 50e-6],
        ),
    ];
    for (case, (names, values)) in cases.iter().enumerate() {
        let (truth_setup, truth) = with_candidates(names, values);
        let h_true = truth.rows(0, 6).into_owned();
        let (mut inside, mut all, mut k_inside, mut share) = (0, 0, 0, 0.0);
        for seed in 0..DATA_SETS {
            let mut rng = ChaCha8Rng::seed_from_u64(10_000 * case as u64 + seed);
            let train = data(&truth_setup, &truth, TRAIN, &mut rng);
            let test = data(&truth_setup, &truth, TEST, &mut rng);
            let obs = Observations::from_measurements(drives.arm(), &train).unwrap();
            let id = obs.least_squares().unwrap();
            let cv = cross_validate(&obs, &id, TRAIN, Method::LeastSquares).unwrap();
            let calibration = calibrate(&obs, &cv, drives.noise().displacement_sd());
            let [a, b] = covered_by_hand(&drives, &calibration, &test, 0.9);
            (inside, all) = (inside + a, all + b);
            let u = id.uncertainty.unwrap();
            k_inside += (0..6)
                .filter(|&j| {
                    (u.compliance_ci95[j][0]..=u.compliance_ci95[j][1]).contains(&h_true[j])
                })
                .count();
            share += cv.explained();
        }
        let coverage = inside as f64 / all as f64;
        let k_coverage = k_inside as f64 / (6 * DATA_SETS) as f64;
        eprintln!(
            "unmodelled {names:?}: 90% prediction coverage {coverage:.4} of {all}, 95% stiffness coverage {k_coverage:.3}, held-out share {:.3}",
            share / DATA_SETS as f64
        );
        assert!(coverage >= 0.88, "{names:?}: {coverage}");
        // Not a vacuous guarantee: the intervals are not all-covering, and the model error is real.
        assert!(coverage <= 0.97, "{names:?}: {coverage}");
        assert!(k_coverage < 0.8, "{names:?}: {k_coverage}");
    }
}

/// With the true model (the drives and the elbow spring), the 95% parameter intervals and the
/// 95% prediction intervals both cover 93-97%.
#[test]
fn with_the_true_model_parameter_and_prediction_intervals_cover_at_their_level() {
    let s = with_elbow(1.5e6);
    let truth = s.model_compliance("test").unwrap().h;
    let parameters = s.model().parameters();
    let (mut inside, mut all, mut k_inside) = (0, 0, 0);
    for seed in 0..DATA_SETS {
        let mut rng = ChaCha8Rng::seed_from_u64(1000 + seed);
        let train = data(&s, &truth, TRAIN, &mut rng);
        let test = data(&s, &truth, TEST, &mut rng);
        let obs = Observations::from_measurements(s.arm(), &train).unwrap();
        let f = fit(&obs, &parameters).unwrap();
        let cv = cross_validate_model(&obs, &f, TRAIN, Method::LeastSquares).unwrap();
        let c = Compliance {
            h: f.compliance.clone(),
            covariance: None,
            prediction: Some(calibrate(&obs, &cv, s.noise().displacement_sd())),
            own_weight: None,
            region: Default::default(),
            model_form: None,
        };
        let [a, b] = covered(&s, &c, &test, 0.95);
        (inside, all) = (inside + a, all + b);
        k_inside += f
            .intervals
            .iter()
            .zip(truth.iter())
            .filter(|(i, h)| {
                let [lo, hi] = i.unwrap().compliance_ci95;
                (lo..=hi).contains(*h)
            })
            .count();
    }
    let coverage = inside as f64 / all as f64;
    let k_coverage = k_inside as f64 / (parameters.len() as u64 * DATA_SETS) as f64;
    eprintln!("true model: 95% prediction coverage {coverage:.4} of {all}, 95% parameter coverage {k_coverage:.4}");
    assert!((0.93..=0.97).contains(&coverage), "{coverage}");
    assert!((0.93..=0.97).contains(&k_coverage), "{k_coverage}");
}

/// Coverage counts `[inside, coordinates]` of the deflection intervals (P3) of `calibration`
/// and `h` at `level` on the true displacements of `test` (`truth_setup` displaced by `truth`,
/// no noise), and the sums of their half-widths, of the prediction's absolute errors and of the
/// measurement intervals' (P2) half-widths (m).
fn deflection_covered(
    s: &Setup,
    h: &DVector<f64>,
    calibration: &Calibration,
    (truth_setup, truth): (&Setup, &DVector<f64>),
    test: &[Measurement],
    level: f64,
) -> [f64; 5] {
    let obs = Observations::from_measurements(s.arm(), test).unwrap();
    let mut out = [0.0; 5];
    for (i, m) in test.iter().enumerate() {
        let rows = obs.psi.rows(3 * i, 3).into_owned();
        let interval = calibration.deflection_interval(&rows, h, level);
        let frames = truth_setup.robot().frames(&m.q);
        let d = (posture_block(truth_setup.arm(), &frames, &m.wrench) * truth)
            .fixed_rows::<3>(3 * m.point)
            .into_owned();
        let mu = &rows * h;
        out[0] += inside(&interval, &[d.x, d.y, d.z])
            .iter()
            .filter(|b| **b)
            .count() as f64;
        out[1] += 3.0;
        out[2] += (0..3)
            .map(|c| (interval[c][1] - interval[c][0]) / 2.0)
            .sum::<f64>();
        out[3] += (0..3).map(|c| (d[c] - mu[c]).abs()).sum::<f64>();
        let measurement = calibration.interval(&rows, level);
        out[4] += (0..3)
            .map(|c| (measurement[c][1] - measurement[c][0]) / 2.0)
            .sum::<f64>();
    }
    out
}

/// The deflection intervals (P3) cover the true deflection, what a compensation by the
/// prediction leaves, at their level, with the true model and with compliances the model lacks;
/// and they are as wide as that error, where the measurement intervals (P2) hold the tracker
/// noise scaled with the deflection.
#[test]
fn deflection_intervals_cover_the_true_deflection() {
    let drives = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let elbow = with_elbow(1.5e6);
    let cases: [(&[&str], &[f64], bool); 3] = [
        (&["tilt3_x"], &[1.0 / 1.5e6], true),
        (&["tilt3_x"], &[1.0 / 1.5e6], false),
        (
            &["tilt3_x", "bend3_x", "lost2"],
            &[1.0 / 3e6, 1.0 / 3e6, 50e-6],
            false,
        ),
    ];
    for (case, (names, values, true_model)) in cases.iter().enumerate() {
        let (truth_setup, truth) = with_candidates(names, values);
        let model = if *true_model { &elbow } else { &drives };
        let parameters = model.model().parameters();
        for level in [0.9, 0.95] {
            let mut sums = [0.0; 5];
            for seed in 0..DATA_SETS {
                let mut rng = ChaCha8Rng::seed_from_u64(20_000 * case as u64 + seed);
                let train = data(&truth_setup, &truth, TRAIN, &mut rng);
                let test = data(&truth_setup, &truth, TEST, &mut rng);
                let obs = Observations::from_measurements(model.arm(), &train).unwrap();
                let f = fit(&obs, &parameters).unwrap();
                let cv = cross_validate_model(&obs, &f, TRAIN, Method::LeastSquares).unwrap();
                let calibration = calibrate(&obs, &cv, model.noise().displacement_sd());
                let c = deflection_covered(
                    model,
                    &f.compliance,
                    &calibration,
                    (&truth_setup, &truth),
                    &test,
                    level,
                );
                sums.iter_mut().zip(c).for_each(|(s, c)| *s += c);
            }
            let coverage = sums[0] / sums[1];
            let [ratio, measurement] = [sums[2] / sums[3], sums[4] / sums[3]];
            eprintln!("{names:?} true model {true_model}: {level} deflection coverage {coverage:.4} of {}, half-width / mean error {ratio:.2} (measurement intervals {measurement:.2})", sums[1]);
            assert!(
                (level - 0.02..=level + 0.025).contains(&coverage),
                "{names:?} {level}: {coverage}"
            );
            // A Gaussian error's mean absolute value is 0.8 sigma: a half-width of z sigma is
            // 2.1 (90%) to 2.5 (95%) times it; heavier tails widen it.
            assert!((2.0..5.0).contains(&ratio), "{names:?} {level}: {ratio}");
            if *true_model {
                // The noise no longer scales with the deflection.
                assert!(measurement > 4.0 * ratio, "{measurement} vs {ratio}");
            }
        }
    }
}
