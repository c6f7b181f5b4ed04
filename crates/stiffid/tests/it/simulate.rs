//! Monte Carlo simulation: agreement with the first-order prediction, exactness without noise,
//! independence of the thread count.

use nalgebra::Vector6;
use stiffid::internal::setup::{self, Noise};
use stiffid::internal::study::simulate::{monte_carlo, Options};

/// Six spread postures within the paper's Table 1 bounds, deg.
fn group() -> Vec<Vector6<f64>> {
    [
        [10.0, -20.0, -100.0, 30.0, 40.0, -60.0],
        [-45.0, 10.0, -70.0, -90.0, -30.0, 120.0],
        [60.0, -40.0, -130.0, 150.0, 60.0, 10.0],
        [-80.0, 30.0, -50.0, -20.0, -70.0, -150.0],
        [30.0, 0.0, -160.0, 100.0, 20.0, 80.0],
        [-10.0, -55.0, -90.0, -160.0, 80.0, -30.0],
    ]
    .iter()
    .map(|q| Vector6::from_iterator(q.iter().map(|d: &f64| d.to_radians())))
    .collect()
}

#[test]
fn mean_deviation_rates_agree_with_the_prediction_at_2000_runs() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let options = Options {
        runs: 2000,
        seed: 7,
    };
    let sim = &monte_carlo(&setup, &[group()], &options).unwrap()[0];
    assert_eq!(sim.mean_deviation_pct.len(), 6);
    for (level, (mean, predicted)) in sim
        .mean_deviation_pct
        .iter()
        .zip(&sim.predicted_deviation_pct)
        .enumerate()
    {
        for j in 0..6 {
            let ratio = mean[j] / predicted[j];
            assert!(
                (ratio - 1.0).abs() < 0.15,
                "level {} joint {}: simulated {:.4}% predicted {:.4}%",
                level + 1,
                j + 1,
                mean[j],
                predicted[j]
            );
        }
    }
    // Noise grows with the level: the level-6 (3x variance) deviation exceeds the level-1 (0.5x).
    for j in 0..6 {
        assert!(sim.mean_deviation_pct[5][j] > sim.mean_deviation_pct[0][j]);
        assert!(sim.std_deviation_pct[5][j] > 0.0);
    }
}

#[test]
fn at_the_smallest_noise_the_stiffness_is_recovered_to_1e_7() {
    // The smallest noise a setup accepts (reading sd 1e-6 mm at multiple 1e-6, sigma about 1 pm,
    // 1e-8 of the deflections): deviation rates about 1e-7 %.
    let setup = setup::builtin("zhang2021-comau-nj165")
        .unwrap()
        .to_builder()
        .with_noise(Noise {
            reading_variance: (1e-6f64 * 1e-3).powi(2), // the least reading sd, mm
            levels: vec![1e-6],                         // the least level multiple
        })
        .build()
        .unwrap();
    let sim = &monte_carlo(&setup, &[group()], &Options { runs: 3, seed: 1 }).unwrap()[0];
    for j in 0..6 {
        assert!(
            sim.mean_deviation_pct[0][j] < 1e-5,
            "{:?}",
            sim.mean_deviation_pct
        );
        let k = sim.mean_stiffness[0][j];
        assert!((k / setup.nominal_stiffness().unwrap()[j] - 1.0).abs() < 1e-7);
    }
}

#[test]
fn same_seed_same_result_whatever_the_thread_count() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let groups = [
        group(),
        group()[..5].iter().chain(&group()[..1]).cloned().collect(),
    ];
    let options = Options { runs: 50, seed: 3 };
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| monte_carlo(&setup, &groups, &options).unwrap())
    };
    assert_eq!(run(1), run(2));
    let other = monte_carlo(&setup, &groups, &Options { seed: 4, ..options }).unwrap();
    assert_ne!(run(2), other);
}

#[test]
fn zero_runs_and_unidentifiable_groups_are_errors() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let e = monte_carlo(&setup, &[group()], &Options { runs: 0, seed: 1 }).unwrap_err();
    assert!(e.to_string().contains("runs"), "{e}");
    let first = setup.tool().measuring_points[0];
    let setup = setup
        .to_builder()
        .with_measuring_points(vec![first])
        .build()
        .unwrap();
    let e = monte_carlo(&setup, &[group()[..1].to_vec()], &Options::default()).unwrap_err();
    assert!(e.to_string().contains("3 observation rows"), "{e}");
}

/// The paper's cell with an elbow tilt spring (about x of joint 3's frame, 5e6 Nm/rad): seven
/// parameters. At 2000 runs the simulated mean deviation rate of every parameter, the virtual
/// spring included, agrees with the first-order prediction within 15% at every level, and the
/// job names the seventh parameter with its unit.
#[test]
fn a_seven_parameter_model_agrees_with_the_prediction_at_2000_runs() {
    let paper = setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut tilt = stiffid::internal::model::Family::Tilt
        .springs(paper.robot(), &[3], Some(5e6), None, "test")
        .unwrap();
    tilt.truncate(1);
    let model = paper
        .to_builder()
        .with_virtual_springs(tilt)
        .build()
        .unwrap();
    let group = stiffid::internal::design::random_group(&model, 12, 3);
    let options = Options {
        runs: 2000,
        seed: 11,
    };
    let sim = &monte_carlo(&model, std::slice::from_ref(&group), &options).unwrap()[0];
    let levels = model.noise().levels.len();
    assert_eq!(sim.spring_mean_deviation_pct.len(), levels);
    for l in 0..levels {
        let mean = sim.mean_deviation_pct[l]
            .iter()
            .chain(&sim.spring_mean_deviation_pct[l]);
        let predicted = sim.predicted_deviation_pct[l]
            .iter()
            .chain(&sim.spring_predicted_deviation_pct[l]);
        let pairs: Vec<(f64, f64)> = mean.copied().zip(predicted.copied()).collect();
        assert_eq!(pairs.len(), 7);
        for (j, (m, p)) in pairs.into_iter().enumerate() {
            assert!(
                (m / p - 1.0).abs() < 0.15,
                "level {} parameter {}: simulated {m:.4}% predicted {p:.4}%",
                l + 1,
                j + 1
            );
        }
        // The mean identified spring stiffness is near the truth.
        assert!((sim.spring_mean_stiffness[l][0] / 5e6 - 1.0).abs() < 0.05);
    }
    // The job and its document over the model: seven named parameters, rates of seven columns.
    let report = stiffid::app::simulate::run(&stiffid::app::simulate::Request {
        setup: &model,
        groups: vec![stiffid::app::simulate::Group {
            name: "g".into(),
            postures: group,
        }],
        options: Options { runs: 20, seed: 1 },
        progress: &(),
    })
    .unwrap();
    let doc = &report;
    let names: Vec<&str> = doc.parameters.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["k1", "k2", "k3", "k4", "k5", "k6", "tilt3_x"]);
    assert_eq!(doc.parameters[6].unit.symbol(), "Nm/rad");
    assert!(doc.groups[0]
        .mean_deviation_pct
        .iter()
        .all(|r| r.len() == 7));
    assert_eq!(doc.groups[0].mean_spring_stiffness[0].len(), 1);
}

/// Noise-free in effect (the smallest noise a setup accepts): a model's virtual spring is
/// recovered to 1e-7 like the drives.
#[test]
fn at_the_smallest_noise_a_virtual_spring_is_recovered() {
    let paper = setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut tilt = stiffid::internal::model::Family::Tilt
        .springs(paper.robot(), &[3], Some(5e6), None, "test")
        .unwrap();
    tilt.truncate(1);
    let model = paper
        .to_builder()
        .with_virtual_springs(tilt)
        .with_noise(Noise {
            reading_variance: (1e-6f64 * 1e-3).powi(2), // the least reading sd, mm
            levels: vec![1e-6],                         // the least level multiple
        })
        .build()
        .unwrap();
    let group = stiffid::internal::design::random_group(&model, 10, 2);
    let sim = &monte_carlo(&model, &[group], &Options { runs: 3, seed: 1 }).unwrap()[0];
    assert!(
        sim.spring_mean_deviation_pct[0][0] < 1e-6,
        "{:?}",
        sim.spring_mean_deviation_pct
    );
    assert!(sim.mean_deviation_pct[0].iter().all(|r| *r < 1e-6));
}
