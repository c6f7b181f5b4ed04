//! The tool axis' lead and tilt as free variables: the axis leaned from the path's own within a
//! cone, the TCP on the path's point (module docs of [`super`], "Lead and tilt").

use super::options::Options;
use super::variables::{offsets, LeadTilt, MAX_GRID_CELLS};
use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use stiffid_core::common::error::JobOption;
use stiffid_core::common::words::number;
use stiffid_core::{Error, Result};

/// Each of `points` points' cone of `free`, rad: the path file's ([`LeadTilt::cone`]) at every
/// point, else `process` (one per point: its operation's), checked.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::LeadTiltRange`]) for a path file's points without a cone
/// or a program's with one (the process file gives it), and for a process whose operations
/// allow no lean; ([`JobOption::LeadTiltStep`]) for a step above the largest cone.
pub(crate) fn cones(free: &LeadTilt, points: usize, process: Option<&[f64]>) -> Result<Vec<f64>> {
    let refuse = |option, message: String| Error::InvalidOption { option, message };
    let cones = match (free.cone, process) {
        (Some(c), None) => vec![c; points],
        (None, Some(p)) => p.to_vec(),
        (None, None) => return Err(refuse(JobOption::LeadTiltRange, "missing: a path file has no process file to allow a lean; give the cone's half angle (--free lead-tilt=-CONE..CONE, free=[\"lead-tilt=-CONE..CONE\"])".into())),
        (Some(_), Some(_)) => return Err(refuse(JobOption::LeadTiltRange, "a program's cone is its process file's ([tool_axis] cone_deg of a milling operation), not an option".into())),
    };
    let largest = cones.iter().copied().fold(0.0, f64::max);
    if largest == 0.0 {
        return Err(refuse(
            JobOption::LeadTiltRange,
            "the process file allows no lean: no milling operation gives [tool_axis] cone_deg"
                .into(),
        ));
    }
    if free.step > largest * (1.0 + 1e-12) {
        return Err(refuse(
            JobOption::LeadTiltStep,
            format!(
                "{}: expected at most the largest cone, {} deg",
                number(free.step.to_degrees()),
                number(largest.to_degrees())
            ),
        ));
    }
    Ok(cones)
}

/// Refuses a fixed-base grid of more than [`MAX_GRID_CELLS`] cells (leans x
/// rotations x `points`) with cones up to `largest` (rad); without a free lean, the free tool
/// rotation's own check ([`super::FreeRange::check_rotation_grid`]).
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::LeadTiltStep`]) with the grid's size and what to
/// change; those of [`super::FreeRange::check_rotation_grid`].
pub(super) fn check_cells(options: &Options, points: usize, largest: f64) -> Result<()> {
    let Some(l) = &options.free.lead_tilt() else {
        return (options.free.tool_rotation()).map_or(Ok(()), |f| f.check_rotation_grid(points));
    };
    let per = lean_count(l, largest);
    let angles = options
        .free
        .tool_rotation()
        .map_or(1.0, |f| f.angle_count());
    let cells = per * angles * points as f64;
    if cells <= MAX_GRID_CELLS {
        return Ok(());
    }
    Err(Error::InvalidOption {
        option: JobOption::LeadTiltStep,
        message: format!(
            "{} deg within a cone of {} deg makes {per} leans x {angles} rotations x {points} path points = {cells:.3e} cells; at most {:.0e} (a larger step, a smaller cone, a coarser rotation grid or a shorter path)",
            number(l.step.to_degrees()),
            number(largest.to_degrees()),
            MAX_GRID_CELLS
        ),
    })
}

/// [`check_cells`] while a path streams in, `read` points read so far (its length unknown):
/// refuses a grid past [`MAX_GRID_CELLS`] naming the states per path point
/// (leans x rotations) and the most path points the limit allows, never a count of the path's
/// points.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::LeadTiltStep`], or [`JobOption::ToolRotationStep`]
/// without a free lean) with the states per point and what to change.
pub(super) fn check_streaming(options: &Options, read: usize, largest: f64) -> Result<()> {
    if check_cells(options, read, largest).is_ok() {
        return Ok(());
    }
    let angles = options
        .free
        .tool_rotation()
        .map_or(1.0, |f| f.angle_count());
    let (option, grid, per, change) =
        match (&options.free.lead_tilt(), &options.free.tool_rotation()) {
            (Some(l), _) => (
                JobOption::LeadTiltStep,
                format!(
                    "{} deg within a cone of {} deg makes {} leans x {angles} rotations",
                    number(l.step.to_degrees()),
                    number(largest.to_degrees()),
                    lean_count(l, largest)
                ),
                lean_count(l, largest),
                "a larger step, a smaller cone, a coarser rotation grid or a shorter path",
            ),
            (None, Some(f)) => (
                JobOption::ToolRotationStep,
                format!(
                    "{} deg with a range of +-{} deg makes {angles} rotations",
                    number(f.step.to_degrees()),
                    number(f.range.to_degrees())
                ),
                1.0,
                "a larger step, a smaller range or a shorter path",
            ),
            (None, None) => return Ok(()),
        };
    let states = per * angles;
    let limit = MAX_GRID_CELLS;
    let most = match (limit / states).floor() {
        0.0 => "not one path point".to_string(),
        n => format!("at most {n} path points"),
    };
    Err(Error::InvalidOption {
        option,
        message: format!(
            "{grid} = {states} states per path point; the grid holds at most {limit:.0e} cells: {most} ({change})"
        ),
    })
}

/// The number of `(lead, tilt)` states of `free` within cones up to `largest` (rad), as a
/// float: `(2 floor(largest / max_step) + 1)^2`.
pub(super) fn lean_count(free: &LeadTilt, largest: f64) -> f64 {
    (2.0 * (largest / free.step + 1e-9).floor() + 1.0).powi(2)
}

/// The lean states of the grid over cones whose largest is `largest` (rad): the offsets of lead
/// and tilt (`k max_step` for `|k| <= floor(largest / max_step)`, ascending), and every
/// `(lead, tilt)` pair, the tilt's index running fastest.
struct Leans {
    /// The offsets of either axis, rad.
    pub offsets: Vec<f64>,
    /// The grid's spacing and largest step, rad.
    pub step: f64,
    /// Every `(lead, tilt)` pair, rad.
    pub states: Vec<(f64, f64)>,
}

impl Leans {
    /// The leans of `free` within cones up to `largest`, rad; `None` without `free`: the one
    /// state `(0, 0)`.
    pub(crate) fn new(free: Option<&LeadTilt>, largest: f64) -> Self {
        let Some(free) = free else {
            return Leans {
                offsets: Vec::new(),
                step: 1.0,
                states: vec![(0.0, 0.0)],
            };
        };
        let offsets = offsets(largest, free.step);
        let states = (offsets.iter())
            .flat_map(|&l| offsets.iter().map(move |&t| (l, t)))
            .collect();
        Leans {
            offsets,
            step: free.step,
            states,
        }
    }
}

/// A lean of the tool axis at every point: the lead and the tilt (rad), each point's lean frame
/// ([`lean_frames`]) and cone (rad; a lean beyond it is not a state there).
#[derive(Clone, Copy)]
pub(super) struct Lean<'a> {
    /// The lead, rad.
    pub lead: f64,
    /// The tilt, rad.
    pub tilt: f64,
    /// Each point's `[f, c]`.
    pub frames: &'a [[Vector3<f64>; 2]],
    /// Each point's cone's half angle, rad.
    pub cones: &'a [f64],
}

impl Lean<'_> {
    /// Whether the lean is none.
    pub(crate) fn zero(&self) -> bool {
        self.lead == 0.0 && self.tilt == 0.0
    }

    /// Whether the lean `(lead, tilt)` (rad; this lean's own, or a refined line's at the
    /// point) is within point `i`'s cone.
    pub(crate) fn inside(&self, i: usize, lead: f64, tilt: f64) -> bool {
        lead.hypot(tilt) <= self.cones[i] * (1.0 + 1e-12)
    }
}

/// The free lead and tilt of a path: the grid's leans, each point's lean frame and cone.
pub(super) struct Leaning {
    leans: Leans,
    frames: Vec<[Vector3<f64>; 2]>,
    cones: Vec<f64>,
}

impl Leaning {
    /// The leaning of `free` for points at `poses` (their nominal TCP poses, in one frame) with
    /// their `cones` (rad, one per point); the one state of no lean without `free`.
    pub(super) fn new(free: Option<&LeadTilt>, poses: &[Isometry3<f64>], cones: Vec<f64>) -> Self {
        let largest = cones.iter().copied().fold(0.0, f64::max);
        Leaning {
            leans: Leans::new(free, largest),
            frames: free.map_or(Vec::new(), |_| lean_frames(poses)),
            cones,
        }
    }

    /// The number of lean states (1 without a free lean).
    pub(crate) fn len(&self) -> usize {
        self.leans.states.len()
    }

    /// State `k`'s lean of every point; `None` without a free lean.
    pub(super) fn at(&self, k: usize) -> Option<Lean<'_>> {
        let (lead, tilt) = self.leans.states[k];
        (!self.leans.offsets.is_empty()).then_some(Lean {
            lead,
            tilt,
            frames: &self.frames,
            cones: &self.cones,
        })
    }

    /// The offsets of the lead and of the tilt, rad, ascending (empty without a free lean).
    pub(crate) fn offsets(&self) -> &[f64] {
        &self.leans.offsets
    }

    /// The grid's spacing and largest step of the lead and the tilt, rad.
    pub(crate) fn step(&self) -> f64 {
        self.leans.step
    }
}

/// Each point's lean frame `[f, c]` (unit vectors, the frame of `poses`): `f` the feed
/// direction across the tool axis (the TCP's motion from the previous point, the first point's
/// to the second, a point that does not move the previous one's), `c = z x f` across the feed;
/// where the motion has no part across the axis (a plunge, a single point) the tool's own x
/// axis is `f`.
pub(super) fn lean_frames(poses: &[Isometry3<f64>]) -> Vec<[Vector3<f64>; 2]> {
    let mut previous: Option<Vector3<f64>> = None;
    (0..poses.len())
        .map(|i| {
            let here = poses[i].translation.vector;
            let motion = match i {
                0 => poses.get(1).map(|p| p.translation.vector - here),
                _ => Some(here - poses[i - 1].translation.vector),
            };
            let z = poses[i].rotation * Vector3::z();
            let across = motion
                .map(|m| m - z * m.dot(&z))
                .filter(|a| a.norm() > 1e-9)
                .map(|a| a.normalize())
                .or(previous.map(|p: Vector3<f64>| (p - z * p.dot(&z)).normalize()))
                .filter(|a| a.iter().all(|v| v.is_finite()))
                .unwrap_or(poses[i].rotation * Vector3::x());
            previous = Some(across);
            [across, z.cross(&across)]
        })
        .collect()
}

/// The rotation (the frame of `frame`) that leans a tool by `lead` (towards `f`) and `tilt`
/// (towards `c`), rad: the rotation by `sqrt(lead^2 + tilt^2)` about `lead c - tilt f`, which
/// takes the tool's z to `cos(a) z + sin(a) (lead f + tilt c) / a`, `a` the lean's angle.
pub fn lean(frame: &[Vector3<f64>; 2], lead: f64, tilt: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_scaled_axis(frame[1] * lead - frame[0] * tilt)
}
