//! Design criteria: how good a group of postures is for identification. All smaller-is-better.
//!
//! For a group of n postures under the setup's rope-mass load, `Psi` is the `3pn x N` observation
//! matrix ([`stiffid_core::observation::rope_observation_matrix`]), one column per parameter of the setup's
//! model (`N = 6` for the six drive springs, more with virtual springs: [`stiffid_core::model`]), and
//! `S = Psi diag(h_nominal) / sigma` its unitless scaling (`sigma` the noise standard deviation at
//! multiple 1, m): `(S^T S)^-1` is the covariance of the *relative* compliance errors at noise
//! level 1. Everything is computed from the triangular factor `Psi = Q R` ([`Evaluator`](super::Evaluator)):
//! `S = Q (R diag(h) / sigma)`, so `S` never needs forming. A group whose `Psi` is rank deficient
//! (the rule of [`stiffid_core::math::lsq::Factor::try_new`]) gets `+infinity` for every criterion that depends
//! on `Psi`, never NaN.

use nalgebra::Vector6;
use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;
use stiffid_core::setup::Setup;
use stiffid_core::{dexterity, Error, Frames};
use stiffid_identify::svd::Identifiability;

/// A design criterion (smaller is better).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Criterion {
    /// `max_i k(J_N)_i` over the postures, J the TCP Jacobian in the springs' coordinates (Eq. 21;
    /// Dumas et al. 2011; the paper's "classical index").
    Classical,
    /// `classical * cond_2(Psi)`: the paper's novel index (Section III-B, step 5).
    Zhang2021,
    /// `cond_2(S)`: the condition number of the scaled observation matrix (scale-free).
    ScaledCond,
    /// `det((S^T S)^-1)^(1/(2N))` (`N` parameters; `1/12` for the six drives): the geometric mean
    /// of the relative standard deviations (D-optimal).
    DOptimal,
    /// `sqrt(mean_j [(S^T S)^-1]_jj)` over the `N` parameters: the RMS predicted relative standard
    /// deviation (A-optimal on relative compliance).
    RelativeA,
    /// `sigma sqrt(mean_t tr(A_t (Psi^T Psi)^-1 A_t^T))`: the RMS error (m) of the deflection predicted
    /// at the setup's test postures under their rope-mass load, `A_t` their observation rows
    /// (Klimchik & Pashkevich's industry-oriented measure).
    TestPose,
}

impl Criterion {
    /// Every criterion, in report order.
    pub const ALL: [Criterion; 6] = [
        Criterion::Classical,
        Criterion::Zhang2021,
        Criterion::ScaledCond,
        Criterion::DOptimal,
        Criterion::RelativeA,
        Criterion::TestPose,
    ];

    /// The name used on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            Criterion::Classical => "classical",
            Criterion::Zhang2021 => "zhang2021",
            Criterion::ScaledCond => "scaled-cond",
            Criterion::DOptimal => "d-optimal",
            Criterion::RelativeA => "relative-a",
            Criterion::TestPose => "test-pose",
        }
    }

    /// Checks that `setup` has the field this criterion needs beyond the robot, tool, load and
    /// noise: the characteristic length for classical and zhang2021 (the dexterity index, Eq. 20),
    /// the nominal stiffness for scaled-cond, d-optimal and relative-a (the scaling
    /// `S = Psi diag(h_nominal) / sigma`: of the drives and of every virtual spring of the model);
    /// test-pose needs test postures (`[test] postures_deg`).
    ///
    /// # Errors
    /// [`Error::MissingField`] naming the field and the criterion (and the spring without one).
    pub fn check(self, setup: &Setup) -> Result<(), Error> {
        let needed_by = || format!("criterion {}", self.name());
        match self {
            Criterion::Classical | Criterion::Zhang2021 => {
                setup.try_characteristic_length(&needed_by()).map(drop)
            }
            Criterion::ScaledCond | Criterion::DOptimal | Criterion::RelativeA => {
                setup.try_model_nominal_compliance(&needed_by()).map(drop)
            }
            Criterion::TestPose => match setup.test_postures().is_empty() {
                false => Ok(()),
                true => Err(Error::MissingField {
                    field: "test.postures_deg",
                    needed_by: needed_by(),
                }),
            },
        }
    }

    /// Whether `setup` has what this criterion needs ([`Criterion::check`]).
    pub fn serves(self, setup: &Setup) -> bool {
        match self {
            Criterion::Classical | Criterion::Zhang2021 => setup.characteristic_length().is_some(),
            Criterion::ScaledCond | Criterion::DOptimal | Criterion::RelativeA => {
                setup.model_nominal_compliance().is_some()
            }
            Criterion::TestPose => !setup.test_postures().is_empty(),
        }
    }

    /// The key of the criterion in JSON documents (`stiffid evaluate --json`): the name with
    /// underscores, and the unit for `test_pose_mm`.
    pub fn key(self) -> &'static str {
        match self {
            Criterion::Classical => "classical",
            Criterion::Zhang2021 => "zhang2021",
            Criterion::ScaledCond => "scaled_cond",
            Criterion::DOptimal => "d_optimal",
            Criterion::RelativeA => "relative_a",
            Criterion::TestPose => "test_pose_mm",
        }
    }
}

impl stiffid_core::common::choice::Choice for Criterion {
    const FIELD: &'static str = "criterion";
    const ALL: &'static [Self] = &Criterion::ALL;
    fn name(self) -> &'static str {
        Criterion::name(self)
    }
    fn help(self) -> &'static str {
        match self {
            Criterion::Classical => {
                "The worst dexterity of the postures (Eq. 21, the classical index)"
            }
            Criterion::Zhang2021 => "The classical index times cond(Psi): the paper's index",
            Criterion::ScaledCond => "The condition number of the scaled observation matrix",
            Criterion::DOptimal => "The geometric mean of the relative standard deviations",
            Criterion::RelativeA => "The RMS predicted relative standard deviation",
            Criterion::TestPose => "The RMS error of the deflection predicted at the test postures",
        }
    }
}

impl fmt::Display for Criterion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Criterion {
    type Err = Error;
    /// A criterion from its [`Criterion::name`] (`relative-a`) or its JSON key
    /// ([`Criterion::key`]: `relative_a`, `test_pose_mm`); one set of spellings for the command
    /// line and files.
    ///
    /// # Errors
    /// [`Error::Unknown`] listing the names.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Criterion::ALL
            .into_iter()
            .find(|c| c.name() == s || c.key() == s)
            .ok_or_else(|| Error::Unknown {
                kind: "criterion",
                name: s.to_string(),
                known: Criterion::ALL.map(|c| c.name()).join(", "),
            })
    }
}

/// Every criterion of one group of postures, the predicted deviation rates and which parameters
/// of the model the group identifies. A criterion the setup lacks a field for
/// ([`Criterion::check`]) is NaN, and so are `relative_std`, `spring_relative_std` and
/// `predicted_deviation_pct` without a nominal stiffness (of the drives and every virtual
/// spring); every other value is NaN-free.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// [`Criterion::Classical`], dimensionless.
    pub classical: f64,
    /// [`Criterion::Zhang2021`], dimensionless.
    pub zhang2021: f64,
    /// [`Criterion::ScaledCond`], dimensionless.
    pub scaled_cond: f64,
    /// [`Criterion::DOptimal`], dimensionless (relative standard deviation at noise level 1).
    pub d_optimal: f64,
    /// [`Criterion::RelativeA`], dimensionless (relative standard deviation at noise level 1).
    pub relative_a: f64,
    /// [`Criterion::TestPose`], m; NaN (not computed) when the setup has no test postures.
    pub test_pose: f64,
    /// `cond_2(Psi)` in SI units.
    pub cond_psi: f64,
    /// Relative standard deviation of each drive's compliance at noise level 1:
    /// `sqrt([(S^T S)^-1]_jj)`.
    pub relative_std: Vector6<f64>,
    /// Relative standard deviation of each virtual spring's compliance at noise level 1, in the
    /// model's order (empty for the drives alone): how well the group identifies it.
    pub spring_relative_std: Vec<f64>,
    /// Predicted mean deviation rate (%) per noise level of the setup and joint, first order:
    /// `100 sqrt(2/pi) sqrt(m) sqrt([(S^T S)^-1]_jj)` (the mean of |N(0, s^2)| is `sqrt(2/pi) s`).
    pub predicted_deviation_pct: Vec<[f64; 6]>,
    /// Which parameters (drives, then virtual springs) the group identifies, and the combinations
    /// it cannot separate: the column-scaled rank of its `Psi`, by the rule of identification
    /// ([`stiffid_identify::svd::identifiability`]); needs no nominal stiffness.
    pub identifiability: Identifiability,
}

impl Evaluation {
    /// The value of one criterion.
    pub fn value(&self, criterion: Criterion) -> f64 {
        match criterion {
            Criterion::Classical => self.classical,
            Criterion::Zhang2021 => self.zhang2021,
            Criterion::ScaledCond => self.scaled_cond,
            Criterion::DOptimal => self.d_optimal,
            Criterion::RelativeA => self.relative_a,
            Criterion::TestPose => self.test_pose,
        }
    }

    /// This evaluation with NaN for what `setup` lacks a field for: the criteria
    /// ([`Criterion::serves`]) and, without a nominal stiffness, the relative standard deviations
    /// and the predicted deviation rates.
    pub(crate) fn without_missing(mut self, setup: &Setup) -> Self {
        let nan = f64::NAN;
        for c in Criterion::ALL.into_iter().filter(|c| !c.serves(setup)) {
            *match c {
                Criterion::Classical => &mut self.classical,
                Criterion::Zhang2021 => &mut self.zhang2021,
                Criterion::ScaledCond => &mut self.scaled_cond,
                Criterion::DOptimal => &mut self.d_optimal,
                Criterion::RelativeA => &mut self.relative_a,
                Criterion::TestPose => &mut self.test_pose,
            } = nan;
        }
        if setup.model_nominal_compliance().is_none() {
            self.relative_std.fill(nan);
            self.spring_relative_std.fill(nan);
            self.predicted_deviation_pct
                .iter_mut()
                .for_each(|p| p.fill(nan));
        }
        self
    }

    /// The predicted average deviation rate, %: the mean of
    /// [`Evaluation::predicted_deviation_pct`] over noise levels and joints (0 without levels).
    pub fn predicted_average_pct(&self) -> f64 {
        let p = &self.predicted_deviation_pct;
        p.iter().flatten().sum::<f64>() / (6 * p.len()).max(1) as f64
    }
}

/// How well a group of postures identifies one parameter of the model
/// ([`Evaluation::parameters`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterQuality {
    /// The parameter's name (`k1` .. `k6`, or the virtual spring's) and unit.
    pub parameter: stiffid_core::model::Parameter,
    /// Whether the group identifies it ([`Evaluation::identifiability`]).
    pub identified: bool,
    /// Relative standard deviation of its compliance at noise level 1 (`+infinity` for a group
    /// whose `Psi` is rank deficient, NaN without a nominal stiffness).
    pub relative_std: f64,
    /// Its predicted mean deviation rate at noise multiple 1, %: `100 sqrt(2/pi) relative_std`.
    pub predicted_deviation_pct: f64,
}

impl Evaluation {
    /// Every parameter of `setup`'s model (the setup evaluated), drives first: whether the group
    /// identifies it and how well.
    pub fn parameters(&self, setup: &Setup) -> Vec<ParameterQuality> {
        let std = self.relative_std.iter().chain(&self.spring_relative_std);
        setup
            .model()
            .parameters()
            .into_iter()
            .zip(std)
            .enumerate()
            .map(|(j, (parameter, &relative_std))| ParameterQuality {
                parameter,
                identified: self
                    .identifiability
                    .identified
                    .get(j)
                    .copied()
                    .unwrap_or(false),
                relative_std,
                predicted_deviation_pct: 100.0 * (2.0 / PI).sqrt() * relative_std,
            })
            .collect()
    }
}

/// `max_i k(J_N)_i` over the postures (axis angles, rad): the classical index; NaN without a
/// characteristic length.
pub fn classical(setup: &Setup, postures: &[Vector6<f64>]) -> f64 {
    if setup.characteristic_length().is_none() {
        return f64::NAN;
    }
    postures
        .iter()
        .map(|q| tcp_dexterity(setup, &setup.robot().frames(q)))
        .fold(0.0, f64::max)
}

/// `k(J_N)` (Eq. 20-21) of the setup's TCP in one posture, its Jacobian in the springs' coordinates
/// and normalised by the setup's characteristic length; `+infinity` at a singularity. Without a
/// characteristic length it is normalised by 1 m, so that no NaN reaches a decomposition (the
/// criteria that need one are NaN then: [`Evaluation`], [`Evaluator::value`](super::Evaluator::value)).
pub(crate) fn tcp_dexterity(setup: &Setup, frames: &Frames) -> f64 {
    let j = frames.jacobian(&setup.tool().tcp, setup.springs());
    let l = setup.characteristic_length().unwrap_or(PLACEHOLDER_LENGTH);
    dexterity(&j, l)
}

/// The length (m) the dexterity is normalised by when a setup has no characteristic length;
/// nothing computed with it is reported.
pub(crate) const PLACEHOLDER_LENGTH: f64 = 1.0;

/// Predicted mean deviation rate (%) of each joint at noise multiple `m` from relative standard
/// deviations at multiple 1: `100 sqrt(2/pi) sqrt(m) s_j`.
pub fn predicted_deviation_pct(relative_std: &Vector6<f64>, multiple: f64) -> [f64; 6] {
    let f = 100.0 * (2.0 / PI).sqrt() * multiple.sqrt();
    std::array::from_fn(|j| f * relative_std[j])
}
