//! The cell's external axes as a scene draws them ([`stiffid_core::robot::external`]): three more
//! links after the robot's, each placed per posture by one frame like the robot's links.
//!
//! - `track` (with a carrier): the rail, a 0.3 m wide, 0.1 m high box under the arm's mount
//!   along the first linear axis over its travel, fixed in the cell frame;
//! - `carriage` (with a carrier): a 0.8 m square, 0.1 m thick plate under the arm's base at the
//!   carrier's pose `C(e)` times the base;
//! - `positioner table` (with a positioner): a disc of 0.5 m radius, 0.04 m thick, about the
//!   last positioner axis through its point, at the positioner's pose `P(e)`.

use super::{frame, Frame, Geometry, Link};
use nalgebra::{Isometry3, Point3, Rotation3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::shape::{Cuboid, Cylinder};
use stiffid_core::robot::external::ExternalAxes;
use stiffid_core::Robot;

/// The external axes' links of `robot` (none without external axes), in the order of
/// [`frames`].
pub(super) fn links(robot: &Robot) -> Vec<Link> {
    let Some(axes) = robot.external() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    if let Some(first) = axes.axes().iter().take(axes.carrier_len()).next() {
        let d = first.direction.into_inner();
        let (from, to) = (first.lower + first.offset, first.upper + first.offset);
        let mount = robot.base().translation.vector - Vector3::z() * 0.15;
        let middle = mount + d * (from + to) / 2.0;
        let along = UnitQuaternion::rotation_between(&Vector3::x(), &d).unwrap_or_else(|| {
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::PI)
        });
        let rail = Cuboid::new(Vector3::new((to - from).abs() / 2.0 + 0.4, 0.15, 0.05));
        let pose = Isometry3::from_parts(Translation3::from(middle), along);
        out.push(link("track", cuboid(&rail, &pose)));
        let plate = Cuboid::new(Vector3::new(0.4, 0.4, 0.05));
        let under = Isometry3::translation(0.0, 0.0, -0.05);
        out.push(link("carriage", cuboid(&plate, &under)));
    }
    if let Some(last) = axes.axes().iter().skip(axes.carrier_len()).last() {
        let (points, triangles) = Cylinder::new(0.02, 0.5).to_trimesh(24);
        // parry's cylinder turns about y; the table's about the axis' direction.
        let turn =
            Rotation3::rotation_between(&Vector3::y(), &last.direction).unwrap_or_else(|| {
                Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
            });
        let pose = Isometry3::from_parts(
            Translation3::from(last.point),
            UnitQuaternion::from_rotation_matrix(&turn),
        );
        out.push(link(
            "positioner table",
            Geometry::new("cylinder", &points, triangles, &pose),
        ));
    }
    out
}

/// The frames of [`links`] at the external axes' values `e` (SI, the cell's order): the rail's
/// (the identity), the carriage's `C(e) base`, the table's `P(e)`.
pub(super) fn frames(robot: &Robot, e: &[f64]) -> Vec<Frame> {
    let Some(axes) = robot.external() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    if axes.carrier_len() > 0 {
        out.push(frame(&Isometry3::identity()));
        out.push(frame(&(axes.carrier_pose(e) * robot.base())));
    }
    if axes.len() > axes.carrier_len() {
        out.push(frame(&axes.positioner_pose(e)));
    }
    out
}

/// The values `e` (SI) of every external axis at zero: the scene's default station.
pub(super) fn zero(axes: Option<&ExternalAxes>) -> Vec<f64> {
    vec![0.0; axes.map_or(0, ExternalAxes::len)]
}

fn link(name: &str, geometry: Geometry) -> Link {
    Link {
        name: name.to_string(),
        part: name.to_string(),
        meshes: Vec::new(),
        geometry: vec![geometry],
    }
}

fn cuboid(c: &Cuboid, pose: &Isometry3<f64>) -> Geometry {
    let (points, triangles): (Vec<Point3<f64>>, _) = c.to_trimesh();
    Geometry::new("box", &points, triangles, pose)
}
