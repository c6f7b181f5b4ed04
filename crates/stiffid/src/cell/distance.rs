//! Signed distances between capsules, boxes and the floor, m (negative: penetration depth), by
//! dimforge's parry (segment-segment closest points; GJK/EPA for a capsule against a box).

use super::bodies::Capsule;
use crate::setup::Obstacle;
use nalgebra::{Isometry3, Point3, Vector3};
use parry3d_f64::query;
use parry3d_f64::shape::{self, SegmentPointLocation};

/// Signed distance between two capsules (a segment is a capsule of radius 0), m: the distance of
/// their segments minus both radii.
pub fn capsule_capsule(c1: &Capsule, c2: &Capsule) -> f64 {
    segment_distance((&c1.a, &c1.b), (&c2.a, &c2.b)) - c1.radius - c2.radius
}

/// Distance between the segments `s1` and `s2`, m.
fn segment_distance(s1: (&Vector3<f64>, &Vector3<f64>), s2: (&Vector3<f64>, &Vector3<f64>)) -> f64 {
    let p = |v: &Vector3<f64>| Point3::from(*v);
    let (a1, b1, a2, b2) = (p(s1.0), p(s1.1), p(s2.0), p(s2.1));
    let (l1, l2) =
        query::details::closest_points_segment_segment_with_locations_nD((&a1, &b1), (&a2, &b2));
    (at(&a1, &b1, l1) - at(&a2, &b2, l2)).norm()
}

fn at(a: &Point3<f64>, b: &Point3<f64>, location: SegmentPointLocation) -> Point3<f64> {
    shape::Segment::new(*a, *b).point_at(&location)
}

/// Signed distance of a capsule above the floor plane `z = floor_z`, m.
pub fn capsule_floor(c: &Capsule, floor_z: f64) -> f64 {
    c.a.z.min(c.b.z) - c.radius - floor_z
}

/// Distances beyond this (m) are not worked out: nothing in a robot cell is that far.
const FAR: f64 = 1e4;

/// Signed distance between a capsule and an axis-aligned box, m (parry's contact query, GJK
/// outside and EPA for the penetration depth inside); at most 10 km.
pub fn capsule_box(c: &Capsule, b: &Obstacle) -> f64 {
    let centre = (b.min + b.max) / 2.0;
    let cuboid = shape::Cuboid::new((b.max - b.min) / 2.0);
    let capsule = shape::Capsule::new(
        Point3::from(c.a - centre),
        Point3::from(c.b - centre),
        c.radius,
    );
    let identity = Isometry3::identity();
    match query::contact(&identity, &capsule, &identity, &cuboid, FAR) {
        Ok(Some(contact)) => contact.dist,
        // No contact within FAR (a capsule and a box are always supported).
        _ => FAR,
    }
}
