//! Drilling forces: thrust and torque from a specific-energy model.
//!
//! A twist drill of diameter `D` fed `f` per revolution removes `pi D^2 / 4 * f` of material per
//! revolution. With the material's specific cutting energy `k_c` (energy per volume, the same
//! number as a pressure, N/mm^2 = J/mm^3) the spindle does `k_c pi D^2 f / 4` of work per
//! revolution, `2 pi T`, so the torque is `T = k_c f D^2 / 8` (the specific-energy method of
//! machining handbooks, e.g. Kalpakjian and Schmid, *Manufacturing Engineering and Technology*,
//! the drilling section). The thrust is taken proportional to the chip area of the two lips,
//! `f D / 2`: `F = k_f f D / 2`, `k_f` the specific thrust, N/mm^2, from the user's own
//! measurement or the tool maker (stiffid ships no drilling presets).
//!
//! On the tool the thrust pushes back along the spindle (feed frame `+z`) and the torque opposes
//! the spindle's clockwise turning (a moment about `+z`).

use nalgebra::Vector3;

/// One drilling operation, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drilling {
    /// Drill diameter `D`, m.
    pub diameter: f64,
    /// Feed per revolution `f`, m.
    pub feed_per_rev: f64,
    /// Specific cutting energy `k_c`, N/m^2 (J/m^3).
    pub specific_energy: f64,
    /// Specific thrust `k_f`, N/m^2.
    pub specific_thrust: f64,
}

impl Drilling {
    /// The thrust `F = k_f f D / 2`, N.
    pub(crate) fn thrust(&self) -> f64 {
        self.specific_thrust * self.feed_per_rev * self.diameter / 2.0
    }

    /// The torque `T = k_c f D^2 / 8`, Nm.
    pub(crate) fn torque(&self) -> f64 {
        self.specific_energy * self.feed_per_rev * self.diameter.powi(2) / 8.0
    }

    /// The force on the tool, feed frame (`[0, 0, F]`), N.
    pub(crate) fn force(&self) -> Vector3<f64> {
        Vector3::new(0.0, 0.0, self.thrust())
    }

    /// The moment on the tool, feed frame (`[0, 0, T]`), Nm.
    pub(crate) fn moment(&self) -> Vector3<f64> {
        Vector3::new(0.0, 0.0, self.torque())
    }
}
