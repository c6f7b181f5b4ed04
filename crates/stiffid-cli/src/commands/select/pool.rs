//! `select --pool FILE.csv`: the best group of the postures of a file, those that fail a check of
//! the cell ([`stiffid::cell::Checker`]: bounds, floor, obstacles, self-collision, rope, line of
//! sight, `[constraints]`) reported and skipped.

use super::{Args, Selection};
use crate::load;
use crate::report::plan::describe;
use anyhow::{bail, Context, Result};
use schemars::JsonSchema;
use serde::Serialize;
use std::path::{Path, PathBuf};
use stiffid::cell::Checker;
use stiffid::design::pool::MAX_POOL;
use stiffid::design::{Pool, PoolMethod, PoolOptions};
use stiffid::Setup;

/// A pool of postures read from a file.
pub struct Input<'a> {
    path: PathBuf,
    pool: Pool<'a>,
    total: usize,
    skipped: Vec<Skipped>,
}

/// A pool posture that cannot be measured, and why.
#[derive(Serialize, Clone, JsonSchema)]
struct Skipped {
    /// Its number in the pool file (1-based).
    posture: usize,
    /// The checks it fails (`floor`, `rope`, ...).
    checks: Vec<&'static str>,
    /// Every failing check in words, `; `-separated.
    reason: String,
}

/// The postures chosen from a pool: their numbers in the file (1-based) and how.
pub struct Chosen {
    numbers: Vec<usize>,
    method: PoolMethod,
}

/// The `pool` object of `select --json`.
#[derive(Serialize, JsonSchema)]
pub struct PoolJson {
    /// The pool file.
    file: String,
    /// Postures in the pool file.
    postures: usize,
    /// Postures that pass every check of the cell.
    usable: usize,
    /// The postures skipped, and why.
    skipped: Vec<Skipped>,
    /// How the group was chosen (`enumeration` or `exchange`).
    method: &'static str,
    /// The chosen postures' numbers in the pool file (1-based).
    chosen: Vec<usize>,
}

impl<'a> Input<'a> {
    /// Reads the pool file (an input: no output is written over it); postures that fail a check
    /// of the cell are skipped.
    pub fn read(path: &Path, setup: &'a Setup) -> Result<Self> {
        let postures = load::postures(path, setup.robot(), None)?;
        if postures.len() > MAX_POOL {
            bail!(
                "{}: {} postures: a pool holds at most {MAX_POOL}",
                path.display(),
                postures.len()
            );
        }
        let checker = Checker::new(setup);
        let skipped: Vec<Skipped> = postures
            .iter()
            .enumerate()
            .filter_map(|(i, q)| {
                let f = checker.feasibility(q);
                let failed: Vec<String> = f.violations().map(describe).collect();
                (!failed.is_empty()).then(|| Skipped {
                    posture: i + 1,
                    checks: f.violations().map(|c| c.kind.key()).collect(),
                    reason: failed.join("; "),
                })
            })
            .collect();
        let usable: Vec<bool> = (1..=postures.len())
            .map(|number| skipped.iter().all(|s| s.posture != number))
            .collect();
        let pool =
            Pool::new(setup, &postures, &usable).with_context(|| path.display().to_string())?;
        Ok(Self {
            path: path.to_path_buf(),
            pool,
            total: postures.len(),
            skipped,
        })
    }

    /// The best group of `n` usable postures for the arguments' criterion.
    ///
    /// # Errors
    /// Fewer usable postures than `n` (naming the checks that failed most often), and the
    /// errors of [`Pool::best`].
    pub fn choose(&self, args: &Args, n: usize) -> Result<Selection> {
        if n > self.usable() && !self.skipped.is_empty() {
            bail!(
                "--pool {}: {} postures asked for, but only {} of the {} pass the cell's checks (failed most often: {})",
                self.path.display(),
                n,
                self.usable(),
                self.total,
                self.most_failed()
            );
        }
        let options = PoolOptions {
            seed: args.seed,
            restarts: args
                .restarts
                .map_or(PoolOptions::default().restarts, |r| r as usize),
            ..PoolOptions::default()
        };
        let c = self
            .pool
            .best(args.criterion, n, &options)
            .with_context(|| format!("--pool {}", self.path.display()))?;
        Ok(Selection {
            search: "pool",
            postures: self.pool.postures(&c.indices),
            start_value: None,
            value: c.value,
            evaluations: c.evaluations,
            pool: Some(Chosen {
                numbers: c.indices.iter().map(|i| i + 1).collect(),
                method: c.method,
            }),
        })
    }

    /// The checks the skipped postures fail, most often first, with their counts.
    fn most_failed(&self) -> String {
        let mut counts: Vec<(&str, usize)> = Vec::new();
        for kind in self.skipped.iter().flat_map(|s| &s.checks) {
            match counts.iter_mut().find(|(k, _)| k == kind) {
                Some(c) => c.1 += 1,
                None => counts.push((kind, 1)),
            }
        }
        counts.sort_by_key(|c| std::cmp::Reverse(c.1));
        let parts: Vec<String> = counts.iter().map(|(k, c)| format!("{k} {c}")).collect();
        parts.join(", ")
    }

    /// Postures the pool can offer.
    pub fn usable(&self) -> usize {
        self.pool.usable().len()
    }

    /// The `pool` object of the JSON output.
    pub fn json(&self, chosen: Option<&Chosen>) -> PoolJson {
        PoolJson {
            file: self.path.display().to_string(),
            postures: self.total,
            usable: self.usable(),
            skipped: self.skipped.clone(),
            method: chosen.map_or("", |c| match c.method {
                PoolMethod::Enumeration => "enumeration",
                PoolMethod::Exchange => "exchange",
            }),
            chosen: chosen.map_or(Vec::new(), |c| c.numbers.clone()),
        }
    }

    /// What the pool held and what was chosen, in words.
    pub fn text(&self, chosen: Option<&Chosen>) -> String {
        let mut s = format!(
            "pool {}: {} postures, {} usable\n",
            self.path.display(),
            self.total,
            self.usable()
        );
        for k in &self.skipped {
            s += &format!("  skipped posture {}: {}\n", k.posture, k.reason);
        }
        if let Some(c) = chosen {
            let numbers: Vec<String> = c.numbers.iter().map(|n| n.to_string()).collect();
            s += &format!(
                "chosen ({}): postures {} of the pool\n",
                method_name(c.method),
                numbers.join(", ")
            );
        }
        s
    }
}

fn method_name(method: PoolMethod) -> &'static str {
    match method {
        PoolMethod::Enumeration => "exact, every group enumerated",
        PoolMethod::Exchange => "exchange algorithm, best of the restarts",
    }
}
