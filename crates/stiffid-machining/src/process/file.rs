//! The process file (TOML): the operations of a machining job. Every field carries its unit in its name and is range-checked ([`limits`](self#limits)).
//!
//! One operation at the top level:
//! ```toml
//! kind = "milling"                 # or "drilling"; default milling
//! [tool]
//! diameter_mm = 20
//! flutes = 3
//! helix_deg = 30
//! [cut]
//! feed_per_tooth_mm = 0.1
//! axial_depth_mm = 4
//! radial_depth_mm = 10
//! mode = "up"                      # or "down"
//! spindle_rpm = 12000              # optional: the tooth-passing frequency for the chatter check
//! [coefficients]
//! preset = "al7075-t6"             # or the six below (a preset's values may be overridden)
//! k_tc_n_per_mm2 = 767.01
//! ```
//! or several as `[[operation]]` tables with the same keys and a `name`, each selected in a
//! program by `tool_number = 2` (the G-code `T2` word), or `lines = [first, last]` (the lines of
//! the motion instructions of a robot program it covers). A drilling operation has
//! `[tool] diameter_mm`, `[cut] feed_per_rev_mm` and `[coefficients] specific_energy_n_per_mm2,
//! specific_thrust_n_per_mm2`.
//! A milling operation may let the tool axis lean from the program's own within a cone (ball-end
//! milling, deburring), which `compensate --free lead-tilt` uses
//! ([`crate::compensate::FreeVariables::lead_tilt`]):
//! ```toml
//! [tool_axis]
//! cone_deg = 10                    # the cone's half angle, [0, 30] deg
//! ```
//! (`[operation.tool_axis]` in an `[[operation]]` table). A drilling operation that gives one is
//! refused: a drill's axis is the hole's.
//! A G-code program's tool length offsets (`G43 Hn`, `G44`, `G49`) are read with the tools'
//! lengths, each operation's `[tool] length_mm` (optional: from the spindle's gauge line to the
//! tip, as the CNC's tool table has it) for its `tool_number` ([`crate::gcode::Machine`]):
//! `G43 H` of the tool in use programs its tip, the setup's `[tool] tcp_mm`.
//! Where the workpiece sits is the cell's, not the process's: `[workpiece] base_from_part` is a
//! field of the setup ([`stiffid_core::setup`]); a process file that has one is refused, saying so.
//!
//! # Limits
//! `diameter_mm` (0, 200]; `length_mm` (0, 1000]; `flutes` 1..=12; `helix_deg` [-60, 60];
//! `feed_per_tooth_mm` and `feed_per_rev_mm` (0, 5]; `spindle_rpm` [1, 100000]; `axial_depth_mm`
//! (0, 200]; `radial_depth_mm` (0, diameter_mm]; cutting coefficients and specific energies [0,
//! 20000] N/mm^2 (`k_ac` [-20000, 20000]); edge coefficients [0, 1000] N/mm (`k_ae` [-1000, 1000]);
//! at most 1000 operations; `lines` two 1-based line numbers, first <= last; `tool_axis.cone_deg`
//! [0, 30] (30 deg).
//!
//! # Ambiguity
//! Two operations with the same name, the same `tool_number` or overlapping `lines` are refused
//! naming both: a program could not tell which one covers a point. Operations without a selector
//! are chosen by name (`(operation: NAME)`); with several of them, a point that names none is
//! refused naming its line.
//! Every key is checked: a key the operation's kind does not take (a drilling operation's
//! `flutes`) or a single operation's key beside `[[operation]]` tables is refused.

use super::drilling::Drilling;
use super::milling::{Coefficients, Milling, Mode};
use super::{presets, Operation, Process, Selector};
use serde::Deserialize;
use stiffid_core::common::limits::{self, Range};
use stiffid_core::{Error, Result};

/// The most operations a process file may hold.
pub(crate) const MAX_OPERATIONS: usize = 1000;

const DIAMETER: Range = Range::new(1e-3, 200.0, "mm");
const FLUTES: Range = Range::new(1.0, 12.0, "");
const HELIX: Range = Range::new(-60.0, 60.0, "deg");
const FEED: Range = Range::new(1e-6, 5.0, "mm");
const DEPTH: Range = Range::new(1e-6, 200.0, "mm");
const CUTTING: Range = Range::new(0.0, 2e4, "N/mm^2");
const CUTTING_SIGNED: Range = Range::new(-2e4, 2e4, "N/mm^2");
const SPINDLE: Range = Range::new(1.0, 1e5, "rpm");
const EDGE: Range = Range::new(0.0, 1e3, "N/mm");
const EDGE_SIGNED: Range = Range::new(-1e3, 1e3, "N/mm");
const LENGTH: Range = Range::new(1e-3, 1000.0, "mm");
const CONE: Range = Range::new(0.0, crate::compensate::LEAD_TILT_MAX_CONE_DEG, "deg");

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileToml {
    workpiece: Option<toml::Value>,
    name: Option<String>,
    kind: Option<String>,
    tool_number: Option<u32>,
    lines: Option<Vec<u64>>,
    tool: Option<ToolToml>,
    cut: Option<CutToml>,
    coefficients: Option<CoefficientsToml>,
    tool_axis: Option<ToolAxisToml>,
    operation: Option<Vec<OperationToml>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OperationToml {
    name: Option<String>,
    kind: Option<String>,
    tool_number: Option<u32>,
    lines: Option<Vec<u64>>,
    tool: ToolToml,
    cut: CutToml,
    coefficients: CoefficientsToml,
    tool_axis: Option<ToolAxisToml>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ToolAxisToml {
    cone_deg: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ToolToml {
    diameter_mm: f64,
    length_mm: Option<f64>,
    flutes: Option<u32>,
    helix_deg: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CutToml {
    feed_per_tooth_mm: Option<f64>,
    axial_depth_mm: Option<f64>,
    radial_depth_mm: Option<f64>,
    mode: Option<String>,
    feed_per_rev_mm: Option<f64>,
    spindle_rpm: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct CoefficientsToml {
    preset: Option<String>,
    k_tc_n_per_mm2: Option<f64>,
    k_rc_n_per_mm2: Option<f64>,
    k_ac_n_per_mm2: Option<f64>,
    k_te_n_per_mm: Option<f64>,
    k_re_n_per_mm: Option<f64>,
    k_ae_n_per_mm: Option<f64>,
    specific_energy_n_per_mm2: Option<f64>,
    specific_thrust_n_per_mm2: Option<f64>,
}

/// Parses a process file (module docs); `source_name` names it in errors.
///
/// # Errors
/// [`Error::Parse`] for malformed TOML, unknown or missing keys and wrong types;
/// [`Error::InvalidField`] naming the field (`source: operation[2].cut.axial_depth_mm`) for a value
/// outside its range, an unknown preset or kind, or a field the kind does not take.
pub fn parse(text: &str, source_name: &str) -> Result<Process> {
    let file: FileToml = toml::from_str(text).map_err(|e| Error::Parse {
        source_name: source_name.to_string(),
        message: limits::one_line(&e.to_string()),
    })?;
    let in_file = |e: Error| match e {
        Error::InvalidField { field, message } => Error::InvalidField {
            field: format!("{source_name}: {field}"),
            message,
        },
        other => other,
    };
    process(file).map_err(in_file)
}

fn process(file: FileToml) -> Result<Process> {
    if file.workpiece.is_some() {
        return Err(invalid(
            "workpiece",
            "the part frame belongs to the setup: move [workpiece] base_from_part into the setup file",
        ));
    }
    let top_level = [
        ("name", file.name.is_some()),
        ("kind", file.kind.is_some()),
        ("tool_number", file.tool_number.is_some()),
        ("lines", file.lines.is_some()),
        ("coefficients", file.coefficients.is_some()),
        ("tool_axis", file.tool_axis.is_some()),
    ];
    let tables = match (file.operation, file.tool, file.cut) {
        (Some(list), None, None) if !top_level.iter().any(|(_, given)| *given) => list
            .into_iter()
            .enumerate()
            .map(|(i, o)| (format!("operation[{}].", i + 1), o))
            .collect(),
        (None, Some(tool), Some(cut)) => {
            let single = OperationToml {
                name: file.name,
                kind: file.kind,
                tool_number: file.tool_number,
                lines: file.lines,
                tool,
                cut,
                coefficients: file.coefficients.unwrap_or_default(),
                tool_axis: file.tool_axis,
            };
            vec![(String::new(), single)]
        }
        (Some(_), tool, cut) => {
            let field = match (tool, cut) {
                (Some(_), _) => "tool",
                (_, Some(_)) => "cut",
                _ => top_level
                    .iter()
                    .find(|(_, given)| *given)
                    .map_or("operation", |(f, _)| f),
            };
            return Err(invalid(field, "a key of a single operation beside [[operation]] tables: give either [[operation]] tables (each with its own name, kind, selector, tool, cut and coefficients) or one operation at the top level, not both"));
        }
        _ => {
            return Err(invalid(
                "tool",
                "missing: expected [tool] and [cut] (one operation) or [[operation]] tables",
            ))
        }
    };
    if tables.is_empty() || tables.len() > MAX_OPERATIONS {
        return Err(invalid(
            "operation",
            &format!(
                "{} operations: expected 1 to {MAX_OPERATIONS}",
                tables.len()
            ),
        ));
    }
    let operations = tables
        .into_iter()
        .enumerate()
        .map(|(i, (prefix, t))| operation(i, &prefix, t))
        .collect::<Result<Vec<_>>>()?;
    unambiguous(&operations)?;
    Ok(Process { operations })
}

/// Refuses two operations a program could not tell apart: the same name, the same
/// `tool_number` or overlapping `lines`. Several without a selector are each chosen by name
/// (`(operation: NAME)`); a point that names none is refused where it needs one.
fn unambiguous(operations: &[Operation]) -> Result<()> {
    let label = |i: usize| match operations.len() {
        1 => String::new(),
        _ => format!("operation[{}]", i + 1),
    };
    for (j, b) in operations.iter().enumerate() {
        for (i, a) in operations[..j].iter().enumerate() {
            let (sa, sb) = (&a.selector, &b.selector);
            let clash = if a.name == b.name {
                Some(format!("the name '{}'", limits::short(&a.name)))
            } else if sa.tool_number.is_some() && sa.tool_number == sb.tool_number {
                Some(format!("tool_number = {}", sa.tool_number.unwrap_or(0)))
            } else if let (Some((a0, a1)), Some((b0, b1))) = (sa.lines, sb.lines) {
                (a0 <= b1 && b0 <= a1)
                    .then(|| format!("overlapping lines [{a0}, {a1}] and [{b0}, {b1}]"))
            } else {
                None
            };
            if let Some(clash) = clash {
                return Err(invalid(
                    &label(j),
                    &format!(
                        "{} and {} share {clash}: a program could not tell which covers a point; give each its own name and selector (at most one operation without one)",
                        label(i),
                        label(j)
                    ),
                ));
            }
        }
    }
    Ok(())
}

fn invalid(field: &str, message: &str) -> Error {
    Error::InvalidField {
        field: field.into(),
        message: message.into(),
    }
}

/// `value` checked against `range`, in the file's unit.
fn ranged(prefix: &str, field: &str, value: f64, range: &Range) -> Result<f64> {
    limits::check(&format!("{prefix}{field}"), &[value], range)?;
    Ok(value)
}

fn required(prefix: &str, field: &str, value: Option<f64>, range: &Range) -> Result<f64> {
    let v = value.ok_or_else(|| invalid(&format!("{prefix}{field}"), "missing"))?;
    ranged(prefix, field, v, range)
}

fn operation(i: usize, prefix: &str, t: OperationToml) -> Result<Operation> {
    let name = t.name.clone().unwrap_or_else(|| (i + 1).to_string());
    let lines = match t.lines.as_deref() {
        None => None,
        Some(&[first, last]) if first >= 1 && first <= last => Some((first, last)),
        Some(other) => {
            return Err(invalid(
                &format!("{prefix}lines"),
                &format!(
                    "{other:?}: expected [first, last] (two line numbers) with 1 <= first <= last"
                ),
            ))
        }
    };
    let selector = Selector {
        tool_number: t.tool_number,
        lines,
    };
    let diameter = ranged(prefix, "tool.diameter_mm", t.tool.diameter_mm, &DIAMETER)?;
    let kind = match t.kind.as_deref().unwrap_or("milling") {
        "milling" => super::Kind::Milling(milling(prefix, diameter, &t)?),
        "drilling" => super::Kind::Drilling(drilling(prefix, diameter, &t)?),
        other => {
            return Err(invalid(
                &format!("{prefix}kind"),
                &format!("'{}': expected milling or drilling", limits::short(other)),
            ))
        }
    };
    let cone = cone(prefix, &kind, t.tool_axis.as_ref())?;
    let tool_length = match t.tool.length_mm {
        Some(l) => Some(ranged(prefix, "tool.length_mm", l, &LENGTH)? * 1e-3),
        None => None,
    };
    Ok(Operation {
        tool_length,
        name,
        selector,
        kind,
        cone,
    })
}

/// The operation's cone, rad: `[tool_axis] cone_deg` within [`CONE`] for milling (0 without),
/// refused for drilling.
fn cone(prefix: &str, kind: &super::Kind, axis: Option<&ToolAxisToml>) -> Result<f64> {
    let Some(axis) = axis else { return Ok(0.0) };
    if matches!(kind, super::Kind::Drilling(_)) {
        return Err(invalid(
            &format!("{prefix}tool_axis.cone_deg"),
            "a drilling operation's tool axis is the hole's: it cannot lean (a cone is for milling: ball-end milling, deburring)",
        ));
    }
    Ok(ranged(prefix, "tool_axis.cone_deg", axis.cone_deg, &CONE)?.to_radians())
}

fn milling(prefix: &str, diameter: f64, t: &OperationToml) -> Result<Milling> {
    let c = &t.cut;
    let flutes = t
        .tool
        .flutes
        .ok_or_else(|| invalid(&format!("{prefix}tool.flutes"), "missing"))?;
    ranged(prefix, "tool.flutes", flutes as f64, &FLUTES)?;
    let helix = ranged(
        prefix,
        "tool.helix_deg",
        t.tool.helix_deg.unwrap_or(0.0),
        &HELIX,
    )?;
    let radial_range = Range::new(1e-6, diameter, "mm (at most diameter_mm)");
    let mode = match c.mode.as_deref() {
        Some("up") => Mode::Up,
        Some("down") => Mode::Down,
        Some(other) => {
            return Err(invalid(
                &format!("{prefix}cut.mode"),
                &format!("'{}': expected up or down", limits::short(other)),
            ))
        }
        None => {
            return Err(invalid(
                &format!("{prefix}cut.mode"),
                "missing: expected up or down",
            ))
        }
    };
    if c.feed_per_rev_mm.is_some() {
        return Err(invalid(
            &format!("{prefix}cut.feed_per_rev_mm"),
            "a drilling field: milling takes feed_per_tooth_mm",
        ));
    }
    Ok(Milling {
        diameter: diameter * 1e-3,
        flutes,
        helix: helix.to_radians(),
        feed_per_tooth: required(prefix, "cut.feed_per_tooth_mm", c.feed_per_tooth_mm, &FEED)?
            * 1e-3,
        axial_depth: required(prefix, "cut.axial_depth_mm", c.axial_depth_mm, &DEPTH)? * 1e-3,
        radial_depth: required(
            prefix,
            "cut.radial_depth_mm",
            c.radial_depth_mm,
            &radial_range,
        )? * 1e-3,
        mode,
        coefficients: coefficients(prefix, &t.coefficients)?,
        spindle_speed: c
            .spindle_rpm
            .map(|n| ranged(prefix, "cut.spindle_rpm", n, &SPINDLE))
            .transpose()?
            .map(|n| n / 60.0),
    })
}

fn coefficients(prefix: &str, k: &CoefficientsToml) -> Result<Coefficients> {
    let base = match &k.preset {
        None => None,
        Some(name) => Some(presets::find(name).ok_or_else(|| {
            let known: Vec<&str> = presets::PRESETS.iter().map(|p| p.name).collect();
            invalid(
                &format!("{prefix}coefficients.preset"),
                &format!(
                    "unknown preset '{}' (known: {})",
                    limits::short(name),
                    known.join(", ")
                ),
            )
        })?),
    };
    let p = base.map(|p| p.coefficients);
    let pick = |field: &str, given: Option<f64>, preset: Option<f64>, scale: f64, range: &Range| {
        let full = format!("coefficients.{field}");
        match (given, preset) {
            (Some(v), _) => Ok(ranged(prefix, &full, v, range)? * scale),
            (None, Some(v)) => Ok(v),
            (None, None) => Err(invalid(
                &format!("{prefix}{full}"),
                "missing (or give a preset)",
            )),
        }
    };
    if k.specific_energy_n_per_mm2.is_some() || k.specific_thrust_n_per_mm2.is_some() {
        return Err(invalid(
            &format!("{prefix}coefficients.specific_energy_n_per_mm2"),
            "a drilling field: milling takes k_tc_n_per_mm2 .. k_ae_n_per_mm",
        ));
    }
    Ok(Coefficients {
        k_tc: pick(
            "k_tc_n_per_mm2",
            k.k_tc_n_per_mm2,
            p.map(|c| c.k_tc),
            1e6,
            &CUTTING,
        )?,
        k_rc: pick(
            "k_rc_n_per_mm2",
            k.k_rc_n_per_mm2,
            p.map(|c| c.k_rc),
            1e6,
            &CUTTING,
        )?,
        k_ac: pick(
            "k_ac_n_per_mm2",
            k.k_ac_n_per_mm2,
            p.map(|c| c.k_ac),
            1e6,
            &CUTTING_SIGNED,
        )?,
        k_te: pick(
            "k_te_n_per_mm",
            k.k_te_n_per_mm,
            p.map(|c| c.k_te),
            1e3,
            &EDGE,
        )?,
        k_re: pick(
            "k_re_n_per_mm",
            k.k_re_n_per_mm,
            p.map(|c| c.k_re),
            1e3,
            &EDGE,
        )?,
        k_ae: pick(
            "k_ae_n_per_mm",
            k.k_ae_n_per_mm,
            p.map(|c| c.k_ae),
            1e3,
            &EDGE_SIGNED,
        )?,
    })
}

fn drilling(prefix: &str, diameter: f64, t: &OperationToml) -> Result<Drilling> {
    let c = &t.cut;
    let k = &t.coefficients;
    let milling_only = [
        ("cut.feed_per_tooth_mm", c.feed_per_tooth_mm.is_some()),
        ("cut.axial_depth_mm", c.axial_depth_mm.is_some()),
        ("cut.radial_depth_mm", c.radial_depth_mm.is_some()),
        ("cut.mode", c.mode.is_some()),
        ("cut.spindle_rpm", c.spindle_rpm.is_some()),
        ("tool.flutes", t.tool.flutes.is_some()),
        ("tool.helix_deg", t.tool.helix_deg.is_some()),
        ("coefficients.preset", k.preset.is_some()),
        ("coefficients.k_tc_n_per_mm2", k.k_tc_n_per_mm2.is_some()),
        ("coefficients.k_rc_n_per_mm2", k.k_rc_n_per_mm2.is_some()),
        ("coefficients.k_ac_n_per_mm2", k.k_ac_n_per_mm2.is_some()),
        ("coefficients.k_te_n_per_mm", k.k_te_n_per_mm.is_some()),
        ("coefficients.k_re_n_per_mm", k.k_re_n_per_mm.is_some()),
        ("coefficients.k_ae_n_per_mm", k.k_ae_n_per_mm.is_some()),
    ];
    if let Some((field, _)) = milling_only.iter().find(|(_, given)| *given) {
        return Err(invalid(
            &format!("{prefix}{field}"),
            "a milling field: drilling takes tool.diameter_mm, cut.feed_per_rev_mm and coefficients.specific_energy_n_per_mm2, specific_thrust_n_per_mm2",
        ));
    }
    Ok(Drilling {
        diameter: diameter * 1e-3,
        feed_per_rev: required(prefix, "cut.feed_per_rev_mm", c.feed_per_rev_mm, &FEED)? * 1e-3,
        specific_energy: required(
            prefix,
            "coefficients.specific_energy_n_per_mm2",
            k.specific_energy_n_per_mm2,
            &CUTTING,
        )? * 1e6,
        specific_thrust: required(
            prefix,
            "coefficients.specific_thrust_n_per_mm2",
            k.specific_thrust_n_per_mm2,
            &CUTTING,
        )? * 1e6,
    })
}
