//! The acceptance rule ([`super::acceptance::lowers`]) at the joint maps' and the error
//! motions' numbers of standard errors.

use super::acceptance::lowers;
use super::maps::{ACCEPT, MAP_ACCEPT};

#[test]
fn a_map_is_kept_at_two_and_a_half_standard_errors_an_error_motion_at_three() {
    // Paired per-posture differences of 2.5 and -0.5 (mean 1, 2.58 standard errors), the total
    // lowered by a tenth: a map is kept, an error motion's order is not.
    let current = vec![10.0; 16];
    let candidate: Vec<f64> = (0..16).map(|i| [7.5, 10.5][i % 2]).collect();
    let d: Vec<f64> = current.iter().zip(&candidate).map(|(a, b)| a - b).collect();
    let mean = d.iter().sum::<f64>() / 16.0;
    let sd = (d.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 15.0).sqrt();
    let z = mean / (sd / 4.0);
    assert!((z - 2.582).abs() < 1e-3, "z {z}");
    let total = |e: &[f64]| e.iter().sum::<f64>();
    let (c, k) = (
        (&current[..], total(&current)),
        (&candidate[..], total(&candidate)),
    );
    assert!(lowers(c, k, MAP_ACCEPT));
    assert!(!lowers(c, k, ACCEPT));
}
