//! Where the robot is used: the postures over which the ladder judges how far a gravity model
//! extrapolates ([`super::ladder`]).
//!
//! A heavy robot is often measured, and works, in a small part of its joint limits (36 postures
//! of a FANUC R-2000iC/165F in front of a fixture). Its gravity terms are then determined there
//! and left to their bound elsewhere: a model that predicts the readings better where the robot
//! works spreads its predictions by millimetres over the whole joint limits, where the robot never
//! goes. The ladder judges the spread where the robot is used, not where it can go.
//!
//! The region is the joint-space hull of the postures the campaign and the setup name (the
//! fitted postures, the held-out postures of `--validate`, the setup's test postures
//! `[test] postures_deg`): those postures and the postures a joint-interpolated move between two
//! of them passes through. It is sampled by `SAMPLES` (512) postures drawn at random (seeded:
//! `SEED`): half of them named postures, where the robot is measured or used, and half on the
//! segment between two named postures at a uniform share of the way (a sample of the moves alone
//! would weigh the hull's middle and leave its ends, the postures named, nearly unsampled), cut
//! to the robot's joint limits and the setup's `[bounds]`. Not the box of each axis's range: its corners pair
//! extreme angles of several axes that no named posture pairs (a campaign that keeps the forearm
//! level moves joints 2 and 3 together), postures the robot is neither measured in nor used in,
//! where a gravity model the campaign determines well would be turned down. A setup that names
//! postures over the whole joint limits (its test postures) judges the models there.

use crate::calibration::error_model::Observation;
use nalgebra::Vector6;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid_core::common::limits::JointBox;
use stiffid_core::Setup;

/// The postures sampled over the region.
pub(crate) const SAMPLES: usize = 512;

/// The seed of the region's sample: the same postures give the same region.
pub(crate) const SEED: u64 = 0x5E_ED_0F_2E_61;

/// The region where the robot is used (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// The box of the sampled postures' axis angles, rad: what a document shows of the region.
    pub bounds: JointBox,
    /// The postures sampled over it (axis angles, rad).
    pub postures: Vec<Vector6<f64>>,
}

/// The region of `postures` (axis angles, rad; module docs) within `limits` and `bounds`; with
/// no posture, [`crate::calibration::gravity::spanning`] postures of `limits`.
pub fn region(postures: &[Vector6<f64>], limits: &JointBox, bounds: &JointBox) -> Region {
    if postures.is_empty() {
        return Region {
            bounds: *limits,
            postures: crate::calibration::gravity::spanning(limits),
        };
    }
    // The limits cut by the bounds; an empty range of an axis (bounds beyond the limits) keeps
    // the limits'.
    let lower = limits.lower.sup(&bounds.lower);
    let upper = limits.upper.inf(&bounds.upper);
    let (lower, upper) = (
        lower.zip_map(&upper, f64::min),
        upper.zip_map(&lower, f64::max),
    );
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let n = postures.len();
    let sample: Vec<Vector6<f64>> = (0..SAMPLES)
        .map(|k| {
            let (a, b) = (
                &postures[rng.random_range(0..n)],
                &postures[rng.random_range(0..n)],
            );
            // Every other sample a named posture itself, the others on the moves between them.
            let t: f64 = match k % 2 {
                0 => 0.0,
                _ => rng.random(),
            };
            (a + (b - a) * t).sup(&lower).inf(&upper)
        })
        .collect();
    let fold = |init: f64, pick: fn(f64, f64) -> f64| {
        (sample.iter()).fold(Vector6::repeat(init), |acc, q| acc.zip_map(q, pick))
    };
    Region {
        bounds: JointBox::new(
            fold(f64::INFINITY, f64::min),
            fold(f64::NEG_INFINITY, f64::max),
        ),
        postures: sample,
    }
}

/// The region of a calibration's `fitted` readings (table readings left out), the postures of
/// the held-out readings `held` (`None` without `--validate`, or when they cannot be read: their
/// error comes with the validation) and the `setup`'s test postures, cut to the robot's limits and
/// the setup's bounds (module docs).
pub fn of(setup: &Setup, fitted: &[Observation], held: Option<&[Vector6<f64>]>) -> Region {
    let mut postures: Vec<Vector6<f64>> =
        (fitted.iter()).filter(|o| !o.table).map(|o| o.q).collect();
    postures.extend(held.unwrap_or_default());
    postures.extend_from_slice(setup.test_postures());
    region(&postures, setup.robot().limits(), setup.bounds())
}
