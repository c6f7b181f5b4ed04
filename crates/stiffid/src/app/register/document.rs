//! The document of the register job's proposal ([`crate::app::register::propose`]): `stiffid
//! register --count N --json`, Python's `register(setup, count=N)` (the register report is its
//! own document, [`crate::app::register::Report`]).

use crate::app::document::transform::TransformStd;
use crate::app::document::{degrees, mm};
use crate::app::register;
use serde::Serialize;

/// The registration postures proposed (`stiffid register --count N --json`, Python's
/// `register(setup, postures=N)`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "register-postures")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("register-postures")))]
pub struct Proposal {
    /// The setup as given.
    pub setup: String,
    /// The seed of the candidates, the exchange runs and the random groups.
    pub seed: u64,
    /// The postures, `R1`, `R2`, ...: axis angles, deg.
    pub postures: Vec<ProposedPosture>,
    /// Measuring points read per posture.
    pub measuring_points: usize,
    /// The tracker noise per coordinate of one reading (the setup's, level multiple 1), mm.
    pub noise_std_mm: f64,
    /// Predicted standard deviations of the transform at that noise (linearised).
    #[serde(flatten)]
    pub std: TransformStd,
    /// The criterion minimised: the root of the summed variances of the three rotation angles,
    /// deg.
    pub rotation_std_total_deg: f64,
    /// The same, median over 101 groups of as many feasible candidates drawn at random, deg.
    pub random_median_rotation_std_total_deg: f64,
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
    /// Axis angles q1..q6, deg.
    pub q_deg: [f64; 6],
}

impl Proposal {
    /// The document of `report`, for the setup named `setup_name` (as the user gave it).
    pub fn new(report: &register::DesignReport, setup_name: &str) -> Self {
        let d = &report.design;
        let postures: Vec<ProposedPosture> = (degrees(&d.postures).into_iter().enumerate())
            .map(|(i, q_deg)| ProposedPosture {
                posture: format!("R{}", i + 1),
                q_deg,
            })
            .collect();
        let template = template(report, &postures);
        Proposal {
            setup: setup_name.to_string(),
            seed: report.seed,
            postures,
            measuring_points: report.measuring_points,
            noise_std_mm: mm(d.noise_std),
            std: TransformStd::new(d.std().into()),
            rotation_std_total_deg: d.rotation_std.to_degrees(),
            random_median_rotation_std_total_deg: d.random_median_rotation_std.to_degrees(),
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
fn template(report: &register::DesignReport, postures: &[ProposedPosture]) -> String {
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
        let q: Vec<String> = p.q_deg.iter().map(|v| format!("{v:.6}")).collect();
        for point in 1..=report.measuring_points {
            text += &format!("{},{point},{},{external},,\n", p.posture, q.join(","));
        }
    }
    text
}
