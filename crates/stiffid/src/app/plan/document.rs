//! The document of the plan job ([`crate::app::plan`]): `plan.json` of `stiffid select --report
//! DIR` (which renders `plan.html` from it) and its `plan.csv` ([`Document::csv`]), Python's
//! `stiffid.plan`.

use crate::app::document::feasibility::describe;
use crate::app::document::group::{parameters, NearDoc, Parameter};
use crate::app::document::{csv_text, finite, finite_each, mm};
use crate::app::plan::{Posture, Report};
use serde::Serialize;
use std::collections::BTreeMap;
use stiffid_core::Setup;
use stiffid_design::unidentifiable;
use stiffid_view as scene;

/// The measurement plan: the setup's load and bodies, what the group predicts, and what each
/// posture asks of the operator.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "plan")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("plan")))]
pub struct Document {
    /// The setup's name.
    pub setup: String,
    /// The robot's name.
    pub robot: String,
    /// The criterion that chose the group (`relative-a`, ...).
    #[cfg_attr(
        feature = "schema",
        schemars(schema_with = "crate::app::document::criterion")
    )]
    pub criterion: &'static str,
    /// The number of measuring points of the tool.
    pub measuring_points: usize,
    /// The load hung from the loading point, N.
    pub load_n: f64,
    /// The rope's anchor (pulley), base frame, mm.
    pub anchor_mm: [f64; 3],
    /// The load steps of `[loading] steps_n`, rising, N; empty without load steps.
    pub load_steps_n: Vec<f64>,
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
    /// Predicted mean deviation rate of each joint at each noise level, percent, `[levels][6]`,
    /// `100 sqrt(2/pi) sqrt(m) sqrt([(S^T S)^-1]_jj)` (`null` for a joint the group cannot
    /// identify).
    pub predicted_deviation_pct: Vec<[Option<f64>; 6]>,
    /// Whether the setup's model has virtual springs beside the drives.
    pub virtual_springs: bool,
    /// Every parameter of the setup's model, drives first: whether the group identifies it and
    /// how well.
    pub parameters: Vec<Parameter>,
    /// The combinations of parameters the group cannot separate; empty when it identifies every
    /// parameter.
    pub unidentifiable: Vec<String>,
    /// Each posture, in the order of the group.
    pub postures: Vec<PlannedPosture>,
    /// Pairs of postures that are not distinct (axis angles within 2 deg, or the same flange
    /// pose within 10 mm and 2 deg: a wrist flip counts); empty when all are.
    pub near_postures: Vec<NearDoc>,
}

/// The robot's bodies in the cell's checks and the drawings.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Bodies {
    /// The number of the robot's own collision shapes (its URDF's, meshes as convex hulls);
    /// `null` when capsules stand for the links.
    pub collision_shapes: Option<usize>,
    /// The capsules' radii for the base and links 1-6, mm; `null` with collision shapes.
    pub link_radii_mm: Option<[f64; 7]>,
    /// The radius of the tool's capsule, mm.
    pub tool_radius_mm: f64,
}

/// What the plan asks of the operator in one posture, and what it expects.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct PlannedPosture {
    /// 1-based position in the group.
    pub posture: usize,
    /// Axis angles q1..q6, deg.
    pub q_deg: [f64; 6],
    /// Where it is read with external axes: each axis's value by its column's name (`e1_mm`,
    /// `e2_deg`, ...: mm for a linear axis, deg for a rotary one), the station or the table's
    /// angles; none when the plan was given none.
    #[serde(flatten)]
    pub external: BTreeMap<String, f64>,
    /// Unit vector from the loading point to the rope anchor, base frame.
    pub rope_direction: [f64; 3],
    /// Distance from the loading point to the anchor, mm.
    pub rope_length_mm: f64,
    /// Height of the loading point (base z), mm.
    pub loading_point_z_mm: f64,
    /// Expected displacement `[dx, dy, dz]` of every measuring point under the load with the
    /// nominal stiffness, base frame, mm.
    pub displacements_mm: Vec<[f64; 3]>,
    /// Each joint's predicted deviation rate at noise level multiple 1 if this posture could not
    /// be measured, percent (`null`: the rest cannot identify the joint).
    pub without_pct: [Option<f64>; 6],
    /// The largest of `without_pct`, percent; `null` when one is.
    pub without_worst_pct: Option<f64>,
    /// The smallest distance between bodies (and lines) that must not touch, mm; `null` without
    /// `[cell]` or `[tracker]`.
    pub min_clearance_mm: Option<f64>,
    /// The smallest margin to a constraint of the cell's lengths (every check but the bounds and
    /// the incidence), mm: how far the posture is from its nearest constraint; `null` without
    /// them.
    pub min_margin_mm: Option<f64>,
    /// The check of `min_margin_mm`, e.g. `line-of-sight`.
    pub min_margin_check: Option<&'static str>,
    /// The cell's checks the posture fails, in words (e.g. `floor (tool - floor) fails by 12
    /// mm`); empty when it passes them all.
    pub failed_checks: Vec<String>,
}

impl Document {
    /// The document of a plan report on `setup`.
    pub fn new(report: &Report, setup: &Setup) -> Self {
        let e = &report.evaluation;
        let shows_bodies = setup.cell().is_some() || setup.tracker().is_some();
        Self {
            setup: setup.name().to_string(),
            robot: setup.robot().name().to_string(),
            criterion: report.criterion.name(),
            measuring_points: setup.tool().measuring_points.len(),
            load_n: setup.load().load,
            anchor_mm: setup.load().anchor.map(mm).into(),
            load_steps_n: setup.load_steps().to_vec(),
            displacement_variance_multiple: setup.displacement_variance()
                / setup.noise().reading_variance,
            bodies: shows_bodies.then(|| bodies(setup)),
            target_pct: report.target_pct,
            noise_levels: setup.noise().levels.clone(),
            predicted_deviation_pct: e
                .predicted_deviation_pct
                .iter()
                .map(|row| row.map(finite))
                .collect(),
            virtual_springs: !setup.model().is_drives_only(),
            parameters: parameters(e, setup),
            unidentifiable: unidentifiable(e, setup),
            postures: (report.postures.iter().enumerate())
                .map(|p| posture(p, setup))
                .collect(),
            near_postures: report.near.iter().map(NearDoc::from).collect(),
        }
    }

    /// `plan.csv`: one row per posture (axis angles, with external axes their values where the
    /// posture is read, `e1_mm`, `e2_deg`, ..., rope direction and length, the loading
    /// point's height, each measuring point's expected displacement, the leave-one-out rates:
    /// each joint's predicted deviation rate at noise multiple 1 if that posture could not be
    /// measured, `inf` where the rest cannot identify it; the smallest clearance and the failed
    /// checks joined by `; `), written by [`csv_text`].
    pub fn csv(&self) -> String {
        let mut header: Vec<String> = [
            "posture",
            "q1_deg",
            "q2_deg",
            "q3_deg",
            "q4_deg",
            "q5_deg",
            "q6_deg",
            "rope_x",
            "rope_y",
            "rope_z",
            "rope_length_mm",
            "loading_point_z_mm",
        ]
        .map(String::from)
        .to_vec();
        let axes: Vec<String> =
            (self.postures.first()).map_or(Vec::new(), |p| p.external.keys().cloned().collect());
        header.splice(7..7, axes.iter().cloned());
        for k in 1..=self.measuring_points {
            header.extend(["dx", "dy", "dz"].map(|c| format!("point{k}_{c}_mm")));
        }
        header.extend((1..=6).map(|j| format!("without_joint{j}_pct")));
        let last = ["min_clearance_mm", "min_margin_mm", "failed_checks"];
        header.extend(last.map(String::from));
        let fixed = |values: &[f64], digits: usize| -> Vec<String> {
            values.iter().map(|v| format!("{v:.digits$}")).collect()
        };
        let rows = self.postures.iter().map(|r| {
            let mut cells = vec![r.posture.to_string()];
            cells.extend(fixed(&r.q_deg, 6));
            let values: Vec<f64> = axes.iter().map(|a| r.external[a]).collect();
            cells.extend(fixed(&values, 6));
            cells.extend(fixed(&r.rope_direction, 6));
            cells.push(format!("{:.1}", r.rope_length_mm));
            cells.push(format!("{:.1}", r.loading_point_z_mm));
            cells.extend(r.displacements_mm.iter().flat_map(|d| fixed(d, 3)));
            let without = r.without_pct.map(|v| v.unwrap_or(f64::INFINITY));
            cells.extend(fixed(&without, 4));
            cells.push(
                r.min_clearance_mm
                    .map_or(String::new(), |c| format!("{c:.1}")),
            );
            cells.push(r.min_margin_mm.map_or(String::new(), |c| format!("{c:.1}")));
            cells.push(r.failed_checks.join("; "));
            cells
        });
        csv_text(&header, rows)
    }
}

fn bodies(setup: &Setup) -> Bodies {
    let shapes = setup.shapes().map(|g| g.shapes.len());
    Bodies {
        collision_shapes: shapes,
        link_radii_mm: shapes
            .is_none()
            .then(|| setup.geometry().link_radii.map(mm)),
        tool_radius_mm: mm(setup.geometry().tool_radius),
    }
}

fn posture((i, p): (usize, &Posture), setup: &Setup) -> PlannedPosture {
    let worst = p.without_pct.iter().copied().fold(0.0, f64::max);
    let external = match setup.robot().external().filter(|_| !p.external.is_empty()) {
        None => BTreeMap::new(),
        Some(axes) => (axes.column_names().into_iter())
            .zip(axes.to_display(&p.external))
            .collect(),
    };
    PlannedPosture {
        posture: i + 1,
        q_deg: p.q.map(f64::to_degrees).into(),
        external,
        rope_direction: p.rope_direction.into(),
        rope_length_mm: mm(p.rope_length),
        loading_point_z_mm: mm(p.loading_point_z),
        displacements_mm: p.displacements.iter().map(|d| d.map(mm).into()).collect(),
        without_pct: finite_each(p.without_pct),
        without_worst_pct: finite(worst),
        min_clearance_mm: p.feasibility.min_clearance().map(mm),
        min_margin_mm: p.feasibility.min_margin().map(|c| mm(c.margin)),
        min_margin_check: p.feasibility.min_margin().map(|c| c.kind.key()),
        failed_checks: p.feasibility.violations().map(describe).collect(),
    }
}

/// The plan's 3D scene ([`stiffid_view`]): the group of `report` in the cell, the
/// rope, the nominal compliance's ellipsoids at the tool centre point under the load and each
/// measuring point's expected displacement (the plan's, nominal stiffness); with external axes
/// each posture where the plan reads it ([`Posture::external`]: the arm on its carriage, the
/// table and the boxes it carries turned; every axis at zero when not given). What `select
/// --report` shows in `plan.html` and writes as `plan.glb`, and Python's `stiffid.scene`.
///
/// # Errors
/// [`stiffid_core::Error::MissingField`] for a setup without a nominal stiffness; those of
/// [`scene::scene`].
pub fn scene(report: &Report, setup: &Setup) -> stiffid_core::Result<scene::Scene> {
    let h = setup.try_model_nominal_compliance(super::NEEDED_BY)?;
    let postures: Vec<_> = report.postures.iter().map(|p| p.q).collect();
    let predicted: Vec<_> = report
        .postures
        .iter()
        .map(|p| p.displacements.clone())
        .collect();
    let external: Vec<Vec<f64>> = match report.postures.iter().all(|p| !p.external.is_empty()) {
        true => report.postures.iter().map(|p| p.external.clone()).collect(),
        false => Vec::new(),
    };
    let extras = scene::Extras {
        compliance: Some(&h),
        predicted: &predicted,
        rope: true,
        external: &external,
        ..scene::Extras::default()
    };
    scene::scene(setup, &postures, &extras)
}
