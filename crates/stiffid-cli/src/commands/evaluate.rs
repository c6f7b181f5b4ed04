//! `stiffid evaluate`: every design criterion of a group of postures and its predicted deviation
//! rates.

use crate::commands::common::Common;
use crate::output::{self, json};
use crate::{feasibility, load};
use anyhow::{Context, Result};
use nalgebra::Vector6;
use schemars::JsonSchema;
use serde::Serialize;
use std::path::PathBuf;
use stiffid::design::{evaluate, Criterion, Evaluation};
use stiffid::limits::short;
use stiffid::lsq::Factor;
use stiffid::observation::rope_observation_matrix;
use stiffid::{Error, Setup};

/// Arguments of `stiffid evaluate`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// Postures file (posture,q1_deg,...,q6_deg).
    #[arg(long)]
    postures: PathBuf,
}

/// Every criterion of a group under the keys of `stiffid evaluate --json`, and its predicted
/// deviation rates.
#[derive(Debug, Serialize, JsonSchema)]
pub struct CriteriaJson {
    #[serde(flatten)]
    values: CriteriaValuesJson,
    /// Predicted mean deviation rate, percent, [levels][6]; `null` for a setup without a nominal
    /// stiffness.
    predicted_deviation_pct: Option<Vec<[f64; 6]>>,
}

/// The design criteria of a group (smaller is better; `null` for `+infinity`: a singular posture
/// for `classical` and `zhang2021`, else a value beyond the floating-point range; `null` also for
/// a criterion the setup lacks a field for: `characteristic_length_mm` for `classical` and
/// `zhang2021`, `nominal_stiffness_nm_per_rad` for `scaled_cond`, `d_optimal` and `relative_a`).
#[derive(Debug, Serialize, JsonSchema)]
pub struct CriteriaValuesJson {
    /// `max_i k(J_N)_i`.
    #[schemars(with = "Option<f64>")]
    classical: f64,
    /// `classical * cond(Psi)`: the paper's index.
    #[schemars(with = "Option<f64>")]
    zhang2021: f64,
    /// `cond(S)`.
    #[schemars(with = "Option<f64>")]
    scaled_cond: f64,
    /// `det((S^T S)^-1)^(1/12)`.
    #[schemars(with = "Option<f64>")]
    d_optimal: f64,
    /// `sqrt(mean_j [(S^T S)^-1]_jj)`.
    #[schemars(with = "Option<f64>")]
    relative_a: f64,
    /// RMS predicted deflection error at the test postures, mm.
    #[schemars(with = "Option<f64>")]
    test_pose_mm: f64,
    /// `cond_2(Psi)`, SI units.
    #[schemars(with = "Option<f64>")]
    cond_psi: f64,
}

impl From<&Evaluation> for CriteriaValuesJson {
    fn from(e: &Evaluation) -> Self {
        Self {
            classical: e.classical,
            zhang2021: e.zhang2021,
            scaled_cond: e.scaled_cond,
            d_optimal: e.d_optimal,
            relative_a: e.relative_a,
            test_pose_mm: e.test_pose * 1e3,
            cond_psi: e.cond_psi,
        }
    }
}

impl From<&Evaluation> for CriteriaJson {
    fn from(e: &Evaluation) -> Self {
        Self {
            values: CriteriaValuesJson::from(e),
            // NaN only without a nominal stiffness (stiffid::design::Evaluation).
            predicted_deviation_pct: (!e
                .predicted_deviation_pct
                .iter()
                .flatten()
                .any(|v| v.is_nan()))
            .then(|| e.predicted_deviation_pct.clone()),
        }
    }
}

/// `stiffid evaluate --json`: the criteria, and every posture's feasibility in the cell.
#[derive(Serialize, JsonSchema)]
pub struct EvaluateJson {
    #[serde(flatten)]
    criteria: CriteriaJson,
    /// Every posture's checks in the cell, in the order of the postures file.
    feasibility: Vec<feasibility::PostureJson>,
    /// Every parameter of the setup's model, drives first: whether the group identifies it and
    /// how well.
    parameters: Vec<ParameterJson>,
    /// The combinations of parameters the group cannot separate (e.g. `0.71 k6 - 0.71 twin6`);
    /// empty when it identifies every parameter.
    unidentifiable: Vec<String>,
}

/// How well the group identifies one parameter.
#[derive(Serialize, JsonSchema)]
pub struct ParameterJson {
    /// `k1` .. `k6`, or the virtual spring's name.
    name: String,
    /// The unit of its stiffness: `Nm/rad` or `N/mm`.
    unit: &'static str,
    /// Whether the group identifies it (column-scaled rank of `Psi`).
    identified: bool,
    /// Predicted mean deviation rate of its stiffness at noise multiple 1, percent; `null` when
    /// the group's `Psi` is rank deficient or the setup has no nominal stiffness.
    predicted_deviation_pct: Option<f64>,
}

/// The parameters' rows and the unidentifiable combinations of an evaluation.
fn parameters(e: &Evaluation, setup: &Setup) -> (Vec<ParameterJson>, Vec<String>) {
    let names = setup.model().parameters();
    let rows = e
        .parameters(setup)
        .into_iter()
        .map(|p| ParameterJson {
            name: p.parameter.name,
            unit: p.parameter.unit.symbol(),
            identified: p.identified,
            predicted_deviation_pct: Some(p.predicted_deviation_pct).filter(|v| v.is_finite()),
        })
        .collect();
    let combinations = e
        .identifiability
        .unidentifiable
        .iter()
        .map(|c| c.describe(&names))
        .collect();
    (rows, combinations)
}

/// The parameters' lines of `stiffid evaluate`: identified or not, and the predicted deviation
/// rate at noise multiple 1; the combinations the group cannot separate.
pub fn parameters_text(e: &Evaluation, setup: &Setup) -> String {
    let (rows, combinations) = parameters(e, setup);
    let mut s =
        "\nparameters: identified by the group, predicted deviation rate at noise level 1\n"
            .to_string();
    for p in rows {
        let pct = p
            .predicted_deviation_pct
            .map_or("-".to_string(), |v| format!("{v:.4} %"));
        let id = if p.identified {
            "identified"
        } else {
            "NOT identified"
        };
        s += &format!("  {:<12} {:<7} {:<15} {pct}\n", p.name, p.unit, id);
    }
    for c in combinations {
        s += &format!("  cannot separate: {c}\n");
    }
    s
}

/// Evaluates the postures file and prints the criteria and the feasibility of every posture.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let group = load::postures(&args.postures, setup.robot(), Some(setup.bounds()))?;
    if setup.model().is_drives_only() {
        identifiable(&setup, &group).with_context(|| args.postures.display().to_string())?;
    }
    let e = evaluate(&setup, &group);
    let checks = feasibility::of_group(&setup, &group);
    if args.common.json {
        let (parameters, unidentifiable) = parameters(&e, &setup);
        let doc = EvaluateJson {
            criteria: CriteriaJson::from(&e),
            feasibility: feasibility::json(&checks),
            parameters,
            unidentifiable,
        };
        return output::print(&json(&doc)?);
    }
    let mut s = format!(
        "{} postures of {} on setup {}\n",
        group.len(),
        args.postures.display(),
        short(setup.name())
    );
    s += &criteria_text(&e, &setup);
    if !setup.model().is_drives_only() {
        s += &parameters_text(&e, &setup);
    }
    s += "\npredicted mean deviation rate, % (first order)\n";
    if let Err(e) = setup.try_nominal_stiffness("the prediction") {
        s += &format!("  not computed: {e}\n");
        s += &feasibility::text(&checks);
        return output::print(&s);
    }
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
    s += &feasibility::text(&checks);
    output::print(&s)
}

/// Fails, naming the joints, when the group's observation matrix cannot identify every joint
/// (the same error as `stiffid simulate`); for a model with virtual springs, naming the
/// combinations of parameters it cannot separate.
pub fn identifiable(setup: &Setup, postures: &[Vector6<f64>]) -> Result<()> {
    if setup.model().is_drives_only() {
        Factor::try_new(rope_observation_matrix(setup, postures))?;
        return Ok(());
    }
    let (_, combinations) = parameters(&evaluate(setup, postures), setup);
    match combinations.is_empty() {
        true => Ok(()),
        false => anyhow::bail!(
            "the group cannot separate {}: choose postures that load these parameters differently",
            combinations.join("; ")
        ),
    }
}

/// Every criterion of an evaluation on `setup`, one per line (smaller is better), for a group
/// that can identify every joint ([`identifiable`]): an infinite value says why, and so does a
/// criterion the setup lacks a field for.
pub fn criteria_text(e: &Evaluation, setup: &Setup) -> String {
    let mut s = String::new();
    for c in Criterion::ALL {
        if let Err(Error::MissingField { field, .. }) = c.check(setup) {
            s += &format!(
                "  {:<12} not computed: the setup has no {field}\n",
                c.name()
            );
            continue;
        }
        let (value, unit) = match c {
            Criterion::TestPose => (e.test_pose * 1e3, " mm"),
            _ => (e.value(c), ""),
        };
        let singular =
            matches!(c, Criterion::Classical | Criterion::Zhang2021) && e.classical.is_infinite();
        let text = match (value.is_finite(), singular) {
            (true, _) => format!("{}{unit}", number(value)),
            (false, true) => SINGULAR.to_string(),
            (false, false) => OVERFLOW.to_string(),
        };
        s += &format!("  {:<12} {text}\n", c.name());
    }
    let cond = match e.cond_psi.is_finite() {
        true => number(e.cond_psi),
        false => OVERFLOW.to_string(),
    };
    s + &format!("  {:<12} {cond}\n", "cond(Psi)")
}

/// An infinite classical index: a posture where the TCP Jacobian has no inverse.
const SINGULAR: &str = "infinite (a posture is singular: its TCP Jacobian has no inverse)";

/// Any other infinite criterion of a full-rank group: a number beyond the range of f64.
const OVERFLOW: &str = "infinite (beyond the floating-point range: loads or variances too extreme)";

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
