//! Cartesian targets of robot programs: a TCP pose in a frame the program names, with the
//! configuration data that picks one of the inverse-kinematics solutions of the pose.
//!
//! Read (each dialect's module says the forms):
//! - KUKA KRL: `PTP`/`LIN` to an aggregate `{X .., Y .., Z .., A .., B .., C .., S .., T ..}`
//!   (optionally typed `{E6POS: ..}`, `POS`, `FRAME`) or to a point declared in the file as
//!   `E6POS`/`POS`/`FRAME`; `S` and `T` as a binary string `'B110'` or a decimal number (as a
//!   `.dat` writes them); external axes `E1`.. as in joint targets. The frame is the `$BASE`
//!   assigned before the motion (a literal frame, or `$NULLFRAME`/`$WORLD`: the world), the tool
//!   the `$TOOL` assigned before it (a literal frame).
//! - ABB RAPID: `MoveL`/`MoveJ` (and `MoveC`'s circle point and end point) to a `robtarget`
//!   literal `[[x,y,z],[q1,q2,q3,q4],[cf1,cf4,cf6,cfx],[eax_a,..]]`, one declared in the module,
//!   or `Offs`/`RelTool` of one with constant arguments, with a `tooldata` declared in the module
//!   (its `tframe`) and `\WObj:=` a `wobjdata` declared in the module (`uframe` then `oframe`,
//!   `robhold FALSE`, `ufprog TRUE`), or `wobj0` / none: the world.
//! - FANUC LS: positions of `/POS` in Cartesian representation, `CONFIG : 'N U T, 0, 0, 0'`,
//!   `X = .. mm` to `R = .. deg` (`R = Rz(R) Ry(P) Rx(W)`), in `UF : 0` (the world) or the user
//!   frame `UF : n` (n >= 1), for the tool frame `UT : n`: frames the controller holds by number
//!   ([`Frame::Numbered`]: the setup's `[controller] bases` and `tools`), or the setup's own part
//!   frame and tool where a remark declares them ([`Frame::Declared`]); the `UFRAME_NUM` and
//!   `UTOOL_NUM` in force checked against each position's (the LS reader's `numbered` rule).
//!
//! A target's orientation is the tool frame's: the flange's turned by the setup's `[tool]
//! tcp_rpy_deg` (identity by default), the tool the program states (`tframe`, `$TOOL`) being
//! the setup's, position and orientation.
//!
//! A target without configuration data (a KRL `FRAME`, or `POS` without `S` and `T`) and a KRL
//! `LIN` (whose `S` and `T` a KUKA controller ignores) keep the configuration of the previous
//! target: its shoulder, elbow and wrist, each axis in the revolution nearest the previous
//! posture's. The first target must name one.
//!
//! ## Axis angles
//! A Cartesian target's axis angles are what the controller would move to: [`resolve`] runs
//! inverse kinematics in the controller's nominal kinematics ([`stiffid_core::Setup::controller_robot`])
//! and keeps the one solution whose configuration data are the target's
//! ([`stiffid_core::robot::configuration`]), the nearest the previous target's; then, when the setup's
//! robot is another (a calibrated one), the posture of the setup's robot that puts the tool on
//! the same pose, continued from it: the robot must land where the program says. Compensated,
//! a target is written back in its own form: the pose the controller must be told (the
//! forward kinematics of the compensated axis angles in the controller's kinematics, in the
//! target's frame) with the configuration data of the compensated posture, as the programs
//! written from G-code state it ([`super::generate`]).

pub(crate) mod computed;
pub mod flags;
pub(crate) mod literal;
mod relocate;
mod resolve;
mod same;
mod solve;

pub use flags::Flags;
pub(crate) use resolve::Writer;
pub use resolve::{check_part, resolve, Controller};
pub(crate) use resolve::{is_cartesian, resolve_placed};
pub(crate) use same::{same, SAME_M};

use super::generate::{number, zyx_deg};
use super::Dialect;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use std::ops::Range;
use stiffid_core::common::{limits, words};
use stiffid_core::robot::configuration::Configuration;

/// Refuses a pose's number outside the limits (`names` and `numbers` in the dialect's order):
/// a position (the first three) beyond [`limits::LENGTH_MM`], an angle (the others) beyond
/// [`limits::ANGLE_DEG`]. A position of 1e300 mm would reach inverse kinematics as an infinite
/// distance, an angle of 1e300 deg any orientation at all.
pub(crate) fn within_limits(
    line: u64,
    names: &[&str],
    numbers: &[(f64, Range<usize>)],
) -> stiffid_core::Result<()> {
    match outside_limits(names, numbers.iter().map(|(v, _)| *v)) {
        Some(message) => Err(super::at(line, message)),
        None => Ok(()),
    }
}

/// The first of a pose's `values` ([`within_limits`]) outside its limits, said: `X 1e300:
/// outside -100000 to 100000 mm`.
pub(crate) fn outside_limits(
    names: &[&str],
    values: impl IntoIterator<Item = f64>,
) -> Option<String> {
    (names.iter().zip(values).enumerate()).find_map(|(k, (name, v))| {
        let range = match k < 3 {
            true => &limits::LENGTH_MM,
            false => &limits::ANGLE_DEG,
        };
        let (shown, min, max) = (words::number(v), words::number(range.min), range.max);
        (!range.contains(v))
            .then(|| format!("{name} {shown}: outside {min} to {max} {}", range.unit))
    })
}

/// A frame a target is given in, or a tool it is given for, as the program states it.
#[derive(Debug, Clone, PartialEq)]
pub enum Frame {
    /// The controller's world (KRL `$NULLFRAME`/`$WORLD`, RAPID `wobj0` or no `\WObj`, LS
    /// `UF : 0`); for a tool, the flange itself (RAPID `tool0`).
    World,
    /// A frame the program states on `line` (KRL `$BASE`, `$TOOL`, RAPID `wobjdata`,
    /// `tooldata`): in the controller's world (a base, a work object) or flange (a tool), m.
    Stated(u64, Isometry3<f64>),
    /// A frame held on the controller by number (KRL `BASE_DATA[n]`, `TOOL_DATA[n]`, LS
    /// `UF : n`, `UT : n`), on `line`: read from the setup's `[controller] bases` or `tools`
    /// (`stiffid_core::setup::numbered`), refused where the setup does not give it.
    Numbered(u64, u32),
    /// A frame held on the controller by number whose value the controller's backup gives
    /// (FANUC `SYSFRAME.VA`): the line, the number, the frame (as
    /// [`Frame::Stated`]) and where the backup states it; refused where the setup's
    /// `[controller]` table gives that number another frame.
    Held(u64, u32, Isometry3<f64>, String),
    /// The setup's own frame of its role (its `[workpiece]` part frame for a base, its `[tool]`
    /// for a tool), which the program declares on `line` that its frame number `n` holds (an
    /// LS remark `! stiffid: user_frame = n ;` or `tool_frame = n`): where the setup's
    /// `[controller]` table gives `n` another frame, refused naming both.
    Declared(u64, u32),
    /// A frame the program leaves to the controller (not set, a variable, a number of the
    /// controller's table): the line of the motion and why.
    Unknown(u64, String),
}

/// A Cartesian target as the program gives it (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Cartesian {
    /// The TCP position in the target's frame, mm, as the program's numbers state it (a target
    /// displaced by an offset, RAPID `Offs` or `RelTool`: its base point's; [`Cartesian::pose`]
    /// is where the controller moves).
    pub position_mm: Vector3<f64>,
    /// The tool's orientation in the target's frame, likewise.
    pub rotation: UnitQuaternion<f64>,
    /// The displacement the motion applies in the target's frame before the stated pose
    /// (RAPID `Offs(p, x, y, z)`: a translation), m; identity without one.
    pub(crate) before: Isometry3<f64>,
    /// The displacement the motion applies in the tool's frame after the stated pose (RAPID
    /// `RelTool(p, x, y, z \Rx \Ry \Rz)`), m; identity without one.
    pub(crate) after: Isometry3<f64>,
    /// The configuration data; `None`: the previous target's (module docs).
    pub flags: Option<Flags>,
    /// The controller ignores the configuration data and continues from the previous posture
    /// (KRL `LIN`, `SLIN`: KUKA reads `S` and `T` for `PTP` only): its shoulder, elbow and
    /// wrist kept, each axis the revolution nearest the previous posture's.
    pub follows: bool,
    /// The frame the pose is in.
    pub frame: Frame,
    /// The tool the pose is of.
    pub tool: Frame,
    /// Where the pose's numbers sit in the text (bytes), in the dialect's order (KRL X, Y, Z,
    /// A, B, C; RAPID x, y, z, q1..q4; LS X, Y, Z, W, P, R).
    pub(crate) spans: Vec<Range<usize>>,
    /// Where the configuration data sit and how they are written.
    pub(crate) flag_spans: Vec<(Range<usize>, flags::Part)>,
    /// The frame in the setup's base frame, once resolved.
    pub(crate) base_from_frame: Option<Isometry3<f64>>,
}

impl Cartesian {
    /// A target of `pose` numbers read in `dialect`'s order (module docs of the dialects): the
    /// position (mm) then the orientation (KRL A, B, C deg; RAPID a quaternion; LS W, P, R deg).
    pub(crate) fn new(dialect: Dialect, numbers: &[(f64, Range<usize>)]) -> Self {
        let n: Vec<f64> = numbers.iter().map(|(v, _)| *v).collect();
        let rotation = dialect.controller().rotation(&n);
        Cartesian {
            position_mm: Vector3::new(n[0], n[1], n[2]),
            rotation,
            before: Isometry3::identity(),
            after: Isometry3::identity(),
            flags: None,
            follows: false,
            frame: Frame::World,
            tool: Frame::World,
            spans: numbers.iter().map(|(_, s)| s.clone()).collect(),
            flag_spans: Vec::new(),
            base_from_frame: None,
        }
    }

    /// The pose the controller moves the tool to, in the target's frame, m: the stated pose
    /// with its displacements (`before * stated * after`).
    pub fn pose(&self) -> Isometry3<f64> {
        let stated =
            Isometry3::from_parts(Translation3::from(self.position_mm * 1e-3), self.rotation);
        self.before * stated * self.after
    }

    /// The pose to state so that the displacements land the tool on `pose` (both in the
    /// target's frame, m): the inverse of [`Cartesian::pose`].
    pub(crate) fn stated(&self, pose: &Isometry3<f64>) -> Isometry3<f64> {
        self.before.inverse() * pose * self.after.inverse()
    }

    /// The texts that state `pose` (in the target's frame, m) with the configuration `arm`, each
    /// with its span: the pose's numbers as the language writes them (by default with
    /// [`super::DECIMALS`] decimals), the configuration
    /// data where they differ from the ones read.
    pub(crate) fn texts(
        &self,
        dialect: Dialect,
        pose: &Isometry3<f64>,
        arm: &Configuration,
    ) -> Vec<(Range<usize>, String)> {
        let p = pose.translation.vector * 1e3;
        let controller = dialect.controller();
        let values = controller.pose_numbers(&p, &pose.rotation);
        let texts = (values.iter().enumerate()).map(|(k, x)| controller.pose_text(k, *x));
        let mut out: Vec<(Range<usize>, String)> =
            (self.spans.iter().cloned()).zip(texts).collect();
        let now = Flags::of(dialect, arm);
        if self.flags.as_ref() != Some(&now) {
            out.extend(
                (self.flag_spans.iter()).map(|(span, part)| (span.clone(), part.text(&now))),
            );
        }
        out
    }
}

/// A frame's pose in words, mm and deg (`X, Y, Z, A, B, C`: `R = Rz(A) Ry(B) Rx(C)`).
pub(crate) fn words(f: &Isometry3<f64>) -> String {
    let p = f.translation.vector * 1e3;
    let [a, b, c] = zyx_deg(&f.rotation);
    format!(
        "X {} mm, Y {} mm, Z {} mm, A {} deg, B {} deg, C {} deg",
        number(p.x),
        number(p.y),
        number(p.z),
        number(a),
        number(b),
        number(c)
    )
}

#[cfg(test)]
mod literal_tests;

#[cfg(test)]
mod flags_tests;
