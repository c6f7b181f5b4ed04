//! The controllers' configuration data (`crate::program::cartesian::flags`, each
//! language's own type in its folder).

use crate::program::cartesian::flags::*;
use crate::program::krl::{StatusPart, StatusTurn};
use crate::program::ls::Config;
use crate::program::rapid::ConfData;
use crate::program::Dialect;
use nalgebra::Vector6;
use stiffid_core::robot::configuration::Configuration;
use stiffid_core::robot::presets;

fn arm(robot: &str, q_deg: [f64; 6]) -> Configuration {
    let robot = presets::get(robot).unwrap();
    Configuration::of(&robot, &Vector6::from(q_deg).map(f64::to_radians))
}

#[test]
fn fanuc_config_is_read_in_its_variants_and_refused_when_unknown() {
    let want = Config::parse("N U T, 0, 0, 0").unwrap();
    assert_eq!(want.as_str(), "N U T, 0, 0, 0");
    for text in ["N U T, 0, 0, 0", "NUT, 0, 0, 0", "N U T", "T U N, 0,0,0"] {
        assert_eq!(Config::parse(text).as_ref(), Ok(&want), "{text}");
    }
    assert_eq!(
        Config::parse("F D B, -1, 0, 1").unwrap().to_string(),
        "F D B, -1, 0, 1"
    );
    for bad in [
        "N X T, 0, 0, 0",
        "N U, 0, 0, 0",
        "N U T, a, 0, 0",
        "N F U T",
    ] {
        assert!(Config::parse(bad).is_err(), "{bad}");
    }
}

#[test]
fn kuka_parts_are_written_in_the_form_read() {
    let f = Flags::new(StatusTurn {
        status: 0b110,
        turn: 0b010101,
    });
    let part = |p: StatusPart| Part::new(p).text(&f);
    assert_eq!(part(StatusPart::Status { binary: true }), "'B110'");
    assert_eq!(part(StatusPart::Turn { binary: false }), "21");
    assert_eq!(
        Part::new(3usize).text(&Flags::new(ConfData([0, -1, 2, 5]))),
        "5"
    );
    // A part of another language's data: the data whole, as they read.
    assert_eq!(Part::new(3usize).text(&f), "S 'B110' T 'B010101'");
}

#[test]
fn each_language_names_the_usual_posture_in_its_own_data() {
    // FANUC's usual posture, tool down: J5 negative, no flip, elbow up, front.
    let a = arm("fanuc-r2000ic-165f", [-23.2, 3.9, -48.1, 0.0, -41.9, 23.2]);
    assert_eq!(Config::of(&a).as_str(), "N U T, 0, 0, 0");
    assert_eq!(ConfData::of(&a), ConfData([-1, 0, 0, 1]));
    // Status: front (bit 0 clear), A3 >= phi (bit 1), A5 <= 0 (bit 2); turn: A1, A3, A5 < 0.
    let kuka = StatusTurn::of(&a);
    assert_eq!((kuka.status, kuka.turn), (0b110, 0b010101));
    // Axis 1 turned half a revolution and the arm swung back over: behind axis 1.
    let back = arm(
        "fanuc-r2000ic-165f",
        [10.0, -80.0, 60.0, 200.0, 30.0, -400.0],
    );
    let fanuc = Config::of(&back).to_string();
    assert!(
        fanuc.starts_with("F ") && fanuc.ends_with(", 0, 1, -1"),
        "{fanuc}"
    );
    assert_eq!(ConfData::of(&back).0[1..3], [2, -5]);
    // Every language's data name the posture's shoulder, elbow and wrist.
    for arm in [a, back] {
        let branch = (arm.behind(), arm.elbow_down(), arm.wrist_negative());
        for d in [
            Dialect::Krl,
            Dialect::Rapid,
            Dialect::FanucLs,
            Dialect::Inform,
        ] {
            assert_eq!(Flags::of(d, &arm).branch(), branch, "{d:?}");
        }
    }
}

#[test]
fn the_data_compare_within_one_language_only() {
    let a = arm("fanuc-r2000ic-165f", [-23.2, 3.9, -48.1, 0.0, -41.9, 23.2]);
    let krl = Flags::of(Dialect::Krl, &a);
    assert_eq!(krl, Flags::new(StatusTurn::of(&a)));
    assert_eq!(krl.get::<StatusTurn>(), Some(&StatusTurn::of(&a)));
    assert_eq!(krl.get::<ConfData>(), None);
    assert_ne!(krl, Flags::of(Dialect::Inform, &a));
    assert_eq!(Flags::of(Dialect::Rapid, &a).text(), "[-1,0,0,1]");
    assert_eq!(Flags::of(Dialect::FanucLs, &a).text(), "'N U T, 0, 0, 0'");
}
