#[test]
fn csv_text_quotes_only_the_fields_that_need_it_and_reads_back() {
    let header = ["name".to_string(), "checks".to_string()];
    let rows = [
        vec!["a,b".to_string(), "floor; \"rope\" blocked".to_string()],
        vec!["plain".to_string(), String::new()],
    ];
    let text = stiffid::app::document::csv_text(&header, rows.clone());
    assert_eq!(
        text,
        "name,checks\n\"a,b\",\"floor; \"\"rope\"\" blocked\"\nplain,\n"
    );
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let back: Vec<Vec<String>> = reader
        .records()
        .map(|r| r.unwrap().iter().map(String::from).collect())
        .collect();
    assert_eq!(back, rows);
}

/// A report's fields in SI through every unit adapter (`app::document::units`).
#[derive(serde::Serialize)]
struct Adapted {
    #[serde(serialize_with = "units::mm")]
    length: f64,
    #[serde(serialize_with = "units::mm_finite")]
    unbounded: f64,
    #[serde(serialize_with = "units::mm_option")]
    maybe: Option<f64>,
    #[serde(serialize_with = "units::mm3")]
    offset: Vector3<f64>,
    #[serde(serialize_with = "units::mm3_option")]
    none: Option<Vector3<f64>>,
    #[serde(serialize_with = "units::mm3_each")]
    points: Vec<Vector3<f64>>,
    #[serde(serialize_with = "units::deg")]
    angle: f64,
    #[serde(serialize_with = "units::mrad")]
    small: f64,
    #[serde(serialize_with = "units::deg6")]
    q: Vector6<f64>,
    #[serde(serialize_with = "units::deg6_each")]
    postures: Vec<Vector6<f64>>,
    #[serde(serialize_with = "units::interval_mm")]
    interval: Option<[[f64; 2]; 3]>,
}

use nalgebra::{Vector3, Vector6};
use stiffid::app::document::units;

#[test]
fn the_unit_adapters_write_si_fields_in_the_documents_units() {
    use std::f64::consts::PI;
    let adapted = Adapted {
        length: 0.25,
        unbounded: f64::INFINITY,
        maybe: Some(-1.5),
        offset: Vector3::new(0.5, 0.0, -0.125),
        none: None,
        points: vec![Vector3::new(1.0, 2.0, 0.75)],
        angle: PI,
        small: 0.002,
        q: Vector6::new(PI, PI / 2.0, -PI / 4.0, 0.0, 2.0 * PI, -PI),
        postures: vec![Vector6::new(0.0, PI, 0.0, -PI / 2.0, 0.0, PI / 4.0)],
        interval: Some([
            [-0.001, 0.002],
            [f64::NEG_INFINITY, 0.5],
            [0.0, f64::INFINITY],
        ]),
    };
    let json = serde_json::to_value(&adapted).unwrap();
    let expected = serde_json::json!({
        "length": 250.0,
        "unbounded": null,
        "maybe": -1500.0,
        "offset": [500.0, 0.0, -125.0],
        "none": null,
        "points": [[1000.0, 2000.0, 750.0]],
        "angle": 180.0,
        "small": 2.0,
        "q": [180.0, 90.0, -45.0, 0.0, 360.0, -180.0],
        "postures": [[0.0, 180.0, 0.0, -90.0, 0.0, 45.0]],
        "interval": [[-1.0, 2.0], [null, 500.0], [0.0, null]],
    });
    assert_eq!(json, expected);
}
