use crate::model::region::*;
use nalgebra::Vector6;

#[test]
fn the_region_is_the_range_widened_by_the_margin() {
    let d = f64::to_radians;
    let postures = [
        Vector6::new(d(0.0), d(10.0), d(-20.0), 0.0, d(30.0), 0.0),
        Vector6::new(d(40.0), d(80.0), d(20.0), 0.0, d(60.0), d(90.0)),
    ];
    let r = PostureRange::of(&postures).unwrap();
    assert_eq!(r.postures, 2);
    assert_eq!(r.range.upper[1], d(80.0));
    // Inside, and within the margin.
    assert!(r.outside(&postures[0]).is_empty());
    let near = Vector6::new(d(44.9), d(5.1), 0.0, d(4.9), d(45.0), d(-4.9));
    assert!(r.outside(&near).is_empty());
    // Axis 2 beyond its range and the margin.
    let far = Vector6::new(d(20.0), d(85.5), 0.0, 0.0, d(45.0), 0.0);
    let v = r.outside(&far);
    assert_eq!(v.len(), 1);
    assert_eq!((v[0].axis, v[0].upper), (1, d(80.0)));
    assert_eq!(
        r.describe(&v),
        "axis 2 at 85.50 deg (identified over 10.00 .. 80.00)"
    );
    assert!(PostureRange::of(&[]).is_none());
    assert_eq!(Region::NotIdentified.outside(&far), None);
}
