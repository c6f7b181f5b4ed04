//! Design for the candidates of the model comparison (stiffid::design::candidates): the verdict
//! per candidate against an independent rank by SVD, and a group designed for the candidates.

use nalgebra::{DMatrix, Vector6};
use stiffid::app::evaluate;
use stiffid::design::candidates::verdicts;
use stiffid::design::random_group;
use stiffid::identify::compare::{default_pool, pool_by_name};
use stiffid::model::Spring;
use stiffid::observation::posture_block;
use stiffid::setup::Setup;

fn paper() -> Setup {
    stiffid::setup::builtin("zhang2021-comau-nj165").unwrap()
}

/// The observation matrix of `postures` under the rope load, at each of `scales` times it, of
/// `setup`'s model with `candidate` added, built through a setup that holds it in its model.
fn augmented(
    setup: &Setup,
    candidate: &Spring,
    postures: &[Vector6<f64>],
    scales: &[f64],
) -> DMatrix<f64> {
    let mut springs = setup.model().springs().to_vec();
    springs.push(candidate.clone());
    let with = setup
        .to_builder()
        .with_virtual_springs(springs)
        .build()
        .unwrap();
    let blocks: Vec<DMatrix<f64>> = postures
        .iter()
        .flat_map(|q| {
            let frames = with.robot().frames(q);
            let w = with.rope_wrench(&frames);
            let with = &with;
            scales
                .iter()
                .map(move |s| posture_block(with.arm(), &frames, &(w * *s)))
        })
        .collect();
    let n = blocks[0].ncols();
    let rows: usize = blocks.iter().map(|b| b.nrows()).sum();
    let mut psi = DMatrix::zeros(rows, n);
    let mut r = 0;
    for b in &blocks {
        psi.view_mut((r, 0), (b.nrows(), n)).copy_from(b);
        r += b.nrows();
    }
    psi
}

/// The rank of `psi` with its columns scaled to unit norm, singular values above 1e-8 of the
/// largest, by SVD; and the sine of the angle between its last column and the others' span.
fn rank_and_sine(psi: &DMatrix<f64>) -> (usize, f64) {
    let mut scaled = psi.clone();
    for mut c in scaled.column_iter_mut() {
        let norm = c.norm();
        if norm > 0.0 {
            c /= norm;
        }
    }
    let s = scaled.clone().svd(false, false).singular_values;
    let rank = s.iter().filter(|v| **v > 1e-8 * s.max()).count();
    let n = scaled.ncols();
    let model = scaled.columns(0, n - 1).into_owned();
    let u = model.svd(true, false).u.unwrap();
    let c = scaled.column(n - 1);
    let inside = (u.transpose() * c).norm_squared();
    (rank, (1.0 - inside).max(0.0).sqrt())
}

/// On groups of 3, 4 and 8 random postures, 4 that differ only in joint 1 and one posture
/// measured 4 times, every candidate's verdict (identified, separation) equals an independent rank
/// and angle by SVD of the augmented observation matrix built through a setup with the candidate
/// in its model; the groups give both verdicts.
#[test]
fn each_candidates_verdict_agrees_with_an_svd_of_the_augmented_matrix() {
    let setup = paper();
    let pool = default_pool(&setup);
    let (mut yes, mut no) = (0, 0);
    let q = random_group(&setup, 1, 5)[0];
    let turned: Vec<Vector6<f64>> = (0..4)
        .map(|k| q + Vector6::new(0.3 * f64::from(k), 0.0, 0.0, 0.0, 0.0, 0.0))
        .collect();
    let groups = [
        random_group(&setup, 3, 1),
        random_group(&setup, 4, 2),
        random_group(&setup, 8, 3),
        turned,
        vec![q; 4],
    ];
    for group in groups {
        let n = group.len();
        let v = verdicts(&setup, &group, &pool).unwrap();
        assert_eq!(v.candidates.len(), pool.candidates.len());
        for (verdict, spring) in v.candidates.iter().zip(&pool.candidates) {
            let (rank, sine) = rank_and_sine(&augmented(&setup, spring, &group, &[1.0]));
            let full = rank == 7;
            assert_eq!(verdict.identified, full, "{} on {n} postures", spring.name);
            assert_eq!(verdict.parameter.name, spring.name);
            if full {
                yes += 1;
                assert!(
                    (verdict.separation - sine).abs() < 1e-7,
                    "{}: {} vs {sine}",
                    spring.name,
                    verdict.separation
                );
                assert!(verdict.unidentifiable.is_empty());
            } else {
                no += 1;
                assert_eq!(verdict.separation, 0.0);
                assert!(!verdict.unidentifiable.is_empty());
            }
        }
    }
    assert!(yes > 0 && no > 0, "identified {yes}, not {no}");
}

/// With load steps, a lost motion's column differs from its joint's within each posture: one
/// posture identifies it with the drives only through its steps. On a group of one load level
/// it is marked as needing load steps; with steps, not, and the verdict agrees with the SVD of
/// the stacked steps' rows.
#[test]
fn load_steps_separate_a_lost_motion_within_a_posture() {
    let setup = paper();
    let pool = pool_by_name(&setup, &["lost2".to_string()]).unwrap();
    let group = random_group(&setup, 8, 4);
    let one = verdicts(&setup, &group, &pool).unwrap();
    assert_eq!(one.load_levels, 1);
    assert!(one.candidates[0].needs_load_steps);
    assert!(one.separable().is_empty());
    let load = setup.load().load;
    let steps = vec![0.25 * load, 0.5 * load, load];
    let stepped = setup
        .to_builder()
        .with_load_steps(steps.clone())
        .build()
        .unwrap();
    let v = verdicts(&stepped, &group, &pool).unwrap();
    assert_eq!(v.load_levels, 3);
    assert!(!v.candidates[0].needs_load_steps);
    let scales: Vec<f64> = steps.iter().map(|f| f / load).collect();
    let (rank, sine) = rank_and_sine(&augmented(&setup, &pool.candidates[0], &group, &scales));
    assert_eq!(rank, 7);
    assert!(v.candidates[0].identified);
    assert!((v.candidates[0].separation - sine).abs() < 1e-7);
    assert_eq!(v.separable(), ["lost2"]);
}

/// The evaluate job reports the default pool's verdicts, and `--candidates` names them; the
/// calibration alone has none; an unknown name is refused naming `candidates`.
#[test]
fn evaluate_reports_the_candidates() {
    let setup = paper();
    let group = random_group(&setup, 6, 1);
    let request = |candidates: Option<Vec<String>>| evaluate::Request {
        setup: &setup,
        postures: &group,
        purpose: Default::default(),
        calibration: Default::default(),
        candidates,
    };
    let all = evaluate::run(&request(None)).unwrap().candidates.unwrap();
    assert_eq!(all.candidates.len(), default_pool(&setup).candidates.len());
    let tilt = evaluate::run(&request(Some(vec!["tilt".into()]))).unwrap();
    let tilt = tilt.candidates.unwrap();
    assert!(tilt.candidates.iter().all(|c| c.family == "tilt"));
    assert!(!tilt.dropped.is_empty(), "tilt1_z is along joint 1's axis");
    let err = evaluate::run(&request(Some(vec!["elbow".into()]))).unwrap_err();
    assert!(err.to_string().contains("candidates"), "{err}");
}
