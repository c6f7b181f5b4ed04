//! The parts of a robot that carry bodies (base, links 1-6, tool) and the polyline each part
//! follows through a posture: what body capsules are built on and what sizes a robot.

use crate::robot::kinematics::Frames;
use nalgebra::Vector3;
use std::fmt;

/// A part of the robot that carries capsules.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Part {
    /// The fixed base: the column along axis 1 from the base origin's foot on axis 1 up to the
    /// height of joint 2.
    Base,
    /// Moving link 1..=6 (link i turns with axis i).
    Link(usize),
    /// The tool on the flange.
    Tool,
}

impl Part {
    /// Index of the part's radius: 0 the base, i link i, 7 the tool.
    pub fn index(self) -> usize {
        match self {
            Part::Base => 0,
            Part::Link(i) => i,
            Part::Tool => 7,
        }
    }
}

impl fmt::Display for Part {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Part::Base => write!(f, "base"),
            Part::Link(i) => write!(f, "link {i}"),
            Part::Tool => write!(f, "tool"),
        }
    }
}

/// The polyline of every robot part, base then links 1-6.
pub(crate) fn polylines(f: &Frames) -> Vec<(Part, Vec<Vector3<f64>>)> {
    let foot = |p: &Vector3<f64>| {
        let (o, d) = (f.axis_points[0], f.axis_directions[0]);
        o + d * d.dot(&(p - o))
    };
    let shoulder = f.axis_points[1];
    let column_top = foot(&shoulder);
    let mut lines = vec![
        (Part::Base, vec![foot(&Vector3::zeros()), column_top]),
        (Part::Link(1), vec![column_top, shoulder]),
    ];
    for i in 2..=6 {
        let next = match i {
            6 => f.flange.translation.vector,
            _ => f.axis_points[i],
        };
        let points = vec![
            f.axis_points[i - 1],
            f.joints[i - 1].translation.vector,
            next,
        ];
        lines.push((Part::Link(i), points));
    }
    lines
}
