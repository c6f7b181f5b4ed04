//! The calibration's 3D scene ([`stiffid_view`]), drawn from its document: the
//! robot at each fitted posture (`postures`: axis angles and, with external axes, the track and
//! the positioner at the posture's values) with each measuring point's error before the
//! calibration (as `measured`) and after it (as `predicted`), base frame, as the document's
//! `errors` of the set `fitted` give them. What `calibrate --report` shows in `report.html`
//! and writes as `errors.glb`, and Python's `stiffid.scene(setup, document=...)`.

use nalgebra::Vector3;
use serde::Deserialize;
use stiffid_core::{Error, Setup};
use stiffid_view::{self as scene, stance, Extras, Scene};

/// One reading's errors of the document's `errors`, as the scene reads them.
#[derive(Deserialize)]
struct Reading {
    set: String,
    posture: String,
    point: usize,
    /// `T1`, `T2`, ... for a reflector on the positioner's table, which has no arrow.
    #[serde(default)]
    point_name: String,
    before_mm: [f64; 3],
    after_mm: [f64; 3],
}

/// The part of a calibrate document the scene reads.
#[derive(Deserialize)]
struct Read {
    postures: Vec<stance::Stance>,
    errors: Vec<Reading>,
}

/// The scene of the calibrate document `document` (its JSON text, [`super::document::Document`])
/// on `setup`: the document's postures (at most [`scene::MAX_POSTURES`], a note says how many
/// of the fitted ones) at their external values; a point without a fitted reading in a posture
/// has no error drawn (zero).
///
/// # Errors
/// [`Error::InvalidField`]: `document` not a calibration with `postures` and `errors`, a
/// measuring point out of the tool's range (`errors`), a posture without the cell's external
/// values (`postures`); those of [`scene::scene`].
pub fn scene(setup: &Setup, document: &str) -> stiffid_core::Result<Scene> {
    let invalid = |field: &str, message: String| Error::InvalidField {
        field: field.to_string(),
        message,
    };
    let read: Read = serde_json::from_str(document).map_err(|e| {
        invalid(
            "document",
            format!("expected a calibrate document, with `postures` and `errors` ({e})"),
        )
    })?;
    let (postures, external) = stance::postures(setup.robot(), &read.postures, "postures")?;
    let points = setup.tool().measuring_points.len();
    let mut before = vec![vec![Vector3::zeros(); points]; postures.len()];
    let mut after = before.clone();
    let mut fitted: Vec<&str> = Vec::new();
    let tool = |r: &&Reading| r.set == "fitted" && !r.point_name.starts_with('T');
    for r in read.errors.iter().filter(tool) {
        if !fitted.contains(&r.posture.as_str()) {
            fitted.push(&r.posture);
        }
        if r.point == 0 || r.point > points {
            return Err(invalid(
                "errors",
                format!(
                    "measuring point {} of posture {}: the tool has {points}",
                    r.point,
                    stiffid_core::common::limits::short(&r.posture)
                ),
            ));
        }
        if let Some(i) = read.postures.iter().position(|p| p.label == r.posture) {
            before[i][r.point - 1] = Vector3::from(r.before_mm) * 1e-3;
            after[i][r.point - 1] = Vector3::from(r.after_mm) * 1e-3;
        }
    }
    let extras = Extras {
        measured: &before,
        predicted: &after,
        arrow_names: Some(["error before calibration", "error after calibration"]),
        external: &external,
        ..Extras::default()
    };
    let mut s = scene::scene(setup, &postures, &extras)?;
    if postures.len() < fitted.len() {
        s.notes.push(format!(
            "the first {} of {} postures are drawn",
            postures.len(),
            fitted.len()
        ));
    }
    Ok(s)
}
