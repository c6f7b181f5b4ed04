//! Where the robot is used (`stiffid::app::calibrate::region`: the postures' joint-space hull) and the bound from the
//! fit where the jackknife+ has none (`fit_bound`).

use nalgebra::Vector6;
use stiffid::app::calibrate::fit_bound::half_width;
use stiffid::app::calibrate::region::region;
use stiffid::internal::common::limits::JointBox;

fn deg(v: [f64; 6]) -> Vector6<f64> {
    Vector6::from(v).map(f64::to_radians)
}

#[test]
fn the_region_is_the_postures_hull_within_the_limits_and_bounds() {
    let limits = JointBox::new(deg([-180.0; 6]), deg([180.0; 6]));
    let bounds = JointBox::new(
        deg([-180.0, -180.0, -180.0, -180.0, -180.0, 8.0]),
        deg([180.0; 6]),
    );
    // A campaign that keeps the forearm level: joint 3 = -joint 2 at every posture.
    let postures = [
        deg([-10.0, -40.0, 40.0, 0.0, 170.0, 10.0]),
        deg([90.0, 40.0, -40.0, 0.0, 179.0, 20.0]),
        deg([20.0, 0.0, 0.0, 30.0, 175.0, 0.0]),
    ];
    let r = region(&postures, &limits, &bounds);
    // The documented sample: 512 postures.
    assert_eq!(r.postures.len(), 512);
    for q in &r.postures {
        let d = q.map(f64::to_degrees);
        // On a segment between two postures: joint 3 stays -joint 2, joint 4 within 0..30 deg.
        assert!((d[2] + d[1]).abs() < 1e-9, "{d:?}");
        assert!((-1e-9..=30.0 + 1e-9).contains(&d[3]), "{d:?}");
        // Joint 6 cut at the bounds' 8 deg, joint 5 within the postures' 170..179 deg.
        assert!(d[5] >= 8.0 - 1e-9 && d[5] <= 20.0 + 1e-9, "{d:?}");
        assert!((170.0 - 1e-9..=179.0 + 1e-9).contains(&d[4]), "{d:?}");
        for j in 0..6 {
            assert!(r.bounds.lower[j] <= q[j] && q[j] <= r.bounds.upper[j]);
        }
    }
    // The box's corner that pairs joint 2 at 40 deg with joint 3 at 40 deg is not in it, though
    // both angles are in the postures' ranges: no sampled posture comes within 20 deg of it.
    let corner = |q: &Vector6<f64>| (q[1].to_degrees() - 40.0).hypot(q[2].to_degrees() - 40.0);
    let nearest = r.postures.iter().map(corner).fold(f64::INFINITY, f64::min);
    assert!(nearest > 20.0, "{nearest}");
    // The sample spans the segments: joint 2 comes within 2 deg of both ends of its range.
    assert!(r.bounds.lower[1].to_degrees() < -38.0 && r.bounds.upper[1].to_degrees() > 38.0);
    // The same postures give the same region.
    assert_eq!(region(&postures, &limits, &bounds), r);
    // No posture: the joint limits, sampled over.
    let none = region(&[], &limits, &bounds);
    assert_eq!(none.bounds, limits);
    // The 512 postures spread over the joint limits (the reference's).
    assert_eq!(none.postures.len(), 512);
}

#[test]
fn the_bound_from_the_fit_is_the_normal_quantile() {
    // z at 0.9985 (two-sided 99.7 %) is 2.967738 (normal tables), at 0.975 1.959964.
    assert!((half_width(0.997, 1.0, 0.0) - 2.967738).abs() < 1e-5);
    assert!((half_width(0.95, 0.5, 0.5) - 1.959964).abs() < 1e-5);
    // A negative variance from rounding counts as none.
    assert!((half_width(0.95, 4.0, -1e-30) - 2.0 * 1.959964).abs() < 1e-5);
}
