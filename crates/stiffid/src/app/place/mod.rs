//! The place job: where to clamp the part so that a machining program's error bound is least.
//!
//! The part frame (`[workpiece] base_from_part`) moves, and with it the work ([`Work`]) in it: a
//! G-code program's points (its coordinates are the part frame's), or a path file's rows, whose
//! TCP poses are read in the part frame (not in the base frame, as `compensate` reads them) and
//! whose `base` wrenches turn with the part ([`read_path`]), or a robot program's Cartesian
//! targets in the part frame (a KRL `$BASE` or a RAPID work object equal to the setup's
//! `[workpiece]`, an LS user frame `UF : n`; [`stiffid_machining::program::cartesian`]), the
//! controller's inverse kinematics in the shoulder, elbow and wrist their configuration data
//! name at every placement. A robot program with joint targets is refused (`Work::check`):
//! axis angles stay where they are when the part moves, as are targets in another frame. The
//! part frame moves within a region of the cell: its origin's x and y in the robot base frame within
//! [`Region::x`] and [`Region::y`], turned about the base z axis (the table's normal, through the
//! part's origin) by an angle within [`Region::rotation`] from the setup's own rotation; with
//! [`Region::free`] also its height and a tilt about the base x and y axes, the six degrees of
//! freedom: `R = Rz(a) Ry(b) Rx(c) R_own`. At every placement tried the work is compensated
//! ([`stiffid_machining::compensate()`]: every point reachable by inverse kinematics from the
//! start posture without a change of configuration, every compensated posture within the joint
//! limits), and the placement is feasible when every axis angle stays [`Request::margin`] from
//! its joint limits, the TCP Jacobian's condition number stays below
//! [`Request::max_condition`] (away from singularities) and, with a `[cell]`, every posture
//! passes the cell's floor, obstacle and self-collision checks. Its cost is the path's largest
//! error bound ([`stiffid_machining::compensate::budget::Budget`], `--objective max`) or their sum.
//!
//! The search (`search`) is global: a grid over x, y and the rotation, seeded random samples
//! over every coordinate, then compass searches from the best distinct placements; the result
//! is the same for a seed whatever the number of threads. Beside it, the same search maximises
//! the smallest distance to the joint limits alone (the placement a reach check picks, as CAM
//! for robots does), and the setup's own placement is evaluated: the report gives the gain
//! against both. The placement chosen is never worse than the own one (when that lies in the
//! region) or the reach-only one: either wins where the search found nothing better.
//!
//! Stiffness-based workpiece placement: Caro, Dumas, Garnier and Furet, "Workpiece placement
//! optimization for machining operations with a KUKA KR270-2 robot", IEEE ICRA 2013.

pub mod document;
mod evaluate;
mod free;
// The turns probe's steps, public for their table test (not API).
#[doc(hidden)]
pub mod turns;
mod work;
pub mod written;

pub use evaluate::Evaluation;
pub use work::{read_path, read_program, read_program_with, Work};
pub use written::with_workpiece;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use std::collections::HashMap;
use std::sync::Mutex;
use stiffid_core::cell::Checker;
use stiffid_core::common::words::number;
use stiffid_core::{Error, Result, Setup};
pub use stiffid_design::search::compass::Effort;
use stiffid_design::search::compass::{self, Space};
use stiffid_machining::compensate::{Aggregate, Compliance, Options};

/// Where the part may go, SI, base frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Region {
    /// The part origin's x range, m.
    pub x: [f64; 2],
    /// The part origin's y range, m.
    pub y: [f64; 2],
    /// The rotation about the base z axis from the setup's own, rad, within +-pi.
    pub rotation: [f64; 2],
    /// The six degrees of freedom: also the height and the tilts.
    pub free: Option<Free>,
}

/// The height and tilt of a free placement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Free {
    /// The part origin's z range, m.
    pub z: [f64; 2],
    /// The tilt about the base x and the base y axis stays within `+-tilt`, rad.
    pub tilt: f64,
}

impl Region {
    /// The largest extent of a range of lengths, m.
    pub(crate) const MAX_EXTENT_M: f64 = 20.0;
    /// The largest tilt, deg.
    pub(crate) const MAX_TILT_DEG: f64 = 45.0;
    /// How far the part may move up or down from its own height by default, mm.
    pub(crate) const DEFAULT_HEIGHT_MM: f64 = 100.0;
    /// The largest tilt by default (`--free tilt`), deg.
    pub(crate) const DEFAULT_TILT_DEG: f64 = 10.0;

    /// The region in the front ends' units: `region_mm` `[x0, x1, y0, y1]`, `rotation_deg`
    /// `[a0, a1]`, and `free` the texts of `place --free` ([`Free::parse`]; `own_z` the part's
    /// own height, m).
    ///
    /// # Errors
    /// Those of [`Free::parse`].
    pub fn from_mm_deg<S: AsRef<str>>(
        region_mm: [f64; 4],
        rotation_deg: [f64; 2],
        free: &[S],
        own_z: f64,
    ) -> Result<Self> {
        Ok(Region {
            x: [region_mm[0] * 1e-3, region_mm[1] * 1e-3],
            y: [region_mm[2] * 1e-3, region_mm[3] * 1e-3],
            rotation: rotation_deg.map(f64::to_radians),
            free: Free::parse(free, own_z)?,
        })
    }

    /// Checks every range: finite, lower <= upper, lengths within +-[`Self::MAX_EXTENT_M`], the
    /// rotation within +-180 deg, the tilt within [0, [`Self::MAX_TILT_DEG`]].
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming the range (`region_mm`, `rotation_deg`, `free`: the height
    /// `z` in the base frame or the `tilt`) and the values, in mm and deg.
    pub(crate) fn validate(&self) -> Result<()> {
        let m = Self::MAX_EXTENT_M;
        let deg = 180.0 / std::f64::consts::PI;
        let mut ranges = vec![
            ("region_mm", "", self.x, 1e3, m),
            ("region_mm", "", self.y, 1e3, m),
            ("rotation_deg", "", self.rotation, deg, std::f64::consts::PI),
        ];
        if let Some(f) = &self.free {
            ranges.push(("free", "z in the base frame, mm: ", f.z, 1e3, m));
            let most = Self::MAX_TILT_DEG.to_radians();
            ranges.push(("free", "tilt, deg: ", [0.0, f.tilt], deg, most));
        }
        for (field, what, [a, b], scale, most) in ranges {
            let ok = a.is_finite() && b.is_finite() && a <= b && a >= -most && b <= most;
            if !ok {
                return Err(Error::InvalidField {
                    field: field.into(),
                    message: format!(
                        "{what}{}, {}: expected two numbers, the first no larger, within +-{}",
                        number(a * scale),
                        number(b * scale),
                        number(most * scale)
                    ),
                });
            }
        }
        Ok(())
    }

    /// The search's box: `[x, y, a]`, then with [`Region::free`] `[z, c, b]`; the tolerances
    /// 1 mm and 0.1 deg.
    fn space(&self) -> Space {
        let (tm, ta) = (1e-3, 0.1f64.to_radians());
        let mut space = Space {
            lower: vec![self.x[0], self.y[0], self.rotation[0]],
            upper: vec![self.x[1], self.y[1], self.rotation[1]],
            tolerance: vec![tm, tm, ta],
            gridded: 3,
        };
        if let Some(f) = &self.free {
            space.lower.extend([f.z[0], -f.tilt, -f.tilt]);
            space.upper.extend([f.z[1], f.tilt, f.tilt]);
            space.tolerance.extend([tm, ta, ta]);
        }
        space
    }
}

/// The pose of the part at the search's coordinates `x` (module docs) from its own `own`.
fn pose(own: &Isometry3<f64>, x: &[f64]) -> Isometry3<f64> {
    let z = x.get(3).copied().unwrap_or(own.translation.vector.z);
    let (c, b) = (
        x.get(4).copied().unwrap_or(0.0),
        x.get(5).copied().unwrap_or(0.0),
    );
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), x[2])
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), b)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), c);
    Isometry3::from_parts(Translation3::new(x[0], x[1], z), turn * own.rotation)
}

/// What to place and how.
pub struct Request<'a> {
    /// The setup, with its `[workpiece]` (the own placement).
    pub setup: &'a Setup,
    /// The setup file's text, written back with the new `[workpiece]`.
    pub setup_text: &'a str,
    /// The joint compliance.
    pub compliance: &'a Compliance,
    /// What is placed: a G-code program and its process, or a path file's points, each in the
    /// part frame ([`Work`]).
    pub work: Work<'a>,
    /// The compensation's options (start posture, level, force tolerance).
    pub options: &'a Options,
    /// Where the part may go.
    pub region: Region,
    /// The peak bound (`Max`) or the sum.
    pub objective: Aggregate,
    /// The smallest distance of every axis angle to its joint limits, rad, in [0, pi/2].
    pub margin: f64,
    /// The largest condition number of the TCP Jacobian, >= 1.
    pub max_condition: f64,
    /// How the search spends its evaluations ([`Effort`]); [`Request::EFFORT`] by default.
    pub effort: Effort,
}

impl Request<'_> {
    /// The default effort: a 5-value grid per coordinate, 32 samples, 3 compass searches, seed 1.
    pub const EFFORT: Effort = Effort {
        grid: 5,
        samples: 32,
        starts: 3,
        seed: 1,
    };
    /// The most grid values per coordinate.
    pub(crate) const MAX_GRID: usize = 21;
    /// The most samples.
    pub(crate) const MAX_SAMPLES: usize = 10_000;
    /// The most compass searches.
    pub(crate) const MAX_STARTS: usize = 16;
}

/// What the place job found. It serialises to its document, `stiffid place --json`, through the
/// borrowed view [`document::Document`] ([`Report::document`]: its placement beside the setup's
/// own, mm and deg), built as it is written.
#[derive(Debug, Clone)]
pub struct Report {
    /// The placement chosen.
    pub placed: Evaluation,
    /// The setup's own placement, or why it is not feasible.
    pub own: std::result::Result<Evaluation, String>,
    /// The setup's own part frame in the robot base frame (`[workpiece] base_from_part`), m.
    pub own_frame: Isometry3<f64>,
    /// The placement a reach check alone picks: the largest smallest distance to the joint
    /// limits over the region.
    pub reach: Evaluation,
    /// The objective minimised.
    pub objective: Aggregate,
    /// Placements evaluated (each once), both searches and the own one.
    pub evaluations: usize,
    /// The setup file's text with the chosen `[workpiece]` ([`with_workpiece`]).
    pub setup_text: String,
    /// What to look at before trusting the placement: other turns of the part as good as the
    /// chosen one ([`turns`]).
    pub warnings: Vec<stiffid_core::common::warning::Warning>,
}

impl Report {
    /// The value of the objective at an evaluation, m.
    pub(crate) fn cost(&self, e: &Evaluation) -> f64 {
        cost(self.objective, e)
    }

    /// The document this report is written as (`stiffid place --json`, Python's
    /// `stiffid.place(...)`), to read: what the command's text prints.
    pub fn document(&self) -> document::Document<'_> {
        document::Document::new(self)
    }
}

impl serde::Serialize for Report {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        self.document().serialize(s)
    }
}

fn cost(objective: Aggregate, e: &Evaluation) -> f64 {
    match objective {
        Aggregate::Max => e.peak,
        Aggregate::Sum => e.sum,
    }
}

/// The place job's report, which is its document (serialised through [`document::Document`]).
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// Runs the place job (module docs).
///
/// # Errors
/// [`Error::InvalidField`] for a region, margin, condition or effort outside its limits, a setup
/// without `[workpiece]` or `[tool] tcp_mm`, work the part cannot carry (`Work::check`: a robot
/// program's joint targets, a path file's axis angles), and no feasible placement in the region (naming why the
/// setup's own placement fails); those of [`Options::validate`].
pub fn run(request: &Request<'_>) -> Result<Outcome> {
    Ok(Outcome {
        report: find(request)?,
        document: crate::app::Itself,
    })
}

/// What [`run`] finds.
fn find(request: &Request<'_>) -> Result<Report> {
    check(request)?;
    let setup = request.setup;
    let own = *setup.workpiece().ok_or_else(|| Error::InvalidField {
        field: "workpiece.base_from_part".into(),
        message: format!("missing in setup {}: placement starts from the part's own frame ([workpiece] base_from_part)", setup.name()),
    })?;
    if setup.robot().part().is_some() {
        return Err(Error::InvalidField {
            field: "workpiece.base_from_part".into(),
            message: format!("setup {}: the part's frame is the one the calibration located from the reflectors on the table or the part ([part] of its calibrated robot file): that part is clamped already; choose a new part's placement on a setup with the nominal robot, then locate it (calibrate --update with the reflectors' readings)", setup.name()),
        });
    }
    let context = context(request);
    let space = request.region.space();
    // Both searches start from the same grid and samples: each placement is evaluated once.
    let cache: Mutex<HashMap<Vec<u64>, Option<Evaluation>>> = Mutex::default();
    let at = |x: &[f64]| {
        let key: Vec<u64> = x.iter().map(|v| v.to_bits()).collect();
        let known = cache
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .get(&key)
            .cloned();
        known.unwrap_or_else(|| {
            let e = context.evaluate(&pose(&own, x)).ok();
            let mut cache = cache.lock().unwrap_or_else(|e| e.into_inner());
            cache.insert(key, e.clone());
            e
        })
    };
    let objective = request.objective;
    let (best, _) = compass::minimise(&space, &request.effort, |x| {
        at(x).map(|e| cost(objective, &e))
    });
    let (reach, _) = compass::minimise(&space, &request.effort, |x| at(x).map(|e| -e.limit_margin));
    let own_evaluation = context.evaluate(&own);
    let (Some(best), Some(reach)) = (best, reach) else {
        let why = match &own_evaluation {
            Ok(_) => "the setup's own placement is feasible but outside the region".to_string(),
            Err(e) => format!("at the setup's own placement: {e}"),
        };
        return Err(Error::InvalidField {
            field: "region_mm".into(),
            message: format!("no placement tried in the region is feasible (every point reachable, {} deg from the joint limits, condition number at most {}); {why}", number(request.margin.to_degrees()), number(request.max_condition)),
        });
    };
    let reach = at(&reach.x).expect("a feasible point stays feasible");
    let mut placed = at(&best.x).expect("a feasible point stays feasible");
    let inside = |p: &Isometry3<f64>| {
        let t = p.translation.vector;
        (request.region.x[0]..=request.region.x[1]).contains(&t.x)
            && (request.region.y[0]..=request.region.y[1]).contains(&t.y)
            && request.region.rotation[0] <= 0.0
            && request.region.rotation[1] >= 0.0
            && request
                .region
                .free
                .is_none_or(|f| (f.z[0]..=f.z[1]).contains(&t.z))
    };
    let mut candidates = vec![reach.clone()];
    candidates.extend(
        own_evaluation
            .iter()
            .filter(|e| inside(&e.base_from_part))
            .cloned(),
    );
    for c in candidates {
        if cost(objective, &c) < cost(objective, &placed) {
            placed = c;
        }
    }
    let cache = cache.into_inner().unwrap_or_else(|e| e.into_inner());
    let tried = cache.len();
    let searched: Vec<Evaluation> = cache.into_values().flatten().collect();
    let turn_of = |p: &Isometry3<f64>| {
        stiffid_core::robot::file::rpy(&(p.rotation * own.rotation.inverse()))[2]
    };
    let probes = turns::probes(&placed.base_from_part, turn_of, request.region.rotation);
    let probed = turns::evaluated(&probes, |p| context.evaluate(p).ok());
    let evaluations = tried + probes.len() + 1;
    let others: Vec<Evaluation> = searched.into_iter().chain(probed).collect();
    let what = match objective {
        Aggregate::Max => "largest",
        Aggregate::Sum => "summed",
    };
    let warnings = turns::warning(&placed, &others, |e| cost(objective, e), what);
    Ok(Report {
        warnings: warnings.into_iter().collect(),
        setup_text: with_workpiece(request.setup_text, &placed.base_from_part),
        placed,
        own: own_evaluation,
        own_frame: own,
        reach,
        objective,
        evaluations,
    })
}

/// The evaluation of the part placed at `base_from_part` (its frame in the robot base frame)
/// under the request's checks and objective (module docs), or why it is not feasible there; the
/// figures [`run`] compares its placements by.
///
/// # Errors
/// Those of [`run`]'s checks of the request (not the region).
pub fn evaluate(
    request: &Request<'_>,
    base_from_part: &Isometry3<f64>,
) -> Result<std::result::Result<Evaluation, String>> {
    check(request)?;
    Ok(context(request).evaluate(base_from_part))
}

/// What a placement is checked against.
fn context<'a>(request: &Request<'a>) -> evaluate::Context<'a> {
    let setup = request.setup;
    evaluate::Context {
        setup,
        compliance: request.compliance,
        work: request.work,
        options: request.options,
        margin: request.margin,
        max_condition: request.max_condition,
        checker: setup.cell().map(|_| Checker::new(setup)),
    }
}

/// Checks the request's limits.
fn check(request: &Request<'_>) -> Result<()> {
    request.options.validate()?;
    request.region.validate()?;
    let field = |field: &str, message: String| {
        Err(Error::InvalidField {
            field: field.into(),
            message,
        })
    };
    if !(0.0..=std::f64::consts::FRAC_PI_2).contains(&request.margin) {
        return field(
            "margin_deg",
            format!("{}: expected 0 to 90", number(request.margin.to_degrees())),
        );
    }
    if !(request.max_condition >= 1.0 && request.max_condition.is_finite()) {
        return field(
            "max_condition",
            format!(
                "{}: expected a finite number >= 1",
                number(request.max_condition)
            ),
        );
    }
    let e = &request.effort;
    if !(2..=Request::MAX_GRID).contains(&e.grid) {
        return field(
            "grid",
            format!("{}: expected 2 to {}", e.grid, Request::MAX_GRID),
        );
    }
    if e.samples > Request::MAX_SAMPLES {
        return field(
            "samples",
            format!("{}: expected at most {}", e.samples, Request::MAX_SAMPLES),
        );
    }
    if !(1..=Request::MAX_STARTS).contains(&e.starts) {
        return field(
            "starts",
            format!("{}: expected 1 to {}", e.starts, Request::MAX_STARTS),
        );
    }
    if !request.setup.tcp_given() {
        return field("tool.tcp_mm", format!("missing in setup {}: placement compensates the cutting tool's centre point ([tool] tcp_mm)", request.setup.name()));
    }
    request.work.check(request.setup)
}
