//! A pool of candidate postures screened for a selection: the postures that fail a check of the
//! cell skipped, those not distinct left out, and the best group of its usable postures.

use crate::distinct::{distinct_pool, Distinctness};
use crate::search::design_checker;
use crate::{Goal, Pool, PoolMethod, PoolOptions};
use nalgebra::Vector6;
use stiffid_core::cell::Check;
use stiffid_core::common::progress::Progress;
use stiffid_core::{Error, Result, Setup};

/// An error `field: message` about the pool `name`.
pub fn in_pool(name: &str, field: &str, message: String) -> Error {
    Error::Input {
        source_name: name.into(),
        error: Box::new(Error::InvalidField {
            field: field.into(),
            message,
        }),
    }
}

/// A pool posture that cannot be measured.
#[derive(Debug, Clone)]
pub struct Skipped {
    /// Its number in the pool (1-based).
    pub posture: usize,
    /// The checks it fails.
    pub checks: Vec<Check>,
}

/// A pool with its unusable postures marked.
pub struct Screened<'a> {
    /// Its name in errors: a file's name, or `arrays`.
    pub name: &'a str,
    /// The postures that pass every check of the cell.
    pub pool: Pool<'a>,
    /// Postures in the pool.
    pub total: usize,
    /// The postures skipped, and why.
    pub skipped: Vec<Skipped>,
    /// With a distinctness: the usable postures left out because they are near one kept before
    /// them, `(left out, kept)`, numbers in the pool (1-based).
    pub not_distinct: Vec<(usize, usize)>,
}

/// The best group of a screened pool.
#[derive(Debug, Clone)]
pub(crate) struct Chosen {
    /// Its postures (axis angles, rad), in the pool's order.
    pub postures: Vec<Vector6<f64>>,
    /// Their numbers in the pool (1-based), ascending.
    pub numbers: Vec<usize>,
    /// The value minimised for it.
    pub value: f64,
    /// Groups evaluated.
    pub evaluations: usize,
    /// Enumeration or exchange.
    pub method: PoolMethod,
}

impl<'a> Screened<'a> {
    /// The pool `postures` (axis angles, rad) of `setup` named `name`: the postures that fail a
    /// check of the cell with the design's `margin` (m; `design_checker`) skipped, and with
    /// `distinct` those near one kept before them ([`distinct_pool`]).
    ///
    /// # Errors
    /// Those of [`Pool::new`], in the pool `name`.
    pub fn new(
        setup: &'a Setup,
        name: &'a str,
        postures: &[Vector6<f64>],
        margin: Option<f64>,
        distinct: Option<&Distinctness>,
    ) -> Result<Self> {
        let checker = design_checker(setup, margin);
        let skipped: Vec<Skipped> = (postures.iter().enumerate())
            .filter_map(|(i, q)| {
                let f = checker.feasibility(q);
                let checks: Vec<Check> = f.violations().cloned().collect();
                (!checks.is_empty()).then_some(Skipped {
                    posture: i + 1,
                    checks,
                })
            })
            .collect();
        let mut usable: Vec<bool> = (1..=postures.len())
            .map(|number| skipped.iter().all(|s| s.posture != number))
            .collect();
        let not_distinct = match distinct {
            Some(d) => distinct_pool(setup.robot(), postures, &mut usable, d)
                .into_iter()
                .map(|(a, b)| (a + 1, b + 1))
                .collect(),
            None => Vec::new(),
        };
        let pool = Pool::new(setup, postures, &usable).map_err(|e| Error::Input {
            source_name: name.into(),
            error: Box::new(e),
        })?;
        Ok(Self {
            name,
            pool,
            total: postures.len(),
            skipped,
            not_distinct,
        })
    }

    /// Its usable postures' count.
    pub fn usable(&self) -> usize {
        self.pool.usable().len()
    }

    /// The best group of `n` usable postures for `goal` (`Pool::best_for`), `progress` told
    /// of the choice.
    ///
    /// # Errors
    /// In the pool: `postures` when more are asked for than pass the cell's checks and are
    /// distinct (naming the checks failed most often); those of `Pool::best_for`.
    pub(crate) fn best(
        &self,
        goal: &Goal,
        n: usize,
        options: &PoolOptions,
        progress: &dyn Progress,
    ) -> Result<Chosen> {
        if n > self.usable() && !(self.skipped.is_empty() && self.not_distinct.is_empty()) {
            let message = format!(
                "{n} asked for, but only {} of the {} pass the cell's checks{}{}",
                self.usable(),
                self.total,
                match self.not_distinct.len() {
                    0 => String::new(),
                    d => format!(" and are distinct ({d} near an earlier one)"),
                },
                match self.skipped.is_empty() {
                    true => String::new(),
                    false => format!(" (failed most often: {})", self.most_failed()),
                }
            );
            return Err(in_pool(self.name, "postures", message));
        }
        progress.begin("choice from the pool", 0);
        let c = self.pool.best_for(goal, n, options);
        progress.end();
        let c = c.map_err(|e| Error::Input {
            source_name: self.name.into(),
            error: Box::new(e),
        })?;
        Ok(Chosen {
            postures: self.pool.postures(&c.indices),
            numbers: c.indices.iter().map(|i| i + 1).collect(),
            value: c.value,
            evaluations: c.evaluations,
            method: c.method,
        })
    }

    /// The checks the skipped postures fail, most often first, with their counts.
    fn most_failed(&self) -> String {
        let mut counts: Vec<(&str, usize)> = Vec::new();
        let kinds = (self.skipped.iter())
            .flat_map(|s| &s.checks)
            .map(|c| c.kind.key());
        for kind in kinds {
            match counts.iter_mut().find(|(k, _)| *k == kind) {
                Some(c) => c.1 += 1,
                None => counts.push((kind, 1)),
            }
        }
        counts.sort_by_key(|c| std::cmp::Reverse(c.1));
        let parts: Vec<String> = counts.iter().map(|(k, c)| format!("{k} {c}")).collect();
        parts.join(", ")
    }
}
