use nalgebra::UnitQuaternion;
use stiffid_core::robot::file::{angle_between, rpy};

/// Near and at pitch -90 and +90 degrees the written angles give the rotation back to 1e-14
/// rad, where the closed form misses by more than 1e-9 rad at least once.
#[test]
fn roll_pitch_yaw_give_the_rotation_back_at_the_gimbal_lock() {
    let mut closed: f64 = 0.0;
    for pitch in [-90.0f64, 90.0] {
        for off in [0.0, 1e-12, 1e-9, 1e-7, 1e-4, 0.3] {
            for (roll, yaw) in [(0.0, 0.0), (0.7, -1.9), (-2.5, 3.0)] {
                let p = pitch.to_radians() - pitch.signum() * off;
                let q = UnitQuaternion::from_euler_angles(roll, p, yaw);
                let [r, p2, y] = rpy(&q);
                let back = UnitQuaternion::from_euler_angles(r, p2, y);
                let miss = angle_between(&back, &q);
                assert!(miss < 1e-14, "{pitch} {off}: {miss:e}");
                let (r, p2, y) = q.euler_angles();
                let back = UnitQuaternion::from_euler_angles(r, p2, y);
                closed = closed.max(angle_between(&back, &q));
            }
        }
    }
    assert!(closed > 1e-9, "{closed}");
}
