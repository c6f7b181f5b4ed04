use crate::setup::load_steps::*;

#[test]
fn one_step_at_the_rope_load_is_two_readings() {
    let w = StepWeights::new(500.0, &[500.0]).unwrap();
    assert_eq!(w.reference, -1.0);
    assert_eq!(w.steps, [1.0]);
    assert_eq!(w.variance_factor(), 2.0);
    // Five steps of 100 N: F^2 (S2 + S1^2) / S2^2 with S1 = 1500, S2 = 550 000.
    let five = StepWeights::new(500.0, &[100.0, 200.0, 300.0, 400.0, 500.0]).unwrap();
    let expected = 500.0f64.powi(2) * (550_000.0 + 1500.0f64.powi(2)) / 550_000.0f64.powi(2);
    assert!((five.variance_factor() - expected).abs() < 1e-12 * expected);
    assert!(StepWeights::new(500.0, &[]).is_none());
}
