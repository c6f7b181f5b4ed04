//! Robots from URDF files (parsed by `urdf-rs`; the kinematics are ours).
//!
//! The chain runs from the root link to a tip link: by default the only leaf link, or the one named.
//! Fixed joints along it are folded into the next revolute joint (or into the flange transform after
//! the last one); revolute and continuous joints may turn about any axis. Prismatic, floating and
//! planar joints in the chain are an error, as is a chain without exactly six revolute joints. The
//! axis map is the identity: axis angles are the URDF joint positions. Joint limits come from each
//! revolute joint's `<limit lower upper>`; continuous joints, and revolute joints without a usable
//! limit (`lower >= upper`, as urdf-rs reads a missing `<limit>`), are unlimited.

use super::{AxisMap, Joint, Robot};
use crate::{Error, Result};
use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3, Vector6};
use std::collections::{HashMap, HashSet};
use urdf_rs::JointType;

/// Parses a URDF document into a [`Robot`]. `source_name` (the file name) is used in errors;
/// `tip` names the tip link, by default the only leaf link.
///
/// # Errors
/// [`Error::Parse`] for malformed XML; [`Error::Chain`] when the tip link is missing or ambiguous,
/// the tree has no single root, a joint in the chain is not revolute or fixed, or the chain does not
/// hold exactly six revolute joints.
pub fn parse(text: &str, source_name: &str, tip: Option<&str>) -> Result<Robot> {
    let urdf = urdf_rs::read_from_string(text).map_err(|e| Error::Parse {
        source_name: source_name.to_string(),
        message: super::file::one_line(&e.to_string()),
    })?;
    let chain_error = |message: String| Error::Chain {
        source_name: source_name.to_string(),
        message,
    };
    let by_child: HashMap<&str, &urdf_rs::Joint> = urdf
        .joints
        .iter()
        .map(|j| (j.child.link.as_str(), j))
        .collect();
    let tip = match tip {
        Some(t) if urdf.links.iter().any(|l| l.name == t) => t.to_string(),
        Some(t) => return Err(chain_error(format!("no link named '{t}' (--tip)"))),
        None => only_leaf(&urdf).map_err(chain_error)?,
    };
    let mut path = Vec::new();
    let mut link = tip.as_str();
    while let Some(joint) = by_child.get(link) {
        path.push(*joint);
        link = joint.parent.link.as_str();
        if path.len() > urdf.joints.len() {
            return Err(chain_error("the joints form a loop".into()));
        }
    }
    path.reverse();
    fold(&path, &urdf.name, source_name).map_err(chain_error)
}

fn only_leaf(urdf: &urdf_rs::Robot) -> std::result::Result<String, String> {
    let parents: HashSet<&str> = urdf.joints.iter().map(|j| j.parent.link.as_str()).collect();
    let leaves: Vec<&str> = urdf
        .links
        .iter()
        .map(|l| l.name.as_str())
        .filter(|l| !parents.contains(l))
        .collect();
    match leaves.as_slice() {
        [one] => Ok(one.to_string()),
        [] => Err("no leaf link: name the tip link with --tip".into()),
        many => Err(format!(
            "several leaf links ({}): name the tip link with --tip",
            many.join(", ")
        )),
    }
}

fn pose(p: &urdf_rs::Pose) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(p.xyz[0], p.xyz[1], p.xyz[2]),
        UnitQuaternion::from_euler_angles(p.rpy[0], p.rpy[1], p.rpy[2]),
    )
}

fn fold(
    path: &[&urdf_rs::Joint],
    name: &str,
    source_name: &str,
) -> std::result::Result<Robot, String> {
    let mut joints = Vec::new();
    let (mut lower, mut upper) = (Vec::new(), Vec::new());
    let mut acc = Isometry3::identity();
    for j in path {
        match j.joint_type {
            JointType::Fixed => acc *= pose(&j.origin),
            JointType::Revolute | JointType::Continuous => {
                let axis = Vector3::new(j.axis.xyz[0], j.axis.xyz[1], j.axis.xyz[2]);
                let axis = Unit::try_new(axis, 1e-12)
                    .ok_or_else(|| format!("joint '{}' has a zero axis", j.name))?;
                joints.push(Joint {
                    pre: acc * pose(&j.origin),
                    axis,
                    post: Isometry3::identity(),
                    offset: 0.0,
                });
                let limited = j.joint_type == JointType::Revolute && j.limit.lower < j.limit.upper;
                lower.push(if limited {
                    j.limit.lower
                } else {
                    f64::NEG_INFINITY
                });
                upper.push(if limited {
                    j.limit.upper
                } else {
                    f64::INFINITY
                });
                acc = Isometry3::identity();
            }
            ref other => {
                return Err(format!(
                "joint '{}' is {other:?}; only revolute, continuous and fixed joints are supported",
                j.name
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
    Ok(Robot {
        name: name.to_string(),
        source: source_name.to_string(),
        joints,
        axis_map: AxisMap::default(),
        lower: Vector6::from_column_slice(&lower),
        upper: Vector6::from_column_slice(&upper),
        base: Isometry3::identity(),
        flange: acc,
    })
}
