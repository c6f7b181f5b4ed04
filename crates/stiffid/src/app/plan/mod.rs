//! The plan job: what the operator needs to carry a group of postures out in their cell (the
//! measurement plan of `stiffid select --report`, Python's `stiffid.plan`). For each posture: the
//! rope's direction and length from the loading point to the anchor, the height of the loading
//! point, the expected displacement of every measuring point under the load with the nominal
//! stiffness (Eq. 3-7), the cell's checks, and each joint's predicted deviation rate if that
//! posture could not be measured (leave-one-out, Eq. 19); for the group, its predicted deviation
//! rates at the setup's noise levels, how well it identifies every parameter of the model, and
//! the pairs of postures that are not distinct ([`stiffid_design::distinct`], by its default
//! distances), each with a warning.

pub mod document;

use crate::app::Warning;
use nalgebra::{Vector3, Vector6};
use stiffid_core::cell::{Checker, Feasibility};
use stiffid_core::observation::stiffness::rope_displacements;
use stiffid_core::{Result, Setup};
use stiffid_design::criteria::predicted_deviation_pct;
use stiffid_design::distinct::{near_pairs, Near};
use stiffid_design::{Criterion, Evaluation, Evaluator};

/// Most postures a plan takes: each posture's leave-one-out factors the group without it, so the
/// work grows with the square of the count.
pub const MAX_POSTURES: usize = 1000;

/// What the setup's nominal stiffness is needed for here, in [`stiffid_core::Error::MissingField`].
pub const NEEDED_BY: &str = "the measurement plan (its expected displacements)";

/// The group to plan.
pub struct Request<'a> {
    /// The setup: robot, tool, load and anchor, noise, nominal stiffness, cell, model.
    pub setup: &'a Setup,
    /// The criterion that chose the group (named in the plan).
    pub criterion: Criterion,
    /// The group: axis angles (rad).
    pub postures: &'a [Vector6<f64>],
    /// The predicted deviation rate (%) the group was chosen to reach, if it was.
    pub target_pct: Option<f64>,
    /// With external axes: where each posture is read, the axes' values (SI, the cell's order,
    /// within their limits), one list per posture (a station, or a calibration's table angles,
    /// [`crate::app::select::Report::placed`]); the plan writes them for the operator and
    /// works each posture out there: the arm on its carriage (its rope, loading point and
    /// displacements, [`stiffid_core::Robot::frames_at`]), its checks with the boxes the positioner
    /// carries turned ([`Checker::feasibility_at`]), its scene. Empty: every axis at 0.
    pub external: &'a [Vec<f64>],
    /// Also the plan's 3D scene ([`document::scene`]): in [`Outcome::scene`].
    pub scene: bool,
}

/// The plan job's report, its document and, if asked, its scene. It reads as its report.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// What the plan found, SI units.
    pub report: Report,
    /// The plan's document (`plan.json`, Python's `stiffid.plan`).
    pub document: document::Document,
    /// With [`Request::scene`]: the plan's 3D scene (`plan.html`, `plan.glb`, Python's
    /// `stiffid.scene`).
    pub scene: Option<stiffid_view::Scene>,
}

impl std::ops::Deref for Outcome {
    type Target = Report;

    fn deref(&self) -> &Report {
        &self.report
    }
}

/// What the plan says about one posture.
#[derive(Debug, Clone)]
pub struct Posture {
    /// Axis angles, rad.
    pub q: Vector6<f64>,
    /// Unit vector from the loading point to the rope anchor, base frame.
    pub rope_direction: Vector3<f64>,
    /// Distance from the loading point to the anchor, m.
    pub rope_length: f64,
    /// Height of the loading point (base z), m.
    pub loading_point_z: f64,
    /// Displacement of every measuring point under the load with the nominal stiffness, m, base
    /// frame.
    pub displacements: Vec<Vector3<f64>>,
    /// Predicted deviation rate of each joint at noise multiple 1 without this posture, %.
    pub without_pct: [f64; 6],
    /// The posture's checks in the cell.
    pub feasibility: Feasibility,
    /// Where it is read: the external axes' values (SI, the cell's order); empty when not given
    /// ([`Request::external`]).
    pub external: Vec<f64>,
}

/// A measurement plan.
#[derive(Debug, Clone)]
pub struct Report {
    /// The criterion that chose the group.
    pub criterion: Criterion,
    /// Each posture, in the order of the group.
    pub postures: Vec<Posture>,
    /// The whole group's criteria and predicted deviation rates.
    pub evaluation: Evaluation,
    /// The predicted deviation rate (%) the group was chosen to reach, if it was.
    pub target_pct: Option<f64>,
    /// The pairs of postures that are not distinct.
    pub near: Vec<Near>,
    /// A warning per pair of postures that are not distinct ([`Near::warning`]).
    pub warnings: Vec<Warning>,
}

/// Plans the group.
///
/// # Errors
/// [`stiffid_core::Error::InvalidField`] (`postures`) for none or more than [`MAX_POSTURES`];
/// external values (field `external`) not one list per posture of values within the axes'
/// limits, or none for a robot with external axes; [`stiffid_core::Error::MissingField`] for a setup without a nominal stiffness; the errors
/// of [`Setup::check_bodies`]; with [`Request::scene`], those of [`document::scene`].
pub fn run(request: &Request) -> Result<Outcome> {
    let report = find(request)?;
    let document = document::Document::new(&report, request.setup);
    let scene = (request.scene)
        .then(|| document::scene(&report, request.setup))
        .transpose()?;
    Ok(Outcome {
        report,
        document,
        scene,
    })
}

/// What [`run`] finds, before its document.
fn find(request: &Request) -> Result<Report> {
    let (setup, postures) = (request.setup, request.postures);
    setup.require_loading("plan (where the rope pulls)")?;
    stiffid_core::common::limits::check_count("postures", postures.len(), 1, MAX_POSTURES)?;
    stiffid_view::check_external(setup, postures.len(), request.external)?;
    if let (Some(axes), true) = (setup.robot().external(), request.external.is_empty()) {
        return Err(stiffid_core::Error::InvalidField {
            field: "external".into(),
            message: format!(
                "none given: the robot has external axes ({}): give where each posture is read, one row per posture (the postures file's columns), as the kinematics needs them",
                axes.column_names().join(", ")
            ),
        });
    }
    let k = setup.try_nominal_stiffness(NEEDED_BY)?;
    setup.check_bodies()?;
    let evaluator = Evaluator::new(setup);
    let checker = Checker::new(setup);
    let without_each = evaluator.relative_std_without_each(postures);
    let planned = postures
        .iter()
        .zip(&without_each)
        .enumerate()
        .map(|(i, (q, without))| {
            let e = request.external.get(i).map_or(&[][..], Vec::as_slice);
            let frames = match e.is_empty() {
                true => setup.robot().frames(q),
                false => setup.robot().frames_at(q, e),
            };
            let lp = frames.point(&setup.tool().loading_point);
            let rope = setup.load().anchor - lp;
            Posture {
                q: *q,
                rope_direction: rope.normalize(),
                rope_length: rope.norm(),
                loading_point_z: lp.z,
                displacements: rope_displacements(setup, &frames, k),
                without_pct: predicted_deviation_pct(without, 1.0),
                feasibility: checker.feasibility_at(q, e),
                external: e.to_vec(),
            }
        })
        .collect();
    let near = near_pairs(setup.robot(), postures);
    Ok(Report {
        criterion: request.criterion,
        postures: planned,
        evaluation: evaluator.evaluation(postures),
        target_pct: request.target_pct,
        warnings: near.iter().map(Near::warning).collect(),
        near,
    })
}
