//! The documents of the compensate job ([`crate::app::compensate`]): the CSV of every path point
//! (`stiffid compensate`'s CSV, [`header`] and [`csv_line`]), the JSON document ([`Document`]:
//! `stiffid compensate --json`, the report's `summary.json`) and its summary ([`Summary`],
//! accumulated point by point so that a path of any length is summarised in bounded memory).

pub(crate) use super::free::FreeVariable;
use crate::app::compensate::{Report, Segment};
use crate::app::document::parameters::{stiffness, ParameterStiffness};
use crate::app::document::units;
use nalgebra::Vector6;
use serde::Serialize;
use serde_json::{Map, Value};
use stiffid_core::common::limits::Violation;
use stiffid_core::common::stop::Stop;
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::io::stiffness::RegionSection;
use stiffid_core::model::region::{self, Region};
use stiffid_core::robot::external::{ExternalAxes, ExternalValues};
use stiffid_core::Coordinates;
use stiffid_machining::compensate::Compensated;

pub use super::columns::{csv_line, external_header, external_values, header, values, DYNAMICS};

/// The value of the document's `generator` key: it marks a compensation report directory.
pub const GENERATOR: &str = "stiffid compensate";

/// The compensate document. Units in the key names.
///
/// A view of the report ([`Report::document`]), built as it is written: its lengths and angles
/// are the report's, in SI, written in the units their keys name by the unit adapters
/// ([`units`]); its `points` are the report's (empty where the front end streams them:
/// [`Document::write_json`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "compensate")]
#[cfg_attr(
    feature = "schema",
    schemars(description = "The compensate document. Units in the key names.")
)]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("compensate")))]
pub struct Document<'a> {
    /// `stiffid compensate`: marks a report directory as ours.
    pub generator: &'static str,
    /// The setup as given.
    pub setup: &'a str,
    /// The stiffness file (or `arrays`).
    pub stiffness: &'a str,
    /// The path file, or the program file.
    pub path: &'a str,
    /// The CSV written (the front end's name for it; empty when none is written).
    pub out: &'a str,
    /// Where the springs sit.
    pub springs: Coordinates,
    /// The joint stiffness used, Nm/rad.
    pub stiffness_nm_per_rad: [f64; 6],
    /// Every parameter of the model (drives first, then the virtual springs) with its name,
    /// kind, unit and the stiffness used, as the stiffness file has them
    /// ([`stiffid_core::io::stiffness`]).
    pub parameters: Vec<ParameterStiffness>,
    /// Whether the stiffness file has the compliance covariance (then the `*_std_*` columns
    /// have values).
    pub has_covariance: bool,
    /// With a stiffness file that holds held-out residuals (`identify --cross-validate`): the
    /// level of the deflection's prediction intervals (the `*_lower_mm`, `*_upper_mm` columns);
    /// else `null` (those columns empty).
    pub prediction_level: Option<f64>,
    /// The region of axis angles the stiffness was identified from (a point outside it
    /// extrapolates: the CSV's `extrapolates`, the summary's `extrapolated`); `null` when the
    /// stiffness records none.
    pub region: Option<RegionSection>,
    /// The free variables (`--free`), in the order given: each one's name, range and step;
    /// empty when nothing is free.
    pub free: Vec<FreeVariable>,
    /// With a free variable: what a point costs (`--minimise`): `deflection`, `surge` or
    /// `bound`; else `null`.
    pub minimise: Option<&'static str>,
    /// With a free variable: how the points' costs add up along the path (`--objective`): `sum`
    /// or `max` (the worst point's); else `null`.
    pub objective: Option<&'static str>,
    /// With a free variable: the feasibility checks of its moved postures and the states each
    /// removed; else `null`.
    pub feasibility: Option<&'a super::feasibility::Feasibility>,
    /// The axes' speed limits at the program's feed: whether the free variables' moves were
    /// checked against them, and each axis's highest share of its largest speed along the path
    /// at the path's own values and at those chosen.
    pub speed_limits: &'a super::speed::SpeedLimits,
    /// With a free variable: the levels its grid was refined around the line chosen on it
    /// (`--refine`, 0 to 4: each halves every free variable's step in a band around the
    /// previous level's line); else `null`.
    pub refine: Option<usize>,
    /// With `--free configuration`: every configuration of the arm evaluated over the path and
    /// the one chosen; else `null`.
    pub configurations: Option<super::configurations::ConfigurationsDocument>,
    /// With a program: the program, its process and each segment's force and deflection; else
    /// `null`.
    pub program: Option<Program<'a>>,
    /// The largest and mean values along the path.
    pub summary: SummaryDocument,
    /// With a stiffness file whose `model_form` holds a recommended model other than its own
    /// (`identify --compare-models --bootstrap N --stiffness-out`): Spearman's rho of the two
    /// models' deflections over the points, whether they rank the postures alike, and the points
    /// whose ranks differ most ([`super::ranking`]); else `null`.
    pub model_ranking: Option<&'a super::ranking::RankingDocument>,
    /// Results to look at before trusting them (points without a force).
    pub warnings: &'a [Warning],
    /// One object per path point: the columns of the CSV by name.
    pub points: &'a [Row],
}

/// The names the front end gives the inputs and outputs of a compensation.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Names {
    /// The setup as given.
    pub setup: String,
    /// The stiffness file (or `arrays`).
    pub stiffness: String,
    /// The CSV written (empty when none is).
    pub out: String,
    /// With a program: the compensated program written (empty when none is).
    pub program_out: String,
}

/// A compensated program: what was read, and each segment's force and deflection.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Program<'a> {
    /// The program's language: `gcode`, `krl`, `rapid`, `ls` or `inform`.
    pub language: &'static str,
    /// The compensated program's language (the program's own, or a robot program's for G-code).
    pub output_language: &'static str,
    /// The process file.
    pub process: &'a str,
    /// The compensated program written (empty when none is).
    pub out: &'a str,
    /// A generated program's sub-programs, in the order its main program calls them (empty
    /// unless it is split): each written beside the main program, in a file of its name.
    pub subprograms: Vec<&'a str>,
    /// One entry per segment (a program line with at least one point), in program order.
    pub segments: &'a [Segment],
    /// The largest force on the tool over the program (of `segments`: the process's and the
    /// tool's weight), N.
    pub max_force_n: f64,
    /// Each operation's breakthrough surge (drilling: the largest over its exits) or first
    /// natural frequency against its tooth-passing frequency (milling); empty when the robot
    /// gives no masses.
    pub dynamics: &'a [crate::app::compensate::dynamics::OperationDynamics],
}

/// The largest and mean values along the path: a view of the [`Summary`], its lengths and
/// angles in SI written in the units their keys name.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[cfg_attr(
    feature = "schema",
    schemars(description = "The largest and mean values along the path.")
)]
pub struct SummaryDocument {
    /// Path points.
    pub points: usize,
    /// The largest TCP deflection: m, written in mm.
    #[serde(rename = "max_deflection_mm", serialize_with = "units::mm")]
    pub max_deflection: f64,
    /// Its line in the path file.
    pub max_deflection_line: u64,
    /// The mean TCP deflection: m, written in mm.
    #[serde(rename = "mean_deflection_mm", serialize_with = "units::mm")]
    pub mean_deflection: f64,
    /// The largest tool rotation: rad, written in mrad.
    #[serde(rename = "max_rotation_mrad", serialize_with = "units::mrad")]
    pub max_rotation: f64,
    /// The largest position residual of the compensated axis angles: m, written in um.
    #[serde(rename = "max_residual_um", serialize_with = "units::um")]
    pub max_residual_position: f64,
    /// The largest rotation residual: rad, written in urad.
    #[serde(rename = "max_residual_urad", serialize_with = "units::urad")]
    pub max_residual_rotation: f64,
    /// The most Newton steps of a point.
    pub max_iterations: usize,
    /// Why the Newton steps stopped along the path: `converged` when every point's residual fell
    /// below 1e-4 um and 1e-4 urad, `iteration-limit` when some point's steps stopped at their
    /// limit first (within the 0.1 um and 1 urad a compensated point must reach, else the point
    /// is refused; a warning names the points).
    pub stop_reason: Stop,
    /// The points whose Newton steps stopped at their limit (`iteration-limit`).
    pub not_converged: usize,
    /// The points outside the region the stiffness was identified from (an axis beyond the
    /// identification postures' range widened by its margin, the CSV's `extrapolates`); `null`
    /// when the stiffness records no region.
    pub extrapolated: Option<usize>,
    /// With prediction intervals: the widest interval of a TCP deflection coordinate along the
    /// path (`upper - lower`); `null` without intervals or when one is unbounded: m, written in
    /// mm.
    #[serde(
        rename = "max_interval_width_mm",
        serialize_with = "units::mm_finite_option"
    )]
    #[cfg_attr(feature = "schema", schemars(with = "Option<f64>"))]
    pub max_interval_width: Option<f64>,
    /// With `--free tool-rotation`: what the rotation about tool z gained; else `null`.
    pub free_tool_axis: Option<FreeSummary>,
    /// With `--free lead-tilt`: the leans chosen; else `null`.
    pub free_lead_tilt: Option<LeanSummary>,
    /// The error budget along the path: the largest and mean bound at the level, the parts
    /// absent, the worst points and what dominates their bound (the points' `bound_*` columns).
    pub budget: super::budget::BudgetSummary,
    /// The largest error predicted to remain after compensation: the standard deviation of the
    /// TCP deflection's length `|d|` from the compliance's covariance (the compensation removes
    /// the predicted deflection, not its uncertainty); `null` without a covariance: m, written
    /// in mm.
    #[serde(
        rename = "max_remaining_error_mm",
        serialize_with = "units::mm_finite_option"
    )]
    #[cfg_attr(feature = "schema", schemars(with = "Option<f64>"))]
    pub max_remaining_error: Option<f64>,
    /// What the 3D scene draws (`compensate --report`'s, Python's `stiffid.scene`): the
    /// postures at the first point and at the largest deflection, the sampled path and its
    /// error.
    pub scene: super::scene::ScenePart,
}

/// What the free tool axis gained.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FreeSummary {
    /// Sum of the TCP deflections with the path's rotation: m, written in mm.
    #[serde(rename = "sum_deflection_before_mm", serialize_with = "units::mm")]
    pub sum_deflection_before: f64,
    /// Sum of the TCP deflections with the rotations chosen: m, written in mm.
    #[serde(rename = "sum_deflection_after_mm", serialize_with = "units::mm")]
    pub sum_deflection_after: f64,
    /// The smallest and largest rotation chosen: rad, written in deg.
    #[serde(rename = "tool_rotation_range_deg", serialize_with = "units::deg2")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 2]"))]
    pub tool_rotation_range: [f64; 2],
    /// The mean TCP deflection with the path's rotation: m, written in mm.
    #[serde(rename = "mean_deflection_before_mm", serialize_with = "units::mm")]
    pub mean_deflection_before: f64,
    /// The mean TCP deflection with the rotations chosen: m, written in mm.
    #[serde(rename = "mean_deflection_after_mm", serialize_with = "units::mm")]
    pub mean_deflection_after: f64,
    /// How much the rotations chosen change the mean TCP deflection, %: negative when they
    /// lower it.
    pub mean_change_pct: f64,
}

/// The leans of the tool axis chosen along the path (`--free lead-tilt`): the points'
/// `lead_deg` and `tilt_deg`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct LeanSummary {
    /// The largest lead (towards the feed) in magnitude: rad, written in deg.
    #[serde(rename = "max_lead_deg", serialize_with = "units::deg")]
    pub max_lead: f64,
    /// The largest tilt (across the feed) in magnitude: rad, written in deg.
    #[serde(rename = "max_tilt_deg", serialize_with = "units::deg")]
    pub max_tilt: f64,
    /// The largest angle of the axis to the path's own, `sqrt(lead^2 + tilt^2)`: rad, written in
    /// deg.
    #[serde(rename = "max_lean_deg", serialize_with = "units::deg")]
    pub max_lean: f64,
    /// The mean of that angle over the path's points: rad, written in deg.
    #[serde(rename = "mean_lean_deg", serialize_with = "units::deg")]
    pub mean_lean: f64,
}

/// One path point: the columns of [`header`] by name, `null` for an empty cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Row(pub Map<String, Value>);

impl Row {
    /// The row of `values` (one per column of [`header`]).
    pub(crate) fn new(values: &[Option<f64>]) -> Self {
        let map = header()
            .into_iter()
            .zip(values.iter().map(|v| serde_json::json!(v)))
            .collect();
        Row(map)
    }
}

impl Serialize for Row {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(serializer)
    }
}

#[cfg(feature = "schema")]
impl schemars::JsonSchema for Row {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Row".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let columns = header();
        let properties: Map<String, Value> = columns
            .iter()
            .map(|name| {
                let kind = match may_be_empty(name) {
                    true => serde_json::json!(["number", "null"]),
                    false => serde_json::json!("number"),
                };
                (name.clone(), serde_json::json!({ "type": kind }))
            })
            .collect();
        schemars::json_schema!({
            "description": "One path point: the columns of the CSV by name (units in the names; `null` for an empty cell: the standard deviations without a covariance, `d_norm_before_mm` without --free tool-rotation, `extrapolates` (1 outside the region the stiffness was identified from, else 0) when the stiffness records no region, the dynamics columns `surge_mm_s` .. `tooth_passing_hz` except at drilling exits and milling points of a program whose robot gives masses, `surge_before_mm_s` also without --free tool-rotation).",
            "type": "object",
            "properties": properties,
            "required": columns,
        })
    }
}

/// Whether the column `name` may be empty (see [`Row`]'s schema).
#[cfg(feature = "schema")]
fn may_be_empty(name: &str) -> bool {
    name.contains("_std_")
        || name.contains("_lower_")
        || name.contains("_upper_")
        || name == "d_norm_before_mm"
        || name == "extrapolates"
        || DYNAMICS.contains(&name)
        || name.starts_with("bound_")
}

impl<'a> Document<'a> {
    /// The document of `report` ([`Report::document`]).
    pub(crate) fn new(report: &'a Report) -> Self {
        let names = &report.names;
        Document {
            generator: GENERATOR,
            setup: &names.setup,
            stiffness: &names.stiffness,
            path: &report.input,
            out: &names.out,
            springs: report.springs,
            stiffness_nm_per_rad: report.compliance.drives_h().map(|h| 1.0 / h).into(),
            parameters: stiffness(&report.parameters, &report.compliance.h),
            has_covariance: report.compliance.covariance.is_some(),
            prediction_level: report.prediction_level,
            region: RegionSection::of(&report.compliance.region),
            free: FreeVariable::all(&report.free),
            minimise: super::free::objective(&report.free).map(|o| o.0),
            objective: super::free::objective(&report.free).map(|o| o.1),
            feasibility: report.feasibility.as_ref(),
            speed_limits: &report.speed_limits,
            refine: report.refine,
            configurations: (report.configurations.as_ref())
                .map(super::configurations::ConfigurationsDocument::new),
            program: report.program.as_ref().map(|p| Program {
                language: p.language.name(),
                output_language: p.output.name(),
                process: &p.process,
                out: &names.program_out,
                subprograms: p.subprograms.iter().map(|f| f.name.as_str()).collect(),
                segments: &p.segments,
                max_force_n: p.segments.iter().map(|s| s.force).fold(0.0, f64::max),
                dynamics: &p.dynamics,
            }),
            summary: report.summary.document(),
            model_ranking: report.model_ranking.as_ref(),
            warnings: &report.warnings,
            points: &report.points,
        }
    }
}

/// Points kept for the report's figures, at most (every k-th point, k a power of 2).
pub(crate) const SAMPLE: usize = 20_000;

/// The largest and mean values along a path, accumulated point by point (`Summary::add`),
/// with the sample and the ten largest deflections a report shows.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Points added.
    pub points: usize,
    max_deflection: (f64, u64),
    sum_deflection: f64,
    max_rotation: f64,
    max_residual_position: f64,
    max_residual_rotation: f64,
    max_iterations: usize,
    /// The points whose Newton steps stopped at their limit.
    not_converged: usize,
    /// The lines of the first ten of them.
    not_converged_lines: Vec<u64>,
    /// The points outside the region the stiffness was identified from; `None` while no point
    /// had a region to check.
    extrapolated: Option<usize>,
    /// The first of them ([`region::NAMED`]): the line and the axes outside.
    extrapolated_lines: Vec<(u64, Vec<Violation>)>,
    /// The widest prediction interval of a deflection coordinate, m (`None` without intervals).
    max_interval_width: Option<f64>,
    /// The largest standard deviation of `|d|`, m (`None` without a covariance).
    max_norm_std: Option<f64>,
    /// Sum of |d| before and after the tool-axis optimisation, and the rotation range, rad.
    free: Option<(f64, f64, f64, f64)>,
    /// With the free lead and tilt: the largest |lead|, |tilt| and lean angle, and the sum of
    /// the lean angles, rad.
    lean: Option<[f64; 4]>,
    /// Every `stride`-th point (0-based index and result), at most 20 001.
    pub sample: Vec<(usize, Compensated)>,
    stride: usize,
    /// The ten largest deflections (0-based index and result), largest first.
    pub largest: Vec<(usize, Compensated)>,
    /// The error budget's worst points.
    pub budget: super::budget::Worst,
    /// The level of the bound.
    level: f64,
    /// The first point's line, nominal axis angles and external values.
    first: Option<(u64, Vector6<f64>, ExternalValues)>,
    /// The same of the largest deflection's point.
    largest_at: Option<(u64, Vector6<f64>, ExternalValues)>,
    /// The cell's external axes (the document's units of the external values).
    axes: Option<ExternalAxes>,
    /// The states the feasibility checks removed, summed over the points.
    pub removed: stiffid_machining::compensate::Removed,
}

fn norm(d: &Vector6<f64>) -> f64 {
    d.fixed_rows::<3>(0).norm()
}

impl Summary {
    /// An empty summary; `free`: the free tool axis was asked for; `level`: the bound's;
    /// `axes`: the cell's external axes.
    pub(crate) fn new(free: bool, level: f64, axes: Option<&ExternalAxes>) -> Self {
        Self {
            points: 0,
            max_deflection: (0.0, 0),
            sum_deflection: 0.0,
            max_rotation: 0.0,
            max_residual_position: 0.0,
            max_residual_rotation: 0.0,
            max_iterations: 0,
            not_converged: 0,
            not_converged_lines: Vec::new(),
            extrapolated: None,
            extrapolated_lines: Vec::new(),
            max_interval_width: None,
            max_norm_std: None,
            free: free.then_some((0.0, 0.0, f64::INFINITY, f64::NEG_INFINITY)),
            lean: None,
            sample: Vec::new(),
            stride: 1,
            largest: Vec::new(),
            budget: Default::default(),
            level,
            first: None,
            largest_at: None,
            axes: axes.cloned(),
            removed: Default::default(),
        }
    }

    /// The summary of a path whose lead and tilt are free: it states the leans chosen
    /// ([`LeanSummary`]).
    pub(crate) fn with_lean(self) -> Self {
        Self {
            lean: Some([0.0; 4]),
            ..self
        }
    }

    /// Adds point `i` (0-based) of the path, from `line` of its file, at the external values
    /// `e` (SI, the cell's order; empty without external axes).
    pub(crate) fn add(&mut self, i: usize, line: u64, r: &Compensated, e: &ExternalValues) {
        let d = norm(&r.deflection);
        if d > self.max_deflection.0 || self.points == 0 {
            self.max_deflection = (d, line);
            self.largest_at = Some((line, r.q, *e));
        }
        if self.points == 0 {
            self.first = Some((line, r.q, *e));
        }
        self.points += 1;
        self.removed += r.removed;
        self.sum_deflection += d;
        let rotation = r.deflection.fixed_rows::<3>(3).norm();
        self.max_rotation = self.max_rotation.max(rotation);
        self.max_residual_position = self.max_residual_position.max(r.residual_position);
        self.max_residual_rotation = self.max_residual_rotation.max(r.residual_rotation);
        self.max_iterations = self.max_iterations.max(r.iterations);
        if r.stop != Stop::Converged {
            self.not_converged += 1;
            if self.not_converged_lines.len() < 10 {
                self.not_converged_lines.push(line);
            }
        }
        if let Some(outside) = &r.outside_region {
            let n = self.extrapolated.get_or_insert(0);
            if !outside.is_empty() {
                *n += 1;
                if self.extrapolated_lines.len() < region::NAMED {
                    self.extrapolated_lines.push((line, outside.clone()));
                }
            }
        }
        if let Some(i) = &r.deflection_interval {
            let width = i.iter().map(|[lo, hi]| hi - lo).fold(0.0, f64::max);
            self.max_interval_width = Some(self.max_interval_width.map_or(width, |w| w.max(width)));
        }
        if let Some(sd) = r.translation_norm_std {
            self.max_norm_std = Some(self.max_norm_std.map_or(sd, |m| m.max(sd)));
        }
        if let (Some((before, after, lo, hi)), Some(b)) = (&mut self.free, &r.deflection_before) {
            *before += norm(b);
            *after += d;
            *lo = lo.min(r.tool_rotation);
            *hi = hi.max(r.tool_rotation);
        }
        if let Some([lead, tilt, most, sum]) = &mut self.lean {
            let angle = r.lead.hypot(r.tilt);
            (*lead, *tilt) = (lead.max(r.lead.abs()), tilt.max(r.tilt.abs()));
            (*most, *sum) = (most.max(angle), *sum + angle);
        }
        self.budget.add(line, r);
        self.keep(i, r, d);
    }

    /// Keeps point `i` in the sample and among the largest, if it belongs there.
    fn keep(&mut self, i: usize, r: &Compensated, d: f64) {
        if i.is_multiple_of(self.stride) {
            self.sample.push((i, r.clone()));
            if self.sample.len() > SAMPLE {
                self.stride *= 2;
                let stride = self.stride;
                self.sample.retain(|(k, _)| k % stride == 0);
            }
        }
        let place = self
            .largest
            .iter()
            .position(|(_, c)| norm(&c.deflection) < d);
        match place {
            Some(k) => self.largest.insert(k, (i, r.clone())),
            None => self.largest.push((i, r.clone())),
        }
        self.largest.truncate(10);
    }

    /// Whether the points carry the standard deviation of `|d|` (a compliance with a
    /// covariance).
    fn has_covariance(&self) -> bool {
        self.max_norm_std.is_some()
    }

    /// The postures a scene draws: the first point's and the largest deflection's, each with
    /// its label, nominal axis angles and external values.
    fn scene_postures(&self) -> Vec<(String, &Vector6<f64>, &ExternalValues)> {
        let first =
            (self.first.iter()).map(|(line, q, e)| (format!("first point (line {line})"), q, e));
        let largest = (self.largest_at.iter())
            .map(|(line, q, e)| (format!("largest deflection (line {line})"), q, e));
        first.chain(largest).collect()
    }

    /// A warning ([`WarningKind::NotConverged`]) when some point's Newton steps stopped at their
    /// limit of `max_iterations` before the residual fell below 1e-10 m and 1e-10 rad: the
    /// points are kept (within 0.1 micrometre and 1 microradian), their compensation less exact.
    pub(crate) fn stop_warning(&self, max_iterations: usize) -> Option<Warning> {
        let (n, lines) = (self.not_converged, &self.not_converged_lines);
        (n > 0).then(|| {
            let shown: Vec<String> = lines.iter().map(u64::to_string).collect();
            let more = match n > lines.len() {
                true => ", ...",
                false => "",
            };
            let word = match n {
                1 => "line",
                _ => "lines",
            };
            Warning::new(
                WarningKind::NotConverged,
                format!(
                    "the compensation's Newton steps stopped at their limit of {max_iterations} at {} of {} ({word} {}{more}) with the residual still above 1e-4 um or 1e-4 urad: kept, as within the 0.1 um and 1 urad required (the largest residual is {:.4} um and {:.4} urad), but not converged (near a singularity, or too few steps)",
                    stiffid_core::common::words::count(n, "point"),
                    self.points,
                    shown.join(", "),
                    self.max_residual_position * 1e6,
                    self.max_residual_rotation * 1e6
                ),
            )
        })
    }

    /// The warnings about the region the stiffness was identified from (`region`, the
    /// compliance's): the path points outside it ([`WarningKind::Extrapolation`], naming the
    /// first lines and their axes), or that the stiffness file does not record it.
    pub(crate) fn region_warnings(&self, region: &Region) -> Vec<Warning> {
        let mut out = Vec::from_iter(region.unrecorded_warning());
        if let (Region::Postures(r), Some(n)) = (region, self.extrapolated)
            && n > 0
        {
            let flagged: Vec<(String, Vec<Violation>)> = (self.extrapolated_lines.iter())
                .map(|(line, axes)| (format!("line {line}"), axes.clone()))
                .collect();
            let subject = format!("{n} of {} path points {}", self.points, region::lie(n));
            out.push(region::extrapolation_warning(
                r,
                &subject,
                &flagged,
                n - flagged.len(),
            ));
        }
        out
    }

    /// The mean TCP deflection, m.
    pub(crate) fn mean_deflection(&self) -> f64 {
        self.sum_deflection / self.points.max(1) as f64
    }

    /// The summary as the document writes it: a view of its values, in SI.
    pub fn document(&self) -> SummaryDocument {
        let n = self.points.max(1) as f64;
        SummaryDocument {
            points: self.points,
            max_deflection: self.max_deflection.0,
            max_deflection_line: self.max_deflection.1,
            mean_deflection: self.mean_deflection(),
            max_rotation: self.max_rotation,
            max_residual_position: self.max_residual_position,
            max_residual_rotation: self.max_residual_rotation,
            max_iterations: self.max_iterations,
            stop_reason: match self.not_converged {
                0 => Stop::Converged,
                _ => Stop::IterationLimit,
            },
            not_converged: self.not_converged,
            extrapolated: self.extrapolated,
            max_interval_width: self.max_interval_width,
            max_remaining_error: self.max_norm_std,
            budget: self.budget.document(self.level),
            scene: super::scene::ScenePart::new(
                &self.sample,
                self.has_covariance(),
                self.scene_postures(),
                self.axes.as_ref(),
            ),
            free_lead_tilt: self.lean.map(|[lead, tilt, most, sum]| LeanSummary {
                max_lead: lead,
                max_tilt: tilt,
                max_lean: most,
                mean_lean: sum / n,
            }),
            free_tool_axis: self.free.map(|(before, after, lo, hi)| {
                let (mean_before, mean_after) = (before / n, after / n);
                FreeSummary {
                    sum_deflection_before: before,
                    sum_deflection_after: after,
                    tool_rotation_range: [lo, hi],
                    mean_deflection_before: mean_before,
                    mean_deflection_after: mean_after,
                    mean_change_pct: 100.0 * (mean_after / mean_before - 1.0),
                }
            }),
        }
    }
}
