//! `stiffid compensate`: the deflection of every point of a machining path under its process
//! wrench, and the compensated axis angles that cancel it ([`stiffid::compensate`]).

use crate::commands::common::choice;
use crate::commands::common::{Common, Stiffness};
use crate::load;
use crate::output::{json, print, write_stdout_parts, OutFile, Part};
use crate::report::{self, compensation};
use anyhow::{anyhow, Context, Result};
use nalgebra::Vector6;
use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::Serialize;
use serde_json::{Map, Value};
use std::borrow::Cow;
use std::io::Write;
use std::path::PathBuf;
use stiffid::compensate::{self, Compensated, FreeToolAxis, Options};
use stiffid::deflection::Frame;
use stiffid::formats::path;
use stiffid::{Coordinates, Error, Setup};

/// Arguments of `stiffid compensate`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    #[command(flatten)]
    stiffness: Stiffness,
    /// Path CSV: q1_deg..q6_deg or x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg, then fx_n,fy_n,fz_n
    /// [,mx_nm,my_nm,mz_nm] [,frame] (at most 1 000 000 rows).
    #[arg(long)]
    path: PathBuf,
    /// Output CSV, one row per path point, units in the header (never one of the inputs).
    #[arg(long)]
    out: PathBuf,
    /// Also write a report into this directory (created; must be missing, empty or hold an
    /// earlier compensation report).
    #[arg(long)]
    report: Option<PathBuf>,
    /// Where inverse kinematics starts for the first pose, axis angles q1..q6, deg; default the
    /// setup's first test posture, else the middle of its bounds.
    #[arg(long, allow_hyphen_values = true)]
    q0_deg: Option<String>,
    /// The frame of the wrench in rows without a `frame` column value.
    #[arg(long, value_parser = choice::<Frame>(), default_value = "base")]
    frame: Frame,
    /// Choose the rotation about the tool z axis of every point to minimise the TCP deflection.
    #[arg(long)]
    free_tool_axis: bool,
    /// With --free-tool-axis: the largest change of that rotation between consecutive points, deg
    /// (0 < value <= 90).
    #[arg(long, default_value_t = 2.0, requires = "free_tool_axis")]
    max_step_deg: f64,
    /// With --free-tool-axis: the rotation stays within +- this of the path's, deg (0 < value <= 180).
    #[arg(long, default_value_t = 90.0, requires = "free_tool_axis")]
    tool_axis_range_deg: f64,
}

/// `stiffid compensate --json` (and the report's `summary.json`).
#[derive(Serialize, JsonSchema)]
pub struct Document<'a> {
    /// `stiffid compensate`: marks a report directory as ours.
    generator: &'static str,
    /// The setup as given (`--setup`).
    setup: &'a str,
    /// The stiffness file (`--stiffness`).
    stiffness: String,
    /// The path file (`--path`).
    path: String,
    /// The CSV written (`--out`).
    out: String,
    /// Where the springs sit.
    springs: Coordinates,
    /// The joint stiffness used, Nm/rad.
    stiffness_nm_per_rad: [f64; 6],
    /// Whether the stiffness file has the compliance covariance (then the `*_std_*` columns
    /// have values).
    has_covariance: bool,
    /// With `--free-tool-axis`: its options; else `null`.
    free_tool_axis: Option<FreeToolAxisJson>,
    /// The largest and mean values along the path.
    summary: SummaryJson,
    /// One object per path point: the columns of the CSV by name.
    points: Vec<Row>,
}

/// The options of `--free-tool-axis`.
#[derive(Serialize, JsonSchema)]
struct FreeToolAxisJson {
    /// The largest change of the rotation about tool z between consecutive points, deg.
    max_step_deg: f64,
    /// The rotation stays within +- this of the path's, deg.
    range_deg: f64,
}

/// The largest and mean values along the path.
#[derive(Serialize, JsonSchema)]
struct SummaryJson {
    /// Path points.
    points: usize,
    /// The largest TCP deflection, mm.
    max_deflection_mm: f64,
    /// Its line in the path file.
    max_deflection_line: u64,
    /// The mean TCP deflection, mm.
    mean_deflection_mm: f64,
    /// The largest tool rotation, mrad.
    max_rotation_mrad: f64,
    /// The largest position residual of the compensated axis angles, um.
    max_residual_um: f64,
    /// The largest rotation residual, urad.
    max_residual_urad: f64,
    /// The most Newton steps of a point.
    max_iterations: usize,
    /// With `--free-tool-axis`: what the rotation about tool z gained; else `null`.
    free_tool_axis: Option<FreeSummaryJson>,
}

/// What the free tool axis gained.
#[derive(Serialize, JsonSchema)]
struct FreeSummaryJson {
    /// Sum of the TCP deflections with the path's rotation, mm.
    sum_deflection_before_mm: f64,
    /// Sum of the TCP deflections with the rotations chosen, mm.
    sum_deflection_after_mm: f64,
    /// The smallest and largest rotation chosen, deg.
    tool_rotation_range_deg: [f64; 2],
}

/// One path point: the columns of [`header`] by name, `null` for an empty cell.
pub struct Row(Map<String, Value>);

impl Serialize for Row {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(serializer)
    }
}

impl JsonSchema for Row {
    fn schema_name() -> Cow<'static, str> {
        "Row".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
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
        json_schema!({
            "description": "One path point: the columns of the CSV by name (units in the names; `null` for an empty cell: the standard deviations without a covariance, `d_norm_before_mm` without --free-tool-axis).",
            "type": "object",
            "properties": properties,
            "required": columns,
        })
    }
}

/// Whether the column `name` may be empty (see [`Row`]'s schema).
fn may_be_empty(name: &str) -> bool {
    name.contains("_std_") || name == "d_norm_before_mm"
}

/// A failure of the streamed run: the library's (placed in the path file), or writing.
enum Failure {
    Library(Error),
    Output(anyhow::Error),
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        Failure::Library(e)
    }
}

/// Compensates the path as it is read, chunk by chunk ([`compensate::stream`]): the CSV (and the
/// rows of the JSON document) written as the results come, the summary accumulated, a sample of
/// the points kept for the report's figures; memory bounded whatever the path's length.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let compliance = args.stiffness.load(&setup)?;
    let options = options(args, &setup)?;
    let name = args.path.display().to_string();
    let text = load::read(&args.path)?;
    let points = path::points(&text, args.frame).context(name.clone())?;
    let out = OutFile::prepare(&args.out, "--out")?;
    let report = args
        .report
        .as_deref()
        .map(|dir| {
            let holds = compensation::holds;
            report::open(dir, "--report", None, compensation::GENERATOR, &holds)
        })
        .transpose()?;
    let columns = header();
    let mut csv = out.writer()?;
    writeln!(csv, "{}", columns.join(","))?;
    let mut rows = (args.common.json || report.is_some())
        .then(|| out.writer())
        .transpose()?;
    let mut summary = Summary::new(options.free_tool_axis.is_some());
    let mut index = 0usize;
    let streamed = compensate::stream(&setup, &compliance, points, &options, |chunk, results| {
        for (p, r) in chunk.iter().zip(results) {
            let values = row(index, p.line, r);
            let mut write = || -> Result<()> {
                writeln!(csv, "{}", csv_line(&values))?;
                if let Some(rows) = rows.as_mut() {
                    let sep = if index == 0 { "" } else { ",\n" };
                    write!(rows, "{sep}{}", json_row(&columns, &values)?)?;
                }
                Ok(())
            };
            write().map_err(Failure::Output)?;
            summary.add(index, p.line, r);
            index += 1;
        }
        Ok(())
    });
    match streamed {
        Ok(_) => {}
        Err(Failure::Output(e)) => return Err(e),
        Err(Failure::Library(e)) => return Err(option_error(e)).context(name),
    }
    csv.sync()?;
    if let Some(rows) = rows.as_mut() {
        rows.sync()?;
    }
    let document = Document {
        generator: compensation::GENERATOR,
        setup: &args.common.setup,
        stiffness: args.stiffness.stiffness.display().to_string(),
        path: args.path.display().to_string(),
        out: args.out.display().to_string(),
        springs: setup.springs(),
        stiffness_nm_per_rad: compliance.drives_h().map(|h| 1.0 / h).into(),
        has_covariance: compliance.covariance.is_some(),
        free_tool_axis: options.free_tool_axis.map(|f| FreeToolAxisJson {
            max_step_deg: f.max_step.to_degrees(),
            range_deg: f.range.to_degrees(),
        }),
        summary: summary.json(),
        points: Vec::new(),
    };
    // Through a `Value`: its keys in alphabetical order, as the output has always had them; the
    // points spliced in from the rows written.
    let document = serde_json::to_value(&document)?;
    let (before, after) = split_at_points(&json(&document)?)?;
    let rows_path = rows.as_ref().map(|r| r.path().to_path_buf());
    fn parts<'a>(before: &'a str, rows: &'a std::path::Path, after: &'a str) -> [Part<'a>; 3] {
        [
            Part::Bytes(before.as_bytes()),
            Part::File(rows),
            Part::Bytes(after.as_bytes()),
        ]
    }
    if let Some(dir) = report {
        let rows = rows_path.as_deref().unwrap_or(std::path::Path::new(""));
        let view = compensation::View {
            sample: &summary.sample,
            largest: &summary.largest,
            points: summary.points,
            csv: csv.path(),
            summary: &parts(&before, rows, &after),
            document: &document,
        };
        compensation::write(dir, &setup, &view)?;
    }
    csv.finish()?;
    match (args.common.json, &rows_path) {
        (true, Some(rows)) => write_stdout_parts(&parts(&before, rows, &after)),
        _ => print(&summary.human(args, &setup, compliance.covariance.is_some())),
    }
}

/// The library's error of the run: a free tool axis' grid as the option names it.
fn option_error(e: Error) -> anyhow::Error {
    match e {
        Error::InvalidField { field, message } if field == "max_step_deg" => {
            anyhow!("--max-step-deg: {message}")
        }
        e => e.into(),
    }
}

/// The pretty JSON document split where its (empty) `points` array goes: the text before the
/// array's first row and after its last.
fn split_at_points(text: &str) -> Result<(String, String)> {
    let key = "\"points\": []";
    let at = text
        .find(key)
        .ok_or_else(|| anyhow!("the document has no points key"))?;
    let before = format!("{}\"points\": [\n", &text[..at]);
    let after = format!("\n  ]{}", &text[at + key.len()..]);
    Ok((before, after))
}

/// One point as a pretty JSON object at the indentation of the document's `points` array, keys
/// in alphabetical order.
fn json_row(columns: &[String], values: &[Option<f64>]) -> Result<String> {
    let map: std::collections::BTreeMap<&str, Option<f64>> = columns
        .iter()
        .map(String::as_str)
        .zip(values.iter().copied())
        .collect();
    let text = serde_json::to_string_pretty(&map)?;
    Ok(text
        .lines()
        .map(|l| format!("    {l}"))
        .collect::<Vec<_>>()
        .join("\n"))
}

/// One CSV line of a point's values: empty cells for missing values.
fn csv_line(values: &[Option<f64>]) -> String {
    let cells: Vec<String> = values
        .iter()
        .map(|v| v.map_or(String::new(), cell))
        .collect();
    cells.join(",")
}

fn options(args: &Args, setup: &Setup) -> Result<Options> {
    let mut options = Options::for_setup(setup);
    if let Some(text) = &args.q0_deg {
        options.q0 = load::posture(text, "--q0-deg", setup.robot())?.1;
    }
    if args.free_tool_axis {
        let free = FreeToolAxis::try_from_degrees(args.max_step_deg, args.tool_axis_range_deg)
            .map_err(|e| match e {
                Error::InvalidField { field, message } => {
                    anyhow!("--{}: {message}", field.replace('_', "-"))
                }
                e => e.into(),
            })?;
        options.free_tool_axis = Some(free);
    }
    Ok(options)
}

fn names(prefix: &str, items: &[&str], unit: &str) -> Vec<String> {
    items.iter().map(|i| format!("{prefix}{i}{unit}")).collect()
}

/// The column names of the table.
fn header() -> Vec<String> {
    let axes = ["1", "2", "3", "4", "5", "6"];
    let xyz = ["x", "y", "z"];
    let mut header = vec!["point".to_string(), "line".to_string()];
    header.extend(names("q", &axes, "_deg"));
    header.extend(names("", &xyz, "_mm"));
    header.extend(names("r", &xyz, "_deg"));
    header.extend(names("f", &xyz, "_base_n"));
    header.extend(names("m", &xyz, "_base_nm"));
    header.extend(names("d", &xyz, "_mm"));
    header.push("d_norm_mm".into());
    header.extend(names("dr", &xyz, "_mrad"));
    header.extend(names("d", &xyz, "_std_mm"));
    header.extend(names("dr", &xyz, "_std_mrad"));
    header.extend(names("qc", &axes, "_deg"));
    header.extend(
        ["residual_um", "residual_urad", "iterations"]
            .iter()
            .map(|s| s.to_string()),
    );
    header.extend(
        ["tool_rotation_deg", "d_norm_before_mm"]
            .iter()
            .map(|s| s.to_string()),
    );
    header
}

fn row(i: usize, line: u64, r: &Compensated) -> Vec<Option<f64>> {
    let deg = |q: &Vector6<f64>| q.iter().map(|v| Some(v.to_degrees())).collect::<Vec<_>>();
    let (rx, ry, rz) = r.pose.rotation.euler_angles();
    let p = r.pose.translation.vector * 1e3;
    let d = &r.deflection;
    let mut v = vec![Some(i as f64 + 1.0), Some(line as f64)];
    v.extend(deg(&r.q));
    v.extend([p.x, p.y, p.z].map(Some));
    v.extend([rx, ry, rz].map(|a| Some(a.to_degrees())));
    v.extend(r.wrench.iter().map(|w| Some(*w)));
    v.extend((0..3).map(|k| Some(d[k] * 1e3)));
    v.push(Some(d.fixed_rows::<3>(0).norm() * 1e3));
    v.extend((3..6).map(|k| Some(d[k] * 1e3)));
    v.extend((0..6).map(|k| r.deflection_std.map(|s| s[k] * 1e3)));
    v.extend(deg(&r.q_compensated));
    v.extend([
        Some(r.residual_position * 1e6),
        Some(r.residual_rotation * 1e6),
        Some(r.iterations as f64),
        Some(r.tool_rotation.to_degrees()),
        r.deflection_before
            .map(|b| b.fixed_rows::<3>(0).norm() * 1e3),
    ]);
    v
}

/// A number with 9 decimals (1 nm in mm, 2e-11 rad in deg), trailing zeros dropped.
fn cell(x: f64) -> String {
    let s = format!("{x:.9}");
    match s.trim_end_matches('0').trim_end_matches('.') {
        "-0" => "0".into(),
        t => t.into(),
    }
}

/// Points of the path kept for the report's figures, at most (every k-th point, k a power of 2).
const SAMPLE: usize = 20_000;

/// The largest and mean values along the path, accumulated point by point, with the sample and
/// the ten largest deflections the report shows.
pub struct Summary {
    points: usize,
    max_deflection_mm: (f64, u64),
    sum_deflection_mm: f64,
    max_rotation_mrad: f64,
    max_residual_um: f64,
    max_residual_urad: f64,
    max_iterations: usize,
    /// Sum of |d| before and after the tool-axis optimisation, and the rotation range, deg.
    free: Option<(f64, f64, f64, f64)>,
    /// Every `stride`-th point (0-based index and result).
    sample: Vec<(usize, Compensated)>,
    stride: usize,
    /// The ten largest deflections (0-based index and result), largest first.
    largest: Vec<(usize, Compensated)>,
}

impl Summary {
    fn new(free: bool) -> Self {
        Self {
            points: 0,
            max_deflection_mm: (0.0, 0),
            sum_deflection_mm: 0.0,
            max_rotation_mrad: 0.0,
            max_residual_um: 0.0,
            max_residual_urad: 0.0,
            max_iterations: 0,
            free: free.then_some((0.0, 0.0, 0.0, 0.0)),
            sample: Vec::new(),
            stride: 1,
            largest: Vec::new(),
        }
    }

    /// Adds point `i` (0-based) of the path, from `line` of the path file.
    fn add(&mut self, i: usize, line: u64, r: &Compensated) {
        let norm = |d: &Vector6<f64>| d.fixed_rows::<3>(0).norm() * 1e3;
        let d = norm(&r.deflection);
        if d > self.max_deflection_mm.0 || self.points == 0 {
            self.max_deflection_mm = (d, line);
        }
        self.points += 1;
        self.sum_deflection_mm += d;
        let rotation = r.deflection.fixed_rows::<3>(3).norm() * 1e3;
        self.max_rotation_mrad = self.max_rotation_mrad.max(rotation);
        self.max_residual_um = self.max_residual_um.max(r.residual_position * 1e6);
        self.max_residual_urad = self.max_residual_urad.max(r.residual_rotation * 1e6);
        self.max_iterations = self.max_iterations.max(r.iterations);
        if let (Some((before, after, lo, hi)), Some(b)) = (&mut self.free, &r.deflection_before) {
            *before += norm(b);
            *after += d;
            *lo = lo.min(r.tool_rotation.to_degrees());
            *hi = hi.max(r.tool_rotation.to_degrees());
        }
        if i % self.stride == 0 {
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

    fn json(&self) -> SummaryJson {
        SummaryJson {
            points: self.points,
            max_deflection_mm: self.max_deflection_mm.0,
            max_deflection_line: self.max_deflection_mm.1,
            mean_deflection_mm: self.sum_deflection_mm / self.points.max(1) as f64,
            max_rotation_mrad: self.max_rotation_mrad,
            max_residual_um: self.max_residual_um,
            max_residual_urad: self.max_residual_urad,
            max_iterations: self.max_iterations,
            free_tool_axis: self.free.map(|(before, after, lo, hi)| FreeSummaryJson {
                sum_deflection_before_mm: before,
                sum_deflection_after_mm: after,
                tool_rotation_range_deg: [lo, hi],
            }),
        }
    }

    fn human(&self, args: &Args, setup: &Setup, covariance: bool) -> String {
        let mut s = format!(
            "{} path points of {} compensated (setup {}, stiffness {}{})\n\
             TCP deflection under the path's wrench: largest {:.4} mm (line {}), mean {:.4} mm; largest tool rotation {:.4} mrad\n\
             compensated axis angles: residual at most {:.2e} um and {:.2e} urad (required: 0.1 um, 1 urad), at most {} Newton steps\n",
            self.points,
            args.path.display(),
            setup.name(),
            args.stiffness.stiffness.display(),
            if covariance { ", with its covariance: standard deviations in the CSV" } else { "" },
            self.max_deflection_mm.0,
            self.max_deflection_mm.1,
            self.sum_deflection_mm / self.points.max(1) as f64,
            self.max_rotation_mrad,
            self.max_residual_um,
            self.max_residual_urad,
            self.max_iterations
        );
        if let Some((before, after, lo, hi)) = self.free {
            s += &format!(
                "free tool axis: mean TCP deflection {:.4} mm before, {:.4} mm after ({:+.1}%), tool rotation within [{lo:.1}, {hi:.1}] deg\n",
                before / self.points as f64,
                after / self.points as f64,
                100.0 * (after / before - 1.0)
            );
        }
        s += &format!("written: {}\n", args.out.display());
        if let Some(dir) = &args.report {
            s += &format!("report: {}\n", dir.join("report.html").display());
        }
        s
    }
}
