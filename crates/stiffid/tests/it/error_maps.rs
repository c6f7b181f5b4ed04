//! A robot file's joint error maps: the kinematics with a map equal the chain turned by the
//! axis angle plus the map's error, computed here term by term.

use nalgebra::{Vector3, Vector6};
use stiffid::internal::robot::file;

const TABLE: &str = r#"
name = "six"
convention = "standard-dh"
[[joint]]
a_mm = 150
alpha_deg = 90
d_mm = 450
lower_deg = -180
upper_deg = 180
ERROR1
[[joint]]
a_mm = 600
alpha_deg = 0
d_mm = 0
lower_deg = -180
upper_deg = 180
[[joint]]
a_mm = 120
alpha_deg = 90
d_mm = 0
lower_deg = -180
upper_deg = 180
ERROR3
[[joint]]
a_mm = 0
alpha_deg = -90
d_mm = 640
lower_deg = -180
upper_deg = 180
[[joint]]
a_mm = 0
alpha_deg = 90
d_mm = 0
lower_deg = -180
upper_deg = 180
[[joint]]
a_mm = 0
alpha_deg = 0
d_mm = 100
lower_deg = -360
upper_deg = 360
"#;

const COS1: [f64; 3] = [0.01, -0.004, 0.002];
const SIN1: [f64; 3] = [0.003, 0.0, -0.001];
const COS3: [f64; 1] = [-0.02];
const SIN3: [f64; 1] = [0.015];

/// The error (rad) of coefficients in degrees at `q` (rad), term by term.
fn error(cos: &[f64], sin: &[f64], q: f64) -> f64 {
    let terms = cos.iter().zip(sin).enumerate();
    terms
        .map(|(i, (a, b))| {
            let h = (i + 1) as f64;
            (a * (h * q).cos() + b * (h * q).sin()).to_radians()
        })
        .sum()
}

fn list(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|x| format!("{x}")).collect();
    format!("[{}]", parts.join(", "))
}

#[test]
fn the_kinematics_with_maps_turn_each_axis_by_its_error() {
    let line = |c: &[f64], s: &[f64]| {
        format!(
            "error_map = {{ cos_deg = {}, sin_deg = {} }}",
            list(c),
            list(s)
        )
    };
    let mapped = TABLE
        .replace("ERROR1", &line(&COS1, &SIN1))
        .replace("ERROR3", &line(&COS3, &SIN3));
    let plain = TABLE.replace("ERROR1", "").replace("ERROR3", "");
    let (mapped, plain) = (
        file::parse(&mapped, "mapped.toml").unwrap(),
        file::parse(&plain, "plain.toml").unwrap(),
    );
    assert!(mapped.error_maps().is_some() && plain.error_maps().is_none());
    let tool = Vector3::new(0.05, -0.02, 0.2);
    for q in [
        Vector6::new(0.3, -0.4, 0.5, -0.6, 0.7, -0.8),
        Vector6::new(-2.1, 0.9, -1.7, 1.3, -0.5, 2.1),
    ] {
        let mut turned = q;
        turned[0] += error(&COS1, &SIN1, q[0]);
        turned[2] += error(&COS3, &SIN3, q[2]);
        let (a, b) = (
            mapped.frames(&q).point(&tool),
            plain.frames(&turned).point(&tool),
        );
        assert!((a - b).norm() < 1e-14, "{:e}", (a - b).norm());
        // The map moves the point by far more than rounding.
        assert!((a - plain.frames(&q).point(&tool)).norm() > 1e-5);
    }
}

/// Each list of a map is optional: one left out holds zeros, the kinematics those of both lists
/// with zeros written out.
#[test]
fn a_map_of_one_list_is_that_list_and_zeros() {
    let zeros = [0.0; 3];
    let cases = [
        (
            "error_map = { cos_deg = [0.01, -0.004, 0.002] }",
            (&COS1, &zeros),
        ),
        (
            "error_map = { sin_deg = [0.003, 0.0, -0.001] }",
            (&zeros, &SIN1),
        ),
    ];
    for (given, (cos, sin)) in cases {
        let one = TABLE.replace("ERROR1", given).replace("ERROR3", "");
        let both = TABLE
            .replace(
                "ERROR1",
                &format!(
                    "error_map = {{ cos_deg = {}, sin_deg = {} }}",
                    list(cos),
                    list(sin)
                ),
            )
            .replace("ERROR3", "");
        let (one, both) = (
            file::parse(&one, "one.toml").unwrap(),
            file::parse(&both, "both.toml").unwrap(),
        );
        let q = Vector6::new(0.3, -0.4, 0.5, -0.6, 0.7, -0.8);
        let tool = Vector3::new(0.05, -0.02, 0.2);
        let (a, b) = (one.frames(&q).point(&tool), both.frames(&q).point(&tool));
        assert_eq!(a, b, "{given}");
    }
}

#[test]
fn a_bad_error_map_is_refused_naming_the_joint() {
    let bad = TABLE
        .replace(
            "ERROR1",
            "error_map = { cos_deg = [0.1, 0.2], sin_deg = [0.1] }",
        )
        .replace("ERROR3", "");
    let e = file::parse(&bad, "bad.toml").unwrap_err().to_string();
    assert!(e.contains("bad.toml: joint[1].error_map"), "{e}");
    let huge = TABLE
        .replace(
            "ERROR1",
            "error_map = { cos_deg = [20.0], sin_deg = [0.0] }",
        )
        .replace("ERROR3", "");
    let e = file::parse(&huge, "huge.toml").unwrap_err().to_string();
    assert!(e.contains("within 10 deg"), "{e}");
}

#[test]
fn a_maps_list_gives_each_joint_once_in_digits() {
    use stiffid::internal::metrology::calibration::maps::{name, JointMaps, Spec};
    let fixed = Spec::parse("J2, j3:8").unwrap();
    assert_eq!(fixed, Spec::Fixed(JointMaps::from([0, 16, 8, 0, 0, 0])));
    // A backlash term: `b` after the count, `:b` alone; named back the same way.
    let backlash = Spec::parse("J2:8b,J4:b,J5").unwrap();
    let want = JointMaps {
        harmonics: [0, 8, 0, 0, 16, 0],
        backlash: [false, true, false, true, false, false],
    };
    assert_eq!(backlash, Spec::Fixed(want));
    assert_eq!(name(&want), "J2:8b,J4:b,J5:16");
    assert_eq!(Spec::parse(&name(&want)).unwrap(), backlash);
    // A joint named twice would silently keep the last count.
    for twice in ["J1,J1:16", "J1:8,J1:16", "J3,j3", "J2:b,J2:8"] {
        let e = Spec::parse(twice).unwrap_err().to_string();
        assert!(
            e.starts_with("maps: ") && e.contains("twice"),
            "{twice}: {e}"
        );
    }
    // Signs, leading zeros and exponents are not a joint or a count.
    for odd in [
        "J+1", "J01", "J1:+4", "J1:08", "J1:1e1", "J1:4.0", "J1:0", "J1:65", "J1:", "J1b", "J1:bb",
        "J1:b8", "J1:0b", "J1:B",
    ] {
        let e = Spec::parse(odd).unwrap_err().to_string();
        assert!(e.starts_with("maps: ") && e.contains(odd), "{odd}: {e}");
    }
}

/// Half a backlash in the robot file (deg) is read as rad, leaves the kinematics (the mean of
/// the two approaches) as they are, and the calibrated robot file writes it back.
#[test]
fn a_backlash_survives_the_robot_file_round_trip() {
    use stiffid::internal::metrology::calibration::error_model::MeasuredIn;
    use stiffid::internal::metrology::calibration::{
        gravity, robot_file, ErrorModel, Estimate, Geometry,
    };
    let text = TABLE
        .replace(
            "ERROR1",
            "error_map = { cos_deg = [0.01], sin_deg = [0.003], half_backlash_deg = 0.02 }",
        )
        .replace("ERROR3", "error_map = { half_backlash_deg = -0.005 }");
    let robot = file::parse(&text, "backlash.toml").unwrap();
    let maps = robot.error_maps().unwrap();
    assert_eq!(maps[0].backlash(), 0.02_f64.to_radians());
    assert_eq!(
        (maps[2].backlash(), maps[2].harmonics()),
        (-0.005_f64.to_radians(), 0)
    );
    // Without a direction the robot stands at the mean: the backlash does not move it.
    let plain = TABLE
        .replace(
            "ERROR1",
            "error_map = { cos_deg = [0.01], sin_deg = [0.003] }",
        )
        .replace("ERROR3", "");
    let plain = file::parse(&plain, "plain.toml").unwrap();
    let q = Vector6::new(0.3, -0.4, 0.5, -0.6, 0.7, -0.8);
    assert_eq!(robot.frames(&q).flange, plain.frames(&q).flange);
    let points = [Vector3::new(0.0, 0.0, 0.1)];
    let model = ErrorModel::new(
        &robot,
        &points,
        MeasuredIn::Base,
        Geometry::Full,
        gravity::Terms::none(&robot),
    )
    .unwrap();
    let estimate = Estimate {
        frame: nalgebra::Isometry3::identity(),
        values: model.nominal(),
    };
    let written = robot_file::robot_toml(&model, &estimate).unwrap();
    assert!(written.contains("half_backlash_deg = "), "{written}");
    let back = file::parse(&written, "calibrated.toml").unwrap();
    let back = back.error_maps().unwrap();
    for j in 0..6 {
        let (a, b) = (maps[j].backlash(), back[j].backlash());
        assert!((a - b).abs() <= 1e-15 * a.abs(), "joint {}: {a} {b}", j + 1);
    }
    let bad = TABLE
        .replace("ERROR1", "error_map = { half_backlash_deg = 11.0 }")
        .replace("ERROR3", "");
    let e = file::parse(&bad, "bad.toml").unwrap_err().to_string();
    assert!(
        e.contains("bad.toml: joint[1].error_map") && e.contains("half backlash"),
        "{e}"
    );
}

/// A map's `range_deg` (the axis angles it was fitted over): within it the kinematics are the
/// map's without a range to the last bit, 10 deg and more beyond it those of no map on that
/// joint, half-way down the ramp the chain turns by half the error; the calibrated robot file
/// writes the range its model's maps were given, and a reversed range is refused naming the
/// joint.
#[test]
fn a_map_tapers_to_zero_beyond_its_range_in_the_robot_file() {
    use stiffid::internal::metrology::calibration::error_model::MeasuredIn;
    use stiffid::internal::metrology::calibration::{
        gravity, robot_file, ErrorModel, Estimate, Geometry,
    };
    let with = |line: &str| {
        let map = format!(
            "error_map = {{ cos_deg = {}, sin_deg = {}{line} }}",
            list(&COS1),
            list(&SIN1)
        );
        let text = TABLE.replace("ERROR1", &map).replace("ERROR3", "");
        file::parse(&text, "ranged.toml").unwrap()
    };
    let ranged = with(", range_deg = [-30.0, 50.0]");
    let free = with("");
    let none = file::parse(
        &TABLE.replace("ERROR1", "").replace("ERROR3", ""),
        "none.toml",
    )
    .unwrap();
    let at = |q1_deg: f64| Vector6::new(q1_deg.to_radians(), -0.4, 0.5, -0.6, 0.7, -0.8);
    for deg in [-30.0, 0.0, 49.9] {
        assert_eq!(
            ranged.frames(&at(deg)).flange,
            free.frames(&at(deg)).flange,
            "{deg}"
        );
    }
    let ramp = 20.0; // the maps' taper at the joint limits, deg
    for deg in [-30.0 - ramp, 50.0 + ramp, 150.0] {
        assert_eq!(
            ranged.frames(&at(deg)).flange,
            none.frames(&at(deg)).flange,
            "{deg}"
        );
        assert_ne!(
            free.frames(&at(deg)).flange,
            none.frames(&at(deg)).flange,
            "{deg}"
        );
    }
    let mid = 50.0 + ramp / 2.0;
    let q = mid.to_radians();
    let half = 0.5 * error(&COS1, &SIN1, q);
    assert!((ranged.mapped(&at(mid))[0] - (q + half)).abs() < 1e-16);
    let model = ErrorModel::new(
        &free,
        &[Vector3::new(0.0, 0.0, 0.1)],
        MeasuredIn::Base,
        Geometry::Full,
        gravity::Terms::none(&free),
    )
    .and_then(|m| m.with_maps([3, 0, 0, 0, 0, 0]))
    .and_then(|m| m.with_map_ranges([(-0.5, 0.9); 6]))
    .unwrap();
    let estimate = Estimate {
        frame: nalgebra::Isometry3::identity(),
        values: model.nominal(),
    };
    let written = robot_file::robot_toml(&model, &estimate).unwrap();
    let back = file::parse(&written, "calibrated.toml").unwrap();
    let (lo, hi) = back.error_maps().unwrap()[0].range().expect(&written);
    assert!(
        (lo + 0.5).abs() < 1e-15 && (hi - 0.9).abs() < 1e-15,
        "{lo} {hi}"
    );
    let bad = TABLE
        .replace(
            "ERROR1",
            "error_map = { cos_deg = [0.01], range_deg = [50.0, -30.0] }",
        )
        .replace("ERROR3", "");
    let e = file::parse(&bad, "bad.toml").unwrap_err().to_string();
    assert!(
        e.contains("bad.toml: joint[1].error_map") && e.contains("the lower first"),
        "{e}"
    );
}

/// A map's `range_deg` of other than two angles is refused naming its length (a third angle was
/// dropped).
#[test]
fn a_range_of_three_angles_is_refused() {
    for range in ["[-30.0, 50.0, 99.0]", "[-30.0]"] {
        let bad = TABLE
            .replace(
                "ERROR1",
                &format!("error_map = {{ cos_deg = [0.01], range_deg = {range} }}"),
            )
            .replace("ERROR3", "");
        let e = file::parse(&bad, "bad.toml").unwrap_err().to_string();
        assert!(
            e.contains("bad.toml") && e.contains("range_deg") && e.contains("an array of length 2"),
            "{e}"
        );
    }
}
