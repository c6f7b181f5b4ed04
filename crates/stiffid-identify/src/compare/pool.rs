//! The candidates of the model comparison: the families' springs placed on the robot, the setup's
//! declared candidates, and those dropped because the data could never tell them from a drive or
//! from an earlier candidate.
//!
//! The pool, in this order:
//! - the setup's declared candidates (`[[model.spring]]` with `candidate = true`), first; a
//!   declared candidate named like a family's is refused
//!   (`stiffid_core::model::check_declared_names`);
//! - `tilt<k>_x`, `tilt<k>_y`, `tilt<k>_z` (k = 1..6): rotations about the three axes of link k's
//!   frame through its origin (the tilt of joint k's bearing, the bending lumped at the joint);
//! - `bend<k>_x`, `bend<k>_y`, `bend<k>_z` (k = 1..5): rotations about the same three axes through
//!   the middle of link k, halfway from its frame's origin to link k+1's at the zero posture
//!   (bending of the link itself), for a link at least [`MIN_BEND_LENGTH`] long;
//! - for a robot on a linear track, `carriage_x`, `carriage_rx`, `carriage_ry`: the carriage
//!   ([`stiffid_core::model::Family::Carriage`]), before the base mount so that a base spring on the
//!   same line is the one dropped;
//! - `base_x`, `base_y`, `base_z`, `base_rx`, `base_ry`, `base_rz`: the base mount
//!   ([`stiffid_core::model::Family::Base`]);
//! - `tool_x`, `tool_y`, `tool_z`: the tool ([`stiffid_core::model::Family::Tool`]);
//! - `lost<j>` (j = 1..6): a lost motion of joint j, `b s(tau_j)` about joint j's own axis
//!   ([`Law::LostMotion`], smoothed over [`stiffid_core::model::DEFAULT_SMOOTHING`] Nm);
//! - `load<j>` (j = 1..6): a load-dependent compliance of joint j, the `c1` of
//!   `(c0 + c1 |tau_j|) tau_j` ([`Law::LoadDependent`]).
//!
//! The last two are fixed in link j about joint j's axis through the point where the robot's
//! zero posture puts it, so their load is the kinematic joint torque `tau_j`.
//!
//! **Dropped.** A rotational spring's column of the observation matrix depends only on the line
//! of its axis at each posture (`[u x (p - o); u]` and the load `u . ((p_f - o) x f) + u . m`,
//! unchanged when `u` turns sign or `o` slides along the axis), a translation's only on its
//! direction. So a rotation whose axis is a joint's axis at every posture gives a column the
//! drives already give (exactly that drive's, in kinematic coordinates; a combination of the
//! drives' in axis coordinates), and two candidates of the same law on the same line (or
//! direction) at every posture give the same column (a nonlinear law's column differs from the
//! drive's by its response, so `lost<j>` and `load<j>` are kept): such a candidate can never be identified, and is dropped with
//! the reason. The test compares the lines at three postures of the setup's bounds (the middle
//! and two fixed off-centre ones) to 1e-9 in direction and 1e-7 m in position. A spring already
//! in the setup's model is not a candidate either.

use nalgebra::{Unit, Vector3, Vector6};
use stiffid_core::model::{Family, Kind, Law, Placed, Spring};
use stiffid_core::Frames;
use stiffid_core::{Result, Robot, Setup};

/// The shortest link that gets `bend` candidates, m (shorter, its middle is its joint).
pub(crate) const MIN_BEND_LENGTH: f64 = 0.05;

/// A candidate left out of the pool, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct Dropped {
    /// The candidate's name.
    pub name: String,
    /// Why the data could never identify it, in words.
    pub reason: String,
}

/// The candidates of a comparison and those dropped.
#[derive(Debug, Clone, PartialEq)]
pub struct Pool {
    /// The candidates, in the order of the module docs.
    pub candidates: Vec<Spring>,
    /// Each candidate's family (`CANDIDATE_FAMILIES`), in the order of `candidates`.
    pub families: Vec<&'static str>,
    /// Those dropped, with the reason.
    pub dropped: Vec<Dropped>,
}

/// Whether `load_levels` load levels per posture separate a lost motion or a load-dependent
/// compliance from the springs, in words ([`stiffid_core::model::Law`]): the data's most load levels in
/// one posture for a comparison, the setup's load steps (1 without) for a design.
pub fn nonlinear_separation(load_levels: usize) -> String {
    match load_levels {
        0 | 1 => "one load level per posture: a lost motion or a load-dependent compliance differs from a spring only through how the load changes from posture to posture, so it also takes up whatever else changes with the posture; trust it only when several load levels in the same posture (load steps) or a wide range of loads confirm it".into(),
        n => format!("up to {n} load levels per posture: each posture's load-deflection curve separates a lost motion (its intercept) and a load-dependent compliance (its curvature) from the springs"),
    }
}

/// The candidate families by name, for `--candidates`.
pub(crate) const CANDIDATE_FAMILIES: [&str; 8] = [
    "tilt", "bend", "carriage", "base", "tool", "lost", "load", "declared",
];

/// Every candidate of the module docs on the setup's robot, before any is dropped, each with its
/// family's name.
fn every_candidate(setup: &Setup) -> Vec<(&'static str, Spring)> {
    let robot = setup.robot();
    let mut out: Vec<(&'static str, Spring)> = setup
        .candidate_springs()
        .iter()
        .map(|s| ("declared", s.clone()))
        .collect();
    let rotation = |name: String, link, axis: Vector3<f64>, point| Spring {
        name,
        kind: Kind::Rotation,
        link,
        axis: Unit::new_normalize(axis),
        point,
        nominal_stiffness: None,
        law: Law::Linear,
    };
    let axes = [
        ("x", Vector3::x()),
        ("y", Vector3::y()),
        ("z", Vector3::z()),
    ];
    for k in 1..=6 {
        for (a, e) in axes {
            out.push((
                "tilt",
                rotation(format!("tilt{k}_{a}"), k, e, Vector3::zeros()),
            ));
        }
    }
    let zero = robot.frames(&Vector6::zeros());
    for k in 1..=5 {
        let next = zero.joints[k - 1].inverse() * zero.joints[k];
        let middle = next.translation.vector * 0.5;
        if 2.0 * middle.norm() >= MIN_BEND_LENGTH {
            for (a, e) in axes {
                out.push(("bend", rotation(format!("bend{k}_{a}"), k, e, middle)));
            }
        }
    }
    let families = [
        (Family::Carriage, "carriage"),
        (Family::Base, "base"),
        (Family::Tool, "tool"),
    ];
    for (f, name) in families {
        // The carriage's springs exist only on a track: elsewhere the family gives none.
        let springs = f.springs(robot, &[], None, None, "candidates");
        out.extend(springs.unwrap_or_default().into_iter().map(|s| (name, s)));
    }
    let lost = Law::LostMotion {
        smoothing: stiffid_core::model::DEFAULT_SMOOTHING,
    };
    for (family, law) in [("lost", lost), ("load", Law::LoadDependent)] {
        for j in 1..=6 {
            let link = zero.joints[j - 1].inverse();
            let axis = link.rotation * zero.axis_directions[j - 1];
            let point = link * nalgebra::Point3::from(zero.axis_points[j - 1]);
            let mut s = rotation(format!("{family}{j}"), j, axis, point.coords);
            s.law = law;
            out.push((family, s));
        }
    }
    out
}

/// Three postures of the setup's bounds: the middle and two fixed off-centre ones.
fn probe_frames(setup: &Setup, robot: &Robot) -> Vec<Frames> {
    let b = setup.bounds();
    let mid = (b.lower + b.upper) * 0.5;
    let half = (b.upper - b.lower) * 0.5;
    let off = [
        Vector6::new(0.31, -0.47, 0.23, 0.61, -0.37, 0.53),
        Vector6::new(-0.43, 0.29, -0.57, -0.27, 0.49, -0.33),
    ];
    std::iter::once(mid)
        .chain(off.iter().map(|o| mid + half.component_mul(o)))
        .map(|q| robot.frames(&q))
        .collect()
}

/// Whether two placed springs lie on the same line (rotations) or along the same direction
/// (translations).
fn same_line(a: &Placed, b: &Placed) -> bool {
    if a.kind != b.kind || a.u.cross(&b.u).norm() > 1e-9 {
        return false;
    }
    a.kind == Kind::Translation || (b.o - a.o).cross(&a.u).norm() <= 1e-7
}

/// Why `spring` is dropped given the candidates kept so far, or `None`.
fn reason(probes: &[Frames], spring: &Spring, kept: &[Spring], model: &[Spring]) -> Option<String> {
    let placed: Vec<Placed> = probes.iter().map(|f| spring.placed(f)).collect();
    let everywhere = |other: &dyn Fn(&Frames) -> Placed| {
        probes
            .iter()
            .zip(&placed)
            .all(|(f, p)| same_line(p, &other(f)))
    };
    if spring.kind == Kind::Rotation && spring.law.is_linear() {
        for j in 0..6 {
            let joint = |f: &Frames| Placed {
                kind: Kind::Rotation,
                u: f.axis_directions[j],
                o: f.axis_points[j],
            };
            if everywhere(&joint) {
                return Some(format!(
                    "its axis is joint {}'s own: the drives already give its column",
                    j + 1
                ));
            }
        }
    }
    let twin = |s: &Spring| s.law == spring.law && everywhere(&|f: &Frames| s.placed(f));
    if let Some(s) = model.iter().find(|s| twin(s)) {
        return Some(format!(
            "the same column as the model's spring '{}' (the same axis)",
            s.name
        ));
    }
    kept.iter().find(|s| twin(s)).map(|s| {
        format!(
            "the same column as the candidate '{}' (the same axis at every posture)",
            s.name
        )
    })
}

/// The pool of the module docs: the candidates of the families named in `families` (all of
/// `CANDIDATE_FAMILIES` for `None`) or named one by one in `names`, each kept unless it
/// duplicates a drive, a spring of the setup's model or an earlier candidate (then in `dropped`
/// with the reason), and never one already in the setup's model (by name).
fn build(setup: &Setup, wanted: &dyn Fn(&str, &Spring) -> bool) -> Pool {
    let probes = probe_frames(setup, setup.robot());
    let model = setup.model().springs();
    let mut pool = Pool {
        candidates: Vec::new(),
        families: Vec::new(),
        dropped: Vec::new(),
    };
    for (family, s) in every_candidate(setup) {
        let taken = |n: &str| {
            model.iter().any(|m| m.name == n)
                || pool.candidates.iter().any(|c| c.name == n)
                || pool.dropped.iter().any(|d| d.name == n)
        };
        if !wanted(family, &s) || taken(&s.name) {
            continue;
        }
        match reason(&probes, &s, &pool.candidates, model) {
            Some(reason) => pool.dropped.push(Dropped {
                name: s.name,
                reason,
            }),
            None => {
                pool.candidates.push(s);
                pool.families.push(family);
            }
        }
    }
    pool
}

/// The default pool: every candidate of the module docs.
pub fn default_pool(setup: &Setup) -> Pool {
    build(setup, &|_, _| true)
}

/// The pool of the candidates named in `names`: families (`CANDIDATE_FAMILIES`; `declared`
/// the setup's declared candidates) or single candidates by name (`tilt3_z`, `bend2_y`,
/// `tool_y`, a declared spring's name), in the pool's order, without repeats.
///
/// # Errors
/// [`stiffid_core::Error::InvalidOption`] ([`stiffid_core::JobOption::Candidates`]) for a name that is neither
/// (the message lists the pool's names), or no candidate left.
pub fn pool_by_name(setup: &Setup, names: &[String]) -> Result<Pool> {
    let all = every_candidate(setup);
    for name in names {
        let known =
            CANDIDATE_FAMILIES.contains(&name.as_str()) || all.iter().any(|(_, s)| s.name == *name);
        if !known {
            let some: Vec<&str> = all.iter().map(|(_, s)| s.name.as_str()).collect();
            return Err(stiffid_core::Error::InvalidOption {
                option: stiffid_core::JobOption::Candidates,
                message: format!(
                    "'{}' is not a candidate: expected a family ({}) or one of: {}",
                    stiffid_core::common::limits::short(name),
                    CANDIDATE_FAMILIES.join(", "),
                    some.join(", ")
                ),
            });
        }
    }
    let pool = build(setup, &|family, s| {
        names.iter().any(|n| n == family || *n == s.name)
    });
    if pool.candidates.is_empty() {
        return Err(stiffid_core::Error::InvalidOption {
            option: stiffid_core::JobOption::Candidates,
            message: match pool.dropped.first() {
                Some(d) => format!("no candidate left: '{}' is dropped ({})", d.name, d.reason),
                None => {
                    "every candidate is already in the setup's model: nothing to compare".into()
                }
            },
        });
    }
    Ok(pool)
}
