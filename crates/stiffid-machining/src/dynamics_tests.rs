//! The tooth-passing harmonics (`crate::dynamics`).

use crate::dynamics::Harmonic;

#[test]
fn the_nearest_harmonic_and_its_distance() {
    let h = Harmonic::nearest(21.0, 20.0);
    assert_eq!(h.order, 1);
    assert!((h.distance - 0.05).abs() < 1e-15);
    let h = Harmonic::nearest(59.0, 20.0);
    assert_eq!(h.order, 3);
    assert!((h.distance - 1.0 / 60.0).abs() < 1e-15);
    // Below the tooth-passing frequency the first harmonic is the nearest.
    let h = Harmonic::nearest(5.0, 20.0);
    assert_eq!(h.order, 1);
    assert!((h.distance - 0.75).abs() < 1e-15);
}
