//! The pool of candidate postures: the unusable ones marked, the best group chosen from it.

use super::{Found, PoolInput, PoolReport, Request, Skipped};
use stiffid_core::cell::Check;
use stiffid_core::{Error, Result};
use stiffid_design::distinct::distinct_pool;
use stiffid_design::search::design_checker;
use stiffid_design::{self as design, Goal, PoolMethod, PoolOptions, Termination};

/// An error `field: message` about the pool `name`.
pub(super) fn in_pool(name: &str, field: &str, message: String) -> Error {
    Error::Input {
        source_name: name.into(),
        error: Box::new(Error::InvalidField {
            field: field.into(),
            message,
        }),
    }
}

/// The pool with its unusable postures marked.
pub(super) struct Candidates<'a> {
    pub(super) name: &'a str,
    pub(super) pool: design::Pool<'a>,
    pub(super) total: usize,
    pub(super) skipped: Vec<Skipped>,
    pub(super) not_distinct: Vec<(usize, usize)>,
}

impl<'a> Candidates<'a> {
    /// The pool `input` of the request: the postures that fail a check of the cell with the
    /// request's margin ([`stiffid_core::cell::Checker::keeping`]) skipped, and those that are not distinct with
    /// [`Request::distinct`].
    pub(super) fn new(request: &Request<'a>, input: &'a PoolInput) -> Result<Self> {
        let (setup, distinct) = (request.setup, request.distinct.as_ref());
        let checker = design_checker(setup, request.options.margin);
        let skipped: Vec<Skipped> = (input.postures.iter().enumerate())
            .filter_map(|(i, q)| {
                let f = checker.feasibility(q);
                let checks: Vec<Check> = f.violations().cloned().collect();
                (!checks.is_empty()).then_some(Skipped {
                    posture: i + 1,
                    checks,
                })
            })
            .collect();
        let mut usable: Vec<bool> = (1..=input.postures.len())
            .map(|number| skipped.iter().all(|s| s.posture != number))
            .collect();
        let not_distinct = match distinct {
            Some(d) => distinct_pool(setup.robot(), &input.postures, &mut usable, d)
                .into_iter()
                .map(|(a, b)| (a + 1, b + 1))
                .collect(),
            None => Vec::new(),
        };
        let pool =
            design::Pool::new(setup, &input.postures, &usable).map_err(|e| Error::Input {
                source_name: input.name.clone(),
                error: Box::new(e),
            })?;
        Ok(Self {
            name: &input.name,
            pool,
            total: input.postures.len(),
            skipped,
            not_distinct,
        })
    }

    pub(super) fn usable(&self) -> usize {
        self.pool.usable().len()
    }

    /// The best group of `n` usable postures.
    pub(super) fn choose(&self, r: &Request, goal: &Goal, n: usize) -> Result<Found> {
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
        let options = PoolOptions {
            seed: r.options.seed,
            restarts: r.restarts.unwrap_or(PoolOptions::default().restarts),
            ..PoolOptions::default()
        };
        r.progress.begin("choice from the pool", 0);
        let c = self.pool.best_for(goal, n, &options);
        r.progress.end();
        let c = c.map_err(|e| Error::Input {
            source_name: self.name.into(),
            error: Box::new(e),
        })?;
        Ok(Found {
            postures: self.pool.postures(&c.indices),
            start_value: None,
            value: c.value,
            evaluations: c.evaluations,
            termination: Termination::Converged,
            terminations: Vec::new(),
            chosen: Some((c.indices.iter().map(|i| i + 1).collect(), c.method)),
        })
    }

    /// The checks the skipped postures fail, most often first, with their counts.
    pub(super) fn most_failed(&self) -> String {
        let mut counts: Vec<(&str, usize)> = Vec::new();
        let kinds = self
            .skipped
            .iter()
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

    pub(super) fn report(self, chosen: Option<(Vec<usize>, PoolMethod)>) -> PoolReport {
        let (chosen, method) = chosen.expect("a pool choice");
        PoolReport {
            name: self.name.into(),
            total: self.total,
            usable: self.usable(),
            skipped: self.skipped,
            method,
            chosen,
            not_distinct: self.not_distinct,
        }
    }
}
