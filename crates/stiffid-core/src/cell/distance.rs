//! Signed distances between capsules, boxes and the floor, m (negative: penetration depth), by
//! dimforge's parry (segment-segment closest points; GJK/EPA for a capsule against a box), with
//! their witness points for the distance's gradient.

use super::bodies::{with_parry, Body, Capsule};
use crate::robot::collision::FAR;
use crate::setup::Obstacle;
use nalgebra::{Isometry3, Point3, Vector3};
use parry3d_f64::query;
use parry3d_f64::shape::{self, SegmentPointLocation};

/// Where a signed distance `d` is attained: a point of each of the two things and the unit
/// normal from the first toward the second, base frame. If the things move, points `a` and `b`
/// with the velocities `v_a`, `v_b` (as points fixed in their things), `d` changes at the rate
/// `normal . (v_b - v_a)` wherever the closest points are unique (the envelope theorem: the
/// witnesses' own motion along the surfaces changes `d` only to second order).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Witness {
    /// The point of the first thing, m.
    pub a: Vector3<f64>,
    /// The point of the second thing, m.
    pub b: Vector3<f64>,
    /// Unit normal from the first toward the second (for a penetration, the direction that
    /// separates them fastest).
    pub normal: Vector3<f64>,
}

/// Signed distance between two capsules (a segment is a capsule of radius 0), m: the distance of
/// their segments minus both radii, with its witness: the closest points of the two segments, and
/// their direction (where the segments cross, the normal of both segments, the direction in which
/// the crossing lines separate).
pub(crate) fn capsule_capsule_witness(c1: &Capsule, c2: &Capsule) -> (f64, Witness) {
    let p = |v: &Vector3<f64>| Point3::from(*v);
    let (a1, b1, a2, b2) = (p(&c1.a), p(&c1.b), p(&c2.a), p(&c2.b));
    let (l1, l2) =
        query::details::closest_points_segment_segment_with_locations_nD((&a1, &b1), (&a2, &b2));
    let (w1, w2) = (at(&a1, &b1, l1).coords, at(&a2, &b2, l2).coords);
    let d = w2 - w1;
    let distance = d.norm();
    let normal = match distance > 1e-12 {
        true => d / distance,
        false => (c1.b - c1.a)
            .cross(&(c2.b - c2.a))
            .try_normalize(1e-12)
            .unwrap_or_else(Vector3::zeros),
    };
    let witness = Witness {
        a: w1,
        b: w2,
        normal,
    };
    (distance - c1.radius - c2.radius, witness)
}

fn at(a: &Point3<f64>, b: &Point3<f64>, location: SegmentPointLocation) -> Point3<f64> {
    shape::Segment::new(*a, *b).point_at(&location)
}

/// Signed distance of a capsule above the floor plane `z = floor_z`, m, with its witness: the lower
/// end of the segment, its foot on the floor, the normal pointing down.
pub(crate) fn capsule_floor_witness(c: &Capsule, floor_z: f64) -> (f64, Witness) {
    let low = if c.a.z <= c.b.z { c.a } else { c.b };
    let witness = Witness {
        a: low,
        b: Vector3::new(low.x, low.y, floor_z),
        normal: -Vector3::z(),
    };
    (low.z - c.radius - floor_z, witness)
}

/// Signed distance between a capsule and a box, m (parry's contact query, GJK outside and EPA
/// for the penetration depth inside); at most 10 km. A turned box ([`Obstacle::pose`]): the
/// capsule moved into the box's frame by the inverse of its pose (a rigid motion keeps the
/// distance), there against the axis-aligned box.
pub fn capsule_box(c: &Capsule, b: &Obstacle) -> f64 {
    capsule_box_witness(c, b).0
}

/// [`capsule_box`] and its witness (parry's contact points and normal, cell frame); `None`
/// beyond 10 km.
pub(crate) fn capsule_box_witness(c: &Capsule, b: &Obstacle) -> (f64, Option<Witness>) {
    if !b.turned() {
        return capsule_aligned_box(c, b);
    }
    let to_box = |p: &Vector3<f64>| b.pose.inverse_transform_point(&Point3::from(*p)).coords;
    let local = Capsule {
        a: to_box(&c.a),
        b: to_box(&c.b),
        ..*c
    };
    let (d, w) = capsule_aligned_box(&local, b);
    let back = |p: Vector3<f64>| (b.pose * Point3::from(p)).coords;
    let w = w.map(|w| Witness {
        a: back(w.a),
        b: back(w.b),
        normal: b.pose.rotation * w.normal,
    });
    (d, w)
}

/// [`capsule_box_witness`] of the box's corners in the capsule's frame (its pose left out).
fn capsule_aligned_box(c: &Capsule, b: &Obstacle) -> (f64, Option<Witness>) {
    let centre = (b.min + b.max) / 2.0;
    let cuboid = shape::Cuboid::new((b.max - b.min) / 2.0);
    let capsule = shape::Capsule::new(
        Point3::from(c.a - centre),
        Point3::from(c.b - centre),
        c.radius,
    );
    let identity = Isometry3::identity();
    match query::contact(&identity, &capsule, &identity, &cuboid, FAR) {
        Ok(Some(contact)) if contact.dist > 0.0 => {
            let witness = refine_segment_box(c, b, contact.point1.coords + centre);
            (contact.dist, Some(witness))
        }
        Ok(Some(contact)) => {
            let witness = Witness {
                a: contact.point1.coords + centre,
                b: contact.point2.coords + centre,
                normal: contact.normal1.into_inner(),
            };
            (contact.dist, Some(witness))
        }
        // No contact within FAR (a capsule and a box are always supported).
        _ => (FAR, None),
    }
}

/// The witness of a capsule apart from a box, from GJK's point `near` on the capsule: GJK stops
/// within a tolerance that leaves its witness points some 0.1 mm along the surfaces (the distance
/// is right to second order, its gradient only to first), so the closest points are refined by
/// alternating projections (the segment point closest to the box point, the box point closest to
/// the segment point: the box clamps exactly), which converge from there in a few rounds.
fn refine_segment_box(c: &Capsule, b: &Obstacle, near: Vector3<f64>) -> Witness {
    let on_segment = |p: &Vector3<f64>| closest_on_segment(c, p);
    let in_box = |p: &Vector3<f64>| p.zip_zip_map(&b.min, &b.max, |v, lo, hi| v.clamp(lo, hi));
    let mut s = on_segment(&near);
    let mut x = in_box(&s);
    for _ in 0..8 {
        let next = on_segment(&x);
        let done = next == s;
        s = next;
        x = in_box(&s);
        if done {
            break;
        }
    }
    let d = x - s;
    let normal = d.try_normalize(0.0).unwrap_or_else(Vector3::zeros);
    Witness { a: s, b: x, normal }
}

/// The point of the segment of `c` closest to `p`.
pub(crate) fn closest_on_segment(c: &Capsule, p: &Vector3<f64>) -> Vector3<f64> {
    let axis = c.b - c.a;
    let length2 = axis.norm_squared();
    match length2 > 0.0 {
        true => c.a + axis * ((p - c.a).dot(&axis) / length2).clamp(0.0, 1.0),
        false => c.a,
    }
}

/// Signed distance between two bodies, m (capsules by their segments, any other pair by parry's
/// GJK, EPA inside); at most 10 km.
pub fn body_body(a: &Body, b: &Body) -> f64 {
    body_body_witness(a, b).0
}

/// [`body_body`] and its witness; `None` beyond 10 km.
pub(crate) fn body_body_witness(a: &Body, b: &Body) -> (f64, Option<Witness>) {
    if let (Body::Capsule(x), Body::Capsule(y)) = (a, b) {
        let (d, w) = capsule_capsule_witness(x, y);
        return (d, Some(w));
    }
    with_parry(a, |sa, pa| with_parry(b, |sb, pb| contact(pa, sa, pb, sb)))
}

/// Signed distance of a body above the floor plane `z = floor_z`, m.
pub fn body_floor(b: &Body, floor_z: f64) -> f64 {
    body_floor_witness(b, floor_z).0
}

/// [`body_floor`] and its witness: the body's lowest point (its support point downward), its
/// foot on the floor, the normal pointing down.
pub(crate) fn body_floor_witness(b: &Body, floor_z: f64) -> (f64, Witness) {
    let s = match b {
        Body::Capsule(c) => return capsule_floor_witness(c, floor_z),
        Body::Solid(s) => s,
    };
    let (shape, fix) = s.shape.parry();
    let down = -Vector3::z();
    let low = shape
        .as_support_map()
        .expect("every collision shape is convex")
        .support_point(&(s.pose * fix), &down)
        .coords;
    let witness = Witness {
        a: low,
        b: Vector3::new(low.x, low.y, floor_z),
        normal: down,
    };
    (low.z - floor_z, witness)
}

/// Signed distance between a body and a box (turned by its [`Obstacle::pose`]), m; at most
/// 10 km.
pub fn body_box(b: &Body, o: &Obstacle) -> f64 {
    body_box_witness(b, o).0
}

/// [`body_box`] and its witness; `None` beyond 10 km.
pub(crate) fn body_box_witness(b: &Body, o: &Obstacle) -> (f64, Option<Witness>) {
    match b {
        Body::Capsule(c) => capsule_box_witness(c, o),
        Body::Solid(_) => {
            let centre = o.pose
                * Isometry3::translation(
                    (o.min.x + o.max.x) / 2.0,
                    (o.min.y + o.max.y) / 2.0,
                    (o.min.z + o.max.z) / 2.0,
                );
            let cuboid = shape::Cuboid::new((o.max - o.min) / 2.0);
            with_parry(b, |s, p| contact(p, s, &centre, &cuboid))
        }
    }
}

/// parry's contact query of two convex shapes (GJK apart, EPA inside; never its box-to-box
/// shortcut, which sums the gaps along the axes instead of taking their norm): the signed distance
/// and the witness.
fn contact(
    pa: &Isometry3<f64>,
    sa: &dyn shape::Shape,
    pb: &Isometry3<f64>,
    sb: &dyn shape::Shape,
) -> (f64, Option<Witness>) {
    match query::contact(pa, sa, pb, sb, FAR) {
        Ok(Some(c)) => {
            let witness = Witness {
                a: c.point1.coords,
                b: c.point2.coords,
                normal: c.normal1.into_inner(),
            };
            (c.dist, Some(witness))
        }
        _ => (FAR, None),
    }
}
