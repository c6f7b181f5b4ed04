//! The measurement plan of `stiffid select --report DIR`: `plan.html` (self-contained, figures
//! inline), `plan.csv` (one row per posture) and `figures/` (SVG and PNG): what the operator needs
//! to carry the experiment out in their cell.

use super::content::Writer;
use super::figures::{self, Figure};
use super::html;
use super::tables::{num, Table};
use crate::output::ReportDir;
use anyhow::Result;
use nalgebra::{Vector3, Vector6};
use std::path::Path;
use stiffid::app::document::feasibility::describe;
use stiffid::cell::Checker;
use stiffid::common::words::{count, is_are};
use stiffid::design::criteria::predicted_deviation_pct;
use stiffid::design::target::TargetOutcome;
use stiffid::design::{Criterion, Evaluation, Evaluator};
use stiffid::observation::stiffness::rope_displacements;
use stiffid::Setup;

/// The generator mark of `plan.html`, by which a plan directory is recognised as ours.
const GENERATOR: &str = "stiffid select";

/// Opens the plan directory `dir` (`--report`) before the search: new, empty or holding a plan of
/// ours (its `plan.html`), unless `force`; see [`ReportDir::prepare`].
pub fn open(dir: &Path, force: bool) -> Result<ReportDir> {
    let holds = |rel: &Path| {
        rel == Path::new("plan.html") || rel == Path::new("plan.csv") || rel.starts_with("figures")
    };
    ReportDir::prepare(dir, "--report", Some(force), &holds, &|d| {
        std::fs::read_to_string(d.join("plan.html"))
            .is_ok_and(|t| t.contains(&format!("content=\"{GENERATOR}\"")))
    })
}

/// What the plan says about one posture.
struct Row {
    /// Axis angles, rad.
    q: Vector6<f64>,
    /// Unit vector from the loading point to the rope anchor, base frame.
    rope_direction: Vector3<f64>,
    /// Distance from the loading point to the anchor, m.
    rope_length: f64,
    /// Height of the loading point (base z), m.
    loading_point_z: f64,
    /// Displacement of every measuring point under the load with the nominal stiffness, m.
    displacements: Vec<Vector3<f64>>,
    /// Predicted deviation rate of each joint at noise multiple 1 without this posture, %.
    without_pct: [f64; 6],
    /// The smallest clearance between bodies (and lines) that must not touch, m; `None` without
    /// `[cell]` or `[tracker]`.
    clearance: Option<f64>,
    /// The cell's checks the posture fails, in words.
    failed: Vec<String>,
}

/// A measurement plan: the group, what each posture asks of the operator, what it predicts.
struct Plan<'a> {
    setup: &'a Setup,
    criterion: Criterion,
    rows: Vec<Row>,
    evaluation: Evaluation,
    target: Option<&'a TargetOutcome>,
}

impl<'a> Plan<'a> {
    fn new(
        setup: &'a Setup,
        k: &Vector6<f64>,
        criterion: Criterion,
        postures: &[Vector6<f64>],
        target: Option<&'a TargetOutcome>,
    ) -> Self {
        let evaluator = Evaluator::new(setup);
        let checker = Checker::new(setup);
        let rows = postures
            .iter()
            .enumerate()
            .map(|(i, q)| {
                let frames = setup.robot().frames(q);
                let lp = frames.point(&setup.tool().loading_point);
                let rope = setup.load().anchor - lp;
                let mut others = postures.to_vec();
                others.remove(i);
                let without = evaluator.evaluation(&others).relative_std;
                let feasibility = checker.feasibility(q);
                Row {
                    q: *q,
                    rope_direction: rope.normalize(),
                    rope_length: rope.norm(),
                    loading_point_z: lp.z,
                    displacements: rope_displacements(setup, &frames, k),
                    without_pct: predicted_deviation_pct(&without, 1.0),
                    clearance: feasibility.min_clearance(),
                    failed: feasibility.violations().map(describe).collect(),
                }
            })
            .collect();
        Self {
            setup,
            criterion,
            rows,
            evaluation: evaluator.evaluation(postures),
            target,
        }
    }

    /// Every figure of the plan: the group, each posture, and the target curve if any.
    fn figures(&self) -> Result<Vec<Figure>> {
        let postures: Vec<Vector6<f64>> = self.rows.iter().map(|r| r.q).collect();
        let mut all = figures::postures::each(self.setup, &postures)?;
        if let Some(t) = self.target {
            all.push(figures::target::figure(t)?);
        }
        Ok(all)
    }
}

/// The setup's nominal stiffness, which the plan's expected displacements need.
pub fn stiffness(setup: &Setup) -> Result<&Vector6<f64>> {
    Ok(setup.try_nominal_stiffness("select --report (the plan's expected displacements)")?)
}

/// Writes `plan.html`, `plan.csv` and `figures/` of `postures` (axis angles, rad) into `dir`,
/// each file whole.
pub fn write(
    dir: ReportDir,
    setup: &Setup,
    criterion: Criterion,
    postures: &[Vector6<f64>],
    target: Option<&TargetOutcome>,
) -> Result<()> {
    let plan = Plan::new(setup, stiffness(setup)?, criterion, postures, target);
    let figures = plan.figures()?;
    let title = format!(
        "Measurement plan: {} postures, {}",
        postures.len(),
        setup.name()
    );
    let page = html::page(&title, GENERATOR, |w| compose(&plan, &figures, w));
    dir.write("plan.html", page.as_bytes())?;
    dir.write("plan.csv", csv(&plan).as_bytes())?;
    for f in &figures {
        dir.write(&format!("figures/{}.svg", f.name), f.svg.as_bytes())?;
        dir.write(&format!("figures/{}.png", f.name), &f.png)?;
    }
    dir.finish()
}

fn mm3(v: &Vector3<f64>) -> [String; 3] {
    std::array::from_fn(|a| format!("{:.3}", v[a] * 1e3))
}

/// `plan.csv`: one row per posture; the leave-one-out rates are each joint's predicted deviation
/// rate at noise multiple 1 if that posture could not be measured.
fn csv(plan: &Plan) -> String {
    let p = plan.setup.tool().measuring_points.len();
    let mut header: Vec<String> = [
        "posture", "q1_deg", "q2_deg", "q3_deg", "q4_deg", "q5_deg", "q6_deg",
    ]
    .map(String::from)
    .to_vec();
    header.extend(
        [
            "rope_x",
            "rope_y",
            "rope_z",
            "rope_length_mm",
            "loading_point_z_mm",
        ]
        .map(String::from),
    );
    for k in 1..=p {
        header.extend(["dx", "dy", "dz"].map(|c| format!("point{k}_{c}_mm")));
    }
    header.extend((1..=6).map(|j| format!("without_joint{j}_pct")));
    header.extend(["min_clearance_mm", "failed_checks"].map(String::from));
    let mut text = header.join(",") + "\n";
    for (i, r) in plan.rows.iter().enumerate() {
        let mut cells = vec![(i + 1).to_string()];
        cells.extend(r.q.iter().map(|v| format!("{:.6}", v.to_degrees())));
        cells.extend(r.rope_direction.iter().map(|v| format!("{v:.6}")));
        cells.push(format!("{:.1}", r.rope_length * 1e3));
        cells.push(format!("{:.1}", r.loading_point_z * 1e3));
        cells.extend(r.displacements.iter().flat_map(mm3));
        cells.extend(r.without_pct.iter().map(|v| format!("{v:.4}")));
        cells.push(
            r.clearance
                .map_or(String::new(), |c| format!("{:.1}", c * 1e3)),
        );
        cells.push(format!("\"{}\"", r.failed.join("; ").replace('"', "'")));
        text += &(cells.join(",") + "\n");
    }
    text
}

fn find<'a>(figures: &'a [Figure], name: &str) -> Option<&'a Figure> {
    figures.iter().find(|f| f.name == name)
}

/// What the cell's checks and the drawings take the robot's bodies to be.
fn bodies_sentence(s: &stiffid::Setup) -> String {
    let tool = s.geometry().tool_radius * 1e3;
    match s.shapes() {
        Some(g) => format!(
            "The cell's checks and the drawings use the robot's own {} collision shapes (its URDF's, meshes as convex hulls) and a tool capsule of radius {tool:.0} mm.",
            g.shapes.len()
        ),
        None => {
            let radii: Vec<String> = s
                .geometry()
                .link_radii
                .iter()
                .map(|r| format!("{:.0}", r * 1e3))
                .collect();
            format!(
                "The cell's checks and the drawings use capsules for the robot's bodies (radii {} mm for the base and links 1-6) and the tool (radius {tool:.0} mm).",
                radii.join(", ")
            )
        }
    }
}

/// The body of `plan.html`.
fn compose(plan: &Plan, figures: &[Figure], w: &mut dyn Writer) {
    let s = plan.setup;
    let n = plan.rows.len();
    w.heading(
        1,
        &format!("Measurement plan: {n} postures on {}", s.name()),
    );
    w.paragraph(&format!(
        "Robot {}, {} measuring point(s), a load of {} N hung from the loading point by a rope over the anchor (pulley) at ({}) mm, base frame. Postures chosen by the design criterion `{}`.",
        s.robot().name(),
        s.tool().measuring_points.len(),
        s.load().load,
        mm3(&s.load().anchor).join(", "),
        plan.criterion
    ));
    if s.cell().is_some() || s.tracker().is_some() {
        w.paragraph(&bodies_sentence(s));
    }
    w.heading(2, "Predicted accuracy");
    w.paragraph("The predicted mean deviation rate |k_identified - k_true| / k_true of each joint (first order, `100 sqrt(2/pi) sqrt(m) sqrt([(S^T S)^-1]_jj)`) at the setup's noise levels, if every posture is measured as planned.");
    if !s.load_steps().is_empty() {
        w.paragraph(&format!(
            "With the load steps, every reading carries the tracker noise and each posture's unloaded reading is shared by its steps: the least squares over every step is worth one load of {} N with {} times the variance of one reading per displacement coordinate (docs/model.md, load steps in the design).",
            s.load().load,
            num(s.displacement_variance() / s.noise().variance)
        ));
    }
    w.table(&accuracy(plan));
    if !s.model().is_drives_only() {
        w.paragraph("Every parameter of the setup's model: whether the group identifies it (the column-scaled rank of the observation matrix) and its predicted deviation rate at noise level multiple 1. A parameter the group does not identify cannot be fitted from these measurements, whatever the noise: add postures that load it differently.");
        w.table(&parameters_table(plan));
    }
    if let Some(t) = plan.target {
        w.paragraph(&format!(
            "{} {} the fewest whose group predicts at most {} % on every joint at noise level multiple 1.",
            count(n, "posture"),
            is_are(n),
            t.target_pct
        ));
        if let Some(f) = find(figures, "target") {
            w.figure(f);
        }
    }
    w.heading(2, "Steps, for each posture");
    w.list(&[
        "Move the robot to the posture's axis angles (the controller's, degrees) and check the rope runs freely from the loading point to the pulley (direction and length below).".into(),
        measure_item(s),
        "Compare with the expected displacement below (nominal stiffness): a measured value several times larger or smaller points at a wrong point, a slipping rope or a wrong load.".into(),
        "If a posture cannot be measured, the last column says what the group predicts without it.".into(),
    ]);
    w.table(&postures_table(plan));
    w.table(&displacements_table(plan));
    w.heading(2, "The postures");
    for f in figures.iter().filter(|f| f.name.starts_with("posture")) {
        w.figure(f);
    }
    w.paragraph("Files: plan.csv (the postures table, one row per posture, machine-readable), figures/ (SVG and PNG).");
}

/// What to read in each posture: unloaded and loaded, or unloaded and at every load step of the
/// setup (`[loading] steps_n`).
fn measure_item(s: &stiffid::Setup) -> String {
    let steps = s.load_steps();
    if steps.is_empty() {
        return "Measure every measuring point with the tracker unloaded, hang the load, measure again: the difference is the displacement.".into();
    }
    let levels: Vec<String> = steps.iter().map(f64::to_string).collect();
    format!(
        "Measure every measuring point with the tracker unloaded, then at each load step, rising: {} N ({} steps; the rope pulls the same way at every step). Write every reading, the unloaded ones with load 0, into a readings CSV with a `load_n` column (docs/reference.md, Readings CSV): each step's displacement is its reading minus the unloaded one, and at step f it is f / {} of the displacement below.",
        levels.join(", "),
        steps.len(),
        s.load().load
    )
}

/// The group's predicted deviation rate per joint at each noise level of the setup.
fn accuracy(plan: &Plan) -> Table {
    let mut header = vec!["noise level (x variance)".to_string()];
    header.extend((1..=6).map(|j| format!("joint {j}, %")));
    let rows = plan
        .setup
        .noise()
        .levels
        .iter()
        .zip(&plan.evaluation.predicted_deviation_pct)
        .map(|(m, rates)| {
            let mut row = vec![num(*m)];
            row.extend(rates.iter().map(|r| num(*r)));
            row
        })
        .collect();
    Table { header, rows }
}

/// Per parameter of the model: identified or not, predicted deviation rate at noise multiple 1;
/// then the combinations the group cannot separate.
fn parameters_table(plan: &Plan) -> Table {
    let header = [
        "parameter",
        "unit",
        "identified",
        "deviation rate at level 1, %",
    ]
    .map(String::from)
    .to_vec();
    let mut rows: Vec<Vec<String>> = plan
        .evaluation
        .parameters(plan.setup)
        .into_iter()
        .map(|p| {
            vec![
                p.parameter.name,
                p.parameter.unit.symbol().to_string(),
                if p.identified { "yes" } else { "NO" }.to_string(),
                num(p.predicted_deviation_pct),
            ]
        })
        .collect();
    let names = plan.setup.model().parameters();
    for c in &plan.evaluation.identifiability.unidentifiable {
        rows.push(vec![
            "cannot separate".into(),
            String::new(),
            "NO".into(),
            c.describe(&names),
        ]);
    }
    Table { header, rows }
}

fn postures_table(plan: &Plan) -> Table {
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
        .rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let angles: Vec<String> =
                r.q.iter()
                    .map(|v| format!("{:.2}", v.to_degrees()))
                    .collect();
            let dir: Vec<String> = r.rope_direction.iter().map(|v| format!("{v:.3}")).collect();
            let worst = r.without_pct.iter().copied().fold(0.0, f64::max);
            vec![
                (i + 1).to_string(),
                angles.join(", "),
                dir.join(", "),
                format!("{:.0}", r.rope_length * 1e3),
                format!("{:.0}", r.loading_point_z * 1e3),
                r.clearance
                    .map_or("-".into(), |c| format!("{:.0}", c * 1e3)),
                match r.failed.is_empty() {
                    true => "pass".into(),
                    false => format!("FAIL: {}", r.failed.join("; ")),
                },
                num(worst),
            ]
        })
        .collect();
    Table { header, rows }
}

fn displacements_table(plan: &Plan) -> Table {
    let p = plan.setup.tool().measuring_points.len();
    let mut header = vec!["posture".to_string()];
    header.extend((1..=p).map(|k| format!("point {k}: dx, dy, dz, mm")));
    let rows = plan
        .rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let mut row = vec![(i + 1).to_string()];
            row.extend(r.displacements.iter().map(|d| mm3(d).join(", ")));
            row
        })
        .collect();
    Table { header, rows }
}
