//! Compensation of a machining program: a G-code or robot program and a process file in, the
//! same program with compensated targets out.
//!
//! 1. The program gives the path: G-code points (part frame, placed in the base frame by the
//!    setup's `[workpiece] base_from_part`) as TCP poses, or a robot program's joint targets
//!    ([`crate::program`]) as axis angles, its Cartesian targets as the axis angles
//!    the controller moves to ([`resolve`] first).
//! 2. The process gives each point its wrench: the operation that covers it
//!    ([`Operation`]: G-code `(operation: NAME)` comments, then `T` tool numbers, then an operation
//!    without a selector; robot programs: the operation whose `lines` hold the target's line, then
//!    one without a selector), its mean force and moment over a revolution, turned from the feed
//!    frame into the base frame along the path's own feed direction (the TCP's motion from the
//!    previous point; the first point takes the second's) and the tool axis
//!    (`Operation::base_wrench`). Where the tool cuts is one rule for every language
//!    (`cutting`): joint moves (G-code `G0`, `PTP`, `MoveJ`, `MoveAbsJ`, `J`, `MOVJ`), a
//!    drill's retracts and moves across its axis, and points no operation covers cut nothing. A
//!    drilling cycle's feed cuts from where the drill meets material (the part's surface, the
//!    depth a peck reached: `gcode::Cycle`) to its end, both compensated under the thrust, so
//!    the drill runs along the compensated hole axis while it cuts; its `R` level and a peck's
//!    re-approach are unloaded. A milling point fed along the tool axis (a plunge) gets no force
//!    and is counted. With the
//!    setup's `[tool] mass_kg` and `centre_of_mass_mm`, the tool's weight joins every point's
//!    wrench ([`stiffid_core::setup::Payload::wrench`]).
//! 3. `compensate::path_with_exits` compensates every point (with
//!    [`compensate::FreeVariables::lead_tilt`], each point's cone its operation's
//!    [`Operation::cone`]; a rapid move, a point no operation covers and a drilling point none), refusing any whose compensated
//!    axis angles leave the joint limits (naming its line); the free tool axis may minimise the
//!    surge at the drilling exits (`dynamics::exit_thrusts`).
//! 4. Compensated targets that move more than 1 degree from the nominal ones, or
//!    change the sign of axis 5 (a wrist flip), change the robot's configuration: refused naming
//!    the line.
//! 5. The program is written back in its own format: robot programs with the compensated axis
//!    angles (Cartesian targets: the pose the controller must be told, with the configuration
//!    data of the compensated posture) and every other byte as read (their external axes' values too: a robot program's
//!    targets are compensated with the external axes as they give them); G-code with the compensated TCP positions in the part
//!    frame (the controller's forward kinematics of the compensated posture, [`compensate_for`]:
//!    where the controller must be sent so that the loaded tool lands on the programmed one). With a free station or positioner
//!    (`compensate::FreeVariables::station`, `compensate::FreeVariables::positioner`) the
//!    values chosen replace the program's in every target (G-code: every point written carries
//!    all its mapped external axes, `gcode::GCode::write_with_external`), and the targets are
//!    the compensated postures there. With a free configuration
//!    ([`compensate::FreeVariables::configuration`]) the whole program is compensated in every
//!    configuration of the arm and the best kept ([`compensate::FreeVariables::configuration`]): one
//!    configuration per program, or with [`compensate::Scope::Run`] one per run
//!    ([`compensate::starts`]: a cut and the joint moves that lead to it, G-code `G0`, robot
//!    programs' `PTP`, `MoveJ`, `MoveAbsJ`, `J`, `MOVJ`); a joint program's targets are solved
//!    in another configuration from their nominal poses, and written back with its angles, a
//!    Cartesian target with the configuration data of its compensated posture. A G-code
//!    program names no configuration: its positions are written whatever the runs' (the
//!    compensate job refuses G-code output whose runs differ).
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links, rustdoc::private_intra_doc_links)]

pub mod cell;
pub mod compensate;
pub(crate) mod cutting;
pub mod dynamics;
pub mod gcode;
pub mod path;
pub mod process;
pub mod program;
mod text;
pub mod weight;

use crate::compensate::{Compensated, Compliance, PathPoint, Target};
use crate::gcode::GCode;
use crate::process::{Operation, Process};
use crate::program::{Dialect, JointProgram};
use nalgebra::{Isometry3, Vector3, Vector6};
use stiffid_core::common::words::{count, is_are};
use stiffid_core::observation::deflection::Frame;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::robot::ik::tool_pose;
use stiffid_core::setup::Arm;
use stiffid_core::{Error, Result};

/// The largest change of an axis angle compensation may make, deg; more means another
/// configuration (or a point next to a singularity).
pub(crate) const MAX_CORRECTION_DEG: f64 = 1.0;

/// A machining program as read.
#[derive(Debug, Clone, PartialEq)]
pub enum Program {
    /// A G-code program (part frame).
    GCode(GCode),
    /// A robot program's joint targets.
    Robot(JointProgram),
}

/// What a program file is written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Language {
    /// G-code (`.nc`, `.ngc`, `.gcode`, `.tap`, `.cnc`).
    GCode,
    /// A robot program.
    Robot(Dialect),
}

impl Language {
    /// The language of a file name's extension (case-insensitive).
    pub(crate) fn from_extension(extension: &str) -> Option<Self> {
        match extension.to_ascii_lowercase().as_str() {
            "nc" | "ngc" | "gcode" | "tap" | "cnc" | "g" => Some(Language::GCode),
            other => Dialect::from_extension(other).map(Language::Robot),
        }
    }

    /// The language of a file name's extension, or [`Error::InvalidField`] naming the file and
    /// the extensions known.
    ///
    /// # Errors
    /// An extension that is none of `Language::from_extension`'s.
    pub fn of_file(name: &str) -> Result<Self> {
        let extension = std::path::Path::new(name)
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("");
        Self::from_extension(extension).ok_or_else(|| Error::InvalidField {
            field: name.into(),
            message: format!(
                "expected a program ending in .nc, .ngc, .gcode, .tap, .cnc or .g (G-code), {}",
                Dialect::ALL.map(robot_extensions).join(", ")
            ),
        })
    }

    /// The language's name in documents: `gcode`, `krl`, `rapid`, `ls` or `inform`.
    pub fn name(self) -> &'static str {
        match self {
            Language::GCode => "gcode",
            Language::Robot(d) => d.controller().key(),
        }
    }

    /// The extension of a file written in the language where no file name says it (Python's
    /// `output=`): `nc`, `src`, `mod`, `ls` or `jbi`; `Language::from_extension` of it is the
    /// language.
    pub fn extension(self) -> &'static str {
        match self {
            Language::GCode => "nc",
            Language::Robot(d) => d.controller().extensions()[0],
        }
    }

    /// The language a compensated program is written in, the one rule of both front ends: that
    /// of the output file's name `out` ([`Language::of_file`]), else the one named `requested`
    /// ([`stiffid_core::common::choice::parse`]), else the program's own `language`; and the file name
    /// it is written under: `out`, else `stem` with the language's [`Language::extension`].
    ///
    /// # Errors
    /// Those of [`Language::of_file`] (naming `out`) and of [`stiffid_core::common::choice::parse`]
    /// (field `output`).
    pub fn output(
        language: Language,
        out: Option<&str>,
        requested: Option<&str>,
        stem: &str,
    ) -> Result<(Language, String)> {
        match (out, requested) {
            (Some(out), _) => Ok((Language::of_file(out)?, out.to_string())),
            (None, requested) => {
                let output = match requested {
                    Some(name) => stiffid_core::common::choice::parse::<Language>(name)?,
                    None => language,
                };
                Ok((output, format!("{stem}.{}", output.extension())))
            }
        }
    }
}

/// A dialect's extensions and name in words: `.src or .dat (KUKA KRL)`.
fn robot_extensions(d: Dialect) -> String {
    let c = d.controller();
    let dotted: Vec<String> = c.extensions().iter().map(|e| format!(".{e}")).collect();
    format!("{} ({})", text::or_list(&dotted), c.title())
}

impl stiffid_core::common::choice::Choice for Language {
    const FIELD: &'static str = "output";
    const ALL: &'static [Self] = &{
        let mut all = [Language::GCode; 1 + Dialect::ALL.len()];
        let mut i = 0;
        while i < Dialect::ALL.len() {
            all[i + 1] = Language::Robot(Dialect::ALL[i]);
            i += 1;
        }
        all
    };

    fn name(self) -> &'static str {
        Language::name(self)
    }

    fn help(self) -> &'static str {
        match self {
            Language::GCode => "G-code",
            Language::Robot(d) => d.controller().title(),
        }
    }
}

impl Program {
    /// The program's language.
    pub fn language(&self) -> Language {
        match self {
            Program::GCode(_) => Language::GCode,
            Program::Robot(p) => Language::Robot(p.dialect),
        }
    }
}

/// Reads a program; `chord_tolerance` (m) splits G-code arcs.
///
/// # Errors
/// Those of [`gcode::parse`] and [`program::parse`].
pub fn read(text: &str, language: Language, chord_tolerance: f64) -> Result<Program> {
    read_in(
        text,
        language,
        chord_tolerance,
        &program::Context::default(),
    )
}

/// [`read`] with what the setup says of a program in `context` (an INFORM job's pulses and
/// tool files, KRL's `.dat` beside the `.src`, a G-code program's controller).
///
/// # Errors
/// Those of [`gcode::parse`] and [`program::parse_in`]; [`Error::InvalidField`] (`data`) for a
/// data file with G-code.
pub fn read_in(
    text: &str,
    language: Language,
    chord_tolerance: f64,
    context: &program::Context,
) -> Result<Program> {
    match (language, context.data) {
        (Language::GCode, None) => match context.machine {
            Some(machine) => gcode::parse_on(text, chord_tolerance, machine),
            None => gcode::parse(text, chord_tolerance),
        }
        .map(Program::GCode),
        (Language::GCode, Some(_)) => Err(Error::InvalidField {
            field: "data".into(),
            message: "a data file is read with a KRL program only".into(),
        }),
        (Language::Robot(d), _) => program::parse_in(text, d, context).map(Program::Robot),
    }
}

/// `program` with its Cartesian targets' axis angles ([`program::cartesian`]: the controller's
/// inverse kinematics in the configuration each names, from `options`' start posture), on
/// `setup`'s controller; with `placed`, the part frame at that pose (the setup's base frame)
/// carries the targets (`program::cartesian::resolve_placed`). Its joint targets as the setup
/// says they were made (`[controller] joint_targets`: taught, or computed by the controller's
/// inverse kinematics). Any other program as it is.
///
/// # Errors
/// Those of [`stiffid_core::Setup::controller_robot`], [`program::cartesian::resolve`] and
/// `program::cartesian::resolve_placed` (naming the line); [`Error::InvalidField`] naming
/// `controller.joint_targets` for joint targets it leaves unsaid where the two robots differ.
pub fn resolve<'a>(
    program: &'a Program,
    setup: &stiffid_core::Setup,
    placed: Option<&Isometry3<f64>>,
    options: &compensate::Options,
) -> Result<std::borrow::Cow<'a, Program>> {
    use program::cartesian;
    use std::borrow::Cow;
    let Program::Robot(read) = program else {
        return Ok(Cow::Borrowed(program));
    };
    let computed = match placed {
        None => cartesian::computed::joint_targets(read, setup, &options.ik)?,
        Some(_) => None,
    };
    let p = computed.as_ref().unwrap_or(read);
    if placed.is_none() && !cartesian::is_cartesian(p) {
        return Ok(computed.map_or(Cow::Borrowed(program), |c| Cow::Owned(Program::Robot(c))));
    }
    let controller = cartesian::Controller::of(setup)?;
    let start = (&options.q0, &options.ik);
    let resolved = match placed {
        Some(part) => cartesian::resolve_placed(p, &controller, part, start)?,
        None => cartesian::resolve(p, &controller, start.0, start.1)?,
    };
    Ok(Cow::Owned(Program::Robot(resolved)))
}

/// The compensation of a program.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// The path points with their base-frame wrenches, as [`compensate::path`] took them.
    pub points: Vec<PathPoint>,
    /// One per point.
    pub results: Vec<Compensated>,
    /// The operation (index into the process) of each point, `None` where nothing cuts.
    pub operations: Vec<Option<usize>>,
    /// The program, compensated, in its own format.
    pub program: String,
    /// Its data file compensated, for a robot program read with one whose targets may live
    /// there (KRL's `.dat`, [`program::parse_with_data`]): written beside the program, together.
    pub data: Option<String>,
    /// The programs of the controller's backup it calls that move (an LS `CALL`), each
    /// compensated in place: the file's name as given and its text, to be written beside the
    /// program under its name.
    pub called: Vec<(String, String)>,
    /// What the user should know: plunges without a milling force, points no operation covers.
    pub warnings: Vec<String>,
    /// With a free configuration ([`compensate::FreeVariables::configuration`]): every
    /// configuration of the arm evaluated over the whole program, the one chosen.
    pub configurations: Option<compensate::Configurations>,
}

/// Compensates `program` under `process` (module docs) on `arm` with the compliance `compliance`
/// of every parameter of its model; `workpiece` is the part frame in the robot base frame (the
/// setup's `[workpiece] base_from_part`, [`stiffid_core::setup::Workcell::workpiece`]) that a G-code
/// program's positions are in.
///
/// # Errors
/// [`Error::InvalidField`] for a G-code program without a `workpiece`; [`Error::Program`] naming the line of a point whose `(operation: NAME)` names no
/// operation, or whose compensation changes the configuration; those of [`compensate::path`]
/// (joint limits, unreachable poses, naming the line); for a robot program, those of
/// [`program::external::cell_values`] (an external axis the robot's cell lacks, a value outside
/// its travel, an axis of the cell without a value, naming the line and the axis).
pub fn compensate(
    arm: &Arm,
    workpiece: Option<&Isometry3<f64>>,
    compliance: &Compliance,
    program: &Program,
    process: &Process,
    options: &compensate::Options,
) -> Result<Report> {
    let at = (arm, workpiece, compliance);
    compensate_for(arm.robot(), at, program, process, options)
}

/// [`compensate()`] for a controller that runs the kinematics of `controller`
/// ([`stiffid_core::Setup::controller_robot`]): a G-code program's positions are written as the
/// controller's forward kinematics of the compensated axis angles (its inverse kinematics then
/// returns them), in the part frame; on a cell with external axes, with the arm on the
/// controller's track and the part on the controller's positioner at the point's values (those
/// of the cell when the controller's robot has no external axes); robot programs' angles.
///
/// # Errors
/// Those of [`compensate()`].
pub fn compensate_for(
    controller: &stiffid_core::Robot,
    (arm, workpiece, compliance): (&Arm, Option<&Isometry3<f64>>, &Compliance),
    program: &Program,
    process: &Process,
    options: &compensate::Options,
) -> Result<Report> {
    if let Program::Robot(p) = program
        && let Some(t) = p
            .targets
            .iter()
            .find(|t| t.q_deg.iter().any(|v| !v.is_finite()))
    {
        return Err(Error::Program {
                line: t.line,
                message: "a Cartesian target without its axis angles: resolve the program on its setup first (machining::resolve)".into(),
            });
    }
    let placements = cell::placements(arm, workpiece, program)?;
    let poses = poses(arm, workpiece, program, placements.as_deref())?;
    let on_part = on_part(&poses, placements.as_deref());
    let joint = cutting::joint_moves(program);
    let idle = cutting::idle(program, &joint);
    let feeds = cutting::feeds_of(program, &on_part);
    let operations = cutting::cutting(
        &idle,
        (&on_part, &feeds),
        process::covering::operations(program, process)?,
    );
    let tool = weight::tool_load(arm, compliance);
    let weight = |pose: &Isometry3<f64>| {
        tool.map_or(Vector6::zeros(), |p| {
            p.wrench(
                &(pose.rotation * arm.tool().rotation.inverse()),
                &arm.tool().tcp,
            )
        })
    };
    let at = (on_part.as_slice(), feeds.as_slice());
    let (points, warnings) = path_points(&poses, at, placements.as_deref(), &operations, weight);
    let indices: Vec<Option<usize>> = operations.iter().map(|o| o.map(|(i, _)| i)).collect();
    let nominal: Vec<Isometry3<f64>> = poses.iter().map(|p| p.2).collect();
    let thrusts = dynamics::exit_thrusts(process, &nominal, &indices);
    let free = options.free.frees_external();
    let cones = match &options.free.lead_tilt() {
        Some(l) => {
            let allowed: Vec<f64> = (operations.iter())
                .map(|o| o.map_or(0.0, |(_, op)| op.cone))
                .collect();
            compensate::cones(l, points.len(), Some(&allowed))?
        }
        None => Vec::new(),
    };
    let own: Vec<ExternalValues> = points.iter().map(|p| p.external).collect();
    // The points from `first` on: each per-point list sliced to them (a run's).
    let evaluate = |first: usize, points: &[PathPoint], options: &compensate::Options| {
        let n = first..first + points.len();
        let cones = cones.get(n.clone()).unwrap_or(&[]);
        match free {
            false => {
                let at = (thrusts.get(n).unwrap_or(&[]), cones);
                compensate::path_in_cones(arm, compliance, points, at, options)
            }
            true => {
                let weighted = tool.is_some();
                compensate::on_track(arm, compliance, points, (&own[n], weighted, cones), options)
            }
        }
    };
    let (mut results, configurations) = match options.free.configuration() {
        None => (evaluate(0, &points, options)?, None),
        Some(_) => {
            let starts = compensate::starts(&joint);
            let at = (points.as_slice(), starts.as_slice());
            let (results, c) = compensate::choose(arm, compliance, at, options, evaluate)?;
            (results, Some(c))
        }
    };
    check_configuration(&points, &results)?;
    let placements = match (&placements, free) {
        (Some(_), true) => Some(cell::at_chosen(arm, workpiece, program, &results)?),
        _ => placements,
    };
    let at = (arm, workpiece);
    let (program, data, called) = write_back(
        controller,
        at,
        program,
        &results,
        (placements.as_deref(), free),
    )?;
    if let Some(p) = &placements {
        cell::to_cell(&mut results, p);
    }
    Ok(Report {
        points,
        results,
        operations: indices,
        program,
        data,
        called,
        warnings,
        configurations,
    })
}

/// The program written back in its own format (module docs, step 5): a robot program with the
/// compensated axis angles, G-code with the controller's positions of them in the part frame;
/// the external values chosen when they are free; a robot program's data file with it, when one
/// was read.
fn write_back(
    controller: &stiffid_core::Robot,
    (arm, workpiece): (&Arm, Option<&Isometry3<f64>>),
    program: &Program,
    results: &[Compensated],
    (placements, free): (Option<&[cell::Placement]>, bool),
) -> Result<program::Written> {
    Ok(match program {
        Program::Robot(p) => {
            let q: Vec<[f64; 6]> = results
                .iter()
                .map(|r| r.q_compensated.map(f64::to_degrees).into())
                .collect();
            match (placements, arm.robot().external()) {
                (Some(placed), axes @ Some(_)) => {
                    let e: Vec<Vec<f64>> = placed
                        .iter()
                        .map(|p| p.external.as_slice().to_vec())
                        .collect();
                    p.write_files(&q, &program::external::program_values(p, &e, axes))?
                }
                _ => {
                    let e: Vec<Vec<Option<f64>>> =
                        p.targets.iter().map(|t| t.external.clone()).collect();
                    p.write_files(&q, &e)?
                }
            }
        }
        Program::GCode(g) => {
            let part = part_frame(workpiece)?.inverse();
            let tcp = &arm.tool().tcp;
            let positions: Vec<Vector3<f64>> = results
                .iter()
                .enumerate()
                .map(|(i, r)| {
                    // On a cell, where the controller's own track and positioner put the tool.
                    let q = &r.q_compensated;
                    let (frames, part) = match (placements, controller.external()) {
                        (Some(p), Some(axes)) if !axes.is_empty() => {
                            let e = p[i].external.as_slice();
                            let turned = axes.positioner_pose(e).inverse();
                            (controller.frames_at(q, e), part * turned)
                        }
                        (p, _) => (controller.frames(q), p.map_or(part, |p| p[i].part)),
                    };
                    let pose = tool_pose(&frames, tcp);
                    part * nalgebra::Point3::from(pose.translation.vector)
                })
                .map(|p| p.coords)
                .collect();
            match (free, arm.robot().external()) {
                (true, Some(axes)) => {
                    let e: Vec<Vec<f64>> = (placements.into_iter().flatten())
                        .map(|p| axes.to_display(p.external.as_slice()))
                        .collect();
                    (g.write_with_external(&positions, &e)?, None, Vec::new())
                }
                _ => (g.write(&positions)?, None, Vec::new()),
            }
        }
    })
}

/// The part frame a G-code program needs: the setup's `[workpiece] base_from_part`.
fn part_frame(workpiece: Option<&Isometry3<f64>>) -> Result<Isometry3<f64>> {
    workpiece.copied().ok_or_else(|| Error::InvalidField {
        field: "workpiece.base_from_part".into(),
        message: "missing: a G-code program needs the part frame in the robot base frame ([workpiece] base_from_part = { xyz_mm = [..], rpy_deg = [..] } in the setup file)".into(),
    })
}

/// Each point's line, target and nominal TCP pose (base frame, in the tool's axes, `[tool]
/// tcp_rpy_deg`, whose z the process pushes along: a G-code point's orientation is the tool's;
/// the target of a G-code point is the flange's axes at the TCP).
///
/// # Errors
/// A G-code program without `[workpiece]`.
fn poses(
    arm: &Arm,
    workpiece: Option<&Isometry3<f64>>,
    program: &Program,
    placements: Option<&[cell::Placement]>,
) -> Result<Vec<(u64, Target, Isometry3<f64>)>> {
    match program {
        Program::GCode(g) => {
            let base = part_frame(workpiece)?;
            Ok(g.points
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let base = placements.map_or(base, |c| c[i].part.inverse());
                    let pose = base * Isometry3::from_parts(p.position.into(), p.orientation);
                    // The tool's axes: the flange's at the TCP turned by `[tool] tcp_rpy_deg`.
                    let mut flange_axes = pose;
                    flange_axes.rotation *= arm.tool().rotation.inverse();
                    (p.line, Target::Pose(flange_axes), pose)
                })
                .collect())
        }
        Program::Robot(r) => Ok(r
            .targets
            .iter()
            .map(|t| {
                let q = nalgebra::Vector6::from(t.q_deg).map(f64::to_radians);
                // The tool's axes (`[tool] tcp_rpy_deg`): the process pushes along its z.
                let mut pose = tool_pose(&arm.robot().frames(&q), &arm.tool().tcp);
                pose.rotation *= arm.tool().rotation;
                (t.line, Target::Posture(q), pose)
            })
            .collect()),
    }
}

/// The TCP poses the feed is measured in: over the part, `placement.part * pose`, when the
/// program moves the cell's external axes (`placements`, [`cell`]); else the base frame's.
fn on_part(
    poses: &[(u64, Target, Isometry3<f64>)],
    placements: Option<&[cell::Placement]>,
) -> Vec<Isometry3<f64>> {
    match placements {
        None => poses.iter().map(|p| p.2).collect(),
        Some(placed) => (poses.iter().zip(placed))
            .map(|((_, _, pose), p)| p.part * pose)
            .collect(),
    }
}

/// The path points with their base-frame wrenches, and the warnings; `feeds` those of
/// `on_part` ([`cutting::feeds_of`]). With `placements` (a program that moves the cell's
/// external axes, [`cell`]) the feed is the tool's motion over the part (`on_part`) and the
/// weight pulls along the cell's `-z`, each turned into the arm's frame.
fn path_points(
    poses: &[(u64, Target, Isometry3<f64>)],
    (on_part, feeds): (&[Isometry3<f64>], &[Option<Vector3<f64>>]),
    placements: Option<&[cell::Placement]>,
    operations: &[Option<(usize, &Operation)>],
    weight: impl Fn(&Isometry3<f64>) -> Vector6<f64>,
) -> (Vec<PathPoint>, Vec<String>) {
    let lines: Vec<u64> = poses.iter().map(|p| p.0).collect();
    let (mut process, warnings) = process_wrenches(&lines, (on_part, feeds), operations);
    if let Some(placed) = placements {
        for (w, p) in process.iter_mut().zip(placed) {
            *w = cell::turned(&p.part.rotation.inverse().to_rotation_matrix(), w);
        }
    }
    let weight = |i: usize, pose: &Isometry3<f64>| match placements {
        None => weight(pose),
        Some(placed) => {
            let c = &placed[i].carrier;
            cell::turned(
                &c.rotation.inverse().to_rotation_matrix(),
                &weight(&(c * pose)),
            )
        }
    };
    let points = poses
        .iter()
        .enumerate()
        .map(|(i, (line, target, pose))| {
            let wrench = process[i];
            PathPoint {
                line: *line,
                target: target.clone(),
                wrench: wrench + weight(i, pose),
                frame: Frame::Base,
                external: placements.map_or(ExternalValues::NONE, |p| p[i].external),
            }
        })
        .collect();
    (points, warnings)
}

/// Each point's process wrench (base frame), and the warnings: `lines` each point's line,
/// `poses` its TCP pose in the frame the feed is measured in ([`on_part`]) and `feeds` its feed.
fn process_wrenches(
    lines: &[u64],
    (poses, feeds): (&[Isometry3<f64>], &[Option<Vector3<f64>>]),
    operations: &[Option<(usize, &Operation)>],
) -> (Vec<Vector6<f64>>, Vec<String>) {
    let mut plunges = Vec::new();
    let mut uncovered = 0;
    let wrenches = (0..poses.len())
        .map(|i| {
            let tool_z = poses[i].rotation * Vector3::z();
            match operations[i] {
                None => {
                    uncovered += 1;
                    Vector6::zeros()
                }
                Some((_, op)) => match feeds[i].and_then(|f| op.base_wrench(&f, &tool_z)) {
                    Some(w) => w,
                    None => {
                        plunges.push(lines[i]);
                        Vector6::zeros()
                    }
                },
            }
        })
        .collect();
    let mut warnings = Vec::new();
    if !plunges.is_empty() {
        let first: Vec<String> = plunges.iter().take(5).map(u64::to_string).collect();
        warnings.push(format!(
            "{} {} fed along the tool axis (a plunge) in a milling operation: no process force there (lines {}{})",
            count(plunges.len(), "point"),
            is_are(plunges.len()),
            first.join(", "),
            if plunges.len() > 5 { ", ..." } else { "" }
        ));
    }
    if uncovered > 0 {
        warnings.push(format!(
            "{uncovered} of {} {} where the tool does not cut (a joint or rapid move, a drill not fed into the part, no operation): no process force there",
            count(poses.len(), "point"),
            is_are(uncovered)
        ));
    }
    (wrenches, warnings)
}

/// Refuses a compensated target that changes the configuration (module docs).
fn check_configuration(points: &[PathPoint], results: &[Compensated]) -> Result<()> {
    for (p, r) in points.iter().zip(results) {
        let dq = (r.q_compensated - r.q).map(f64::to_degrees);
        let (axis, worst) = dq.iamax_full();
        let worst = dq[(axis, worst)];
        let flip = r.q[4].abs() > 1e-9 && r.q_compensated[4].signum() != r.q[4].signum();
        if worst.abs() > MAX_CORRECTION_DEG || flip {
            return Err(Error::Program {
                line: p.line,
                message: match flip {
                    true => "the compensated target flips the wrist (axis 5 changes sign): another configuration; refused".into(),
                    false => format!("the compensated target moves axis {} by {worst:.3} deg (more than {MAX_CORRECTION_DEG} deg): another configuration or a singularity; refused", axis + 1),
                },
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod dynamics_tests;
