//! A prediction outside the region of the postures the stiffness was identified from is flagged:
//! identify writes the region (each axis' range over the 43 FANUC postures, widened by 5 deg)
//! into its stiffness file, and predict, validate and compensate flag and warn about a posture
//! with an axis beyond it; a posture inside gives no flag, and a stiffness file without the
//! region is read with one warning that nothing is checked.

use nalgebra::Vector6;
use stiffid::app::compensate::document::{header, values};
use stiffid::app::compensate::{self, Input};
use stiffid::app::identify::{self, Options};
use stiffid::app::measurements::Data;
use stiffid::app::{predict, validate};
use stiffid::internal::common::warning::{Warning, WarningKind};
use stiffid::internal::io::stiffness;
use stiffid::internal::machining::compensate::{Compensated, PathPoint};
use stiffid::internal::machining::dynamics::Dynamics;
use stiffid::internal::model::{Compliance, Region};
use stiffid::internal::observation::deflection::Frame;
use stiffid::{Error, Setup};

const DATA: &str = include_str!("../../../../examples/data/fanuc-r2000ic-165f/measurements.csv");

fn fanuc() -> Setup {
    let s = stiffid::internal::setup::builtin("fanuc-r2000ic-165f").unwrap();
    s.to_builder().with_tcp(s.tool().tcp).build().unwrap()
}

/// The stiffness file identify writes from the FANUC data (`identify --out`), as JSON.
fn stiffness_file(setup: &Setup) -> serde_json::Value {
    let request = identify::Request {
        progress: &(),
        setup_name: "setup".into(),
        setup,
        data: Data::File {
            name: "measurements.csv".into(),
            reader: DATA.as_bytes(),
        },
        options: Options::default(),
    };
    let report = identify::run(request).unwrap();
    serde_json::to_value(report.document()).unwrap()
}

fn compliance(setup: &Setup, file: &serde_json::Value) -> Compliance {
    let parsed = stiffness::parse(&file.to_string()).unwrap();
    parsed.compliance(setup.model()).unwrap()
}

/// The first FANUC posture, rad, with axis 2 moved to `q2_deg`.
fn posture(q2_deg: Option<f64>) -> Vector6<f64> {
    let d = f64::to_radians;
    let mut q = Vector6::new(
        d(-59.991000024985645),
        d(-16.692999997970958),
        d(-28.93000002280604),
        d(3.7879999962445363),
        d(-62.929999983955376),
        d(144.91900001732265),
    );
    if let Some(v) = q2_deg {
        q[1] = d(v);
    }
    q
}

fn predicted(setup: &Setup, c: &Compliance, q: Vector6<f64>) -> predict::Report {
    predict::run(&predict::Request {
        setup_name: "setup".into(),
        setup,
        q,
        wrench: Vector6::new(0.0, 0.0, -1000.0, 0.0, 0.0, 0.0),
        frame: Frame::Base,
        at: None,
        compliance: Some(c.clone()),
        level: None,
    })
    .unwrap()
    .report
}

fn extrapolation(warnings: &[Warning]) -> Vec<&str> {
    (warnings.iter())
        .filter(|w| w.kind == WarningKind::Extrapolation)
        .map(|w| w.message.as_str())
        .collect()
}

#[test]
fn identify_writes_the_region_of_its_postures_and_reads_it_back() {
    let setup = fanuc();
    let file = stiffness_file(&setup);
    let region = &file["region"];
    assert_eq!(region["postures"], 43);
    assert_eq!(region["margin_deg"], 5.0);
    // The data's range of axis 2 (its README's table of the 43 postures).
    let lower = region["lower_deg"][1].as_f64().unwrap();
    let upper = region["upper_deg"][1].as_f64().unwrap();
    assert!((lower - -52.028).abs() < 1e-3 && (upper - 38.503).abs() < 1e-3);
    let Region::Postures(r) = compliance(&setup, &file).region else {
        panic!("no region read back");
    };
    assert_eq!(r.postures, 43);
    assert!((r.range.upper[1].to_degrees() - upper).abs() < 1e-9);
    assert!((r.margin.to_degrees() - 5.0).abs() < 1e-12);
}

#[test]
fn predict_flags_a_posture_with_one_axis_beyond_the_identification_range() {
    let setup = fanuc();
    let c = compliance(&setup, &stiffness_file(&setup));
    // A measured posture, and one 4 deg beyond axis 2's largest angle (within the margin).
    for q2 in [None, Some(38.503 + 4.0)] {
        let inside = predicted(&setup, &c, posture(q2));
        assert_eq!(inside.outside_region, Some(vec![]));
        assert!(extrapolation(&inside.warnings).is_empty());
        let doc = serde_json::to_value(&inside).unwrap();
        assert_eq!(doc["extrapolates"], false);
        assert_eq!(doc["outside_region"], serde_json::json!([]));
    }
    // 10 deg beyond: flagged, warned about, in the document with the axis and its range.
    let outside = predicted(&setup, &c, posture(Some(48.5)));
    let axes = outside.outside_region.clone().unwrap();
    assert_eq!(axes.len(), 1);
    assert_eq!(axes[0].axis, 1);
    let warnings = extrapolation(&outside.warnings);
    assert_eq!(warnings.len(), 1);
    assert!(
        warnings[0].starts_with("the posture lies outside the region the stiffness was identified from (each axis' range over its 43 postures, widened by 5.0 deg)"),
        "{}",
        warnings[0]
    );
    assert!(
        warnings[0].contains("axis 2 at 48.50 deg (identified over -52.03 .. 38.50)"),
        "{}",
        warnings[0]
    );
    let doc = serde_json::to_value(&outside).unwrap();
    assert_eq!(doc["extrapolates"], true);
    assert_eq!(doc["outside_region"][0]["axis"], 2);
    assert!((doc["outside_region"][0]["q_deg"].as_f64().unwrap() - 48.5).abs() < 1e-9);
    assert!(
        (doc["outside_region"][0]["identified_deg"][1]
            .as_f64()
            .unwrap()
            - 38.503)
            .abs()
            < 1e-3
    );
    assert_eq!(doc["region"]["postures"], 43);
    // The nominal stiffness is not identified from postures: nothing to check, nothing said.
    let nominal = predict::run(&predict::Request {
        setup_name: "setup".into(),
        setup: &setup,
        q: posture(Some(48.5)),
        wrench: Vector6::new(0.0, 0.0, -1000.0, 0.0, 0.0, 0.0),
        frame: Frame::Base,
        at: None,
        compliance: None,
        level: None,
    })
    .unwrap();
    assert_eq!(nominal.outside_region, None);
    assert!(extrapolation(&nominal.warnings).is_empty());
}

#[test]
fn a_stiffness_file_without_its_region_is_read_and_said_once_unchecked() {
    let setup = fanuc();
    let mut file = stiffness_file(&setup);
    file.as_object_mut().unwrap().remove("region");
    let c = compliance(&setup, &file);
    assert_eq!(c.region, Region::Unrecorded);
    let report = predicted(&setup, &c, posture(Some(48.5)));
    assert_eq!(report.outside_region, None);
    let warnings = extrapolation(&report.warnings);
    assert_eq!(warnings.len(), 1);
    assert!(
        warnings[0].contains("does not record the postures"),
        "{}",
        warnings[0]
    );
    let doc = serde_json::to_value(&report).unwrap();
    assert_eq!(doc["extrapolates"], serde_json::Value::Null);
    // Validation over 43 postures says it once too.
    let v = validated(&setup, &c, DATA);
    assert_eq!(extrapolation(&v.warnings).len(), 1);
}

/// A stiffness file saved with a byte-order mark (as editors on Windows write) reads as without
/// it, region included (it was refused as "line 1, column 1: expected value").
#[test]
fn a_stiffness_file_with_a_byte_order_mark_reads_as_without_it() {
    let text = include_str!("../../../../examples/milling/stiffness.json");
    let plain = stiffness::parse(text).unwrap();
    let marked = stiffness::parse(&format!("\u{feff}{text}")).unwrap();
    assert_eq!(format!("{marked:?}"), format!("{plain:?}"));
    assert!(stiffness::parse(&format!(" \u{feff}{text}")).is_err());
}

#[test]
fn a_region_out_of_shape_is_refused_naming_the_field() {
    let setup = fanuc();
    let mut file = stiffness_file(&setup);
    file["region"]["margin_deg"] = serde_json::json!(-1.0);
    match stiffness::parse(&file.to_string()) {
        Err(Error::InvalidField { field, message }) => {
            assert_eq!(field, "region.margin_deg");
            assert!(
                message.contains("expected within [0, 360] deg"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    let mut file = stiffness_file(&setup);
    file["region"]["lower_deg"][2] = serde_json::json!(50.0);
    match stiffness::parse(&file.to_string()) {
        Err(Error::InvalidField { field, .. }) => {
            assert_eq!(field, "region.lower_deg[3], region.upper_deg[3]")
        }
        other => panic!("{other:?}"),
    }
    // An angle's documented range, -10 000 to 10 000 deg, holds at its edges.
    let mut file = stiffness_file(&setup);
    file["region"]["upper_deg"][4] = serde_json::json!(1e308);
    match stiffness::parse(&file.to_string()) {
        Err(Error::InvalidField { field, message }) => {
            assert_eq!(field, "region.upper_deg[5]");
            assert_eq!(message, "1e308 is outside [-10000, 10000] deg");
        }
        other => panic!("{other:?}"),
    }
    let mut file = stiffness_file(&setup);
    file["region"]["upper_deg"][4] = serde_json::json!(10000.0);
    file["region"]["lower_deg"][0] = serde_json::json!(-10000.0);
    assert!(stiffness::parse(&file.to_string()).is_ok());
    file["region"]["lower_deg"][0] = serde_json::json!(-10000.5);
    assert!(stiffness::parse(&file.to_string()).is_err());
}

fn validated(setup: &Setup, c: &Compliance, text: &str) -> validate::Report {
    validate::run(validate::Request {
        setup_name: "setup".into(),
        setup,
        compliance: c,
        data: Data::File {
            name: "data.csv".into(),
            reader: text.as_bytes(),
        },
        level: None,
    })
    .unwrap()
    .report
}

#[test]
fn validate_flags_each_posture_beyond_the_identification_range() {
    let setup = fanuc();
    let c = compliance(&setup, &stiffness_file(&setup));
    let inside = validated(&setup, &c, DATA);
    assert!(extrapolation(&inside.warnings).is_empty());
    let doc = inside.document();
    assert_eq!(doc.extrapolated_postures, Some(0));
    assert!(doc.checks.iter().all(|c| c.extrapolates == Some(false)));
    // Posture 2's axis 2 moved to 60 deg (its one measurement), the others as measured.
    let moved = DATA.replace(
        "2,1,-61.110999989328384,-12.853000013817956,",
        "2,1,-61.110999989328384,60,",
    );
    assert_ne!(moved, DATA);
    let outside = validated(&setup, &c, &moved);
    let doc = outside.document();
    assert_eq!(doc.extrapolated_postures, Some(1));
    let flagged: Vec<&str> = (doc.checks.iter())
        .filter(|c| c.extrapolates == Some(true))
        .map(|c| c.posture)
        .collect();
    assert_eq!(flagged, ["2"]);
    let warnings = extrapolation(&outside.warnings);
    assert_eq!(warnings.len(), 1);
    assert!(
        warnings[0].starts_with("1 of 43 postures lies outside the region"),
        "{}",
        warnings[0]
    );
    assert!(
        warnings[0].contains("posture 2: axis 2 at 60.00 deg (identified over -52.03 .. 38.50)"),
        "{}",
        warnings[0]
    );
}

#[test]
fn compensate_flags_each_path_point_beyond_the_identification_range() {
    let setup = fanuc();
    let c = compliance(&setup, &stiffness_file(&setup));
    let mut text = String::from("q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n\n");
    for q2 in [None, Some(20.0), Some(48.5)] {
        let deg: Vec<String> = (posture(q2).iter())
            .map(|a| a.to_degrees().to_string())
            .collect();
        text += &format!("{},0,0,-500\n", deg.join(","));
    }
    let request = compensate::Request {
        names: Default::default(),
        setup: &setup,
        options: stiffid::internal::machining::compensate::Options::for_setup(&setup),
        compliance: c,
        input: Input::Path {
            name: "path.csv".into(),
            text: &text,
            frame: Frame::Base,
        },
    };
    let mut rows = Vec::new();
    let report = compensate::run(
        request,
        |first, p: &[PathPoint], r: &[Compensated], d: &[Dynamics]| {
            for (k, ((p, r), d)) in p.iter().zip(r).zip(d).enumerate() {
                rows.push(values(first + k, p.line, r, d));
            }
            Ok::<(), Error>(())
        },
    )
    .unwrap();
    let column = header().iter().position(|h| h == "extrapolates").unwrap();
    let flags: Vec<Option<f64>> = rows.iter().map(|v| v[column]).collect();
    assert_eq!(flags, [Some(0.0), Some(0.0), Some(1.0)]);
    let warnings = extrapolation(&report.warnings);
    assert_eq!(warnings.len(), 1);
    assert!(
        warnings[0].starts_with("1 of 3 path points lies outside the region"),
        "{}",
        warnings[0]
    );
    assert!(
        warnings[0].contains("line 4: axis 2 at 48.50 deg"),
        "{}",
        warnings[0]
    );
    let doc = report.document();
    assert_eq!(doc.summary.extrapolated, Some(1));
    assert_eq!(doc.region.map(|r| r.postures), Some(43));
}

/// A fold's scores are three per held-out measurement (x, y, z): identify's own file reads,
/// and the same file with one score more, or one less, in a fold is refused naming the fold.
#[test]
fn a_fold_with_a_score_more_or_less_is_refused_naming_it() {
    let setup = fanuc();
    let request = identify::Request {
        progress: &(),
        setup_name: "setup".into(),
        setup: &setup,
        data: Data::File {
            name: "measurements.csv".into(),
            reader: DATA.as_bytes(),
        },
        options: Options {
            folds: Some(4),
            ..Options::default()
        },
    };
    let report = identify::run(request).unwrap();
    let file = serde_json::to_value(report.document()).unwrap();
    assert!(stiffness::parse(&file.to_string()).is_ok());
    let scores = file["prediction"]["folds"][1]["scores"]
        .as_array()
        .unwrap()
        .clone();
    assert_eq!(scores.len() % 3, 0);
    let (mut more, mut less) = (file.clone(), file.clone());
    more["prediction"]["folds"][1]["scores"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!(0.5));
    less["prediction"]["folds"][1]["scores"]
        .as_array_mut()
        .unwrap()
        .pop();
    for bad in [more, less] {
        match stiffness::parse(&bad.to_string()) {
            Err(Error::InvalidField { field, message }) => {
                assert_eq!(field, "prediction.folds[2].scores");
                assert!(
                    message.contains("expected three per measurement"),
                    "{message}"
                );
            }
            other => panic!("{other:?}"),
        }
    }
}

/// identify's stiffness file of the FANUC data, computed once for the property test.
fn shared_file() -> &'static serde_json::Value {
    static FILE: std::sync::OnceLock<serde_json::Value> = std::sync::OnceLock::new();
    FILE.get_or_init(|| stiffness_file(&fanuc()))
}

/// A hostile number for a region's field: huge, tiny, negative, the edges and just past them.
fn hostile() -> impl proptest::strategy::Strategy<Value = f64> {
    use proptest::prelude::*;
    prop_oneof![
        -2e4..2e4f64,
        prop::sample::select(vec![
            1e308, -1e308, 1e4, -1e4, 10000.5, 360.0, 360.5, -0.0, 5e-324
        ]),
        any::<f64>(),
    ]
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig {
        // A fixed seed: every run tries the same cases (set another to explore).
        rng_seed: proptest::test_runner::RngSeed::Fixed(20_211_126),
        ..proptest::prelude::ProptestConfig::with_cases(64)
    })]
    /// A region with any of its numbers mutated is either refused or read within its documented
    /// ranges: angles within [-10 000, 10 000] deg, each lower at most its upper, the margin
    /// within [0, 360] deg.
    #[test]
    fn a_mutated_region_never_reads_outside_its_ranges(
        axis in 0usize..6,
        lower in hostile(),
        upper in hostile(),
        margin in hostile(),
    ) {
        let mut file = shared_file().clone();
        file["region"]["lower_deg"][axis] = serde_json::json!(lower);
        file["region"]["upper_deg"][axis] = serde_json::json!(upper);
        file["region"]["margin_deg"] = serde_json::json!(margin);
        if let Ok(parsed) = stiffness::parse(&file.to_string()) {
            let Some(r) = parsed.region.as_ref() else { panic!("the region was dropped") };
            for (lo, hi) in r.lower_deg.iter().zip(&r.upper_deg) {
                proptest::prop_assert!(lo.abs() <= 1e4 && hi.abs() <= 1e4 && lo <= hi, "{lo} {hi}");
            }
            proptest::prop_assert!((0.0..=360.0).contains(&r.margin_deg), "{}", r.margin_deg);
        }
    }
}
