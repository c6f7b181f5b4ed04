//! Process forces: the cutting force and moment a machining operation puts on the tool, from the
//! tool, the cut and the material.
//!
//! - `milling`: the mechanistic model with linear edge forces (Altintas, *Manufacturing
//!   Automation*, 2nd ed., 2012, ch. 2.4): mean force over a revolution in closed form, the
//!   instantaneous force and its peak.
//! - `drilling`: thrust and torque from a specific-energy model.
//! - `presets`: cutting coefficients of common materials, each with its published source.
//! - [`mod@file`]: the process file (TOML) that names the operations of a job.
//!
//! ## The feed frame
//! Forces are computed in the feed frame of the cut: `x` along the feed, `z` along the tool axis
//! from the tip towards the spindle, `y = z x x` (the material of up milling is on `+y`); the tool
//! turns clockwise seen from the spindle (M03). The tool frame of stiffid's setups has its `z` axis
//! out of the flange, from the spindle towards the tip, so the feed frame's `z` is the tool's `-z`.
//! `feed_frame` builds the feed frame in the robot base frame from the path's own feed direction
//! (the TCP's motion) and the tool axis, and `Operation::base_wrench` turns the operation's
//! mean force and moment into the base-frame wrench on the tool that compensation takes.

pub(crate) mod covering;
pub(crate) mod drilling;
pub mod file;
pub(crate) mod milling;
pub(crate) mod presets;

use nalgebra::{Matrix3, Rotation3, Vector3, Vector6};
use serde::Serialize;
use stiffid_core::{Error, Result};

/// The operations of a machining job (a parsed process file).
#[derive(Debug, Clone, PartialEq)]
pub struct Process {
    /// The operations, in file order.
    pub operations: Vec<Operation>,
}

/// Which blocks of a program an operation covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Selector {
    /// The G-code tool number (`T` word) that selects it.
    pub tool_number: Option<u32>,
    /// The robot program lines it covers, 1-based, inclusive.
    pub lines: Option<(u64, u64)>,
}

/// One operation: its name, what selects it in a program, and the process.
#[derive(Debug, Clone, PartialEq)]
pub struct Operation {
    /// Its name (`name`, else its 1-based number).
    pub name: String,
    /// Which blocks it covers.
    pub selector: Selector,
    /// Milling or drilling.
    pub kind: Kind,
    /// The half angle of the cone the tool axis may lean within about the program's own, rad
    /// (`[tool_axis] cone_deg`, [`mod@file`]; 0: no lean, always for drilling), which
    /// `compensate --free lead-tilt` uses ([`crate::compensate::FreeVariables::lead_tilt`]).
    pub cone: f64,
    /// The tool's length from the spindle's gauge line to its tip as the CNC's tool table has
    /// it, m (`[tool] length_mm`): what a G-code program's tool length offsets `G43`/`G44`/`G49`
    /// are read with ([`crate::gcode::Machine`]); `None` when not given.
    pub tool_length: Option<f64>,
}

impl Process {
    /// The tool table of its operations that give `[tool] length_mm`: per `tool_number` (none:
    /// every tool's, an operation without one) the length, m.
    pub fn tool_lengths(&self) -> Vec<(Option<u32>, f64)> {
        (self.operations.iter())
            .filter_map(|o| Some((o.selector.tool_number, o.tool_length?)))
            .collect()
    }

    /// Each operation's tool number and its tool's radius (half its `diameter_mm`), m: what
    /// a G-code's cutter radius compensation (`G41`/`G42`) offsets the path by.
    pub(crate) fn tool_radii(&self) -> Vec<(Option<u32>, f64)> {
        (self.operations.iter())
            .map(|o| {
                let d = match &o.kind {
                    Kind::Milling(m) => m.diameter,
                    Kind::Drilling(d) => d.diameter,
                };
                (o.selector.tool_number, d / 2.0)
            })
            .collect()
    }
}

/// The process of an operation.
#[derive(Debug, Clone, PartialEq)]
pub enum Kind {
    /// Milling with the linear edge-force model.
    Milling(milling::Milling),
    /// Drilling with the specific-energy model.
    Drilling(drilling::Drilling),
}

impl Operation {
    /// The mean force (N) and moment (Nm) on the tool, feed frame.
    pub(crate) fn mean_wrench(&self) -> (Vector3<f64>, Vector3<f64>) {
        match &self.kind {
            Kind::Milling(m) => (m.mean_force(), m.mean_moment()),
            Kind::Drilling(d) => (d.force(), d.moment()),
        }
    }

    /// The mean wrench `[f; m]` on the tool in the base frame, for a cut fed along `feed` (base
    /// frame, any length) with the tool z axis `tool_z` (base frame, unit, spindle to tip); `None`
    /// for a milling cut fed along the tool axis (a plunge: no lateral feed to define the frame).
    pub(crate) fn base_wrench(
        &self,
        feed: &Vector3<f64>,
        tool_z: &Vector3<f64>,
    ) -> Option<Vector6<f64>> {
        let frame = match &self.kind {
            Kind::Milling(_) => feed_frame(feed, tool_z)?,
            Kind::Drilling(_) => {
                let any = tool_z.cross(&Vector3::x()).norm() > 0.1;
                let side = if any { Vector3::x() } else { Vector3::y() };
                feed_frame(&side, tool_z)?
            }
        };
        let (f, m) = self.mean_wrench();
        let (f, m) = (frame * f, frame * m);
        Some(Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z))
    }
}

/// The largest part of a feed across the tool axis, relative to the feed, that is still a feed
/// along the axis (a plunge): 0.01, within 0.57 deg of the axis. A plunge written as a robot
/// program's targets stays one: rounded to their decimals, or to an INFORM job's whole pulses
/// (at 1000 pulses per degree, about 40 um on a 2.5 m reach, 0.4% of a 10 mm plunge).
pub(crate) const PLUNGE: f64 = 1e-2;

/// The feed frame in the base frame (module docs): `x` the part of `feed` across the tool axis,
/// `z = -tool_z`, `y = z x x`. `None` when `feed` has no part across the axis (relative
/// [`PLUNGE`]).
pub(crate) fn feed_frame(feed: &Vector3<f64>, tool_z: &Vector3<f64>) -> Option<Rotation3<f64>> {
    let z = -tool_z.normalize();
    let across = feed - z * feed.dot(&z);
    if across.norm() <= PLUNGE * feed.norm() || !across.norm().is_finite() {
        return None;
    }
    let x = across.normalize();
    let y = z.cross(&x);
    Some(Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[
        x, y, z,
    ])))
}

/// The forces of one operation, as `stiffid force` prints them.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct OperationForce {
    /// The operation's name.
    pub name: String,
    /// `milling` or `drilling`.
    pub kind: &'static str,
    /// The mean force on the tool over one revolution, feed frame `[feed, normal, axial]`, N.
    pub mean_force_n: [f64; 3],
    /// The mean moment on the tool about the tool tip, feed frame, Nm (milling: the cutting
    /// torque and the moments of the forces up the flutes; drilling: the torque about the axis).
    pub mean_moment_nm: [f64; 3],
    /// Milling, when asked: the force of largest magnitude over one revolution at the stated
    /// resolution, feed frame, N.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_force_n: Option<[f64; 3]>,
}

/// The forces of every operation; with `peak_resolution_deg` (the grid of spindle angles, deg,
/// 0.01 to 10) also the milling peak (`Milling::peak_force`).
///
/// # Errors
/// [`Error::InvalidField`] (`peak_resolution_deg`) for a resolution outside its range.
pub fn forces(process: &Process, peak_resolution_deg: Option<f64>) -> Result<Vec<OperationForce>> {
    use milling::{MAX_RESOLUTION_DEG, MIN_RESOLUTION_DEG};
    if let Some(deg) = peak_resolution_deg
        && !(MIN_RESOLUTION_DEG..=MAX_RESOLUTION_DEG).contains(&deg)
    {
        return Err(Error::InvalidField {
            field: "peak_resolution_deg".into(),
            message: format!(
                "{deg}: expected a number >= {MIN_RESOLUTION_DEG} and <= {MAX_RESOLUTION_DEG}"
            ),
        });
    }
    let peak_resolution = peak_resolution_deg.map(f64::to_radians);
    Ok(process
        .operations
        .iter()
        .map(|o| {
            let (f, m) = o.mean_wrench();
            let (kind, peak) = match &o.kind {
                Kind::Milling(mill) => (
                    "milling",
                    peak_resolution.map(|r| mill.peak_force(r).into()),
                ),
                Kind::Drilling(_) => ("drilling", None),
            };
            OperationForce {
                name: o.name.clone(),
                kind,
                mean_force_n: f.into(),
                mean_moment_nm: m.into(),
                peak_force_n: peak,
            }
        })
        .collect())
}

#[cfg(test)]
mod forces_tests;
