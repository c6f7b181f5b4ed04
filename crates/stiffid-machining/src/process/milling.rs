//! Milling forces: the mechanistic model with linear edge forces (Altintas, *Manufacturing
//! Automation*, 2nd ed., Cambridge University Press 2012, ch. 2.4).
//!
//! A flute at immersion angle `psi` (measured clockwise from the feed frame's `+y` axis, seen from
//! the spindle) cuts a chip of thickness `h = c sin(psi)` (`c` the feed per tooth). On a length
//! `dz` of its edge it feels the tangential, radial and axial forces
//! `dF_t = (K_tc h + K_te) dz`, `dF_r = (K_rc h + K_re) dz`, `dF_a = (K_ac h + K_ae) dz`, which in
//! the feed frame are
//! `dF_x = -dF_t cos(psi) - dF_r sin(psi)`, `dF_y = dF_t sin(psi) - dF_r cos(psi)`,
//! `dF_z = dF_a`. A flute cuts only while `psi` lies in the immersion `[psi_st, psi_ex]`: up
//! milling `[0, acos(1 - 2 a_e / D)]`, down milling `[pi - acos(1 - 2 a_e / D), pi]`, a slot
//! `[0, pi]`. With helix angle `beta` the flute at height `z` lags by `k_b z`, `k_b = 2 tan(beta) / D`.
//!
//! ## The mean force over one revolution (closed form)
//! Every point of every flute sweeps the immersion once per revolution, so the helix drops out of
//! the mean and
//! `F_mean = N a_p / (2 pi) [G(psi_ex) - G(psi_st)]`, with the antiderivative `G` of the force per
//! unit edge length (Altintas' Eq. 2.42, the immersion integral):
//! - `G_x = c/4 [K_tc cos 2psi - K_rc (2psi - sin 2psi)] - K_te sin psi + K_re cos psi`
//! - `G_y = c/4 [K_tc (2psi - sin 2psi) + K_rc cos 2psi] - K_te cos psi - K_re sin psi`
//! - `G_z = -K_ac c cos psi + K_ae psi`
//!
//! ## The mean moment about the tool tip (closed form)
//! The flute's point at immersion `psi` lies at `R (sin psi, cos psi)` (`R = D / 2`) in the feed
//! frame's `x`-`y` plane, at height `z` above the tip. Its force's moment about the tip is
//! `r x dF`: about the axis `R dF_t` (the radial force passes through the axis), across it
//! `R cos(psi) dF_a - z dF_y` and `-R sin(psi) dF_a + z dF_x`. Every height sweeps the immersion
//! once per revolution, so the mean is `N a_p / (2 pi) R [H(psi_ex) - H(psi_st)]` plus
//! `a_p / 2 (z x F_mean)`, with
//! - `H_x = K_ac c sin^2(psi) / 2 + K_ae sin psi`,
//! - `H_y = -(K_ac c (psi / 2 - sin 2psi / 4) - K_ae cos psi)`,
//! - `H_z = -K_tc c cos psi + K_te psi` (the cutting torque `T = R N a_p / (2 pi) [H_z]`),
//!
//! the axial terms turned around for a left-hand helix.
//!
//! ## The instantaneous force and its peak
//! At the spindle angle `phi` flute `j` spans `psi` from `phi + 2 pi j / N - k_b a_p` to
//! `phi + 2 pi j / N` along the axial depth, so its force is `[G]` over the part of that span inside
//! the immersion (and its copies `+- 2 pi`), divided by `k_b`; without helix it is `a_p` times the
//! force per unit length at `phi + 2 pi j / N`. The peak is the largest magnitude of that sum on a
//! grid of spindle angles of the stated resolution (`Milling::peak_force`).

use nalgebra::Vector3;
use std::f64::consts::PI;

/// Up or down (climb) milling: which side of the feed the material is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Up (conventional) milling: the chip starts thin; material on the feed frame's `+y` side.
    Up,
    /// Down (climb) milling: the chip starts thick; material on the `-y` side.
    Down,
}

/// The six cutting and edge coefficients of the linear edge-force model (SI: N/m^2 and N/m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients {
    /// Tangential cutting coefficient `K_tc`, N/m^2.
    pub k_tc: f64,
    /// Radial cutting coefficient `K_rc`, N/m^2.
    pub k_rc: f64,
    /// Axial cutting coefficient `K_ac`, N/m^2.
    pub k_ac: f64,
    /// Tangential edge coefficient `K_te`, N/m.
    pub k_te: f64,
    /// Radial edge coefficient `K_re`, N/m.
    pub k_re: f64,
    /// Axial edge coefficient `K_ae`, N/m.
    pub k_ae: f64,
}

/// One milling operation: tool, cut and coefficients, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Milling {
    /// Tool diameter `D`, m.
    pub diameter: f64,
    /// Number of flutes `N`.
    pub flutes: u32,
    /// Helix angle `beta`, rad; a negative angle is a left-hand helix, which turns the axial
    /// force around.
    pub helix: f64,
    /// Feed per tooth `c`, m.
    pub feed_per_tooth: f64,
    /// Axial depth of cut `a_p`, m.
    pub axial_depth: f64,
    /// Radial depth of cut `a_e`, m, at most `D` (`D` is a slot).
    pub radial_depth: f64,
    /// Up or down milling.
    pub mode: Mode,
    /// The material's cutting and edge coefficients.
    pub coefficients: Coefficients,
    /// The spindle speed, rev/s, when the process gives it (`cut.spindle_rpm`): the tooth-passing
    /// frequency is `N` times it (`Milling::tooth_passing_frequency`).
    pub spindle_speed: Option<f64>,
}

impl Milling {
    /// The tooth-passing frequency `N n` (Hz, `n` the spindle speed in rev/s) that excites the
    /// structure (Altintas 2012, ch. 3.2), when the spindle speed is given.
    pub(crate) fn tooth_passing_frequency(&self) -> Option<f64> {
        self.spindle_speed.map(|n| n * self.flutes as f64)
    }

    /// The immersion `[psi_st, psi_ex]`, rad.
    pub(crate) fn immersion(&self) -> (f64, f64) {
        let ratio = (self.radial_depth / self.diameter).min(1.0);
        let swept = (1.0 - 2.0 * ratio).clamp(-1.0, 1.0).acos();
        match self.mode {
            Mode::Up => (0.0, swept),
            Mode::Down => (PI - swept, PI),
        }
    }

    /// `G(psi)`: the antiderivative of the force per unit edge length over the immersion angle
    /// (module docs), N.
    pub(crate) fn antiderivative(&self, psi: f64) -> Vector3<f64> {
        let k = &self.coefficients;
        let c = self.feed_per_tooth;
        let (s, co) = psi.sin_cos();
        let (s2, c2) = (2.0 * psi).sin_cos();
        Vector3::new(
            c / 4.0 * (k.k_tc * c2 - k.k_rc * (2.0 * psi - s2)) - k.k_te * s + k.k_re * co,
            c / 4.0 * (k.k_tc * (2.0 * psi - s2) + k.k_rc * c2) - k.k_te * co - k.k_re * s,
            self.axial_sign() * (-k.k_ac * c * co + k.k_ae * psi),
        )
    }

    /// The force per unit edge length at immersion angle `psi` inside the immersion, N/m
    /// (module docs): `d G / d psi`.
    pub(crate) fn per_length(&self, psi: f64) -> Vector3<f64> {
        let k = &self.coefficients;
        let h = self.feed_per_tooth * psi.sin();
        let (t, r, a) = (
            k.k_tc * h + k.k_te,
            k.k_rc * h + k.k_re,
            k.k_ac * h + k.k_ae,
        );
        let (s, c) = psi.sin_cos();
        Vector3::new(-t * c - r * s, t * s - r * c, self.axial_sign() * a)
    }

    fn axial_sign(&self) -> f64 {
        match self.helix < 0.0 {
            true => -1.0,
            false => 1.0,
        }
    }

    /// The mean force on the tool over one revolution, feed frame `[feed, normal, axial]`, N
    /// (closed form, module docs).
    pub(crate) fn mean_force(&self) -> Vector3<f64> {
        let (st, ex) = self.immersion();
        let g = self.antiderivative(ex) - self.antiderivative(st);
        g * (self.flutes as f64 * self.axial_depth / (2.0 * PI))
    }

    /// The mean moment on the tool over one revolution about the tool tip (the TCP: on the tool
    /// axis at the bottom of the cut), feed frame, Nm (closed form, module docs): the cutting
    /// torque about the spindle axis, and the moments of the lateral forces acting up the flutes
    /// (on average at `a_p / 2` above the tip) and of the axial forces acting at the radius.
    pub(crate) fn mean_moment(&self) -> Vector3<f64> {
        let (st, ex) = self.immersion();
        let h = self.moment_antiderivative(ex) - self.moment_antiderivative(st);
        let per_revolution = self.flutes as f64 * self.axial_depth / (2.0 * PI);
        let f = self.mean_force();
        let lever = Vector3::new(-f.y, f.x, 0.0) * (self.axial_depth / 2.0);
        h * (per_revolution * self.diameter / 2.0) + lever
    }

    /// `H(psi)`: the antiderivative over the immersion angle of the moment per unit edge length
    /// and unit radius of the forces at the flute's point `R (sin psi, cos psi)` of the tip
    /// plane: `[cos(psi) dF_a, -sin(psi) dF_a, dF_t]` (module docs), N.
    fn moment_antiderivative(&self, psi: f64) -> Vector3<f64> {
        let k = &self.coefficients;
        let c = self.feed_per_tooth;
        let (s, co) = psi.sin_cos();
        let sign = self.axial_sign();
        Vector3::new(
            sign * (k.k_ac * c * s * s / 2.0 + k.k_ae * s),
            -sign * (k.k_ac * c * (psi / 2.0 - (2.0 * psi).sin() / 4.0) - k.k_ae * co),
            -k.k_tc * c * co + k.k_te * psi,
        )
    }

    /// The force on the tool at spindle angle `phi` (rad), feed frame, N (module docs).
    pub(crate) fn force_at(&self, phi: f64) -> Vector3<f64> {
        let (st, ex) = self.immersion();
        let pitch = 2.0 * PI / self.flutes as f64;
        let lag = 2.0 * self.helix.abs().tan() / self.diameter * self.axial_depth;
        let mut f = Vector3::zeros();
        for j in 0..self.flutes {
            let top = phi + j as f64 * pitch;
            if lag < 1e-12 {
                let psi = (top).rem_euclid(2.0 * PI);
                if psi >= st && psi <= ex {
                    f += self.per_length(psi) * self.axial_depth;
                }
                continue;
            }
            let (lo, hi) = (top - lag, top);
            let first = ((lo - ex) / (2.0 * PI)).floor() as i64;
            let last = ((hi - st) / (2.0 * PI)).ceil() as i64;
            for m in first..=last {
                let shift = 2.0 * PI * m as f64;
                let (a, b) = (lo.max(st + shift), hi.min(ex + shift));
                if b > a {
                    f += (self.antiderivative(b - shift) - self.antiderivative(a - shift))
                        * (self.axial_depth / lag);
                }
            }
        }
        f
    }

    /// The largest force magnitude over one revolution on a grid of spindle angles `resolution`
    /// (rad) apart, and the force there, feed frame, N. `resolution` is clamped to at least
    /// [`MIN_RESOLUTION_DEG`].
    pub(crate) fn peak_force(&self, resolution: f64) -> Vector3<f64> {
        let step = resolution.max(MIN_RESOLUTION_DEG.to_radians());
        let count = (2.0 * PI / step).ceil() as usize;
        (0..count)
            .map(|i| self.force_at(i as f64 * step))
            .max_by(|a, b| a.norm().total_cmp(&b.norm()))
            .unwrap_or_else(Vector3::zeros)
    }
}

/// The finest angular resolution of the peak force, deg (at most 36 000 spindle angles).
pub(crate) const MIN_RESOLUTION_DEG: f64 = 0.01;

/// The coarsest angular resolution of a peak, deg.
pub(crate) const MAX_RESOLUTION_DEG: f64 = 10.0;
