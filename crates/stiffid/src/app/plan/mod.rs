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

use crate::app::document::{group, units};
use crate::app::Warning;
use document::Bodies;
use nalgebra::{Vector3, Vector6};
use serde::Serialize;
use std::collections::BTreeMap;
use stiffid_core::cell::{Checker, Feasibility};
use stiffid_core::observation::stiffness::rope_displacements;
use stiffid_core::{Result, Setup};
use stiffid_design::criteria::{predicted_deviation_pct, ParameterQuality};
use stiffid_design::distinct::{near_pairs, Near};
use stiffid_design::{unidentifiable, Criterion, Evaluation, Evaluator};

/// Most postures a plan takes: each posture's leave-one-out factors the group without it, so the
/// work grows with the square of the count.
pub const MAX_POSTURES: usize = 1000;

/// What the setup's nominal stiffness is needed for here, in [`stiffid_core::Error::MissingField`].
pub(crate) const NEEDED_BY: &str = "the measurement plan (its expected displacements)";

/// The group to plan.
pub struct Request<'a> {
    /// The setup: robot, tool, load and anchor, noise, nominal stiffness, cell, model.
    pub setup: &'a Setup,
    /// The criterion that chose the group (named in the plan).
    pub criterion: Criterion,
    /// The group: axis angles (rad).
    pub postures: &'a [Vector6<f64>],
    /// The predicted deviation rate (%) the group was chosen to reach, if it was: 1e-6 to 1e4 %.
    pub target_pct: Option<f64>,
    /// With external axes: where each posture is read, the axes' values (SI, the cell's order,
    /// within their limits), one list per posture (a station, or a calibration's table angles,
    /// [`crate::app::select::Report::placed`]); the plan writes them for the operator and
    /// works each posture out there: the arm on its carriage (its rope, loading point and
    /// displacements, [`stiffid_core::Robot::frames_at`]), its checks with the boxes the positioner
    /// carries turned ([`Checker::feasibility_at`]), its scene. Empty: every axis at 0.
    pub external: &'a [Vec<f64>],
    /// Also the plan's 3D scene: in [`Outcome::scene`].
    pub scene: bool,
}

/// The plan job's report, which is its document, and, if asked, its scene. It reads as its
/// report.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// What the plan found, SI units; the plan's document (`plan.json`, Python's
    /// `stiffid.plan`).
    pub report: Report,
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

/// What the plan says about one posture: what it asks of the operator, and what it expects.
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[cfg_attr(
    feature = "schema",
    schemars(
        rename = "PlannedPosture",
        description = "What the plan asks of the operator in one posture, and what it expects."
    )
)]
pub struct Posture {
    /// 1-based position in the group.
    pub posture: usize,
    /// Axis angles q1..q6: rad, written in deg.
    #[serde(rename = "q_deg", serialize_with = "units::deg6")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 6]"))]
    pub q: Vector6<f64>,
    /// Where it is read with external axes: each axis's value by its column's name (`e1_mm`,
    /// `e2_deg`, ...: mm for a linear axis, deg for a rotary one), the station or the table's
    /// angles; none when the plan was given none.
    #[serde(flatten)]
    pub columns: BTreeMap<String, f64>,
    /// Unit vector from the loading point to the rope anchor, base frame: no unit, written in plain
    /// numbers.
    #[serde(serialize_with = "units::plain3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub rope_direction: Vector3<f64>,
    /// Distance from the loading point to the anchor: m, written in mm.
    #[serde(rename = "rope_length_mm", serialize_with = "units::mm")]
    pub rope_length: f64,
    /// Height of the loading point (base z): m, written in mm.
    #[serde(rename = "loading_point_z_mm", serialize_with = "units::mm")]
    pub loading_point_z: f64,
    /// Expected displacement `[dx, dy, dz]` of every measuring point under the load with the
    /// nominal stiffness, base frame: m, written in mm.
    #[serde(rename = "displacements_mm", serialize_with = "units::mm3_each")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<[f64; 3]>"))]
    pub displacements: Vec<Vector3<f64>>,
    /// Predicted deviation rate of each joint at noise multiple 1 without this posture, %
    /// (`+infinity` where the rest cannot identify the joint).
    #[serde(flatten, serialize_with = "document::without")]
    #[cfg_attr(feature = "schema", schemars(with = "document::Without"))]
    pub without_pct: [f64; 6],
    /// The posture's checks in the cell.
    #[serde(flatten, serialize_with = "document::checks")]
    #[cfg_attr(feature = "schema", schemars(with = "document::Checks"))]
    pub feasibility: Feasibility,
    /// Where it is read: the external axes' values (SI, the cell's order); empty when not given
    /// ([`Request::external`]).
    #[serde(skip)]
    pub external: Vec<f64>,
}

impl Posture {
    /// The posture's checks in the cell as the plan writes them (its `min_clearance_mm`,
    /// `min_margin_mm`, `min_margin_check` and `failed_checks`).
    pub fn checks(&self) -> document::Checks {
        document::Checks::of(&self.feasibility)
    }

    /// The posture's leave-one-out rates as the plan writes them (its `without_pct` and
    /// `without_worst_pct`, percent, `None` where the rest cannot identify a joint).
    pub fn without(&self) -> document::Without {
        document::Without::of(&self.without_pct)
    }
}

/// A measurement plan: the setup's load and bodies, what the group predicts, and what each
/// posture asks of the operator. It is its own document (`plan.json` of `stiffid select --report
/// DIR`, Python's `stiffid.plan`; its `plan.csv`, [`document::csv`]).
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "plan")]
#[cfg_attr(
    feature = "schema",
    schemars(
        description = "The measurement plan: the setup's load and bodies, what the group predicts, and what each\nposture asks of the operator."
    )
)]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("plan")))]
pub struct Report {
    /// The setup's name.
    pub setup: String,
    /// The robot's name.
    pub robot: String,
    /// The criterion that chose the group: a choice, written in its name (`relative-a`, ...).
    #[serde(serialize_with = "units::name")]
    #[cfg_attr(
        feature = "schema",
        schemars(schema_with = "crate::app::document::criterion")
    )]
    pub criterion: Criterion,
    /// The number of measuring points of the tool.
    pub measuring_points: usize,
    /// The load hung from the loading point, N.
    #[serde(rename = "load_n")]
    pub load: f64,
    /// The rope's anchor (pulley), base frame: m, written in mm.
    #[serde(rename = "anchor_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub anchor: Vector3<f64>,
    /// The load steps of `[loading] steps_n`, rising, N; empty without load steps.
    #[serde(rename = "load_steps_n")]
    pub load_steps: Vec<f64>,
    /// The variance of one displacement coordinate at the rope load, in multiples of the
    /// variance of one reading (docs/model.md, the noise convention and load steps in the
    /// design): 2 without load steps (a loaded minus an unloaded reading).
    pub displacement_variance_multiple: f64,
    /// What the cell's checks and the drawings take the robot's bodies to be; `null` without
    /// `[cell]` or `[tracker]`.
    pub bodies: Option<Bodies>,
    /// The predicted deviation rate (%) the group was chosen to reach; `null` for a group of a
    /// given size.
    pub target_pct: Option<f64>,
    /// The setup's noise levels, multiples of its variance.
    pub noise_levels: Vec<f64>,
    /// The whole group's criteria and predicted deviation rates; written as its predicted mean
    /// deviation rate of each joint at each noise level, percent, `[levels][6]`.
    #[serde(
        rename = "predicted_deviation_pct",
        serialize_with = "document::predicted"
    )]
    #[cfg_attr(
        feature = "schema",
        schemars(
            with = "Vec<[Option<f64>; 6]>",
            description = "Predicted mean deviation rate of each joint at each noise level, percent, `[levels][6]`,\n`100 sqrt(2/pi) sqrt(m) sqrt([(S^T S)^-1]_jj)` (`null` for a joint the group cannot\nidentify)."
        )
    )]
    pub evaluation: Evaluation,
    /// Whether the setup's model has virtual springs beside the drives.
    pub virtual_springs: bool,
    /// Every parameter of the setup's model, drives first: whether the group identifies it and
    /// how well.
    #[serde(serialize_with = "group::parameters")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<group::Parameter>"))]
    pub parameters: Vec<ParameterQuality>,
    /// The combinations of parameters the group cannot separate; empty when it identifies every
    /// parameter.
    pub unidentifiable: Vec<String>,
    /// Each posture, in the order of the group.
    pub postures: Vec<Posture>,
    /// Pairs of postures that are not distinct (axis angles within 2 deg, or the same flange
    /// pose within 10 mm and 2 deg: a wrist flip counts); empty when all are.
    #[serde(rename = "near_postures", serialize_with = "group::near")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<group::NearDoc>"))]
    pub near: Vec<Near>,
    /// A warning per pair of postures that are not distinct ([`Near::warning`]).
    #[serde(skip)]
    pub warnings: Vec<Warning>,
}

/// Plans the group.
///
/// # Errors
/// [`stiffid_core::Error::InvalidField`] (`postures`) for none or more than [`MAX_POSTURES`];
/// external values (field `external`) not one list per posture of values within the axes'
/// limits, or none for a robot with external axes; [`stiffid_core::Error::MissingField`] for a setup without a nominal stiffness; the errors
/// of [`Setup::check_bodies`]; with [`Request::scene`], those of `document::scene`.
pub fn run(request: &Request) -> Result<Outcome> {
    let report = find(request)?;
    let scene = (request.scene)
        .then(|| document::scene(&report, request.setup))
        .transpose()?;
    Ok(Outcome { report, scene })
}

/// What [`run`] finds, before its document.
fn find(request: &Request) -> Result<Report> {
    let (setup, postures) = (request.setup, request.postures);
    setup.require_loading("plan (where the rope pulls)")?;
    stiffid_core::common::limits::check_count("postures", postures.len(), 1, MAX_POSTURES)?;
    if let Some(pct) = request.target_pct {
        let range = &stiffid_core::common::limits::TARGET_PCT;
        stiffid_core::common::limits::check("target_pct", &[pct], range)?;
    }
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
                posture: i + 1,
                q: *q,
                columns: document::columns(setup, e),
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
    let evaluation = evaluator.evaluation(postures);
    let shows_bodies = setup.cell().is_some() || setup.tracker().is_some();
    Ok(Report {
        setup: setup.name().to_string(),
        robot: setup.robot().name().to_string(),
        criterion: request.criterion,
        measuring_points: setup.tool().measuring_points.len(),
        load: setup.load().load,
        anchor: setup.load().anchor,
        load_steps: setup.load_steps().to_vec(),
        displacement_variance_multiple: setup.displacement_variance()
            / setup.noise().reading_variance,
        bodies: shows_bodies.then(|| Bodies::of(setup)),
        target_pct: request.target_pct,
        noise_levels: setup.noise().levels.clone(),
        virtual_springs: !setup.model().is_drives_only(),
        parameters: evaluation.parameters(setup),
        unidentifiable: unidentifiable(&evaluation, setup),
        evaluation,
        postures: planned,
        warnings: near.iter().map(Near::warning).collect(),
        near,
    })
}
