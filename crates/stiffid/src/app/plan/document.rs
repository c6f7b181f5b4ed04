//! The parts of the plan's document ([`crate::app::plan`]; the report is the document,
//! [`super::Report`]): `plan.json` of `stiffid select --report DIR` (which renders `plan.html`
//! from it) and its `plan.csv` ([`csv()`]), Python's `stiffid.plan`; the robot's bodies
//! ([`Bodies`]), each posture's leave-one-out rates ([`Without`]) and checks ([`Checks`]).

use crate::app::document::feasibility::describe;
use crate::app::document::units::Written;
use crate::app::document::{csv_text, finite, finite_each, mm, units};
use crate::app::plan::Report;
use serde::{Serialize, Serializer};
use std::collections::BTreeMap;
use stiffid_core::cell::Feasibility;
use stiffid_core::Setup;
use stiffid_design::Evaluation;
use stiffid_view as scene;

/// The robot's bodies in the cell's checks and the drawings.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Bodies {
    /// The number of the robot's own collision shapes (its URDF's, meshes as convex hulls);
    /// `null` when capsules stand for the links.
    pub collision_shapes: Option<usize>,
    /// The capsules' radii for the base and links 1-6: m, written in mm; `null` with collision
    /// shapes.
    #[serde(rename = "link_radii_mm", serialize_with = "units::mm7_option")]
    #[cfg_attr(feature = "schema", schemars(with = "Option<[f64; 7]>"))]
    pub link_radii: Option<[f64; 7]>,
    /// The radius of the tool's capsule: m, written in mm.
    #[serde(rename = "tool_radius_mm", serialize_with = "units::mm")]
    pub tool_radius: f64,
}

impl Bodies {
    /// The bodies of `setup` (m).
    pub(crate) fn of(setup: &Setup) -> Self {
        let shapes = setup.shapes().map(|g| g.shapes.len());
        Bodies {
            collision_shapes: shapes,
            link_radii: shapes.is_none().then(|| setup.geometry().link_radii),
            tool_radius: setup.geometry().tool_radius,
        }
    }
}

/// A posture's leave-one-out rates as the plan writes them.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Without {
    /// Each joint's predicted deviation rate at noise level multiple 1 if this posture could not
    /// be measured, percent (`null`: the rest cannot identify the joint).
    pub without_pct: [Option<f64>; 6],
    /// The largest of `without_pct`, percent; `null` when one is.
    pub without_worst_pct: Option<f64>,
}

impl Without {
    /// The rates of `without` (%, infinite where the rest cannot identify the joint).
    pub(crate) fn of(without: &[f64; 6]) -> Self {
        let worst = without.iter().copied().fold(0.0, f64::max);
        Self {
            without_pct: finite_each(*without),
            without_worst_pct: finite(worst),
        }
    }
}

/// A posture's checks in the cell as the plan writes them.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Checks {
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

impl Checks {
    /// The checks of the posture's feasibility `f`.
    pub(crate) fn of(f: &Feasibility) -> Self {
        Self {
            min_clearance_mm: f.min_clearance().map(mm),
            min_margin_mm: f.min_margin().map(|c| mm(c.margin)),
            min_margin_check: f.min_margin().map(|c| c.kind.key()),
            failed_checks: f.violations().map(describe).collect(),
        }
    }
}

/// A posture's leave-one-out rates (%), written as [`Without`] (flattened). Schema: `Without`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn without<S: Serializer>(without: &[f64; 6], s: S) -> Written<S> {
    Without::of(without).serialize(s)
}

/// A posture's checks in the cell, written as [`Checks`] (flattened). Schema: `Checks`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn checks<S: Serializer>(f: &Feasibility, s: S) -> Written<S> {
    Checks::of(f).serialize(s)
}

/// A group's predicted mean deviation rate of each joint at each noise level, percent, `null`
/// where not finite. Schema: `Vec<[Option<f64>; 6]>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn predicted<S: Serializer>(e: &Evaluation, s: S) -> Written<S> {
    s.collect_seq(e.predicted_deviation_pct.iter().map(|row| row.map(finite)))
}

/// The external axes' values `e` (SI; empty: none given) by their columns' names, in mm and deg;
/// empty without external axes or values.
pub(crate) fn columns(setup: &Setup, e: &[f64]) -> BTreeMap<String, f64> {
    match setup.robot().external().filter(|_| !e.is_empty()) {
        None => BTreeMap::new(),
        Some(axes) => (axes.column_names().into_iter())
            .zip(axes.to_display(e))
            .collect(),
    }
}

/// `plan.csv` of `plan`: one row per posture (axis angles, with external axes their values where the
/// posture is read, `e1_mm`, `e2_deg`, ..., rope direction and length, the loading
/// point's height, each measuring point's expected displacement, the leave-one-out rates:
/// each joint's predicted deviation rate at noise multiple 1 if that posture could not be
/// measured, `inf` where the rest cannot identify it; the smallest clearance and the failed
/// checks joined by `; `), written by [`csv_text`].
pub fn csv(plan: &Report) -> String {
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
        (plan.postures.first()).map_or(Vec::new(), |p| p.columns.keys().cloned().collect());
    header.splice(7..7, axes.iter().cloned());
    for k in 1..=plan.measuring_points {
        header.extend(["dx", "dy", "dz"].map(|c| format!("point{k}_{c}_mm")));
    }
    header.extend((1..=6).map(|j| format!("without_joint{j}_pct")));
    let last = ["min_clearance_mm", "min_margin_mm", "failed_checks"];
    header.extend(last.map(String::from));
    let fixed = |values: &[f64], digits: usize| -> Vec<String> {
        values.iter().map(|v| format!("{v:.digits$}")).collect()
    };
    let rows = plan.postures.iter().map(|r| {
        let mut cells = vec![r.posture.to_string()];
        cells.extend(fixed(r.q.map(f64::to_degrees).as_slice(), 6));
        let values: Vec<f64> = axes.iter().map(|a| r.columns[a]).collect();
        cells.extend(fixed(&values, 6));
        cells.extend(fixed(r.rope_direction.as_slice(), 6));
        cells.push(format!("{:.1}", mm(r.rope_length)));
        cells.push(format!("{:.1}", mm(r.loading_point_z)));
        cells.extend(
            r.displacements
                .iter()
                .flat_map(|d| fixed(d.map(mm).as_slice(), 3)),
        );
        let without = r.without_pct.map(|v| finite(v).unwrap_or(f64::INFINITY));
        cells.extend(fixed(&without, 4));
        let checks = r.checks();
        let one = |v: Option<f64>| v.map_or(String::new(), |c| format!("{c:.1}"));
        cells.push(one(checks.min_clearance_mm));
        cells.push(one(checks.min_margin_mm));
        cells.push(checks.failed_checks.join("; "));
        cells
    });
    csv_text(&header, rows)
}

/// The plan's 3D scene ([`stiffid_view`]): the group of `report` in the cell, the
/// rope, the nominal compliance's ellipsoids at the tool centre point under the load and each
/// measuring point's expected displacement (the plan's, nominal stiffness); with external axes
/// each posture where the plan reads it ([`super::Posture::external`]: the arm on its carriage, the
/// table and the boxes it carries turned; every axis at zero when not given). What `select
/// --report` shows in `plan.html` and writes as `plan.glb`, and Python's `stiffid.scene`.
///
/// # Errors
/// [`stiffid_core::Error::MissingField`] for a setup without a nominal stiffness; those of
/// [`scene::scene`].
pub(crate) fn scene(report: &Report, setup: &Setup) -> stiffid_core::Result<scene::Scene> {
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
