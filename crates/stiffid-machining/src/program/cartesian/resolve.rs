//! A program's Cartesian targets turned into the axis angles the controller moves to (module
//! docs of [`super`]).

use super::same::same;
use super::solve::{configured, Miss};
use super::{words, Cartesian, Flags, Frame};
use crate::program::{at, external, Dialect, JointProgram};
use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use stiffid_core::robot::configuration::Configuration;
use stiffid_core::robot::ik::{self, tool_pose};
use stiffid_core::robot::ExternalAxes;
use stiffid_core::setup::NumberedFrames;
use stiffid_core::{Result, Robot, Setup};

/// What a Cartesian target is resolved against: the controller's kinematics and frames, and
/// the setup's robot.
#[derive(Debug, Clone, Copy)]
pub struct Controller<'a> {
    /// The kinematics the controller runs ([`Setup::controller_robot`]).
    pub robot: &'a Robot,
    /// The setup's robot, whose axis angles compensation takes.
    pub truth: &'a Robot,
    /// The tool centre point, flange frame of both robots, m (`[tool] tcp_mm`).
    pub tcp: Vector3<f64>,
    /// The tool's axes in the flange frame of both robots (`[tool] tcp_rpy_deg`): a target's
    /// orientation is the tool's, the flange's turned by it.
    pub tcp_rotation: UnitQuaternion<f64>,
    /// The tool frame as the controller holds it: in its flange frame (after the setup's
    /// `[robot_flange]` adapter), m.
    pub tool: Isometry3<f64>,
    /// The controller's world in the setup's base frame ([`Setup::program_world`]), m.
    pub world: Isometry3<f64>,
    /// The part frame in the setup's base frame (`[workpiece] base_from_part`), if given.
    pub part: Option<Isometry3<f64>>,
    /// The tools the controller holds by number, in its flange frame (`[controller] tools`).
    pub tools: &'a NumberedFrames,
    /// The bases the controller holds by number, in its world (`[controller] bases`).
    pub bases: &'a NumberedFrames,
    /// Whether the setup's robot is a calibrated one and the controller's another (its nominal
    /// robot): the program's own frames were taught in the nominal cell (module `relocate`).
    pub nominal_cell: bool,
    /// The part's frame the calibration located, the setup's base frame, m
    /// ([`stiffid_core::Robot::part`]), if it did.
    pub located: Option<Isometry3<f64>>,
}

impl<'a> Controller<'a> {
    /// The controller of `setup`.
    ///
    /// # Errors
    /// Those of [`Setup::controller_robot`].
    pub fn of(setup: &'a Setup) -> Result<Self> {
        let c = setup.workcell().controller();
        let robot = setup.controller_robot()?;
        Ok(Controller {
            robot,
            truth: setup.robot(),
            tcp: setup.tool().tcp,
            tcp_rotation: setup.tool().rotation,
            tool: c.adapter * setup.tool().frame(),
            world: setup.program_world(),
            part: setup.workpiece().copied(),
            tools: &c.tools,
            bases: &c.bases,
            nominal_cell: setup.robot().is_calibrated() && !std::ptr::eq(robot, setup.robot()),
            located: setup.robot().part().copied(),
        })
    }
}

/// What writes a resolved program's Cartesian targets back: the controller's kinematics and the
/// tool centre point.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Writer {
    pub robot: Robot,
    pub tcp: Vector3<f64>,
    pub tcp_rotation: UnitQuaternion<f64>,
    /// The controller's external axes: its track carries the arm.
    pub axes: Option<ExternalAxes>,
}

impl Writer {
    /// The texts of Cartesian target `c` at axis angles `q` (rad) with the external values `e`
    /// (the program's, mm or deg, in its order: the first are the cell's), with their spans.
    pub(crate) fn texts(
        &self,
        dialect: Dialect,
        c: &Cartesian,
        (q, e): (&Vector6<f64>, &[Option<f64>]),
    ) -> Vec<(std::ops::Range<usize>, String)> {
        let carrier = self.axes.as_ref().map_or_else(Isometry3::identity, |axes| {
            let shown: Vec<f64> = (0..axes.len())
                .map(|k| e.get(k).copied().flatten().unwrap_or(0.0))
                .collect();
            axes.carrier_pose(&axes.to_si(&shown))
        });
        let mut pose = carrier * tool_pose(&self.robot.frames(q), &self.tcp);
        pose.rotation *= self.tcp_rotation;
        let local = c.base_from_frame.unwrap_or_default().inverse() * pose;
        c.texts(
            dialect,
            &c.stated(&local),
            &Configuration::of(&self.robot, q),
        )
    }

    /// Why Cartesian target `c` cannot be written at axis angles `q` (rad): the posture's
    /// configuration data are not the ones read, and the program states them where the target
    /// cannot change them alone (INFORM's `///RCONF`, a line every position after it shares);
    /// `None` when it can be written.
    pub(crate) fn stale_flags(
        &self,
        dialect: Dialect,
        c: &Cartesian,
        q: &Vector6<f64>,
    ) -> Option<String> {
        let read = c.flags.as_ref().filter(|_| c.flag_spans.is_empty())?;
        let now = Flags::of(dialect, &Configuration::of(&self.robot, q));
        (now != *read).then(|| {
            format!(
                "the compensated posture's configuration data are {}, the position's {}, which a line of the program states for every position after it: move the target away from the configuration's boundary, or give the position its own configuration line",
                now.text(),
                read.text()
            )
        })
    }
}

/// Whether a program has Cartesian targets.
pub(crate) fn is_cartesian(program: &JointProgram) -> bool {
    program.targets.iter().any(|t| t.cartesian.is_some())
}

/// The program with every Cartesian target's axis angles (module docs of [`super`]): from
/// `start` (rad) for the first target, then each from the previous one, by inverse kinematics
/// with `options` (its seed for the random starts). A program without Cartesian targets comes
/// back as it is.
///
/// # Errors
/// [`Error::Program`](stiffid_core::Error::Program) naming the target's line (or the line that
/// states the frame): a frame the program leaves to the controller (KRL without `$BASE` or `$TOOL`,
/// `BASE_DATA[n]`), a tool that is not the setup's (1 micrometre, 1 microradian), an LS user frame
/// without the setup's `[workpiece]`, the first target without configuration data, a pose out of
/// reach in the configuration it names (with the configurations it is reached in); on a cell
/// with external axes, those of [`external::cell_values`] (a target without the value of an
/// axis of the cell, a value outside its travel). A target's external values place the arm on
/// its track (the controller's and the setup's robot's each their own).
pub fn resolve(
    program: &JointProgram,
    controller: &Controller,
    start: &Vector6<f64>,
    options: &ik::Options,
) -> Result<JointProgram> {
    resolve_in(program, controller, None, (start, options))
}

/// [`resolve`] with the part at `base_from_part` (the setup's base frame) instead of the
/// setup's `[workpiece]`: every Cartesian target must be in the part frame (a KRL `$BASE` or
/// RAPID work object equal to the setup's `[workpiece]`, an LS user frame), and moves with it.
/// The configuration data name the shoulder, elbow and wrist ([`Flags::branch`]); the
/// revolutions of the axes (KUKA's turn, ABB's quadrants, FANUC's turn numbers, which hold for
/// the program's own placement) are those nearest the start posture and the previous target,
/// as for a G-code program's points: a compensated program written for the new placement
/// states its own.
///
/// # Errors
/// Those of [`resolve`]; [`Error::Program`](stiffid_core::Error::Program) naming the line of a joint target (axis angles do
/// not move with the part) or of a target in another frame than the part's.
pub(crate) fn resolve_placed(
    program: &JointProgram,
    controller: &Controller,
    base_from_part: &Isometry3<f64>,
    (start, options): (&Vector6<f64>, &ik::Options),
) -> Result<JointProgram> {
    check_placed(program, controller)?;
    resolve_in(program, controller, Some(base_from_part), (start, options))
}

/// Refuses, before any placement is tried, a program whose targets cannot move with the part
/// on `setup`'s controller (`check_placed`: every target a Cartesian one, for the setup's tool,
/// in the part frame).
///
/// # Errors
/// Those of [`Controller::of`]; [`Error::Program`](stiffid_core::Error::Program) naming the line
/// of the first target (or of the frame it states) that fails.
pub fn check_part(program: &JointProgram, setup: &Setup) -> Result<()> {
    check_placed(program, &Controller::of(setup)?)
}

/// The checks of `resolve_placed` that hold wherever the part is placed: every target a
/// Cartesian one, for the setup's tool, in the part frame. A placement search runs them once,
/// before it tries any placement.
///
/// # Errors
/// [`Error::Program`](stiffid_core::Error::Program) naming the line of the first target (or of the frame it states) that
/// fails: a joint target, a tool that is not the setup's or that the program leaves to the
/// controller, a frame that is not the part's (as `resolve_placed`).
pub(crate) fn check_placed(program: &JointProgram, controller: &Controller) -> Result<()> {
    let part = Isometry3::identity();
    for t in &program.targets {
        let Some(c) = t.cartesian.as_deref() else {
            return Err(at(t.line, "a joint target: axis angles do not move with the part; give every target as a Cartesian one in the part frame".into()));
        };
        check_tool(&c.tool, t.line, controller)?;
        base_frame(&c.frame, t.line, (controller, program.dialect), Some(&part))?;
    }
    Ok(())
}

fn resolve_in(
    program: &JointProgram,
    controller: &Controller,
    placed: Option<&Isometry3<f64>>,
    (start, options): (&Vector6<f64>, &ik::Options),
) -> Result<JointProgram> {
    if !is_cartesian(program) {
        return Ok(program.clone());
    }
    let dialect = program.dialect;
    let (carriers, axes) = carriers(program, controller)?;
    let mut out = program.clone();
    let mut previous = *start;
    let mut flags: Option<Flags> = None;
    let mut previous_arm: Option<Configuration> = None;
    let mut notes = Vec::new();
    // The target being resolved: a refusal of one of a called program's names its file.
    let mut at_target = 0;
    let each = || -> Result<()> {
        for (k, (t, (on_controller, on_truth_carrier))) in
            out.targets.iter_mut().zip(carriers).enumerate()
        {
            at_target = k;
            let line = t.line;
            let Some(c) = t.cartesian.as_deref_mut() else {
                previous = Vector6::from(t.q_deg).map(f64::to_radians);
                let arm = Configuration::of(controller.robot, &previous);
                (flags, previous_arm) = (Some(Flags::of(dialect, &arm)), Some(arm));
                continue;
            };
            check_tool(&c.tool, line, controller)?;
            let frame = base_frame(&c.frame, line, (controller, dialect), placed)?;
            let frame = match placed {
                None => {
                    let cell = (
                        controller.nominal_cell,
                        controller.located,
                        controller.world,
                    );
                    super::relocate::relocated(cell, &c.frame, frame, &mut notes)
                }
                Some(_) => frame,
            };
            // The flange's axes at the TCP: the tool's turned back by the tool's rotation; in the
            // frame of the arm on its carriage (the cell's when it has no track).
            let mut in_cell = frame * c.pose();
            in_cell.rotation *= controller.tcp_rotation.inverse();
            let target = on_controller.inverse() * in_cell;
            let kept = previous_arm.filter(|_| c.follows || c.flags.is_none());
            let wanted = c.flags.clone().or(flags.clone()).ok_or_else(|| at(line, format!("a Cartesian target without configuration data ({}), and no target before it to keep the configuration of: the pose has up to eight solutions; give them", dialect.controller().flags_name())))?;
            let accept = |arm: &Configuration| match (&kept, placed) {
                (Some(before), _) => arm.change_from(before).is_none(),
                (None, Some(_)) => Flags::of(dialect, arm).branch() == wanted.branch(),
                (None, None) => Flags::of(dialect, arm) == wanted,
            };
            let q = configured(
                controller.robot,
                &controller.tcp,
                &target,
                &previous,
                (dialect, &accept),
                options,
            )
            .map_err(|miss| {
                at(
                    line,
                    missed(&wanted, kept.is_some().then_some(c.follows), miss),
                )
            })?;
            let truth_target = on_truth_carrier.inverse() * in_cell;
            let q = on_truth(controller, (&target, &truth_target), q, options)
                .map_err(|why| at(line, why))?;
            c.base_from_frame = Some(frame);
            t.q_deg = q.map(f64::to_degrees).into();
            previous = q;
            let arm = Configuration::of(controller.robot, &q);
            (flags, previous_arm) = (Some(Flags::of(dialect, &arm)), Some(arm));
        }
        Ok(())
    };
    each().map_err(|e| in_file(program, at_target, e))?;
    out.notes.extend(notes);
    out.writer = Some(Box::new(Writer {
        robot: controller.robot.clone(),
        tcp: controller.tcp,
        tcp_rotation: controller.tcp_rotation,
        axes,
    }));
    Ok(out)
}

/// The refusal `e` of target `k` of `program`, naming the file of the backup it is in when it is
/// a called program's (its line is that file's).
fn in_file(program: &JointProgram, k: usize, e: stiffid_core::Error) -> stiffid_core::Error {
    match (e, program.called_in(k)) {
        (stiffid_core::Error::Program { line, message }, Some(file)) => {
            at(line, format!("{file} line {line}: {message}"))
        }
        (e, _) => e,
    }
}

/// A target's carriers: the controller's and the setup's robot's (the cell frame from the
/// arm's base frame).
type Carriers = (Isometry3<f64>, Isometry3<f64>);

/// Each target's carrier (the cell frame from the arm's base frame on its track, at the
/// target's external values: [`external::cell_values`]) on the controller and on the setup's
/// robot, and the controller's external axes. The controller runs its own robot's axes (a
/// nominal straight track), or the cell's where its robot has none; the setup's robot its
/// own (a calibrated track's error motions). A positioner carries the part, not the arm: a
/// target in a fixed frame is where the program says whatever the table's angle. Without
/// external axes, every carrier is the identity.
///
/// # Errors
/// Those of [`external::cell_values`] (naming the line and the axis); [`Error::Program`](stiffid_core::Error::Program) naming
/// the first target's line when the controller's robot has other external axes than the cell.
fn carriers(
    program: &JointProgram,
    controller: &Controller,
) -> Result<(Vec<Carriers>, Option<ExternalAxes>)> {
    // Without external axes the targets' values are checked where they are compensated.
    let Some(cell) = controller.truth.external().filter(|c| !c.is_empty()) else {
        let none = (Isometry3::identity(), Isometry3::identity());
        return Ok((vec![none; program.targets.len()], None));
    };
    let values = external::cell_values(program, Some(cell))?;
    let own = controller.robot.external().filter(|c| !c.is_empty());
    if let Some(own) = own.filter(|own| own.len() != cell.len()) {
        let line = program.targets.first().map_or(1, |t| t.line);
        return Err(at(line, format!("the controller's robot ([controller] robot) has {} external axes and the cell {}: give the controller's robot the cell's axes, in its order", own.len(), cell.len())));
    }
    let run = own.unwrap_or(cell);
    let carriers = (values.iter())
        .map(|e| (run.carrier_pose(e), cell.carrier_pose(e)))
        .collect();
    Ok((carriers, Some(run.clone())))
}

/// The message of a pose not reached in the configuration `wanted`, or (`kept`: whether the
/// motion is linear or circular) without a change of the arm's configuration from the target
/// before it.
fn missed(wanted: &Flags, kept: Option<bool>, miss: Miss) -> String {
    let found = |found: &[Flags]| found.iter().map(Flags::text).collect::<Vec<_>>().join(", ");
    match (miss, kept) {
        (Miss::Elsewhere(f), None) => format!(
            "the pose is out of reach in the configuration {} within the joint limits; inverse kinematics reaches it in {}",
            wanted.text(),
            found(&f)
        ),
        (Miss::Elsewhere(f), Some(follows)) => format!(
            "the pose is out of reach within the joint limits without changing the arm's configuration from the target before it (its shoulder, elbow and wrist: {}); inverse kinematics reaches it in {} only by changing it: a joint motion to it, or a target between them",
            match follows {
                true => "a linear or circular motion keeps them",
                false => "the target gives no configuration data of its own",
            },
            found(&f)
        ),
        (Miss::Unreachable(why), _) => format!("the pose is out of reach: {why}"),
    }
}

/// The setup's robot's posture at the pose the controller's posture `q` reaches, continued
/// from it (the same when both are one robot).
fn on_truth(
    controller: &Controller,
    (target, truth_target): (&Isometry3<f64>, &Isometry3<f64>),
    q: Vector6<f64>,
    options: &ik::Options,
) -> std::result::Result<Vector6<f64>, String> {
    if std::ptr::eq(controller.robot, controller.truth) && target == truth_target {
        return Ok(q);
    }
    let one = ik::Options {
        restarts: 0,
        ..*options
    };
    let truth = controller.truth;
    let s = ik::solve(truth, &controller.tcp, truth_target, &q, &one).map_err(|e| {
        format!("the setup's robot does not reach the pose near the controller's posture: {e}")
    })?;
    match Configuration::of(truth, &s.q).change_from(&Configuration::of(controller.robot, &q)) {
        Some(change) => Err(format!("the setup's robot reaches the pose only in another configuration than the controller's ({change})")),
        None => Ok(s.q),
    }
}

/// Refuses a tool that is not the setup's (module docs of [`resolve`]).
fn check_tool(tool: &Frame, line: u64, controller: &Controller) -> Result<()> {
    let (stated, on) = match tool {
        Frame::Declared(l, n) => {
            return declared_agrees(controller.tools, (*l, *n), &controller.tool, "tools")
        }
        Frame::Unknown(l, why) => return Err(at(*l, why.clone())),
        Frame::World => (Isometry3::identity(), line),
        Frame::Stated(l, f) => (*f, *l),
        Frame::Numbered(l, n) => (*numbered(controller.tools, (*l, *n), "tools")?, *l),
        Frame::Held(l, n, f, source) => {
            (held(controller.tools, (*l, *n), (f, source), "tools")?, *l)
        }
    };
    if same(&stated, &controller.tool) {
        return Ok(());
    }
    Err(at(on, format!("the program's tool ({}) is not the setup's ({}: its [tool] tcp_mm and tcp_rpy_deg, after [robot_flange]); compensation moves the setup's tool: write the program for it", words(&stated), words(&controller.tool))))
}

/// The frame of a target in the setup's base frame; with `placed`, the part's at that pose.
fn base_frame(
    frame: &Frame,
    line: u64,
    (c, dialect): (&Controller, Dialect),
    placed: Option<&Isometry3<f64>>,
) -> Result<Isometry3<f64>> {
    let form = dialect.controller().part_forms().unwrap_or("none");
    let not_part = |l: u64, what: String| {
        at(l, format!("{what}: the targets are not in the part frame (the setup's [workpiece]), so they do not move with the part; give them as {form}"))
    };
    match frame {
        Frame::Unknown(l, why) => Err(at(*l, why.clone())),
        Frame::World => match placed {
            Some(_) => Err(not_part(line, "the world frame".into())),
            None => Ok(c.world),
        },
        Frame::Stated(l, f) => {
            let base = c.world * f;
            match placed {
                None => Ok(base),
                Some(p) if c.part.is_some_and(|part| same(&part, &base)) => Ok(*p),
                Some(_) => Err(not_part(*l, format!("the frame {}", words(f)))),
            }
        }
        Frame::Numbered(l, n) => {
            let f = numbered(c.bases, (*l, *n), "bases")?;
            base_frame(&Frame::Stated(*l, *f), line, (c, dialect), placed)
        }
        Frame::Held(l, n, f, source) => {
            let f = held(c.bases, (*l, *n), (f, source), "bases")?;
            base_frame(&Frame::Stated(*l, f), line, (c, dialect), placed)
        }
        Frame::Declared(l, n) => {
            if let Some(part) = c.part {
                // The table's frames are in the controller's world, the part in the setup's base.
                declared_agrees(c.bases, (*l, *n), &(c.world.inverse() * part), "bases")?;
            }
            placed.copied().or(c.part).ok_or_else(|| {
                at(*l, "the program declares its user frame the part frame, and the setup gives none ([workpiece] base_from_part)".into())
            })
        }
    }
}

/// The program's own statement and the setup's table agree: a frame number `n` the program
/// declares on `line` holds the setup's own frame `own` (its part frame in the controller's
/// world, its tool in the flange) is either absent from the setup's `[controller]` table
/// `table` or that same frame there.
///
/// # Errors
/// [`stiffid_core::Error::Program`] on `line` naming both frames and how far apart they are.
fn declared_agrees(
    frames: &NumberedFrames,
    (line, n): (u64, u32),
    own: &Isometry3<f64>,
    table: &str,
) -> Result<()> {
    let Some(f) = frames.get(n).filter(|f| !same(f, own)) else {
        return Ok(());
    };
    let (role, field) = match table {
        "bases" => ("the part frame", "[workpiece] base_from_part"),
        _ => ("the tool", "[tool] tcp_mm, tcp_rpy_deg"),
    };
    Err(at(line, format!(
        "the program declares its frame number {n} {role} (the setup's {field}: {}), and the setup's [controller] {table} gives number {n} another frame ({}), {:.3} mm and {:.3} deg apart: one number holds one frame on the controller; give the table the frame the controller holds, or drop the one that is not",
        words(own),
        words(f),
        (f.translation.vector - own.translation.vector).norm() * 1e3,
        f.rotation.angle_to(&own.rotation).to_degrees()
    )))
}

/// The frame numbered `n` (on `line`) the controller's backup gives as `frame` (stated at
/// `source`), refused where the setup's `[controller]` table `table` (`tools`, `bases`) gives
/// that number another frame: one controller holds one.
fn held(
    frames: &NumberedFrames,
    (line, n): (u64, u32),
    (frame, source): (&Isometry3<f64>, &str),
    table: &str,
) -> Result<Isometry3<f64>> {
    match frames.get(n) {
        Some(given) if !same(given, frame) => Err(at(line, format!("frame number {n} of the controller's {table}: the backup's {source} gives {}, the setup's [controller] {table} {}; one controller holds one frame per number: remove the setup's entry or make the two agree", words(frame), words(given)))),
        _ => Ok(*frame),
    }
}

/// The frame numbered `n` (stated on `line`) of the setup's `[controller]` table `table`
/// (`tools`, `bases`).
fn numbered<'t>(
    frames: &'t NumberedFrames,
    (line, n): (u64, u32),
    table: &str,
) -> Result<&'t Isometry3<f64>> {
    frames.get(n).ok_or_else(|| {
        let given = match frames.numbers().map(|k| k.to_string()).collect::<Vec<_>>() {
            k if k.is_empty() => "gives none".to_string(),
            k => format!("gives {}", k.join(", ")),
        };
        at(line, format!("frame number {n} of the controller's {table}, which the program selects by number without stating it, and the setup's [controller] {table} {given}: give it there ({{ number = {n}, xyz_mm = [..], rpy_deg = [..] }}, as the controller holds it)"))
    })
}
