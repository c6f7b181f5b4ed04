//! Load steps in the experiment design: how the readings of `[loading] steps_n` combine in the
//! least squares, and the noise of one displacement at the rope load they are worth (docs/model.md,
//! "Load steps in the design").
//!
//! In each posture every measuring point is read unloaded (`x_0`) and at each step `f_s` (N) of
//! the rope load, pulling along the rope as the rope load `F` does, so step `s`'s block of the
//! observation matrix is `(f_s / F) Psi_i` and its displacement `d_s = x_s - x_0`. Every reading
//! carries the tracker noise `sigma^2` per coordinate; the reference `x_0` is shared by every step.
//! The least squares over every step's rows (what `identify` computes from such readings) has the
//! normal equations `sum_s (f_s / F)^2 Psi^T Psi h = sum_s (f_s / F) Psi^T d_s`, the same as one
//! block `Psi` at the rope load with the displacement `D = F sum_s f_s d_s / S2`
//! (`S1 = sum f_s`, `S2 = sum f_s^2`). `D`'s noise is `(F / S2) (sum_s f_s e_s - S1 e_0)`, of
//! variance `sigma^2 F^2 (S2 + S1^2) / S2^2` per coordinate and independent between points and
//! postures: the covariance of the compliances is that of one load at `F` with this displacement
//! noise. Without steps the setup's noise is that of a displacement coordinate (the paper's
//! convention), and nothing changes.

/// Most load steps of a setup (`[loading] steps_n`).
pub(crate) const MAX_STEPS: usize = 100;

/// The weights of the readings in the displacement `D` at the rope load (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct StepWeights {
    /// Of the unloaded reference reading: `-F S1 / S2`.
    pub reference: f64,
    /// Of each step's reading: `F f_s / S2`.
    pub steps: Vec<f64>,
}

impl StepWeights {
    /// The weights of the steps `steps` (N, positive) under the rope load `load` (N); `None`
    /// without steps.
    pub fn new(load: f64, steps: &[f64]) -> Option<Self> {
        if steps.is_empty() {
            return None;
        }
        let s1: f64 = steps.iter().sum();
        let s2: f64 = steps.iter().map(|f| f * f).sum();
        Some(Self {
            reference: -load * s1 / s2,
            steps: steps.iter().map(|f| load * f / s2).collect(),
        })
    }

    /// The variance of `D` per unit reading variance: `F^2 (S2 + S1^2) / S2^2`, the sum of the
    /// squared weights.
    pub(crate) fn variance_factor(&self) -> f64 {
        self.reference * self.reference + self.steps.iter().map(|w| w * w).sum::<f64>()
    }
}
