//! The document of the register job's proposal ([`crate::app::register::propose`]): `stiffid
//! register --count N --json`, Python's `register(setup, count=N)` (the register report is its
//! own document, [`crate::app::register::Report`]).

use crate::app::document::transform::TransformStd;
use crate::app::document::units;
use crate::app::register::DesignReport;
use nalgebra::Vector6;
use serde::Serialize;

/// The registration postures proposed (`stiffid register --count N --json`, Python's
/// `register(setup, postures=N)`).
///
/// A view of the report ([`DesignReport::document`]), built as it is written: its lengths and
/// angles are the design's, in SI, written in the units their keys name by the unit adapters
/// ([`units`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "register-postures")]
#[cfg_attr(
    feature = "schema",
    schemars(
        description = "The registration postures proposed (`stiffid register --count N --json`, Python's\n`register(setup, postures=N)`)."
    )
)]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("register-postures")))]
pub struct Proposal<'a> {
    /// The setup as given.
    pub setup: &'a str,
    /// The seed of the candidates, the exchange runs and the random groups.
    pub seed: u64,
    /// The postures, `R1`, `R2`, ...: axis angles, deg.
    pub postures: Vec<ProposedPosture>,
    /// Measuring points read per posture.
    pub measuring_points: usize,
    /// The tracker noise per coordinate of one reading (the setup's, level multiple 1): m,
    /// written in mm.
    #[serde(rename = "noise_std_mm", serialize_with = "units::mm")]
    pub noise_std: f64,
    /// Predicted standard deviations of the transform at that noise (linearised).
    #[serde(flatten)]
    pub std: TransformStd,
    /// The criterion minimised: the root of the summed variances of the three rotation angles:
    /// rad, written in deg.
    #[serde(rename = "rotation_std_total_deg", serialize_with = "units::deg")]
    pub rotation_std_total: f64,
    /// The same, median over 101 groups of as many feasible candidates drawn at random: rad,
    /// written in deg.
    #[serde(
        rename = "random_median_rotation_std_total_deg",
        serialize_with = "units::deg"
    )]
    pub random_median_rotation_std_total: f64,
    /// Candidate postures drawn in the bounds.
    pub candidates: usize,
    /// Candidates that pass the cell's checks.
    pub feasible: usize,
    /// The cell's checks the postures pass (those that apply without the load).
    pub checks: Vec<&'static str>,
    /// How the group was chosen (`enumeration` or `exchange`).
    pub method: &'static str,
    /// Groups evaluated.
    pub evaluations: usize,
    /// The readings CSV to fill in: one row per posture and measuring point, the external axes'
    /// columns (`e1_mm`, ...) at the station the postures were chosen at, the tracker's columns
    /// empty.
    pub readings_template: String,
}

/// A posture proposed.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ProposedPosture {
    /// Its label, `R1`, `R2`, ...
    pub posture: String,
    /// Axis angles q1..q6: rad, written in deg.
    #[serde(rename = "q_deg", serialize_with = "units::deg6")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 6]"))]
    pub q: Vector6<f64>,
}

impl<'a> Proposal<'a> {
    /// The document of `report`.
    pub(crate) fn new(report: &'a DesignReport) -> Self {
        let d = &report.design;
        let postures: Vec<ProposedPosture> = (d.postures.iter().enumerate())
            .map(|(i, q)| ProposedPosture {
                posture: format!("R{}", i + 1),
                q: *q,
            })
            .collect();
        let template = template(report, &postures);
        Proposal {
            setup: &report.setup,
            seed: report.seed,
            postures,
            measuring_points: report.measuring_points,
            noise_std: d.noise_std,
            std: TransformStd::new(d.std().into()),
            rotation_std_total: d.rotation_std,
            random_median_rotation_std_total: d.random_median_rotation_std,
            candidates: d.candidates,
            feasible: d.feasible,
            checks: report.checks.iter().map(|k| k.key()).collect(),
            method: d.method.name(),
            evaluations: d.evaluations,
            readings_template: template,
        }
    }
}

/// The readings CSV of `postures` to fill in: one row per posture and measuring point, the
/// external axes' columns (`e1_mm`, ...) at the design's station, the tracker's columns empty.
fn template(report: &DesignReport, postures: &[ProposedPosture]) -> String {
    let header = stiffid_core::io::readings::header();
    let (header, external) = match &report.external {
        Some(axes) => {
            let e = &report.design.external;
            let names = axes.column_names().join(",");
            let values: Vec<String> = (axes.to_display(e).iter())
                .map(|v| format!("{v:.6},"))
                .collect();
            let header = header.replace("q6_deg,", &format!("q6_deg,{names},"));
            (header, values.concat())
        }
        None => (header, String::new()),
    };
    let mut text = header + "\n";
    for p in postures {
        let q: Vec<String> =
            p.q.iter()
                .map(|v| format!("{:.6}", v.to_degrees()))
                .collect();
        for point in 1..=report.measuring_points {
            text += &format!("{},{point},{},{external},,\n", p.posture, q.join(","));
        }
    }
    text
}
