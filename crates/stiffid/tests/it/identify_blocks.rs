//! Identification in blocks (`identify::least_squares`, bounded memory, parallel) against the
//! one-shot QR of the whole `Psi` (`Observations::least_squares`): the same compliance,
//! covariance, residuals and intervals to rounding; the same bits with 1 and 2 threads; noise-free
//! recovery of the stiffness from a generated measurement file of many postures.

use crate::common;
use stiffid::internal::identify::Identify;

use common::{assert_close, measurement_csv, noisy, synthetic};
use stiffid::internal::identify;
use stiffid::internal::io::measurements;
use stiffid::internal::observation::Observations;
use stiffid::internal::setup;

#[test]
fn blocks_equal_the_one_shot_qr_to_rounding() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    // 1500 postures x 4 points: six blocks, the last one partial.
    let data = noisy(&setup, 1500, 1);
    const BLOCK: usize = 1024; // the rows least squares takes a block at a time
    assert!(data.len() > 5 * BLOCK && !data.len().is_multiple_of(BLOCK));
    let blocks = identify::least_squares(setup.arm(), &data).unwrap();
    let whole = Observations::from_measurements(setup.arm(), &data)
        .unwrap()
        .least_squares()
        .unwrap();
    assert_close(&blocks, &whole);
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
            .install(|| identify::least_squares(setup.arm(), &data).unwrap())
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
    let text = measurement_csv(&data);
    let mut file = measurements::parse(&text).unwrap();
    file.to_base_frame(&setup).unwrap();
    let id = identify::least_squares(setup.arm(), &file.measurements).unwrap();
    assert_eq!((id.rows, id.postures), (60_000, 5000));
    let k = setup.nominal_stiffness().unwrap();
    let error = (id.stiffness - k).component_div(k).amax();
    assert!(error < 1e-9, "relative error {error:e}");
}
