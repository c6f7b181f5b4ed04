//! The measurement plan of `stiffid select --report DIR`: `plan.html` (self-contained, figures
//! inline), `plan.csv` (one row per posture), `plan.json` (the plan job's document,
//! [`stiffid::app::plan`], which the other files render) and `figures/` (SVG and PNG): what the
//! operator needs to carry the experiment out in their cell.

use super::content::Writer;
use super::figures::{self, Figure, Png};
use super::html;
use super::tables::{num, Table};
use crate::output::{json, ReportDir};
use anyhow::Result;
use nalgebra::Vector6;
use std::path::Path;
use stiffid::app::document::{finite, mm};
use stiffid::app::plan::document::{self as document, Bodies};
use stiffid::app::plan::{self as job, Report, Request};
use stiffid::internal::common::words::{count, is_are};
use stiffid::internal::design::target::TargetOutcome;
use stiffid::internal::design::Criterion;
use stiffid::internal::view::{glb, Scene};
use stiffid::Setup;

/// The generator mark of `plan.html`, by which a plan directory is recognised as ours.
const GENERATOR: &str = "stiffid select";

/// Opens the plan directory `dir` (`--report`) before the search: new, empty or holding a plan of
/// ours (its `plan.html`), unless `force`; see [`ReportDir::prepare`].
pub fn open(dir: &Path, force: bool) -> Result<ReportDir> {
    let holds = |rel: &Path| {
        ["plan.html", "plan.csv", "plan.json", "plan.glb"]
            .contains(&rel.to_str().unwrap_or_default())
            || (rel.starts_with("figures") && super::figures::is_ours(dir, rel))
    };
    ReportDir::prepare(dir, "--report", Some(force), &holds, &|d| {
        std::fs::read_to_string(d.join("plan.html"))
            .is_ok_and(|t| t.contains(&format!("content=\"{GENERATOR}\"")))
    })
}

/// A measurement plan to render: the plan (its document), the setup and the group drawn, the
/// target curve if any.
struct Plan<'a> {
    setup: &'a Setup,
    postures: &'a [Vector6<f64>],
    doc: Report,
    target: Option<&'a TargetOutcome>,
}

impl Plan<'_> {
    /// Every figure of the plan: the group, each posture, and the target curve if any.
    fn figures(&self) -> Result<Vec<Figure>> {
        let mut all = stiffid_figures::postures::each(self.setup, self.postures);
        if let Some(t) = self.target {
            all.push(stiffid_figures::target::figure(t));
        }
        figures::all(&all, Png::No)
    }
}

/// The setup's nominal stiffness, which the plan's expected displacements need.
pub fn stiffness(setup: &Setup) -> Result<&Vector6<f64>> {
    Ok(setup.try_nominal_stiffness("select --report (the plan's expected displacements)")?)
}

/// How the group was chosen, as the plan states it.
pub struct Provenance {
    /// The command line.
    pub command: String,
    /// The seed of the search.
    pub seed: u64,
    /// The criterion's value for the group.
    pub value: f64,
}

/// Writes `plan.html`, `plan.csv`, `plan.json`, `plan.glb` and `figures/` of `postures` (axis
/// angles, rad; with external axes each read at its `external` values, SI, one list per
/// posture) into `dir`, each file whole.
pub fn write(
    dir: ReportDir,
    setup: &Setup,
    criterion: Criterion,
    postures: &[Vector6<f64>],
    external: &[Vec<f64>],
    target: Option<&TargetOutcome>,
    provenance: &Provenance,
) -> Result<()> {
    let request = Request {
        setup,
        criterion,
        postures,
        target_pct: target.map(|t| t.target_pct),
        external,
        scene: true,
    };
    let job::Outcome { report: doc, scene } = job::run(&request)?;
    let scene = scene.ok_or_else(|| anyhow::anyhow!("the plan job returned no scene"))?;
    let plan = Plan {
        setup,
        postures,
        doc,
        target,
    };
    let figures = plan.figures()?;
    let title = format!(
        "Measurement plan: {} postures, {}",
        postures.len(),
        setup.name()
    );
    let page = html::page(&title, GENERATOR, |w| {
        compose(&plan.doc, &figures, &scene, provenance, w);
    });
    let files = vec![
        ("plan.html".to_string(), page.into_bytes()),
        ("plan.glb".into(), glb::glb(&scene)),
        ("plan.csv".into(), document::csv(&plan.doc).into_bytes()),
        ("plan.json".into(), json(&plan.doc)?.into_bytes()),
    ];
    dir.write_all(&files)?;
    dir.write_all(&figures::files(&figures))?;
    dir.finish()
}

fn fixed<const N: usize>(values: &[f64; N], digits: usize) -> [String; N] {
    values.map(|v| format!("{v:.digits$}"))
}

/// A percentage of the document (`null`: infinite) as the tables write it.
fn pct(v: Option<f64>) -> String {
    num(v.unwrap_or(f64::INFINITY))
}

fn find<'a>(figures: &'a [Figure], name: &str) -> Option<&'a Figure> {
    figures.iter().find(|f| f.name == name)
}

/// What the cell's checks and the drawings take the robot's bodies to be.
fn bodies_sentence(b: &Bodies) -> String {
    let tool = mm(b.tool_radius);
    match (b.collision_shapes, &b.link_radii) {
        (Some(n), _) => format!(
            "The cell's checks and the drawings use the robot's own {n} collision shapes (its URDF's, meshes as convex hulls) and a tool capsule of radius {tool:.0} mm."
        ),
        (None, radii) => {
            let radii: Vec<String> = (radii.iter().flatten())
                .map(|r| format!("{:.0}", mm(*r)))
                .collect();
            format!(
                "The cell's checks and the drawings use capsules for the robot's bodies (radii {} mm for the base and links 1-6) and the tool (radius {tool:.0} mm).",
                radii.join(", ")
            )
        }
    }
}

/// The body of `plan.html`.
fn compose(
    plan: &Report,
    figures: &[Figure],
    scene: &Scene,
    provenance: &Provenance,
    w: &mut dyn Writer,
) {
    let n = plan.postures.len();
    w.heading(
        1,
        &format!("Measurement plan: {n} postures on {}", plan.setup),
    );
    w.paragraph(&format!(
        "Robot {}, {} measuring point(s), a load of {} N hung from the loading point by a rope over the anchor (pulley) at ({}) mm, base frame. Postures chosen by the design criterion `{}`.",
        plan.robot,
        plan.measuring_points,
        plan.load,
        fixed(&plan.anchor.map(mm).into(), 3).join(", "),
        plan.criterion
    ));
    w.paragraph(&format!(
        "Chosen by `{}` (seed {}): the criterion `{}` is {} for this group.",
        provenance.command,
        provenance.seed,
        plan.criterion,
        num(provenance.value)
    ));
    if let Some(b) = &plan.bodies {
        w.paragraph(&bodies_sentence(b));
    }
    w.heading(2, "The postures in the cell");
    w.paragraph("Each posture with the robot's bodies as the cell's checks take them, the tracker's lines of sight (coloured by their margin), the rope to the anchor, the compliance ellipsoid at the tool centre point under the load (nominal stiffness) and each measuring point's expected displacement (magnified, the factor in the legend).");
    w.scene(scene, "plan.glb");
    w.heading(2, "Predicted accuracy");
    w.paragraph("The predicted mean deviation rate |k_identified - k_true| / k_true of each joint (first order, `100 sqrt(2/pi) sqrt(m) sqrt([(S^T S)^-1]_jj)`) at the setup's noise levels, if every posture is measured as planned.");
    if !plan.load_steps.is_empty() {
        w.paragraph(&format!(
            "With the load steps, every reading carries the tracker noise and each posture's unloaded reading is shared by its steps: the least squares over every step is worth one load of {} N with {} times the variance of one reading per displacement coordinate (docs/model.md, load steps in the design).",
            plan.load,
            num(plan.displacement_variance_multiple)
        ));
    }
    w.table(&accuracy(plan));
    if plan.virtual_springs {
        w.paragraph("Every parameter of the setup's model: whether the group identifies it (the column-scaled rank of the observation matrix) and its predicted deviation rate at noise level multiple 1. A parameter the group does not identify cannot be fitted from these measurements, whatever the noise: add postures that load it differently.");
        w.table(&parameters_table(plan));
    }
    if let Some(t) = plan.target_pct {
        w.paragraph(&format!(
            "{} {} the fewest whose group predicts at most {t} % on every joint at noise level multiple 1.",
            count(n, "posture"),
            is_are(n),
        ));
        if let Some(f) = find(figures, "target") {
            w.figure(f);
        }
    }
    if !plan.near.is_empty() {
        let pairs: Vec<String> = (plan.near.iter())
            .map(|p| match p.same_pose_other_branch() {
                true => format!(
                    "{} and {} (the same flange pose on another branch)",
                    p.a + 1,
                    p.b + 1
                ),
                false => format!(
                    "{} and {} (axis angles within {:.2} deg)",
                    p.a + 1,
                    p.b + 1,
                    p.joint_distance.to_degrees()
                ),
            })
            .collect();
        w.paragraph(&format!(
            "Not distinct: postures {}. Such a pair measures nearly the same thing: choose another posture for one of them (`select --pool --distinct` forbids them).",
            pairs.join("; ")
        ));
    }
    w.heading(2, "Steps, for each posture");
    w.list(&[
        "Move the robot to the posture's axis angles (the controller's, degrees) and check the rope runs freely from the loading point to the pulley (direction and length below).".into(),
        measure_item(plan),
        "Compare with the expected displacement below (nominal stiffness): a measured value several times larger or smaller points at a wrong point, a slipping rope or a wrong load.".into(),
        "If a posture cannot be measured, the last column says what the group predicts without it.".into(),
    ]);
    w.table(&postures_table(plan));
    w.table(&displacements_table(plan));
    w.heading(2, "The postures");
    for f in figures.iter().filter(|f| f.name.starts_with("posture")) {
        w.figure(f);
    }
    w.paragraph("Files: plan.glb (the 3D scene as glTF binary), plan.csv (the postures table, one row per posture, machine-readable), figures/ (SVG and PNG).");
}

/// What to read in each posture: unloaded and loaded, or unloaded and at every load step of the
/// setup (`[loading] steps_n`).
fn measure_item(plan: &Report) -> String {
    let steps = &plan.load_steps;
    if steps.is_empty() {
        return "Measure every measuring point with the tracker unloaded, hang the load, measure again: the difference is the displacement.".into();
    }
    let levels: Vec<String> = steps.iter().map(f64::to_string).collect();
    format!(
        "Measure every measuring point with the tracker unloaded, then at each load step, rising: {} N ({} steps; the rope pulls the same way at every step). Write every reading, the unloaded ones with load 0, into a readings CSV with a `load_n` column (docs/reference.md, Readings CSV): each step's displacement is its reading minus the unloaded one, and at step f it is f / {} of the displacement below.",
        levels.join(", "),
        steps.len(),
        plan.load
    )
}

/// The group's predicted deviation rate per joint at each noise level of the setup.
fn accuracy(plan: &Report) -> Table {
    let mut header = vec!["noise level (x variance)".to_string()];
    header.extend((1..=6).map(|j| format!("joint {j}, %")));
    let rows = plan
        .noise_levels
        .iter()
        .zip(&plan.evaluation.predicted_deviation_pct)
        .map(|(m, rates)| {
            let mut row = vec![num(*m)];
            row.extend(rates.iter().map(|r| pct(finite(*r))));
            row
        })
        .collect();
    Table { header, rows }
}

/// Per parameter of the model: identified or not, predicted deviation rate at noise multiple 1;
/// then the combinations the group cannot separate.
fn parameters_table(plan: &Report) -> Table {
    let header = [
        "parameter",
        "unit",
        "identified",
        "deviation rate at level 1, %",
    ]
    .map(String::from)
    .to_vec();
    let mut rows: Vec<Vec<String>> = plan
        .parameters
        .iter()
        .map(|p| {
            vec![
                p.parameter.name.clone(),
                p.parameter.unit.symbol().to_string(),
                if p.identified { "yes" } else { "NO" }.to_string(),
                pct(finite(p.predicted_deviation_pct)),
            ]
        })
        .collect();
    for c in &plan.unidentifiable {
        rows.push(vec![
            "cannot separate".into(),
            String::new(),
            "NO".into(),
            c.clone(),
        ]);
    }
    Table { header, rows }
}

fn postures_table(plan: &Report) -> Table {
    let mut header: Vec<String> = [
        "posture",
        "q1..q6, deg",
        "rope direction (x, y, z)",
        "rope length, mm",
        "loading point z, mm",
    ]
    .map(String::from)
    .to_vec();
    header.extend(
        [
            "smallest clearance, mm",
            "cell checks",
            "without it: worst joint, %",
        ]
        .map(String::from),
    );
    let rows = plan
        .postures
        .iter()
        .map(|r| {
            let checks = r.checks();
            vec![
                r.posture.to_string(),
                fixed(&r.q.map(f64::to_degrees).into(), 2).join(", "),
                fixed(&r.rope_direction.into(), 3).join(", "),
                format!("{:.0}", mm(r.rope_length)),
                format!("{:.0}", mm(r.loading_point_z)),
                (checks.min_clearance_mm).map_or("-".into(), |c| format!("{c:.0}")),
                match checks.failed_checks.is_empty() {
                    true => "pass".into(),
                    false => format!("FAIL: {}", checks.failed_checks.join("; ")),
                },
                pct(r.without().without_worst_pct),
            ]
        })
        .collect();
    Table { header, rows }
}

fn displacements_table(plan: &Report) -> Table {
    let mut header = vec!["posture".to_string()];
    header.extend((1..=plan.measuring_points).map(|k| format!("point {k}: dx, dy, dz, mm")));
    let rows = plan
        .postures
        .iter()
        .map(|r| {
            let mut row = vec![r.posture.to_string()];
            row.extend((r.displacements.iter()).map(|d| fixed(&d.map(mm).into(), 3).join(", ")));
            row
        })
        .collect();
    Table { header, rows }
}
