//! The design's evaluator (`crate::Evaluator`, `evaluate`): criteria by QR against other ways.

//! The n-parameter evaluator (a model with virtual springs) against the criteria computed from
//! the whole observation matrix by nalgebra's SVD, and its exact gradients against central
//! differences.

use crate::evaluator::*;
use crate::random_group;
use crate::Criterion;
use nalgebra::{DMatrix, Vector6};
use stiffid_core::observation::rope_observation_matrix;
use stiffid_core::setup::Setup;

/// The paper's setup (or the FANUC one, one measuring point) with a `[model]` fragment appended.
pub(crate) fn with_model(builtin: &str, model: &str) -> Setup {
    let text = stiffid_core::setup::builtin_text(builtin)
        .unwrap()
        .to_string()
        + model;
    stiffid_core::setup::parse(&text, "model.toml", |r, _| {
        stiffid_core::robot::presets::get(r)
    })
    .unwrap()
}

/// An elbow tilt spring (7 parameters).
pub(crate) const ELBOW: &str = r#"
[[model.spring]]
name = "elbow_x"
kind = "rotation"
link = 3
axis = [1, 0, 0]
nominal_stiffness_nm_per_rad = 4e6
"#;

/// A translational tool compliance (with [`ELBOW`]: 8 parameters).
pub(crate) const TOOL_Y: &str = r#"
[[model.spring]]
name = "tool_y"
kind = "translation"
link = 6
axis = [0, 1, 0]
nominal_stiffness_n_per_mm = 2e4
"#;

/// Every kind of spring and link: an off-origin rotation in link 1, the tilt of joints 2 and 3,
/// the tool translations and a base rotation (with the drives: 15 parameters).
const MANY: &str = r#"
[[model.spring]]
name = "upper_arm"
kind = "rotation"
link = 1
axis = [0.3, -1, 0.2]
point_mm = [100, -50, 400]
nominal_stiffness_nm_per_rad = 5e6

[[model.spring]]
name = "base_rx"
kind = "rotation"
link = 0
axis = [1, 0, 0]
point_mm = [0, 0, 200]
nominal_stiffness_nm_per_rad = 2e7

[[model.family]]
family = "tilt"
links = [2, 3]
nominal_stiffness_nm_per_rad = 4e6

[[model.family]]
family = "tool"
nominal_stiffness_n_per_mm = 2e4
"#;

fn models() -> Vec<Setup> {
    vec![
        with_model("zhang2021-comau-nj165", ELBOW),
        with_model("zhang2021-comau-nj165", &format!("{ELBOW}{TOOL_Y}")),
        with_model("fanuc-r2000ic-165f", &format!("{ELBOW}{TOOL_Y}")),
        with_model("zhang2021-comau-nj165", MANY),
    ]
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Every criterion of a 7-, 8- and 15-parameter model equals its definition on the whole
/// observation matrix (`3pn x n`, nalgebra's SVD and inverse): `cond(Psi)`, `cond(S)`,
/// `det((S^T S)^-1)^(1/2n)`, the relative standard deviations and their RMS, and the test-pose
/// error; the Cholesky path of the pool agrees.
#[test]
fn wide_criteria_equal_their_definitions() {
    for setup in models() {
        let n = setup.model().len();
        let evaluator = Evaluator::new(&setup);
        assert_eq!(evaluator.parameters(), n);
        let group = random_group(&setup, 12, 5);
        let psi = rope_observation_matrix(&setup, &group);
        assert_eq!(psi.ncols(), n);
        let h = setup.model_nominal_compliance().unwrap() / setup.noise().displacement_sd();
        let s = DMatrix::from_fn(psi.nrows(), n, |i, j| psi[(i, j)] * h[j]);
        let sv = |a: &DMatrix<f64>| a.clone().svd(false, false).singular_values;
        let (psv, ssv) = (sv(&psi), sv(&s));
        let cov = (s.transpose() * &s).try_inverse().unwrap();
        let e = evaluator.evaluation(&group);
        assert!(rel(e.cond_psi, psv.max() / psv.min()) < 1e-8);
        assert!(rel(e.scaled_cond, ssv.max() / ssv.min()) < 1e-8);
        let det: f64 = ssv.iter().map(|v| v.ln()).sum();
        assert!(rel(e.d_optimal, (-det / n as f64).exp()) < 1e-8);
        assert!(rel(e.relative_a, (cov.trace() / n as f64).sqrt()) < 1e-8);
        for j in 0..n {
            let want = cov[(j, j)].sqrt();
            let got = if j < 6 {
                e.relative_std[j]
            } else {
                e.spring_relative_std[j - 6]
            };
            assert!(rel(got, want) < 1e-8, "parameter {j}: {got} vs {want}");
        }
        let a = rope_observation_matrix(&setup, setup.test_postures());
        let m = (psi.transpose() * &psi).try_inverse().unwrap();
        let t = setup.test_postures().len() as f64;
        let test = setup.noise().displacement_sd() * ((&a * m * a.transpose()).trace() / t).sqrt();
        assert!(rel(e.test_pose, test) < 1e-8);
        assert_eq!(e.identifiability.identified, vec![true; n]);
        assert_eq!(e.identifiability.rank, n);
        let pool = crate::Pool::new(&setup, &group, &[]).unwrap();
        for criterion in Criterion::ALL {
            assert_eq!(evaluator.value(criterion, &group), e.value(criterion));
            let terms: Vec<PostureTerms> = group.iter().map(|q| evaluator.posture(q)).collect();
            let refs: Vec<&PostureTerms> = terms.iter().collect();
            assert_eq!(evaluator.value_of(criterion, &refs), e.value(criterion));
            let info = Information::sum(
                terms
                    .iter()
                    .map(|t| evaluator.information(t))
                    .collect::<Vec<_>>()
                    .iter(),
            )
            .unwrap();
            let classical = evaluator.classical(&refs);
            let from_info = evaluator.value_from_information(criterion, &info, classical);
            assert!(rel(from_info, e.value(criterion)) < 1e-7, "{criterion}");
        }
        drop(pool);
    }
}

/// Fourth-order central differences of `f` at `q`, one axis at a time.
fn central(q: &Vector6<f64>, f: impl Fn(&Vector6<f64>) -> f64) -> Vector6<f64> {
    let h = 1e-4;
    Vector6::from_fn(|a, _| {
        let mut step = Vector6::zeros();
        step[a] = h;
        let one = f(&(q + step)) - f(&(q - step));
        let two = f(&(q + 2.0 * step)) - f(&(q - 2.0 * step));
        (8.0 * one - two) / (12.0 * h)
    })
}

/// Every criterion's exact gradient for 7-, 8- and 15-parameter models (springs in every link,
/// rotations and translations, one and four measuring points) against central differences.
#[test]
fn every_wide_criterion_gradient_matches_central_differences() {
    for setup in models() {
        let evaluator = Evaluator::new(&setup);
        for seed in [3, 4] {
            let group = random_group(&setup, 8, seed);
            for criterion in Criterion::ALL {
                let (value, exact) = evaluator.value_and_gradient(criterion, &group);
                assert_eq!(value, evaluator.value(criterion, &group), "{criterion}");
                assert!(value.is_finite(), "{criterion}");
                let (mut diff, mut norm) = (0.0, 0.0);
                for i in 0..group.len() {
                    let approx = central(&group[i], |q| {
                        let mut probed = group.clone();
                        probed[i] = *q;
                        evaluator.value(criterion, &probed)
                    });
                    diff += (exact[i] - approx).norm_squared();
                    norm += exact[i].norm_squared();
                }
                let err = (diff / norm).sqrt();
                assert!(
                    err < 1e-6,
                    "{criterion}, {} parameters: {err:e}",
                    setup.model().len()
                );
            }
        }
    }
}

/// A rotational spring about joint 6's own axis duplicates the drive k6: the group identifies
/// the other parameters and names the pair; the drives alone are identified.
#[test]
fn a_spring_on_the_drive_axis_is_not_identified() {
    let setup = with_model(
        "zhang2021-comau-nj165",
        r#"
[[model.spring]]
name = "twin6"
kind = "rotation"
link = 6
axis = [0, 0, 1]
nominal_stiffness_nm_per_rad = 1e6
"#,
    );
    let group = random_group(&setup, 8, 2);
    let e = Evaluator::new(&setup).evaluation(&group);
    assert_eq!(e.relative_a, f64::INFINITY);
    let id = &e.identifiability;
    assert_eq!(id.rank, 6);
    let mut expected = vec![true; 7];
    expected[5] = false;
    expected[6] = false;
    assert_eq!(id.identified, expected);
    let combination = &id.unidentifiable[0].terms;
    assert_eq!(combination.len(), 2);
    assert!(combination
        .iter()
        .all(|(j, c)| [5, 6].contains(j) && c.abs() > 0.7));
    let drives = stiffid_core::setup::builtin("zhang2021-comau-nj165").unwrap();
    let d = Evaluator::new(&drives).evaluation(&group).identifiability;
    assert_eq!(
        (d.rank, d.identified, d.unidentifiable.len()),
        (6, vec![true; 6], 0)
    );
}

#[test]
fn leave_one_out_is_the_evaluation_of_the_others() {
    for setup in [
        stiffid_core::setup::builtin("zhang2021-comau-nj165").unwrap(),
        with_model("zhang2021-comau-nj165", ELBOW),
    ] {
        let evaluator = Evaluator::new(&setup);
        let group = random_group(&setup, 7, 3);
        let without = evaluator.relative_std_without_each(&group);
        assert_eq!(without.len(), group.len());
        for (i, got) in without.iter().enumerate() {
            let mut others = group.clone();
            others.remove(i);
            assert_eq!(
                *got,
                evaluator.evaluation(&others).relative_std,
                "posture {i}"
            );
        }
    }
}

#[test]
fn cached_posture_terms_give_the_same_values() {
    let setup = stiffid_core::setup::builtin("zhang2021-comau-nj165").unwrap();
    let group = random_group(&setup, 7, 2);
    let fast = Evaluator::new(&setup);
    let terms: Vec<_> = group.iter().map(|q| fast.posture(q)).collect();
    let refs: Vec<_> = terms.iter().collect();
    for c in Criterion::ALL {
        assert_eq!(fast.value_of(c, &refs), fast.value(c, &group), "{c}");
    }
}
