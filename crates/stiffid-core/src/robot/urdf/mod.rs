//! Robots from URDF files (parsed by `urdf-rs`; the kinematics are ours).
//!
//! The chain runs from the root link to a tip link: the one named, else the only leaf link, else the
//! only leaf ending a chain of six revolute joints, else `tool0` among several such (ROS-Industrial).
//! Fixed joints along it are folded into the next revolute joint (or into the flange transform after
//! the last one); revolute and continuous joints may turn about any axis. Floating and planar
//! joints in the chain are an error, as is a chain without exactly six revolute joints. The
//! axis map is the identity: axis angles are the URDF joint positions. Joint limits come from each
//! revolute joint's `<limit lower upper>`; continuous joints, and revolute joints without a
//! `<limit>` (urdf-rs reads it as `lower = upper = 0`), are unlimited; an inverted or non-finite
//! limit is an error. Each joint's `<limit velocity>` (rad/s, m/s for a track's prismatic joint)
//! is its axis's largest speed; zero or none: no limit.
//!
//! A robot on a track: prismatic joints before the arm's first revolute joint are the carrier's
//! linear axes ([`crate::robot::external`]; at most three), their directions in the root link's
//! frame (the cell frame), their travel the joint's `<limit>` (m, required); a prismatic joint
//! after it, where the arm's revolute joints are expected, is an error naming the joint. A part on
//! a positioner: a second chain of one or two revolute joints from the root link (through no moving
//! joint of the arm's chain) to a leaf link is the positioner, its axes' lines those of the
//! joints at zero, their travel the joints' limits (a continuous joint: +-175 rad); several such
//! chains are an error, and so is such a chain hanging from a link the arm moves (a positioner
//! axis on the arm's path to the tool: the error names the joint, the link and the arm's joint).
//!
//! Before the XML parser sees the text, its element nesting is bounded (64 levels), so a hostile
//! file cannot overflow the stack. Each link and joint name must be declared once, every joint must
//! name declared links, no link may be the child of two joints, every link must hang from one root,
//! and every number of an origin, axis or limit must be finite and within the limits ([-100, 100]
//! m, [`crate::common::limits::ANGLE_RAD`]).

mod elements;

use super::{Joint, LinkMass, Robot};
use crate::common::limits::{self, JointBox};
use crate::{Error, Result};
use elements::{check_elements, check_text};
use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3, Vector6};
use std::collections::{HashMap, HashSet};
use urdf_rs::JointType;

/// The URDF a [`Robot`] was read from: its text, its tip link and its chain's six revolute
/// joints, base first.
#[derive(Debug, Clone, PartialEq)]
pub struct UrdfSource {
    /// The document as read.
    pub text: String,
    /// The tip link of the chain.
    pub tip: String,
    /// The names of the chain's revolute joints, base first.
    pub joints: [String; 6],
    /// Their `<origin>` transforms (parent link to joint frame, m).
    pub origins: [Isometry3<f64>; 6],
}

/// Parses a URDF document into a [`Robot`]. `source_name` (the file name) is used in errors;
/// `tip` names the tip link; by default the only leaf link, else the only leaf at the end of a
/// chain of six revolute joints, else `tool0` among several (ROS-Industrial URDFs have the leaves
/// `tool0` and `base`). The robot's `source` names the tip link used.
///
/// # Errors
/// [`Error::Parse`] for malformed XML, nesting deeper than 64 levels, an element after the root, or
/// a misspelt element of a joint or of a link's inertial, visual or collision; [`Error::Chain`]
/// when a joint names an undeclared link, a link is the child of two joints, the links do not hang
/// from one root, the tip link is missing or ambiguous, a joint in the chain is not revolute or
/// fixed, has a non-finite or out-of-range number or an inverted limit, the chain does not hold
/// exactly six revolute joints, or a chain of one or two revolute joints (a positioner) hangs from
/// a link the arm moves.
pub fn parse(text: &str, source_name: &str, tip: Option<&str>) -> Result<Robot> {
    let parse_error = |message: String| Error::Parse {
        source_name: source_name.to_string(),
        message,
    };
    check_elements(text).map_err(parse_error)?;
    check_text(text).map_err(parse_error)?;
    let urdf = urdf_rs::read_from_string(text)
        .map_err(|e| parse_error(limits::one_line(&e.to_string())))?;
    let chain_error = |message: String| Error::Chain {
        source_name: source_name.to_string(),
        message,
    };
    let by_child = tree(&urdf).map_err(chain_error)?;
    let tip = match tip {
        Some(t) if urdf.links.iter().any(|l| l.name == t) => t.to_string(),
        Some(t) => {
            let t = limits::short(t);
            return Err(chain_error(format!("no link named '{t}' (the tip link)")));
        }
        None => default_tip(&urdf, &by_child).map_err(chain_error)?,
    };
    let path = chain_to(&tip, &by_child, urdf.joints.len()).map_err(chain_error)?;
    let source = format!("{source_name}, tip link '{}'", limits::short(&tip));
    let world = controller_world(&by_child, urdf.joints.len()).map_err(chain_error)?;
    let mut robot = fold(&path, &urdf.name, &source)
        .and_then(|r| r.with_controller_world(world).map_err(|e| e.to_string()))
        .map_err(chain_error)?;
    let turning = positioner(&urdf, &by_child, &path).map_err(chain_error)?;
    if !turning.is_empty() {
        let mut axes = robot.external().map_or(Vec::new(), |a| a.axes().to_vec());
        axes.extend(turning);
        let axes = super::ExternalAxes::new(axes).map_err(|e| chain_error(e.to_string()))?;
        robot = robot.with_external(Some(axes));
    }
    let masses = masses(&urdf, &path).map_err(chain_error)?;
    let revolute: Vec<&urdf_rs::Joint> = (path.iter().copied())
        .filter(|j| matches!(j.joint_type, JointType::Revolute | JointType::Continuous))
        .collect();
    let mut origins = [Isometry3::identity(); 6];
    for (o, j) in origins.iter_mut().zip(&revolute) {
        *o = pose(j).map_err(chain_error)?;
    }
    Ok(robot.with_masses(masses).with_urdf_source(UrdfSource {
        text: text.to_string(),
        tip,
        joints: std::array::from_fn(|i| revolute[i].name.clone()),
        origins,
    }))
}

/// The rigid bodies of the six moving links from the links' `<inertial>` (a fixed joint's child
/// folded into the link it hangs from, carried into that link's frame: [`LinkMass::moved`],
/// [`LinkMass::plus`]), or none when no link of the chain has mass. Each mass within
/// [`limits::MASS_KG`], each centre within [`limits::LENGTH_M`], each tensor component within
/// [`limits::INERTIA_KG_M2`] and each tensor physical
/// ([`super::dynamics::body::physical`]); the `<inertial>` origin's rotation turns the tensor.
fn masses(
    urdf: &urdf_rs::Robot,
    path: &[&urdf_rs::Joint],
) -> std::result::Result<Option<[LinkMass; 6]>, String> {
    let links: HashMap<&str, &urdf_rs::Link> =
        urdf.links.iter().map(|l| (l.name.as_str(), l)).collect();
    let mut out = [LinkMass::default(); 6];
    let (mut link, mut acc) = (None::<usize>, Isometry3::identity());
    let mut any = false;
    for j in path {
        match j.joint_type {
            JointType::Fixed | JointType::Prismatic => acc *= pose(j)?,
            _ => {
                link = Some(link.map_or(0, |l| l + 1));
                acc = Isometry3::identity();
            }
        }
        let (Some(l), Some(child)) = (link, links.get(j.child.link.as_str())) else {
            continue;
        };
        let body = inertial(child)?;
        out[l.min(5)] = out[l.min(5)].plus(&body.moved(&acc));
        any |= body.mass > 0.0;
    }
    Ok(any.then_some(out))
}

/// The body of a link's `<inertial>`, in the link's frame, its numbers checked.
fn inertial(link: &urdf_rs::Link) -> std::result::Result<LinkMass, String> {
    let i = &link.inertial;
    let name = limits::short(&link.name);
    let check = |what: &str, values: &[f64], range: &limits::Range| {
        limits::check(&format!("link '{name}': inertial {what}"), values, range)
            .map_err(|e| e.to_string())
    };
    check("mass", &[i.mass.value], &limits::MASS_KG)?;
    let c = &i.origin.xyz;
    check("origin xyz", &c[..], &limits::LENGTH_M)?;
    check("origin rpy", &i.origin.rpy[..], &limits::ANGLE_RAD)?;
    let t = &i.inertia;
    let six = [t.ixx, t.iyy, t.izz, t.ixy, t.ixz, t.iyz];
    check("inertia", &six, &limits::INERTIA_KG_M2)?;
    let inertia = super::dynamics::body::tensor(six);
    super::dynamics::body::physical(&inertia)
        .map_err(|m| format!("link '{name}': inertial inertia: {m}"))?;
    let [r, p, y] = [i.origin.rpy[0], i.origin.rpy[1], i.origin.rpy[2]];
    let frame = Isometry3::from_parts(
        Translation3::new(c[0], c[1], c[2]),
        UnitQuaternion::from_euler_angles(r, p, y),
    );
    let body = LinkMass {
        mass: i.mass.value,
        centre: Vector3::zeros(),
        inertia,
    };
    Ok(body.moved(&frame))
}

/// The joints from the root to `tip`, root first.
fn chain_to<'a>(
    tip: &str,
    by_child: &HashMap<&str, &'a urdf_rs::Joint>,
    joint_count: usize,
) -> std::result::Result<Vec<&'a urdf_rs::Joint>, String> {
    let mut path = Vec::new();
    let mut link = tip;
    while let Some(joint) = by_child.get(link) {
        path.push(*joint);
        link = joint.parent.link.as_str();
        if path.len() > joint_count {
            return Err("the joints form a loop".into());
        }
    }
    path.reverse();
    Ok(path)
}

/// The controller's world frame in the root link's frame: the ROS-Industrial `base` link
/// ("base_link to <vendor> World Coordinates", REP 199's `base`), when it hangs from the root
/// through fixed joints and a track's prismatic joints (taken at zero: the world where the
/// carriage stands at 0, as a robot file's `[controller_world]` on a track); the identity
/// otherwise (no such link, the root itself, or a revolute joint on the way).
fn controller_world(
    by_child: &HashMap<&str, &urdf_rs::Joint>,
    joint_count: usize,
) -> std::result::Result<Isometry3<f64>, String> {
    let path = chain_to("base", by_child, joint_count)?;
    if path
        .iter()
        .any(|j| !matches!(j.joint_type, JointType::Fixed | JointType::Prismatic))
    {
        return Ok(Isometry3::identity());
    }
    path.iter()
        .try_fold(Isometry3::identity(), |at, j| Ok(at * pose(j)?))
}

/// Checks the links and joints form one tree (each link and joint name declared once, every
/// joint between declared links, no link the child of two joints, one root) and returns each
/// joint by its child link.
pub(super) fn tree(
    urdf: &urdf_rs::Robot,
) -> std::result::Result<HashMap<&str, &urdf_rs::Joint>, String> {
    let links = unique("link", urdf.links.iter().map(|l| l.name.as_str()))?;
    unique("joint", urdf.joints.iter().map(|j| j.name.as_str()))?;
    let mut by_child = HashMap::new();
    for j in &urdf.joints {
        for (role, link) in [("parent", &j.parent.link), ("child", &j.child.link)] {
            if !links.contains(link.as_str()) {
                return Err(format!(
                    "joint '{}' names the {role} link '{}', which is not declared",
                    limits::short(&j.name),
                    limits::short(link)
                ));
            }
        }
        if let Some(other) = by_child.insert(j.child.link.as_str(), j) {
            return Err(format!(
                "link '{}' is the child of two joints ('{}' and '{}')",
                limits::short(&j.child.link),
                limits::short(&other.name),
                limits::short(&j.name)
            ));
        }
    }
    if let Some(cycle) = cycle(&by_child) {
        return Err(format!("the joints form a loop: {}", limits::short(&cycle)));
    }
    let roots: Vec<&str> = urdf
        .links
        .iter()
        .map(|l| l.name.as_str())
        .filter(|l| !by_child.contains_key(l))
        .collect();
    match roots.len() {
        1 => Ok(by_child),
        0 => Err("every link is the child of a joint: the joints form a loop".into()),
        n => Err(format!(
            "the links are not connected: {n} links have no parent joint ({}); a robot has one root link",
            limits::short(&roots.join(", "))
        )),
    }
}

/// The names of the elements `kind` (links or joints), each declared once: a second element of
/// one name would be passed over where the name is looked up (its mass, its origin written back).
fn unique<'a>(
    kind: &str,
    names: impl Iterator<Item = &'a str>,
) -> std::result::Result<HashSet<&'a str>, String> {
    let mut seen = HashSet::new();
    for name in names {
        if !seen.insert(name) {
            return Err(format!(
                "{kind} '{}' is declared twice",
                limits::short(name)
            ));
        }
    }
    Ok(seen)
}

/// A loop of parent links, as `a -> b -> a`, if any.
fn cycle(by_child: &HashMap<&str, &urdf_rs::Joint>) -> Option<String> {
    let mut done: HashSet<&str> = HashSet::new();
    let mut starts: Vec<&str> = by_child.keys().copied().collect();
    starts.sort_unstable();
    for start in starts {
        let mut seen: Vec<&str> = Vec::new();
        let mut link = start;
        while let Some(joint) = by_child.get(link) {
            if done.contains(link) {
                break;
            }
            if let Some(at) = seen.iter().position(|l| *l == link) {
                let mut names: Vec<&str> = seen[at..].to_vec();
                names.push(link);
                return Some(names.join(" -> "));
            }
            seen.push(link);
            link = joint.parent.link.as_str();
        }
        done.extend(seen);
    }
    None
}

/// The tip link when none is named: the only leaf link; else the only leaf at the end of a chain
/// of six revolute joints; else, among several such leaves, `tool0` (the ROS-Industrial
/// convention, whose URDFs also have a `base` leaf).
pub(super) fn default_tip(
    urdf: &urdf_rs::Robot,
    by_child: &HashMap<&str, &urdf_rs::Joint>,
) -> std::result::Result<String, String> {
    let parents: HashSet<&str> = urdf.joints.iter().map(|j| j.parent.link.as_str()).collect();
    let leaves: Vec<&str> = urdf
        .links
        .iter()
        .map(|l| l.name.as_str())
        .filter(|l| !parents.contains(l))
        .collect();
    let six_revolute = |leaf: &&str| {
        chain_to(leaf, by_child, urdf.joints.len()).is_ok_and(|path| {
            let revolute = [JointType::Revolute, JointType::Continuous];
            path.iter()
                .filter(|j| revolute.contains(&j.joint_type))
                .count()
                == 6
        })
    };
    let ends: Vec<&str> = leaves.iter().copied().filter(six_revolute).collect();
    let name_it =
        "name the tip link (the tip: `--tip` on the command line, `robot_tip` in a setup file)";
    match (leaves.as_slice(), ends.as_slice()) {
        ([one], _) | (_, [one]) => Ok(one.to_string()),
        (_, many) if many.contains(&"tool0") => Ok("tool0".into()),
        ([], _) => Err(format!("no leaf link: {name_it}")),
        (all, []) => Err(format!(
            "no leaf link ({}) ends a chain of six revolute joints: {name_it}",
            limits::short(&all.join(", "))
        )),
        (_, many) => Err(format!(
            "several leaf links end a chain of six revolute joints ({}): {name_it}",
            limits::short(&many.join(", "))
        )),
    }
}

/// The origin of joint `j`, its numbers checked against the limits.
fn pose(j: &urdf_rs::Joint) -> std::result::Result<Isometry3<f64>, String> {
    let (p, name) = (&j.origin, limits::short(&j.name));
    let field = |f: &str| format!("joint '{name}': origin {f}");
    limits::check(&field("xyz"), &p.xyz[..], &limits::LENGTH_M).map_err(|e| e.to_string())?;
    limits::check(&field("rpy"), &p.rpy[..], &limits::ANGLE_RAD).map_err(|e| e.to_string())?;
    Ok(Isometry3::from_parts(
        Translation3::new(p.xyz[0], p.xyz[1], p.xyz[2]),
        UnitQuaternion::from_euler_angles(p.rpy[0], p.rpy[1], p.rpy[2]),
    ))
}

/// The unit axis of joint `j`.
fn axis(j: &urdf_rs::Joint) -> std::result::Result<Unit<Vector3<f64>>, String> {
    let name = limits::short(&j.name);
    let xyz = &j.axis.xyz[..];
    limits::check(&format!("joint '{name}': axis xyz"), xyz, &limits::LENGTH_M)
        .map_err(|e| e.to_string())?;
    Unit::try_new(Vector3::new(xyz[0], xyz[1], xyz[2]), 1e-12)
        .ok_or_else(|| format!("joint '{name}' has a zero axis"))
}

/// The limits `(lower, upper)` of joint `j`, rad: infinite for a continuous joint or a revolute
/// joint without `<limit>` (read as `lower = upper = 0`).
fn joint_limits(j: &urdf_rs::Joint) -> std::result::Result<(f64, f64), String> {
    let (lower, upper) = (j.limit.lower, j.limit.upper);
    let missing = lower == 0.0 && upper == 0.0;
    if j.joint_type == JointType::Continuous || missing {
        return Ok((f64::NEG_INFINITY, f64::INFINITY));
    }
    let name = limits::short(&j.name);
    check_limit(&name, lower, upper, &limits::ANGLE_RAD)?;
    Ok((lower, upper))
}

fn fold(
    path: &[&urdf_rs::Joint],
    name: &str,
    source_name: &str,
) -> std::result::Result<Robot, String> {
    let mut joints = Vec::new();
    let (mut lower, mut upper, mut speeds) = (Vec::new(), Vec::new(), Vec::new());
    let mut acc = Isometry3::identity();
    let mut carrier = Vec::new();
    let mut last = "";
    for j in path {
        match j.joint_type {
            JointType::Fixed => acc *= pose(j)?,
            JointType::Prismatic if joints.is_empty() => {
                acc *= pose(j)?;
                carrier.push(linear_axis(j, &acc)?);
            }
            JointType::Prismatic => {
                return Err(format!(
                    "joint '{}' is Prismatic where the arm's six revolute joints are expected (after joint '{}'): a track's prismatic joint goes before the arm's first revolute joint",
                    limits::short(&j.name),
                    limits::short(last),
                ))
            }
            JointType::Revolute | JointType::Continuous if j.mimic.is_some() => {
                let master = j.mimic.as_ref().map_or("", |m| m.joint.as_str());
                return Err(format!(
                    "joint '{}' mimics joint '{}': a mimic joint follows its master and is no independent sprung axis; stiffid needs six independent revolute joints in the chain (a robot TOML with an axis_map describes coupled axes)",
                    limits::short(&j.name),
                    limits::short(master)
                ));
            }
            JointType::Revolute | JointType::Continuous => {
                last = j.name.as_str();
                joints.push(Joint {
                    pre: acc * pose(j)?,
                    axis: axis(j)?,
                    post: Isometry3::identity(),
                    offset: 0.0,
                });
                let (l, u) = joint_limits(j)?;
                lower.push(l);
                upper.push(u);
                speeds.push(velocity(j)?);
                acc = Isometry3::identity();
            }
            ref other => {
                return Err(format!(
                "joint '{}' is {other:?}; only revolute, continuous and fixed joints are supported",
                limits::short(&j.name)
            ))
            }
        }
    }
    let joints: [Joint; 6] = joints.try_into().map_err(|v: Vec<Joint>| {
        format!(
            "the chain to the tip holds {} revolute joints; expected 6",
            v.len()
        )
    })?;
    let limits = JointBox::new(
        Vector6::from_column_slice(&lower),
        Vector6::from_column_slice(&upper),
    );
    let robot = Robot::new(name, source_name, joints, limits)
        .and_then(|r| r.with_flange(acc))
        .and_then(|r| r.with_max_speeds(Vector6::from_column_slice(&speeds)))
        .map_err(|e| e.to_string())?;
    match carrier.is_empty() {
        true => Ok(robot),
        false => Ok(robot.with_external(Some(
            super::ExternalAxes::new(carrier).map_err(|e| e.to_string())?,
        ))),
    }
}

/// The carrier axis of the prismatic joint `j` whose frame (at zero) is `at` in the root link's
/// frame: its direction there, its travel its `<limit>` (m).
fn linear_axis(
    j: &urdf_rs::Joint,
    at: &Isometry3<f64>,
) -> std::result::Result<super::external::ExternalAxis, String> {
    let name = limits::short(&j.name);
    let (lower, upper) = (j.limit.lower, j.limit.upper);
    if lower == 0.0 && upper == 0.0 {
        return Err(format!(
            "prismatic joint '{name}' (a track) has no <limit lower upper>: an external axis needs its travel, m"
        ));
    }
    check_limit(&name, lower, upper, &limits::LENGTH_M)?;
    let direction = Unit::new_normalize(at.rotation * axis(j)?.into_inner());
    Ok(super::external::ExternalAxis {
        max_speed: velocity(j)?,
        ..super::external::ExternalAxis::linear(&j.name, direction, lower, upper)
    })
}

/// The largest speed of joint `j`, its `<limit velocity>` (rad/s or m/s): infinite (no limit)
/// where it is zero or absent (urdf-rs reads an absent one as 0).
///
/// # Errors
/// A message naming the joint for a negative or non-finite velocity.
fn velocity(j: &urdf_rs::Joint) -> std::result::Result<f64, String> {
    match j.limit.velocity {
        0.0 => Ok(f64::INFINITY),
        v if v > 0.0 && v.is_finite() => Ok(v),
        v => Err(format!(
            "joint '{}': limit velocity {} is not a speed (expected above 0; 0 or none: no limit)",
            limits::short(&j.name),
            crate::common::words::number(v)
        )),
    }
}

/// The positioner: the chain of one or two revolute joints from the root link to a leaf link
/// that shares no moving joint with the arm's chain `arm` (module docs); `None` when there is
/// none. Such a chain hanging from a link the arm moves is an error ([`on_the_arm`]).
fn positioner(
    urdf: &urdf_rs::Robot,
    by_child: &HashMap<&str, &urdf_rs::Joint>,
    arm: &[&urdf_rs::Joint],
) -> std::result::Result<Vec<super::external::ExternalAxis>, String> {
    let on_arm: HashSet<&str> = arm.iter().map(|j| j.name.as_str()).collect();
    let parents: HashSet<&str> = urdf.joints.iter().map(|j| j.parent.link.as_str()).collect();
    let mut found: Vec<(String, Vec<&urdf_rs::Joint>)> = Vec::new();
    for leaf in urdf.links.iter().map(|l| l.name.as_str()) {
        if parents.contains(leaf) {
            continue;
        }
        let path = chain_to(leaf, by_child, urdf.joints.len())?;
        let moving = |j: &&&urdf_rs::Joint| j.joint_type != JointType::Fixed;
        let shared_moving = path
            .iter()
            .filter(|j| on_arm.contains(j.name.as_str()))
            .any(|j| moving(&j));
        let own: Vec<&urdf_rs::Joint> = (path.iter().copied())
            .filter(|j| !on_arm.contains(j.name.as_str()))
            .collect();
        let revolute = own.iter().filter(moving).count();
        if revolute == 0 || revolute > 2 {
            continue;
        }
        if own.iter().any(|j| {
            !matches!(
                j.joint_type,
                JointType::Fixed | JointType::Revolute | JointType::Continuous
            ) || j.mimic.is_some()
        }) {
            continue;
        }
        if shared_moving {
            return Err(on_the_arm(&path, &own, &on_arm));
        }
        if !found.iter().any(|(_, p)| {
            let names = |p: &[&urdf_rs::Joint]| -> Vec<String> {
                p.iter().filter(moving).map(|j| j.name.clone()).collect()
            };
            names(p) == names(&path)
        }) {
            found.push((leaf.to_string(), path));
        }
    }
    let path = match found.as_slice() {
        [] => return Ok(Vec::new()),
        [(_, path)] => path,
        many => {
            let leaves: Vec<&str> = many.iter().map(|(l, _)| l.as_str()).collect();
            return Err(format!(
                "several chains of revolute joints besides the arm's end in leaf links ({}): stiffid takes one positioner",
                limits::short(&leaves.join(", "))
            ));
        }
    };
    let mut at = Isometry3::identity();
    let mut axes = Vec::new();
    for j in path {
        at *= pose(j)?;
        if j.joint_type == JointType::Fixed {
            continue;
        }
        let (lower, upper) = match joint_limits(j)? {
            (l, u) if l.is_finite() && u.is_finite() => (l, u),
            _ => (-limits::ANGLE_RAD.max, limits::ANGLE_RAD.max),
        };
        let direction = Unit::new_normalize(at.rotation * axis(j)?.into_inner());
        axes.push(super::external::ExternalAxis {
            max_speed: velocity(j)?,
            ..super::external::ExternalAxis::rotary(
                &j.name,
                at.translation.vector,
                direction,
                lower,
                upper,
            )
        });
    }
    Ok(axes)
}

/// The error for a chain of revolute joints `own` hanging from a link that the arm's joints
/// move (`path` runs root first): a positioner riding on the arm would turn the tool, not the
/// part. Names the chain's first moving joint, the arm's link it hangs from and the arm joint
/// that moves it.
fn on_the_arm(path: &[&urdf_rs::Joint], own: &[&urdf_rs::Joint], on_arm: &HashSet<&str>) -> String {
    let first = own.iter().find(|j| j.joint_type != JointType::Fixed);
    let joint = first.map_or("", |j| j.name.as_str());
    let from = own.first().map_or("", |j| j.parent.link.as_str());
    let arm_joint = (path.iter().rev())
        .find(|j| on_arm.contains(j.name.as_str()) && j.joint_type != JointType::Fixed)
        .map_or("", |j| j.name.as_str());
    format!(
        "joint '{}' turns a chain hanging from link '{}', which joint '{}' of the arm's chain moves: a positioner axis on the arm's path to the tool is refused (a positioner hangs from the root link through no moving joint of the arm); make the joint fixed or hang its chain from the root",
        limits::short(joint),
        limits::short(from),
        limits::short(arm_joint)
    )
}

/// A joint's `<limit lower upper>`: both within `range` (rad or m), lower below upper.
fn check_limit(
    name: &str,
    lower: f64,
    upper: f64,
    range: &limits::Range,
) -> std::result::Result<(), String> {
    limits::check(
        &format!("joint '{name}': limit lower, upper"),
        &[lower, upper],
        range,
    )
    .map_err(|e| e.to_string())?;
    if lower >= upper {
        return Err(format!(
            "joint '{name}': limit lower = {} is not below upper = {}",
            crate::common::words::number(lower),
            crate::common::words::number(upper)
        ));
    }
    Ok(())
}
