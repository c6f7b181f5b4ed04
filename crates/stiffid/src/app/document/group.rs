//! What a group of postures is worth, as several documents show it: its design criteria (the
//! evaluate and select documents, the study's summary), its calibration criteria, how well it
//! identifies each parameter of the model (evaluate, plan), its postures that are not distinct
//! (select, plan) and its simulated deviation rates (simulate, the study's summary).
//!
//! A report holds these in SI, as the design library gives them ([`Evaluation`], [`Near`], ...);
//! the crate's serde adapters here (`criteria`, `parameters`, `calibration`, `near`) write them
//! as the parts below, so that the report serialises to its document itself.

use crate::app::document::units::Written;
use crate::app::document::{finite, mm};
use crate::app::purpose::CalibrationOptions;
use serde::{Serialize, Serializer};
use stiffid_core::model::Parameter as ModelParameter;
use stiffid_design::criteria::ParameterQuality;
use stiffid_design::distinct::Near;
use stiffid_design::observability::CalibrationCriteria;
use stiffid_design::study::simulate::GroupSimulation;
use stiffid_design::{Criterion, Evaluation};

/// Every criterion of a group, and its predicted deviation rates.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Criteria {
    /// The criteria.
    #[serde(flatten)]
    pub values: CriteriaValues,
    /// Relative standard deviation of each drive's compliance at noise level 1,
    /// `sqrt([(S^T S)^-1]_jj)`; `null` for a setup without a nominal stiffness.
    pub relative_std: Option<[Option<f64>; 6]>,
    /// Predicted mean deviation rate, percent, `[levels][6]` (`null` inside for a joint the group
    /// cannot identify); `null` for a setup without a nominal stiffness.
    pub predicted_deviation_pct: Option<Vec<[Option<f64>; 6]>>,
    /// Every criterion that is `+infinity` (`null` above), in the order of the criteria, with
    /// why; empty when every computed criterion is finite.
    pub infinite: Vec<InfiniteCriterion>,
}

/// A criterion that is `+infinity`, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct InfiniteCriterion {
    /// The criterion's key (`classical`, `zhang2021`, `scaled_cond`, `d_optimal`, `relative_a`,
    /// `test_pose_mm`, `cond_psi`).
    pub criterion: &'static str,
    /// Why it is infinite.
    pub reason: Infinite,
}

/// Why a criterion of a group is `+infinity`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "kebab-case")]
pub enum Infinite {
    /// A posture is singular: its TCP Jacobian has no inverse (`classical` and `zhang2021`).
    Singular,
    /// The group cannot separate every parameter of the model (`unidentifiable` names the
    /// combinations).
    NotSeparable,
    /// A group that separates the parameters: a number beyond the floating-point range (loads or
    /// variances too extreme).
    Overflow,
}

impl Infinite {
    /// Why the value `value` of `criterion` (`None`: `cond(Psi)`) in `e` is infinite; `None` if
    /// it is not (finite, or NaN: not computed).
    pub(crate) fn of(e: &Evaluation, criterion: Option<Criterion>, value: f64) -> Option<Self> {
        let singular = matches!(criterion, Some(Criterion::Classical | Criterion::Zhang2021))
            && e.classical.is_infinite();
        if !value.is_infinite() {
            None
        } else if singular {
            Some(Infinite::Singular)
        } else if e.identifiability.unidentifiable.is_empty() {
            Some(Infinite::Overflow)
        } else {
            Some(Infinite::NotSeparable)
        }
    }
}

/// Every infinite criterion of `e` and `cond(Psi)`, with why.
fn infinite(e: &Evaluation) -> Vec<InfiniteCriterion> {
    let criteria = Criterion::ALL.map(|c| (c.key(), Some(c), e.value(c)));
    let all = criteria.into_iter().chain([("cond_psi", None, e.cond_psi)]);
    all.filter_map(|(key, c, v)| {
        Infinite::of(e, c, v).map(|reason| InfiniteCriterion {
            criterion: key,
            reason,
        })
    })
    .collect()
}

/// The design criteria of a group (smaller is better; `null` for `+infinity`: a singular posture
/// for `classical` and `zhang2021`, else a value beyond the floating-point range; `null` also for
/// a criterion the setup lacks a field for: `characteristic_length_mm` for `classical` and
/// `zhang2021`, `nominal_stiffness_nm_per_rad` for `scaled_cond`, `d_optimal` and `relative_a`,
/// test postures for `test_pose_mm`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct CriteriaValues {
    /// `max_i k(J_N)_i` (Eq. 20-21).
    pub classical: Option<f64>,
    /// `classical * cond(Psi)`: the paper's index.
    pub zhang2021: Option<f64>,
    /// `cond(S)`.
    pub scaled_cond: Option<f64>,
    /// `det((S^T S)^-1)^(1/12)`.
    pub d_optimal: Option<f64>,
    /// `sqrt(mean_j [(S^T S)^-1]_jj)`.
    pub relative_a: Option<f64>,
    /// RMS predicted deflection error at the test postures, mm.
    pub test_pose_mm: Option<f64>,
    /// `cond_2(Psi)`, SI units.
    pub cond_psi: Option<f64>,
}

impl CriteriaValues {
    /// The value of `criterion` as the document has it (`test_pose_mm` in mm; `None` where
    /// the document has `null`).
    pub fn get(&self, criterion: Criterion) -> Option<f64> {
        match criterion {
            Criterion::Classical => self.classical,
            Criterion::Zhang2021 => self.zhang2021,
            Criterion::ScaledCond => self.scaled_cond,
            Criterion::DOptimal => self.d_optimal,
            Criterion::RelativeA => self.relative_a,
            Criterion::TestPose => self.test_pose_mm,
        }
    }
}

impl From<&Evaluation> for CriteriaValues {
    fn from(e: &Evaluation) -> Self {
        Self {
            classical: finite(e.classical),
            zhang2021: finite(e.zhang2021),
            scaled_cond: finite(e.scaled_cond),
            d_optimal: finite(e.d_optimal),
            relative_a: finite(e.relative_a),
            test_pose_mm: finite(mm(e.test_pose)),
            cond_psi: finite(e.cond_psi),
        }
    }
}

impl Criteria {
    /// The document of the evaluation `e`.
    pub(crate) fn of(e: &Evaluation) -> Self {
        // NaN only without a nominal stiffness (stiffid_design::Evaluation).
        let scaled = !e.relative_std.iter().any(|v| v.is_nan());
        Self {
            values: CriteriaValues::from(e),
            relative_std: scaled.then(|| e.relative_std.map(finite).into()),
            predicted_deviation_pct: scaled.then(|| {
                let rows = e.predicted_deviation_pct.iter();
                rows.map(|row| row.map(finite)).collect()
            }),
            infinite: infinite(e),
        }
    }
}

/// How well a group identifies one parameter of the setup's model.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub(crate) struct Parameter {
    /// `k1` .. `k6`, or the virtual spring's name.
    pub name: String,
    /// The unit of its stiffness: `Nm/rad` or `N/mm`.
    pub unit: &'static str,
    /// Whether the group identifies it (column-scaled rank of `Psi`).
    pub identified: bool,
    /// Predicted mean deviation rate of its stiffness at noise multiple 1, percent; `null` when
    /// the group's `Psi` is rank deficient or the setup has no nominal stiffness.
    pub predicted_deviation_pct: Option<f64>,
}

impl From<&ParameterQuality> for Parameter {
    fn from(p: &ParameterQuality) -> Self {
        Self {
            name: p.parameter.name.clone(),
            unit: p.parameter.unit.symbol(),
            identified: p.identified,
            predicted_deviation_pct: finite(p.predicted_deviation_pct),
        }
    }
}

/// The calibration criteria of a group (docs/model.md, "Design for calibration"), over the
/// column-scaled identification Jacobian of the calibration's kept parameters (a scaled column
/// is the position change of a typical parameter error: mm).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct CalibrationDoc {
    /// The criterion a selection minimises (`o1`, `o3`, `o4`, `o5`, `d-optimality`,
    /// `test-pose`).
    pub criterion: &'static str,
    /// The joint errors of the calibration (`none`, `offsets`, `full`).
    pub geometry: &'static str,
    /// Its gravity terms (`none`, `masses`, `lumped`).
    pub gravity: &'static str,
    /// The kept (identifiable) parameters' count.
    pub parameters: usize,
    /// `O1`: the geometric mean of the singular values over `sqrt(n)`, mm (larger is better).
    pub o1_mm: f64,
    /// `O3`: the smallest singular value, mm (larger is better; 0 for a group that does not
    /// separate the parameters).
    pub o3_mm: f64,
    /// `O4`: the smallest singular value squared over the largest, mm (larger is better).
    pub o4_mm: f64,
    /// `O5`: the inverse sum of the singular values' inverses, mm (larger is better).
    pub o5_mm: f64,
    /// D-optimality `det(J_s^T J_s)^(1/p)`, mm^2 (larger is better).
    pub d_optimality_mm2: f64,
    /// The predicted RMS position error after calibration at the test postures, mm (smaller is
    /// better; `null` for a group that does not separate the parameters).
    pub predicted_rms_mm: Option<f64>,
}

impl CalibrationDoc {
    /// The document of the options `o` and the criteria `c`.
    pub(crate) fn new(o: &CalibrationOptions, c: &CalibrationCriteria) -> Self {
        use stiffid_core::common::choice::Choice;
        Self {
            criterion: o.criterion().name(),
            geometry: o.geometry().name(),
            gravity: o.gravity().name(),
            parameters: c.parameters,
            o1_mm: c.o1 * 1e3,
            o3_mm: c.o3 * 1e3,
            o4_mm: c.o4 * 1e3,
            o5_mm: c.o5 * 1e3,
            d_optimality_mm2: c.d_optimality * 1e6,
            predicted_rms_mm: finite(mm(c.predicted_rms)),
        }
    }
}

/// Two postures of the group that are not distinct.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub(crate) struct NearDoc {
    /// The two postures' numbers in the group (1-based).
    pub postures: [usize; 2],
    /// The largest difference of their axis angles, deg.
    pub joint_distance_deg: f64,
    /// The distance between their flange origins, mm.
    pub flange_distance_mm: f64,
    /// The angle between their flange orientations, deg.
    pub flange_angle_deg: f64,
    /// The same flange pose reached on another branch (a wrist flip), not close axis angles.
    pub same_pose_other_branch: bool,
}

impl From<&Near> for NearDoc {
    fn from(n: &Near) -> Self {
        NearDoc {
            postures: [n.a + 1, n.b + 1],
            joint_distance_deg: n.joint_distance.to_degrees(),
            flange_distance_mm: n.position_distance * 1e3,
            flange_angle_deg: n.angle_distance.to_degrees(),
            same_pose_other_branch: n.same_pose_other_branch(),
        }
    }
}

/// One group's simulation: deviation rates in percent, per level then parameter (the drives,
/// then the model's virtual springs, in the order of `parameters`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Group {
    /// Name of the group.
    pub name: String,
    /// Mean deviation rate, percent, `[levels][parameters]`.
    pub mean_deviation_pct: Vec<Vec<f64>>,
    /// Standard deviation of the deviation rate, percent, `[levels][parameters]`.
    pub std_deviation_pct: Vec<Vec<f64>>,
    /// First-order predicted mean deviation rate, percent, `[levels][parameters]`.
    pub predicted_deviation_pct: Vec<Vec<f64>>,
    /// Mean identified stiffness of the drives, Nm/rad, `[levels][6]`.
    pub mean_stiffness_nm_per_rad: Vec<[f64; 6]>,
    /// Mean identified stiffness of each virtual spring, in its parameter's unit (Nm/rad for a
    /// rotation, N/mm for a translation), `[levels][springs]`; left out for the drives alone.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    #[cfg_attr(feature = "schema", schemars(default))]
    pub mean_spring_stiffness: Vec<Vec<f64>>,
}

impl Group {
    /// The document of group `name`'s simulation of a model with `parameters` (drives first).
    pub(crate) fn new(name: &str, sim: &GroupSimulation, parameters: &[ModelParameter]) -> Self {
        let join = |drives: &[[f64; 6]], springs: &[Vec<f64>]| -> Vec<Vec<f64>> {
            drives
                .iter()
                .enumerate()
                .map(|(l, d)| {
                    let rest = springs.get(l).map_or(&[][..], Vec::as_slice);
                    d.iter().chain(rest).copied().collect()
                })
                .collect()
        };
        let springs = parameters.get(6..).unwrap_or_default();
        Self {
            name: name.into(),
            mean_deviation_pct: join(&sim.mean_deviation_pct, &sim.spring_mean_deviation_pct),
            std_deviation_pct: join(&sim.std_deviation_pct, &sim.spring_std_deviation_pct),
            predicted_deviation_pct: join(
                &sim.predicted_deviation_pct,
                &sim.spring_predicted_deviation_pct,
            ),
            mean_stiffness_nm_per_rad: sim.mean_stiffness.iter().map(|k| (*k).into()).collect(),
            mean_spring_stiffness: sim
                .spring_mean_stiffness
                .iter()
                .map(|k| {
                    k.iter()
                        .zip(springs)
                        .map(|(k, p)| k * p.unit.per_si())
                        .collect()
                })
                .collect(),
        }
    }
}

/// A group's evaluation written as its [`Criteria`] (flattened into a document). Schema:
/// `Criteria`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn criteria<S: Serializer>(e: &Evaluation, s: S) -> Written<S> {
    Criteria::of(e).serialize(s)
}

/// How well a group identifies every parameter of the model ([`Evaluation::parameters`]),
/// written as [`Parameter`]s. Schema: `Vec<Parameter>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn parameters<S: Serializer>(p: &[ParameterQuality], s: S) -> Written<S> {
    s.collect_seq(p.iter().map(Parameter::from))
}

/// The calibration options and a group's calibration criteria (SI) or none, written as a
/// [`CalibrationDoc`] or `null`. Schema: `Option<CalibrationDoc>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn calibration<S: Serializer>(
    c: &Option<(CalibrationOptions, CalibrationCriteria)>,
    s: S,
) -> Written<S> {
    (c.as_ref().map(|(o, c)| CalibrationDoc::new(o, c))).serialize(s)
}

/// The pairs of postures of a group that are not distinct, written as [`NearDoc`]s. Schema:
/// `Vec<NearDoc>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn near<S: Serializer>(pairs: &[Near], s: S) -> Written<S> {
    s.collect_seq(pairs.iter().map(NearDoc::from))
}
