//! What a controller knows beyond the program's text, and the frames a program's coordinates
//! are in: the setup's work offsets, start and home positions ([`ProgramFrames`]), the process's
//! tool lengths, and how a position moves from one frame to another (a work offset `G54`-`G59.3`,
//! `G54.1 Pn` or `G53` chosen, a tool length offset `G43`/`G44`/`G49` put in force).
//!
//! Every position of the path is the tool tip (the setup's TCP) in the `G54` part frame. A
//! program's coordinates are those of the controlled point in the frame in force, the tool
//! length offset in force applied as LinuxCNC and FANUC apply it, along the frame's `Z`: with
//! `h` the offset in force (`G43 Hn`: tool `n`'s length; `G44 Hn`: minus it; `G49`: 0) and `L`
//! the length of the tool in use (`T`), the tip is at the programmed point `+ (h - L) Z`; with
//! `G43 H` of the tool in use, the programmed point is the tip. A `G53` block's coordinates are
//! the spindle's gauge line in machine coordinates, the offset not applied (`h = 0` under `G43`
//! and `G49` alike, as LinuxCNC and FANUC). A process without tool lengths
//! reads every program as the tip's path (`G43`/`G44` refused).

use nalgebra::{Isometry3, Translation3, Vector3};
pub use stiffid_core::setup::{GcodeDialect, ProgramFrames};

/// What the controller knows beyond the text (module docs); the default knows nothing: `G54`
/// is the part frame, the start is unknown, no tool has a length.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Machine {
    /// The setup's `[workpiece]` offsets, start and home positions and tool orientation.
    pub frames: ProgramFrames,
    /// The tool table: per tool number (`T`) its length from the spindle's gauge line to the
    /// tip, m; a `None` number is the length of every tool (a process of one operation
    /// without a `tool_number`). Empty: no tool length offsets (module docs).
    pub tool_lengths: Vec<(Option<u32>, f64)>,
    /// Per tool number its radius, m (the process's `[tool] diameter_mm` / 2; a `None` number
    /// every tool's): what cutter radius compensation `G41`/`G42` offsets by. Empty: `G41`/`G42`
    /// refused.
    pub tool_radii: Vec<(Option<u32>, f64)>,
    /// The controller's wear offsets of the tools' radii, by the number `D` names (the setup's
    /// `[controller] radius_wear_mm`), m: added to the process's radius under `G41`/`G42`.
    pub radius_wear: Vec<(u32, f64)>,
    /// The controller the program is written for (`[controller] dialect`), where controllers
    /// read the same words differently (module `dialect`); `None`: the setup does not say, and
    /// a block whose reading depends on it is refused.
    pub dialect: Option<GcodeDialect>,
}

impl Machine {
    /// What `setup`'s `[workpiece]` and `process`'s tool lengths tell.
    pub fn of(setup: &stiffid_core::Setup, process: Option<&crate::process::Process>) -> Self {
        Machine {
            frames: setup.workcell().program_frames().clone(),
            tool_lengths: process.map(|p| p.tool_lengths()).unwrap_or_default(),
            tool_radii: process.map(|p| p.tool_radii()).unwrap_or_default(),
            radius_wear: setup.workcell().controller().radius_wear.clone(),
            dialect: setup.workcell().controller().dialect,
        }
    }

    /// The length of tool `n` (m), `None` when the table lacks it.
    pub(crate) fn tool_length(&self, n: Option<u32>) -> Option<f64> {
        let exact = n.and_then(|n| self.tool_lengths.iter().find(|(t, _)| *t == Some(n)));
        exact
            .or_else(|| self.tool_lengths.iter().find(|(t, _)| t.is_none()))
            .map(|(_, l)| *l)
    }
}

/// A coordinate frame of the program: the part frame of a work offset (or `G53`), in the `G54`
/// part frame, and its name.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Frame {
    pub(super) name: String,
    pub(super) part_from: Isometry3<f64>,
}

impl Default for Frame {
    fn default() -> Self {
        Frame {
            name: "G54".into(),
            part_from: Isometry3::identity(),
        }
    }
}

/// How the tip sits from the programmed point along the frame's `Z`, m (`h - L`, module docs);
/// `None` when the tool in use has no length in the table.
pub(super) type Lift = Option<f64>;

/// The programmed coordinates of the tip `tip` (`G54` part frame, m) in `frame` with `lift`.
pub(super) fn to_program(frame: &Frame, lift: f64) -> Isometry3<f64> {
    Translation3::new(0.0, 0.0, -lift) * frame.part_from.inverse()
}

/// A position known per axis in `from` (with its lift) expressed in `to` (with its): exact
/// when every axis and both lifts are known; axis by axis when the frames are parallel (a work
/// offset that only shifts keeps the axes known, `Z` only with both lifts known or equal); else
/// nothing known.
pub(super) fn convert(
    (p, known): (Vector3<f64>, [bool; 3]),
    (from, lift_from): (&Frame, Lift),
    (to, lift_to): (&Frame, Lift),
) -> (Vector3<f64>, [bool; 3]) {
    if let (true, Some(a), Some(b)) = (known.iter().all(|k| *k), lift_from, lift_to) {
        let tip = from.part_from * nalgebra::Point3::from(p + Vector3::z() * a);
        return ((to_program(to, b) * tip).coords, known);
    }
    let relative = to.part_from.inverse() * from.part_from;
    if relative.rotation.angle() > 1e-12 {
        return (p, [false; 3]);
    }
    let dz = match (lift_from, lift_to) {
        (Some(a), Some(b)) => Some(a - b),
        // The same tool and offset on both sides: the lift cancels.
        _ if lift_from == lift_to => Some(0.0),
        _ => None,
    };
    let shifted = p + relative.translation.vector + Vector3::z() * dz.unwrap_or(0.0);
    (shifted, [known[0], known[1], known[2] && dz.is_some()])
}
