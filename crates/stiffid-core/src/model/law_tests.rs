use crate::model::*;

#[test]
fn responses() {
    let lost = Law::LostMotion { smoothing: 10.0 };
    assert_eq!(lost.response(0.0), 0.0);
    assert!((lost.response(70.0) - 0.99).abs() < 1e-3);
    assert!((lost.response(-1e6) + 1.0).abs() < 1e-9);
    assert!((lost.response(1e-3) - 1e-4).abs() < 1e-9);
    assert_eq!(Law::LoadDependent.response(-3.0), -9.0);
    assert_eq!(Law::Linear.response(-3.0), -3.0);
}
