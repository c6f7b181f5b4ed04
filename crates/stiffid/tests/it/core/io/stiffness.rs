//! Stiffness files: the drives' stiffness and covariance, every parameter in its unit checked
//! against the setup's model, the errors naming the key, and the files written before.

use nalgebra::{DMatrix, Matrix6};
use stiffid_core::io::stiffness::*;
use stiffid_core::model::Model;
use stiffid_core::Error;

/// The check of a 6 x 6 covariance of the drives' compliance, through the check of any size.
fn check_covariance(c: &Matrix6<f64>) -> stiffid_core::Result<()> {
    let c = DMatrix::from_column_slice(6, 6, c.as_slice());
    check_covariance_of(&c, "compliance_covariance_rad2_per_nm2")
}

const K: &str = "[950000, 3000000, 900000, 250000, 200000, 150000]";

fn covariance(c: &Matrix6<f64>) -> String {
    let rows: Vec<String> = c
        .row_iter()
        .map(|r| {
            format!(
                "[{}]",
                r.iter().map(f64::to_string).collect::<Vec<_>>().join(",")
            )
        })
        .collect();
    format!("[{}]", rows.join(","))
}

#[test]
fn reads_stiffness_and_covariance() {
    let c = Matrix6::from_fn(|r, col| {
        if r == col {
            1e-12 * (r + 1) as f64
        } else {
            1e-14
        }
    });
    let text = format!(
        r#"{{"stiffness_nm_per_rad": {K}, "compliance_covariance_rad2_per_nm2": {}}}"#,
        covariance(&c)
    );
    let file = parse(&text).unwrap();
    let got = file.compliance(&Model::default()).unwrap();
    assert_eq!(got.h[5], 1.0 / 150000.0);
    assert_eq!(
        got.covariance.unwrap(),
        DMatrix::from_column_slice(6, 6, c.as_slice())
    );
    let back = parse(&serde_json::to_string(&file).unwrap()).unwrap();
    assert_eq!(back, file);
}

fn model_file(names: &[(&str, &str, &str, f64)], cov: Option<&str>) -> String {
    let params: Vec<String> = names
        .iter()
        .map(|(n, k, u, v)| {
            format!(r#"{{"name": "{n}", "kind": "{k}", "unit": "{u}", "stiffness": {v}}}"#)
        })
        .collect();
    let cov = cov.map_or(String::new(), |c| {
        format!(r#", "compliance_covariance_si": {c}"#)
    });
    format!(r#"{{"parameters": [{}]{cov}}}"#, params.join(", "))
}

const DRIVES: [(&str, &str, &str, f64); 6] = [
    ("k1", "drive", "Nm/rad", 1e6),
    ("k2", "drive", "Nm/rad", 2e6),
    ("k3", "drive", "Nm/rad", 1e6),
    ("k4", "drive", "Nm/rad", 3e5),
    ("k5", "drive", "Nm/rad", 2e5),
    ("k6", "drive", "Nm/rad", 1e5),
];

fn model_with_tool_y() -> Model {
    let robot =
        stiffid_core::robot::presets::get(stiffid_core::robot::presets::names().next().unwrap())
            .unwrap();
    let springs = stiffid_core::model::Family::Tool
        .springs(&robot, &[], None, None, "test")
        .unwrap();
    let y: Vec<_> = springs.into_iter().filter(|s| s.name == "tool_y").collect();
    Model::new(stiffid_core::Coordinates::Axis, y).unwrap()
}

#[test]
fn reads_every_parameter_in_its_unit_and_checks_them_against_the_model() {
    let mut names = DRIVES.to_vec();
    names.push(("tool_y", "translation", "N/mm", 5e4));
    let diag: Vec<String> = (0..7)
        .map(|r| {
            let row: Vec<&str> = (0..7).map(|c| if r == c { "1e-14" } else { "0" }).collect();
            format!("[{}]", row.join(","))
        })
        .collect();
    let cov = format!("[{}]", diag.join(","));
    let file = parse(&model_file(&names, Some(&cov))).unwrap();
    let c = file.compliance(&model_with_tool_y()).unwrap();
    // 5e4 N/mm is 5e7 N/m.
    assert!((c.h[6] * 5e7 - 1.0).abs() < 1e-15, "{}", c.h[6]);
    assert_eq!(c.h[1], 0.5e-6);
    assert_eq!(c.covariance.unwrap()[(6, 6)], 1e-14);
    // The drives-only model refuses the file, naming the count and both lists.
    let e = file.compliance(&Model::default()).unwrap_err().to_string();
    assert!(
        e.starts_with("parameters: the file has 7 parameters"),
        "{e}"
    );
    assert!(e.contains("tool_y") && e.contains("has 6"), "{e}");
    // Another spring at the same place is named.
    names[6] = ("tool_x", "translation", "N/mm", 5e4);
    let e = parse(&model_file(&names, None))
        .unwrap()
        .compliance(&model_with_tool_y())
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("parameters[7]: 'tool_x' (translation) where the setup's model has 'tool_y' (translation)"), "{e}");
    // A six-drive file does not fit a model with springs.
    let six = parse(&format!(r#"{{"stiffness_nm_per_rad": {K}}}"#)).unwrap();
    let e = six
        .compliance(&model_with_tool_y())
        .unwrap_err()
        .to_string();
    assert!(e.contains("virtual springs tool_y"), "{e}");
}

#[test]
fn a_parameter_in_the_wrong_unit_or_null_or_a_covariance_of_the_wrong_size_is_named() {
    let mut names = DRIVES.to_vec();
    names.push(("tool_y", "translation", "Nm/rad", 5e4));
    let e = parse(&model_file(&names, None)).unwrap_err().to_string();
    assert!(
        e.starts_with("parameters[7].unit: 'Nm/rad' for the translation 'tool_y': expected 'N/mm'"),
        "{e}"
    );
    let text = model_file(&DRIVES, None).replace("1000000}", "null}");
    let e = parse(&text).unwrap_err().to_string();
    assert!(
        e.starts_with("parameters[1].stiffness: the stiffness of 'k1' is null"),
        "{e}"
    );
    let e = parse(&model_file(&DRIVES, Some("[[1]]")))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("compliance_covariance_si: expected 6 rows of 6 numbers"),
        "{e}"
    );
    let e = parse(&model_file(&DRIVES[..5], None))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("parameters: 5 entries: expected 6 to"), "{e}");
    let e = parse("{}").unwrap_err().to_string();
    assert!(e.starts_with("parameters: missing: expected JSON"), "{e}");
}

#[test]
fn errors_name_the_key_and_position() {
    let e = parse(r#"{"stiffness_nm_per_rad": [1, 2, 3, 4, 5, -6]}"#).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("stiffness_nm_per_rad[6]: -6 is outside"),
        "{e}"
    );
    let e = parse("{\n \"stiffness_nm_per_rad\": [1, 2]\n}").unwrap_err();
    // The length is known once the array is read: the position is at or just after it.
    assert!(matches!(e, Error::Json { line: 2..=3, .. }), "{e:?}");
    assert!(e.to_string().contains("expected JSON with the key"), "{e}");
    let mut c = Matrix6::identity() * 1e-12;
    c[(0, 1)] = 1e-13;
    let text = format!(
        r#"{{"stiffness_nm_per_rad": {K}, "compliance_covariance_rad2_per_nm2": {}}}"#,
        covariance(&c)
    );
    let e = parse(&text).unwrap_err().to_string();
    assert!(
        e.starts_with("compliance_covariance_rad2_per_nm2: expected a covariance"),
        "{e}"
    );
    // Symmetric with a positive diagonal, but var(h1 - h2) = 2e-12 - 2 * 3e-12 < 0.
    let mut c = Matrix6::identity() * 1e-12;
    c[(0, 1)] = 3e-12;
    c[(1, 0)] = 3e-12;
    assert!(check_covariance(&c).is_err());
    c[(0, 1)] = 0.5e-12;
    c[(1, 0)] = 0.5e-12;
    assert!(check_covariance(&c).is_ok());
}

#[test]
fn a_file_written_with_the_former_percent_keys_still_reads() {
    let old = format!(
        r#"{{"kind": "identify-drives", "stiffness_nm_per_rad": {K}, "std_error_percent": [1, 2, 3, 4, 5, 6], "poorly_determined_above_percent": 10}}"#
    );
    let new = old.replace("_percent", "_pct");
    assert_eq!(parse(&old).unwrap(), parse(&new).unwrap());
    // Any other spelling is still an unknown key.
    let wrong = old.replace("std_error_percent", "std_error_per_cent");
    let e = parse(&wrong).unwrap_err().to_string();
    assert!(e.contains("std_error_per_cent: unknown key"), "{e}");
}

#[test]
fn a_file_with_its_kind_reads_as_one_without_as_written_before() {
    // What `calibrate --stiffness-out` writes names itself (`kind`); older files do not.
    let params = r#"[{"name": "k1", "kind": "drive", "unit": "Nm/rad", "stiffness": 950000},
        {"name": "k2", "kind": "drive", "unit": "Nm/rad", "stiffness": 3000000},
        {"name": "k3", "kind": "drive", "unit": "Nm/rad", "stiffness": 900000},
        {"name": "k4", "kind": "drive", "unit": "Nm/rad", "stiffness": 250000},
        {"name": "k5", "kind": "drive", "unit": "Nm/rad", "stiffness": 200000},
        {"name": "k6", "kind": "drive", "unit": "Nm/rad", "stiffness": 150000}]"#;
    let old = parse(&format!(r#"{{"parameters": {params}}}"#)).unwrap();
    let new = parse(&format!(
        r#"{{"kind": "stiffness", "parameters": {params}}}"#
    ))
    .unwrap();
    assert_eq!((old.kind, new.kind), (None, Some(FileKind::Stiffness)));
    assert_eq!(
        old,
        StiffnessFile {
            kind: None,
            ..new.clone()
        }
    );
    let h = new.compliance(&Model::default()).unwrap().h;
    assert_eq!(h[1], 1.0 / 3_000_000.0);
    // Another document given as the stiffness file is refused naming its kind.
    let plan = format!(r#"{{"kind": "plan", "parameters": {params}}}"#);
    let e = parse(&plan).unwrap_err().to_string();
    assert!(e.contains("plan") && e.contains("identify-springs"), "{e}");
}

#[test]
fn a_positive_diagonal_covariance_passes_and_a_negative_one_is_refused() {
    assert!(check_covariance(&Matrix6::from_diagonal_element(1e-14)).is_ok());
    assert!(check_covariance(&Matrix6::from_diagonal_element(-1e-14)).is_err());
}
