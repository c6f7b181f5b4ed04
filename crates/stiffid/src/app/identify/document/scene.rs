//! The identification's 3D scene ([`stiffid_view`]): the load-test postures in the
//! cell, the rope from the loading point to its anchor, the identified compliance's ellipsoid at
//! the tool centre point under the setup's load, and each measuring point's measured and
//! predicted displacement as the identify document gives them (`residuals`: `measured_mm`,
//! `predicted_mm`). What `identify --report` shows in `report.html` and writes as
//! `identify.glb`, and Python's `stiffid.scene(setup, postures_deg, document=...)`.

use nalgebra::{Vector3, Vector6};
use serde::Deserialize;
use stiffid_core::{Error, Setup};
use stiffid_view::{self as scene, Extras, Scene};

/// One measurement of the document's `residuals`, as the scene reads it.
#[derive(Deserialize)]
struct Measurement {
    posture: String,
    point: usize,
    measured_mm: [f64; 3],
    predicted_mm: [f64; 3],
}

/// The part of an identify document the scene reads.
#[derive(Deserialize)]
struct Read {
    residuals: Vec<Measurement>,
}

/// The scene of the identify document `document` (its JSON text: the drives' or a model's form;
/// [`super::Document`]) whose postures are `postures` (axis angles, rad): one per posture of the
/// document in the order they first appear in its `residuals` (the measurement file's order), or
/// one per measurement (per residual, as arrays give them: each posture is its first
/// measurement's). Each measuring point of a posture carries the displacement of its
/// longest measured displacement (the full load of load steps): measured and predicted, base
/// frame, as `measured_mm` and `predicted_mm` say (m here); a point not measured in a posture
/// has zero. With external axes, `external` gives each posture's values (SI, the cell's order:
/// one list per entry of `postures`, or none: all at zero); the track and the positioner stand
/// there. The ellipsoid is the identified compliance's (the document read as a stiffness
/// file against the setup's model, [`stiffid_core::io::stiffness`]) under the setup's load; a document
/// that does not fit the setup's model has none (a note says why).
///
/// # Errors
/// [`Error::InvalidField`]: `document` not an identification with residuals (the model
/// comparison has none), a measuring point out of the tool's range (`residuals`), `postures`
/// not one per posture of the document; those of [`scene::scene`].
pub fn scene(
    setup: &Setup,
    postures: &[Vector6<f64>],
    external: &[Vec<f64>],
    document: &str,
) -> stiffid_core::Result<Scene> {
    let invalid = |field: &str, message: String| Error::InvalidField {
        field: field.to_string(),
        message,
    };
    let read: Read = serde_json::from_str(document).map_err(|e| {
        invalid(
            "document",
            format!(
                "expected an identify document of the drives or a model, with `residuals` ({e})"
            ),
        )
    })?;
    let mut labels: Vec<&str> = Vec::new();
    for m in &read.residuals {
        if !labels.contains(&m.posture.as_str()) {
            labels.push(&m.posture);
        }
    }
    let (postures, external): (Vec<Vector6<f64>>, Vec<Vec<f64>>) =
        match postures.len() == read.residuals.len() {
            true => {
                let firsts: Vec<usize> = (labels.iter())
                    .map(|l| (read.residuals.iter().position(|m| m.posture == *l)).unwrap_or(0))
                    .collect();
                let e = firsts.iter().filter_map(|&i| external.get(i).cloned());
                (firsts.iter().map(|&i| postures[i]).collect(), e.collect())
            }
            false => (postures.to_vec(), external.to_vec()),
        };
    if labels.len() != postures.len() {
        return Err(invalid(
            "postures",
            format!(
                "{} postures: expected one per posture of the document ({}), in the order they first appear in its residuals, or one per measurement ({})",
                postures.len(),
                labels.len(),
                read.residuals.len()
            ),
        ));
    }
    let points = setup.tool().measuring_points.len();
    let mut measured = vec![vec![Vector3::zeros(); points]; postures.len()];
    let mut predicted = measured.clone();
    for m in &read.residuals {
        if m.point == 0 || m.point > points {
            return Err(invalid(
                "residuals",
                format!(
                    "measuring point {} of posture {}: the tool has {points}",
                    m.point, m.posture
                ),
            ));
        }
        let i = labels.iter().position(|l| *l == m.posture).unwrap_or(0);
        let d = Vector3::from(m.measured_mm) * 1e-3;
        let at = m.point - 1;
        if d.norm() >= measured[i][at].norm() {
            measured[i][at] = d;
            predicted[i][at] = Vector3::from(m.predicted_mm) * 1e-3;
        }
    }
    let compliance = stiffid_core::io::stiffness::parse(document)
        .and_then(|f| f.compliance(setup.model()))
        .map(|c| c.h);
    let extras = Extras {
        compliance: compliance.as_ref().ok(),
        measured: &measured,
        predicted: &predicted,
        rope: true,
        arrow_names: Some(["measured displacement", "displacement the fit predicts"]),
        external: &external,
        ..Extras::default()
    };
    let mut s = scene::scene(setup, &postures, &extras)?;
    if let Err(e) = compliance {
        s.notes.push(format!("no compliance ellipsoid: {e}"));
    }
    Ok(s)
}
