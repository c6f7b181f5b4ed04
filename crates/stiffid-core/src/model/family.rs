//! Named families of virtual springs, so that a setup need not write axes.
//!
//! - `tilt` at joint k (1..6): two rotational springs about the x and y axes of link k's frame
//!   through its origin, named `tilt<k>_x`, `tilt<k>_y`: the tilt of joint k's bearing and the
//!   bending of the links next to it, lumped at the joint (z is the drive's own axis for a DH
//!   table, whose frame k has its z axis on joint k).
//! - `tool`: three translational springs along the flange's x, y and z axes (fixed in link 6),
//!   named `tool_x`, `tool_y`, `tool_z`: the compliance of the tool and its mount at the tool
//!   centre point.
//! - `base`: six springs of the base mount in the robot's base frame, translations `base_x`,
//!   `base_y`, `base_z` and rotations `base_rx`, `base_ry`, `base_rz` about its axes through its
//!   origin: a pedestal or floor anchoring that is not rigid.
//! - `carriage`: three springs of the carriage of a robot on a linear track (the first carrier
//!   axis, [`crate::robot::external`]), fixed in link 0 through the base frame's origin, in the
//!   track's axis frame ([`crate::robot::external::ExternalAxis::frame`]): the translation
//!   `carriage_x` along the track (the drive and rack's give), the rotations `carriage_rx` about
//!   the track (roll) and `carriage_ry` about its horizontal cross axis (pitch): the tilt of the
//!   carriage on its rails and guide shoes. They move with the carriage
//!   ([`crate::Frames::base`]).

use super::{Kind, Spring};
use crate::robot::external::Role;
use crate::{Error, Result, Robot};
use nalgebra::{Unit, Vector3};

/// A named family of virtual springs (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// Rotations about x and y of joint k's frame.
    Tilt,
    /// Translations along the flange's x, y, z.
    Tool,
    /// The six springs of the base mount.
    Base,
    /// The carriage of a linear track: along it, roll and pitch.
    Carriage,
}

/// The families and their names in files.
pub(crate) const FAMILIES: [(&str, Family); 4] = [
    ("tilt", Family::Tilt),
    ("tool", Family::Tool),
    ("base", Family::Base),
    ("carriage", Family::Carriage),
];

impl Family {
    /// The family named `name` (`tilt`, `tool`, `base`, `carriage`).
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming `field` for another name.
    pub fn parse(name: &str, field: &str) -> Result<Self> {
        FAMILIES
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, f)| *f)
            .ok_or_else(|| Error::InvalidField {
                field: field.to_string(),
                message: format!(
                    "'{}' is not a family: expected tilt, tool, base or carriage",
                    crate::common::limits::short(name)
                ),
            })
    }

    /// The family's springs on `robot` at the joints `links` (`tilt` only: 1 to 6, each at most
    /// once; empty for `tool` and `base`), with the nominal stiffness `rotation` (Nm/rad) of its
    /// rotational and `translation` (N/m) of its translational springs.
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming `field` (`model.family[1].links`) for `tilt` without links,
    /// a link outside 1..6 or repeated, for links given to `tool`, `base` or `carriage`, and for
    /// `carriage` on a robot without a carrier.
    pub fn springs(
        self,
        robot: &Robot,
        links: &[usize],
        rotation: Option<f64>,
        translation: Option<f64>,
        field: &str,
    ) -> Result<Vec<Spring>> {
        let invalid = |message: String| Error::InvalidField {
            field: field.to_string(),
            message,
        };
        let spring = |name: String, kind, link, axis: Vector3<f64>| Spring {
            name,
            kind,
            link,
            axis: Unit::new_normalize(axis),
            point: Vector3::zeros(),
            nominal_stiffness: match kind {
                Kind::Rotation => rotation,
                Kind::Translation => translation,
            },
            law: super::Law::Linear,
        };
        match self {
            Family::Tilt => {
                if links.is_empty() {
                    return Err(invalid(
                        "tilt needs its joints: expected links = [1 to 6, ...]".into(),
                    ));
                }
                let mut out = Vec::new();
                for (i, &k) in links.iter().enumerate() {
                    if !(1..=6).contains(&k) || links[..i].contains(&k) {
                        return Err(invalid(format!("{k}: expected distinct joints 1 to 6")));
                    }
                    out.push(spring(
                        format!("tilt{k}_x"),
                        Kind::Rotation,
                        k,
                        Vector3::x(),
                    ));
                    out.push(spring(
                        format!("tilt{k}_y"),
                        Kind::Rotation,
                        k,
                        Vector3::y(),
                    ));
                }
                Ok(out)
            }
            Family::Tool | Family::Base | Family::Carriage if !links.is_empty() => Err(invalid(
                "only tilt takes links (tool is fixed in link 6, base and carriage in link 0)"
                    .into(),
            )),
            Family::Carriage => {
                let carrier = robot.external().and_then(|a| a.axes().first());
                let Some(track) = carrier.filter(|a| a.role == Role::Carrier) else {
                    return Err(invalid(
                        "carriage needs a robot on a track: expected a carrier axis \
                         ([[external_axis]] with role = \"carrier\")"
                            .into(),
                    ));
                };
                let axes = robot.base().rotation.inverse() * track.frame();
                let along = |i| axes * Vector3::ith(i, 1.0);
                Ok(vec![
                    spring("carriage_x".into(), Kind::Translation, 0, along(0)),
                    spring("carriage_rx".into(), Kind::Rotation, 0, along(0)),
                    spring("carriage_ry".into(), Kind::Rotation, 0, along(1)),
                ])
            }
            Family::Tool => {
                let r = robot.flange().rotation;
                Ok(["x", "y", "z"]
                    .iter()
                    .enumerate()
                    .map(|(i, a)| {
                        let e = Vector3::ith(i, 1.0);
                        spring(format!("tool_{a}"), Kind::Translation, 6, r * e)
                    })
                    .collect())
            }
            Family::Base => {
                let axes = ["x", "y", "z"].iter().enumerate();
                let t = axes.clone().map(|(i, a)| {
                    spring(
                        format!("base_{a}"),
                        Kind::Translation,
                        0,
                        Vector3::ith(i, 1.0),
                    )
                });
                let r = axes.map(|(i, a)| {
                    spring(
                        format!("base_r{a}"),
                        Kind::Rotation,
                        0,
                        Vector3::ith(i, 1.0),
                    )
                });
                Ok(t.chain(r).collect())
            }
        }
    }
}

/// Whether `name` is one of the names of the model comparison's candidates of the families
/// (`stiffid_identify::compare::pool`'s module docs), on any robot.
pub(crate) fn is_family_name(name: &str) -> bool {
    let index = |s: &str, most: u8| s.len() == 1 && (b'1'..=b'0' + most).contains(&s.as_bytes()[0]);
    let at = |prefix: &str, most: u8| {
        name.strip_prefix(prefix)
            .and_then(|r| r.split_once('_'))
            .is_some_and(|(k, a)| index(k, most) && matches!(a, "x" | "y" | "z"))
    };
    let joint = |prefix: &str| name.strip_prefix(prefix).is_some_and(|k| index(k, 6));
    let fixed = [
        "carriage_x",
        "carriage_rx",
        "carriage_ry",
        "base_x",
        "base_y",
        "base_z",
        "base_rx",
        "base_ry",
        "base_rz",
        "tool_x",
        "tool_y",
        "tool_z",
    ];
    at("tilt", 6) || at("bend", 5) || joint("lost") || joint("load") || fixed.contains(&name)
}

/// Refuses a declared candidate named like a family's candidate ([`is_family_name`]): the two
/// would be one name in the comparison, `--candidates` and the reports.
///
/// # Errors
/// [`crate::Error::InvalidField`] (`model.spring`) naming the spring.
pub(crate) fn check_declared_names(declared: &[Spring]) -> crate::Result<()> {
    match declared.iter().find(|s| is_family_name(&s.name)) {
        Some(s) => Err(crate::Error::InvalidField {
            field: "model.spring".into(),
            message: format!(
                "{:?}: a declared candidate named like a built-in candidate of the model comparison (tilt<k>_x, bend<k>_y, base_z, tool_x, lost<j>, load<j>, ..); give it a name of its own",
                crate::common::limits::short(&s.name)
            ),
        }),
        None => Ok(()),
    }
}
