//! How the things of the cell move with the axis angles, for the exact gradients of the
//! feasibility margins ([`super::Checker`]).

use super::bodies::Part;
use super::check::Margin;
use super::distance::Witness;
use crate::robot::kinematics::Frames;
use nalgebra::{Matrix3, Matrix3x6, Vector3, Vector6};

/// What carries a point of a thing of the cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Carrier {
    /// Nothing moves it: the floor, obstacles, the tracker, the rope's anchor.
    Fixed,
    /// It is fixed in link k (0 the base, 6 the flange and the tool).
    Link(usize),
    /// It lies on the segment from the fixed point `from` to the point `to + exempt u` (`u` the
    /// unit vector from `to` toward `from`), `to` fixed in the flange: a rope or a line of sight,
    /// whole (`exempt` 0) or without its last `exempt` metres at the tool.
    Line {
        from: Vector3<f64>,
        to: Vector3<f64>,
        end: Vector3<f64>,
        exempt: f64,
    },
}

impl Carrier {
    /// A line from `from` to `end`, `exempt` (m) short of `to`.
    pub(super) fn line(
        from: &Vector3<f64>,
        to: &Vector3<f64>,
        end: &Vector3<f64>,
        exempt: f64,
    ) -> Self {
        Carrier::Line {
            from: *from,
            to: *to,
            end: *end,
            exempt,
        }
    }
}

/// The carrier of a robot or tool body.
pub(super) fn part_carrier(part: Part) -> Carrier {
    match part {
        Part::Base => Carrier::Fixed,
        Part::Link(i) => Carrier::Link(i),
        Part::Tool => Carrier::Link(6),
    }
}

/// The velocity (3x6, base frame, m/rad per axis angle) of the point `p` (base frame, m) of a thing
/// carried by `carrier`, at the posture of `frames`. On a line, the point at the fraction `t` of
/// the way from `from` to `end` moves `t` times as fast as `end`, and `end = to + e (from - to) /
/// L` (L the line's length) moves with `(I - (e / L)(I - u u^T)) v_to`.
pub(super) fn velocity(frames: &Frames, carrier: Carrier, p: &Vector3<f64>) -> Matrix3x6<f64> {
    match carrier {
        Carrier::Fixed | Carrier::Link(0) => Matrix3x6::zeros(),
        Carrier::Link(k) => frames.link_point_jacobian(p, k),
        Carrier::Line {
            from,
            to,
            end,
            exempt,
        } => {
            let span = (end - from).norm();
            if span == 0.0 {
                return Matrix3x6::zeros();
            }
            let t = (p - from).norm() / span;
            let d = from - to;
            let length = d.norm();
            let v_to = frames.link_point_jacobian(&to, 6);
            let scale = match exempt > 0.0 && length > 0.0 {
                true => {
                    let u = d / length;
                    Matrix3::identity()
                        - (Matrix3::identity() - u * u.transpose()) * (exempt / length)
                }
                false => Matrix3::identity(),
            };
            scale * v_to * t
        }
    }
}

/// The gradient (rad per rad of each axis) of the angle between the measuring point's normal
/// `normal` (a direction fixed in the flange, base frame) and the line of sight `sight = tracker -
/// p` (`p` the measuring point, base frame, m). With `a` the normal, `b` the sight, `c`, `s` the
/// cosine and sine of the angle: `d angle = -((b^ - c a^) . da / |a| + (a^ - c b^) . db / |b|) /
/// s`, `da = omega x a`, `db = -v_p`. Zero where the angle is 0 or pi (no unique direction).
pub(super) fn angle_gradient(
    frames: &Frames,
    normal: &Vector3<f64>,
    sight: &Vector3<f64>,
    p: &Vector3<f64>,
) -> Vector6<f64> {
    let (na, nb) = (normal.norm(), sight.norm());
    let (a, b) = (normal / na, sight / nb);
    let c = a.dot(&b);
    let s = a.cross(&b).norm();
    if s < 1e-12 || na == 0.0 || nb == 0.0 {
        return Vector6::zeros();
    }
    // d angle = g_a . da + g_b . db
    let g_a = -(b - a * c) / (na * s);
    let g_b = -(a - b * c) / (nb * s);
    // g_a . (omega x normal) = omega . (normal x g_a)
    let rotation = frames.flange_rotation_jacobian();
    let v_p = frames.link_point_jacobian(p, 6);
    rotation.transpose() * normal.cross(&g_a) - v_p.transpose() * g_b
}

/// What the gradient of one margin is worked out from.
#[derive(Debug, Clone, Copy)]
pub(super) enum Deferred {
    /// The gradient itself.
    Value(Vector6<f64>),
    /// A distance: its witness points, carried by the first and the second carrier (zero
    /// without a witness).
    Witness(Carrier, Carrier, Option<Witness>),
    /// The incidence angle between `normal` and `sight` at the measuring point `p`, as a margin
    /// `max - angle - keep / |sight|` ([`angle_gradient`]; `keep` in m).
    Angle {
        normal: Vector3<f64>,
        sight: Vector3<f64>,
        p: Vector3<f64>,
        keep: f64,
    },
    /// The height of a point of the flange (base frame, m).
    Height(Vector3<f64>),
}

/// Margins of a posture allocated for at first: the bounds, a robot's bodies against the floor,
/// each other, the rope and four lines of sight come to about 70 (more with obstacles).
const CAPACITY: usize = 128;

/// The margins of one posture as they are worked out, and what their gradients come from when
/// asked for.
pub(super) struct Margins {
    pub(super) margins: Vec<Margin>,
    /// Whether far pairs get their bounding spheres' gap ([`super::feasibility::FAR_MARGIN`]).
    pub(super) broad: bool,
    deferred: Option<Vec<Deferred>>,
    frames: Option<Frames>,
}

/// The gradients of the margins of one posture ([`super::Checker::margins_and_gradients`]), each
/// worked out when asked for: a distance's from its witness points (the contact normal times the
/// difference of the witness points' velocities, `n^T (J_b(p_b) - J_a(p_a))`), an incidence
/// angle's and a height's from their closed forms, a bound's constant.
pub struct MarginGradients {
    frames: Option<Frames>,
    deferred: Vec<Deferred>,
}

impl MarginGradients {
    /// The gradient of margin `i` (its index in the margins returned with these) with respect to
    /// the six axis angles (m/rad, or rad/rad for angles).
    ///
    /// # Panics
    /// If `i` is not the index of one of those margins.
    pub fn gradient(&self, i: usize) -> Vector6<f64> {
        let frames = || {
            self.frames
                .as_ref()
                .expect("frames of a constrained posture")
        };
        match self.deferred[i] {
            Deferred::Value(g) => g,
            Deferred::Witness(_, _, None) => Vector6::zeros(),
            Deferred::Witness(a, b, Some(w)) => {
                let f = frames();
                (velocity(f, b, &w.b) - velocity(f, a, &w.a)).transpose() * w.normal
            }
            Deferred::Angle {
                normal,
                sight,
                p,
                keep,
            } => {
                // d(keep / L) = -keep / L^2 dL, dL = -(sight / L) . v_p (the tracker fixed).
                let f = frames();
                let l = sight.norm();
                let turn = match keep > 0.0 && l > 0.0 {
                    true => f.link_point_jacobian(&p, 6).transpose() * sight * (keep / (l * l * l)),
                    false => Vector6::zeros(),
                };
                -angle_gradient(f, &normal, &sight, &p) - turn
            }
            Deferred::Height(p) => frames().link_point_jacobian(&p, 6).row(2).transpose(),
        }
    }
}

impl Margins {
    /// Margins only, or margins and what their gradients come from; with the broad phase or
    /// every distance exact.
    pub(super) fn new(gradients: bool, broad: bool) -> Self {
        Self {
            margins: Vec::with_capacity(CAPACITY),
            broad,
            deferred: gradients.then(|| Vec::with_capacity(CAPACITY)),
            frames: None,
        }
    }

    /// The posture's frames, for the gradients that follow (kept only when gradients are asked
    /// for).
    pub(super) fn frames(&mut self, frames: Frames) {
        if self.deferred.is_some() {
            self.frames = Some(frames);
        }
    }

    /// Adds a margin and what its gradient comes from.
    pub(super) fn push(&mut self, m: Margin, gradient: Deferred) {
        self.margins.push(m);
        if let Some(d) = &mut self.deferred {
            d.push(gradient);
        }
    }

    /// Adds a distance margin whose witness points `w.a`, `w.b` are carried by `a` and `b`.
    pub(super) fn witness(&mut self, m: Margin, a: Carrier, b: Carrier, w: Option<Witness>) {
        self.push(m, Deferred::Witness(a, b, w));
    }

    /// The margins and their gradients.
    pub(super) fn finish(self) -> (Vec<Margin>, MarginGradients) {
        let gradients = MarginGradients {
            frames: self.frames,
            deferred: self.deferred.unwrap_or_default(),
        };
        (self.margins, gradients)
    }
}
