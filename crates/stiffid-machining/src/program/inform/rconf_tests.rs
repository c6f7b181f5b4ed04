//! `///RCONF` read and stated from a posture as Yaskawa defines each choice.

use super::rconf::Rconf;
use crate::program::cartesian::flags::ConfigurationData;
use stiffid_core::robot::configuration::Configuration;

#[test]
fn rconf_is_read_and_stated_from_the_posture() {
    assert_eq!(
        Rconf::parse("1,0,0,0,0,0,0,0").unwrap(),
        Rconf([1, 0, 0, 0, 0, 0])
    );
    let bad = Rconf::parse("0,0,2,0,0,0,0,0").unwrap_err();
    assert!(bad.contains("number 3 is '2', expected 0 or 1"), "{bad}");
    let short = Rconf::parse("0,0,0").unwrap_err();
    assert!(short.contains("at least six numbers"), "{short}");
    // B negative: no flip; the wrist centre behind the S axis: rear; R beyond 180 deg, T at
    // -180 deg (outside -180 excluded to 180 included), S at 180 deg (inside).
    let arm = Configuration {
        q_deg: [180.0, 10.0, -20.0, 190.0, -10.0, -180.0],
        front: -0.1,
        elbow: 0.2,
    };
    let r = Rconf::of(&arm);
    assert_eq!(r, Rconf([1, 0, 1, 1, 1, 0]));
    assert_eq!(r.branch(), (true, false, true));
    assert_eq!(ConfigurationData::text(&r), "RCONF 1,0,1,1,1,0");
    let upright = Configuration {
        q_deg: [-30.0, 10.0, -20.0, 0.0, 0.0, 90.0],
        front: 0.8,
        elbow: -0.05,
    };
    assert_eq!(Rconf::of(&upright), Rconf([0, 1, 0, 0, 0, 0]));
}
