//! The COMAU SMART5 NJ 165-3.0 flange check positions of docs/model.md section 4.

use nalgebra::{Vector3, Vector6};
use stiffid::internal::robot::presets;

fn q_deg(q: [f64; 6]) -> Vector6<f64> {
    Vector6::from_iterator(q.iter().map(|v| v.to_radians()))
}

#[test]
fn comau_flange_check_positions_to_0_01_mm() {
    let robot = presets::get("comau-smart5-nj165-3.0").unwrap();
    let checks = [
        ([0.0, 0.0, -90.0, 0.0, 0.0, 0.0], [2074.0, 0.0, 2255.0]),
        ([0.0, 10.0, -90.0, 0.0, 0.0, 0.0], [2278.04, 0.0, 2237.15]),
        ([0.0, 0.0, -80.0, 0.0, 0.0, 0.0], [2005.16, 0.0, 2541.89]),
        (
            [10.0, 20.0, -90.0, 30.0, 20.0, 10.0],
            [2417.77, -466.26, 2116.01],
        ),
    ];
    for (q, expected_mm) in checks {
        let p = robot.frames(&q_deg(q)).point(&Vector3::zeros()) * 1e3;
        for i in 0..3 {
            assert!(
                (p[i] - expected_mm[i]).abs() < 0.01,
                "q = {q:?}: flange {p:?} mm, expected {expected_mm:?}"
            );
        }
    }
}
