//! Models beyond the six drives: identification of virtual springs, identifiability, and model
//! choice by forward selection (crate::model, crate::identify::svd, crate::identify::compare).

use nalgebra::{DVector, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::internal::design::{local, random_group, Criterion, SearchOptions};
use stiffid::internal::identify::compare::compare;
use stiffid::internal::identify::cross_validation::{cross_validate_model, Method};
use stiffid::internal::identify::svd::fit;
use stiffid::internal::identify::Identify;
use stiffid::internal::model::{Family, Kind, Spring};
use stiffid::internal::observation::{posture_block, Measurement, Observations};
use stiffid::internal::setup::Setup;

/// `setup` with the virtual springs `springs` added after its own.
fn with_springs(setup: &Setup, springs: Vec<Spring>) -> Setup {
    let mut all = setup.model().springs().to_vec();
    all.extend(springs);
    setup
        .to_builder()
        .with_virtual_springs(all)
        .build()
        .unwrap()
}

/// Measurements of `postures` under the rope load with compliance `h` of `truth`'s model, plus
/// Gaussian noise of standard deviation `sigma` (m) from `rng`.
fn measure(
    truth: &Setup,
    postures: &[Vector6<f64>],
    h: &DVector<f64>,
    sigma: f64,
    rng: &mut ChaCha8Rng,
) -> Vec<Measurement> {
    let normal = Normal::new(0.0, 1.0).unwrap();
    let mut out = Vec::new();
    for (posture, q) in postures.iter().enumerate() {
        let frames = truth.robot().frames(q);
        let wrench = truth.rope_wrench(&frames);
        let d = posture_block(truth.arm(), &frames, &wrench) * h;
        for point in 0..truth.tool().measuring_points.len() {
            let noise = Vector3::from_fn(|_, _| sigma * normal.sample(rng));
            let displacement = d.fixed_rows::<3>(3 * point).into_owned() + noise;
            out.push(Measurement {
                posture,
                point,
                q: *q,
                e: Default::default(),
                wrench,
                displacement,
            });
        }
    }
    out
}

/// The paper's cell with an elbow tilt spring (about x of joint 3's frame) of `k` Nm/rad.
fn elbow_truth(k: f64) -> (Setup, DVector<f64>) {
    let paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut tilt = Family::Tilt
        .springs(paper.robot(), &[3], Some(k), None, "test")
        .unwrap();
    tilt.truncate(1);
    let truth = with_springs(&paper, tilt);
    let h = truth.model_nominal_compliance().unwrap();
    (truth, h)
}

/// Noise-free data of drives plus an elbow tilt spring, from a design for that model (`relative-a`
/// over its seven parameters, from a random start), give every compliance back to 1e-9; the same
/// data fitted with the drives alone fail the model check.
#[test]
fn an_elbow_spring_is_recovered_and_the_drives_alone_fail_the_check() {
    let (truth, h) = elbow_truth(5e6);
    let start = random_group(&truth, 10, 4);
    let design = local(
        &truth,
        Criterion::RelativeA,
        &start,
        &SearchOptions::default(),
    )
    .unwrap();
    assert!(design.value < design.start_value, "{design:?}");
    let postures = design.postures;
    let data = measure(
        &truth,
        &postures,
        &h,
        0.0,
        &mut ChaCha8Rng::seed_from_u64(0),
    );
    let obs = Observations::from_measurements(truth.arm(), &data).unwrap();
    assert_eq!(obs.psi.ncols(), 7);
    let f = fit(&obs, &truth.model().parameters()).unwrap();
    assert_eq!(f.identifiability.rank, 7);
    for j in 0..7 {
        assert!(
            (f.compliance[j] / h[j] - 1.0).abs() < 1e-9,
            "{j}: {} vs {}",
            f.compliance[j],
            h[j]
        );
    }
    assert_eq!(f.parameters[6].name, "tilt3_x");
    let drives = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let id = Observations::from_measurements(drives.arm(), &data)
        .unwrap()
        .least_squares()
        .unwrap();
    let check = id.adequacy(drives.noise().displacement_variance()).unwrap();
    assert!(check.model_error_dominates(), "{check:?}");
    assert!(check.noise_ratio > 3.0, "{}", check.noise_ratio);
}

/// The flange's compliance seen at one measuring point under forces alone: its rotation about
/// the flange z axis through the flange origin is joint 6's own column, so the data cannot
/// separate them; the combination is named and neither gets an interval.
#[test]
fn a_flange_compliance_from_one_point_and_forces_is_named_unidentifiable() {
    let fanuc = stiffid::internal::setup::builtin("fanuc-r2000ic-165f").unwrap();
    let r = fanuc.robot().flange().rotation;
    let flange = |name: &str, kind, i: usize| Spring {
        name: name.into(),
        kind,
        link: 6,
        axis: nalgebra::Unit::new_normalize(r * Vector3::ith(i, 1.0)),
        point: fanuc.robot().flange().translation.vector,
        nominal_stiffness: Some(1e7),
        law: stiffid::internal::model::Law::Linear,
    };
    let springs = vec![
        flange("flange_rx", Kind::Rotation, 0),
        flange("flange_ry", Kind::Rotation, 1),
        flange("flange_rz", Kind::Rotation, 2),
        flange("flange_x", Kind::Translation, 0),
        flange("flange_y", Kind::Translation, 1),
        flange("flange_z", Kind::Translation, 2),
    ];
    let model = with_springs(&fanuc, springs);
    let h = model.model_nominal_compliance().unwrap();
    let postures = random_group(&model, 30, 2);
    let data = measure(
        &model,
        &postures,
        &h,
        1e-5,
        &mut ChaCha8Rng::seed_from_u64(1),
    );
    assert!(data
        .iter()
        .all(|m| m.wrench.fixed_rows::<3>(3).norm() == 0.0));
    let obs = Observations::from_measurements(model.arm(), &data).unwrap();
    let f = fit(&obs, &model.model().parameters()).unwrap();
    let id = &f.identifiability;
    assert!(id.rank < 12, "rank {}", id.rank);
    let named: Vec<String> = id
        .unidentifiable
        .iter()
        .map(|c| c.describe(&f.parameters))
        .collect();
    let with_k6 = named
        .iter()
        .find(|n| n.contains("k6") && n.contains("flange_rz"))
        .unwrap_or_else(|| panic!("{named:?}"));
    assert!(with_k6.contains("0.71"), "{with_k6}");
    for name in ["k6", "flange_rz"] {
        let j = f.parameters.iter().position(|p| p.name == name).unwrap();
        assert!(!id.identified[j] && f.intervals[j].is_none(), "{name}");
    }
    // k1 .. k3 stay identified, with intervals.
    assert!((0..3).all(|j| id.identified[j] && f.intervals[j].is_some()));
}

/// Forward selection over 100 seeded noisy data sets (noise level 1): the true elbow spring is
/// recommended in at least 90, a spring of zero true compliance in at most 10.
#[test]
fn forward_selection_finds_the_true_spring_and_rarely_a_false_one() {
    let (truth, h) = elbow_truth(2e7);
    let paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let robot = paper.robot();
    let mut candidates = Family::Tilt
        .springs(robot, &[2, 3], None, None, "test")
        .unwrap();
    candidates.extend(
        Family::Tool
            .springs(robot, &[], None, None, "test")
            .unwrap(),
    );
    candidates.retain(|c| ["tilt3_x", "tilt2_y", "tool_x", "tool_y"].contains(&c.name.as_str()));
    let postures = random_group(&truth, 12, 7);
    let sigma = truth.noise().displacement_sd();
    let (mut found, mut false_added) = (0, 0);
    for seed in 0..100 {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let data = measure(&truth, &postures, &h, sigma, &mut rng);
        let c = compare(&paper, &data, &candidates, false).unwrap();
        let chosen = &c.models[c.recommended].springs;
        found += usize::from(chosen.iter().any(|s| s == "tilt3_x"));
        false_added += usize::from(chosen.iter().any(|s| s != "tilt3_x"));
    }
    eprintln!("true spring in {found} of 100, a zero-compliance spring in {false_added}");
    assert!(found >= 90, "{found}");
    assert!(false_added <= 10, "{false_added}");
}

/// Data the drives explain to the tracker noise: the comparison says no extension is needed.
#[test]
fn on_data_the_model_fits_no_extension_is_needed() {
    let paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let h = paper.model_nominal_compliance().unwrap();
    let postures = random_group(&paper, 12, 5);
    let data = measure(
        &paper,
        &postures,
        &h,
        paper.noise().displacement_sd(),
        &mut ChaCha8Rng::seed_from_u64(3),
    );
    let candidates = stiffid::internal::identify::compare::default_candidates(&paper);
    let c = compare(&paper, &data, &candidates, false).unwrap();
    assert!(c.model_fits);
    assert_eq!(c.recommended, 0);
    assert!(
        c.conclusion().contains("no extension is needed"),
        "{}",
        c.conclusion()
    );
    let ratio = c.models[0].noise_ratio.unwrap();
    assert!((0.8..1.2).contains(&ratio), "{ratio}");
}

/// The FANUC data: the drives alone explain 76.5% held out; the recommended model adds springs,
/// explains at least 81% held out with every compliance positive, and the nested estimate is
/// given.
#[test]
fn fanuc_data_choose_a_larger_model() {
    let (setup, measurements) = crate::common::fanuc();
    let pool = stiffid::internal::identify::compare::default_pool(&setup);
    // 18 tilt, 12 bend (links 1, 2, 3 and 5), 6 base, 3 tool, 6 lost, 6 load; 12 dropped.
    assert_eq!((pool.candidates.len(), pool.dropped.len()), (39, 12));
    let candidates = pool.candidates;
    let c = compare(&setup, &measurements, &candidates, true).unwrap();
    let drives = c.models[0].held_out_explained.unwrap();
    assert!((drives - 0.765).abs() < 5e-4, "{drives}");
    let rec = &c.models[c.recommended];
    assert!(rec.parameters > 6 && rec.physical);
    assert!(rec.held_out_explained.unwrap() >= 0.81, "{rec:?}");
    let nested = c.nested.as_ref().unwrap();
    assert_eq!(nested.parameters.len(), 43);
    assert!(nested.held_out_explained > drives);
    let se = nested.held_out_explained_std_error;
    assert!((0.005..0.05).contains(&se), "{se}");
    // The row's standard error (from the hat matrix) is the cross-validation's (43 refits).
    let model = setup
        .to_builder()
        .with_virtual_springs(c.recommended_springs.clone())
        .build()
        .unwrap();
    let obs = Observations::from_measurements(model.arm(), &measurements).unwrap();
    let f = fit(&obs, &model.model().parameters()).unwrap();
    let cv = cross_validate_model(&obs, &f, 43, Method::LeastSquares).unwrap();
    let se = rec.held_out_explained_std_error.unwrap();
    assert!(
        (cv.explained_std_error - se).abs() <= 1e-9 * se,
        "{cv:?} {se}"
    );
    // No candidate of the pool is a drive's own column: every one is identified in the first
    // step (tilt4_y, joint 5's axis through the wrist centre, is dropped from the pool).
    assert!(c.steps[0].candidates.iter().all(|r| r.identified));
    assert!(pool.dropped.iter().any(|d| d.name == "tilt4_y"));
}
