//! Identification in blocks (`identify::least_squares`, bounded memory, parallel) against the
//! one-shot QR of the whole `Psi` (`Observations::least_squares`): the same compliance,
//! covariance, residuals and intervals to rounding; the same bits with 1 and 2 threads; noise-free
//! recovery of the stiffness from a generated measurement file of many postures.

mod common;

use common::synthetic;
use nalgebra::Vector6;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::formats::measurements;
use stiffid::identify::{self, BLOCK};
use stiffid::observation::{Measurement, Observations};
use stiffid::{setup, Setup};

/// Noisy measurements of `n` random postures under random wrenches (4 points each on the paper
/// setup), seeded.
fn noisy(setup: &Setup, n: usize, seed: u64) -> Vec<Measurement> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (lo, hi) = (setup.robot().limits.lower, setup.robot().limits.upper);
    let postures: Vec<Vector6<f64>> = (0..n)
        .map(|_| Vector6::from_fn(|i, _| lo[i] + rng.random_range(0.1..0.9) * (hi[i] - lo[i])))
        .collect();
    let wrenches: Vec<Vector6<f64>> = (0..n)
        .map(|_| Vector6::from_fn(|i, _| rng.random_range(-1.0..1.0) * [800.0, 150.0][i / 3]))
        .collect();
    let noise = Normal::new(0.0, setup.noise().sigma()).unwrap();
    let mut data = synthetic(setup, &postures, |i, _| wrenches[i]);
    for m in &mut data {
        m.displacement += Vector6::from_fn(|_, _| noise.sample(&mut rng)).fixed_rows::<3>(0);
    }
    data
}

#[test]
fn blocks_equal_the_one_shot_qr_to_rounding() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    // 1500 postures x 4 points: six blocks, the last one partial.
    let data = noisy(&setup, 1500, 1);
    assert!(data.len() > 5 * BLOCK && data.len() % BLOCK != 0);
    let blocks = identify::least_squares(&setup, &data).unwrap();
    let whole = Observations::from_measurements(&setup, &data)
        .unwrap()
        .least_squares()
        .unwrap();
    let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-12 * scale;
    let h = whole.compliance.amax();
    for j in 0..6 {
        assert!(
            close(blocks.compliance[j], whole.compliance[j], h),
            "joint {}",
            j + 1
        );
        assert!(close(
            blocks.stiffness[j],
            whole.stiffness[j],
            whole.stiffness[j].abs()
        ));
    }
    let c = whole.unit_covariance.amax();
    assert!((blocks.unit_covariance - whole.unit_covariance).amax() <= 1e-12 * c);
    let d = data
        .iter()
        .map(|m| m.displacement.amax())
        .fold(0.0, f64::max);
    assert!((&blocks.residuals - &whole.residuals).amax() <= 1e-12 * d);
    assert!(close(
        blocks.residual_rms,
        whole.residual_rms,
        whole.residual_rms
    ));
    assert!(close(blocks.cond_psi, whole.cond_psi, whole.cond_psi));
    assert_eq!((blocks.rows, blocks.postures), (whole.rows, whole.postures));
    let (ub, uw) = (blocks.uncertainty.unwrap(), whole.uncertainty.unwrap());
    assert_eq!(ub.dof, uw.dof);
    for j in 0..6 {
        let se = uw.stiffness_std_error[j];
        assert!(close(ub.stiffness_std_error[j], se, se));
        assert!(close(
            ub.stiffness_ci95[j][0],
            uw.stiffness_ci95[j][0],
            whole.stiffness[j]
        ));
    }
    // The noise is the tracker's: the fit is near the truth (a sanity check, not rounding).
    let k = setup.nominal_stiffness().unwrap();
    assert!((blocks.stiffness - k).component_div(k).amax() < 0.05);
}

#[test]
fn blocks_give_the_same_bits_with_one_and_two_threads() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let data = noisy(&setup, 800, 2);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| identify::least_squares(&setup, &data).unwrap())
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one, two);
    assert_eq!(
        one.compliance.map(f64::to_bits),
        two.compliance.map(f64::to_bits)
    );
}

#[test]
fn a_generated_file_of_many_postures_gives_back_the_known_stiffness() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut data = noisy(&setup, 5000, 3);
    // Noise-free: the displacements of the forward model with the nominal stiffness.
    let exact = synthetic(
        &setup,
        &data.iter().step_by(4).map(|m| m.q).collect::<Vec<_>>(),
        |i, _| data[4 * i].wrench,
    );
    for (m, e) in data.iter_mut().zip(&exact) {
        m.displacement = e.displacement;
    }
    let mut text = String::from("posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n,mx_nm,my_nm,mz_nm,dx_mm,dy_mm,dz_mm\n");
    for m in &data {
        let q = m.q.map(f64::to_degrees);
        let d = m.displacement * 1e3;
        let numbers: Vec<String> = q
            .iter()
            .chain(m.wrench.iter())
            .chain(d.iter())
            .map(|v| format!("{v:e}"))
            .collect();
        text += &format!("pose {},{},{}\n", m.posture, m.point + 1, numbers.join(","));
    }
    let mut file = measurements::parse(&text).unwrap();
    file.to_base_frame(&setup).unwrap();
    let id = identify::least_squares(&setup, &file.measurements).unwrap();
    assert_eq!((id.rows, id.postures), (60_000, 5000));
    let k = setup.nominal_stiffness().unwrap();
    let error = (id.stiffness - k).component_div(k).amax();
    assert!(error < 1e-9, "relative error {error:e}");
}
