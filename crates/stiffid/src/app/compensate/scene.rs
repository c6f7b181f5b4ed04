//! The compensation's 3D scene ([`stiffid_view`]), drawn from its document's
//! `summary.scene`: the robot at the path's first point and at its largest deflection (nominal
//! axis angles; with external axes, the track and the positioner at the point's values), and
//! the sampled path over the part coloured by its predicted error. What `compensate --report`
//! shows in `report.html` and writes as `scene.glb`, and Python's `stiffid.scene(setup,
//! document=...)`.

use nalgebra::Vector6;
use serde::{Deserialize, Serialize};
use stiffid_core::robot::external::{ExternalAxes, ExternalValues};
use stiffid_core::{Error, Setup};
use stiffid_machining::compensate::Compensated;
use stiffid_view::{self as scene, stance, Extras, PathPoint, Scene};

/// What the compensation's scene draws, as its document records it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ScenePart {
    /// The postures drawn: the path's first point's, then the largest deflection's (none for an
    /// empty path), nominal axis angles.
    pub postures: Vec<stance::Stance>,
    /// What the path's error is, in words.
    pub path_error: String,
    /// The sampled path points (every k-th, at most 20 001, the summary's sample): the TCP
    /// `x, y, z` (base frame, mm) and the error (mm) the words name.
    pub path_mm: Vec<[f64; 4]>,
}

/// The part of a compensate document the scene reads.
#[derive(Deserialize)]
struct Read {
    summary: ReadSummary,
}

#[derive(Deserialize)]
struct ReadSummary {
    scene: ScenePart,
}

impl ScenePart {
    /// The scene's part of a path's summary: `sample` its sampled points, `remaining` whether
    /// they carry a covariance, `postures` the drawn postures (label, nominal axis angles,
    /// external values, SI), the external values at the edges' units of `axes`. Each sampled TCP
    /// position carries the error predicted to remain after compensation, the standard
    /// deviation of `|d|`; without a covariance, the deflection `|d|` compensated.
    pub fn new(
        sample: &[(usize, Compensated)],
        remaining: bool,
        postures: Vec<(String, &Vector6<f64>, &ExternalValues)>,
        axes: Option<&ExternalAxes>,
    ) -> Self {
        let error = |c: &Compensated| match remaining {
            true => c.translation_norm_std.unwrap_or(0.0),
            false => c.deflection.fixed_rows::<3>(0).norm(),
        };
        let path_mm = (sample.iter())
            .map(|(_, c)| {
                let p = c.pose.translation.vector * 1e3;
                [p.x, p.y, p.z, error(c) * 1e3]
            })
            .collect();
        let path_error = match remaining {
            true => "error remaining after compensation (std of |d|)",
            false => "deflection compensated |d| (no covariance: no remaining error)",
        };
        let postures = (postures.into_iter())
            .map(|(label, q, e)| stance::Stance::new(axes, label, q, e))
            .collect();
        ScenePart {
            postures,
            path_error: path_error.to_string(),
            path_mm,
        }
    }
}

/// The scene of a compensate document's `summary.scene` on `setup`; `None` for an empty path.
///
/// # Errors
/// Those of [`stance::postures`] (field `summary.scene.postures`) and [`scene::scene`].
pub fn scene(setup: &Setup, part: &ScenePart) -> stiffid_core::Result<Option<Scene>> {
    if part.postures.is_empty() {
        return Ok(None);
    }
    let field = "summary.scene.postures";
    let (postures, external) = stance::postures(setup.robot(), &part.postures, field)?;
    let path: Vec<PathPoint> = (part.path_mm.iter())
        .map(|p| PathPoint {
            at_m: [p[0] * 1e-3, p[1] * 1e-3, p[2] * 1e-3],
            error_m: p[3] * 1e-3,
        })
        .collect();
    let extras = Extras {
        path: &path,
        path_error: &part.path_error,
        external: &external,
        ..Extras::default()
    };
    scene::scene(setup, &postures, &extras).map(Some)
}

/// The scene of the compensate document `document` (its JSON text) on `setup` ([`scene()`]).
///
/// # Errors
/// [`Error::InvalidField`] (`document`) when it is not a compensate document with
/// `summary.scene`; those of [`scene()`].
pub fn of_document(setup: &Setup, document: &str) -> stiffid_core::Result<Option<Scene>> {
    let read: Read = serde_json::from_str(document).map_err(|e| Error::InvalidField {
        field: "document".into(),
        message: format!("expected a compensate document, with `summary.scene` ({e})"),
    })?;
    scene(setup, &read.summary.scene)
}
