//! `stiffid compensate`: the deflection of every point of a machining path under its process
//! wrench, and the compensated axis angles that cancel it ([`stiffid::compensate`]).

use crate::commands::common::{Common, Stiffness};
use crate::load::{self, WrenchFrame};
use crate::output::{print_json_or, OutFile};
use crate::report::{self, compensation};
use anyhow::{anyhow, Context, Result};
use nalgebra::Vector6;
use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::Serialize;
use serde_json::{Map, Value};
use std::borrow::Cow;
use std::path::PathBuf;
use stiffid::compensate::{self, Compensated, Compliance, FreeToolAxis, Options};
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
    #[arg(long, value_enum, default_value = "base")]
    frame: WrenchFrame,
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

/// Compensates, writes the CSV (and the report), prints.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let file = args.stiffness.load()?;
    let compliance = Compliance {
        h: file.stiffness().map(|k| 1.0 / k),
        covariance: file.covariance(),
    };
    let name = args.path.display().to_string();
    let points = path::parse(&load::read(&args.path)?, args.frame.into()).context(name.clone())?;
    let options = options(args, &setup, points.len())?;
    let out = OutFile::prepare(&args.out, "--out")?;
    let report = args
        .report
        .as_deref()
        .map(|dir| {
            let holds = compensation::holds;
            report::open(dir, "--report", None, compensation::GENERATOR, &holds)
        })
        .transpose()?;
    let results = compensate::path(&setup, &compliance, &points, &options).context(name)?;
    let lines: Vec<u64> = points.iter().map(|p| p.line).collect();
    let table = table(&results, &lines);
    out.write(table.csv().as_bytes())?;
    let summary = Summary::of(&results, &lines);
    let document = Document {
        generator: compensation::GENERATOR,
        setup: &args.common.setup,
        stiffness: args.stiffness.stiffness.display().to_string(),
        path: args.path.display().to_string(),
        out: args.out.display().to_string(),
        springs: setup.springs(),
        stiffness_nm_per_rad: file.stiffness_nm_per_rad,
        has_covariance: compliance.covariance.is_some(),
        free_tool_axis: options.free_tool_axis.map(|f| FreeToolAxisJson {
            max_step_deg: f.max_step.to_degrees(),
            range_deg: f.range.to_degrees(),
        }),
        summary: summary.json(),
        points: table.json(),
    };
    // Through a `Value`: its keys in alphabetical order, as the output has always had them.
    let document = serde_json::to_value(&document)?;
    if let Some(dir) = report {
        compensation::write(dir, &setup, &results, &table, &document)?;
    }
    print_json_or(args.common.json, &document, |_| {
        summary.human(args, &setup, compliance.covariance.is_some())
    })
}

fn options(args: &Args, setup: &Setup, points: usize) -> Result<Options> {
    let mut options = Options::for_setup(setup);
    if let Some(text) = &args.q0_deg {
        options.q0 = load::posture(text, "--q0-deg", setup.robot())?.1;
    }
    if args.free_tool_axis {
        let free = FreeToolAxis::try_from_degrees(args.max_step_deg, args.tool_axis_range_deg)
            .and_then(|f| f.check_grid(points).map(|()| f))
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

/// The per-point results as named columns, units in the names; `None` for an empty cell.
pub struct Table {
    /// Column names.
    pub header: Vec<String>,
    /// One row per path point.
    pub rows: Vec<Vec<Option<f64>>>,
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

fn table(results: &[Compensated], lines: &[u64]) -> Table {
    let rows = results
        .iter()
        .zip(lines)
        .enumerate()
        .map(|(i, (r, line))| row(i, *line, r))
        .collect();
    Table {
        header: header(),
        rows,
    }
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

impl Table {
    /// The CSV text: header, then one line per point; empty cells for missing values.
    pub fn csv(&self) -> String {
        let mut s = self.header.join(",") + "\n";
        for row in &self.rows {
            let cells: Vec<String> = row.iter().map(|v| v.map_or(String::new(), cell)).collect();
            s += &(cells.join(",") + "\n");
        }
        s
    }

    /// One JSON object per point, keyed by the column names (`null` for a missing value).
    pub fn json(&self) -> Vec<Row> {
        self.rows
            .iter()
            .map(|row| {
                let map = self
                    .header
                    .iter()
                    .zip(row)
                    .map(|(h, v)| (h.clone(), serde_json::json!(v)))
                    .collect();
                Row(map)
            })
            .collect()
    }
}

/// A number with 9 decimals (1 nm in mm, 2e-11 rad in deg), trailing zeros dropped.
fn cell(x: f64) -> String {
    let s = format!("{x:.9}");
    match s.trim_end_matches('0').trim_end_matches('.') {
        "-0" => "0".into(),
        t => t.into(),
    }
}

/// The largest and mean values along the path.
pub struct Summary {
    points: usize,
    max_deflection_mm: (f64, u64),
    mean_deflection_mm: f64,
    max_rotation_mrad: f64,
    max_residual_um: f64,
    max_residual_urad: f64,
    max_iterations: usize,
    /// Sum of |d| before and after the tool-axis optimisation, and the rotation range, deg.
    free: Option<(f64, f64, f64, f64)>,
}

impl Summary {
    fn of(results: &[Compensated], lines: &[u64]) -> Self {
        let norm = |d: &Vector6<f64>| d.fixed_rows::<3>(0).norm() * 1e3;
        let max = |f: &dyn Fn(&Compensated) -> f64| results.iter().map(f).fold(0.0, f64::max);
        let (mut worst, mut worst_line) = (0.0, lines[0]);
        for (r, line) in results.iter().zip(lines) {
            if norm(&r.deflection) > worst {
                (worst, worst_line) = (norm(&r.deflection), *line);
            }
        }
        let free = results[0].deflection_before.map(|_| {
            let before: f64 = results
                .iter()
                .filter_map(|r| r.deflection_before.as_ref().map(norm))
                .sum();
            let after: f64 = results.iter().map(|r| norm(&r.deflection)).sum();
            let (lo, hi) = results.iter().fold((0f64, 0f64), |(lo, hi), r| {
                (
                    lo.min(r.tool_rotation.to_degrees()),
                    hi.max(r.tool_rotation.to_degrees()),
                )
            });
            (before, after, lo, hi)
        });
        Self {
            points: results.len(),
            max_deflection_mm: (worst, worst_line),
            mean_deflection_mm: results.iter().map(|r| norm(&r.deflection)).sum::<f64>()
                / results.len() as f64,
            max_rotation_mrad: max(&|r| r.deflection.fixed_rows::<3>(3).norm() * 1e3),
            max_residual_um: max(&|r| r.residual_position * 1e6),
            max_residual_urad: max(&|r| r.residual_rotation * 1e6),
            max_iterations: results.iter().map(|r| r.iterations).max().unwrap_or(0),
            free,
        }
    }

    fn json(&self) -> SummaryJson {
        SummaryJson {
            points: self.points,
            max_deflection_mm: self.max_deflection_mm.0,
            max_deflection_line: self.max_deflection_mm.1,
            mean_deflection_mm: self.mean_deflection_mm,
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
            self.mean_deflection_mm,
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
