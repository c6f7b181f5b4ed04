//! `[workpiece]`'s fields for a G-code program as a controller runs it: the frames of the work
//! offsets other than `G54` (and of `G53`, the machine coordinates), where the tool is when the
//! program starts, and the `G28`/`G30` positions ([`ProgramFrames`]).
//!
//! ```toml
//! [workpiece]
//! base_from_part = { xyz_mm = [1200, 0, 300], rpy_deg = [0, 0, 0] }   # G54
//! start_mm = [0, 0, 100]          # the tool tip when the program starts, G54 frame
//! g28_mm = [0, 0, 150]            # the tool tip at the G28 position, G54 frame
//! tool_rpy_deg = [180, 0, 0]      # the tool frame in the part frame (tool down the part's -Z)
//! [workpiece.offsets]
//! G55 = { xyz_mm = [300, 0, 0], rpy_deg = [0, 0, 0] }   # G55's frame in G54's
//! "G54.1 P2" = { xyz_mm = [0, 250, 0] }
//! ```
//! Offsets are named as a program writes them: `G55`..`G59`, `G59.1`..`G59.3` (LinuxCNC's
//! manual, "Coordinate Systems"), `G54.1 P1`..`G54.1 P99` (FANUC's and Haas's additional work
//! offsets) and `G53` (the machine coordinates); `G54` is `base_from_part` itself. Each is the
//! offset's frame in the `G54` part frame, the translation within `limits::LENGTH_MM`.

use crate::common::limits;
use crate::{Error, Result};
use nalgebra::{Isometry3, UnitQuaternion, Vector3};

/// The highest `P` of an additional work offset `G54.1 P..` (Haas's 99; FANUC's 48 or 300).
pub(crate) const MAX_EXTENDED_OFFSET: u32 = 99;

/// The most work offsets `[workpiece.offsets]` may give (`G53`, `G55`..`G59.3` and every
/// `G54.1 P..`).
pub(crate) const MAX_OFFSETS: usize = 9 + MAX_EXTENDED_OFFSET as usize;

/// `[workpiece]`'s fields for a G-code program (module docs): all in the `G54` part frame
/// (`base_from_part`), m; all optional.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ProgramFrames {
    /// Each work offset given, by its canonical name (`offset_name`), with its frame in the
    /// `G54` part frame (`part_from_offset`), m.
    pub offsets: Vec<(String, Isometry3<f64>)>,
    /// The tool tip (the TCP) when the program starts, `G54` part frame, m.
    pub start: Option<Vector3<f64>>,
    /// The tool tip at the `G28` position, `G54` part frame, m.
    pub g28: Option<Vector3<f64>>,
    /// The tool tip at the `G30` position, `G54` part frame, m.
    pub g30: Option<Vector3<f64>>,
    /// The tool frame in the `G54` part frame for a program whose header does not state it
    /// (`tool_rpy_deg`, fixed-axis roll-pitch-yaw; `[180, 0, 0]` points the tool down the
    /// part's -Z).
    pub tool: Option<UnitQuaternion<f64>>,
}

impl ProgramFrames {
    /// The frame of the offset named `name` (canonical, `offset_name`) in the `G54` part
    /// frame: the identity for `G54`, `None` when the setup does not give it.
    pub fn offset(&self, name: &str) -> Option<Isometry3<f64>> {
        if name == "G54" {
            return Some(Isometry3::identity());
        }
        self.offsets
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, f)| *f)
    }
}

/// The canonical name of a work offset as a setup or a program writes it (`g55`, `G59.1`,
/// `G54.1 P2`, `G54.1P2`, `G53`), or `None` for anything else (`G54.1 P0`, `G60`).
pub(crate) fn offset_name(text: &str) -> Option<String> {
    let t: String = text
        .split_whitespace()
        .collect::<String>()
        .to_ascii_uppercase();
    let t = t.strip_prefix('G')?;
    if let Some(p) = t.strip_prefix("54.1P") {
        let n: u32 = p
            .parse()
            .ok()
            .filter(|n| (1..=MAX_EXTENDED_OFFSET).contains(n))?;
        return Some(format!("G54.1 P{n}"));
    }
    match t {
        "53" | "54" | "55" | "56" | "57" | "58" | "59" | "59.1" | "59.2" | "59.3" => {
            Some(format!("G{t}"))
        }
        _ => None,
    }
}

/// `[workpiece]`'s `offsets` table and `[start_mm, g28_mm, g30_mm, tool_rpy_deg]` read and checked (module
/// docs).
///
/// # Errors
/// [`Error::InvalidField`] naming the field (`workpiece.offsets.G60`,
/// `workpiece.offsets.G55.xyz_mm`, `workpiece.start_mm`) for a name that is no work offset, a
/// name given twice (`G55` and `g55`), `G54` (that is `base_from_part`), more than
/// [`MAX_OFFSETS`], or a value outside its range.
pub(super) fn read(
    offsets: &std::collections::BTreeMap<String, crate::robot::file::TransformFile>,
    [start, g28, g30, tool]: [Option<[f64; 3]>; 4],
) -> Result<ProgramFrames> {
    let invalid = |field: String, message: String| Error::InvalidField { field, message };
    if offsets.len() > MAX_OFFSETS {
        return Err(invalid(
            "workpiece.offsets".into(),
            format!("at most {MAX_OFFSETS} work offsets"),
        ));
    }
    let mut out = ProgramFrames::default();
    for (key, t) in offsets {
        let field = format!("workpiece.offsets.{}", limits::short(key));
        let name = offset_name(key).ok_or_else(|| invalid(field.clone(), format!("expected a work offset as a program names it: G53 (machine coordinates), G55 to G59, G59.1 to G59.3 or G54.1 P1 to G54.1 P{MAX_EXTENDED_OFFSET}")))?;
        if name == "G54" {
            return Err(invalid(
                field,
                "G54 is the part frame itself: give it as [workpiece] base_from_part".into(),
            ));
        }
        if out.offsets.iter().any(|(n, _)| *n == name) {
            return Err(invalid(field, format!("{name} given twice")));
        }
        limits::check(&format!("{field}.xyz_mm"), &t.xyz_mm, &limits::LENGTH_MM)?;
        limits::check(&format!("{field}.rpy_deg"), &t.rpy_deg, &limits::ANGLE_DEG)?;
        out.offsets.push((name, t.isometry()));
    }
    let position = |name: &str, v: Option<[f64; 3]>| -> Result<Option<Vector3<f64>>> {
        let Some(v) = v else { return Ok(None) };
        limits::check(&format!("workpiece.{name}"), &v, &limits::LENGTH_MM)?;
        Ok(Some(Vector3::from(v) * 1e-3))
    };
    out.start = position("start_mm", start)?;
    out.g28 = position("g28_mm", g28)?;
    out.g30 = position("g30_mm", g30)?;
    if let Some(rpy) = tool {
        limits::check("workpiece.tool_rpy_deg", &rpy, &limits::ANGLE_DEG)?;
        let [r, p, y] = rpy.map(f64::to_radians);
        out.tool = Some(UnitQuaternion::from_euler_angles(r, p, y));
    }
    Ok(out)
}
