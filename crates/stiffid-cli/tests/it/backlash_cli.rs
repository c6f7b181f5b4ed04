//! `calibrate` with the readings' directions of approach (`dir1..dir6`): the backlash terms
//! fitted with the geometry, named in `--maps` or chosen by `auto`, written to the calibrated
//! robot file as `half_backlash_deg` and read back; `--maps J2:b` refused without directions.

use crate::calibrate_cli::{model, postures, readings, truth, SETUP};
use crate::common::{json, refused, stiffid, temp_dir, write_file};
use nalgebra::{DVector, Isometry3, Point3, Vector3, Vector6};
use stiffid::internal::metrology::calibration::error_model::{JointMaps, Observation};
use stiffid::internal::metrology::calibration::maps::Spec;
use stiffid::internal::metrology::calibration::ErrorModel;

/// Half the backlash of joints 2 and 3, rad (0.3 and -0.2 mrad).
const HALF: [f64; 2] = [3e-4, -2e-4];

/// The COMAU's model with backlash terms on joints 2 and 3, and its truth: the geometric errors
/// of [`truth`] and half backlashes [`HALF`].
fn backlash_truth() -> (ErrorModel, DVector<f64>) {
    let geometry = model();
    let x = truth(&geometry);
    let terms = JointMaps {
        harmonics: [0; 6],
        backlash: [false, true, true, false, false, false],
    };
    let model = geometry.with_maps(terms).unwrap();
    let mut values = model.nominal();
    values.rows_mut(0, x.len()).copy_from(&x);
    let n = values.len();
    values[n - 2] = HALF[0];
    values[n - 1] = HALF[1];
    (model, values)
}

/// Readings of every measuring point at `qs` (deg) with each posture's directions of approach
/// (`dir1..dir6`, a fixed pattern of signs), by a tracker at `tracker`.
fn approached(
    model: &ErrorModel,
    x: &DVector<f64>,
    tracker: &Isometry3<f64>,
    qs: &[[f64; 6]],
) -> String {
    let mut text = stiffid::internal::io::readings::header() + ",dir1,dir2,dir3,dir4,dir5,dir6\n";
    for (i, q_deg) in qs.iter().enumerate() {
        let q = Vector6::from_iterator(q_deg.iter().map(|d| d.to_radians()));
        let direction = Vector6::from_fn(|j, _| match (i * 7 + j * 3) % 5 < 2 {
            true => -1.0,
            false => 1.0,
        });
        for k in 0..model.points() {
            let o = Observation {
                posture: i,
                point: k,
                q,
                measured: Vector3::zeros(),
                wrench: Vector6::zeros(),
                e: stiffid::internal::robot::external::ExternalValues::NONE,
                table: false,
                direction,
            };
            let t = tracker.inverse() * Point3::from(model.predict(x, &[o]).unwrap()[0]);
            let q: Vec<String> = q_deg.iter().map(|v| format!("{v:?}")).collect();
            let d: Vec<String> = direction.iter().map(|v| format!("{v}")).collect();
            text += &format!(
                "P{},{},{},{:?},{:?},{:?},{}\n",
                i + 1,
                k + 1,
                q.join(","),
                t.x * 1e3,
                t.y * 1e3,
                t.z * 1e3,
                d.join(",")
            );
        }
    }
    text
}

#[test]
fn calibrate_fits_the_backlash_and_writes_it_to_the_robot_file() {
    let d = temp_dir("calibrate-backlash");
    let (model, x) = backlash_truth();
    let tracker = crate::calibrate_cli::tracker();
    let data = write_file(
        &d,
        "fit.csv",
        &approached(&model, &x, &tracker, &postures(40, 3)),
    );
    let robot = d.join("robot.toml");
    let args = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
        "--maps",
        "J2:b,J3:b",
        "--gravity",
        "none",
        "--out",
        robot.to_str().unwrap(),
        "--json",
    ];
    let doc = json(&stiffid(&args));
    assert!(doc["residual_rms_mm"].as_f64().unwrap() < 1e-6, "{doc}");
    assert_eq!(doc["maps"]["chosen"], "J2:b,J3:b", "{}", doc["maps"]);
    let value = |name: &str| {
        let p = (doc["parameters"].as_array().unwrap().iter())
            .find(|p| p["name"] == name)
            .unwrap_or_else(|| panic!("{name} missing"));
        assert_eq!(p["unit"], "deg");
        p["value"].as_f64().unwrap()
    };
    // Noise-free: the truth, but for the bias of the least ridge chosen (1e-6 per reading).
    let fitted: Vec<f64> = (2..=3)
        .map(|joint| value(&format!("joint{joint}.map.backlash")))
        .collect();
    for (got, half) in fitted.iter().zip(HALF) {
        let want = half.to_degrees();
        assert!((got - want).abs() < 1e-5 * want.abs(), "{got} vs {want}");
    }
    // The robot file holds them (deg) and reads them back (rad).
    let text = std::fs::read_to_string(&robot).unwrap();
    assert_eq!(text.matches("half_backlash_deg = ").count(), 2, "{text}");
    let written = stiffid::internal::robot::file::parse(&text, "robot.toml").unwrap();
    let maps = written.error_maps().unwrap();
    for (joint, deg) in [(1, fitted[0]), (2, fitted[1])] {
        let got = maps[joint].backlash().to_degrees();
        assert!((got - deg).abs() < 1e-12 * deg.abs(), "{got} vs {deg}");
        assert_eq!(maps[joint].harmonics(), 0);
    }
    // `--maps auto` finds both terms from the 40 postures (30 or more).
    let auto = [&args[..5], &["--gravity", "none", "--json"]].concat();
    let doc = json(&stiffid(&auto));
    let chosen = doc["maps"]["chosen"].as_str().unwrap().to_string();
    let Spec::Fixed(found) = Spec::parse(&chosen).unwrap() else {
        panic!("{chosen}")
    };
    assert_eq!(
        found.backlash,
        [false, true, true, false, false, false],
        "{chosen}"
    );
    assert!(doc["residual_rms_mm"].as_f64().unwrap() < 1e-6, "{doc}");
}

#[test]
fn a_backlash_term_without_directions_is_refused() {
    let d = temp_dir("calibrate-backlash-refused");
    let geometry = model();
    let tracker = Isometry3::identity();
    let plain = readings(&geometry, &truth(&geometry), &tracker, &postures(12, 4));
    let data = write_file(&d, "plain.csv", &plain);
    let base = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
    ];
    for maps in ["J2:b", "J1,J3:8b"] {
        refused(
            &d,
            &[&base[..], &["--maps", maps]].concat(),
            &["--maps", "backlash", "dir1..dir6"],
        );
    }
    // A bad syntax is refused as any other.
    for odd in ["J2:bb", "J2b", "J2:b8"] {
        refused(
            &d,
            &[&base[..], &["--maps", odd]].concat(),
            &["--maps", odd],
        );
    }
}
