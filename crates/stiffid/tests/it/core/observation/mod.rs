mod model_tests;

use nalgebra::Vector3;
use stiffid_core::observation::*;

/// `B^T B = C^T C` for the compact block C of a posture's block B, with 4, 2 and 1 measuring
/// points (`R_P` of 6, 6 and 3 rows), at seeded random postures of both built-in setups.
#[test]
fn compact_block_has_the_gram_matrix_of_the_posture_block() {
    let paper = stiffid_core::setup::builtin("zhang2021-comau-nj165").unwrap();
    let two_points = paper
        .to_builder()
        .with_measuring_points(vec![
            Vector3::new(0.1, -0.2, 0.3),
            Vector3::new(0.0, 0.1, 0.4),
        ])
        .build()
        .unwrap();
    let fanuc = stiffid_core::setup::builtin("fanuc-r2000ic-165f").unwrap();
    for (setup, rows) in [(&paper, 6), (&two_points, 6), (&fanuc, 3)] {
        let factor = points_factor(setup.tool());
        assert!(factor.rows(rows, 6 - rows).iter().all(|&x| x == 0.0));
        for q in stiffid_design::random_group(setup, 5, 7) {
            let frames = setup.robot().frames(&q);
            let b = posture_block(setup.arm(), &frames, &setup.rope_wrench(&frames));
            let c = compact_posture_block(setup, &frames, &factor);
            let (bb, cc) = (b.transpose() * &b, c.transpose() * c);
            let scale = bb.amax();
            assert!(scale > 0.0);
            for i in 0..6 {
                for j in 0..6 {
                    assert!(
                        (bb[(i, j)] - cc[(i, j)]).abs() < 1e-13 * scale,
                        "{bb} vs {cc}"
                    );
                }
            }
        }
    }
}
