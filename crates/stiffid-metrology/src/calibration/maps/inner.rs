//! The inner cross-validation of the maps' choice: its splits prepared once, each candidate's
//! held-out errors at its best ridge scored once; and the inner splits the nested figure's outer
//! folds share (module docs of [`super`], "The honest figure").
//!
//! Where the choice is made inside an outer fold, its inner folds are the other outer folds:
//! outer fold `k`'s inner fold `f` trains on the postures of neither `k` nor `f` and holds out
//! `f`'s, so outer fold `f`'s inner fold `k` trains on the same postures. The `K (K - 1) / 2`
//! pairs are each prepared once ([`Pairs`]), holding out both folds, and each candidate's steps
//! on a pair are computed once for both outer folds: half the work of `K` inner cross-validations
//! of their own, to the same figures as two splits of one training set would give.

use super::linear::{self, Linear};
use super::{JointMaps, FOLDS, RIDGES};
use rayon::prelude::*;
use std::ops::Range;
use std::sync::{Arc, Mutex, OnceLock};
use stiffid_core::Result;

/// The folds of `postures`: fold `k` holds `postures[i]` with `i mod K = k`, `K = min(FOLDS, n)`.
pub(super) fn folds(postures: &[usize]) -> Vec<(Vec<usize>, Vec<usize>)> {
    let k = FOLDS.min(postures.len());
    (0..k)
        .map(|f| {
            let in_fold = |keep: bool| {
                (postures.iter().enumerate())
                    .filter(|(i, _)| (i % k == f) == keep)
                    .map(|(_, p)| *p)
                    .collect::<Vec<usize>>()
            };
            (in_fold(false), in_fold(true))
        })
        .collect()
}

/// The held-out errors of each candidate at every ridge, computed once.
type Memo = Mutex<Vec<(JointMaps, Arc<OnceLock<Result<Vec<Vec<f64>>>>>)>>;

/// A split (its training postures and its held-out ones) and the held-out errors of every
/// candidate scored on it.
struct Trained {
    split: linear::Split,
    /// The training readings (the ridge's `n`).
    readings: usize,
    /// Per candidate, per ridge of `RIDGES`, per held-out posture, the sum of squared errors
    /// (m^2).
    scored: Memo,
}

impl Trained {
    fn new(linear: &Linear, train: &[usize], test: &[usize]) -> Result<Trained> {
        Ok(Trained {
            split: linear.split(train, test)?,
            readings: readings_of(linear, train),
            scored: Mutex::default(),
        })
    }

    /// The held-out errors of `choice` at every ridge of `RIDGES`, computed once (a caller
    /// asking while another computes them waits for them).
    fn errors(&self, linear: &Linear, choice: &JointMaps) -> Result<Vec<Vec<f64>>> {
        let cell = {
            let mut memo = self.scored.lock().unwrap_or_else(|e| e.into_inner());
            match memo.iter().find(|(m, _)| m == choice) {
                Some((_, cell)) => cell.clone(),
                None => {
                    let cell = Arc::new(OnceLock::new());
                    memo.push((*choice, cell.clone()));
                    cell
                }
            }
        };
        let lambdas: Vec<f64> = RIDGES.iter().map(|mu| mu * self.readings as f64).collect();
        cell.get_or_init(|| linear.errors(&self.split, choice, &lambdas))
            .clone()
    }
}

/// The readings of the postures `ps` of `linear`.
fn readings_of(linear: &Linear, ps: &[usize]) -> usize {
    ps.iter().map(|&p| linear.rows[p].len() / 3).sum()
}

/// One inner fold: a split and the range of its held-out postures the fold holds out.
struct Fold {
    trained: Arc<Trained>,
    held: Range<usize>,
}

/// The inner cross-validation of some postures: its folds, prepared once.
pub(super) struct Inner<'a> {
    pub(super) linear: &'a Linear,
    folds: Vec<Fold>,
    /// The readings of the held-out postures, all folds.
    readings: usize,
    /// The candidates scored so far: the forward and joint steps meet some again.
    scored: Mutex<Vec<(JointMaps, Scored)>>,
}

/// A candidate's held-out errors at its best ridge.
#[derive(Clone)]
pub(super) struct Scored {
    pub(super) ridge: f64,
    /// Per held-out posture (all folds, in order), the sum of squared errors, m^2.
    pub(super) errors: Vec<f64>,
    pub(super) total: f64,
}

impl<'a> Inner<'a> {
    /// The inner cross-validation of `postures` over [`folds`].
    pub(super) fn new(linear: &'a Linear, postures: &[usize]) -> Result<Self> {
        Self::of(linear, &folds(postures))
    }

    /// The inner cross-validation of the splits `parts` (training postures, held-out postures),
    /// each prepared on its own.
    pub(super) fn of(linear: &'a Linear, parts: &[(Vec<usize>, Vec<usize>)]) -> Result<Self> {
        let folds = (parts.par_iter())
            .map(|(train, test)| {
                Ok(Fold {
                    trained: Arc::new(Trained::new(linear, train, test)?),
                    held: 0..test.len(),
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let held: Vec<usize> = parts.iter().flat_map(|(_, t)| t.iter().copied()).collect();
        Ok(Inner {
            linear,
            folds,
            readings: readings_of(linear, &held),
            scored: Mutex::default(),
        })
    }

    /// The held-out errors of `choice` at its best ridge of `RIDGES`, scored once.
    pub(super) fn score(&self, choice: &JointMaps) -> Result<Scored> {
        let known = |memo: &[(JointMaps, Scored)]| {
            (memo.iter().find(|(m, _)| m == choice)).map(|(_, s)| s.clone())
        };
        let memo = self.scored.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(s) = known(&memo) {
            return Ok(s);
        }
        drop(memo);
        let s = self.scored_anew(choice)?;
        let mut memo = self.scored.lock().unwrap_or_else(|e| e.into_inner());
        memo.push((*choice, s.clone()));
        Ok(s)
    }

    /// [`Self::score`] where `choice` can matter: `None` once the held-out errors of the folds
    /// scored so far, at every ridge, reach `bound` (m^2; errors are never negative, so its
    /// total would too). The folds are scored one after the other, so a candidate that cannot
    /// be kept costs the folds that show it; one scored in full is the same to the last bit as
    /// [`Self::score`]'s, and kept.
    pub(super) fn score_below(&self, choice: &JointMaps, bound: f64) -> Result<Option<Scored>> {
        let memo = self.scored.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, s)) = memo.iter().find(|(m, _)| m == choice) {
            return Ok(Some(s.clone()));
        }
        drop(memo);
        let mut per_fold = Vec::with_capacity(self.folds.len());
        let mut partial = vec![0.0; RIDGES.len()];
        for f in &self.folds {
            let all = f.trained.errors(self.linear, choice)?;
            let held: Vec<Vec<f64>> = all.iter().map(|e| e[f.held.clone()].to_vec()).collect();
            // The same order of additions as the totals' below: a prefix of each sum.
            for (p, e) in partial.iter_mut().zip(&held) {
                *p = e.iter().fold(*p, |a, v| a + v);
            }
            per_fold.push(held);
            if partial.iter().all(|&p| p >= bound) {
                return Ok(None);
            }
        }
        let s = self.totalled(&per_fold);
        let mut memo = self.scored.lock().unwrap_or_else(|e| e.into_inner());
        memo.push((*choice, s.clone()));
        Ok(Some(s))
    }

    /// [`Self::score`] computed.
    fn scored_anew(&self, choice: &JointMaps) -> Result<Scored> {
        let per_fold = (self.folds.par_iter())
            .map(|f| {
                let all = f.trained.errors(self.linear, choice)?;
                Ok(all.iter().map(|e| e[f.held.clone()].to_vec()).collect())
            })
            .collect::<Result<Vec<Vec<Vec<f64>>>>>()?;
        Ok(self.totalled(&per_fold))
    }

    /// The candidate's score from its held-out errors per fold, per ridge, per posture: its best
    /// ridge's.
    fn totalled(&self, per_fold: &[Vec<Vec<f64>>]) -> Scored {
        let totals: Vec<f64> = (0..RIDGES.len())
            .map(|r| per_fold.iter().flat_map(|f| &f[r]).sum())
            .collect();
        let best = (0..RIDGES.len())
            .min_by(|&a, &b| totals[a].total_cmp(&totals[b]))
            .unwrap_or(0);
        Scored {
            ridge: RIDGES[best],
            errors: per_fold.iter().flat_map(|f| f[best].clone()).collect(),
            total: totals[best],
        }
    }

    /// The held-out RMS error of `s`, m.
    pub(super) fn rms(&self, s: &Scored) -> f64 {
        (s.total / self.readings.max(1) as f64).sqrt()
    }
}

/// The inner splits of the outer folds of some postures, prepared once for all of them (module
/// docs).
pub(super) struct Pairs<'a> {
    linear: &'a Linear,
    /// The outer folds' held-out postures.
    folds: Vec<Vec<usize>>,
    /// The split of each pair of outer folds `a < b` (training on neither, holding out `a`'s
    /// postures then `b`'s), in the order `(0, 1), (0, 2), .., (1, 2), ..`.
    pairs: Vec<Arc<Trained>>,
}

impl<'a> Pairs<'a> {
    /// The pairs of the outer folds of `postures` ([`folds`]); `None` with fewer than 3 folds
    /// (an outer fold's training postures would be one fold, with no inner fold to train on).
    pub(super) fn new(linear: &'a Linear, postures: &[usize]) -> Result<Option<Self>> {
        let folds: Vec<Vec<usize>> = folds(postures).into_iter().map(|(_, t)| t).collect();
        if folds.len() < 3 {
            return Ok(None);
        }
        let k = folds.len();
        let pairs: Vec<(usize, usize)> = (0..k)
            .flat_map(|a| (a + 1..k).map(move |b| (a, b)))
            .collect();
        let pairs = (pairs.par_iter())
            .map(|&(a, b)| {
                // Posture `i` of `postures` is in fold `i mod k` ([`folds`]).
                let train: Vec<usize> = (postures.iter().enumerate())
                    .filter(|(i, _)| i % k != a && i % k != b)
                    .map(|(_, &p)| p)
                    .collect();
                let test = [folds[a].as_slice(), folds[b].as_slice()].concat();
                Ok(Arc::new(Trained::new(linear, &train, &test)?))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Some(Pairs {
            linear,
            folds,
            pairs,
        }))
    }

    /// The inner cross-validation of outer fold `k`'s training postures: its inner folds the other
    /// outer folds, in order.
    pub(super) fn inner(&self, k: usize) -> Inner<'a> {
        let folds = (0..self.folds.len())
            .filter(|&f| f != k)
            .map(|f| {
                let (a, b) = (k.min(f), k.max(f));
                // The pairs `(a, b)` before it: those of every first fold below `a`, then `b - a - 1`.
                let n = self.folds.len();
                let trained = self.pairs[a * n - a * (a + 1) / 2 + (b - a - 1)].clone();
                let first = self.folds[a].len();
                let held = match f == a {
                    true => 0..first,
                    false => first..first + self.folds[b].len(),
                };
                Fold { trained, held }
            })
            .collect();
        let training: Vec<usize> = (0..self.folds.len())
            .filter(|&f| f != k)
            .flat_map(|f| self.folds[f].iter().copied())
            .collect();
        Inner {
            linear: self.linear,
            folds,
            readings: readings_of(self.linear, &training),
            scored: Mutex::default(),
        }
    }
}
