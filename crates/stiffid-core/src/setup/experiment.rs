//! The experiment: the rope load and its steps, the tracker's noise, the bounds of the postures,
//! the test postures, the nominal stiffness and the characteristic length; what the design and
//! the identification need beyond the arm ([`super::Setup::experiment`]).

use crate::common::limits::JointBox;
use crate::model::Spring;
use crate::setup::load_steps::StepWeights;
use crate::{Error, Result};
use nalgebra::{Vector3, Vector6};

/// Rope-and-mass loading: a force of magnitude `load` (N) pulling the loading point toward the rope
/// anchor (pulley), `F = G (P2 - P1) / |P2 - P1|` (Zhang et al. 2021, Section IV-A), no moment.
#[derive(Debug, Clone, PartialEq)]
pub struct RopeLoad {
    /// `G`, N.
    pub load: f64,
    /// `P2`, base frame, m.
    pub anchor: Vector3<f64>,
}

impl RopeLoad {
    /// The wrench `[f; m]` (N, Nm, base frame) at a loading point `p1` (base frame, m). A loading
    /// point at the anchor gets a zero wrench.
    pub(crate) fn wrench(&self, p1: &Vector3<f64>) -> Vector6<f64> {
        let d = self.anchor - p1;
        let n = d.norm();
        let f = if n > 0.0 {
            d * (self.load / n)
        } else {
            Vector3::zeros()
        };
        Vector6::new(f.x, f.y, f.z, 0.0, 0.0, 0.0)
    }

    /// The gradient with respect to the loading point `p1` (base frame, m) of `e . f(p1)`, f the
    /// force of `RopeLoad::wrench` and `e` a weight on it (per N): with `d = P2 - p1`,
    /// `u = d / |d|`, `df = -(G / |d|) (I - u u^T) dp1`, so the gradient is
    /// `-(G / |d|) (e - (u . e) u)` (per m). Zero at the anchor, where the wrench is zero.
    pub fn force_gradient(&self, p1: &Vector3<f64>, e: &Vector3<f64>) -> Vector3<f64> {
        let d = self.anchor - p1;
        let n = d.norm();
        if n == 0.0 {
            return Vector3::zeros();
        }
        let u = d / n;
        (e - u * u.dot(e)) * (-self.load / n)
    }
}

/// Laser-tracker noise: white Gaussian on every coordinate of every reading (docs/model.md, "The
/// noise convention"). A displacement is a loaded minus an unloaded reading, so its variance per
/// coordinate is twice the reading's ([`Noise::displacement_variance`]); with load steps the
/// displacement at the rope load has `Experiment::displacement_variance`.
#[derive(Debug, Clone, PartialEq)]
pub struct Noise {
    /// Variance `sigma_r^2` of one coordinate of one tracker reading at multiple 1, m^2
    /// (`[noise] reading_sd_mm` squared).
    pub reading_variance: f64,
    /// The noise levels, as multiples of the variance (Table 3: 0.5 .. 3.0).
    pub levels: Vec<f64>,
}

impl Noise {
    /// The noise levels of a setup file that gives none (`[noise] level_multiples` left out):
    /// the reading noise as given, `[1.0]`. A setup used only to identify and compensate
    /// simulates nothing.
    pub(crate) fn one_level() -> Vec<f64> {
        vec![1.0]
    }

    /// Standard deviation `sigma_r` of one coordinate of one reading at multiple 1, m.
    pub fn reading_sd(&self) -> f64 {
        self.reading_variance.sqrt()
    }

    /// Variance of one coordinate of one displacement, a loaded minus an unloaded reading, at
    /// multiple 1: `2 sigma_r^2`, m^2 (the paper's noise, Table 3, is this one).
    pub fn displacement_variance(&self) -> f64 {
        2.0 * self.reading_variance
    }

    /// Standard deviation of one coordinate of one displacement at multiple 1, m.
    pub fn displacement_sd(&self) -> f64 {
        self.displacement_variance().sqrt()
    }
}

/// How the arm is loaded and measured, and what is known of it beforehand: the rope load and its
/// steps, the noise, the bounds the postures stay in, the test postures, the nominal stiffness,
/// the characteristic length of the dexterity index and the candidate springs of the model
/// comparison. Part of a [`super::Setup`], checked by its builder
/// ([`super::SetupBuilder::build`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Experiment {
    pub(super) load: RopeLoad,
    /// The loading fields the setup left out (`loading`, `tool.loading_point_mm`).
    pub(super) missing: Vec<&'static str>,
    pub(super) load_steps: Vec<f64>,
    pub(super) noise: Noise,
    pub(super) bounds: JointBox,
    pub(super) test_postures: Vec<Vector6<f64>>,
    pub(super) nominal_stiffness: Option<Vector6<f64>>,
    pub(super) characteristic_length: Option<f64>,
    pub(super) candidate_springs: Vec<Spring>,
}

impl Experiment {
    /// The loading of the simulation and of the posture search (a zero load in a
    /// calibration-only setup, which has none: `Experiment::require_loading`).
    pub(crate) fn load(&self) -> &RopeLoad {
        &self.load
    }

    /// Nothing, when the setup gives the rope load and the loading point, for `needed_by` (a job
    /// or computation, named in the error).
    ///
    /// # Errors
    /// [`Error::MissingField`] naming the first field the setup left out (`loading`, the
    /// table with `load_n` and `anchor_mm`, or `tool.loading_point_mm`) and `needed_by`.
    pub(crate) fn require_loading(&self, needed_by: &str) -> Result<()> {
        match self.missing.first() {
            None => Ok(()),
            Some(field) => Err(Error::MissingField {
                field,
                needed_by: needed_by.to_string(),
            }),
        }
    }

    /// The load levels applied in each posture, N, rising (`[loading] steps_n`); empty for one
    /// load per posture, the rope load ([`crate::setup::load_steps`]).
    pub(crate) fn load_steps(&self) -> &[f64] {
        &self.load_steps
    }

    /// Measurement noise.
    pub(crate) fn noise(&self) -> &Noise {
        &self.noise
    }

    /// The variance of one displacement coordinate at the rope load, at noise level multiple 1,
    /// m^2, that gives the compliances' covariance of the design: a loaded minus an unloaded
    /// reading without load steps ([`Noise::displacement_variance`], twice the reading
    /// variance); with them, that of the displacement their readings are worth
    /// (`crate::setup::load_steps::StepWeights::variance_factor` times the reading variance,
    /// also 2 for one step at the rope load).
    pub(crate) fn displacement_variance(&self) -> f64 {
        match StepWeights::new(self.load.load, &self.load_steps) {
            None => self.noise.displacement_variance(),
            Some(w) => self.noise.reading_variance * w.variance_factor(),
        }
    }

    /// Experiment bounds, axis coordinates, rad.
    pub(crate) fn bounds(&self) -> &JointBox {
        &self.bounds
    }

    /// Test (validation) postures, axis angles, rad.
    pub(crate) fn test_postures(&self) -> &[Vector6<f64>] {
        &self.test_postures
    }

    /// Nominal (or true, in simulation) joint stiffness, Nm/rad, if the setup gives one. The
    /// criteria scaled by it (relative-a, d-optimal, scaled-cond), the predicted deviation rates,
    /// simulation and the study need it; [`Experiment::try_nominal_stiffness`] says so when it
    /// is missing.
    pub(crate) fn nominal_stiffness(&self) -> Option<&Vector6<f64>> {
        self.nominal_stiffness.as_ref()
    }

    /// The nominal joint stiffness, Nm/rad, for `needed_by` (a criterion or computation, named
    /// in the error).
    ///
    /// # Errors
    /// [`Error::MissingField`] (`nominal_stiffness_nm_per_rad`) naming `needed_by`, with where a
    /// value comes from.
    pub(crate) fn try_nominal_stiffness(&self, needed_by: &str) -> Result<&Vector6<f64>> {
        self.nominal_stiffness().ok_or_else(|| Error::MissingField {
            field: "nominal_stiffness_nm_per_rad",
            needed_by: needed_by.to_string(),
        })
    }

    /// The nominal compliance `h = 1 / k` (Eq. 8), rad/Nm, if the setup gives a nominal
    /// stiffness.
    pub(crate) fn nominal_compliance(&self) -> Option<Vector6<f64>> {
        self.nominal_stiffness.map(|k| k.map(|k| 1.0 / k))
    }

    /// Characteristic length `L` of the dexterity index (Eq. 20), m, if the setup gives one (the
    /// classical and zhang2021 criteria need it).
    pub(crate) fn characteristic_length(&self) -> Option<f64> {
        self.characteristic_length
    }

    /// The characteristic length, m, for `needed_by` (named in the error).
    ///
    /// # Errors
    /// [`Error::MissingField`] (`characteristic_length_mm`) naming `needed_by`, with where a value
    /// comes from.
    pub(crate) fn try_characteristic_length(&self, needed_by: &str) -> Result<f64> {
        self.characteristic_length
            .ok_or_else(|| Error::MissingField {
                field: "characteristic_length_mm",
                needed_by: needed_by.to_string(),
            })
    }

    /// The declared candidate springs (`[[model.spring]]` with `candidate = true`): not in the
    /// model, candidates of the model comparison (`stiffid_identify::compare`).
    pub(crate) fn candidate_springs(&self) -> &[Spring] {
        &self.candidate_springs
    }
}
