//! `stiffid kinematics` end to end: real values through `--json` and the text output, and bad
//! input giving one line on stderr that names what was wrong, exit code 2, no panic.

use crate::common;

use common::{assert_success, assert_usage_error, json, stiffid, write_file};
use std::path::Path;

const COMAU: &str = "comau-smart5-nj165-3.0";

/// A file of the library's test data.
fn data(name: &str) -> String {
    format!(
        "{}/../stiffid/tests/data/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// Writes `text` to a file in the test scratch directory; returns its path.
fn scratch(name: &str, text: &str) -> String {
    let path = write_file(Path::new(env!("CARGO_TARGET_TMPDIR")), name, text);
    path.to_string_lossy().into_owned()
}

#[test]
fn json_gives_the_comau_flange_check_position_and_an_si_jacobian() {
    let out = stiffid(&[
        "kinematics",
        "--robot",
        COMAU,
        "--q-deg",
        "10,20,-90,30,20,10",
        "--json",
    ]);
    let v = json(&out);
    let numbers = |key: &str| -> Vec<f64> {
        v[key]
            .as_array()
            .unwrap_or_else(|| panic!("{key} missing"))
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let flange = numbers("flange_position_mm");
    for (got, want) in flange.iter().zip([2417.77, -466.26, 2116.01]) {
        assert!((got - want).abs() < 0.01, "flange {flange:?}");
    }
    assert_eq!(numbers("point_position_mm"), flange);
    // Column of axis 1: theta_1 = -q_1, so [v; omega] = [(p_y, -p_x, 0) m/rad; (0, 0, -1)].
    let jacobian = v["jacobian"].as_array().unwrap();
    assert_eq!(jacobian.len(), 6);
    let column_1: Vec<f64> = jacobian
        .iter()
        .map(|row| row[0].as_f64().unwrap())
        .collect();
    let expected = [flange[1] * 1e-3, -flange[0] * 1e-3, 0.0, 0.0, 0.0, -1.0];
    for (got, want) in column_1.iter().zip(expected) {
        assert!(
            (got - want).abs() < 1e-9,
            "column 1 {column_1:?}, expected {expected:?}"
        );
    }
    let rotation = v["flange_rotation"].as_array().unwrap();
    assert_eq!(rotation.len(), 3);
    let k = v["dexterity"].as_f64().unwrap();
    assert!(k > 1.0 && k.is_finite());
    // No length given: the robot's own, the one that minimises the median dexterity of the point.
    let robot = stiffid::internal::robot::presets::get(COMAU).unwrap();
    let l = stiffid::internal::setup::prior::robot_characteristic_length(
        &robot,
        &nalgebra::Vector3::zeros(),
    )
    .unwrap();
    assert_eq!(v["characteristic_length_source"], "derived");
    assert_eq!(v["characteristic_length_mm"].as_f64().unwrap(), l * 1e3);
    assert_eq!(v["joint_positions_mm"].as_array().unwrap().len(), 6);
}

#[test]
fn text_output_names_units_and_shows_the_point() {
    let out = stiffid(&[
        "kinematics",
        "--robot",
        COMAU,
        "--q-deg",
        "0,0,-90,0,0,0",
        "--point-mm",
        "0,0,100",
        "--coordinates",
        "kinematic",
    ]);
    assert_success(&out);
    let text = String::from_utf8(out.stdout).unwrap();
    // At this posture the flange z axis points along the base x axis, and axes 4 and 6 align.
    for part in [
        "flange position_mm: 2074.000, 0.000, 2255.000",
        "point position_mm: 2174.000, 0.000, 2255.000",
        "kinematic angles",
        "m/rad",
        "theta6",
        "dexterity k(J_N) (L = ",
        " mm, derived from the robot: minimises the point's median dexterity): infinite (singular posture)",
    ] {
        assert!(text.contains(part), "'{part}' missing from: {text}");
    }
}

#[test]
fn a_urdf_robot_works_with_its_tip() {
    assert_success(&stiffid(&[
        "kinematics",
        "--robot",
        &data("comau-nj165-two-leaves.urdf"),
        "--tip",
        "tool0",
        "--q-deg",
        "0,-90,0,0,0,180",
        "--json",
    ]));
}

#[test]
fn unknown_preset() {
    assert_usage_error(
        &stiffid(&[
            "kinematics",
            "--robot",
            "kuka-kr9000",
            "--q-deg",
            "0,0,0,0,0,0",
        ]),
        &["unknown robot preset 'kuka-kr9000'", COMAU],
    );
}

#[test]
fn missing_robot_file() {
    assert_usage_error(
        &stiffid(&[
            "kinematics",
            "--robot",
            "no/such/robot.toml",
            "--q-deg",
            "0,0,0,0,0,0",
        ]),
        &["no/such/robot.toml", "no file", "no preset"],
    );
}

#[test]
fn malformed_robot_toml() {
    let file = scratch(
        "malformed-robot.toml",
        "name = \"x\"\nconvention = \"modified-dh\n",
    );
    assert_usage_error(
        &stiffid(&["kinematics", "--robot", &file, "--q-deg", "0,0,0,0,0,0"]),
        &[&file, "line 2"],
    );
}

#[test]
fn unknown_key_in_a_robot_toml() {
    let preset = include_str!("../../../stiffid-core/presets/comau-smart5-nj165-3.0.toml");
    let text = preset.replacen("d_mm = 830.0", "d_mm = 830.0\nlength_mm = 1.0", 1);
    assert_ne!(text, preset);
    let file = scratch("unknown-key-robot.toml", &text);
    assert_usage_error(
        &stiffid(&["kinematics", "--robot", &file, "--q-deg", "0,0,-90,0,0,0"]),
        &[&file, "unknown field `length_mm`", "a_mm"],
    );
}

#[test]
fn urdf_without_the_tip_link() {
    // A tip link missing, one ending a short chain, and one given for a preset (no tip to choose).
    for (robot, tip, message) in [
        (
            data("comau-nj165.urdf"),
            "gripper",
            "no link named 'gripper'",
        ),
        (
            data("comau-nj165-two-leaves.urdf"),
            "camera",
            "3 revolute joints; expected 6",
        ),
        (
            "comau-smart5-nj165-3.0".to_string(),
            "tool0",
            "tip link: 'tool0' given, but only a URDF robot has a tip link to choose",
        ),
    ] {
        let args = [
            "kinematics",
            "--robot",
            &robot,
            "--tip",
            tip,
            "--q-deg",
            "0,0,0,0,0,0",
        ];
        assert_usage_error(&stiffid(&args), &[&robot, message]);
    }
}

#[test]
fn urdf_with_a_prismatic_joint() {
    let urdf = data("comau-nj165-prismatic.urdf");
    assert_usage_error(
        &stiffid(&["kinematics", "--robot", &urdf, "--q-deg", "0,0,0,0,0,0"]),
        &[&urdf, "joint_3", "Prismatic", "revolute"],
    );
}

#[test]
fn bad_angles_are_named_with_the_value() {
    // COMAU axis 3 (absolute forearm angle) runs from -256 to -10 deg.
    let limits = "--q-deg[3] = 0.00 deg: expected within the robot's limits [-256.00, -10.00] deg";
    let cases: [(&str, &[&str]); 4] = [
        ("0,0,-90", &["--q-deg", "expected 6", "got 3"]),
        ("0,0,NaN,0,0,0", &["--q-deg[3]: NaN is outside"]),
        (
            "0,ten,-90,0,0,0",
            &["--q-deg", "value 2 'ten'", "not a number"],
        ),
        ("0,0,0,0,0,0", &[limits]),
    ];
    for (q, expected) in cases {
        let args = ["kinematics", "--robot", COMAU, "--q-deg", q];
        assert_usage_error(&stiffid(&args), expected);
    }
}

#[test]
fn bad_point_and_characteristic_length() {
    let args = ["kinematics", "--robot", COMAU, "--q-deg", "0,0,-90,0,0,0"];
    let e = stiffid(&[&args[..], &["--point-mm", "1,2"]].concat());
    assert_usage_error(&e, &["--point-mm", "expected 3"]);
    let e = stiffid(&[&args[..], &["--characteristic-length-mm", "0"]].concat());
    assert_usage_error(
        &e,
        &["--characteristic-length-mm", "0 is outside [1, 100000] mm"],
    );
}

#[test]
fn a_given_characteristic_length_is_used_and_named_given() {
    let args = [
        "kinematics",
        "--robot",
        COMAU,
        "--q-deg",
        "10,20,-90,30,20,10",
    ];
    let given = json(&stiffid(
        &[&args[..], &["--json", "--characteristic-length-mm", "1200"]].concat(),
    ));
    assert_eq!(given["characteristic_length_mm"], 1200.0);
    assert_eq!(given["characteristic_length_source"], "given");
    let derived = json(&stiffid(&[&args[..], &["--json"]].concat()));
    // The same Jacobian, normalised by another length: another dexterity.
    assert_eq!(given["jacobian"], derived["jacobian"]);
    assert_ne!(given["dexterity"], derived["dexterity"]);
    let text = String::from_utf8(
        stiffid(&[&args[..], &["--characteristic-length-mm", "1200"]].concat()).stdout,
    )
    .unwrap();
    assert!(text.contains("(L = 1200.0 mm, given)"), "{text}");
}

#[test]
fn radians_given_to_q_deg_get_the_radians_warning() {
    let radians = "0,0.5,-1.571,0,1.2,0";
    for args in [
        vec![
            "kinematics",
            "--robot",
            "fanuc-r2000ic-165f",
            "--q-deg",
            radians,
        ],
        vec![
            "predict",
            "--setup",
            "fanuc-r2000ic-165f",
            "--q-deg",
            radians,
            "--wrench",
            "0,0,-200,0,0,0",
        ],
    ] {
        let out = stiffid(&args);
        assert_success(&out);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr
                .starts_with("warning: --q-deg: every axis angle lies within +-1.571 deg: radians"),
            "{stderr}"
        );
    }
    // Degrees, small whole ones included, get none.
    for degrees in ["0,30,-90,0,45,0", "0,5,-5,0,0,0", "0,0,0,0,0,0"] {
        let out = stiffid(&[
            "kinematics",
            "--robot",
            "fanuc-r2000ic-165f",
            "--q-deg",
            degrees,
        ]);
        assert_success(&out);
        assert!(
            out.stderr.is_empty(),
            "{degrees}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// The example cell: a KUKA KR 210 on a 6 m track along x, a part on a tilt-rotate positioner.
fn track_cell() -> String {
    format!(
        "{}/../../examples/track/track-cell.toml",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn numbers_of(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn a_cell_on_a_track_and_a_positioner_gives_cell_positions_and_external_columns() {
    let q = "10,30,-20,40,60,-30";
    let on_track = json(&stiffid(&[
        "kinematics",
        "--setup",
        &track_cell(),
        "--q-deg",
        q,
        "--external",
        "3000,20,45",
        "--point-mm",
        "0,0,250",
        "--json",
    ]));
    let fixed = json(&stiffid(&[
        "kinematics",
        "--robot",
        "kuka-kr210-robond",
        "--q-deg",
        q,
        "--point-mm",
        "0,0,250",
        "--json",
    ]));
    // The carriage at 3000 mm along x: every position moved by (3000, 0, 0) mm, the arm's
    // Jacobian unchanged (a translation turns no column).
    for key in ["flange_position_mm", "point_position_mm"] {
        let (a, b) = (numbers_of(&on_track[key]), numbers_of(&fixed[key]));
        for (i, shift) in [3000.0, 0.0, 0.0].iter().enumerate() {
            assert!((a[i] - b[i] - shift).abs() < 1e-9, "{key}: {a:?} {b:?}");
        }
    }
    let rows = |v: &serde_json::Value| -> Vec<f64> {
        v.as_array().unwrap().iter().flat_map(numbers_of).collect()
    };
    let (a, b) = (rows(&on_track["jacobian"]), rows(&fixed["jacobian"]));
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-12, "{a:?} {b:?}");
    }
    let columns: Vec<&str> = (on_track["external"].as_array().unwrap().iter())
        .map(|e| e["column"].as_str().unwrap())
        .collect();
    assert_eq!(columns, ["e1_mm", "e2_deg", "e3_deg"]);
    // 6 rows of 3 columns; the track's column is its direction.
    let je: Vec<Vec<f64>> = (on_track["external_jacobian"].as_array().unwrap().iter())
        .map(numbers_of)
        .collect();
    assert_eq!(je.len(), 6);
    let track: Vec<f64> = je.iter().map(|row| row[0]).collect();
    assert_eq!(track, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    // The rotate axis turns the part under the tool: -omega = -(its direction, tilted 20 deg
    // about x) = (0, sin 20, -cos 20).
    let (s, c) = 20f64.to_radians().sin_cos();
    let rotate: Vec<f64> = je[3..].iter().map(|row| row[2]).collect();
    for (got, want) in rotate.iter().zip([0.0, s, -c]) {
        assert!((got - want).abs() < 1e-12, "{rotate:?}");
    }
    // The part's origin (3000, 1800, 900) mm tilted 20 deg about the line along x through
    // (3000, 1800, 700): the rotate axis goes through it.
    let part = numbers_of(&on_track["part_position_mm"]);
    for (got, want) in part
        .iter()
        .zip([3000.0, 1800.0 - 200.0 * s, 700.0 + 200.0 * c])
    {
        assert!((got - want).abs() < 1e-9, "{part:?}");
    }
    let text = stiffid(&[
        "kinematics",
        "--setup",
        &track_cell(),
        "--q-deg",
        q,
        "--external",
        "3000,20,45",
    ]);
    assert_success(&text);
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(text.contains("e1_mm (track, carrier) = 3000.000"), "{text}");
    assert!(
        text.contains("part frame position_mm: 3000.000, 1731.596"),
        "{text}"
    );
}

#[test]
fn a_cell_with_external_axes_refuses_a_posture_without_their_values() {
    let q = "0,30,0,0,60,0";
    let base = ["kinematics", "--setup", &track_cell(), "--q-deg", q];
    assert_usage_error(
        &stiffid(&base),
        &["--external", "e1_mm track", "e3_deg rotate"],
    );
    let with = |e: &str| {
        let mut args = base.to_vec();
        args.extend(["--external", e]);
        stiffid(&args)
    };
    assert_usage_error(
        &with("3000,20"),
        &["--external", "expected 3 external axis values"],
    );
    assert_usage_error(
        &with("6500,20,45"),
        &["--external e1_mm (track)", "0 to 6000 mm"],
    );
    assert_usage_error(&with("3000,120,45"), &["e2_deg (tilt)", "-95 to 95 deg"]);
    let plain = stiffid(&[
        "kinematics",
        "--robot",
        "kuka-kr210-robond",
        "--q-deg",
        q,
        "--external",
        "100",
    ]);
    assert_usage_error(&plain, &["--external", "no external axes"]);
    let robot = scratch(
        "track-robot.toml",
        &format!(
            "{}\n[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1, 0, 0]\nlimits_deg = [0, 90]\n",
            stiffid::internal::robot::presets::text("kuka-kr210-robond").unwrap()
        ),
    );
    let out = stiffid(&["kinematics", "--robot", &robot, "--q-deg", q]);
    assert_usage_error(
        &out,
        &[
            "track-robot.toml",
            "external_axis[1] (track).limits_deg",
            "limits_mm",
        ],
    );
}

#[test]
fn a_group_on_a_track_is_designed_at_each_station_and_written_with_its_columns() {
    let dir = common::temp_dir("track-select");
    let out = dir.join("group.csv");
    let cell = track_cell();
    let run = |stations: &[&str]| {
        let mut args = vec![
            "select", "--setup", &cell, "--global", "--count", "8", "--starts", "4",
        ];
        for s in stations {
            args.extend(["--station", s]);
        }
        let out = out.to_str().unwrap();
        stiffid(&[&args[..], &["--out", out, "--json"]].concat())
    };
    let doc = json(&run(&["500,0,0", "5500,0,0"]));
    let stations = doc["stations"].as_array().unwrap();
    assert_eq!(stations.len(), 2);
    let values: Vec<f64> = stations
        .iter()
        .map(|s| s["value"].as_f64().unwrap())
        .collect();
    let best = if values[0] <= values[1] { 0 } else { 1 };
    assert_eq!(doc["station"]["e1_mm"], stations[best]["e1_mm"]);
    assert_eq!(doc["value"].as_f64().unwrap(), values[best]);
    let csv = std::fs::read_to_string(&out).unwrap();
    let mut lines = csv.lines();
    assert!(lines
        .next()
        .unwrap()
        .ends_with(",q6_deg,e1_mm,e2_deg,e3_deg"));
    let e1 = doc["station"]["e1_mm"].as_f64().unwrap();
    assert!(
        lines.all(|l| l.ends_with(&format!(",{e1:.6},0.000000,0.000000"))),
        "{csv}"
    );
    std::fs::remove_file(&out).unwrap();
    // The plan's scene stands the group at its station: the carriage and the arm's base moved
    // along the rail by e1, the external values the station's (SI).
    let report = dir.join("plan");
    let (o, r) = (out.to_str().unwrap(), report.to_str().unwrap());
    let args = ["select", "--setup", &cell, "--start-random", "--count", "6"];
    let more = ["--station", "3000,20,45", "--out", o, "--report", r];
    assert!(stiffid(&[&args[..], &more[..]].concat()).status.success());
    let html = std::fs::read_to_string(report.join("plan.html")).unwrap();
    let open = "id=\"scene-data\">";
    let from = html.find(open).unwrap() + open.len();
    let to = from + html[from..].find("</script>").unwrap();
    let scene: serde_json::Value = serde_json::from_str(&html[from..to]).unwrap();
    let names: Vec<&str> = (scene["links"].as_array().unwrap().iter())
        .map(|l| l["name"].as_str().unwrap())
        .collect();
    assert_eq!(names[8..], ["track", "carriage", "positioner table"]);
    for p in scene["postures"].as_array().unwrap() {
        let e: Vec<f64> = serde_json::from_value(p["external"].clone()).unwrap();
        assert!((e[0] - 3.0).abs() < 1e-12 && (e[1] - 20f64.to_radians()).abs() < 1e-12);
        assert!((p["link_frames"][9]["translation_m"][0].as_f64().unwrap() - 3.0).abs() < 1e-12);
        assert!((p["joint_positions_m"][0][0].as_f64().unwrap() - 3.0).abs() < 1e-9);
    }
    std::fs::remove_file(&out).unwrap();
    assert_usage_error(&run(&["7000,0,0"]), &["e1_mm (track)", "7000"]);
    assert_usage_error(&run(&["500"]), &["--station", "3 comma-separated numbers"]);
    assert_usage_error(&run(&[]), &["station", "e1_mm, e2_deg, e3_deg"]);
    assert!(!out.exists());
}
