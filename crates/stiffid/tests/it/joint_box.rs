//! The one box type of axis angles (joint limits, setup bounds) and the errors of every place that
//! checks a posture against it: each names the field as the user gave it, the value and the range.

use nalgebra::Vector6;
use proptest::prelude::*;
use stiffid::internal::common::limits::JointBox;
use stiffid::internal::design::{self, Criterion, SearchOptions};
use stiffid::internal::io::postures;
use stiffid::{internal::setup, Error};

fn unit_box() -> JointBox {
    JointBox::new(Vector6::repeat(-1.0), Vector6::repeat(1.0))
}

#[test]
fn first_violation_table() {
    let b = unit_box();
    let q = |a: usize, v: f64| Vector6::from_fn(|i, _| if i == a { v } else { 0.0 });
    // (posture, expected violation axis)
    let cases = [
        (Vector6::zeros(), None),
        (Vector6::repeat(1.0), None),
        (Vector6::repeat(-1.0), None),
        (q(0, 1.0 + 1e-15), Some(0)),
        (q(3, -1.5), Some(3)),
        (q(5, f64::NAN), Some(5)),
        (q(2, f64::INFINITY), Some(2)),
        (Vector6::repeat(f64::NAN), Some(0)),
    ];
    for (q, axis) in cases {
        let v = b.first_violation(&q);
        assert_eq!(v.map(|v| v.axis), axis, "{q:?}");
        assert_eq!(b.contains(&q), axis.is_none());
        if let Some(v) = v {
            assert!(v.value == q[v.axis] || v.value.is_nan());
            assert_eq!((v.lower, v.upper), (-1.0, 1.0));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        // A fixed seed: every run tries the same cases (set another to explore).
        rng_seed: proptest::test_runner::RngSeed::Fixed(20_211_126),
        ..ProptestConfig::default()
    })]
    #[test]
    fn contains_first_violation_check_and_clamp_agree(
        lower in prop::array::uniform6(-4.0f64..0.0),
        width in prop::array::uniform6(0.0f64..4.0),
        q in prop::array::uniform6(-9.0f64..9.0),
    ) {
        let lower = Vector6::from(lower);
        let b = JointBox::new(lower, lower + Vector6::from(width));
        let q = Vector6::from(q);
        let inside = (0..6).all(|i| b.lower[i] <= q[i] && q[i] <= b.upper[i]);
        prop_assert_eq!(b.contains(&q), inside);
        let check = b.check(&q, "the box", |a| format!("q{}", a + 1));
        prop_assert_eq!(check.is_ok(), inside);
        if let Some(v) = b.first_violation(&q) {
            prop_assert!((0..v.axis).all(|i| b.lower[i] <= q[i] && q[i] <= b.upper[i]));
            prop_assert!(q[v.axis] < v.lower || q[v.axis] > v.upper);
            let message = check.unwrap_err().to_string();
            let given = format!("q{} = ", v.axis + 1);
            prop_assert!(message.starts_with(&given), "{}", message);
            let range = format!("[{:.2}, {:.2}] deg", v.lower.to_degrees(), v.upper.to_degrees());
            prop_assert!(message.contains(&range), "{}", message);
        }
        let c = b.clamp(&q);
        prop_assert!(b.contains(&c));
        if inside {
            prop_assert_eq!(c, q);
        }
    }
}

fn paper() -> stiffid::Setup {
    setup::builtin("zhang2021-comau-nj165").unwrap()
}

#[test]
fn a_start_posture_outside_the_bounds_names_itself_with_the_value() {
    let setup = paper();
    let mut start = vec![setup.bounds().lower; 3];
    start[1][1] = 45f64.to_radians();
    let options = SearchOptions::default();
    let e = design::local(&setup, Criterion::DOptimal, &start, &options).unwrap_err();
    assert_eq!(
        e.to_string(),
        "start posture 2, q2_deg = 45.00 deg: expected within the setup's bounds [-60.00, 40.00] deg"
    );
    assert!(matches!(e, Error::OutsideBox { .. }));
}

#[test]
fn a_postures_file_outside_the_robots_limits_shows_the_value() {
    let setup = paper();
    let text = "posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\n1,0,0,-5,0,0,0\n";
    let e = postures::parse(text, setup.robot(), None).unwrap_err();
    assert_eq!(
        e.to_string(),
        "line 2, column 4 (q3_deg): q3_deg = -5 is outside the robot's limits [-256.0, -10.0]"
    );
}
