//! The gravity regressors of the postures a model met, each computed once: they depend on the
//! commanded posture alone (the torques are the nominal chain's, module docs of [`super`]), and a
//! calibration's fits evaluate them at the same postures at every step, every trial damping and
//! every refit.

use nalgebra::Vector6;
use std::collections::HashMap;
use std::sync::Mutex;

/// Most postures remembered; beyond, the regressors are computed each time.
const MOST: usize = 8192;

/// The regressors computed so far, by the bits of the posture's axis angles. A clone starts
/// empty (the same model computes the same values again); two memos are always equal (a cache,
/// not a part of the model).
#[derive(Default)]
pub(super) struct Memo(Mutex<HashMap<[u64; 6], Vec<f64>>>);

impl Memo {
    /// The regressors at `q`: remembered, or `compute`d and remembered.
    pub(super) fn at(&self, q: &Vector6<f64>, compute: impl FnOnce() -> Vec<f64>) -> Vec<f64> {
        let key: [u64; 6] = std::array::from_fn(|i| q[i].to_bits());
        let lock = || self.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(y) = lock().get(&key) {
            return y.clone();
        }
        let y = compute();
        let mut memo = lock();
        if memo.len() < MOST {
            memo.insert(key, y.clone());
        }
        y
    }
}

impl Clone for Memo {
    fn clone(&self) -> Self {
        Memo::default()
    }
}

impl PartialEq for Memo {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl std::fmt::Debug for Memo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Memo")
    }
}
