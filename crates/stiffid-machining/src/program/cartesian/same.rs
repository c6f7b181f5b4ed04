//! When two frames are one: the tolerance a frame a program states is compared with the
//! setup's (its tool, its `[workpiece]`, the located part).

use nalgebra::Isometry3;

/// How far a frame the program states may be from the setup's (its tool, its `[workpiece]`)
/// and still be it: 1 micrometre.
pub(crate) const SAME_M: f64 = 1e-6;
/// The same for the frames' orientations: 1 microradian.
pub(crate) const SAME_RAD: f64 = 1e-6;

/// Whether two frames are one within [`SAME_M`] and [`SAME_RAD`].
pub(crate) fn same(a: &Isometry3<f64>, b: &Isometry3<f64>) -> bool {
    (a.translation.vector - b.translation.vector).norm() <= SAME_M
        && a.rotation.angle_to(&b.rotation) <= SAME_RAD
}
