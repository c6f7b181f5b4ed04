//! Where the robot is used (`stiffid::app::calibrate::region`) and the bound from the
//! fit where the jackknife+ has none (`fit_bound`).

use nalgebra::Vector6;
use stiffid::app::calibrate::fit_bound::half_width;
use stiffid::app::calibrate::region::region;
use stiffid::common::limits::JointBox;

fn deg(v: [f64; 6]) -> Vector6<f64> {
    Vector6::from(v).map(f64::to_radians)
}

#[test]
fn the_region_is_the_postures_box_with_its_margin_within_the_limits() {
    let limits = JointBox::new(deg([-180.0; 6]), deg([180.0; 6]));
    let bounds = JointBox::new(
        deg([-180.0, -180.0, -180.0, -180.0, -180.0, 8.0]),
        deg([180.0; 6]),
    );
    let postures = [
        deg([-10.0, 0.0, 100.0, 0.0, 175.0, 10.0]),
        deg([90.0, 2.0, 120.0, 0.0, 178.0, 20.0]),
    ];
    let r = region(&postures, &limits, &bounds);
    // Joint 1: -10..90 widened by 10 % of 100 deg; joint 2: 0..2 by the 5 deg least margin;
    // joint 3: 100..120 by 5 deg (10 % is 2 deg); joint 5 cut at the limit; joint 6's lower end
    // cut at the bounds' 8 deg.
    let expected_lower = [-20.0, -5.0, 95.0, -5.0, 170.0, 8.0];
    let expected_upper = [100.0, 7.0, 125.0, 5.0, 180.0, 25.0];
    for j in 0..6 {
        assert!(
            (r.lower[j].to_degrees() - expected_lower[j]).abs() < 1e-9,
            "{j}: {}",
            r.lower[j].to_degrees()
        );
        assert!(
            (r.upper[j].to_degrees() - expected_upper[j]).abs() < 1e-9,
            "{j}: {}",
            r.upper[j].to_degrees()
        );
    }
    // No posture: the joint limits.
    assert_eq!(region(&[], &limits, &bounds), limits);
}

#[test]
fn the_bound_from_the_fit_is_the_normal_quantile() {
    // z at 0.9985 (two-sided 99.7 %) is 2.967738 (normal tables), at 0.975 1.959964.
    assert!((half_width(0.997, 1.0, 0.0) - 2.967738).abs() < 1e-5);
    assert!((half_width(0.95, 0.5, 0.5) - 1.959964).abs() < 1e-5);
    // A negative variance from rounding counts as none.
    assert!((half_width(0.95, 4.0, -1e-30) - 2.0 * 1.959964).abs() < 1e-5);
}
