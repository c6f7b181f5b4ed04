//! Design for the candidates of the model comparison (stiffid::internal::design::candidates): the verdict
//! per candidate against an independent rank by SVD, and a group designed for the candidates.

use nalgebra::{DMatrix, Vector6};
use stiffid::app::{evaluate, select};
use stiffid::internal::design::candidates::{design_setup, verdicts};
use stiffid::internal::design::{random_group, SearchOptions};
use stiffid::internal::identify::compare::{compare, default_pool, pool_by_name};
use stiffid::internal::model::Spring;
use stiffid::internal::observation::posture_block;
use stiffid::internal::setup::Setup;

fn paper() -> Setup {
    stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap()
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
    let all = evaluate::run(&request(None))
        .unwrap()
        .report
        .candidates
        .unwrap();
    assert_eq!(all.candidates.len(), default_pool(&setup).candidates.len());
    let tilt = evaluate::run(&request(Some(vec!["tilt".into()]))).unwrap();
    let tilt = tilt.report.candidates.unwrap();
    assert!(tilt.candidates.iter().all(|c| c.family == "tilt"));
    assert!(!tilt.dropped.is_empty(), "tilt1_z is along joint 1's axis");
    let err = evaluate::run(&request(Some(vec!["elbow".into()]))).unwrap_err();
    assert!(err.to_string().contains("candidates"), "{err}");
}

/// A select request on `setup`: a global search of `n` postures (8 starts, seed 1), for the
/// candidates or not.
fn global<'a>(setup: &'a Setup, n: usize, for_candidates: bool) -> select::Request<'a> {
    select::Request {
        setup,
        criterion: stiffid::internal::design::Criterion::RelativeA,
        purpose: Default::default(),
        calibration: Default::default(),
        method: select::Method::Global,
        start: None,
        pool: None,
        postures: n,
        target_pct: None,
        options: SearchOptions {
            starts: 8,
            ..Default::default()
        },
        restarts: None,
        distinct: None,
        for_candidates,
        candidates: None,
        stations: Vec::new(),
        progress: &(),
        out: None,
        report_dir: None,
    }
}

/// On the paper's setup, a global search of 12 postures for the candidates identifies the model
/// and every designable candidate at once (full rank of the design's Psi, every separation
/// positive) and more accurately than the default stiffness design of 12 postures (which has full
/// rank too, as generic groups do): relative-a over the model and the candidates, and the worst
/// candidate's relative standard deviation, are lower; 4 postures cannot identify them together
/// and the verdicts name one combination per missing rank. Then, on noise-free data simulated on the designed group with one designable candidate
/// (bending of link 3 about x) as the truth, the comparison over the designable candidates adds it
/// first and recovers its compliance to 1e-9.
#[test]
fn a_design_for_the_candidates_identifies_them_and_the_comparison_recovers_one() {
    let setup = paper();
    let pool = default_pool(&setup);
    let (design, designable) = design_setup(&setup, &pool).unwrap();
    assert_eq!(design.model().len(), 6 + designable.kept.len());
    assert!(designable.kept.len() >= 15, "{}", designable.kept.len());
    // base_x, base_y, base_z and tool_x, tool_y, tool_z deflect alike under equal compliances.
    assert!(designable
        .left_out
        .iter()
        .any(|d| d.name.starts_with("tool_")));
    let chosen = select::run(&global(&setup, 12, true)).unwrap();
    let identified = |group: &[Vector6<f64>]| evaluate_design(&design, group).identifiability;
    let id = identified(&chosen.postures);
    assert_eq!(id.rank, design.model().len());
    let c = chosen.candidates.as_ref().unwrap();
    assert!(c.verdicts.together.is_empty(), "{:?}", c.verdicts.together);
    for &k in &designable.kept {
        let v = &c.verdicts.candidates[k];
        assert!(v.identified && v.separation > 0.0, "{v:?}");
    }
    assert!(chosen.evaluation.relative_a.is_finite());
    let plain = select::run(&global(&setup, 12, false)).unwrap();
    let (for_them, default) = (
        evaluate_design(&design, &chosen.postures),
        evaluate_design(&design, &plain.postures),
    );
    let worst = |e: &stiffid::internal::design::Evaluation| {
        e.spring_relative_std.iter().copied().fold(0.0, f64::max)
    };
    eprintln!(
        "relative-a over the model and the candidates: {} designed for them, {} the stiffness design; worst candidate's relative std {} vs {}",
        for_them.relative_a,
        default.relative_a,
        worst(&for_them),
        worst(&default)
    );
    assert!(for_them.relative_a < 0.8 * default.relative_a);
    assert!(worst(&for_them) < worst(&default));
    // A group of 4 postures (24 rows for 27 parameters) cannot identify them together: the
    // verdicts name the combinations.
    let four = verdicts(&setup, &plain.postures[..4], &pool).unwrap();
    assert!(!four.together.is_empty());
    let rank = evaluate_design(&design, &plain.postures[..4])
        .identifiability
        .rank;
    assert_eq!(four.together.len(), design.model().len() - rank);

    let k = pool
        .candidates
        .iter()
        .position(|s| s.name == "bend3_x")
        .unwrap();
    assert!(designable.kept.contains(&k));
    let mut truth_spring = pool.candidates[k].clone();
    truth_spring.nominal_stiffness = Some(4e6);
    let mut springs = setup.model().springs().to_vec();
    springs.push(truth_spring);
    let truth = setup
        .to_builder()
        .with_virtual_springs(springs)
        .build()
        .unwrap();
    let h = truth.model_nominal_compliance().unwrap();
    let data = crate::candidates::measure(&truth, &chosen.postures, &h, 0.0, 0);
    let candidates: Vec<Spring> = designable
        .kept
        .iter()
        .map(|&c| pool.candidates[c].clone())
        .collect();
    let comparison = compare(&setup, &data, &candidates, false).unwrap();
    assert_eq!(comparison.models[1].added.as_deref(), Some("bend3_x"));
    let j = (comparison.recommended_fit.parameters.iter())
        .position(|p| p.name == "bend3_x")
        .unwrap();
    let got = comparison.recommended_fit.compliance[j];
    assert!((got / h[6] - 1.0).abs() < 1e-9, "{got} vs {}", h[6]);
}

/// Every criterion of `group` on `design`.
fn evaluate_design(
    design: &Setup,
    group: &[Vector6<f64>],
) -> stiffid::internal::design::Evaluation {
    stiffid::internal::design::evaluate(design, group)
}

/// A design for the candidates is refused with too few postures (naming the count needed), for
/// the calibration, and with a target; candidates without it are refused too.
#[test]
fn a_design_for_the_candidates_refuses_what_it_cannot_do() {
    let setup = paper();
    let err = select::run(&global(&setup, 3, true))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("for_candidates") && err.contains("at least 5 postures"),
        "{err}"
    );
    let calibration = select::Request {
        purpose: stiffid::app::purpose::Purpose::Calibration,
        ..global(&setup, 12, true)
    };
    let err = select::run(&calibration).unwrap_err().to_string();
    assert!(err.contains("for_candidates"), "{err}");
    let target = select::Request {
        target_pct: Some(5.0),
        ..global(&setup, 12, true)
    };
    assert!(select::run(&target)
        .unwrap_err()
        .to_string()
        .contains("for_candidates"));
    let names = select::Request {
        candidates: Some(vec!["tilt".into()]),
        ..global(&setup, 12, false)
    };
    let err = select::run(&names).unwrap_err().to_string();
    assert!(err.starts_with("candidates"), "{err}");
}
