//! `stiffid evaluate`: every design criterion of a group of postures and its predicted deviation
//! rates.

use crate::commands::common::{choice, Common};
use crate::output::{self, json};
use crate::{feasibility, load};
use anyhow::Result;
use std::path::PathBuf;
use stiffid::app::document::candidates::CandidatesDoc;
use stiffid::app::document::group::{CalibrationDoc, Criteria, Infinite, InfiniteCriterion};
use stiffid::app::evaluate::{self as job, Report, Request};
use stiffid::app::purpose::{CalibrationOptions, Purpose};
use stiffid::internal::common::limits::short;
use stiffid::internal::common::words::count;
use stiffid::internal::design::observability::CalibrationCriterion;
use stiffid::internal::design::{Criterion, Evaluation};
use stiffid::internal::metrology::calibration::gravity::Gravity;
use stiffid::internal::metrology::calibration::Geometry;
use stiffid::{Error, Setup};

/// Arguments of `stiffid evaluate`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// Postures file (posture,q1_deg,...,q6_deg).
    #[arg(long)]
    postures: PathBuf,
    #[command(flatten)]
    purpose: ForArgs,
    /// The candidates of `identify --compare-models` to judge the group for, comma-separated:
    /// single candidates (`tilt3_z`, `bend2_y`, `lost2`, a declared spring's name) or families
    /// (`tilt`, `bend`, `carriage`, `base`, `tool`, `lost`, `load`, `declared`); default all of them.
    #[arg(long, value_delimiter = ',')]
    candidates: Option<Vec<String>>,
}

/// What a group is designed for, and the calibration it is for (`select`, `evaluate`).
#[derive(clap::Args)]
pub struct ForArgs {
    /// What the group is for: stiffness (the identification), calibration (the robot's
    /// geometric and elastostatic calibration, as `stiffid calibrate` fits it), both (the
    /// weighted sum of the two log-criteria, --weight) or check (a calibrated robot's check
    /// campaign, 10 postures by default: D-optimal for what `calibrate --update` refits, the
    /// joint offsets, the tracker and the measuring points).
    #[arg(long = "for", value_name = "PURPOSE", value_parser = choice::<Purpose>(), default_value = "stiffness")]
    pub purpose: Purpose,
    /// The calibration criterion: test-pose (the predicted RMS position error after
    /// calibration at the setup's test postures, the default), o1, o3, o4, o5 or d-optimality.
    /// With --for calibration or both only.
    #[arg(long, value_parser = choice::<CalibrationCriterion>())]
    pub calibration_criterion: Option<CalibrationCriterion>,
    /// The joint errors the calibration fits: none, offsets or full (as `calibrate --geometry`;
    /// the default full). With --for calibration or both only.
    #[arg(long, value_parser = choice::<Geometry>())]
    pub geometry: Option<Geometry>,
    /// The gravity terms the calibration fits: none, arm, masses, lumped or lumped-links (as
    /// `calibrate --gravity`; the default none). With --for calibration or both only.
    #[arg(long, value_parser = choice::<Gravity>())]
    pub gravity: Option<Gravity>,
    /// With --for both only: the weight of the calibration's log-criterion, between 0 and 1
    /// (the stiffness criterion's is 1 - weight; the default 0.5).
    #[arg(long)]
    pub weight: Option<f64>,
}

impl ForArgs {
    /// The calibration options of the arguments.
    pub fn options(&self) -> CalibrationOptions {
        CalibrationOptions {
            criterion: self.calibration_criterion,
            geometry: self.geometry,
            gravity: self.gravity,
            weight: self.weight,
        }
    }
}

/// The calibration criteria, one per line.
pub fn calibration_text(c: &CalibrationDoc) -> String {
    let mut s = format!(
        "
calibration criteria (geometry {}, gravity {}, {} identifiable parameters; the indices larger is better)
",
        c.geometry, c.gravity, c.parameters
    );
    for (name, v, unit) in [
        ("o1", c.o1_mm, " mm"),
        ("o3", c.o3_mm, " mm"),
        ("o4", c.o4_mm, " mm"),
        ("o5", c.o5_mm, " mm"),
        ("d-optimality", c.d_optimality_mm2, " mm^2"),
    ] {
        s += &format!(
            "  {name:<13} {}{unit}
",
            number(v)
        );
    }
    let rms = c.predicted_rms_mm.map_or(
        "infinite (the group does not separate the parameters)".to_string(),
        |v| format!("{} mm", number(v)),
    );
    s + &format!(
        "  {:<13} {rms} (predicted RMS position error after calibration)
",
        "test-pose"
    )
}

/// The parameters' lines of `stiffid evaluate`: identified or not, and the predicted deviation
/// rate at noise multiple 1; the combinations the group cannot separate.
fn parameters_text(report: &Report) -> String {
    let mut s =
        "\nparameters: identified by the group, predicted deviation rate at noise level 1\n"
            .to_string();
    for p in &report.parameters {
        let pct = match p.predicted_deviation_pct {
            v if v.is_finite() => format!("{v:.4} %"),
            _ => "-".to_string(),
        };
        let id = if p.identified {
            "identified"
        } else {
            "NOT identified"
        };
        let unit = p.parameter.unit.symbol();
        s += &format!("  {:<12} {unit:<7} {id:<15} {pct}\n", p.parameter.name);
    }
    for c in &report.unidentifiable {
        s += &format!("  cannot separate: {c}\n");
    }
    s
}

/// Evaluates the postures file and prints the criteria and the feasibility of every posture.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    setup.check_bodies()?;
    let group = load::postures(&args.postures, setup.robot(), Some(setup.bounds()))?;
    let request = Request {
        setup: &setup,
        postures: &group,
        purpose: args.purpose.purpose,
        calibration: args.purpose.options(),
        candidates: args.candidates.clone(),
    };
    let outcome = job::run(&request).map_err(|e| match e {
        Error::InvalidOption { .. } => e.into(),
        e => anyhow::Error::new(e).context(args.postures.display().to_string()),
    })?;
    output::warnings(&outcome.warnings);
    if args.common.json {
        return output::print(&json(outcome.written())?);
    }
    let report = &outcome.report;
    let e = &report.evaluation;
    let mut s = format!(
        "{} of {} on setup {}\n",
        count(group.len(), "posture"),
        args.postures.display(),
        short(setup.name())
    );
    let feasibility = report.postures();
    if let Some(c) = &report.calibration_criteria() {
        s += &calibration_text(c);
        if args.purpose.purpose.calibration_only() {
            s += &feasibility::text(&feasibility);
            return output::print(&s);
        }
        s += "\nstiffness criteria\n";
    }
    s += &criteria_text(&report.criteria(), &setup);
    if !setup.model().is_drives_only() || !separable(e) {
        s += &parameters_text(report);
    }
    s += "\npredicted mean deviation rate, % (first order)\n";
    let not_computed = match setup.try_model_nominal_compliance("the prediction") {
        Err(e) => Some(e.to_string()),
        Ok(_) if !separable(e) => Some(NOT_SEPARABLE.to_string()),
        Ok(_) => None,
    };
    if let Some(why) = not_computed {
        s += &format!("  not computed: {why}\n");
    } else {
        s += &deviation_text(&setup, e);
    }
    if let Some(v) = &report.candidate_verdicts() {
        s += &candidates_text(v);
    }
    s += &feasibility::text(&feasibility);
    output::print(&s)
}

/// The predicted mean deviation rates, one row per noise level.
fn deviation_text(setup: &Setup, e: &Evaluation) -> String {
    let mut s = String::new();
    s += &format!("{:>5} {:>6}  {}\n", "level", "x var", joints_header());
    for (l, (m, row)) in setup
        .noise()
        .levels
        .iter()
        .zip(&e.predicted_deviation_pct)
        .enumerate()
    {
        let cells: Vec<String> = row.iter().map(|v| format!("{v:>9.4}")).collect();
        s += &format!("{:>5} {:>6.2}  {}\n", l + 1, m, cells.join(" "));
    }
    s
}

/// The candidates of the model comparison as the group identifies them with the model: one line
/// each, then those `--compare-models` can separate on data measured in the group.
pub fn candidates_text(c: &CandidatesDoc) -> String {
    let mut s = format!(
        "\ncandidates of --compare-models with the model ({}; separation: the share of the candidate's deflections the model cannot reproduce, 0 to 1)\n",
        count(c.load_levels, "load level")
    );
    s += &format!(
        "  {:<16} {:<9} {:<16} {:>10}\n",
        "candidate", "family", "identified", "separation"
    );
    for k in &c.candidates {
        let id = match (k.identified, k.needs_load_steps) {
            (false, _) => "NOT identified",
            (true, true) => "by posture only",
            (true, false) => "identified",
        };
        s += &format!(
            "  {:<16} {:<9} {id:<16} {:>10.4}\n",
            k.name, k.family, k.separation
        );
        for u in &k.unidentifiable {
            s += &format!("    cannot separate: {u}\n");
        }
    }
    s += &format!(
        "  --compare-models can separate {} of the {} on data measured in this group{}\n",
        c.separable.len(),
        c.candidates.len(),
        match c.separable.len() == c.candidates.len() {
            true => String::new(),
            false => format!(": {}", c.separable.join(", ")),
        }
    );
    s += &format!(
        "  the model and the {} candidates a design can identify together, at once: {}\n",
        c.designable.len(),
        match c.together {
            true => "identified (and so is every model a forward selection among them reaches)".to_string(),
            false => format!(
                "NOT identified ({} combinations cannot be separated; select --for-candidates designs for them)",
                c.together_unidentifiable.len()
            ),
        }
    );
    for d in &c.not_designable {
        s += &format!("  {}: {}\n", d.name, d.reason);
    }
    if let Some(note) = &c.nonlinear_separation {
        s += &format!("  lost motion and load-dependent compliance ('by posture only'): {note}\n");
    }
    if !c.dropped.is_empty() {
        let names: Vec<&str> = c.dropped.iter().map(|d| d.name.as_str()).collect();
        s += &format!(
            "  left out of the pool (along a joint's own axis or another candidate's): {}\n",
            names.join(", ")
        );
    }
    s
}

/// Every criterion of a document's `criteria` on `setup`, one per line (smaller is better): an
/// infinite value says why, as the document's `infinite` has it, and so does a criterion the
/// setup lacks a field for.
pub fn criteria_text(criteria: &Criteria, setup: &Setup) -> String {
    let infinite = &criteria.infinite;
    let mut s = String::new();
    for c in Criterion::ALL {
        match c.check(setup) {
            Err(Error::MissingField { field, .. }) => {
                s += &format!(
                    "  {:<12} not computed: the setup has no {field}\n",
                    c.name()
                );
                continue;
            }
            Err(e @ Error::InvalidField { .. }) => {
                s += &format!("  {:<12} not computed: {e}\n", c.name());
                continue;
            }
            _ => {}
        }
        let unit = match c {
            Criterion::TestPose => " mm",
            _ => "",
        };
        let text = match criteria.values.get(c) {
            Some(value) => format!("{}{unit}", number(value)),
            None => why(infinite, c.key()),
        };
        s += &format!("  {:<12} {text}\n", c.name());
    }
    let cond = match criteria.values.cond_psi {
        Some(cond) => number(cond),
        None => why(infinite, "cond_psi"),
    };
    s + &format!("  {:<12} {cond}\n", "cond(Psi)")
}

/// An infinite classical index: a posture where the TCP Jacobian has no inverse.
const SINGULAR: &str = "infinite (a posture is singular: its TCP Jacobian has no inverse)";

/// Any other infinite criterion of a full-rank group: a number beyond the range of f64.
const OVERFLOW: &str = "infinite (beyond the floating-point range: loads or variances too extreme)";

/// An infinite criterion or prediction of a group that cannot separate the model's parameters.
const NOT_SEPARABLE: &str =
    "the group cannot separate every parameter of the model (the combinations are named below)";

/// Whether the group separates every parameter of the setup's model.
fn separable(e: &Evaluation) -> bool {
    e.identifiability.unidentifiable.is_empty()
}

/// Why the criterion of JSON key `key` is infinite, in words, as `infinite` (the document's) has
/// it.
fn why(infinite: &[InfiniteCriterion], key: &str) -> String {
    let reason = infinite.iter().find(|i| i.criterion == key);
    match reason.map(|i| i.reason) {
        Some(Infinite::Singular) => SINGULAR.to_string(),
        Some(Infinite::NotSeparable) => format!("infinite: {NOT_SEPARABLE}"),
        Some(Infinite::Overflow) => OVERFLOW.to_string(),
        None => "infinite".into(),
    }
}

/// A criterion value for people: 6 significant digits, `infinite` for `+infinity`.
pub fn number(v: f64) -> String {
    if v.is_infinite() {
        "infinite".into()
    } else if v != 0.0 && !(1e-3..1e6).contains(&v.abs()) {
        format!("{v:.5e}")
    } else {
        format!("{v:.6}")
    }
}

fn joints_header() -> String {
    (1..=6)
        .map(|j| format!("{:>9}", format!("joint {j}")))
        .collect::<Vec<_>>()
        .join(" ")
}
